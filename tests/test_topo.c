/* test_topo.c -- topologies, links and placement against closed forms.
 *
 * Costs are binary fractions (m = 1/4, r = 1/8, beta = 1/64 s per byte), so
 * every expected time below is exact and compared with ==.  The expected
 * values come from the formulas of topo.h, link.h and place.h (and the
 * design note's counting), computed here independently of sim/:
 *   routes: h(s, d) by the distance formula of each topology, and the route's
 *     links chained by their names from s to d;
 *   one message over h hops: m + h*r + L*beta cut-through, m + h*(r + L*beta)
 *     store-and-forward, m + r + L*beta on the bus;
 *   a token ring per lap: on a line (linear), a ring, a hypercube (gray), a
 *     mesh (snake);
 *   the line bisection's arrivals, shifts and reversal's busiest link;
 *   the butterfly: every cyclic shift conflict-free, bit reversal's sqrt(N)
 *     on the middle wires, all-to-one's tree of saturation;
 *   conservation: bytes over links = hop-bytes, hops = the sum of distances;
 *   the bus topology = the bus model, full with no network cost = ideal,
 *     bit for bit, on random programs;
 *   the parallel algorithm's result unchanged by any topology or placement.
 * The machines and their closed forms are topomachine.h's; the placement
 * maps are test_place.c's. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/gen.h"
#include "sim/link.h"
#include "mp/mp.h"
#include "sim/place.h"
#include "tests/randprog.h"
#include "util/rng.h"
#include "tests/parmachine.h"
#include "sim/sim.h"
#include "algo/tiling.h"
#include "sim/topo.h"
#include "util/xmem.h"

#include "tests/topomachine.h"

/* ==== routes ============================================================== */

static void test_routes(void) {
  char err[256], name[64];
  int bad = 0;
  for (int i = 0; i < NMACHINES; i++) {
    const machine *mc = &machines[i];
    dims x = tm_dims(mc);
    topo *t = tm_topo(mc, err, sizeof err);
    CHECK(t != NULL, "machine %d: %s", i, err);
    if (!t) continue;
    CHECK(topo_nodes(t) == x.N, "machine %d: %d processors, expected %d", i, topo_nodes(t), x.N);
    int *route = xmallocarray((size_t)topo_max_hops(t), sizeof *route), maxh = 0;
    for (int s = 0; s < x.N; s++)
      for (int d = 0; d < x.N; d++) {
        if (s == d) continue;
        int h = topo_route(t, s, d, route), want = tm_hops(mc, &x, s, d);
        if (h > maxh) maxh = h;
        if (h != want) {
          if (bad++ < 5) CHECK(0, "machine %d: %d -> %d: %d links, expected %d", i, s, d, h, want);
          continue;
        }
        int at = s, ok = 1;
        for (int j = 0; j < h; j++) {
          ok &= topo_link_exists(t, route[j]);
          for (int q = 0; q < j; q++) ok &= route[q] != route[j];
          topo_link_name(t, route[j], name, sizeof name);
          int a, b, lv, w;
          if (mc->kind == TOPO_BUS) {
            ok &= strcmp(name, "bus") == 0;
          } else if (mc->kind == TOPO_FULL) {
            char want_name[32];
            snprintf(want_name, sizeof want_name, j == 0 ? "%d>sw" : "sw>%d", j == 0 ? s : d);
            ok &= strcmp(name, want_name) == 0;
          } else if (mc->kind == TOPO_BUTTERFLY) {
            /* Level j's wire: the top j digits of d, the bottom n-j of s. */
            int hi = 1;
            for (int q = 0; q < x.n - j; q++) hi *= x.k;
            int wire = d / hi * hi + s % hi;
            if (j == 0) ok &= sscanf(name, "in %d", &w) == 1 && w == s;
            else if (j == x.n) ok &= sscanf(name, "out %d", &w) == 1 && w == d;
            else ok &= sscanf(name, "L%d w%d", &lv, &w) == 2 && lv == j && w == wire;
          } else {
            /* A processor-to-processor link: it starts where the last ended. */
            ok &= sscanf(name, "%d>%d", &a, &b) == 2 && a == at && tm_hops(mc, &x, a, b) == 1;
            at = b;
          }
        }
        if (mc->kind != TOPO_BUS && mc->kind != TOPO_FULL && mc->kind != TOPO_BUTTERFLY)
          ok &= at == d;
        if (!ok && bad++ < 5) CHECK(0, "machine %d: the route %d -> %d is not a chain of links", i, s, d);
      }
    CHECK(maxh <= topo_max_hops(t), "machine %d: a route of %d links, max_hops %d", i, maxh,
          topo_max_hops(t));
    free(route);
    topo_free(t);
  }
  CHECK(bad == 0, "%d routes wrong", bad);

  /* The tie rule: exactly half way round goes up. */
  topo_spec ring8 = {TOPO_RING, 8, 0};
  topo *t = topo_new(&ring8, 8, err, sizeof err);
  int route[8];
  CHECK(topo_route(t, 2, 6, route) == 4, "ring:8 2 -> 6 is 4 links");
  topo_link_name(t, route[0], name, sizeof name);
  CHECK(strcmp(name, "2>3") == 0, "ring:8 2 -> 6 goes up first, took %s", name);
  topo_free(t);
}

