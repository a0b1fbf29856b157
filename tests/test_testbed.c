/* test_testbed.c -- the testbed's C API (machine/tilesim.h) for programs that
 * drive many runs in one process: a machine, a run, its statistics.
 *
 * Runs are checked against closed forms of sim.h's model with binary-fraction
 * costs (exact), and against the simulator's own statistics of the same run;
 * options against the machine's parser that ./tile and ./bench use. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "machine/machine.h"
#include "tests/parmachine.h"
#include "machine/tilesim.h"

static tilesim_machine *machine(const char *const *opts) {
  tilesim_machine *m = tilesim_machine_new();
  char err[512];
  for (int i = 0; opts[i]; i += 2)
    CHECK(tilesim_machine_option(m, opts[i], opts[i + 1], err, sizeof err) == 1, "%s %s: %s", opts[i], opts[i + 1], err);
  return m;
}

typedef struct {
  int laps;
  int units;   /* rank 0 computes this many units before each lap */
} ring_arg;

static void ring(mp *self, void *ud) {
  const ring_arg *a = ud;
  int me = mp_rank(self), n = mp_size(self);
  double tok = 0;
  for (int k = 0; k < a->laps; k++) {
    if (me == 0) {
      mp_compute(self, a->units);
      mp_send(self, (me + 1) % n, 0, &tok, sizeof tok);
      mp_recv(self, (me + n - 1) % n, 0, &tok, sizeof tok, NULL);
    } else {
      mp_recv(self, (me + n - 1) % n, 0, &tok, sizeof tok, NULL);
      mp_send(self, (me + 1) % n, 0, &tok, sizeof tok);
    }
  }
}

/* A sweep: one machine, --m changed between runs; each run's makespan is
 * laps (units c + n (m + 8 per_byte)), and its statistics are sums over the
 * ranks of what each did. */
static void test_sweep(void) {
  const char *opts[] = {"--procs", "5", "--net", "ideal", "--c", "0.125", "--per-byte", "0.0625", NULL};
  tilesim_machine *m = machine(opts);
  ring_arg a = {3, 2};
  char err[512];
  for (int k = 0; k < 4; k++) {
    char mv[16];
    double mm = 0.25 * (k + 1);
    snprintf(mv, sizeof mv, "%g", mm);
    CHECK(tilesim_machine_option(m, "--m", mv, err, sizeof err) == 1, "--m %s: %s", mv, err);
    tilesim_stats st;
    int rc = tilesim_run(m, 5, ring, &a, &st, err, sizeof err);
    double expect = 3 * (2 * 0.125 + 5 * (mm + 8 * 0.0625));
    CHECK(rc == 0 && st.makespan == expect, "sweep --m %g: rc %d, makespan %.17g, the model says %.17g (%s)", mm, rc,
          st.makespan, expect, err);
    CHECK(strcmp(st.backend, "sim") == 0 && st.ranks == 5 && st.procs == 5 && st.messages == 15 && st.bytes == 120 &&
              st.measured == 2,
          "sweep: %s %d ranks %d procs %lld messages %lld bytes", st.backend, st.ranks, st.procs, st.messages, st.bytes);
    CHECK(st.compute_sum == 3 * 2 * 0.125 && st.compute_max == st.compute_sum && st.unread == 0 && !st.deadlock,
          "sweep: compute %g (max %g)", st.compute_sum, st.compute_max);
  }
  /* More ranks than processors, the same program: 10 ranks on 5 (r mod 5). */
  tilesim_stats st;
  CHECK(tilesim_run(m, 10, ring, &a, &st, err, sizeof err) == 0 && st.ranks == 10 && st.procs == 5, "10 ranks on 5: %s", err);
  CHECK(tilesim_machine_ranks(m) == 5, "the default ranks: one per processor (%d)", tilesim_machine_ranks(m));
  CHECK(tilesim_machine_option(m, "--ranks", "7", err, sizeof err) == 1 && tilesim_machine_ranks(m) == 7, "--ranks 7");
  CHECK(tilesim_run(m, 0, ring, &a, &st, err, sizeof err) == -1 && strstr(err, "0 ranks"), "0 ranks: %s", err);
  tilesim_machine_free(m);
}

