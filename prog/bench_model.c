/* bench_model.c -- section 7.2's model of one diagonal, cd/p + 2m(p-1),
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
#include "bench_model.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atomicfile.h"
#include "bench_list.h"
#include "contour.h"
#include "gen.h"
#include "run.h"
#include "xmem.h"

static int usage(const char *why, const char *val) {
  if (why) fprintf(stderr, "bench: %s (%s)\n", why, val ? val : "");
  fprintf(stderr, "usage: bench --model [--diag LIST] [--procs LIST] [--m S] [--c S] "
                  "[--net ideal|bus|loggp] [-o FILE]\n"
                  "       bench --glass [--slices N] [--points N] [-o FILE]\n");
  return 2;
}

int bench_model(int argc, char **argv) {
  bench_list diags = {0}, procs = {0};
  const char *outpath = NULL;
  run_config rc;
  run_config_init(&rc);
  char err[300];
  for (int i = 2; i < argc; i += 2) {   /* every option takes a value */
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!v) return usage("an option needs a value", a);
    if (strcmp(a, "--diag") == 0) {
      if (bench_list_parse(v, &diags, 1, 4, 5000) != 0) return usage("--diag takes a list of 4..5000", v);
    } else if (strcmp(a, "--procs") == 0) {
      if (bench_list_parse(v, &procs, 1, 1, 4096) != 0) return usage("--procs takes a list of 1..4096", v);
    } else if (strcmp(a, "-o") == 0) {
      outpath = v;
    } else {
      int k = run_option(&rc, a, v, err, sizeof err);
      if (k < 0) return usage(err, NULL);
      if (k == 0 || strcmp(a, "--procs") == 0) return usage("unknown option", a);
    }
  }
  if (diags.n == 0) bench_list_parse("100,250,500", &diags, 1, 4, 5000);
  if (procs.n == 0) bench_list_parse("2..16", &procs, 1, 1, 4096);
  atomicfile af = {NULL, NULL, NULL};
  FILE *f = stdout;
  if (outpath) {
    if (atomicfile_open(&af, outpath, "w", err, sizeof err) != 0) {
      fprintf(stderr, "bench: %s\n", err);
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
      run_config r = rc;
      r.procs = (int)procs.v[j];
      r.opt.only_mu0 = 1;
      r.machine.warn = NULL;
      int p = r.procs < 2 ? 1 : r.procs - 1;
      par_pair pr;
      memset(&pr, 0, sizeof pr);
      pr.P = P, pr.np = m, pr.zp = 0, pr.Q = Q, pr.nq = n, pr.zq = 5;
      if (run_sim(&r, &pr, 1, NULL, err, sizeof err) != 0) {
        fprintf(stderr, "bench: the run on %d processors failed: %s\n", r.procs, err);
        status = 1;
        break;
      }
      const sim_config *c = &r.machine;
      double model = c->c * D / p + 2 * (c->m / 2) * (p - 1);
      fprintf(f, "%d,%d,%d,%s,%.9g,%.9g,%d,%.9f,%.9g,%.9g,%.17g\n", D, r.procs, p, sim_net_name(c->net),
              c->m, c->c, m + n, pr.mu0_time, pr.mu0_time / (m + n), model, pr.t.cost);
      tiling_free(&pr.t);
    }
    free(P), free(Q);
  }
  if (outpath && atomicfile_close(&af, status == 0, err, sizeof err) != 0 && status == 0) {
    fprintf(stderr, "bench: %s\n", err);
    status = 1;
  }
  return status;
}

int bench_glass(int argc, char **argv) {
  int slices = 24, points = 96;
  const char *outpath = NULL;
  for (int i = 2; i < argc; i += 2) {   /* every option takes a value */
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    char *e = NULL;
    long x = v ? strtol(v, &e, 10) : 0;
    if (!v) return usage("an option needs a value", a);
    if (strcmp(a, "-o") == 0) outpath = v;
    else if (strcmp(a, "--slices") == 0 && !*e && x >= 3 && x <= 10000) slices = (int)x;
    else if (strcmp(a, "--points") == 0 && !*e && x >= 3 && x <= 100000) points = (int)x;
    else return usage("unknown option or bad value", a);
  }
  contour_stack s;
  gen_glass(&s, slices, points);
  char err[300];
  atomicfile af = {NULL, NULL, NULL};
  FILE *f = stdout;
  if (outpath) {
    if (atomicfile_open(&af, outpath, "w", err, sizeof err) != 0) {
      fprintf(stderr, "bench: %s\n", err);
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
    fprintf(stderr, "bench: %s\n", err);
    return 1;
  }
  return bad;
}