static void test_parse(void) {
  char err[256], buf[64];
  static const char *const good[] = {"full", "bus", "line", "ring", "mesh", "torus", "hypercube",
                                     "butterfly", "line:5", "ring:12", "mesh:4x4", "torus:32x32",
                                     "hypercube:4", "butterfly:8", "full:16", "mesh:7x1"};
  for (size_t i = 0; i < sizeof good / sizeof *good; i++) {
    topo_spec sp;
    int ok = topo_parse(good[i], &sp, err, sizeof err) == 0;
    CHECK(ok, "topology %s refused: %s", good[i], err);
    if (!ok) continue;
    topo_spec_str(&sp, buf, sizeof buf);
    CHECK(strcmp(buf, good[i]) == 0, "topology %s reads back as %s", good[i], buf);
  }
  static const char *const bad[] = {"",          "mesh:",      "mesh:4",     "mesh:4x",
                                    "mesh:0x4",  "mesh:4x4x4", "mesh: 4x4",  "hypercube:23",
                                    "line:0",    "butterfly:1", "ring:-3",   "star",
                                    "torus:9999x9999", "line:5 ", "Mesh:4x4", "hypercube:x"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    topo_spec sp;
    err[0] = 0;
    CHECK(topo_parse(bad[i], &sp, err, sizeof err) != 0 && err[0],
          "topology '%s' accepted", bad[i]);
  }
  topo_spec sp = {TOPO_MESH, 2, 2};
  CHECK(topo_new(&sp, 5, err, sizeof err) == NULL && strstr(err, "has 4 processors"),
        "mesh:2x2 for 5 processors: %s", err);

  static const char *const pgood[] = {"linear", "snake", "gray", "random:0", "random:18446744073709551615"};
  for (size_t i = 0; i < sizeof pgood / sizeof *pgood; i++) {
    place_spec p;
    int ok = place_parse(pgood[i], &p, err, sizeof err) == 0;
    CHECK(ok, "placement %s refused: %s", pgood[i], err);
    if (ok) place_spec_str(&p, buf, sizeof buf);
    CHECK(ok && strcmp(buf, pgood[i]) == 0, "placement %s reads back as %s", pgood[i], buf);
  }
  static const char *const pbad[] = {"", "Linear", "random", "random:", "random:x", "random:-1",
                                     "random:99999999999999999999", "file:", "hilbert"};
  for (size_t i = 0; i < sizeof pbad / sizeof *pbad; i++) {
    place_spec p;
    err[0] = 0;
    CHECK(place_parse(pbad[i], &p, err, sizeof err) != 0 && err[0], "placement '%s' accepted",
          pbad[i]);
  }
}

/* ==== one message over h hops ============================================= */

typedef struct {
  size_t len;
  double got;   /* when rank 1 held the message */
  int bad;
} single;

static void single_main(mp *self, void *ud) {
  single *x = ud;
  char buf[64] = {0};
  if (mp_rank(self) == 0) {
    x->bad |= mp_send(self, 1, 0, buf, x->len) != MP_OK;
  } else {
    x->bad |= mp_recv(self, 0, 0, buf, sizeof buf, NULL) != MP_OK;
    x->got = mp_time(self);
  }
}

