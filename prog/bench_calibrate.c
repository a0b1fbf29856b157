/* bench_calibrate.c -- bench --calibrate: make the simulator model this host.
 *
 *   bench --calibrate [--points N] [--procs LIST] [--repeat R] [--seed S]
 *                     [--messages K]
 *
 * Measured here, each the fastest of R runs (what else runs on the machine
 * only adds time):
 *   c         seconds per node: the serial solver on the generated pair of
 *             N points (the kernels the slaves run), wall time / nodes;
 *   m         seconds per message, one way: two ranks of the threads backend
 *             send a 20-byte message (a boundary message's size) back and
 *             forth K times, wall time / 2K;
 *   per_byte  seconds per byte: the same with 64 KiB messages, less m, per byte.
 * Then, for each P of the list, the paper's algorithm on the pair: measured
 * on the threads backend, and predicted by the simulator on the ideal
 * network with those m, c and per_byte (--net ideal --m M --c C --per-byte B,
 * printed in the options column, ready to paste).  One CSV row per P with
 * both times, the relative error (predicted / measured - 1), both speedups
 * T(1)/T(P), and the pair's optimum as a checksum.
 *
 * What the simulator cannot know: the threads share the host's cores (P
 * ranks on 2 cores here, where the simulator gives each rank a processor of
 * its own for P >= 2, and lets master and slave share one at P = 1), and
 * two cores that both work lose time to each other (caches, memory, the
 * hypervisor).  A line on stderr measures the latter: the serial solver
 * twice at once on two threads, against once alone.
 *
 * Measurements go in rounds (the serial solver, the pair of solvers, then
 * the threads run at each P) and each figure is the fastest over the
 * rounds, so that a slow spell of the machine touches them all alike. */
#include "bench_calibrate.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_list.h"
#include "bench_paper.h"
#include "run.h"
#include "threads.h"
#include "tiling.h"
#include "wallclock.h"
#include "xmem.h"

static int usage(const char *why, const char *val) {
  if (why) fprintf(stderr, "bench: %s (%s)\n", why, val ? val : "");
  fprintf(stderr, "usage: bench --calibrate [--points N] [--procs LIST] [--repeat R] [--seed S] "
                  "[--messages K]\n");
  return 2;
}

/* ==== the ping-pong ======================================================= */

typedef struct {
  int rounds;
  size_t len;
  int bad;
} pingpong;

static void pingpong_main(mp *self, void *ud) {
  pingpong *p = ud;
  int me = mp_rank(self);
  unsigned char *buf = xcalloc(p->len ? p->len : 1, 1);
  for (int i = 0; i < p->rounds; i++) {
    buf[0] = (unsigned char)i;
    if (me == 0) {
      p->bad += mp_send(self, 1, 0, buf, p->len) != MP_OK;
      p->bad += mp_recv(self, 1, 0, buf, p->len, NULL) != MP_OK || buf[0] != (unsigned char)i;
    } else {
      p->bad += mp_recv(self, 0, 0, buf, p->len, NULL) != MP_OK || buf[0] != (unsigned char)i;
      p->bad += mp_send(self, 0, 0, buf, p->len) != MP_OK;
    }
  }
  free(buf);
}

/* Seconds per one-way message of len bytes, the fastest of `repeat` runs of
 * `rounds` round trips; < 0 if a run failed. */
static double one_way(int rounds, size_t len, int repeat, char *err, size_t errlen) {
  double best = -1;
  for (int r = 0; r < repeat; r++) {
    mpt_config cfg;
    mpt_config_init(&cfg);
    mpt *t = mpt_new(&cfg, 2, err, errlen);
    if (!t) return -1;
    pingpong pp = {rounds, len, 0};
    mp_proc procs[2] = {{pingpong_main, &pp}, {pingpong_main, &pp}};
    int rc = mpt_run(t, procs, err, errlen);
    double w = mpt_stats_get(t)->wall_s / (2.0 * rounds);
    mpt_free(t);
    if (rc != 0 || pp.bad) {
      if (rc == 0) snprintf(err, errlen, "the ping-pong delivered wrong messages");
      return -1;
    }
    if (best < 0 || w < best) best = w;
  }
  return best;
}

/* ==== two solves at once ================================================== */

typedef struct {
  const vec2 *A, *B;
  int n;
  double wall;
} solo;

