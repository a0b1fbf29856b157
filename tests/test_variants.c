/* test_variants.c -- the variants of the parallel algorithm (--alloc fit,
 * --block k, --schedule dynamic): every one equal to the serial solver bit
 * for bit (cost, start, path, hence mesh) for every P from 1 to 32, every
 * allocation, d in {1, 20, 80} and k in {1, 2, 7, 64}, on random pairs
 * (m != n, ties, clockwise) and real stacks, on the simulator and on
 * threads, without deadlock or unread messages; the blocked wavefront's
 * messages per diagonal against its closed form; and the paper's algorithm
 * reproduced bit for bit, times included, when the variants' options name
 * the paper's choices. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/contour.h"
#include "input/gen.h"
#include "util/rng.h"
#include "tests/parmachine.h"
#include "algo/split.h"
#include "algo/tiling.h"
#include "util/xmem.h"

static const split_alloc allocs[3] = {ALLOC_HALF, ALLOC_SIZE, ALLOC_FIT};
static const int blocks[4] = {1, 2, 7, 64};
static const int ds[3] = {1, 20, 80};

typedef struct {
  int procs, d, block;
  split_alloc alloc;
  par_schedule sched;
} variant;

static int same_tiling(const tiling *a, const tiling *b) {
  return a->quanta == b->quanta && a->start == b->start && a->m == b->m && a->n == b->n &&
         a->transposed == b->transposed &&
         memcmp(a->col, b->col, sizeof *a->col * (size_t)(a->m + a->n + 1)) == 0;
}

static par_machine config(const variant *v, machine_backend backend) {
  par_machine rc;
  par_machine_init(&rc);
  rc.mc.backend = backend;
  rc.mc.procs = v->procs;
  rc.mc.sim.warn = NULL;
  rc.mc.threads.warn = NULL;
  rc.pc.opt.alloc = v->alloc;
  rc.pc.opt.min_diag = v->d;
  rc.pc.opt.block = v->block;
  rc.pc.opt.schedule = v->sched;
  return rc;
}

static const char *name(const variant *v) {
  static char buf[96];
  snprintf(buf, sizeof buf, "P=%d %s d=%d k=%d %s", v->procs, split_alloc_name(v->alloc), v->d,
           v->block, par_schedule_name(v->sched));
  return buf;
}

/* A random pair: stars, grids (ties), regular polygons (ties), clockwise,
 * m != n; every eighth one large enough for d = 80 and k = 64 to split. */
static void random_pair(rng *g, int i, vec2 *P, int *np, vec2 *Q, int *nq) {
  int shape = i % 4, maxn = i % 8 == 7 ? 260 : i % 8 == 3 ? 90 : 40;
  *np = rng_int(g, 3, maxn);
  *nq = rng_int(g, 3, maxn);
  if (shape == 0 || shape == 3) {
    gen_star(g, P, *np, 0, 0, 10, 0.4);
    double cx = rng_uniform(g) * 3;
    double cy = rng_uniform(g) * 3;
    double r = 6 + 6 * rng_uniform(g);
    gen_star(g, Q, *nq, cx, cy, r, 0.4);
    if (shape == 3) geom_reverse(P, *np), geom_reverse(Q, *nq);
  } else if (shape == 1) {
    int sp = 4 + rng_int(g, 0, 4);
    *np = gen_grid(g, P, *np + 4, sp);
    sp = 4 + rng_int(g, 0, 4);
    *nq = gen_grid(g, Q, *nq + 4, sp);
    if (*np < 3 || geom_collinear(P, *np)) *np = 3, P[0] = (vec2){0, 0}, P[1] = (vec2){3, 0}, P[2] = (vec2){0, 3};
    if (*nq < 3 || geom_collinear(Q, *nq)) *nq = 3, Q[0] = (vec2){1, 1}, Q[1] = (vec2){4, 1}, Q[2] = (vec2){1, 4};
  } else {
    *nq = rng_int(g, 0, 1) ? *np + 1 : 2 * *np;
    gen_regular(P, *np, 0, 0, 5, 0);
    gen_regular(Q, *nq, 0, 0, 5, rng_int(g, 0, 1) ? 0 : 0.3);
  }
}