static void test_one_message(void) {
  char err[256];
  int bad = 0, runs = 0;
  for (int i = 0; i < NMACHINES; i++) {
    const machine *mc = &machines[i];
    dims x = tm_dims(mc);
    for (int saf = 0; saf <= 1; saf++)
      for (int s = 0; s < x.N; s++)
        for (int d = 0; d < x.N; d++) {
          if (s == d || (x.N > 12 && (s + 3 * d) % 5 != 0)) continue;   /* a sample of the big ones */
          sim_config cfg = tm_netcfg(mc, saf);
          int place[2] = {s, d}, rc;
          cfg.place = place;
          single one = {24, -1, 0};
          sim *sm = simrun(&cfg, 2, single_main, &one, &rc, err, sizeof err);
          int h = tm_hops(mc, &x, s, d);
          double want = tm_alone(mc, saf, h, one.len);
          net_stats ns;
          links_total(sim_links(sm), &ns);
          runs++;
          if (rc != 0 || one.bad || one.got != want || ns.messages != 1 || ns.hops != h ||
              ns.hop_bytes != (long long)h * 24 || ns.link_wait != 0 || ns.max_link_msgs != 1) {
            if (bad++ < 5)
              CHECK(0, "machine %d %s %d -> %d (h %d): arrived %.17g, expected %.17g; %lld hops (%s)",
                    i, saf ? "saf" : "ct", s, d, h, one.got, want, ns.hops, err);
          }
          sim_free(sm);
        }
  }
  CHECK(bad == 0 && runs > 1000, "%d of %d single messages wrong", bad, runs);
}

/* ==== token rings, per lap ================================================ */

static void test_rings(void) {
  char err[256];
  /* name, machine, placement, P, store-and-forward, the lap's links crossed */
  static const struct {
    machine mc;
    const char *place;
    int saf;
    int links;   /* summed over the P hops of a lap */
  } cases[] = {
      {{TOPO_LINE, 0, 0, 6}, "linear", 0, 2 * 5},   /* P-1 hops of 1, one of P-1 */
      {{TOPO_LINE, 0, 0, 6}, "linear", 1, 2 * 5},
      {{TOPO_RING, 0, 0, 6}, "linear", 0, 6},       {{TOPO_RING, 0, 0, 7}, "linear", 1, 7},
      {{TOPO_HYPERCUBE, 3, 0, 8}, "gray", 0, 8},    {{TOPO_HYPERCUBE, 4, 0, 16}, "gray", 1, 16},
      {{TOPO_HYPERCUBE, 3, 0, 8}, "linear", 0, 11 + 3},   /* 2^(d+1)-d-2, then 7 -> 0 */
      {{TOPO_MESH, 4, 4, 16}, "snake", 0, 15 + 3},  /* snake ends below its start */
      {{TOPO_MESH, 4, 4, 16}, "linear", 0, 4 * 3 + 3 * 4 + 6},   /* row-major, then 15 -> 0 */
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    const machine *mc = &cases[i].mc;
    sim_config cfg = tm_netcfg(mc, cases[i].saf);
    int P = mc->procs, place[16], rc;
    place_spec ps;
    CHECK(place_parse(cases[i].place, &ps, err, sizeof err) == 0, "%s", err);
    topo *t = tm_topo(mc, err, sizeof err);
    CHECK(place_map(&ps, t, P, place, err, sizeof err) == 0, "%s", err);
    topo_free(t);
    cfg.place = place;
    simrun_ring g = {3, 2, 8, 0, 0};
    sim *s = simrun(&cfg, P, simrun_ring_main, &g, &rc, err, sizeof err);
    double lb = (double)g.len * BETA;
    double lap = P * (g.work * C + M) +
                 (cases[i].saf ? cases[i].links * (R + lb) : cases[i].links * R + P * lb);
    CHECK(rc == 0 && !g.bad && g.token == 3 * P, "ring case %zu: %s", i, err);
    CHECK(sim_stats_get(s)->makespan == g.laps * lap,
          "ring case %zu (%s): makespan %.17g, expected %d laps of %.17g", i, cases[i].place,
          sim_stats_get(s)->makespan, g.laps, lap);
    net_stats ns;
    links_total(sim_links(s), &ns);
    CHECK(ns.hops == (long long)g.laps * cases[i].links && ns.link_wait == 0,
          "ring case %zu: %lld hops, expected %d", i, ns.hops, g.laps * cases[i].links);
    sim_free(s);
  }
}

/* ==== permutations sent at t = 0 ========================================== */

