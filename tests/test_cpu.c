/* test_cpu.c -- the simulator's processor-side model (sim/cpu.h) against
 * closed forms, and against the LogGP model it must reproduce.
 *
 * Costs are exact binary fractions, so every simulated time is exact and is
 * compared with ==.  The expected values are worked out here from cpu.h's
 * model, independently of sim.c:
 *   - a ping-pong: each one-way message costs os(len) + m + or(len) on the
 *     ideal network, os + (len-1)G + L + or on LogGP;
 *   - a sleeper: a receiver blocked longer than spin runs wake after the
 *     arrival, and the first sender to find it asleep pays o_wake;
 *   - busy neighbours: k ranks computing at once each take c u (1 + s(k-1));
 *     beside k-1 ranks spinning in recv c u (1 + s_spin(k-1)), beside
 *     ranks asleep in recv c u;
 *   - o_send = o_recv = x on LogGP with o = 0 gives the very times of LogGP
 *     with o = x (both sides busy x a message), on random programs;
 *   - all costs 0: the module is off, and random programs give the same
 *     times with any spin (spin alone is no cost). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "sim/cpu.h"
#include "tests/randprog.h"
#include "tests/simrun.h"
#include "sim/sim.h"
#include "mp/threads.h"

/* simrun's machine with no per-byte cost and no LogGP overhead or gap. */
static sim_config config(sim_net net, int procs) {
  sim_config cfg = simrun_config(net, procs);
  cfg.per_byte = 0;
  cfg.o = 0;
  cfg.g = 0;
  return cfg;
}

/* simrun, whose run must succeed. */
static sim *run(const sim_config *cfg, int n, mp_main fn, void *ud, int *rc) {
  char err[300];
  sim *s = simrun(cfg, n, fn, ud, rc, err, sizeof err);
  CHECK(*rc == 0, "sim_run: %s", err);
  return s;
}

/* ==== ping-pong ============================================================ */

typedef struct {
  int rounds;
  size_t len;
} pingpong;

static void pingpong_main(mp *self, void *ud) {
  pingpong *p = ud;
  char buf[64] = {0};
  for (int k = 0; k < p->rounds; k++) {
    if (mp_rank(self) == 0) {
      mp_send(self, 1, 0, buf, p->len);
      mp_recv(self, 1, 0, buf, sizeof buf, NULL);
    } else {
      mp_recv(self, 0, 0, buf, sizeof buf, NULL);
      mp_send(self, 0, 0, buf, p->len);
    }
  }
}

static void test_pingpong(void) {
  for (int net = 0; net < 2; net++) {
    for (size_t len = 1; len <= 33; len += 32) {
      sim_config cfg = config(net ? SIM_NET_LOGGP : SIM_NET_IDEAL, 2);
      cfg.cpu.o_send = 0.125, cfg.cpu.o_send_byte = 0x1p-8;
      cfg.cpu.o_recv = 0.0625, cfg.cpu.o_recv_byte = 0x1p-9;
      double os = 0.125 + (double)len * 0x1p-8, orc = 0.0625 + (double)len * 0x1p-9;
      double wire = net ? (double)(len - 1) * cfg.G + cfg.L : cfg.m;
      double way = os + wire + orc;
      pingpong p = {5, len};
      int rc;
      sim *s = run(&cfg, 2, pingpong_main, &p, &rc);
      double want0 = 2 * p.rounds * way;
      double want1 = want0 - wire - orc;   /* rank 1 ends with its last send */
      CHECK(sim_rank(s, 0)->finish == want0, "%s len %zu: rank 0 at %.17g, want %.17g", sim_net_name(cfg.net),
            len, sim_rank(s, 0)->finish, want0);
      CHECK(sim_rank(s, 1)->finish == want1, "%s len %zu: rank 1 at %.17g, want %.17g", sim_net_name(cfg.net),
            len, sim_rank(s, 1)->finish, want1);
      CHECK(sim_rank(s, 0)->overhead == p.rounds * (os + orc), "overhead %.17g, want %.17g",
            sim_rank(s, 0)->overhead, p.rounds * (os + orc));
      sim_free(s);
    }
  }
}

/* ==== a sleeper ============================================================ */

typedef struct {
  double work;        /* rank 0 computes this much first */
  int early;          /* rank 0 sends before rank 1 blocks (rank 1 computes first) */
  int second;         /* rank 2 also sends to rank 1, after rank 0 */
  double got;         /* when rank 1's recv returned */
} sleeper;