static void *solve_thread(void *ud) {
  solo *s = ud;
  tiling t;
  double t0 = wallclock();
  tiling_solve(s->A, s->n, 0, s->B, s->n, 5, COST_AREA, -1, &t);
  s->wall = wallclock() - t0;
  tiling_free(&t);
  return NULL;
}

/* The serial solver on two threads at once: the slower one's time.  What
 * the two cores lose to each other when both work (shared caches, memory,
 * the hypervisor), which no simulated processor loses.  < 0 on failure. */
static double two_at_once(const vec2 *A, const vec2 *B, int n) {
  solo s[2] = {{A, B, n, 0}, {A, B, n, 0}};
  pthread_t t[2];
  for (int i = 0; i < 2; i++)
    if (pthread_create(&t[i], NULL, solve_thread, &s[i]) != 0) {
      if (i == 1) pthread_join(t[0], NULL);
      return -1;
    }
  for (int i = 0; i < 2; i++) pthread_join(t[i], NULL);
  return s[0].wall > s[1].wall ? s[0].wall : s[1].wall;
}

/* ==== the runs ============================================================ */

typedef struct {
  double time;     /* the master's time for the pair */
  double cost;
  uint64_t nodes, msgs;
} result;

static int one(run_config *rc, run_backend b, int P, const vec2 *A, const vec2 *B, int n, result *out,
               char *err, size_t errlen) {
  rc->backend = b;
  rc->procs = P;
  par_pair pr;
  memset(&pr, 0, sizeof pr);
  pr.P = A, pr.np = n, pr.zp = 0, pr.Q = B, pr.nq = n, pr.zq = 5;
  if (run_pairs(rc, &pr, 1, err, errlen) != 0) return -1;
  out->time = pr.time;
  out->cost = pr.t.cost;
  out->nodes = pr.counts.nodes;
  out->msgs = 0;
  for (int k = 0; k < PAR_KINDS; k++) out->msgs += pr.counts.msgs[k];
  tiling_free(&pr.t);
  return 0;
}

