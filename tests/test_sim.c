/* test_sim.c -- the simulator against closed-form times and random programs
 * (its error reports: test_simerrors.c).
 *
 * Costs are exact binary fractions (m = 0.25, c = 0.125, ...) so that every
 * simulated time is exact and expected values can be compared with ==.  The
 * expected values are computed here from the model in sim.h, independently
 * of the simulator's code. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "tests/randprog.h"
#include "tests/simrun.h"
#include "mp/mp.h"
#include "util/rng.h"
#include "sim/sim.h"

/* ==== helpers ============================================================= */

static const sim_net nets[] = {SIM_NET_IDEAL, SIM_NET_BUS, SIM_NET_LOGGP};

/* The one-way time of a len-byte message between processors, and what the
 * receiver's clock gains on top of the sender's send call: the model. */
static double hop(const sim_config *c, size_t len) {
  switch (c->net) {
  case SIM_NET_IDEAL:
  case SIM_NET_BUS: return c->m + (double)len * c->per_byte;
  default: return c->o + (len > 1 ? (double)(len - 1) * c->G : 0) + c->L + c->o;
  }
}

/* ==== ping-pong and ring: closed forms ==================================== */

typedef struct {
  int rounds;
  double work0, work1;  /* units each side computes per round */
  size_t len;
  int bad;              /* an mp call failed */
} pingpong;

static void pingpong_main(mp *self, void *ud) {
  pingpong *p = ud;
  char buf[64] = {0};
  int me = mp_rank(self);
  for (int k = 0; k < p->rounds; k++) {
    if (me == 0) {
      p->bad |= mp_compute(self, p->work0) != MP_OK;
      p->bad |= mp_send(self, 1, 1, buf, p->len) != MP_OK;
      p->bad |= mp_recv(self, 1, 1, buf, sizeof buf, NULL) != MP_OK;
    } else {
      p->bad |= mp_recv(self, 0, 1, buf, sizeof buf, NULL) != MP_OK;
      p->bad |= mp_compute(self, p->work1) != MP_OK;
      p->bad |= mp_send(self, 0, 1, buf, p->len) != MP_OK;
    }
  }
}

static void test_pingpong(void) {
  char err[512];
  for (int ni = 0; ni < 3; ni++) {
    for (size_t len = 1; len <= 9; len += 8) {
      sim_config cfg = simrun_config(nets[ni], 2);
      pingpong p = {7, 3, 5, len, 0};
      int rc;
      sim *s = simrun(&cfg, 2, pingpong_main, &p, &rc, err, sizeof err);
      double h = hop(&cfg, len);
      double round = (p.work0 + p.work1) * cfg.c + 2 * h;
      double want0 = p.rounds * round;
      /* Rank 1 ends with its last send: on LogGP it still pays the send's o. */
      double want1 = want0 - h + (cfg.net == SIM_NET_LOGGP ? cfg.o : 0);
      const char *nn = sim_net_name(cfg.net);
      CHECK(rc == 0 && !p.bad, "%s ping-pong failed: %s", nn, err);
      CHECK(sim_rank(s, 0)->finish == want0, "%s len %zu: rank 0 finished at %.17g, expected %.17g",
            nn, len, sim_rank(s, 0)->finish, want0);
      CHECK(sim_rank(s, 1)->finish == want1, "%s len %zu: rank 1 finished at %.17g, expected %.17g",
            nn, len, sim_rank(s, 1)->finish, want1);
      CHECK(sim_stats_get(s)->makespan == want0, "%s: makespan %.17g, expected %.17g", nn,
            sim_stats_get(s)->makespan, want0);
      sim_free(s);
    }
  }
}

static void test_ring(void) {
  char err[512];
  for (int ni = 0; ni < 3; ni++) {
    sim_config cfg = simrun_config(nets[ni], 5);
    simrun_ring g = {4, 2, 9, 0, 0};
    int rc;
    sim *s = simrun(&cfg, 5, simrun_ring_main, &g, &rc, err, sizeof err);
    double want = 5 * g.laps * (g.work * cfg.c + hop(&cfg, g.len));
    const char *nn = sim_net_name(cfg.net);
    CHECK(rc == 0 && !g.bad, "%s ring failed: %s", nn, err);
    CHECK(g.token == 5LL * g.laps, "%s ring: token %lld, expected %d", nn, g.token, 5 * g.laps);
    CHECK(sim_stats_get(s)->makespan == want, "%s ring: makespan %.17g, expected %.17g", nn,
          sim_stats_get(s)->makespan, want);
    CHECK(sim_stats_get(s)->messages == 5 * g.laps, "%s ring: %lld messages", nn,
          sim_stats_get(s)->messages);
    sim_free(s);
  }
}

