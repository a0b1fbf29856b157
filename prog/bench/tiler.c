/* tiler.c -- ./bench --tiler: how fast the exact tiler is, and how much
 * memory it takes.
 *
 *   bench --tiler [--points N[,N...]] [--naive N] [--input STACK]... [--cost area|span]
 *                 [--seed S] [--repeat R] [--data DIR]
 *
 * One CSV row per case: a generated pair of N-point contours (the paper's
 * "somewhat random" star-shaped contours, section 6), the naive
 * one-DP-per-start reference on the same pair, or a whole contour stack.
 * Each case runs in a child process, so peak_mb is that case's own peak
 * resident memory.  `cost` is the optimum (for a stack, the sum over its
 * pairs): a checksum that shows a fast wrong answer.
 *
 * The default stack, tests/data/slicerrt/prostate_0.contours, and a stack
 * named without a folder are looked for as data.h says: here, in
 * --data DIR, installed (PREFIX/share/tilesim) or in the source tree beside
 * the program, so that an installed bench runs anywhere. */
#include "prog/bench/bench.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "util/args.h"
#include "prog/bench/data.h"
#include "input/contour.h"
#include "input/gen.h"
#include "algo/naive.h"
#include "util/progname.h"
#include "algo/tiling.h"
#include "util/wallclock.h"
#include "util/xmem.h"

typedef struct {
  char name[64];
  int m, n;
  int runs;
  double wall;          /* best of `runs`, seconds */
  double nodes, paths;
  double cost;
} row;

static double peak_mb(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;   /* Linux reports kilobytes */
}

static void pair_of(int n, unsigned long long seed, vec2 **P, vec2 **Q) {
  rng g;
  rng_seed(&g, seed);
  *P = xmallocarray((size_t)n, sizeof **P);
  *Q = xmallocarray((size_t)n, sizeof **Q);
  gen_star(&g, *P, n, 0, 0, 100, 0.3);
  gen_star(&g, *Q, n, 5, -3, 90, 0.3);
}

static void run_exact(row *r, int n, unsigned long long seed, cost_kind kind, int repeat) {
  vec2 *P, *Q;
  pair_of(n, seed, &P, &Q);
  snprintf(r->name, sizeof r->name, "exact");
  r->m = r->n = n;
  r->runs = n <= 1000 ? repeat : 1;
  r->wall = 1e300;
  for (int i = 0; i < r->runs; i++) {
    tiling t;
    double t0 = wallclock();
    tiling_solve(P, n, 0, Q, n, 2.5, kind, -1, &t);
    double dt = wallclock() - t0;
    if (dt < r->wall) r->wall = dt;
    r->nodes = (double)t.count.nodes;
    r->paths = (double)t.count.paths;
    r->cost = t.cost;
    tiling_free(&t);
  }
  free(P);
  free(Q);
}

static void run_naive(row *r, int n, unsigned long long seed, cost_kind kind) {
  vec2 *P, *Q;
  pair_of(n, seed, &P, &Q);
  snprintf(r->name, sizeof r->name, "naive");
  r->m = r->n = n;
  r->runs = 1;
  double t0 = wallclock();
  weights *w = weights_new(P, n, 0, Q, n, 2.5, kind, 0);
  int start;
  double q = naive_dp(w, &start);
  r->wall = wallclock() - t0;
  r->cost = q * weights_quantum(w);
  r->nodes = (double)n * (n + 1) * (n + 1);   /* m DPs of (m+1)(n+1) nodes */
  r->paths = n;
  weights_free(w);
  free(P);
  free(Q);
}

static int run_stack(row *r, const char *file, cost_kind kind) {
  contour_stack s;
  char err[512];
  if (contour_read(file, &s, NULL, progname_as("bench"), err, sizeof err) != 0) {
    progname_eprintf("bench: %s\n", err);
    return -1;
  }
  if (contour_stack_pairs(&s, file, err, sizeof err) != 0) {
    progname_eprintf("bench: %s\n", err);
    contour_stack_free(&s);
    return -1;
  }
  const char *base = strrchr(file, '/');
  snprintf(r->name, sizeof r->name, "stack:%s", base ? base + 1 : file);
  r->m = s.n;   /* contours */
  r->n = 0;     /* points in all */
  for (int i = 0; i < s.n; i++) r->n += s.c[i].n;
  r->runs = 1;
  r->nodes = r->paths = r->cost = 0;
  double t0 = wallclock();
  for (int i = 0; i + 1 < s.n; i++) {
    tiling t;
    const contour *P = &s.c[i], *Q = &s.c[i + 1];
    tiling_solve(P->pt, P->n, P->z, Q->pt, Q->n, Q->z, kind, -1, &t);
    r->nodes += (double)t.count.nodes;
    r->paths += (double)t.count.paths;
    r->cost += t.cost;
    tiling_free(&t);
  }
  r->wall = wallclock() - t0;
  contour_stack_free(&s);
  return 0;
}

typedef enum { EXACT, NAIVE, STACK } kind_of_case;

