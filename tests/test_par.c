/* test_par.c -- the parallel algorithm on the simulated machine: the same
 * cost and the same path as the serial solver, bit for bit, for every P from
 * 1 to 32, both allocations and d in {1, 20, 80}, on hundreds of random pairs
 * and on the real stacks; boundary messages per diagonal against section
 * 7.2's 2(p-1); no deadlock; the statistics add up. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/contour.h"
#include "input/gen.h"
#include "algo/par_slave.h"
#include "util/rng.h"
#include "tests/parmachine.h"
#include "algo/tiling.h"
#include "util/xmem.h"

static int same_tiling(const tiling *a, const tiling *b) {
  return a->quanta == b->quanta && a->start == b->start && a->m == b->m && a->n == b->n &&
         a->transposed == b->transposed &&
         memcmp(a->col, b->col, sizeof *a->col * (size_t)(a->m + a->n + 1)) == 0;
}

static par_pair mkpair(const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq) {
  par_pair pr;
  memset(&pr, 0, sizeof pr);
  pr.P = P, pr.np = np, pr.zp = zp, pr.Q = Q, pr.nq = nq, pr.zq = zq;
  return pr;
}

static par_machine config(int P, split_alloc alloc, int d, cost_kind kind) {
  par_machine rc;
  memset(&rc, 0, sizeof rc);
  rc.mc.procs = P;
  sim_config_init(&rc.mc.sim);
  rc.mc.sim.warn = NULL;
  rc.pc.opt.alloc = alloc;
  rc.pc.opt.min_diag = d;
  rc.pc.kind = kind;
  return rc;
}

/* A random pair, as in test_tiling: stars, grids (ties), regular polygons
 * (ties), clockwise input, m != n. */
static void random_pair(rng *g, int shape, vec2 *P, int *np, vec2 *Q, int *nq, int maxn) {
  *np = rng_int(g, 3, maxn);
  *nq = rng_int(g, 3, maxn);
  if (shape == 0 || shape == 3) {
    gen_star(g, P, *np, 0, 0, 10, 0.4);
    gen_star(g, Q, *nq, rng_uniform(g) * 3, rng_uniform(g) * 3, 6 + 6 * rng_uniform(g), 0.4);
    if (shape == 3) geom_reverse(P, *np), geom_reverse(Q, *nq);
  } else if (shape == 1) {
    *np = gen_grid(g, P, *np + 4, 4 + rng_int(g, 0, 4));
    *nq = gen_grid(g, Q, *nq + 4, 4 + rng_int(g, 0, 4));
    if (*np < 3 || geom_collinear(P, *np)) *np = 3, P[0] = (vec2){0, 0}, P[1] = (vec2){3, 0}, P[2] = (vec2){0, 3};
    if (*nq < 3 || geom_collinear(Q, *nq)) *nq = 3, Q[0] = (vec2){1, 1}, Q[1] = (vec2){4, 1}, Q[2] = (vec2){1, 4};
  } else {
    *nq = rng_int(g, 0, 1) ? *np : 2 * *np;
    gen_regular(P, *np, 0, 0, 5, 0);
    gen_regular(Q, *nq, 0, 0, 5, rng_int(g, 0, 1) ? 0 : 0.3);
  }
}