/* ==== contention: the bus, shared processors, local messages ============== */

enum { MAXLOG = 64 };

typedef struct {
  int n;                    /* entries logged by rank 0 */
  double t[MAXLOG];         /* its clock after each recv */
  int src[MAXLOG];
  double work;              /* for the co-located test */
} fanin;

/* Ranks 1..n-1 send to rank 0 at t = 0; rank 0 receives with MP_ANY. */
static void fanin_main(mp *self, void *ud) {
  fanin *f = ud;
  int me = mp_rank(self), n = mp_size(self);
  if (me != 0) {
    mp_send(self, 0, me, NULL, 0);
    return;
  }
  for (int i = 1; i < n; i++) {
    mp_status st;
    if (mp_recv(self, MP_ANY, MP_ANY, NULL, 0, &st) != MP_OK) return;
    f->t[f->n] = mp_time(self);
    f->src[f->n++] = st.source;
  }
}

static void test_bus_spacing(void) {
  char err[512];
  enum { K = 6 };
  for (int ni = 0; ni < 3; ni++) {
    sim_config cfg = simrun_config(nets[ni], K + 1);
    fanin f = {0};
    int rc;
    sim *s = simrun(&cfg, K + 1, fanin_main, &f, &rc, err, sizeof err);
    const char *nn = sim_net_name(cfg.net);
    CHECK(rc == 0 && f.n == K, "%s fan-in: %d received: %s", nn, f.n, err);
    for (int j = 0; j < f.n; j++) {
      double want = cfg.net == SIM_NET_BUS     ? (j + 1) * cfg.m       /* spaced by m */
                    : cfg.net == SIM_NET_IDEAL ? cfg.m                 /* all at once */
                                               : cfg.o + cfg.L + (j + 1) * cfg.o;
      CHECK(f.t[j] == want, "%s: receive %d at %.17g, expected %.17g", nn, j, f.t[j], want);
      CHECK(f.src[j] == j + 1, "%s: receive %d from rank %d, expected rank %d (send order)", nn,
            j, f.src[j], j + 1);
    }
    sim_free(s);
  }
}

static void colocated_main(mp *self, void *ud) {
  fanin *f = ud;
  mp_compute(self, f->work);
}

static void test_colocated(void) {
  char err[512];
  /* Three ranks on one processor: their computes run one after the other. */
  sim_config cfg = simrun_config(SIM_NET_BUS, 1);
  fanin f = {.work = 3};
  int rc;
  sim *s = simrun(&cfg, 3, colocated_main, &f, &rc, err, sizeof err);
  for (int r = 0; r < 3; r++) {
    double want = (r + 1) * f.work * cfg.c;
    CHECK(sim_rank(s, r)->finish == want, "co-located rank %d finished at %.17g, expected %.17g",
          r, sim_rank(s, r)->finish, want);
    CHECK(sim_rank(s, r)->cpu_wait == r * f.work * cfg.c, "rank %d waited %.17g for the cpu", r,
          sim_rank(s, r)->cpu_wait);
  }
  sim_free(s);

  /* Four ranks on two processors (r % 2): pairs serialise, not all four. */
  cfg = simrun_config(SIM_NET_IDEAL, 2);
  s = simrun(&cfg, 4, colocated_main, &f, &rc, err, sizeof err);
  for (int r = 0; r < 4; r++) {
    double want = (r / 2 + 1) * f.work * cfg.c;
    CHECK(sim_rank(s, r)->finish == want, "2 procs: rank %d finished at %.17g, expected %.17g", r,
          sim_rank(s, r)->finish, want);
  }
  sim_free(s);

  /* Messages on one processor cost `local`, whatever the network. */
  for (int ni = 0; ni < 3; ni++) {
    cfg = simrun_config(nets[ni], 1);
    cfg.local = 0.0625;
    pingpong p = {5, 1, 2, 9, 0};
    s = simrun(&cfg, 2, pingpong_main, &p, &rc, err, sizeof err);
    double want = p.rounds * ((p.work0 + p.work1) * cfg.c + 2 * cfg.local);
    CHECK(rc == 0 && sim_stats_get(s)->makespan == want,
          "%s on one processor: makespan %.17g, expected %.17g (%s)", sim_net_name(cfg.net),
          sim_stats_get(s)->makespan, want, err);
    sim_free(s);
  }
}