static void test_line(void) {
  char err[256];
  perm p;
  p.len = 32;
  double lb = (double)p.len * BETA;
  for (int P = 8; P <= 16; P += 8) {
    machine mc = {TOPO_LINE, 0, 0, P};
    /* The bisection: i -> i + P/2; every message crosses the middle link. */
    for (int saf = 0; saf <= 1; saf++) {
      for (int i = 0; i < P; i++) p.dst[i] = i < P / 2 ? i + P / 2 : -1;
      sim *s = tm_run_perm(&mc, saf, &p, P, err, sizeof err);
      for (int k = 0; k < P / 2; k++) {
        double want = saf ? M + (P / 2) * (R + lb) + k * (R + 2 * lb)
                          : M + (k + P / 2) * R + (k + 1) * lb;
        CHECK(p.at[k] == want, "line:%d bisection %s: message %d arrived %.17g, expected %.17g", P,
              saf ? "saf" : "ct", k, p.at[k], want);
      }
      links *n = sim_links(s);
      net_stats ns;
      links_total(n, &ns);
      int route[1];
      topo_route(links_topo(n), P / 2 - 1, P / 2, route);
      CHECK(ns.max_link_msgs == P / 2 && links_get(n, route[0]).msgs == P / 2,
            "line:%d bisection: busiest link %lld, the middle one %lld, expected %d", P,
            ns.max_link_msgs, links_get(n, route[0]).msgs, P / 2);
      sim_free(s);
    }
    /* Shifts i -> i + s (not wrapping): the busiest link carries min(s, P - s);
     * the neighbour shift is contention-free. */
    for (int sh = 1; sh < P; sh++) {
      for (int i = 0; i < P; i++) p.dst[i] = i + sh < P ? i + sh : -1;
      sim *s = tm_run_perm(&mc, 0, &p, P, err, sizeof err);
      net_stats ns;
      links_total(sim_links(s), &ns);
      int want = sh < P - sh ? sh : P - sh;
      CHECK(ns.max_link_msgs == want, "line:%d shift %d: busiest link %lld, expected %d", P, sh,
            ns.max_link_msgs, want);
      if (sh == 1)
        for (int i = 0; i + 1 < P; i++)
          CHECK(p.at[i] == M + R + lb, "line:%d neighbour shift: %d arrived %.17g", P, i, p.at[i]);
      sim_free(s);
    }
    /* Reversal i -> P-1-i: floor(P/2) on the busiest link. */
    for (int i = 0; i < P; i++) p.dst[i] = P - 1 - i;
    sim *s = tm_run_perm(&mc, 0, &p, P, err, sizeof err);
    net_stats ns;
    links_total(sim_links(s), &ns);
    CHECK(ns.max_link_msgs == P / 2, "line:%d reversal: busiest link %lld", P, ns.max_link_msgs);
    sim_free(s);
  }
}

/* Over the links of butterfly level lv (1 .. n-1), by their names "L<lv>
 * w<wire>": the most messages one carried; *used the wires that carried any,
 * *least the fewest messages one of those carried. */
static long long level_max(links *n, int lv, int *used, long long *least) {
  const topo *t = links_topo(n);
  long long mx = 0;
  *used = 0, *least = -1;
  for (int l = 0; l < topo_nlinks(t); l++) {
    char name[48];
    int a, w;
    topo_link_name(t, l, name, sizeof name);
    if (sscanf(name, "L%d w%d", &a, &w) != 2 || a != lv) continue;
    long long v = links_get(n, l).msgs;
    if (v > mx) mx = v;
    if (v == 0) continue;
    ++*used;
    if (*least < 0 || v < *least) *least = v;
  }
  return mx;
}

