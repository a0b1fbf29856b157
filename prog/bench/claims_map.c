/* claims_map.c -- where the paper's claims hold: every configuration (a
 * network, a message cost m, a node cost c, a pair) swept on the paper's
 * setup and judged by the claims' one judge (judge.h).
 *
 *   bench --claims-map [--net LIST] [--m LIST] [--c LIST] [--seed LIST]
 *         [--input STACK --pair LIST] [--points LIST] [machine options]
 *         [--jobs N] [-o FILE]
 *
 * A configuration is one of each list: net (bus, ideal, loggp; under loggp
 * each m is the latency L, the other LogGP parameters from --o --g --G),
 * m, c and a pair: generated from a seed (sections 6's contours, default
 * 1993), or pair K of a real stack.  Its sweeps are the paper's (section 6
 * and 7; what make bench runs for Fig. 16, 18/19 and 20): contours of 100,
 * 200, .., 500 points (--points; a real pair has its own), P = 1..16, half
 * and size, d = 1; and d = 20, 40, .., 100 at the largest size, P = 1..16,
 * size.  Every run of every configuration goes to one pool of --jobs
 * workers (bench_sweep_runs); the output does not depend on --jobs.  The
 * judge sees each time as the sweep's CSV prints it (%.9f), so a row's
 * verdicts are those of bench --claims on the same sweeps made by ./bench.
 *
 * One CSV row per configuration: the configuration, claim1..claim7 (1, 0,
 * or n/a where the sweep cannot show the claim), and the figures behind
 * them (judge.h): t2_t1 and t3_t2 (the largest over the sizes that
 * count), t4_t3, t6_t5 (half) and size_t4_t3, size_t6_t5 at the largest
 * size, each allocation's best P and speedup there, and the best d. */
#include "prog/bench/bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "prog/bench/judge.h"
#include "prog/bench/paper.h"
#include "input/contour.h"
#include "util/progname.h"
#include "util/xmem.h"

static const char map_usage[] =
    "usage: bench --claims-map [--net LIST] [--m LIST] [--c LIST] [--seed LIST] [--input STACK --pair LIST] "
    "[--points LIST] [machine options] [--jobs N] [-o FILE]   (bench --help: every mode)\n";

static int usage(const char *why, const char *val) { return args_usage("bench", map_usage, why, val); }

enum { NDS = 5 };   /* d = 20, 40, .., 100 */

typedef struct {
  int nets[3], nnet;
  args_list ms, cs, seeds, pairs, points;
  int seeds_given;
  const char *input;
  int jobs;
  const char *out;
  bench_machine base;
} map_opts;

/* Options that would change what the map judges, or that it cannot record. */
static int refused(const char *a) {
  static const char *const no[] = {"--procs", "--alloc", "--min-diag", "--block", "--schedule", "--backend",
                                   "--topology", "--place", "--hop-latency", "--switching", "--spin", "--repeat",
                                   "--variant"};
  for (size_t i = 0; i < sizeof no / sizeof *no; i++)
    if (strcmp(a, no[i]) == 0) return 1;
  return 0;
}

static int parse(int argc, char **argv, map_opts *o) {
  memset(o, 0, sizeof *o);
  bench_machine_init(&o->base);
  o->base.mc.backend = MACHINE_SIM;
  o->jobs = 1;
  char err[300];
  for (int i = 2; i < argc; i += 2) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int bad = 0;
    if (refused(a)) return usage("the claims map runs the paper's setup on --net's machines; it does not take", a);
    if (!v) {
      static const char *const own[] = {"--net", "--m", "--c", "--seed", "--pair", "--points", "--input", "--jobs", "-o"};
      bench_machine scratch = o->base;
      int known = bench_option(&scratch, a, "", err, sizeof err) != 0;
      for (size_t k = 0; k < sizeof own / sizeof *own; k++) known |= strcmp(a, own[k]) == 0;
      return usage(known ? "an option needs a value" : "unknown option", a);
    }
    if (strcmp(a, "--net") == 0) {
      /* the words in sim_net's order: the index is the model */
      o->nnet = args_word_list(a, v, "ideal|bus|loggp", o->nets, 3, err, sizeof err);
      bad = o->nnet < 0;
      for (int x = 0; !bad && x < o->nnet; x++)
        for (int y = 0; y < x; y++)
          if (o->nets[x] == o->nets[y]) {
            snprintf(err, sizeof err, "--net names %s twice", sim_net_name((sim_net)o->nets[x]));
            bad = 1;
          }
    } else if (strcmp(a, "--m") == 0 || strcmp(a, "--c") == 0) {
      bad = args_list_parse(a, v, 0, 0, 1e9, a[2] == 'm' ? &o->ms : &o->cs, err, sizeof err);
    } else if (strcmp(a, "--seed") == 0) {
      bad = args_list_parse(a, v, 1, 0, 9007199254740992.0, &o->seeds, err, sizeof err);
      o->seeds_given = 1;
    } else if (strcmp(a, "--pair") == 0) {
      bad = args_list_parse(a, v, 1, 0, 1 << 30, &o->pairs, err, sizeof err);
    } else if (strcmp(a, "--points") == 0) {
      bad = args_list_parse(a, v, 1, 3, 100000, &o->points, err, sizeof err);
    } else if (strcmp(a, "--input") == 0) {
      bad = args_name(a, v, "a contour stack", 1, err, sizeof err);
      o->input = v;
    } else if (strcmp(a, "--jobs") == 0) {
      long x = 0;
      bad = args_long(a, v, 1, 256, &x, err, sizeof err);
      o->jobs = (int)x;
    } else if (strcmp(a, "-o") == 0) {
      bad = args_name(a, v, "a file name", 0, err, sizeof err);
      o->out = v;
    } else {
      int k = bench_option(&o->base, a, v, err, sizeof err);
      if (k == 0) return usage("unknown option", a);
      bad = k < 0;
    }
    if (bad) return usage(err, NULL);
  }
  if (o->pairs.n && !o->input) return usage("--pair needs --input (it picks pairs of a real stack)", NULL);
  if (o->input && !o->pairs.n) o->pairs.n = 1, o->pairs.v[0] = 0;
  if (o->input && o->points.n) return usage("--points is for generated pairs; a real pair has its own", NULL);
  if (!o->seeds_given && !o->input) o->seeds.n = 1, o->seeds.v[0] = 1993;
  if (!o->nnet) o->nnet = 1, o->nets[0] = (int)o->base.mc.sim.net;
  if (!o->ms.n) o->ms.n = 1, o->ms.v[0] = o->base.mc.sim.m;
  if (!o->cs.n) o->cs.n = 1, o->cs.v[0] = o->base.mc.sim.c;
  if (!o->points.n) args_list_parse("--points", "100,200,300,400,500", 1, 3, 100000, &o->points, err, sizeof err);
  return 0;
}