/* A rank waiting in recv leaves its processor to the other rank there. */
typedef struct {
  double t1;
} waitfree;

static void waitfree_main(mp *self, void *ud) {
  waitfree *w = ud;
  int me = mp_rank(self);
  if (me == 0) {
    mp_recv(self, 2, 0, NULL, 0, NULL);
  } else if (me == 1) {
    mp_compute(self, 2);
    w->t1 = mp_time(self);
  } else {
    mp_compute(self, 8);
    mp_send(self, 0, 0, NULL, 0);
  }
}

static void test_recv_frees_cpu(void) {
  char err[512];
  int place[3] = {0, 0, 1};
  sim_config cfg = simrun_config(SIM_NET_BUS, 2);
  cfg.place = place;
  waitfree w = {0};
  int rc;
  sim *s = simrun(&cfg, 3, waitfree_main, &w, &rc, err, sizeof err);
  CHECK(w.t1 == 2 * cfg.c, "rank 1 computed until %.17g, expected %.17g", w.t1, 2 * cfg.c);
  CHECK(sim_rank(s, 0)->finish == 8 * cfg.c + cfg.m, "rank 0 finished at %.17g",
        sim_rank(s, 0)->finish);
  sim_free(s);
}

/* ==== LogGP: o, g, G ====================================================== */

typedef struct {
  int n;
  double t[MAXLOG];
  size_t len;
} burst;

/* Rank 0 sends four messages back to back; rank 1 logs when each recv returns. */
static void burst_main(mp *self, void *ud) {
  burst *b = ud;
  char buf[32] = {0};
  if (mp_rank(self) == 0) {
    for (int i = 0; i < 4; i++) mp_send(self, 1, 0, buf, b->len);
  } else {
    for (int i = 0; i < 4; i++) {
      mp_recv(self, 0, 0, buf, sizeof buf, NULL);
      b->t[b->n++] = mp_time(self);
    }
  }
}

static void test_loggp(void) {
  char err[512];
  sim_config cfg = simrun_config(SIM_NET_LOGGP, 2);
  cfg.o = 0.125;
  cfg.g = 0.5;   /* > o: the gap, not the overhead, spaces the injections */
  cfg.L = 1;
  cfg.G = 0.0625;
  for (size_t len = 0; len <= 9; len += 9) {
    burst b = {.len = len};
    int rc;
    sim *s = simrun(&cfg, 2, burst_main, &b, &rc, err, sizeof err);
    double gbytes = len > 1 ? (double)(len - 1) * cfg.G : 0;
    CHECK(rc == 0 && b.n == 4, "loggp burst: %s", err);
    for (int j = 0; j < b.n; j++) {
      /* inject_j = o + j*g; arrival_j = inject_j + (len-1)G + L; + o to receive */
      double want = cfg.o + j * cfg.g + gbytes + cfg.L + cfg.o;
      CHECK(b.t[j] == want, "loggp len %zu: recv %d at %.17g, expected %.17g", len, j, b.t[j],
            want);
    }
    CHECK(sim_rank(s, 0)->finish == 4 * cfg.o, "loggp sender finished at %.17g, expected %.17g",
          sim_rank(s, 0)->finish, 4 * cfg.o);
    CHECK(sim_rank(s, 0)->overhead == 4 * cfg.o && sim_rank(s, 1)->overhead == 4 * cfg.o,
          "loggp overheads %.17g and %.17g", sim_rank(s, 0)->overhead, sim_rank(s, 1)->overhead);
    sim_free(s);
  }
}

/* ==== ordering: non-overtaking, earliest arrival first, probe ============= */