static void test_butterfly(void) {
  char err[256];
  perm p;
  p.len = 16;
  double lb = (double)p.len * BETA;
  static const machine flies[] = {{TOPO_BUTTERFLY, 2, 0, 16}, {TOPO_BUTTERFLY, 4, 0, 16},
                                  {TOPO_BUTTERFLY, 3, 0, 9},  {TOPO_BUTTERFLY, 2, 0, 8},
                                  {TOPO_BUTTERFLY, 8, 0, 64}, {TOPO_BUTTERFLY, 4, 0, 64}};
  for (size_t f = 0; f < sizeof flies / sizeof *flies; f++) {
    const machine *mc = &flies[f];
    dims x = tm_dims(mc);
    int N = x.N, bad = 0;
    /* Every cyclic shift: conflict-free, each message as on an idle machine. */
    for (int c = 1; c < N; c++) {
      for (int i = 0; i < N; i++) p.dst[i] = (i + c) % N;
      sim *s = tm_run_perm(mc, 0, &p, N, err, sizeof err);
      net_stats ns;
      links_total(sim_links(s), &ns);
      bad += ns.max_link_msgs != 1 || ns.link_wait != 0;
      for (int i = 0; i < N; i++) bad += p.at[i] != M + (x.n + 1) * R + lb;
      sim_free(s);
    }
    CHECK(bad == 0, "butterfly k=%d N=%d: %d conflicts in cyclic shifts", x.k, N, bad);
    /* All to one: N-1 messages down the ejection link; k^l at level l. */
    for (int i = 0; i < N; i++) p.dst[i] = 0;
    sim *s = tm_run_perm(mc, 0, &p, N, err, sizeof err);
    links *n = sim_links(s);
    net_stats ns;
    links_total(n, &ns);
    CHECK(ns.max_link_msgs == N - 1, "butterfly k=%d N=%d all-to-one: busiest link %lld", x.k, N,
          ns.max_link_msgs);
    double last = 0;
    for (int i = 1; i < N; i++) last = p.at[i] > last ? p.at[i] : last;
    CHECK(last == M + (x.n + 1) * R + (N - 1) * lb,
          "butterfly k=%d N=%d all-to-one: the last arrived %.17g, expected %.17g", x.k, N, last,
          M + (x.n + 1) * R + (N - 1) * lb);
    for (int lv = 1, kl = x.k; lv < x.n; lv++, kl *= x.k) {
      int used;
      long long mn, mx = level_max(n, lv, &used, &mn);
      CHECK(mx == kl, "butterfly k=%d N=%d all-to-one: level %d's busiest wire %lld, expected %d",
            x.k, N, lv, mx, kl);
    }
    sim_free(s);
  }
  /* Bit reversal on a 2-ary n-fly, n even: a middle wire is the reversed
   * bottom half b of the source followed by b, so sqrt(N) wires are used and
   * sqrt(N) sources share each; one of them is a palindrome, which sends to
   * itself and never enters the network, so each carries sqrt(N) - 1. */
  for (int nn = 2; nn <= 6; nn += 2) {
    int N = 1 << nn, root = 1 << (nn / 2);
    machine mc = {TOPO_BUTTERFLY, 2, 0, N};
    for (int i = 0; i < N; i++) {
      int r = 0;
      for (int b = 0; b < nn; b++) r |= (i >> b & 1) << (nn - 1 - b);
      p.dst[i] = r;
    }
    sim *s = tm_run_perm(&mc, 0, &p, N, err, sizeof err);
    links *n = sim_links(s);
    net_stats ns;
    links_total(n, &ns);
    int used;
    long long mn, mx = level_max(n, nn / 2, &used, &mn);
    CHECK(ns.max_link_msgs == root - 1 && mx == root - 1 && mn == root - 1 && used == root,
          "bit reversal N=%d: busiest link %lld, %d middle wires used carrying %lld..%lld, "
          "expected %d carrying %d",
          N, ns.max_link_msgs, used, mn, mx, root, root - 1);
    sim_free(s);
  }
}

/* ==== conservation, and the old models bit for bit ======================== */