/* Run one pair under v on a backend and compare with the serial solver. */
static int one(const variant *v, machine_backend backend, const vec2 *P, int np, const vec2 *Q, int nq,
               cost_kind kind, const tiling *ser, const char *what) {
  par_machine rc = config(v, backend);
  rc.pc.kind = kind;
  par_pair pr;
  memset(&pr, 0, sizeof pr);
  pr.P = P, pr.np = np, pr.zp = 0, pr.Q = Q, pr.nq = nq, pr.zq = 1.5;
  char err[300];
  int ok = 1;
  if (backend == MACHINE_SIM) {
    sim_stats st;
    ok = par_machine_sim(&rc, &pr, 1, &st, err, sizeof err) == 0;
    if (ok && (st.deadlock || st.unread || st.messages != st.received)) {
      snprintf(err, sizeof err, "messages lost or deadlock");
      ok = 0;
      tiling_free(&pr.t);
    }
  } else {
    mpt_stats st;
    ok = par_machine_threads(&rc, &pr, 1, &st, err, sizeof err) == 0;
    if (ok && (st.deadlock || st.unread || st.messages != st.received)) {
      snprintf(err, sizeof err, "messages lost or deadlock");
      ok = 0;
      tiling_free(&pr.t);
    }
  }
  if (!ok) {
    CHECK(0, "%s (m=%d n=%d) %s on %s: %s", what, np, nq, name(v), machine_backend_name(backend), err);
    return 0;
  }
  int same = same_tiling(&pr.t, ser);
  /* The blocked wavefront recomputes ghost nodes: never fewer than serial. */
  int nodes = v->block > 1 ? pr.counts.nodes >= ser->count.nodes : pr.counts.nodes == ser->count.nodes;
  if (!same || !nodes)
    CHECK(0, "%s (m=%d n=%d) %s on %s: %.17g start %d, %llu nodes; serial %.17g start %d, %llu nodes",
          what, np, nq, name(v), machine_backend_name(backend), pr.t.quanta, pr.t.start,
          (unsigned long long)pr.counts.nodes, ser->quanta, ser->start,
          (unsigned long long)ser->count.nodes);
  tiling_free(&pr.t);
  return same && nodes;
}

/* Every (variant, P) once on the simulator: 3 allocations x 2 schedules x
 * 4 blocks x 32 processor counts = 768 runs, d cycling through 1, 20, 80
 * (every (variant, d) and every (P, d) several times), a new random pair
 * every 4 runs. */
static void sim_random(rng *g) {
  vec2 *P = xmallocarray(600, sizeof *P), *Q = xmallocarray(600, sizeof *Q);
  int np = 0, nq = 0, bad = 0, runs = 0, seen[3][2][4][3] = {{{{0}}}}, seenp[33][3] = {{0}};
  cost_kind kind = COST_AREA;
  tiling ser = {0};
  for (int i = 0; i < 768; i++) {
    if (i % 4 == 0) {
      if (i) tiling_free(&ser);
      random_pair(g, i / 4, P, &np, Q, &nq);
      kind = (i / 4) % 5 == 4 ? COST_SPAN : COST_AREA;
      tiling_solve(P, np, 0, Q, nq, 1.5, kind, -1, &ser);
    }
    int vi = i % 24, a = vi % 3, sc = (vi / 3) % 2, b = vi / 6;
    int procs = 1 + (i / 24 + 7 * vi) % 32, di = (i / 24 + vi) % 3;
    variant v = {procs, ds[di], blocks[b], allocs[a], sc ? PAR_DYNAMIC : PAR_STATIC};
    seen[a][sc][b][di]++;
    seenp[procs][di]++;
    runs++;
    bad += !one(&v, MACHINE_SIM, P, np, Q, nq, kind, &ser, "random pair");
  }
  tiling_free(&ser);
  int all = 1;
  for (int a = 0; a < 3; a++)
    for (int sc = 0; sc < 2; sc++)
      for (int b = 0; b < 4; b++)
        for (int di = 0; di < 3; di++) all &= seen[a][sc][b][di] >= 1;
  for (int p = 1; p <= 32; p++)
    for (int di = 0; di < 3; di++) all &= seenp[p][di] >= 1;
  CHECK(all, "every (allocation, schedule, k, d) and every (P, d) covered");
  CHECK(bad == 0, "simulator: %d of %d variant runs differ from the serial solver", bad, runs);
  free(P);
  free(Q);
}