typedef struct {
  int n;
  double t[MAXLOG];
  size_t len[MAXLOG];
  int src[MAXLOG];
  int probes[4];
} order;

/* Rank 0 sends a long then a short message to rank 2; rank 1 a short one.
 * Rank 2 receives: first from MP_ANY (the earliest arrival), then two from 0. */
static void order_main(mp *self, void *ud) {
  order *o = ud;
  static char big[1000];
  mp_status st;
  switch (mp_rank(self)) {
  case 0:
    mp_send(self, 2, 0, big, sizeof big);
    mp_send(self, 2, 1, big, 1);
    break;
  case 1:
    mp_send(self, 2, 2, big, 2);
    break;
  case 2:
    for (int i = 0; i < 3; i++) {
      mp_recv(self, i == 0 ? MP_ANY : 0, MP_ANY, big, sizeof big, &st);
      o->t[o->n] = mp_time(self);
      o->len[o->n] = st.len;
      o->src[o->n++] = st.source;
    }
    break;
  }
}

static void probe_main(mp *self, void *ud) {
  order *o = ud;
  if (mp_rank(self) == 0) {
    mp_send(self, 1, 5, "hi", 2);
    return;
  }
  mp_status st = {-1, -1, 0};
  o->probes[0] = mp_probe(self, 0, 5, &st);  /* t = 0: not yet there */
  mp_compute(self, 1);
  o->probes[1] = mp_probe(self, 0, 5, &st);  /* t = c < m */
  mp_compute(self, 1);
  o->probes[2] = mp_probe(self, MP_ANY, MP_ANY, &st);  /* t = 2c = m: arrived */
  o->probes[3] = mp_probe(self, 0, 4, NULL);  /* wrong tag */
  o->src[0] = st.source;
  o->len[0] = st.len;
  char buf[2];
  mp_recv(self, 0, 5, buf, sizeof buf, NULL);
}

static void test_order(void) {
  char err[512];
  sim_config cfg = simrun_config(SIM_NET_IDEAL, 3);
  order o = {0};
  int rc;
  sim *s = simrun(&cfg, 3, order_main, &o, &rc, err, sizeof err);
  double big = cfg.m + 1000 * cfg.per_byte;
  CHECK(rc == 0 && o.n == 3, "ordering run: %s", err);
  CHECK(o.src[0] == 1 && o.len[0] == 2 && o.t[0] == cfg.m + 2 * cfg.per_byte,
        "MP_ANY took %zu bytes from rank %d at %.17g: expected rank 1's earlier short message",
        o.len[0], o.src[0], o.t[0]);
  CHECK(o.len[1] == 1000 && o.t[1] == big, "first from rank 0: %zu bytes at %.17g", o.len[1],
        o.t[1]);
  CHECK(o.len[2] == 1 && o.t[2] == big,
        "second from rank 0: %zu bytes at %.17g: must not overtake the first (%.17g)", o.len[2],
        o.t[2], big);
  sim_free(s);

  order p = {0};
  cfg.m = 0.25; /* = 2c */
  cfg.per_byte = 0;
  s = simrun(&cfg, 2, probe_main, &p, &rc, err, sizeof err);
  CHECK(p.probes[0] == 0 && p.probes[1] == 0, "probe saw the message early: %d %d", p.probes[0],
        p.probes[1]);
  CHECK(p.probes[2] == 1 && p.src[0] == 0 && p.len[0] == 2, "probe at arrival: %d, src %d, len %zu",
        p.probes[2], p.src[0], p.len[0]);
  CHECK(p.probes[3] == 0, "probe matched the wrong tag");
  CHECK(rc == 0 && sim_stats_get(s)->unread == 0, "probe run: %s", err);
  sim_free(s);
}

/* ==== determinism: any-source order and byte-identical traces ============= */

typedef struct {
  int n;
  int seen[MAXLOG];
} anysrc;

/* Every rank but 0 sends three messages to 0 at the same instants; rank 0
 * takes them with MP_ANY and logs the order. */