/* The statistics are the simulator's: the same run through sim.h directly. */
static void busy(mp *self, void *ud) {
  (void)ud;
  int me = mp_rank(self), v = me;
  mp_compute(self, me + 1);
  if (me > 0) mp_send(self, 0, 1, &v, sizeof v);
  else
    for (int i = 1; i < mp_size(self); i++) mp_recv(self, MP_ANY, 1, &v, sizeof v, NULL);
  mp_sleep(self, 0.5);
}

static void test_against_sim(void) {
  const char *opts[] = {"--procs", "2", "--net", "loggp", "--L", "0.5", "--o", "0.25", "--g", "0.125", "--c", "0.25", NULL};
  tilesim_machine *m = machine(opts);
  tilesim_stats st;
  char err[512];
  CHECK(tilesim_run(m, 4, busy, NULL, &st, err, sizeof err) == 0, "busy: %s", err);
  /* The same run on the simulator by hand: 4 ranks on 2 processors, r mod 2. */
  machine_config mc;
  machine_config_init(&mc);
  mc.sim.warn = NULL;
  const char *const *o = opts;
  for (int i = 0; o[i]; i += 2) machine_option(&mc, o[i], o[i + 1], err, sizeof err);
  sim_config cfg = mc.sim;
  int place[4] = {0, 1, 0, 1};
  cfg.procs = 2;
  cfg.place = place;
  sim *s = sim_new(&cfg, 4, err, sizeof err);
  mp_proc pr[4];
  for (int r = 0; r < 4; r++) pr[r] = (mp_proc){busy, NULL};
  CHECK(sim_run(s, pr, err, sizeof err) == 0, "sim: %s", err);
  const sim_stats *ss = sim_stats_get(s);
  double cs = 0, cm = 0, ws = 0, wm = 0, os = 0, om = 0, qs = 0, qm = 0, sl = 0;
  for (int r = 0; r < 4; r++) {
    const sim_rank_stats *rs = sim_rank(s, r);
    cs += rs->compute, ws += rs->recv_wait, os += rs->overhead, qs += rs->cpu_wait, sl += rs->slept;
    if (rs->compute > cm) cm = rs->compute;
    if (rs->recv_wait > wm) wm = rs->recv_wait;
    if (rs->overhead > om) om = rs->overhead;
    if (rs->cpu_wait > qm) qm = rs->cpu_wait;
  }
  CHECK(st.makespan == ss->makespan && st.messages == ss->messages && st.bytes == ss->bytes && st.compute_sum == cs &&
            st.compute_max == cm && st.wait_sum == ws && st.wait_max == wm && st.overhead_sum == os &&
            st.overhead_max == om && st.cpu_wait_sum == qs && st.cpu_wait_max == qm && st.slept_sum == sl && sl == 2,
        "the statistics are not the simulator's: makespan %g/%g compute %g/%g wait %g/%g overhead %g/%g cpu_wait %g/%g",
        st.makespan, ss->makespan, st.compute_sum, cs, st.wait_sum, ws, st.overhead_sum, os, st.cpu_wait_sum, qs);
  CHECK(cs == 0.25 * (1 + 2 + 3 + 4) && om > 0 && qs > 0, "busy: compute %g, overhead max %g, cpu_wait %g", cs, om, qs);
  sim_free(s);
  /* The CSV: a header and a row of as many fields. */
  char *text = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  tilesim_stats_csv(f, &st, 1);
  fclose(f);
  int commas[2] = {0, 0}, line = 0;
  for (size_t i = 0; i < len; i++) {
    if (text[i] == '\n') line++;
    else if (text[i] == ',' && line < 2) commas[line]++;
  }
  CHECK(line == 2 && commas[0] == 16 && commas[1] == 16, "the summary: %d lines, %d and %d commas:\n%s", line, commas[0],
        commas[1], text);
  CHECK(strncmp(text + strcspn(text, "\n") + 1, "sim,4,2,", 8) == 0, "the summary's row: %s", text);
  free(text);
  tilesim_machine_free(m);
}