static void sleeper_main(mp *self, void *ud) {
  sleeper *z = ud;
  char buf[8] = {0};
  int me = mp_rank(self);
  if (me == 0) {
    mp_compute(self, z->work);
    mp_send(self, 1, 0, buf, 8);
  } else if (me == 1) {
    if (z->early) mp_compute(self, 2 * z->work + 64);
    mp_recv(self, MP_ANY, 0, buf, sizeof buf, NULL);
    z->got = mp_time(self);
    if (z->second) mp_recv(self, MP_ANY, 0, buf, sizeof buf, NULL);
  } else if (z->second) {
    mp_compute(self, z->work + 1);
    mp_send(self, 1, 0, buf, 8);
  }
}

static void test_sleeper(void) {
  const double os = 0.125, orc = 0.0625, wake = 2, owake = 0.25;
  for (int spin_long = 0; spin_long <= 1; spin_long++) {
    for (int early = 0; early <= 1; early++) {
      sim_config cfg = config(SIM_NET_IDEAL, 3);
      cfg.c = 1;
      cfg.cpu.o_send = os, cfg.cpu.o_recv = orc, cfg.cpu.wake = wake, cfg.cpu.o_wake = owake;
      cfg.cpu.spin = spin_long ? 100 : 0.5;
      sleeper z = {4, early, 1, 0};
      int rc;
      sim *s = run(&cfg, 3, sleeper_main, &z, &rc);
      double arrival = 4 + os + cfg.m;
      /* Asleep: blocked at 0, the message arrives at 4.375 > spin = 0.5.
       * Early: rank 1 blocks only at 72, the message long there. */
      int asleep = !spin_long && !early;
      double want_got = early ? 2 * 4 + 64 + orc : arrival + (asleep ? wake : 0) + orc;
      double want0 = 4 + os + (asleep ? owake : 0);
      /* Rank 2's message (sent at 5 + os) finds rank 1 already woken: no o_wake. */
      double want2 = 5 + os;
      CHECK(z.got == want_got, "spin %g early %d: recv returned at %.17g, want %.17g", cfg.cpu.spin, early, z.got,
            want_got);
      CHECK(sim_rank(s, 0)->finish == want0, "spin %g early %d: the waker finished at %.17g, want %.17g",
            cfg.cpu.spin, early, sim_rank(s, 0)->finish, want0);
      CHECK(sim_rank(s, 2)->finish == want2, "spin %g early %d: the second sender finished at %.17g, want %.17g",
            cfg.cpu.spin, early, sim_rank(s, 2)->finish, want2);
      const sim_rank_stats *r1 = sim_rank(s, 1);
      CHECK(r1->finish == r1->compute + r1->cpu_wait + r1->overhead + r1->recv_wait,
            "the statistics identity: %.17g != %.17g", r1->finish,
            r1->compute + r1->cpu_wait + r1->overhead + r1->recv_wait);
      sim_free(s);
    }
  }
}

/* ==== busy neighbours ====================================================== */

typedef struct {
  double units;
  int waiters;        /* ranks 1.. wait for rank 0 instead of computing */
} crowd;

static void crowd_main(mp *self, void *ud) {
  crowd *k = ud;
  char b = 0;
  if (!k->waiters) {
    mp_compute(self, k->units);
  } else if (mp_rank(self) == 0) {
    mp_compute(self, 1);          /* the others have not acted yet: working */
    mp_compute(self, k->units);   /* they have blocked in recv: spinning */
    mp_compute(self, k->units);   /* by now they sleep */
    for (int r = 1; r < mp_size(self); r++) mp_send(self, r, 0, &b, 1);
  } else {
    mp_recv(self, 0, 0, &b, 1, NULL);
  }
}

static void test_crowd(void) {
  const double s = 0.0625, sp = 0.03125;
  for (int k = 1; k <= 9; k += 4) {
    sim_config cfg = config(SIM_NET_IDEAL, k);
    cfg.cpu.slowdown = s;
    cfg.cpu.slowdown_spin = sp;
    cfg.cpu.spin = 1;
    crowd c = {8, 0};
    int rc;
    sim *sm = run(&cfg, k, crowd_main, &c, &rc);
    double want = 8 * cfg.c * (1 + s * (k - 1));
    for (int r = 0; r < k; r++)
      CHECK(sim_rank(sm, r)->finish == want, "%d at once: rank %d finished at %.17g, want %.17g", k, r,
            sim_rank(sm, r)->finish, want);
    sim_free(sm);
    /* One computes, k - 1 wait in recv: at time 0 they have not acted yet
     * (working, for a first short compute), then they spin (slowdown_spin
     * each) for the second, then (spin 1 < its end) they sleep. */
    c.waiters = 1;
    sm = run(&cfg, k, crowd_main, &c, &rc);
    double first = cfg.c * (1 + s * (k - 1)), second = 8 * cfg.c * (1 + sp * (k - 1));
    want = first + second + 8 * cfg.c;
    CHECK(first < cfg.cpu.spin && first + second > cfg.cpu.spin, "the test's premise: spinning, then asleep");
    CHECK(sim_rank(sm, 0)->compute == want, "%d ranks: the computing rank's compute %.17g, want %.17g", k,
          sim_rank(sm, 0)->compute, want);
    sim_free(sm);
  }
}