static void test_random_programs(void) {
  char err[512];
  int failed = 0, runs = 0;
  for (uint64_t seed = 1; seed <= 120; seed++) {
    rng r;
    rng_seed(&r, seed * 7 + 3);
    static randprog p;
    int nranks = randprog_draw(&p, seed, &r);
    machine mc = machines[seed % NMACHINES];
    dims x = tm_dims(&mc);
    int saf = rng_int(&r, 0, 1);
    sim_config cfg = tm_netcfg(&mc, saf);
    int place[RANDPROG_RANKS];
    for (int k = 0; k < nranks; k++) place[k] = rng_int(&r, 0, x.N - 1);   /* some share */
    cfg.place = place;
    cfg.m = randprog_cost(&r), cfg.hop_latency = randprog_cost(&r), cfg.per_byte = randprog_cost(&r) / 64;
    cfg.c = randprog_cost(&r), cfg.local = randprog_cost(&r) / 4;
    int rc;
    sim *s = simrun(&cfg, nranks, randprog_main, &p, &rc, err, sizeof err);
    runs++;
    const char *why;
    int failures = randprog_failures(&p, &why);
    links *n = sim_links(s);
    net_stats ns;
    links_total(n, &ns);
    /* Independently: the messages between processors and their links. */
    long long want_msgs = 0, want_hops = 0, want_hb = 0, link_msgs = 0, link_bytes = 0;
    double want_busy = 0, busy = 0;
    for (int i = 0; i < p.nmsg; i++) {
      int a = place[p.msgs[i].src], b = place[p.msgs[i].dst];
      if (a == b) continue;
      int h = tm_hops(&mc, &x, a, b);
      want_msgs++;
      want_hops += h;
      want_hb += h * (long long)p.msgs[i].len;
      double lb = (double)p.msgs[i].len * cfg.per_byte;
      want_busy += mc.kind == TOPO_BUS ? cfg.m + cfg.hop_latency + lb : h * lb;
    }
    for (int l = 0; l < topo_nlinks(links_topo(n)); l++) {
      link_stats ls = links_get(n, l);
      link_msgs += ls.msgs, link_bytes += ls.bytes, busy += ls.busy;
    }
    int ok = rc == 0 && !failures && ns.messages == want_msgs && ns.hops == want_hops &&
             ns.hop_bytes == want_hb && link_msgs == ns.hops && link_bytes == ns.hop_bytes &&
             busy == want_busy;
    if (!ok && failed++ < 3)
      CHECK(0, "random program %llu on machine %d: rc %d (%s), %d failures (%s); messages %lld/%lld, "
               "hops %lld/%lld, hop-bytes %lld/%lld, link bytes %lld, busy %.17g/%.17g",
            (unsigned long long)seed, (int)(seed % NMACHINES), rc, err, failures, why, ns.messages,
            want_msgs, ns.hops, want_hops, ns.hop_bytes, want_hb, link_bytes, busy, want_busy);
    sim_free(s);
  }
  CHECK(failed == 0, "%d of %d random programs on topologies failed", failed, runs);
}

/* The same random program on two configurations: every rank's clock, bit for bit. */
static int same_run(const sim_config *a, const sim_config *b, uint64_t seed, int nranks,
                    const char *what) {
  char err[512];
  static randprog p1, p2;
  randprog_make(&p1, seed, nranks);
  randprog_make(&p2, seed, nranks);
  int rc1, rc2;
  sim *s1 = simrun(a, nranks, randprog_main, &p1, &rc1, err, sizeof err);
  sim *s2 = simrun(b, nranks, randprog_main, &p2, &rc2, err, sizeof err);
  int same = rc1 == 0 && rc2 == 0;
  for (int k = 0; same && k < nranks; k++) {
    const sim_rank_stats *x = sim_rank(s1, k), *y = sim_rank(s2, k);
    same = x->finish == y->finish && x->recv_wait == y->recv_wait && x->cpu_wait == y->cpu_wait;
  }
  if (!same) CHECK(0, "%s: seed %llu differs (%.17g against %.17g)", what, (unsigned long long)seed,
                   sim_stats_get(s1)->makespan, sim_stats_get(s2)->makespan);
  sim_free(s1);
  sim_free(s2);
  return same;
}

static void test_old_models(void) {
  int bad = 0;
  for (uint64_t seed = 1; seed <= 80; seed++) {
    rng r;
    rng_seed(&r, seed);
    int nranks = rng_int(&r, 2, RANDPROG_RANKS), procs = rng_int(&r, 1, nranks);
    int place[RANDPROG_RANKS];
    for (int k = 0; k < nranks; k++) place[k] = rng_int(&r, 0, procs - 1);
    sim_config old;
    sim_config_init(&old);
    old.procs = procs, old.place = place, old.warn = NULL;
    old.stack = 64 * 1024;
    /* Decimal costs: bit for bit needs the same rounding, not exact numbers. */
    old.m = 1e-4 * (1 + rng_int(&r, 0, 9)), old.per_byte = 3e-8 * rng_int(&r, 0, 3);
    old.c = 7e-6 * (1 + rng_int(&r, 0, 5)), old.local = 1e-6 * rng_int(&r, 0, 2);
    /* bus */
    old.net = SIM_NET_BUS;
    sim_config tp = old;
    tp.topo = (topo_spec){TOPO_BUS, 0, 0};
    tp.store_forward = rng_int(&r, 0, 1);   /* irrelevant on a bus */
    bad += !same_run(&old, &tp, seed, nranks, "bus topology against the bus");
    /* full with no network cost against ideal */
    old.net = SIM_NET_IDEAL;
    old.per_byte = 0;
    tp = old;
    tp.topo = (topo_spec){TOPO_FULL, 0, 0};
    tp.hop_latency = 0;
    bad += !same_run(&old, &tp, seed, nranks, "full, no network cost, against ideal");
  }
  CHECK(bad == 0, "%d random programs differ between the old models and their topologies", bad);
}

