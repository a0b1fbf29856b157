/* calibrate.c -- bench --calibrate: make the simulator model this host.
 *
 *   bench --calibrate [--points LIST] [--procs LIST] [--repeat R] [--seed S]
 *                     [--messages K] [--options-only]
 *
 * Measured here by micro-benchmarks (micro.h), never by the parallel
 * runs they then predict, each the fastest of R runs, in rounds:
 *   c, c_table  seconds per node: the serial solver on the generated pair,
 *               weights on the fly and (where the slaves use them) from
 *               tables, wall time / nodes;
 *   messages    two ranks of the threads backend: a ping-pong of small and
 *               of 64 KiB messages, a burst of sends and the burst's
 *               receives, a one-way stream, and a ping-pong whose receiver
 *               sleeps; from them the processor overheads of a send and of
 *               a receive (per message and per byte), the one-way latency,
 *               the gap per message and per byte, and the sleeper's wake-up
 *               and its waker's cost (micro_derive says how);
 *   slowdown    k copies of the serial solver at once, k = 1, 2, 4, ... up
 *               to the processors: the least-squares slope of each copy's
 *               time against k - 1, relative to one alone;
 *   table-c     a slave's weight table built alone (where slaves use one),
 *               wall time / its m (n+1) cells;
 *   back-c      a backtracking step of a slave (micro_backtrack): a bit
 *               looked up, the edge's weight computed, stored.
 * The options that make the simulator model this host follow from them:
 *   --net loggp --L L --o 0 --g g --G G --o-send .. --o-send-byte ..
 *   --o-recv .. --o-recv-byte .. --spin S --wake .. --o-wake ..
 *   --slowdown F --back-c B [--table-c T] --c C
 * (cpu.h states the model, par.h the two prices).  Then, for each size of
 * --points and each P of --procs, the paper's algorithm (or the variant the
 * options name) on the pair: measured on the threads backend and predicted
 * by the simulator with those options (c_table, the kernel's per node with
 * tables, for the P whose slaves use them; their build charged at
 * --table-c), one CSV row each with the relative
 * error (predicted / measured - 1), and beside it what the plain ideal
 * network with the ping-pong's one-way time as m predicts (the old
 * calibration).  With --options-only, no parallel run, measured or
 * simulated: one row per size and P with the first six columns alone (the
 * options that model this host for that P), for a script that runs the
 * simulator itself (tests/bench_cores.sh).  stderr says what was measured
 * and how long it all took. */
#include "prog/bench/bench.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "prog/bench/micro.h"
#include "prog/bench/paper.h"
#include "mp/cpuload.h"
#include "algo/par_slave.h"
#include "util/progname.h"
#include "util/progress.h"
#include "mp/threads.h"
#include "algo/tiling.h"
#include "util/wallclock.h"
#include "algo/weights.h"
#include "util/xmem.h"

static const char calibrate_usage[] =
    "usage: bench --calibrate [--points LIST] [--procs LIST] [--repeat R] [--seed S] [--messages K] "
    "[--alloc A] [--block k] [--schedule S] [--min-diag d] [--options-only]   (bench --help: every mode)\n";

/* Bad usage: "bench: why", arg (or NULL) shown after it, the usage line, 2. */
static int usage(const char *why, const char *arg) { return args_usage("bench", calibrate_usage, why, arg); }

typedef struct {
  double time;     /* the master's time for the pair */
  double cost;
  uint64_t nodes, msgs;
  mpt_stats ts;    /* threads runs: the backend's statistics */
} result;