static void anysrc_main(mp *self, void *ud) {
  anysrc *a = ud;
  int me = mp_rank(self), n = mp_size(self);
  if (me != 0) {
    for (int i = 0; i < 3; i++) {
      int v = me * 10 + i;
      mp_send(self, 0, i, &v, sizeof v);
      mp_compute(self, me % 2);
    }
    return;
  }
  mp_compute(self, 1);
  for (int i = 0; i < 3 * (n - 1); i++) {
    int v = -1;
    mp_recv(self, MP_ANY, MP_ANY, &v, sizeof v, NULL);
    a->seen[a->n++] = v;
    if (i % 4 == 0) mp_compute(self, 0.5);
  }
}

/* Run anysrc with traces into memory: the order seen, the CSV, the JSON. */
static void anysrc_run(sim_net net, int procs, anysrc *a, char **csv, char **json) {
  char err[512];
  size_t lc, lj;
  FILE *fc = open_memstream(csv, &lc), *fj = open_memstream(json, &lj);
  sim_config cfg = simrun_config(net, procs);
  sim *s = sim_new(&cfg, 6, err, sizeof err);
  sim_trace(s, fc, fj);
  mp_proc pr[6];
  for (int i = 0; i < 6; i++) pr[i] = (mp_proc){anysrc_main, a};
  int rc = sim_run(s, pr, err, sizeof err);
  CHECK(rc == 0, "anysrc run: %s", err);
  fclose(fc);
  fclose(fj);
  sim_free(s);
}

/* A minimal JSON syntax check: enough to see that the trace parses. */
static const char *json_value(const char *p);

static const char *json_ws(const char *p) {
  while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r') p++;
  return p;
}

static const char *json_string(const char *p) {
  if (*p != '"') return NULL;
  for (p++; *p && *p != '"'; p++)
    if (*p == '\\' && !*++p) return NULL;
  return *p == '"' ? p + 1 : NULL;
}

static const char *json_value(const char *p) {
  p = json_ws(p);
  if (*p == '{' || *p == '[') {
    char close = *p == '{' ? '}' : ']';
    p = json_ws(p + 1);
    if (*p == close) return p + 1;
    for (;;) {
      if (close == '}') {
        p = json_string(json_ws(p));
        if (!p || *(p = json_ws(p)) != ':') return NULL;
        p++;
      }
      if (!(p = json_value(p))) return NULL;
      p = json_ws(p);
      if (*p == close) return p + 1;
      if (*p != ',') return NULL;
      p++;
    }
  }
  if (*p == '"') return json_string(p);
  if (*p == '-' || (*p >= '0' && *p <= '9')) {
    char *end;
    strtod(p, &end);
    return end;
  }
  if (strncmp(p, "true", 4) == 0 || strncmp(p, "null", 4) == 0) return p + 4;
  if (strncmp(p, "false", 5) == 0) return p + 5;
  return NULL;
}

static int json_valid(const char *s) {
  const char *end = json_value(s);
  return end && *json_ws(end) == 0;
}

static void test_determinism(void) {
  for (int ni = 0; ni < 3; ni++) {
    anysrc a = {0}, b = {0};
    char *csv1, *json1, *csv2, *json2;
    anysrc_run(nets[ni], 3, &a, &csv1, &json1);
    anysrc_run(nets[ni], 3, &b, &csv2, &json2);
    const char *nn = sim_net_name(nets[ni]);
    CHECK(a.n == 15 && a.n == b.n && memcmp(a.seen, b.seen, sizeof a.seen) == 0,
          "%s: MP_ANY resolved differently on two runs", nn);
    CHECK(strcmp(csv1, csv2) == 0, "%s: two runs gave different CSV traces", nn);
    CHECK(strcmp(json1, json2) == 0, "%s: two runs gave different JSON traces", nn);
    const char *header = "time,rank,proc,event,peer,tag,bytes,duration,msg,arrival\n";
    CHECK(strncmp(csv1, header, strlen(header)) == 0,
          "%s: CSV header: %.60s", nn, csv1);
    CHECK(json_valid(json1), "%s: the JSON trace does not parse", nn);
    CHECK(strstr(json1, "\"traceEvents\":[") && strstr(json1, "\"ph\":\"X\"") &&
              strstr(json1, "\"ph\":\"s\"") && strstr(json1, "\"ph\":\"f\"") &&
              strstr(json1, "\"name\":\"thread_name\"") && strstr(json1, "\"rank 5\""),
          "%s: the JSON trace lacks slices, flows or names", nn);
    /* Every CSV row has ten fields. */
    int rows = 0, badrows = 0;
    for (char *line = csv1; *line; rows++) {
      char *nl = strchr(line, '\n');
      int commas = 0;
      for (char *q = line; q < nl; q++) commas += *q == ',';
      badrows += commas != 9;
      line = nl + 1;
    }
    CHECK(rows > 30 && badrows == 0, "%s: %d CSV rows, %d without 10 fields", nn, rows, badrows);
    free(csv1), free(json1), free(csv2), free(json2);
  }
}