/* Every (P, alloc, d) at least six times, over 200 random pairs. */
static void check_random(rng *g) {
  static const int ds[3] = {1, 20, 80};
  vec2 *P = xmallocarray(200, sizeof *P), *Q = xmallocarray(200, sizeof *Q);
  int bad = 0, runs = 0, failed = 0, nodes_bad = 0;
  for (int pair = 0; pair < 200; pair++) {
    int np, nq;
    random_pair(g, pair % 4, P, &np, Q, &nq, pair % 10 == 9 ? 90 : 40);
    cost_kind kind = pair % 5 == 4 ? COST_SPAN : COST_AREA;
    tiling ser;
    tiling_solve(P, np, 0, Q, nq, 1.5, kind, -1, &ser);
    for (int i = 0; i < 6; i++) {
      int c = (pair * 6 + i) % 192;
      int procs = 1 + c % 32, alloc = (c / 32) % 2, d = ds[c / 64];
      par_machine rc = config(procs, (split_alloc)alloc, d, kind);
      par_pair pr = mkpair(P, np, 0, Q, nq, 1.5);
      char err[300];
      runs++;
      if (par_machine_sim(&rc, &pr, 1, NULL, err, sizeof err) != 0) {
        failed++;
        CHECK(0, "pair %d P=%d %s d=%d: %s", pair, procs, split_alloc_name((split_alloc)alloc), d, err);
        continue;
      }
      if (!same_tiling(&pr.t, &ser)) {
        bad++;
        CHECK(0, "pair %d (m=%d n=%d) P=%d %s d=%d: parallel %.17g start %d, serial %.17g start %d",
              pair, np, nq, procs, split_alloc_name((split_alloc)alloc), d, pr.t.quanta, pr.t.start,
              ser.quanta, ser.start);
      }
      if (pr.counts.nodes != ser.count.nodes) nodes_bad++;
      tiling_free(&pr.t);
    }
    tiling_free(&ser);
  }
  CHECK(bad == 0 && failed == 0, "%d of %d parallel runs differ from the serial solver, %d failed", bad, runs, failed);
  CHECK(nodes_bad == 0, "%d runs evaluated a different number of nodes than the serial solver", nodes_bad);
  free(P);
  free(Q);
}

/* The real stacks: every pair of a stack in one simulation, each equal to serial. */
static void check_real(void) {
  static const struct { const char *name; int procs; split_alloc alloc; int d; int pairs; } cases[] = {
      {"prostate_1", 1, ALLOC_HALF, 1, 99},  {"prostate_1", 7, ALLOC_SIZE, 20, 99},
      {"prostate_2", 2, ALLOC_SIZE, 80, 99}, {"prostate_3", 16, ALLOC_HALF, 1, 99},
      {"prostate_4", 32, ALLOC_SIZE, 1, 99}, {"prostate_5", 12, ALLOC_HALF, 20, 99},
      {"tinypatient_1", 3, ALLOC_HALF, 1, 99}, {"prostate_0", 16, ALLOC_SIZE, 80, 3},
      {"prostate_0", 9, ALLOC_HALF, 1, 2},
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
    for (int k = 0; k < np; k++)
      pr[k] = mkpair(s.c[k].pt, s.c[k].n, s.c[k].z, s.c[k + 1].pt, s.c[k + 1].n, s.c[k + 1].z);
    par_machine rc = config(cases[i].procs, cases[i].alloc, cases[i].d, COST_AREA);
    int rcode = par_machine_sim(&rc, pr, np, NULL, err, sizeof err);
    CHECK(rcode == 0, "%s P=%d: %s", cases[i].name, cases[i].procs, err);
    int bad = 0;
    for (int k = 0; rcode == 0 && k < np; k++) {
      tiling ser;
      tiling_solve(pr[k].P, pr[k].np, pr[k].zp, pr[k].Q, pr[k].nq, pr[k].zq, COST_AREA, -1, &ser);
      bad += !same_tiling(&pr[k].t, &ser) || pr[k].counts.nodes != ser.count.nodes;
      CHECK(pr[k].time > 0, "%s pair %d: no time", cases[i].name, k);
      tiling_free(&ser);
    }
    CHECK(bad == 0, "%s P=%d %s d=%d: %d of %d pairs differ from serial", cases[i].name, cases[i].procs,
          split_alloc_name(cases[i].alloc), cases[i].d, bad, np);
    for (int k = 0; k < np; k++) tiling_free(&pr[k].t);
    free(pr);
    contour_stack_free(&s);
  }
}