/* The receiver takes one message at a time on full: a fan-in is spaced by
 * L*beta, where ideal delivers all at once. */
static void test_full_fanin(void) {
  char err[256];
  machine mc = {TOPO_FULL, 0, 0, 7};
  perm p;
  p.len = 32;
  for (int i = 0; i < 7; i++) p.dst[i] = i ? 0 : -1;
  sim *s = tm_run_perm(&mc, 0, &p, 7, err, sizeof err);
  double lb = p.len * BETA;
  for (int i = 1; i < 7; i++)
    CHECK(p.at[i] == M + 2 * R + i * lb, "full fan-in: rank %d arrived %.17g, expected %.17g", i,
          p.at[i], M + 2 * R + i * lb);
  sim_free(s);
}

/* ==== traces ============================================================== */

static void test_trace(void) {
  char err[256], *csv[2], *json[2];
  size_t clen, jlen;
  for (int k = 0; k < 2; k++) {
    FILE *fc = open_memstream(&csv[k], &clen), *fj = open_memstream(&json[k], &jlen);
    machine mc = {TOPO_MESH, 3, 2, 6};
    sim_config cfg = tm_netcfg(&mc, 0);
    sim *s = sim_new(&cfg, 6, err, sizeof err);
    sim_trace(s, fc, fj);
    simrun_ring g = {2, 1, 8, 0, 0};
    mp_proc pr[6];
    for (int i = 0; i < 6; i++) pr[i] = (mp_proc){simrun_ring_main, &g};
    CHECK(sim_run(s, pr, err, sizeof err) == 0, "traced ring: %s", err);
    fclose(fc);
    fclose(fj);
    sim_free(s);
  }
  CHECK(strcmp(csv[0], csv[1]) == 0 && strcmp(json[0], json[1]) == 0, "two traced runs differ");
  CHECK(strstr(json[0], "\"name\":\"network\"") && strstr(json[0], "\"link 0>1\"") &&
            strstr(json[0], "\"cat\":\"link\"") && strstr(json[0], "\"pid\":6,\"tid\":"),
        "the JSON trace lacks the network's link tracks");
  int nlink = 0, badrows = 0;
  for (char *line = csv[0]; *line;) {
    char *nl = strchr(line, '\n');
    int commas = 0;
    for (char *q = line; q < nl; q++) commas += *q == ',';
    badrows += commas != 9;
    nlink += strstr(line, ",link,") != NULL && strstr(line, ",link,") < nl;
    line = nl + 1;
  }
  /* The ring of 6 on a 3x2 mesh, row-major: four hops of 1, 2 -> 3 and 5 -> 0 of 3. */
  CHECK(badrows == 0 && nlink == 2 * (4 + 3 + 3), "CSV trace: %d link rows (expected 20), %d rows not of 10 fields",
        nlink, badrows);
  for (int k = 0; k < 2; k++) free(csv[k]), free(json[k]);
}

static void test_sim_errors(void) {
  char err[256];
  machine mc = {TOPO_MESH, 2, 2, 4};
  sim_config cfg = tm_netcfg(&mc, 0);
  int place[2] = {0, 4};
  cfg.place = place;
  CHECK(sim_new(&cfg, 2, err, sizeof err) == NULL && strstr(err, "place[1] = 4"),
        "a rank outside the topology: %s", err);
  cfg.place = NULL;
  cfg.procs = 5;
  CHECK(sim_new(&cfg, 5, err, sizeof err) == NULL && strstr(err, "has 4 processors"),
        "a topology too small: %s", err);
  cfg.procs = 3;   /* a run on 3 of mesh:2x2's 4 processors */
  sim *s = sim_new(&cfg, 3, err, sizeof err);
  CHECK(s && sim_stats_get(s)->procs == 4, "3 processors of mesh:2x2: %s", err);
  sim_free(s);
  cfg.hop_latency = -1;
  CHECK(sim_new(&cfg, 3, err, sizeof err) == NULL && strstr(err, "hop_latency"), "hop_latency -1: %s", err);
  sim_config none;
  sim_config_init(&none);
  none.net = SIM_NET_TOPOLOGY;
  CHECK(sim_new(&none, 2, err, sizeof err) == NULL, "SIM_NET_TOPOLOGY without a topology accepted");
  sim_net nt;
  CHECK(sim_net_parse("topology", &nt) != 0, "--net topology accepted");
}