/* Run one case in a child; print its row.  Returns 0 or -1. */
static int one(kind_of_case what, int n, const char *file, unsigned long long seed,
               cost_kind kind, int repeat, row *out) {
  int fd[2];
  if (pipe(fd) != 0) return -1;
  fflush(stdout);
  pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    row r;
    memset(&r, 0, sizeof r);
    int rc = 0;
    if (what == EXACT) run_exact(&r, n, seed, kind, repeat);
    else if (what == NAIVE) run_naive(&r, n, seed, kind);
    else rc = run_stack(&r, file, kind);
    double mb = peak_mb();
    if (rc == 0 && write(fd[1], &r, sizeof r) == (ssize_t)sizeof r &&
        write(fd[1], &mb, sizeof mb) == (ssize_t)sizeof mb)
      _exit(0);
    _exit(1);
  }
  close(fd[1]);
  double mb = 0;
  int ok = read(fd[0], out, sizeof *out) == (ssize_t)sizeof *out &&
           read(fd[0], &mb, sizeof mb) == (ssize_t)sizeof mb;
  close(fd[0]);
  int st;
  waitpid(pid, &st, 0);
  if (!ok || !WIFEXITED(st) || WEXITSTATUS(st) != 0) return -1;
  printf("%s,%d,%d,%d,%.6f,%.0f,%.4g,%.0f,%.1f,%.17g\n", out->name, out->m, out->n, out->runs,
         out->wall, out->nodes, out->nodes / out->wall, out->paths, mb, out->cost);
  fflush(stdout);
  return 0;
}

static const char tiler_usage[] =
    "usage: bench --tiler [--points N[,N...]] [--naive N] [--input STACK]... [--cost area|span] "
    "[--seed S] [--repeat R] [--data DIR]   (bench --help: every mode)\n";

/* Bad usage: "bench: why", arg (or NULL) shown after it, the usage line, 2. */
static int usage(const char *why, const char *arg) { return args_usage("bench", tiler_usage, why, arg); }

int bench_tiler(int argc, char **argv) {
  int points[16], npoints = 0, naive = -1, repeat = 20;
  const char *inputs[16], *data = NULL;
  int ninputs = 0;
  unsigned long long seed = 1993;
  cost_kind kind = COST_AREA;
  char msg[400];
  static const char *const opts[] = {"--points", "--naive", "--input", "--cost", "--seed", "--repeat", "--data"};
  for (int i = 2; i < argc; i += 2) {   /* argv[1] is --tiler; every option takes a value */
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int known = 0, bad = 0;
    long x = 0;
    for (size_t k = 0; k < sizeof opts / sizeof *opts; k++) known |= strcmp(a, opts[k]) == 0;
    if (!known) return usage(a[0] == '-' ? "unknown option" : "unexpected argument", a);
    if (!v) return usage("an option needs a value", a);
    if (strcmp(a, "--points") == 0) {
      args_list l;
      bad = args_list_max(a, v, 1, 3, 100000, 16, &l, msg, sizeof msg);
      for (int k = 0; !bad && k < l.n; k++) points[k] = (int)l.v[k];
      if (!bad) npoints = l.n;
    } else if (strcmp(a, "--naive") == 0) {
      bad = args_long(a, v, 3, 5000, &x, msg, sizeof msg);
      naive = (int)x;
    } else if (strcmp(a, "--input") == 0) {
      if (ninputs == 16) return usage("--input takes at most 16 stacks", v);
      bad = args_name(a, v, "a contour stack", 1, msg, sizeof msg);
      inputs[ninputs++] = v;
    } else if (strcmp(a, "--cost") == 0) {
      if (cost_parse(v, &kind) != 0) bad = args_word(a, v, "area|span", msg, sizeof msg);
    } else if (strcmp(a, "--seed") == 0) {
      bad = args_u64(a, v, 0, ULLONG_MAX, &seed, msg, sizeof msg);
    } else if (strcmp(a, "--repeat") == 0) {
      bad = args_long(a, v, 1, 1000, &x, msg, sizeof msg);
      repeat = (int)x;
    } else {
      bad = args_name(a, v, "a folder", 0, msg, sizeof msg);
      data = v;
    }
    if (bad) return usage(msg, NULL);
  }
  if (npoints == 0 && naive < 0 && ninputs == 0) {   /* the figures */
    points[npoints++] = 500;
    points[npoints++] = 5000;
    naive = 500;
    inputs[ninputs++] = "tests/data/slicerrt/prostate_0.contours";
  }
  /* Every stack found before any work. */
  static char paths[16][2300];
  for (int i = 0; i < ninputs; i++) {
    if (bench_data_find(inputs[i], data, paths[i], sizeof paths[i]) != 0) {
      progname_eprintf("bench: %s\n", paths[i]);
      return 1;
    }
    inputs[i] = paths[i];
  }
  printf("case,m,n,runs,wall_s,nodes,nodes_per_s,paths,peak_mb,cost\n");
  row r, ex500 = {0}, nv = {0};
  for (int i = 0; i < npoints; i++) {
    if (one(EXACT, points[i], NULL, seed, kind, repeat, &r) != 0) return 1;
    if (naive == points[i]) ex500 = r;
  }
  if (naive > 0) {
    if (one(NAIVE, naive, NULL, seed, kind, 1, &nv) != 0) return 1;
    if (ex500.wall > 0 && ex500.cost != nv.cost) {
      progname_eprintf("bench: the exact solver and the naive reference disagree: %s, %s\n",
              ARGS_G(ex500.cost), ARGS_G(nv.cost));
      return 1;
    }
  }
  for (int i = 0; i < ninputs; i++)
    if (one(STACK, 0, inputs[i], seed, kind, 1, &r) != 0) return 1;
  if (ex500.wall > 0 && nv.wall > 0)
    progname_eprintf("bench: at %d x %d the exact solver is %.0f times faster than the naive "
                    "reference (%.0f times fewer nodes), with the same optimum %s\n",
            naive, naive, nv.wall / ex500.wall, nv.nodes / ex500.nodes, ARGS_G(nv.cost));
  return 0;
}