/* ==== against LogGP, and the module off ==================================== */

/* Run a random program; its makespan and every rank's finish and overhead. */
static void random_run(const sim_config *cfg, uint64_t seed, int n, double *out) {
  static randprog p;
  randprog_make(&p, seed, n);
  char err[300];
  sim *s = sim_new(cfg, n, err, sizeof err);
  CHECK(s != NULL, "sim_new: %s", err);
  if (!s) abort();
  mp_proc pr[RANDPROG_RANKS];
  for (int i = 0; i < n; i++) pr[i] = (mp_proc){randprog_main, &p};
  int rc = sim_run(s, pr, err, sizeof err);
  const char *why = "";
  CHECK(rc == 0 && randprog_failures(&p, &why) == 0, "random program %llu: %s %s", (unsigned long long)seed, err,
        why);
  out[0] = sim_stats_get(s)->makespan;
  for (int r = 0; r < n; r++) out[1 + 2 * r] = sim_rank(s, r)->finish, out[2 + 2 * r] = sim_rank(s, r)->overhead;
  sim_free(s);
}

static void test_equivalences(void) {
  enum { N = 6 };
  double a[1 + 2 * N], b[1 + 2 * N];
  int differ_loggp = 0, differ_off = 0;
  for (uint64_t seed = 1; seed <= 40; seed++) {
    int procs = 1 + (int)(seed % N);
    /* o_send = o_recv = 0.125 on LogGP with o = 0, against LogGP's o = 0.125. */
    sim_config x = config(SIM_NET_LOGGP, procs), y = x;
    x.o = 0.125;
    y.cpu.o_send = y.cpu.o_recv = 0.125;
    random_run(&x, seed, N, a);
    random_run(&y, seed, N, b);
    differ_loggp += memcmp(a, b, sizeof a) != 0;
    /* Every cost 0 and a different spin: nothing changes, on any network. */
    for (int net = 0; net < 3; net++) {
      sim_config u = config((sim_net)net, procs), v = u;
      v.cpu.spin = 1e-9;
      CHECK(!cpu_model_on(&u.cpu) && !cpu_model_on(&v.cpu), "no cost set: the module is off");
      random_run(&u, seed, N, a);
      random_run(&v, seed, N, b);
      differ_off += memcmp(a, b, sizeof a) != 0;
    }
  }
  CHECK(differ_loggp == 0, "%d random programs differ between cpu o_send/o_recv and LogGP's o", differ_loggp);
  CHECK(differ_off == 0, "%d random programs differ with spin alone", differ_off);
}

/* ==== the options =========================================================== */

static void test_config(void) {
  sim_config cfg;
  sim_config_init(&cfg);
  mpt_config tc;
  mpt_config_init(&tc);
  CHECK(!cpu_model_on(&cfg.cpu) && cfg.cpu.spin == (double)tc.spin_ns * 1e-9,
        "the default profile: no processor costs, the threads backend's spin (%g s, %ld ns)", cfg.cpu.spin,
        tc.spin_ns);
  cpu_model m;
  cpu_model_init(&m);
  const char *opts[] = {"--o-send", "--o-send-byte", "--o-recv", "--o-recv-byte", "--spin", "--wake", "--o-wake",
                        "--slowdown", "--slowdown-spin"};
  for (size_t i = 0; i < sizeof opts / sizeof *opts; i++) {
    double *f = cpu_model_field(&m, opts[i]);
    CHECK(f != NULL, "%s has a field", opts[i]);
    if (f) *f = 0.5;
  }
  CHECK(cpu_model_field(&m, "--o") == NULL && cpu_model_field(&m, "--frob") == NULL, "unknown options: no field");
  CHECK(m.o_send == 0.5 && m.o_recv_byte == 0.5 && m.spin == 0.5 && m.slowdown == 0.5, "the fields set");
  char err[200];
  CHECK(cpu_model_check(&m, err, sizeof err) == 0, "valid model refused: %s", err);
  m.wake = -1;
  CHECK(cpu_model_check(&m, err, sizeof err) == -1 && strstr(err, "wake"), "a negative wake: %s", err);
  m.wake = INFINITY;
  CHECK(cpu_model_check(&m, err, sizeof err) == -1, "an infinite wake accepted");
  sim_config bad;
  sim_config_init(&bad);
  bad.cpu.o_recv = NAN;
  bad.warn = NULL;
  CHECK(sim_new(&bad, 2, err, sizeof err) == NULL && strstr(err, "o_recv"), "sim_new with o_recv NaN: %s", err);
}

int main(void) {
  test_pingpong();
  test_sleeper();
  test_crowd();
  test_equivalences();
  test_config();
  return check_done("test_cpu");
}