/* A tiny run whose whole CSV trace is known: unit costs, bus. */
static void tiny_main(mp *self, void *ud) {
  (void)ud;
  int x = 0;
  if (mp_rank(self) == 0) {
    mp_compute(self, 2);
    mp_send(self, 1, 3, &x, sizeof x);
  } else {
    mp_recv(self, MP_ANY, 3, &x, sizeof x, NULL);
    mp_compute(self, 1);
  }
}

static void test_trace_exact(void) {
  char err[512], *csv;
  size_t len;
  FILE *f = open_memstream(&csv, &len);
  sim_config cfg;
  sim_profile("unit", &cfg);
  cfg.procs = 2;
  cfg.warn = NULL;
  sim *s = sim_new(&cfg, 2, err, sizeof err);
  sim_trace(s, f, NULL);
  mp_proc pr[2] = {{tiny_main, NULL}, {tiny_main, NULL}};
  CHECK(sim_run(s, pr, err, sizeof err) == 0, "tiny run: %s", err);
  fclose(f);
  const char *want =
      "time,rank,proc,event,peer,tag,bytes,duration,msg,arrival\n"
      "0.000000000,0,0,compute,,,,2.000000000,,\n"
      "2.000000000,0,0,send,1,3,4,0.000000000,3,3.000000000\n"
      "2.000000000,0,0,finish,,,,,,\n"
      "0.000000000,1,1,wait,any,3,,3.000000000,,\n"
      "3.000000000,1,1,recv,0,3,4,0.000000000,3,\n"
      "3.000000000,1,1,compute,,,,1.000000000,,\n"
      "4.000000000,1,1,finish,,,,,,\n";
  CHECK(strcmp(csv, want) == 0, "tiny trace:\n%s\nexpected:\n%s", csv, want);
  free(csv);
  sim_free(s);
}

/* ==== deadlock ============================================================ */

typedef struct {
  int rc[4][3];  /* per rank: the blocked recv's status, then two later calls */
} dl;

static void deadlock_main(mp *self, void *ud) {
  dl *d = ud;
  int me = mp_rank(self);
  if (me == 2) {
    mp_compute(self, 1);
    return;
  }
  d->rc[me][0] = mp_recv(self, me == 0 ? MP_ANY : 0, me == 0 ? 3 : MP_ANY, NULL, 0, NULL);
  d->rc[me][1] = mp_send(self, 2, 0, NULL, 0);
  d->rc[me][2] = mp_compute(self, 1);
}

static void test_deadlock(void) {
  char err[512];
  sim_config cfg = simrun_config(SIM_NET_BUS, 3);
  dl d;
  memset(&d, 0x55, sizeof d);
  int rc;
  sim *s = simrun(&cfg, 3, deadlock_main, &d, &rc, err, sizeof err);
  CHECK(rc == -1, "a deadlock must fail the run");
  CHECK(strstr(err, "deadlock at t=0.125:") != NULL, "deadlock message: %s", err);
  CHECK(strstr(err, "rank 0 waits in recv(src=any, tag=3)") != NULL, "rank 0 not named: %s", err);
  CHECK(strstr(err, "rank 1 waits in recv(src=0, tag=any)") != NULL, "rank 1 not named: %s", err);
  CHECK(strstr(err, "rank 2") == NULL, "rank 2 finished, but is named: %s", err);
  for (int r = 0; r < 2; r++) {
    CHECK(d.rc[r][0] == MP_EDEADLOCK, "rank %d: the blocked recv returned %d", r, d.rc[r][0]);
    CHECK(d.rc[r][1] == MP_ESTOPPED && d.rc[r][2] == MP_ESTOPPED,
          "rank %d: calls after the deadlock returned %d, %d", r, d.rc[r][1], d.rc[r][2]);
    CHECK(sim_rank(s, r)->done, "rank %d did not get to return", r);
  }
  CHECK(sim_stats_get(s)->deadlock == 1, "deadlock not flagged in the statistics");
  sim_free(s);
}