int bench_calibrate(int argc, char **argv) {
  int points = 2000, repeat = 10, messages = 100000;
  unsigned long long seed = 1993;
  bench_list procs = {0};
  for (int i = 2; i < argc; i += 2) {   /* an option and its value */
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    char *e;
    if (!v) return usage("an option needs a value", a);
    if (strcmp(a, "--points") == 0) {
      long x = strtol(v, &e, 10);
      if (*e || e == v || x < 3 || x > 100000) return usage("--points takes 3..100000", v);
      points = (int)x;
    } else if (strcmp(a, "--procs") == 0) {
      if (bench_list_parse(v, &procs, 1, 1, 64) != 0) return usage("--procs takes a list of 1..64", v);
    } else if (strcmp(a, "--repeat") == 0) {
      long x = strtol(v, &e, 10);
      if (*e || e == v || x < 1 || x > 1000) return usage("--repeat takes 1..1000", v);
      repeat = (int)x;
    } else if (strcmp(a, "--messages") == 0) {
      long x = strtol(v, &e, 10);
      if (*e || e == v || x < 10 || x > 100000000) return usage("--messages takes 10..1e8", v);
      messages = (int)x;
    } else if (strcmp(a, "--seed") == 0) {
      seed = strtoull(v, &e, 10);
      if (*e || e == v) return usage("--seed takes a whole number", v);
    } else {
      return usage("unknown option", a);
    }
  }
  if (procs.n == 0) bench_list_parse("1,2,3", &procs, 1, 1, 64);
  char err[300];
  vec2 *A, *B;
  bench_make_pair(seed, points, &A, &B);

  /* P = 1 first: the speedups' base. */
  bench_list order = procs;
  int has1 = 0;
  for (int i = 0; i < procs.n; i++) has1 |= procs.v[i] == 1;
  if (!has1) {
    order.v[0] = 1;
    for (int i = 0; i < procs.n && i + 1 < BENCH_LIST_MAX; i++) order.v[i + 1] = procs.v[i];
    order.n = procs.n + 1 < BENCH_LIST_MAX ? procs.n + 1 : BENCH_LIST_MAX;
  }
  run_config rc;
  run_config_init(&rc);
  rc.machine.warn = NULL;
  rc.threads.warn = NULL;
  char e2[300];
  if (run_option(&rc, "--net", "ideal", e2, sizeof e2) != 1) xpanic("--net ideal");

  /* The measurements, in rounds: the serial solver, then the threads run
   * at each P; the fastest of each over the rounds.  Rounds rather than R
   * runs in a row, so that a slow spell of the machine (other work, its
   * neighbours in a virtual machine) touches every figure alike. */
  int rcode = 0;
  double solve = -1, serial_cost = 0, pair_of = -1;
  uint64_t nodes = 0;
  result *meas = xcalloc((size_t)order.n, sizeof *meas);
  for (int i = 0; i < order.n; i++) meas[i].time = -1;
  for (int r = 0; r < repeat && !rcode; r++) {
    tiling t;
    double t0 = wallclock();
    tiling_solve(A, points, 0, B, points, 5, COST_AREA, -1, &t);
    double w = wallclock() - t0;
    if (solve < 0 || w < solve) solve = w;
    nodes = t.count.nodes;
    serial_cost = t.cost;
    tiling_free(&t);
    double two = two_at_once(A, B, points);
    if (two > 0 && (pair_of < 0 || two < pair_of)) pair_of = two;
    for (int i = 0; i < order.n; i++) {
      int P = (int)order.v[i];
      result x;
      if (one(&rc, RUN_THREADS, P, A, B, points, &x, err, sizeof err) != 0) {
        fprintf(stderr, "bench: the threads run on %d processors failed: %s\n", P, err);
        rcode = 1;
        break;
      }
      if (x.cost != serial_cost || x.nodes != nodes) {
        fprintf(stderr, "bench: the threads run on %d processors gave %.17g, the serial solver %.17g\n", P,
                x.cost, serial_cost);
        rcode = 1;
        break;
      }
      if (meas[i].time < 0 || x.time < meas[i].time) meas[i] = x;
    }
  }
  /* m and per_byte: the ping-pong. */
  size_t small = 20, big = 65536;
  double m = rcode ? -1 : one_way(messages, small, repeat, err, sizeof err);
  double mbig = m < 0 ? -1 : one_way(messages / 20 + 10, big, repeat, err, sizeof err);
  if (!rcode && (m < 0 || mbig < 0)) {
    fprintf(stderr, "bench: the ping-pong failed: %s\n", err);
    rcode = 1;
  }
  if (rcode) {
    free(meas);
    free(A), free(B);
    return rcode;
  }
  double c = solve / (double)nodes;
  double per_byte = mbig > m ? (mbig - m) / (double)(big - small) : 0;
  fprintf(stderr,
          "bench: c = %.4g s per node: the serial solver, %.6f s for %llu nodes (%d points, fastest of %d)\n"
          "bench: m = %.4g s per message: threads ping-pong of %zu bytes, one way (%d round trips, fastest of %d)\n"
          "bench: per_byte = %.4g s: the same with %zu-byte messages, %.4g s one way\n",
          c, solve, (unsigned long long)nodes, points, repeat, m, small, messages, repeat, per_byte, big, mbig);
  if (pair_of > 0)
    fprintf(stderr,
            "bench: two serial solves at once, on two threads: %.6f s, %.3f times one solve (what the\n"
            "       cores lose to each other when both work; no simulated processor does)\n",
            pair_of, pair_of / solve);

  /* The simulator's predictions with those costs. */
  char options[160];
  snprintf(options, sizeof options, "--net ideal --m %.4g --c %.4g --per-byte %.4g", m, c, per_byte);
  rc.machine.m = m, rc.machine.c = c, rc.machine.per_byte = per_byte;
  printf("points,procs,c,m,per_byte,options,measured_s,predicted_s,error,measured_speedup,"
         "predicted_speedup,nodes,messages,cost\n");
  double pred1 = 0;
  for (int i = 0; i < order.n; i++) {
    int P = (int)order.v[i];
    result pred;
    if (one(&rc, RUN_SIM, P, A, B, points, &pred, err, sizeof err) != 0) {
      fprintf(stderr, "bench: the simulated run on %d processors failed: %s\n", P, err);
      rcode = 1;
      break;
    }
    if (i == 0) pred1 = pred.time;
    if (i == 0 && !has1) continue;
    printf("%d,%d,%.4g,%.4g,%.4g,%s,%.6f,%.6f,%+.4f,%.3f,%.3f,%llu,%llu,%.17g\n", points, P, c, m,
           per_byte, options, meas[i].time, pred.time, pred.time / meas[i].time - 1,
           meas[0].time / meas[i].time, pred1 / pred.time, (unsigned long long)meas[i].nodes,
           (unsigned long long)meas[i].msgs, meas[i].cost);
  }
  free(meas);
  free(A), free(B);
  return rcode;
}