/* Section 7.2: a diagonal computed by p slaves needs 2(p-1) messages, one
 * sent and one received at each of the p-1 run boundaries.  Here: every
 * diagonal of mu(0) where all p slaves worked on it and on the one before,
 * with runs long enough that only neighbours trade, has exactly p-1 BOUNDARY
 * sends and p-1 receives. */
static void check_messages(rng *g) {
  int m = 150, n = 170, T = m + n;
  vec2 *P = xmallocarray((size_t)m, sizeof *P), *Q = xmallocarray((size_t)n, sizeof *Q);
  gen_star(g, P, m, 0, 0, 10, 0.3);
  gen_star(g, Q, n, 0, 0, 9, 0.3);
  static const int ps[] = {2, 3, 5, 8, 16, 31};
  for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++) {
    int p = ps[i];
    int *sends = xcalloc((size_t)T + 1, sizeof *sends), *recvs = xcalloc((size_t)T + 1, sizeof *recvs);
    par_machine rc = config(p + 1, ALLOC_HALF, 1, COST_AREA);
    rc.diag_sends = sends, rc.diag_recvs = recvs, rc.diag_len = T + 1;
    par_pair pr = mkpair(P, m, 0, Q, n, 1);
    char err[300];
    sim_stats st;
    CHECK(par_machine_sim(&rc, &pr, 1, &st, err, sizeof err) == 0, "p=%d: %s", p, err);
    /* mu(0)'s band is the (m+1) x (n+1) rectangle: diagonal t has
     * min(t, m, n, T - t) + 1 nodes. */
    int checked = 0, wrong = 0;
    for (int t = 2; t <= T; t++) {
      int len = t, lp = t - 1;
      if (len > m) len = m;
      if (len > T - t) len = T - t;
      if (lp > m) lp = m;
      if (lp > T - t + 1) lp = T - t + 1;
      len++, lp++;
      if (len < 3 * p || lp < 3 * p) continue;   /* all p active, runs of 3 or more */
      checked++;
      if (sends[t] != p - 1 || recvs[t] != p - 1) wrong++;
    }
    CHECK(checked > 50 && wrong == 0, "p=%d: %d of %d full diagonals do not have p-1 sends and p-1 receives",
          p, wrong, checked);
    long long total = 0;
    for (int t = 0; t <= T; t++) total += sends[t];
    CHECK(total > 0 && (uint64_t)total <= pr.counts.msgs[PAR_BOUNDARY], "p=%d: boundary counts", p);
    tiling_free(&pr.t);
    free(sends);
    free(recvs);
  }
  free(P);
  free(Q);
}

/* The statistics add up: each slave's simulated compute time is c times the
 * nodes it evaluated; the master's is c times its own units; the messages of
 * each kind match the simulator's per-tag counts; sends = receives. */