/* A rank that ignores the stop and keeps calling is abandoned, not waited for. */
static void stubborn_main(mp *self, void *ud) {
  (void)ud;
  if (mp_rank(self) == 0) {
    while (mp_recv(self, 1, 0, NULL, 0, NULL) != MP_OK) {
    }
  } else {
    mp_recv(self, 0, 0, NULL, 0, NULL);
  }
}

static void test_abandon(void) {
  char err[512];
  sim_config cfg = simrun_config(SIM_NET_BUS, 2);
  int rc;
  sim *s = simrun(&cfg, 2, stubborn_main, NULL, &rc, err, sizeof err);
  CHECK(rc == -1 && strstr(err, "rank 0 kept calling") && strstr(err, "deadlock at"),
        "abandon: %s", err);
  CHECK(!sim_rank(s, 0)->done && sim_rank(s, 1)->done, "rank 0 should be abandoned, rank 1 done");
  sim_free(s);
}

/* ==== 10,000 ranks ======================================================== */

static void test_many_ranks(void) {
  char err[512];
  enum { N = 10000 };
  sim_config cfg = simrun_config(SIM_NET_BUS, N);
  simrun_ring g = {1, 1, 8, 0, 0};
  int rc;
  sim *s = simrun(&cfg, N, simrun_ring_main, &g, &rc, err, sizeof err);
  CHECK(rc == 0 && !g.bad, "10,000 ranks: %s", err);
  CHECK(g.token == N, "10,000 ranks: token %lld", g.token);
  double want = N * (g.work * cfg.c + cfg.m + 8 * cfg.per_byte);
  CHECK(sim_stats_get(s)->makespan == want, "10,000 ranks: makespan %.17g, expected %.17g",
        sim_stats_get(s)->makespan, want);
  sim_free(s);

  /* Many ranks on few processors, with small stacks. */
  cfg = simrun_config(SIM_NET_LOGGP, 7);
  cfg.stack = 32 * 1024;
  g = (simrun_ring){2, 1, 8, 0, 0};
  s = simrun(&cfg, 3000, simrun_ring_main, &g, &rc, err, sizeof err);
  CHECK(rc == 0 && !g.bad && g.token == 6000, "3,000 ranks on 7 processors: %s", err);
  sim_free(s);
}

/* ==== random matching programs (tests/randprog.c) ======================== */