/* ==== the parallel algorithm: placement never changes a result ============ */

static int same_tiling(const tiling *a, const tiling *b) {
  return a->quanta == b->quanta && a->start == b->start && a->m == b->m && a->n == b->n &&
         memcmp(a->col, b->col, sizeof *a->col * (size_t)(a->m + a->n + 1)) == 0;
}

static void test_par_results(void) {
  static const struct {
    const char *topo, *place;
    int procs;
    int saf;
  } cfgs[] = {{"line", "linear", 6, 0},          {"line", "random:5", 9, 1},
              {"mesh:4x4", "snake", 13, 0},      {"mesh:4x4", "random:2", 16, 0},
              {"hypercube:4", "gray", 11, 1},    {"torus:3x3", "linear", 9, 0},
              {"butterfly:2", "random:9", 7, 0}, {"full", "gray", 5, 0},
              {"ring", "snake", 4, 1},           {"bus", "random:1", 8, 0}};
  rng g;
  rng_seed(&g, 2026);
  vec2 P[80], Q[80];
  int bad = 0, runs = 0;
  for (int pair = 0; pair < 6; pair++) {
    int np = rng_int(&g, 20, 70), nq = rng_int(&g, 20, 70);
    gen_star(&g, P, np, 0, 0, 10, 0.4);
    gen_star(&g, Q, nq, 1, 0.5, 8, 0.4);
    tiling ser;
    tiling_solve(P, np, 0, Q, nq, 1.5, COST_AREA, -1, &ser);
    for (size_t c = 0; c < sizeof cfgs / sizeof *cfgs; c++) {
      par_machine rc;
      par_machine_init(&rc);
      rc.mc.sim.warn = NULL;
      rc.mc.procs = cfgs[c].procs;
      rc.pc.opt.alloc = pair % 2 ? ALLOC_SIZE : ALLOC_HALF;
      rc.mc.sim.hop_latency = 1e-5;
      rc.mc.sim.store_forward = cfgs[c].saf;
      char err[300];
      CHECK(topo_parse(cfgs[c].topo, &rc.mc.sim.topo, err, sizeof err) == 0, "%s", err);
      rc.mc.sim.net = SIM_NET_TOPOLOGY;
      CHECK(place_parse(cfgs[c].place, &rc.mc.place, err, sizeof err) == 0, "%s", err);
      net_stats ns;
      rc.pair_net = &ns;
      par_pair pr;
      memset(&pr, 0, sizeof pr);
      pr.P = P, pr.np = np, pr.zp = 0, pr.Q = Q, pr.nq = nq, pr.zq = 1.5;
      runs++;
      if (par_machine_sim(&rc, &pr, 1, NULL, err, sizeof err) != 0) {
        CHECK(0, "pair %d on %s/%s: %s", pair, cfgs[c].topo, cfgs[c].place, err);
        bad++;
        continue;
      }
      if (!same_tiling(&pr.t, &ser) || pr.counts.nodes != ser.count.nodes || ns.messages <= 0) {
        bad++;
        CHECK(0, "pair %d on %s/%s P=%d: %.17g (start %d), serial %.17g (start %d); %lld messages",
              pair, cfgs[c].topo, cfgs[c].place, cfgs[c].procs, pr.t.quanta, pr.t.start,
              ser.quanta, ser.start, ns.messages);
      }
      tiling_free(&pr.t);
    }
    tiling_free(&ser);
  }
  CHECK(bad == 0, "%d of %d runs on topologies differ from the serial solver", bad, runs);
}

int main(void) {
  test_parse();
  test_routes();
  test_one_message();
  test_rings();
  test_line();
  test_butterfly();
  test_full_fanin();
  test_random_programs();
  test_old_models();
  test_trace();
  test_sim_errors();
  test_par_results();
  return check_done("test_topo");
}