static int one(bench_machine *rc, machine_backend b, int P, const vec2 *A, const vec2 *B, int n, result *out,
               char *err, size_t errlen) {
  rc->mc.backend = b;
  rc->mc.procs = P;
  par_pair pr;
  memset(&pr, 0, sizeof pr);
  pr.P = A, pr.np = n, pr.zp = 0, pr.Q = B, pr.nq = n, pr.zq = 5;
  memset(&out->ts, 0, sizeof out->ts);
  launch_extra x;
  memset(&x, 0, sizeof x);
  x.threads = &out->ts;   /* threads runs */
  int res = bench_run_pairs(rc, &pr, 1, &x, err, errlen);
  if (res != 0) return -1;
  out->time = pr.time;
  out->cost = pr.t.cost;
  out->nodes = pr.counts.nodes;
  out->msgs = 0;
  for (int k = 0; k < PAR_KINDS; k++) out->msgs += pr.counts.msgs[k];
  tiling_free(&pr.t);
  return 0;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/* Whether the slaves of a P-processor run use weight tables on n x n. */
static int slaves_tables(int P, const vec2 *A, const vec2 *B, int n) {
  int table = par_slave_table(P < 2 ? 1 : P - 1);
  if (table == 0) return 0;
  weights *w = weights_new(A, n, 0, B, n, 5, COST_AREA, table);
  int has = weights_has_table(w);
  weights_free(w);
  return has;
}

/* The simulator options of the model, c aside. */
static void model_options(const micro_model *d, double spin, double slowdown, double slowdown_spin, char *buf,
                          size_t len) {
  snprintf(buf, len,
           "--net loggp --L %.4g --o 0 --g %.4g --G %.4g --o-send %.4g --o-send-byte %.4g "
           "--o-recv %.4g --o-recv-byte %.4g --spin %.4g --wake %.4g --o-wake %.4g --slowdown %.4g "
           "--slowdown-spin %.4g",
           d->L, d->g, d->G, d->o_send, d->o_send_byte, d->o_recv, d->o_recv_byte, spin, d->wake,
           d->o_wake, slowdown, slowdown_spin);
}

/* The same, set in rc->mc.sim (through bench_option, as a user's would be). */
static void set_options(bench_machine *rc, const char *opts, double c) {
  char buf[900], err[200];
  snprintf(buf, sizeof buf, "%s --c %.4g", opts, c);
  sim_config_init(&rc->mc.sim);
  rc->mc.sim.warn = NULL;
  rc->pc.table_c = rc->pc.back_c = 0;
  char *save = NULL;
  for (char *o = strtok_r(buf, " ", &save); o; o = strtok_r(NULL, " ", &save)) {
    char *v = strtok_r(NULL, " ", &save);
    if (!v || bench_option(rc, o, v, err, sizeof err) != 1) xpanic("calibrate: option %s: %s", o, err);
  }
}

/* The busy cores' slowdown: k copies of the serial solver at once for
 * k = 1, 2, 4, ... cpus; the least-squares slope of (t_k / t_1 - 1) against
 * k - 1.  One line on stderr per k. */
static double slowdown(const vec2 *A, const vec2 *B, int n, int repeat, double *spin_slow) {
  int cpus = cpuload_cpus(), ks[32], nk = 0;
  for (int k = 1; k < cpus && nk < 30; k *= 2) ks[nk++] = k;
  ks[nk++] = cpus;
  double t[32], spun = -1;
  for (int i = 0; i < nk; i++) t[i] = -1;
  for (int r = 0; r < repeat; r++) {   /* in rounds, every k once a round: the fastest of each */
    for (int i = 0; i < nk; i++) {
      double x = micro_together(A, B, n, 0, ks[i], 0, 1);
      if (x > 0 && (t[i] < 0 || x < t[i])) t[i] = x;
    }
    if (cpus > 1) {
      double x = micro_together(A, B, n, 0, cpus, 1, 1);
      if (x > 0 && (spun < 0 || x < spun)) spun = x;
    }
  }
  double sxy = 0, sxx = 0;
  progname_eprintf("bench: busy cores: the serial solver (%d points) k times at once, each copy's mean time"
                  " (fastest of %d):\n", n, repeat);
  for (int i = 0; i < nk && t[0] > 0; i++) {
    if (t[i] < 0) continue;
    double f = t[i] / t[0], x = ks[i] - 1;
    sxy += x * (f - 1), sxx += x * x;
    progname_eprintf("bench:   k = %2d: %.6f s, %.3f times one alone\n", ks[i], t[i], f);
  }
  *spin_slow = 0;
  if (spun > 0 && t[0] > 0) {
    progname_eprintf("bench:   one copy beside %d spinning threads: %.6f s, %.3f times alone\n", cpus - 1, spun,
            spun / t[0]);
    double f = (spun / t[0] - 1) / (cpus - 1);
    *spin_slow = f > 0 ? f : 0;
  }
  double sl = sxx > 0 ? sxy / sxx : 0;
  return sl > 0 ? sl : 0;
}

int bench_calibrate(int argc, char **argv) {
  double w0 = wallclock();
  int repeat = 10, messages = 100000, options_only = 0;
  unsigned long long seed = 1993;
  args_list procs = {0}, sizes = {0};
  char msg[400];
  bench_machine rc;
  bench_machine_init(&rc);
  rc.mc.sim.warn = NULL;
  rc.mc.threads.warn = NULL;
  static const char *const algo_opts[] = {"--alloc", "--min-diag", "--block", "--schedule"};
  for (int i = 2; i < argc; i += 2) {   /* an option and its value */
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (strcmp(a, "--options-only") == 0) {   /* the one flag */
      options_only = 1;
      i--;
      continue;
    }
    long x = 0;
    int bad = 0;
    int known = strcmp(a, "--points") == 0 || strcmp(a, "--procs") == 0 || strcmp(a, "--repeat") == 0 ||
                strcmp(a, "--messages") == 0 || strcmp(a, "--seed") == 0;
    for (size_t k = 0; k < sizeof algo_opts / sizeof *algo_opts; k++) known |= strcmp(a, algo_opts[k]) == 0;
    if (!known) return usage(a[0] == '-' ? "unknown option" : "unexpected argument", a);
    if (!v) return usage("an option needs a value", a);
    if (strcmp(a, "--points") == 0) bad = args_list_parse(a, v, 1, 3, 100000, &sizes, msg, sizeof msg);
    else if (strcmp(a, "--procs") == 0) bad = args_list_parse(a, v, 1, 1, 64, &procs, msg, sizeof msg);
    else if (strcmp(a, "--repeat") == 0) bad = args_long(a, v, 1, 1000, &x, msg, sizeof msg), repeat = (int)x;
    else if (strcmp(a, "--messages") == 0)
      bad = args_long(a, v, 10, 100000000, &x, msg, sizeof msg), messages = (int)x;
    else if (strcmp(a, "--seed") == 0) bad = args_u64(a, v, 0, ULLONG_MAX, &seed, msg, sizeof msg);
    else bad = bench_option(&rc, a, v, msg, sizeof msg) != 1;   /* one of algo_opts */
    if (bad) return usage(msg, NULL);
  }
  if (procs.n == 0) args_list_parse("--procs", "1,2,3", 1, 1, 64, &procs, msg, sizeof msg);
  if (sizes.n == 0) args_list_parse("--points", "2000", 1, 3, 100000, &sizes, msg, sizeof msg);
  char err[300];

  /* P = 1 first: the speedups' base. */
  args_list order = procs;
  int has1 = 0;
  for (int i = 0; i < procs.n; i++) has1 |= procs.v[i] == 1;
  if (!has1) {
    order.v[0] = 1;
    for (int i = 0; i < procs.n && i + 1 < ARGS_LIST_MAX; i++) order.v[i + 1] = procs.v[i];
    order.n = procs.n + 1 < ARGS_LIST_MAX ? procs.n + 1 : ARGS_LIST_MAX;
  }

  /* The micro-benchmarks: messages, then busy cores. */
  micro_msgs mm;
  if (micro_messages(messages, repeat, &mm, err, sizeof err) != 0) {
    progname_eprintf("bench: the message benchmarks failed: %s\n", err);
    return 1;
  }
  micro_model d;
  micro_derive(&mm, &d);
  mpt_config tcfg;
  mpt_config_init(&tcfg);
  double spin = (double)tcfg.spin_ns * 1e-9;
  progname_eprintf(
          "bench: messages between threads (fastest of %d; %d messages, %d of the big ones):\n"
          "bench:   ping-pong one way: %.4g s (%zu bytes), %.4g s (%zu bytes)\n"
          "bench:   exchange with two neighbours (%d ranks in a ring): a send %.4g s, %.4g s; a receive %.4g s, %.4g s\n"
          "bench:   a stream: %.4g s a message\n"
          "bench:   a sleeping receiver, the sender idle %.4g s first: one way %.4g s, the send that wakes it %.4g s\n"
          "bench:   so o_send %.4g s + %.4g s/byte, o_recv %.4g s + %.4g s/byte, L %.4g s, g %.4g s, G %.4g s/byte,\n"
          "bench:      wake %.4g s after the arrival, o_wake %.4g s (beyond a spin of %.4g s)\n",
          repeat, messages, messages / 20 + 10, mm.pp_small, mm.small, mm.pp_big, mm.big, mm.exchange_ranks, mm.os_small, mm.os_big,
          mm.or_small, mm.or_big, mm.stream, mm.idle, mm.pp_sleep, mm.send_sleep, d.o_send, d.o_send_byte,
          d.o_recv, d.o_recv_byte, d.L, d.g, d.G, d.wake, d.o_wake, spin);

  vec2 *A0, *B0;
  bench_make_pair(seed, (int)sizes.v[0], &A0, &B0);
  double slow_spin, slow = slowdown(A0, B0, (int)sizes.v[0], repeat, &slow_spin);
  progname_eprintf("bench:   so slowdown %.4g per other working core (the least-squares slope), %.4g per spinning one\n",
          slow, slow_spin);
  double back = micro_backtrack(A0, B0, (int)sizes.v[0], repeat);
  free(A0), free(B0);
  progname_eprintf("bench: a backtracking step (a bit looked up, the edge's weight computed and stored): %.4g s\n",
          back);
  unsigned long long nblocks = 0;
  double block = micro_block(repeat, &nblocks);
  progname_eprintf("bench: a basic block of an MPI program (cpi's loop, %llu blocks): %.4g s, "
                  "tilesim-mpirun --compute blocks --block-c %.4g\n", nblocks, block, block);
  char opts[700];
  model_options(&d, spin, slow, slow_spin, opts, sizeof opts);
  snprintf(opts + strlen(opts), sizeof opts - strlen(opts), " --back-c %.4g", back > 0 ? back : 0);

  if (options_only)   /* the model alone: no parallel run, measured or simulated */
    printf("points,procs,slaves,tables,c,options\n");
  else
    printf("points,procs,slaves,tables,c,options,measured_s,predicted_s,error,measured_speedup,"
           "predicted_speedup,ideal_s,ideal_error,measured_median_s,sleeps,wake_us,nodes,messages,cost\n");
  int rcode = 0;
  progress *pg = progress_new(progname_as("bench"), "calibration rounds done:", 0);   /* a line every 5 s in a log */
  for (int si = 0; si < sizes.n && !rcode; si++) {
    int points = (int)sizes.v[si];
    vec2 *A, *B;
    bench_make_pair(seed, points, &A, &B);
    int *tab = xcalloc((size_t)order.n, sizeof *tab), any_tab = 0;
    for (int i = 0; i < order.n; i++) any_tab |= tab[i] = slaves_tables((int)order.v[i], A, B, points);
    /* In rounds: the serial solver (on the fly, and with tables if some
     * slaves use them), then the threads run at each P; the fastest of each. */
    double solve = -1, solve_t = -1, build = -1, serial_cost = 0;
    uint64_t nodes = 0;
    result *meas = xcalloc((size_t)order.n, sizeof *meas);
    double *all = xcalloc((size_t)order.n * (size_t)repeat, sizeof *all);   /* every run's time */
    for (int i = 0; i < order.n; i++) meas[i].time = -1;
    for (int r = 0; r < repeat && !rcode; r++) {
      progress_step(pg, (long long)si * repeat + r, (long long)sizes.n * repeat);
      if (any_tab) {   /* the table alone: what every slave that uses one builds first */
        double t0 = wallclock();
        weights *w = weights_new(A, points, 0, B, points, 5, COST_AREA, 1);
        double x = wallclock() - t0;
        weights_free(w);
        if (build < 0 || x < build) build = x;
      }
      for (int table = 0; table <= any_tab; table++) {
        tiling t;
        double t0 = wallclock();
        tiling_solve(A, points, 0, B, points, 5, COST_AREA, table, &t);
        double w = wallclock() - t0;
        if (table == 0 && (solve < 0 || w < solve)) solve = w;
        if (table == 1 && (solve_t < 0 || w < solve_t)) solve_t = w;
        nodes = t.count.nodes;
        serial_cost = t.cost;
        tiling_free(&t);
      }
      for (int j = 0; j < order.n && !options_only; j++) {
        int i = r % 2 ? order.n - 1 - j : j;   /* every other round backwards: no P always first */
        int P = (int)order.v[i];
        result x;
        if (one(&rc, MACHINE_THREADS, P, A, B, points, &x, err, sizeof err) != 0) {
          progname_eprintf("bench: the threads run on %d processors failed: %s\n", P, err);
          rcode = 1;
          break;
        }
        if (x.cost != serial_cost) {   /* (the variants may evaluate more nodes than the serial solver) */
          progname_eprintf("bench: the threads run on %d processors gave %s, the serial solver %s\n", P,
                  ARGS_G(x.cost), ARGS_G(serial_cost));
          rcode = 1;
          break;
        }
        if (meas[i].time < 0 || x.time < meas[i].time) meas[i] = x;
        all[(size_t)i * (size_t)repeat + (size_t)r] = x.time;
      }
    }
    /* c per node on the fly; with tables, the kernel's per node, and the
     * table each slave that uses one builds first, per cell: --table-c
     * (par.h; the slave charges its build, m (n+1) cells, to mp_compute). */
    double c = solve / (double)nodes, c_kern = c, table_c = 0;
    /* On a noisy machine the table's build alone (the fastest of R) can take
     * as long as the whole solve with it (the fastest of R): the two are
     * then not told apart, and the with-tables time goes per node, the
     * build included (--table-c 0), rather than a kernel of 0 s a node. */
    int apart = any_tab && solve_t > build;
    if (apart) c_kern = (solve_t - build) / (double)nodes, table_c = build / ((double)points * (points + 1));
    else if (any_tab) c_kern = solve_t / (double)nodes;
    char sopts[800];
    snprintf(sopts, sizeof sopts, "%s", opts);
    if (any_tab) snprintf(sopts + strlen(sopts), sizeof sopts - strlen(sopts), " --table-c %.4g", table_c);
    if (!rcode) {
      progname_eprintf("bench: %d points: c = %.4g s per node (the serial solver, %.6f s for %llu nodes)", points, c,
              solve, (unsigned long long)nodes);
      if (any_tab && !apart)
        progname_eprintf(";\nbench:   with weight tables %.6f s, of which %.6f s building the table: too noisy to tell\n"
                        "bench:   apart, so %.4g s per node with the table's build in it (--table-c 0)",
                solve_t, build, c_kern);
      else if (any_tab)
        progname_eprintf(";\nbench:   with weight tables %.6f s, of which %.6f s building the table: %.4g s per node\n"
                        "bench:   and %.4g s per cell of the table (%d x %d), which every slave that uses one builds",
                solve_t, build, c_kern, table_c, points, points + 1);
      progname_eprintf("\nbench: %d points: the simulator models this host with\n    %s --c %.4g%s\n", points, sopts,
              any_tab ? c : c, any_tab ? " (--c c_table where the slaves use tables)" : "");
    }
    for (int i = 0; i < order.n && options_only; i++) {   /* each P's options, as below */
      if (i == 0 && !has1) continue;
      double cp = tab[i] ? c_kern : c;
      printf("%d,%d,%d,%d,%.4g,%s --c %.4g\n", points, (int)order.v[i], order.v[i] < 2 ? 1 : (int)order.v[i] - 1, tab[i],
             cp, sopts, cp);
      fflush(stdout);
    }
    double pred1 = 0;
    for (int i = 0; i < order.n && !rcode && !options_only; i++) {
      int P = (int)order.v[i];
      int slaves = P < 2 ? 1 : P - 1;
      double cp = tab[i] ? c_kern : c;
      double cold = !tab[i] ? c : apart ? c_kern + build * slaves / (double)nodes : (solve_t + build * (slaves - 1)) / (double)nodes;
      result pred, ideal;
      set_options(&rc, sopts, cp);
      if (one(&rc, MACHINE_SIM, P, A, B, points, &pred, err, sizeof err) != 0) {
        progname_eprintf("bench: the simulated run on %d processors failed: %s\n", P, err);
        rcode = 1;
        break;
      }
      char iopt[200];
      snprintf(iopt, sizeof iopt, "--net ideal --m %.4g --per-byte %.4g", mm.pp_small,
               mm.pp_big > mm.pp_small ? (mm.pp_big - mm.pp_small) / (double)(mm.big - mm.small) : 0);
      set_options(&rc, iopt, cold);   /* the old calibration: the table spread over a slave's nodes */
      if (one(&rc, MACHINE_SIM, P, A, B, points, &ideal, err, sizeof err) != 0) {
        progname_eprintf("bench: the simulated run on %d processors failed: %s\n", P, err);
        rcode = 1;
        break;
      }
      if (i == 0) pred1 = pred.time;
      if (i == 0 && !has1) continue;
      const mpt_stats *ts = &meas[i].ts;
      double *mine = all + (size_t)i * (size_t)repeat;
      qsort(mine, (size_t)repeat, sizeof *mine, cmp_double);
      double med = repeat % 2 ? mine[repeat / 2] : (mine[repeat / 2 - 1] + mine[repeat / 2]) / 2;
      printf("%d,%d,%d,%d,%.4g,%s --c %.4g,%.6f,%.6f,%+.4f,%.3f,%.3f,%.6f,%+.4f,%.6f,%lld,%.1f,%llu,%llu,%.17g\n",
             points, P, slaves, tab[i], cp, sopts, cp, meas[i].time, pred.time, pred.time / meas[i].time - 1,
             meas[0].time / meas[i].time, pred1 / pred.time, ideal.time, ideal.time / meas[i].time - 1, med, ts->sleeps,
             ts->wakes ? ts->wake_s / (double)ts->wakes * 1e6 : 0.0, (unsigned long long)meas[i].nodes,
             (unsigned long long)meas[i].msgs, meas[i].cost);
      fflush(stdout);
    }
    free(meas);
    free(all);
    free(tab);
    free(A), free(B);
  }
  progress_step(pg, (long long)sizes.n * repeat, (long long)sizes.n * repeat);
  progress_end(pg);
  progname_eprintf("bench: the calibration took %.1f s\n", wallclock() - w0);
  return rcode;
}
