/* model.c -- section 7.2's model of one diagonal, cd/p + 2m(p-1),
 * against the simulated machine; and the glass of Fig. 17.
 *
 *   bench --model [--diag LIST] [--procs LIST] [--m S] [--c S] [--net MODEL] ...
 *
 * For each diagonal length D: a pair of D-1 and 20 D points, so that mu(0)'s
 * band is a strip whose diagonals (all but the two ends) hold D nodes.  Only
 * mu(0) is computed (par_options.only_mu0), by p = P-1 slaves (P = 1: one),
 * and the slaves' time on its diagonals is divided by their number.  The
 * paper's model counts a message twice, sent and received, each costing its
 * m: our bus charges one message m for both, so the model's m is ours over 2:
 * cD/p + 2 (m/2) (p-1) = cD/p + m (p-1), smallest at p = sqrt(cD/m). */
#include "prog/bench/bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "input/contour.h"
#include "input/gen.h"
#include "util/progname.h"
#include "prog/bench/paper.h"
#include "util/xmem.h"

static const char model_usage[] =
    "usage: bench --model [--diag LIST] [--procs LIST] [-o FILE] [--m S] [--c S] [--net ideal|bus|loggp] "
    "[machine options]   (bench --model --help: every option)\n";
static const char glass_usage[] =
    "usage: bench --glass [--slices N] [--points N] [-o FILE]   (bench --help: every mode)\n";

/* Bad usage: "bench: why", arg (or NULL) shown after it, the mode's usage line, 2. */
static int usage(const char *line, const char *why, const char *arg) { return args_usage("bench", line, why, arg); }

int bench_model(int argc, char **argv) {
  args_list diags = {0}, procs = {0};
  const char *outpath = NULL;
  bench_machine rc;
  bench_machine_init(&rc);
  char err[400];
  for (int i = 2; i < argc; i += 2) {   /* every option takes a value */
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int bad = 0;
    if (strcmp(a, "--backend") == 0)   /* bench_option takes it; the model is the simulator's */
      return usage(model_usage, "--model runs the simulated machine; it does not take", a);
    bench_machine scratch = rc;
    int theirs = strcmp(a, "--procs") != 0 && bench_option(&scratch, a, "", err, sizeof err) != 0;
    if (strcmp(a, "--diag") != 0 && strcmp(a, "--procs") != 0 && strcmp(a, "-o") != 0 && !theirs)
      return usage(model_usage, a[0] == '-' ? "unknown option" : "unexpected argument", a);
    if (!v) return usage(model_usage, "an option needs a value", a);
    if (strcmp(a, "--diag") == 0) bad = args_list_parse(a, v, 1, 4, 5000, &diags, err, sizeof err);
    else if (strcmp(a, "--procs") == 0) bad = args_list_parse(a, v, 1, 1, MACHINE_MAX_PROCS, &procs, err, sizeof err);
    else if (strcmp(a, "-o") == 0) bad = args_name(a, v, "a file name", 0, err, sizeof err), outpath = v;
    else bad = bench_option(&rc, a, v, err, sizeof err) < 0;
    if (bad) return usage(model_usage, err, NULL);
  }
  if (diags.n == 0) args_list_parse("--diag", "100,250,500", 1, 4, 5000, &diags, err, sizeof err);
  if (procs.n == 0) args_list_parse("--procs", "2..16", 1, 1, MACHINE_MAX_PROCS, &procs, err, sizeof err);
  atomicfile af = {NULL, NULL, NULL};
  FILE *f = stdout;
  if (outpath) {
    if (atomicfile_open(&af, outpath, "w", err, sizeof err) != 0) {
      progname_eprintf("bench: %s\n", err);
      return 1;
    }
    f = af.f;
  }
  fprintf(f, "diag,procs,slaves,net,m,c,diagonals,mu0_time,sim_per_diag,model_per_diag,cost\n");
  int status = 0;
  for (int i = 0; i < diags.n && !status; i++) {
    int D = (int)diags.v[i], m = D - 1, n = 20 * D;
    rng g;
    rng_seed(&g, 1993 + (unsigned long long)D);
    vec2 *P = xmallocarray((size_t)m, sizeof *P), *Q = xmallocarray((size_t)n, sizeof *Q);
    gen_star(&g, P, m, 0, 0, 100, 0.3);
    gen_star(&g, Q, n, 1, -1, 95, 0.3);
    for (int j = 0; j < procs.n && !status; j++) {
      bench_machine r = rc;
      r.mc.procs = (int)procs.v[j];
      r.pc.opt.only_mu0 = 1;
      r.mc.sim.warn = NULL;
      r.mc.backend = MACHINE_SIM;   /* the model's, in an MPI build too */
      int p = r.mc.procs < 2 ? 1 : r.mc.procs - 1;
      par_pair pr;
      memset(&pr, 0, sizeof pr);
      pr.P = P, pr.np = m, pr.zp = 0, pr.Q = Q, pr.nq = n, pr.zq = 5;
      if (bench_run_pairs(&r, &pr, 1, NULL, err, sizeof err) != 0) {
        progname_eprintf("bench: the run on %d processors failed: %s\n", r.mc.procs, err);
        status = 1;
        break;
      }
      const sim_config *c = &r.mc.sim;
      double model = c->c * D / p + 2 * (c->m / 2) * (p - 1);
      fprintf(f, "%d,%d,%d,%s,%.9g,%.9g,%d,%.9f,%.9g,%.9g,%.17g\n", D, r.mc.procs, p, sim_net_name(c->net),
              c->m, c->c, m + n, pr.mu0_time, pr.mu0_time / (m + n), model, pr.t.cost);
      tiling_free(&pr.t);
    }
    free(P), free(Q);
  }
  if (outpath && atomicfile_close(&af, status == 0, err, sizeof err) != 0 && status == 0) {
    progname_eprintf("bench: %s\n", err);
    status = 1;
  }
  return status;
}

int bench_glass(int argc, char **argv) {
  int slices = 24, points = 96;
  const char *outpath = NULL;
  char err[400];
  for (int i = 2; i < argc; i += 2) {   /* every option takes a value */
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    long x = 0;
    int bad = 0;
    if (strcmp(a, "-o") != 0 && strcmp(a, "--slices") != 0 && strcmp(a, "--points") != 0)
      return usage(glass_usage, a[0] == '-' ? "unknown option" : "unexpected argument", a);
    if (!v) return usage(glass_usage, "an option needs a value", a);
    if (strcmp(a, "-o") == 0) bad = args_name(a, v, "a file name", 0, err, sizeof err), outpath = v;
    else if (strcmp(a, "--slices") == 0) bad = args_long(a, v, 3, 10000, &x, err, sizeof err), slices = (int)x;
    else bad = args_long(a, v, 3, 100000, &x, err, sizeof err), points = (int)x;
    if (bad) return usage(glass_usage, err, NULL);
  }
  contour_stack s;
  gen_glass(&s, slices, points);
  atomicfile af = {NULL, NULL, NULL};
  FILE *f = stdout;
  if (outpath) {
    if (atomicfile_open(&af, outpath, "w", err, sizeof err) != 0) {
      progname_eprintf("bench: %s\n", err);
      contour_stack_free(&s);
      return 1;
    }
    f = af.f;
  }
  fprintf(f, "# A wine glass (the paper's Fig. 17): %d slices of %d points, generated by tilesim\n",
          slices, points);
  int bad = contour_write(f, &s) != 0;
  contour_stack_free(&s);
  if (outpath && atomicfile_close(&af, !bad, err, sizeof err) != 0) {
    progname_eprintf("bench: %s\n", err);
    return 1;
  }
  return bad;
}