/* On threads: every variant at four processor counts, P running over 1..32
 * and d over 1, 20, 80; a new random pair every 2 runs. */
static void threads_random(rng *g) {
  vec2 *P = xmallocarray(600, sizeof *P), *Q = xmallocarray(600, sizeof *Q);
  int np = 0, nq = 0, bad = 0, runs = 0, seenp[33] = {0};
  tiling ser = {0};
  for (int i = 0; i < 96; i++) {
    if (i % 2 == 0) {
      if (i) tiling_free(&ser);
      random_pair(g, i / 2, P, &np, Q, &nq);
      tiling_solve(P, np, 0, Q, nq, 1.5, COST_AREA, -1, &ser);
    }
    int vi = i % 24, a = vi % 3, sc = (vi / 3) % 2, b = vi / 6;
    int procs = 1 + (i * 11) % 32;
    variant v = {procs, ds[(i / 3) % 3], blocks[b], allocs[a], sc ? PAR_DYNAMIC : PAR_STATIC};
    seenp[procs]++;
    runs++;
    bad += !one(&v, MACHINE_THREADS, P, np, Q, nq, COST_AREA, &ser, "random pair");
  }
  tiling_free(&ser);
  int all = 1;
  for (int p = 1; p <= 32; p++) all &= seenp[p] >= 1;
  CHECK(all, "threads: every P from 1 to 32");
  CHECK(bad == 0, "threads: %d of %d variant runs differ from the serial solver", bad, runs);
  free(P);
  free(Q);
}

/* Real stacks: every pair of a stack in one run, each equal to serial. */
static void real(void) {
  static const struct {
    const char *name;
    int pairs;
    machine_backend backend;
    variant v;
  } cases[] = {
      {"prostate_1", 99, MACHINE_SIM, {9, 20, 7, ALLOC_FIT, PAR_DYNAMIC}},
      {"prostate_2", 99, MACHINE_SIM, {32, 1, 64, ALLOC_HALF, PAR_DYNAMIC}},
      {"prostate_3", 99, MACHINE_SIM, {16, 80, 2, ALLOC_SIZE, PAR_STATIC}},
      {"tinypatient_1", 99, MACHINE_SIM, {5, 1, 7, ALLOC_FIT, PAR_STATIC}},
      {"prostate_0", 3, MACHINE_SIM, {24, 1, 2, ALLOC_FIT, PAR_DYNAMIC}},
      {"prostate_0", 2, MACHINE_SIM, {7, 20, 64, ALLOC_SIZE, PAR_STATIC}},
      {"prostate_2", 99, MACHINE_THREADS, {16, 1, 7, ALLOC_SIZE, PAR_DYNAMIC}},
      {"prostate_4", 99, MACHINE_THREADS, {6, 20, 2, ALLOC_FIT, PAR_STATIC}},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char path[128], err[300];
    snprintf(path, sizeof path, "tests/data/slicerrt/%s.contours", cases[i].name);
    contour_stack s;
    if (contour_read(path, &s, NULL, "test", err, sizeof err) != 0) {
      CHECK(0, "%s", err);
      continue;
    }
    int np = s.n - 1 < cases[i].pairs ? s.n - 1 : cases[i].pairs;
    par_pair *pr = xcalloc((size_t)np, sizeof *pr);
    for (int k = 0; k < np; k++) {
      pr[k].P = s.c[k].pt, pr[k].np = s.c[k].n, pr[k].zp = s.c[k].z;
      pr[k].Q = s.c[k + 1].pt, pr[k].nq = s.c[k + 1].n, pr[k].zq = s.c[k + 1].z;
    }
    const variant *v = &cases[i].v;
    par_machine rc = config(v, cases[i].backend);
    int rcode = par_machine_run(&rc, pr, np, err, sizeof err);
    CHECK(rcode == 0, "%s %s on %s: %s", cases[i].name, name(v), machine_backend_name(cases[i].backend), err);
    int bad = 0;
    for (int k = 0; rcode == 0 && k < np; k++) {
      tiling ser;
      tiling_solve(pr[k].P, pr[k].np, pr[k].zp, pr[k].Q, pr[k].nq, pr[k].zq, COST_AREA, -1, &ser);
      bad += !same_tiling(&pr[k].t, &ser) || pr[k].counts.nodes < ser.count.nodes;
      tiling_free(&ser);
      tiling_free(&pr[k].t);
    }
    CHECK(bad == 0, "%s %s on %s: %d of %d pairs differ from serial", cases[i].name, name(v),
          machine_backend_name(cases[i].backend), bad, np);
    free(pr);
    contour_stack_free(&s);
  }
}