/* A time as the sweep's CSV prints it, read back. */
static double as_printed(double t) {
  char b[64];
  snprintf(b, sizeof b, "%.9f", t);
  return strtod(b, NULL);
}

static void field_claim(FILE *f, int h) { fputs(h < 0 ? ",n/a" : h ? ",1" : ",0", f); }

static void field_num(FILE *f, double x) {
  if (isnan(x)) fputs(",n/a", f);
  else fprintf(f, ",%.6f", x);
}

static void field_int(FILE *f, int x) {
  if (x <= 0) fputs(",n/a", f);
  else fprintf(f, ",%d", x);
}

int bench_claims_map(int argc, char **argv) {
  map_opts o;
  int u = parse(argc, argv, &o);
  if (u) return u;
  char err[400];
  if (o.out && atomicfile_check(o.out, err, sizeof err) != 0) {   /* before any work */
    progname_eprintf("bench: %s\n", err);
    return 1;
  }
  contour_stack stack = {0, NULL, 0};
  if (o.input) {
    if (contour_read(o.input, &stack, NULL, progname_as("bench"), err, sizeof err) != 0 ||
        contour_stack_pairs(&stack, o.input, err, sizeof err) != 0) {
      if (stack.c) contour_stack_free(&stack);
      progname_eprintf("bench: %s\n", err);
      return 1;
    }
    for (int i = 0; i < o.pairs.n; i++)
      if ((int)o.pairs.v[i] + 1 >= stack.n) {
        progname_eprintf("bench: %s has %d pairs, no pair %d\n", o.input, stack.n - 1, (int)o.pairs.v[i]);
        contour_stack_free(&stack);
        return 1;
      }
    if (strchr(o.input, ',') || strchr(o.input, '\n')) {
      progname_eprintf("bench: %s: a comma or newline in the name would break the CSV\n", o.input);
      contour_stack_free(&stack);
      return 1;
    }
  }
  /* The configurations: net, then pair (seeds, then real pairs), c, m. */
  int nsrc = o.seeds.n + (o.input ? o.pairs.n : 0);
  int ncfg = o.nnet * nsrc * o.cs.n * o.ms.n;
  bench_cfg *cfg = xcalloc((size_t)ncfg, sizeof *cfg);
  int *largest = xcalloc((size_t)ncfg, sizeof *largest);
  int k = 0;
  for (int a = 0; a < o.nnet; a++)
    for (int s = 0; s < nsrc; s++)
      for (int y = 0; y < o.cs.n; y++)
        for (int x = 0; x < o.ms.n; x++, k++) {
          bench_cfg *cf = &cfg[k];
          cf->rc = o.base;
          cf->rc.mc.sim.warn = NULL;
          cf->rc.mc.sim.net = (sim_net)o.nets[a];
          cf->rc.mc.sim.c = o.cs.v[y];
          if (cf->rc.mc.sim.net == SIM_NET_LOGGP) cf->rc.mc.sim.L = o.ms.v[x];
          else cf->rc.mc.sim.m = o.ms.v[x];
          if (s < o.seeds.n) {
            cf->seed = (unsigned long long)o.seeds.v[s];
            largest[k] = (int)o.points.v[0];
            for (int i = 1; i < o.points.n; i++)
              if ((int)o.points.v[i] > largest[k]) largest[k] = (int)o.points.v[i];
          } else {
            cf->input = &stack;
            cf->pair = (int)o.pairs.v[s - o.seeds.n];
            largest[k] = stack.c[cf->pair].n;
          }
          par_options po;
          if (par_config_prices(&cf->rc.pc, cf->rc.mc.sim.c, &po, err, sizeof err) != 0) {
            free(cfg), free(largest);
            contour_stack_free(&stack);
            return usage(err, NULL);
          }
        }
  /* Each configuration's runs: sizes x {half, size} x P, then d x P. */
  int per_gen = o.points.n * 2 * 16 + NDS * 16, per_real = 2 * 16 + NDS * 16;
  int nrun = 0;
  for (int c = 0; c < ncfg; c++) nrun += cfg[c].input ? per_real : per_gen;
  bench_run *run = xmallocarray((size_t)nrun, sizeof *run);
  int *first = xmallocarray((size_t)ncfg + 1, sizeof *first);
  int r = 0;
  for (int c = 0; c < ncfg; c++) {
    first[c] = r;
    int ns = cfg[c].input ? 1 : o.points.n;
    for (int i = 0; i < ns; i++)
      for (int al = 0; al < 2; al++)
        for (int P = 1; P <= 16; P++)
          run[r++] = (bench_run){c, cfg[c].input ? largest[c] : (int)o.points.v[i], P,
                                 al ? ALLOC_SIZE : ALLOC_HALF, 1};
    for (int d = 1; d <= NDS; d++)
      for (int P = 1; P <= 16; P++) run[r++] = (bench_run){c, largest[c], P, ALLOC_SIZE, 20 * d};
  }
  first[ncfg] = r;
  double *times = xmallocarray((size_t)nrun, sizeof *times);
  int bad = bench_sweep_runs(cfg, run, nrun, o.jobs, times, err, sizeof err) != 0;
  if (bad) progname_eprintf("bench: %s\n", err);

  FILE *f = stdout;
  atomicfile af = {NULL, NULL, NULL};
  if (!bad && o.out) {
    if (atomicfile_open(&af, o.out, "w", err, sizeof err) != 0) {
      progname_eprintf("bench: %s\n", err);
      bad = 1;
    }
    f = af.f;
  }
  if (!bad)
    fputs("net,m,c,m_over_c,L,o,g,G,per_byte,master_c,input,pair,seed,points,"
          "claim1,claim2,claim3,claim4,claim5,claim6,claim7,t2_t1,t3_t2,t4_t3,t6_t5,half_best_p,"
          "half_best_speedup,size_t4_t3,size_t6_t5,size_best_p,size_best_speedup,best_d\n",
          f);
  static judge_sweep js;
  for (int c = 0; !bad && c < ncfg; c++) {
    judge_init(&js);
    for (int i = first[c]; i < first[c + 1]; i++) {
      double t = as_printed(times[i]);
      if (run[i].d == 1) judge_add(&js, run[i].points, run[i].procs, run[i].alloc == ALLOC_SIZE, t);
      else judge_add_d(&js, run[i].points, run[i].d, t);
    }
    judge_verdict v;
    if (judge_run(&js, &v, err, sizeof err) != 0) xpanic("claims map: configuration %d %s", c, err);
    const sim_config *mc = &cfg[c].rc.mc.sim;
    double m = mc->net == SIM_NET_LOGGP ? mc->L : mc->m;
    fprintf(f, "%s,%.9g,%.9g", sim_net_name(mc->net), m, mc->c);
    if (mc->c > 0) fprintf(f, ",%.9g", m / mc->c);
    else fputs(",n/a", f);
    fprintf(f, ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,", mc->L, mc->o, mc->g, mc->G, mc->per_byte, par_config_master_c(&cfg[c].rc.pc, cfg[c].rc.mc.sim.c));
    if (cfg[c].input) fprintf(f, "%s,%d,n/a,%d", o.input, cfg[c].pair, v.points);
    else fprintf(f, "generated,n/a,%llu,%d", cfg[c].seed, v.points);
    for (int q = 1; q <= 7; q++) field_claim(f, v.holds[q]);
    field_num(f, v.t2_t1), field_num(f, v.t3_t2), field_num(f, v.t4_t3), field_num(f, v.t6_t5);
    field_int(f, v.half_best_p), field_num(f, v.half_best);
    field_num(f, v.size_t4_t3), field_num(f, v.size_t6_t5);
    field_int(f, v.size_best_p), field_num(f, v.size_best);
    field_int(f, v.best_d);
    fputc('\n', f);
  }
  if (!bad && o.out && atomicfile_close(&af, 1, err, sizeof err) != 0) {
    progname_eprintf("bench: %s\n", err);
    bad = 1;
  }
  free(times), free(run), free(first), free(cfg), free(largest);
  contour_stack_free(&stack);
  return bad ? 1 : 0;
}