static void check_stats(rng *g) {
  int np = 80, nq = 95;
  vec2 *P = xmallocarray((size_t)np, sizeof *P), *Q = xmallocarray((size_t)nq, sizeof *Q);
  gen_star(g, P, np, 0, 0, 10, 0.3);
  gen_star(g, Q, nq, 0, 1, 9, 0.3);
  for (int procs = 1; procs <= 12; procs += 11) {
    int nr = par_ranks(procs);
    sim_config cfg;
    sim_config_init(&cfg);
    cfg.c = 0x1p-10, cfg.m = 0x1p-9, cfg.warn = NULL;   /* binary fractions: exact sums */
    cfg.procs = procs;
    int place[16];
    for (int r = 0; r < nr; r++) place[r] = procs == 1 ? 0 : r;
    cfg.place = place;
    char err[300];
    sim *s = sim_new(&cfg, nr, err, sizeof err);
    par_pair pr = mkpair(P, np, 0, Q, nq, 2);
    par_master_arg marg;
    memset(&marg, 0, sizeof marg);
    marg.npairs = 1, marg.pairs = &pr, marg.kind = COST_AREA;
    marg.opt = (par_options){ALLOC_SIZE, 1, 0, 1, PAR_STATIC, 1, 0, 0};
    par_slave_arg sarg[16];
    memset(sarg, 0, sizeof sarg);
    mp_proc procv[16];
    procv[0] = (mp_proc){par_master, &marg};
    for (int r = 1; r < nr; r++) procv[r] = (mp_proc){par_slave, &sarg[r]};
    CHECK(sim_run(s, procv, err, sizeof err) == 0 && !marg.failed, "P=%d: %s %s", procs, err, marg.err);
    const sim_stats *st = sim_stats_get(s);
    CHECK(st->deadlock == 0 && st->unread == 0 && st->messages == st->received, "P=%d: messages lost", procs);
    uint64_t nodes = 0;
    long long tags[SIM_TAGS] = {0};
    for (int r = 1; r < nr; r++) {
      const sim_rank_stats *rs = sim_rank(s, r);
      CHECK(rs->compute == cfg.c * (double)sarg[r].total.nodes && sarg[r].total.units == sarg[r].total.nodes,
            "P=%d slave %d: compute %.17g s, c x nodes %.17g s", procs, r, rs->compute,
            cfg.c * (double)sarg[r].total.nodes);
      nodes += sarg[r].total.nodes;
    }
    for (int r = 0; r < nr; r++)
      for (int k = 0; k < SIM_TAGS; k++) tags[k] += sim_rank(s, r)->sent_tag[k];
    CHECK(sim_rank(s, 0)->compute == cfg.c * (double)pr.master.book && pr.master.book > 0,
          "P=%d master: compute %.17g, c x bookkeeping units %.17g (at the node price)", procs,
          sim_rank(s, 0)->compute, cfg.c * (double)pr.master.book);
    CHECK(nodes == pr.counts.nodes, "P=%d: slaves' nodes %llu, reported %llu", procs,
          (unsigned long long)nodes, (unsigned long long)pr.counts.nodes);
    /* Kinds against tags: terminates are the master's BACK messages and count
     * as control; REPORT and QUIT (one each per slave) and STATS are not counted. */
    long long term = sim_rank(s, 0)->sent_tag[PAR_TAG_BACK], S = nr - 1;
    CHECK((uint64_t)tags[PAR_TAG_BOUNDARY] == pr.counts.msgs[PAR_BOUNDARY], "P=%d: boundary", procs);
    CHECK((uint64_t)tags[PAR_TAG_BOUND] == pr.counts.msgs[PAR_BOUNDS], "P=%d: bounds", procs);
    CHECK((uint64_t)(tags[PAR_TAG_PIECE] + tags[PAR_TAG_BACK] - term) == pr.counts.msgs[PAR_BACKTRACK],
          "P=%d: backtrack %llu, tags say %lld", procs, (unsigned long long)pr.counts.msgs[PAR_BACKTRACK],
          tags[PAR_TAG_PIECE] + tags[PAR_TAG_BACK] - term);
    CHECK((uint64_t)(tags[PAR_TAG_POINTS] + tags[PAR_TAG_TASK] - 2 * S + term + tags[PAR_TAG_RESULT]) ==
              pr.counts.msgs[PAR_CONTROL],
          "P=%d: control %llu, tags say %lld", procs, (unsigned long long)pr.counts.msgs[PAR_CONTROL],
          tags[PAR_TAG_POINTS] + tags[PAR_TAG_TASK] - 2 * S + term + tags[PAR_TAG_RESULT]);
    CHECK(tags[PAR_TAG_STATS] == S, "P=%d: %lld STATS messages", procs, tags[PAR_TAG_STATS]);
    CHECK(pr.time > 0 && pr.time <= st->makespan, "P=%d: time %.9f, makespan %.9f", procs, pr.time, st->makespan);
    tiling_free(&pr.t);
    sim_free(s);
  }
  free(P);
  free(Q);
}

int main(void) {
  rng g;
  rng_seed(&g, 1993);
  check_messages(&g);
  check_stats(&g);
  check_random(&g);
  check_real();
  return check_done("test_par");
}