/* The blocked wavefront's closed form (par_block.h): on mu(0), whose band is
 * the (m+1) x (n+1) rectangle, the diagonals go in blocks t = 1 + ik ..
 * (i+1)k; every block where all p slaves are active with runs at least
 * twice k + 1 wide (diagonal length >= 2p(k+1) on it and on the block
 * before) has exactly p - 1 BOUNDARY sends and p - 1 receives on its first
 * diagonal, one across each run boundary, and none on its other k - 1:
 * (p - 1)/k a diagonal against the paper's p - 1. */
static void messages(rng *g) {
  static const struct { int p, k, m, n; } cases[] = {
      {2, 2, 300, 340}, {3, 7, 300, 340}, {5, 7, 300, 340}, {8, 7, 300, 340},
      {16, 2, 300, 340}, {4, 16, 300, 340}, {2, 64, 400, 450}, {31, 2, 300, 340},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    int p = cases[i].p, k = cases[i].k, m = cases[i].m, n = cases[i].n, T = m + n;
    vec2 *P = xmallocarray((size_t)m, sizeof *P), *Q = xmallocarray((size_t)n, sizeof *Q);
    gen_star(g, P, m, 0, 0, 10, 0.3);
    gen_star(g, Q, n, 0, 0, 9, 0.3);
    int *sends = xcalloc((size_t)T + 1, sizeof *sends), *recvs = xcalloc((size_t)T + 1, sizeof *recvs);
    variant v = {p + 1, 1, k, ALLOC_HALF, PAR_STATIC};
    par_machine rc = config(&v, MACHINE_SIM);
    rc.pc.opt.only_mu0 = 1;
    rc.diag_sends = sends, rc.diag_recvs = recvs, rc.diag_len = T + 1;
    par_pair pr;
    memset(&pr, 0, sizeof pr);
    pr.P = P, pr.np = m, pr.zp = 0, pr.Q = Q, pr.nq = n, pr.zq = 1;
    char err[300];
    CHECK(par_machine_sim(&rc, &pr, 1, NULL, err, sizeof err) == 0, "p=%d k=%d: %s", p, k, err);
    int checked = 0, wrong = 0, inside = 0;
    long long total = 0;
    for (int t = 1; t <= T; t++) {
      total += sends[t];
      if ((t - 1) % k != 0 && t != T && (sends[t] || recvs[t])) inside++;
    }
    for (int t0 = 1 + k; t0 + k - 1 <= T; t0 += k) {
      int full = 1;
      for (int t = t0 - k; t <= t0 + k - 1; t++) {
        int len = t < m ? t : m;
        if (T - t < len) len = T - t;
        full &= len + 1 >= 2 * p * (k + 1);
      }
      if (!full) continue;
      checked++;
      if (sends[t0] != p - 1 || recvs[t0] != p - 1) wrong++;
    }
    CHECK(checked >= 3 && wrong == 0, "p=%d k=%d: %d of %d full blocks without p-1 sends and receives", p, k,
          wrong, checked);
    CHECK(inside == 0, "p=%d k=%d: messages on %d diagonals inside blocks", p, k, inside);
    CHECK(total > 0 && (uint64_t)total == pr.counts.msgs[PAR_BOUNDARY], "p=%d k=%d: %lld sends, %llu counted",
          p, k, total, (unsigned long long)pr.counts.msgs[PAR_BOUNDARY]);
    tiling_free(&pr.t);
    free(sends), free(recvs), free(P), free(Q);
  }
}