static void test_random(void) {
  char err[512];
  int runs = 0, failed_runs = 0;
  for (uint64_t seed = 1; seed <= 240; seed++) {
    rng r;
    rng_seed(&r, seed);
    static randprog p;
    int nranks = randprog_draw(&p, seed, &r);
    sim_config cfg = simrun_config(nets[seed % 3], rng_int(&r, 1, nranks));
    int place[RANDPROG_RANKS];
    for (int k = 0; k < nranks; k++) place[k] = rng_int(&r, 0, cfg.procs - 1);
    cfg.place = place;
    cfg.c = randprog_cost(&r), cfg.m = randprog_cost(&r), cfg.per_byte = randprog_cost(&r) / 64;
    cfg.local = randprog_cost(&r) / 4, cfg.L = randprog_cost(&r), cfg.o = randprog_cost(&r) / 2;
    cfg.g = randprog_cost(&r), cfg.G = randprog_cost(&r) / 64;
    int rc;
    sim *s = simrun(&cfg, nranks, randprog_main, &p, &rc, err, sizeof err);
    runs++;
    const char *why;
    int failures = randprog_failures(&p, &why);
    const sim_stats *st = sim_stats_get(s);
    int ok = rc == 0 && !failures && st->messages == p.nmsg && st->received == p.nmsg && st->unread == 0 &&
             st->warnings == 0;
    /* The statistics add up, exactly (binary fractions). */
    long long sent = 0, recvd = 0, bsent = 0, brecvd = 0, bytags = 0;
    for (int k = 0; k < nranks; k++) {
      const sim_rank_stats *rs = sim_rank(s, k);
      sent += rs->sent, recvd += rs->received;
      bsent += rs->bytes_sent, brecvd += rs->bytes_received;
      for (int t = 0; t < SIM_TAGS; t++) bytags += rs->sent_tag[t];
      if (rs->units != p.units[k] || rs->compute != p.units[k] * cfg.c) ok = 0;
      if (rs->finish != rs->compute + rs->cpu_wait + rs->overhead + rs->recv_wait) ok = 0;
      if (rs->finish > st->makespan || !rs->done) ok = 0;
    }
    if (sent != p.nmsg || recvd != p.nmsg || bsent != brecvd || bytags != p.nmsg) ok = 0;
    if (!ok && failed_runs++ < 3)
      CHECK(0, "random seed %llu (%s, %d ranks, %d procs, %d messages): rc %d (%s), %d failures (%s), "
               "%lld/%lld/%lld sent/received/unread",
            (unsigned long long)seed, sim_net_name(cfg.net), nranks, cfg.procs, p.nmsg, rc, err, failures,
            why, st->messages, st->received, st->unread);
    sim_free(s);
  }
  CHECK(failed_runs == 0, "%d of %d random programs failed", failed_runs, runs);
}

static void test_config(void) {
  char err[512];
  sim_config cfg = simrun_config(SIM_NET_BUS, 2);
  sim *s;
  cfg.procs = 0;
  CHECK(!(s = sim_new(&cfg, 2, err, sizeof err)) && strstr(err, "0 processors"), "procs 0: %s",
        err);
  sim_free(s);
  cfg = simrun_config(SIM_NET_BUS, 2);
  cfg.m = -1;
  CHECK(!(s = sim_new(&cfg, 2, err, sizeof err)) && strstr(err, "cost m = -1"), "m < 0: %s", err);
  sim_free(s);
  cfg = simrun_config(SIM_NET_BUS, 2);
  int place[2] = {0, 2};
  cfg.place = place;
  CHECK(!(s = sim_new(&cfg, 2, err, sizeof err)) && strstr(err, "place[1] = 2"), "place: %s", err);
  sim_free(s);
  cfg = simrun_config(SIM_NET_BUS, 2);
  CHECK(!(s = sim_new(&cfg, 0, err, sizeof err)), "0 ranks accepted");
  sim_free(s);

  sim_net net;
  CHECK(sim_net_parse("loggp", &net) == 0 && net == SIM_NET_LOGGP, "parse loggp");
  CHECK(sim_net_parse("ring", &net) == -1, "parse accepted 'ring'");
  CHECK(strcmp(sim_net_name(SIM_NET_BUS), "bus") == 0, "name of bus");
  CHECK(sim_profile("tc2000", &cfg) == 0 && cfg.net == SIM_NET_BUS && cfg.c == 50e-6 &&
            cfg.m == 275e-6 && cfg.per_byte == 2.6e-8 && cfg.local == 0,
        "tc2000 profile");
  CHECK(sim_profile("unit", &cfg) == 0 && cfg.c == 1 && cfg.m == 1 && cfg.per_byte == 0, "unit profile");
  CHECK(sim_profile("nope", &cfg) == -1, "unknown profile accepted");

  /* Once per sim. */
  cfg = simrun_config(SIM_NET_BUS, 1);
  int rc;
  s = simrun(&cfg, 1, colocated_main, &(fanin){.work = 1}, &rc, err, sizeof err);
  mp_proc pr = {colocated_main, NULL};
  CHECK(rc == 0 && sim_run(s, &pr, err, sizeof err) == -1 && strstr(err, "run already"),
        "second run: %s", err);
  sim_free(s);
}

int main(void) {
  test_pingpong();
  test_ring();
  test_bus_spacing();
  test_colocated();
  test_recv_frees_cpu();
  test_loggp();
  test_order();
  test_determinism();
  test_trace_exact();
  test_deadlock();
  test_abandon();
  test_many_ranks();
  test_random();
  test_config();
  return check_done("test_sim");
}