/* Different mains per rank, and the threads backend: the same deliveries. */
static void producer(mp *self, void *ud) {
  int *v = ud;
  for (int i = 0; i < 5; i++) mp_send(self, 1, 2, v, sizeof *v);
}

static void consumer(mp *self, void *ud) {
  int *sum = ud, v;
  for (int i = 0; i < 5; i++) {
    mp_recv(self, 0, 2, &v, sizeof v, NULL);
    *sum += v;
  }
}

static void test_procs(void) {
  for (int be = 0; be < 2; be++) {
    tilesim_machine *m = tilesim_machine_new();
    char err[512];
    if (be) tilesim_machine_option(m, "--backend", "threads", err, sizeof err);
    int v = 7, sum = 0;
    mp_proc pr[2] = {{producer, &v}, {consumer, &sum}};
    tilesim_stats st;
    CHECK(tilesim_run_procs(m, 2, pr, &st, err, sizeof err) == 0 && sum == 35 && st.messages == 5 && st.bytes == 20,
          "%s: two mains: sum %d, %lld messages (%s)", be ? "threads" : "sim", sum, st.messages, err);
    CHECK(strcmp(st.backend, be ? "threads" : "sim") == 0 && st.measured == (be ? 1 : 2), "%s: measured %d", st.backend,
          st.measured);
    /* A trace on threads, a topology on threads: refused. */
    if (be) {
      CHECK(tilesim_machine_option(m, "--trace", "x.csv", err, sizeof err) == 1 &&
                tilesim_run_procs(m, 2, pr, &st, err, sizeof err) == -1 && strstr(err, "--trace traces the simulated"),
            "a trace on threads: %s", err);
    }
    tilesim_machine_free(m);
  }
}

/* The options: the same parser, values and messages as the programs' (par_machine_option). */
static void test_options(void) {
  static const char *const cases[][2] = {
      {"--procs", "0"},      {"--procs", "4097"},     {"--net", "wormhole"},  {"--m", "-1"},
      {"--c", "1e-400"},     {"--topology", "mesh:0x3"}, {"--place", "spiral"}, {"--switching", "x"},
      {"--backend", "mpi"},  {"--machine", "cray"},   {"--slowdown", "-1"},  {"--trace-limit", "1Q"},
      {"--spin", "11"},      {"--hop-latency", "abc"}, {"--trace", "--x"},   {"--ranks", "0"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    tilesim_machine *m = tilesim_machine_new();
    par_machine rc;
    par_machine_init(&rc);
    char e1[512] = "", e2[512] = "";
    int k1 = tilesim_machine_option(m, cases[i][0], cases[i][1], e1, sizeof e1);
    int k2 = par_machine_option(&rc, cases[i][0], cases[i][1], e2, sizeof e2);
    int ranks = strcmp(cases[i][0], "--ranks") == 0;   /* the algorithm refuses --ranks, in its own words */
    CHECK(k1 == -1 && k2 == -1 && (ranks || strcmp(e1, e2) == 0) && strstr(e1, cases[i][0]) == e1,
          "%s %s: %d '%s', par_machine_option %d '%s'", cases[i][0], cases[i][1], k1, e1, k2, e2);
    tilesim_machine_free(m);
  }
  tilesim_machine *m = tilesim_machine_new();
  char err[64];
  CHECK(tilesim_machine_option(m, "--alloc", "half", err, sizeof err) == 0, "--alloc is the algorithm's, not the machine's");
  CHECK(tilesim_machine_flag("--print-place") && !tilesim_machine_flag("--procs"), "flags");
  CHECK(strstr(tilesim_machine_help(), "--topology") && !strstr(tilesim_machine_help(), "--alloc"), "the help");
  CHECK(strcmp(tilesim_version(), TILESIM_VERSION) == 0, "the version");
  tilesim_machine_free(m);
}

int main(void) {
  test_sweep();
  test_against_sim();
  test_procs();
  test_options();
  return check_done("test_testbed");
}