/* The options naming the paper's choices (--block 1 --alloc half --schedule
 * static, parsed as a user gives them) against the paper's configuration as
 * the tests before the variants built it (every new option zero): the same
 * times, messages and statistics, bit for bit, on the simulator. */
static void paper_times(rng *g) {
  static const char *const args[][2] = {
      {"--block", "1"}, {"--alloc", "half"}, {"--schedule", "static"}};
  int np = 150, nq = 173;
  vec2 *P = xmallocarray((size_t)np, sizeof *P), *Q = xmallocarray((size_t)nq, sizeof *Q);
  gen_star(g, P, np, 0, 0, 10, 0.3);
  gen_star(g, Q, nq, 1, 0, 9, 0.3);
  for (int procs = 1; procs <= 13; procs += 4)
    for (int di = 0; di < 2; di++) {
      par_machine a, b;
      memset(&a, 0, sizeof a);   /* the paper's, every variant field zero */
      a.mc.procs = procs;
      sim_config_init(&a.mc.sim);
      a.mc.sim.warn = NULL;
      a.pc.opt.alloc = ALLOC_HALF;
      a.pc.opt.min_diag = ds[di];
      a.pc.kind = COST_AREA;
      par_machine_init(&b);
      b.mc.backend = MACHINE_SIM;
      b.mc.sim.warn = NULL;
      char err[300], num[16];
      snprintf(num, sizeof num, "%d", procs);
      CHECK(par_machine_option(&b, "--procs", num, err, sizeof err) == 1, "--procs: %s", err);
      snprintf(num, sizeof num, "%d", ds[di]);
      CHECK(par_machine_option(&b, "--min-diag", num, err, sizeof err) == 1, "--min-diag: %s", err);
      for (int i = 0; i < 3; i++)
        CHECK(par_machine_option(&b, args[i][0], args[i][1], err, sizeof err) == 1, "%s: %s", args[i][0], err);
      par_pair x, y;
      memset(&x, 0, sizeof x);
      x.P = P, x.np = np, x.zp = 0, x.Q = Q, x.nq = nq, x.zq = 2;
      y = x;
      sim_stats sx, sy;
      CHECK(par_machine_sim(&a, &x, 1, &sx, err, sizeof err) == 0, "paper P=%d: %s", procs, err);
      CHECK(par_machine_sim(&b, &y, 1, &sy, err, sizeof err) == 0, "options P=%d: %s", procs, err);
      int same = x.time == y.time && x.mu0_time == y.mu0_time && same_tiling(&x.t, &y.t) &&
                 memcmp(&x.counts, &y.counts, sizeof x.counts) == 0 && sx.makespan == sy.makespan &&
                 sx.events == sy.events && sx.messages == sy.messages && sx.bytes == sy.bytes;
      CHECK(same, "P=%d d=%d: the paper %.17g s, %llu messages; --block 1 --alloc half --schedule static "
                  "%.17g s, %llu messages", procs, ds[di], x.time, (unsigned long long)sx.messages, y.time,
            (unsigned long long)sy.messages);
      tiling_free(&x.t);
      tiling_free(&y.t);
    }
  free(P);
  free(Q);
}

/* split_usable on mu(0)'s band, the (m+1) x (n+1) rectangle: its widest
 * diagonal has min(m, n) + 1 nodes, so it keeps max(1, (min(m, n) + 1)/d)
 * slaves busy. */
static void usable(void) {
  int bad = 0;
  for (int m = 1; m <= 40; m += 3)
    for (int n = m; n <= 60; n += 7)
      for (int d = 1; d <= 50; d += 7) {
        int want = (m + 1) / d > 1 ? (m + 1) / d : 1;
        bad += split_usable(m, n, 0, NULL, NULL, d) != want;
      }
  CHECK(bad == 0, "split_usable on the rectangle: %d wrong", bad);
}

int main(void) {
  rng g;
  rng_seed(&g, 2024);
  usable();
  paper_times(&g);
  messages(&g);
  sim_random(&g);
  threads_random(&g);
  real();
  return check_done("test_variants");
}
