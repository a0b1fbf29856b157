/* test_threads.c -- the threads backend (mp/threads.h) against mp.h's
 * contract: ping-pong, any-source, FIFO per pair, tags, causal order of
 * receives from any source, long messages across chunks, truncation, bad
 * ranks and arguments, deadlock detection and its report, unread messages,
 * many ranks, random matching programs delivering every message exactly
 * once; then the paper's parallel algorithm on threads, equal to the serial
 * solver bit for bit for P = 1..16 on random pairs and on a real stack. */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "tests/randprog.h"
#include "input/contour.h"
#include "input/gen.h"
#include "util/rng.h"
#include "tests/parmachine.h"
#include "mp/threads.h"
#include "algo/tiling.h"
#include "util/xmem.h"

/* Run n ranks of one main with one user pointer; returns the machine (free
 * it) and mpt_run's status in *rc. */
static mpt *run(int n, long spin_ns, mp_main main, void *ud, int *rc, char *err, size_t errlen) {
  mpt_config cfg;
  mpt_config_init(&cfg);
  cfg.warn = NULL;
  cfg.spin_ns = spin_ns;
  mpt *t = mpt_new(&cfg, n, err, errlen);
  XASSERT(t);
  mp_proc *procs = xmallocarray((size_t)n, sizeof *procs);
  for (int i = 0; i < n; i++) procs[i] = (mp_proc){main, ud};
  err[0] = 0;
  *rc = mpt_run(t, procs, err, errlen);
  free(procs);
  return t;
}

/* ==== ping-pong, any-source, FIFO, tags ================================== */

typedef struct {
  int rounds;
  _Atomic int bad;
} pingpong;

static void pingpong_main(mp *self, void *ud) {
  pingpong *p = ud;
  int me = mp_rank(self), peer = 1 - me;
  if (me > 1) return;
  for (int i = 0; i < p->rounds; i++) {
    int v = i * 2 + me, got = -1;
    mp_status st;
    if (me == 0) {
      if (mp_send(self, peer, 7, &v, sizeof v) != MP_OK) p->bad++;
      if (mp_recv(self, peer, 7, &got, sizeof got, &st) != MP_OK || got != i * 2 + 1) p->bad++;
    } else {
      if (mp_recv(self, peer, 7, &got, sizeof got, &st) != MP_OK || got != i * 2) p->bad++;
      if (st.source != 0 || st.tag != 7 || st.len != sizeof got) p->bad++;
      if (mp_send(self, peer, 7, &v, sizeof v) != MP_OK) p->bad++;
    }
  }
}

static void test_pingpong(void) {
  char err[512];
  int rc;
  for (long spin = 0; spin <= 200000; spin += 200000) {   /* sleep at once, and spin first */
    pingpong p = {2000, 0};
    mpt *t = run(2, spin, pingpong_main, &p, &rc, err, sizeof err);
    const mpt_stats *st = mpt_stats_get(t);
    CHECK(rc == 0 && p.bad == 0, "ping-pong (spin %ld ns): rc %d (%s), %d bad", spin, rc, err, p.bad);
    CHECK(st->messages == 4000 && st->received == 4000 && st->unread == 0 && st->bytes == 16000,
          "ping-pong statistics: %lld sent, %lld received", st->messages, st->received);
    CHECK(mpt_rank(t, 0)->done && mpt_rank(t, 1)->done && st->wall_s > 0, "ping-pong: done, wall time");
    if (spin == 0) CHECK(st->sleeps > 0, "spin 0: recvs should sleep (%lld)", st->sleeps);
    mpt_free(t);
  }
}

enum { FIFO_SENDERS = 7, FIFO_MSGS = 400 };

typedef struct {
  _Atomic int bad;
  int got[FIFO_SENDERS + 1];
  int tagged;   /* messages taken by tag first */
} fifo;

/* Ranks 1..7 each send 400 numbered messages to rank 0, tags alternating 1
 * and 2.  Rank 0 first takes 50 tag-2 messages from rank 3 (in order,
 * passing over the tag-1 ones), then everything else from any source with
 * any tag, and checks each sender's order. */
static void fifo_main(mp *self, void *ud) {
  fifo *f = ud;
  int me = mp_rank(self);
  if (me > 0) {
    for (int i = 0; i < FIFO_MSGS; i++) {
      int v[2] = {me, i};
      if (mp_send(self, 0, 1 + (i & 1), v, sizeof v) != MP_OK) f->bad++;
    }
    return;
  }
  int next[FIFO_SENDERS + 1] = {0}, v[2];
  mp_status st;
  for (int k = 0; k < 50; k++) {   /* rank 3's odd-numbered messages (tag 2), in order */
    if (mp_recv(self, 3, 2, v, sizeof v, &st) != MP_OK || v[0] != 3 || v[1] != 2 * k + 1 || st.tag != 2)
      f->bad++;
    f->tagged++;
  }
  int taken3[FIFO_MSGS] = {0};
  for (int k = 0; k < 50; k++) taken3[2 * k + 1] = 1;
  for (int k = 0; k < FIFO_SENDERS * FIFO_MSGS - 50; k++) {
    if (mp_recv(self, MP_ANY, MP_ANY, v, sizeof v, &st) != MP_OK) {
      f->bad++;
      return;
    }
    int s = v[0];
    if (s < 1 || s > FIFO_SENDERS || st.source != s || st.len != sizeof v) {
      f->bad++;
      continue;
    }
    if (s == 3)
      while (next[3] < FIFO_MSGS && taken3[next[3]]) next[3]++;
    if (v[1] != next[s]) f->bad++;   /* per-pair FIFO */
    if (st.tag != 1 + (v[1] & 1)) f->bad++;
    next[s] = v[1] + 1;
    f->got[s]++;
  }
}

static void test_fifo(void) {
  char err[512];
  int rc;
  fifo f;
  memset(&f, 0, sizeof f);
  mpt *t = run(FIFO_SENDERS + 1, 200000, fifo_main, &f, &rc, err, sizeof err);
  int all = 1;
  for (int s = 1; s <= FIFO_SENDERS; s++) all &= f.got[s] == (s == 3 ? FIFO_MSGS - 50 : FIFO_MSGS);
  CHECK(rc == 0 && f.bad == 0 && all && f.tagged == 50, "any-source / FIFO / tags: rc %d (%s), %d bad", rc,
        err, f.bad);
  CHECK(mpt_stats_get(t)->unread == 0, "FIFO: unread messages");
  mpt_free(t);
}

/* ==== causal order of receives from any source =========================== */

enum { CAUSAL_ROUNDS = 300 };

typedef struct {
  _Atomic int bad;   /* added to by every rank at once */
  int violations;
} causal;

/* Ranks 0, 1, 2; each round the roles rotate (and so which channel a scan
 * of 0's channels in index order meets first): the first sender F sends
 * "first" to the receiver R, then a token to the relay M; M receives it and
 * sends "second" to R.  R waits (by probe) until "second" is there; then
 * "first" was sent before it in happens-before order, and a receive from
 * any source must take it first, whichever channel it sits in. */
static void causal_main(mp *self, void *ud) {
  causal *c = ud;
  int me = mp_rank(self);
  for (int i = 0; i < CAUSAL_ROUNDS; i++) {
    int rot = i % 6, R = rot % 3, F = (R + 1 + rot / 3) % 3, M = 3 - R - F;
    int v = i;
    if (me == F) {
      c->bad += mp_send(self, R, 1, &v, sizeof v) != MP_OK;
      c->bad += mp_send(self, M, 2, &v, sizeof v) != MP_OK;
    } else if (me == M) {
      c->bad += mp_recv(self, F, 2, &v, sizeof v, NULL) != MP_OK || v != i;
      c->bad += mp_send(self, R, 3, &v, sizeof v) != MP_OK;
    } else {
      mp_status st;
      while (mp_probe(self, M, 3, NULL) == 0) {
      }
      c->bad += mp_recv(self, MP_ANY, MP_ANY, &v, sizeof v, &st) != MP_OK;
      c->violations += st.source != F || st.tag != 1 || v != i;
      /* (F's next message, a barrier below, races with "second": by tag.) */
      c->bad += mp_recv(self, M, 3, &v, sizeof v, &st) != MP_OK || v != i;
    }
    /* All three in step before the next round. */
    int x = 0;
    for (int r = 0; r < 3; r++)
      if (r != me) c->bad += mp_send(self, r, 9, &x, sizeof x) != MP_OK;
    for (int r = 0; r < 3; r++)
      if (r != me) c->bad += mp_recv(self, r, 9, &x, sizeof x, NULL) != MP_OK;
  }
}

static void test_causal(void) {
  char err[512];
  int rc;
  causal c;
  atomic_init(&c.bad, 0);
  c.violations = 0;
  mpt *t = run(3, 200000, causal_main, &c, &rc, err, sizeof err);
  int bad = atomic_load(&c.bad);
  CHECK(rc == 0 && bad == 0, "causal order: rc %d (%s), %d bad", rc, err, bad);
  CHECK(c.violations == 0, "causal order: a receive from any source took a message before one sent "
                           "earlier in happens-before order, %d times of %d", c.violations, CAUSAL_ROUNDS);
  CHECK(mpt_stats_get(t)->unread == 0, "causal order: unread messages");
  mpt_free(t);
}

/* ==== channels: chunks, long messages, taking out of order =============== */

enum { CH_MSGS = 3000 };

typedef struct {
  _Atomic int bad;   /* added to by both ranks at once */
  int got;
} chanstress;

static size_t ch_len(int i) { return (size_t)(i * 37 % 2500); }   /* 0 .. 2499 bytes: both kinds */

static void chan_main(mp *self, void *ud) {
  chanstress *c = ud;
  unsigned char *buf = xmalloc(4096);
  if (mp_rank(self) == 1) {
    for (int i = 0; i < CH_MSGS; i++) {
      size_t len = ch_len(i);
      for (size_t k = 0; k < len; k++) buf[k] = (unsigned char)(i + k);
      c->bad += mp_send(self, 0, i % 3, buf, len) != MP_OK;
    }
    /* Never received: a long and a short one (freed with the machine). */
    c->bad += mp_send(self, 0, 7, buf, 3000) != MP_OK;
    c->bad += mp_send(self, 0, 7, buf, 8) != MP_OK;
  } else {
    /* Tag 2 first (passing over tags 0 and 1 across many chunks), then
     * tag 0, then whatever comes: each in send order, intact. */
    for (int pass = 0; pass < 3; pass++) {
      int tag = pass == 0 ? 2 : pass == 1 ? 0 : 1;
      for (int i = tag; i < CH_MSGS; i += 3) {
        mp_status st;
        int rc = mp_recv(self, pass == 2 ? MP_ANY : 1, pass == 2 ? MP_ANY : tag, buf, 4096, &st);
        size_t len = ch_len(i);
        int ok = rc == MP_OK && st.tag == tag && st.len == len && st.source == 1;
        for (size_t k = 0; ok && k < len; k++) ok = buf[k] == (unsigned char)(i + k);
        c->bad += !ok;
        c->got++;
      }
    }
  }
  free(buf);
}

static void test_channels(void) {
  char err[512];
  int rc;
  chanstress c = {0, 0};
  mpt *t = run(2, 200000, chan_main, &c, &rc, err, sizeof err);
  const mpt_stats *st = mpt_stats_get(t);
  CHECK(rc == 0 && c.bad == 0 && c.got == CH_MSGS, "channels: rc %d (%s), %d bad, %d received", rc, err,
        c.bad, c.got);
  CHECK(st->unread == 2 && st->received == CH_MSGS && st->warnings == 1, "channels: %lld unread, %lld warnings",
        st->unread, st->warnings);
  mpt_free(t);
}

/* ==== probe, truncation, unread ========================================== */

typedef struct {
  int rc[12];
  mp_status st[4];
  unsigned char buf[16];
} probes;

static void probe_main(mp *self, void *ud) {
  probes *p = ud;
  if (mp_rank(self) == 1) {
    unsigned char big[100];
    for (int i = 0; i < 100; i++) big[i] = (unsigned char)i;
    mp_send(self, 0, 5, big, sizeof big);
    int one = 1;
    mp_send(self, 0, 6, &one, sizeof one);
    mp_send(self, 0, 9, &one, sizeof one);   /* never received */
    mp_send(self, 0, 9, &one, sizeof one);   /* never received */
    mp_send(self, 0, 4, NULL, 0);            /* the go signal, last */
    return;
  }
  /* Wait for everything to be there (the go signal is sent last). */
  while (mp_probe(self, 1, 4, NULL) == 0) {
  }
  p->rc[0] = mp_probe(self, MP_ANY, 6, &p->st[0]);
  p->rc[1] = mp_probe(self, 1, 7, &p->st[1]);   /* no such tag */
  p->rc[2] = mp_recv(self, 1, 5, p->buf, 10, &p->st[2]);   /* truncated */
  int x = 0;
  p->rc[3] = mp_recv(self, MP_ANY, MP_ANY, &x, sizeof x, &p->st[3]);   /* the next: tag 6 */
  p->rc[4] = x;
  p->rc[5] = mp_recv(self, 1, 4, NULL, 0, NULL);
}

static void test_probe_trunc_unread(void) {
  char err[512];
  int rc;
  probes p;
  memset(&p, 0, sizeof p);
  mpt *t = run(2, 200000, probe_main, &p, &rc, err, sizeof err);
  const mpt_stats *st = mpt_stats_get(t);
  CHECK(rc == 0, "probe run: %s", err);
  CHECK(p.rc[0] == 1 && p.st[0].source == 1 && p.st[0].tag == 6 && p.st[0].len == 4, "probe found %d", p.rc[0]);
  CHECK(p.rc[1] == 0, "probe of an absent tag: %d", p.rc[1]);
  int pattern = 1;
  for (int i = 0; i < 10; i++) pattern &= p.buf[i] == i;
  CHECK(p.rc[2] == MP_ETRUNC && p.st[2].len == 100 && pattern && p.buf[10] == 0,
        "truncation: rc %d, len %zu", p.rc[2], p.st[2].len);
  CHECK(p.rc[3] == MP_OK && p.st[3].tag == 6 && p.rc[4] == 1, "the truncated message was consumed: tag %d",
        p.st[3].tag);
  CHECK(p.rc[5] == MP_OK, "empty message: %d", p.rc[5]);
  CHECK(st->unread == 2 && mpt_rank(t, 0)->unread == 2 && st->warnings == 2,
        "unread: %lld (expected 2), warnings %lld (truncation + unread)", st->unread, st->warnings);
  mpt_free(t);
}

/* ==== bad arguments ======================================================= */

typedef struct {
  int rc[10];
} badargs;

static void bad_main(mp *self, void *ud) {
  badargs *b = ud;
  if (mp_rank(self) != 0) return;
  int x = 0;
  b->rc[0] = mp_send(self, 3, 0, &x, sizeof x);
  b->rc[1] = mp_send(self, -1, 0, &x, sizeof x);
  b->rc[2] = mp_send(self, 1, -2, &x, sizeof x);
  b->rc[3] = mp_recv(self, 5, 0, &x, sizeof x, NULL);
  b->rc[4] = mp_probe(self, 1, -7, NULL);
  b->rc[5] = mp_compute(self, -1);
  b->rc[6] = mp_compute(self, NAN);
  b->rc[7] = mp_compute(self, INFINITY);
  b->rc[8] = mp_compute(self, 12.5);
  b->rc[9] = mp_send(self, 1, 0, NULL, 4);
}

static void test_bad_args(void) {
  char err[512];
  int rc;
  badargs b;
  memset(&b, 0, sizeof b);
  mpt *t = run(2, 200000, bad_main, &b, &rc, err, sizeof err);
  CHECK(rc == -1, "bad arguments: the run should fail (rc %d)", rc);
  CHECK(b.rc[0] == MP_ERANK && b.rc[1] == MP_ERANK && b.rc[2] == MP_EARG && b.rc[3] == MP_ERANK &&
            b.rc[4] == MP_EARG && b.rc[5] == MP_EARG && b.rc[6] == MP_EARG && b.rc[7] == MP_EARG &&
            b.rc[8] == MP_OK && b.rc[9] == MP_EARG,
        "codes %d %d %d %d %d %d %d %d %d %d", b.rc[0], b.rc[1], b.rc[2], b.rc[3], b.rc[4], b.rc[5],
        b.rc[6], b.rc[7], b.rc[8], b.rc[9]);
  CHECK(strstr(err, "rank 0: mp_send to rank 3, which does not exist (2 ranks)") != NULL,
        "the error names the rank: %s", err);
  CHECK(strstr(err, "(9 errors in all)") != NULL && mpt_stats_get(t)->errors == 9, "error count: %s", err);
  CHECK(mpt_stats_get(t)->deadlock == 0, "no deadlock");
  mpt_free(t);
}

/* ==== deadlock ============================================================ */

typedef struct {
  int rc[8][3];
  int early;   /* rank 0 returns at once */
} dead;

static void dead_main(mp *self, void *ud) {
  dead *d = ud;
  int me = mp_rank(self), n = mp_size(self), x = 0;
  if (d->early && me == 0) return;
  if (me == 1) mp_send(self, 2, 8, &x, sizeof x);   /* rank 2 waits for tag 3: unmatched */
  d->rc[me][0] = mp_recv(self, me == 2 ? MP_ANY : (me + 1) % n, me == 2 ? 3 : MP_ANY, &x, sizeof x, NULL);
  d->rc[me][1] = mp_send(self, 0, 1, &x, sizeof x);
  d->rc[me][2] = mp_recv(self, MP_ANY, MP_ANY, &x, sizeof x, NULL);
}

static void test_deadlock(void) {
  char err[1024];
  int rc;
  for (int early = 0; early <= 1; early++) {
    for (long spin = 0; spin <= 100000; spin += 100000) {
      dead d;
      memset(&d, 0, sizeof d);
      d.early = early;
      mpt *t = run(4, spin, dead_main, &d, &rc, err, sizeof err);
      int ok = 1;
      for (int r = early; r < 4; r++)
        ok &= d.rc[r][0] == MP_EDEADLOCK && d.rc[r][1] == MP_ESTOPPED && d.rc[r][2] == MP_ESTOPPED;
      CHECK(rc == -1 && ok && mpt_stats_get(t)->deadlock == 1,
            "deadlock (early %d, spin %ld): rc %d, codes %d %d %d: %s", early, spin, rc, d.rc[1][0],
            d.rc[1][1], d.rc[1][2], err);
      CHECK(strstr(err, "deadlock after") && strstr(err, "rank 1 waits in recv(src=2, tag=any)") &&
                strstr(err, "rank 2 waits in recv(src=any, tag=3)") &&
                (early || strstr(err, "rank 0 waits in recv(src=1, tag=any)")),
            "deadlock report: %s", err);
      CHECK(mpt_stats_get(t)->unread == 1, "the unmatched message is unread (%lld)",
            mpt_stats_get(t)->unread);
      mpt_free(t);
    }
  }
}

/* ==== many ranks: a token ring ============================================ */

typedef struct {
  int laps;
  _Atomic int bad;
  long long token;
} ring;

static void ring_main(mp *self, void *ud) {
  ring *g = ud;
  int me = mp_rank(self), n = mp_size(self);
  long long tok = 0;
  for (int lap = 0; lap < g->laps; lap++) {
    if (me == 0) {
      tok++;
      if (mp_send(self, 1 % n, 0, &tok, sizeof tok) != MP_OK) g->bad++;
      if (mp_recv(self, n - 1, 0, &tok, sizeof tok, NULL) != MP_OK) g->bad++;
    } else {
      if (mp_recv(self, me - 1, 0, &tok, sizeof tok, NULL) != MP_OK) g->bad++;
      tok++;
      if (mp_send(self, (me + 1) % n, 0, &tok, sizeof tok) != MP_OK) g->bad++;
    }
  }
  if (me == 0) g->token = tok;
}

static void test_many(void) {
  char err[512];
  int rc;
  ring g = {5, 0, 0};
  mpt *t = run(200, 20000, ring_main, &g, &rc, err, sizeof err);
  CHECK(rc == 0 && g.bad == 0 && g.token == 1000, "200 ranks, 5 laps: rc %d (%s), token %lld", rc, err,
        g.token);
  mpt_free(t);
}

/* ==== random matching programs (tests/randprog.c) ======================== */

static void test_random(void) {
  char err[512];
  int failed = 0, runs = 0;
  for (uint64_t seed = 1; seed <= 60; seed++) {
    rng r;
    rng_seed(&r, seed);
    static randprog p;
    int n = randprog_draw(&p, seed, &r);
    int rc;
    mpt *t = run(n, seed % 3 == 0 ? 0 : 50000, randprog_main, &p, &rc, err, sizeof err);
    const mpt_stats *st = mpt_stats_get(t);
    const char *why;
    int failures = randprog_failures(&p, &why);
    long long bs = 0, br = 0;
    for (int k = 0; k < n; k++) bs += mpt_rank(t, k)->bytes_sent, br += mpt_rank(t, k)->bytes_received;
    runs++;
    if (!(rc == 0 && !failures && st->messages == p.nmsg && st->received == p.nmsg && st->unread == 0 &&
          bs == br) &&
        failed++ < 3)
      CHECK(0, "random seed %llu (%d ranks, %d messages): rc %d (%s), %d failures (%s)",
            (unsigned long long)seed, n, p.nmsg, rc, err, failures, why);
    mpt_free(t);
  }
  CHECK(failed == 0, "%d of %d random programs failed", failed, runs);
}

/* ==== the parallel algorithm on threads =================================== */

static int same_tiling(const tiling *a, const tiling *b) {
  return a->quanta == b->quanta && a->start == b->start && a->m == b->m && a->n == b->n &&
         a->transposed == b->transposed &&
         memcmp(a->col, b->col, sizeof *a->col * (size_t)(a->m + a->n + 1)) == 0;
}

static par_machine config(int P, split_alloc alloc, int d) {
  par_machine rc;
  par_machine_init(&rc);
  rc.mc.backend = MACHINE_THREADS;
  rc.mc.procs = P;
  rc.mc.sim.warn = NULL;
  rc.mc.threads.warn = NULL;
  rc.pc.opt.alloc = alloc;
  rc.pc.opt.min_diag = d;
  return rc;
}

static par_pair mkpair(const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq) {
  par_pair pr;
  memset(&pr, 0, sizeof pr);
  pr.P = P, pr.np = np, pr.zp = zp, pr.Q = Q, pr.nq = nq, pr.zq = zq;
  return pr;
}

/* Three dozen random pairs, each at several P in 1..16, both allocations,
 * d in {1, 20}; every P from 1 to 16 at least twice. */
static void test_par_random(rng *g) {
  vec2 *P = xmallocarray(120, sizeof *P), *Q = xmallocarray(120, sizeof *Q);
  int bad = 0, failed = 0, runs = 0, seen[17] = {0};
  for (int pair = 0; pair < 36; pair++) {
    int np = rng_int(g, 3, pair % 6 == 5 ? 120 : 50);
    int nq = rng_int(g, 3, 60);
    gen_star(g, P, np, 0, 0, 10, 0.4);
    double cx = rng_uniform(g) * 3;
    double cy = rng_uniform(g) * 3;
    double r = 6 + 6 * rng_uniform(g);
    gen_star(g, Q, nq, cx, cy, r, 0.4);
    tiling ser;
    tiling_solve(P, np, 0, Q, nq, 2, COST_AREA, -1, &ser);
    for (int i = 0; i < 3; i++) {
      int procs = 1 + (pair * 3 + i) % 16, alloc = (pair + i) % 2, d = pair % 4 == 3 ? 20 : 1;
      seen[procs]++;
      par_machine rc = config(procs, (split_alloc)alloc, d);
      par_pair pr = mkpair(P, np, 0, Q, nq, 2);
      char err[300];
      runs++;
      if (par_machine_run(&rc, &pr, 1, err, sizeof err) != 0) {
        if (failed++ < 3) CHECK(0, "pair %d P=%d: %s", pair, procs, err);
        continue;
      }
      if (!same_tiling(&pr.t, &ser) || pr.counts.nodes != ser.count.nodes) {
        if (bad++ < 3)
          CHECK(0, "pair %d (m=%d n=%d) P=%d: threads %.17g start %d, serial %.17g start %d", pair, np, nq,
                procs, pr.t.quanta, pr.t.start, ser.quanta, ser.start);
      }
      CHECK(pr.time > 0, "pair %d P=%d: no time", pair, procs);
      tiling_free(&pr.t);
    }
    tiling_free(&ser);
  }
  int all = 1;
  for (int p = 1; p <= 16; p++) all &= seen[p] >= 2;
  CHECK(all, "every P from 1 to 16 at least twice");
  CHECK(bad == 0 && failed == 0, "%d of %d threaded runs differ from the serial solver, %d failed", bad,
        runs, failed);
  free(P);
  free(Q);
}

/* A real stack, every pair in one run, at P = 3 and 16. */
static void test_par_real(void) {
  char err[300];
  contour_stack s;
  if (contour_read("tests/data/slicerrt/prostate_2.contours", &s, NULL, "test", err, sizeof err) != 0) {
    CHECK(0, "%s", err);
    return;
  }
  static const int procs[] = {3, 16};
  for (int c = 0; c < 2; c++) {
    int np = s.n - 1;
    par_pair *pr = xcalloc((size_t)np, sizeof *pr);
    for (int k = 0; k < np; k++)
      pr[k] = mkpair(s.c[k].pt, s.c[k].n, s.c[k].z, s.c[k + 1].pt, s.c[k + 1].n, s.c[k + 1].z);
    par_machine rc = config(procs[c], c ? ALLOC_SIZE : ALLOC_HALF, 1);
    mpt_stats st;
    int rcode = par_machine_threads(&rc, pr, np, &st, err, sizeof err);
    CHECK(rcode == 0, "prostate_2 P=%d: %s", procs[c], err);
    int bad = 0;
    for (int k = 0; rcode == 0 && k < np; k++) {
      tiling ser;
      tiling_solve(pr[k].P, pr[k].np, pr[k].zp, pr[k].Q, pr[k].nq, pr[k].zq, COST_AREA, -1, &ser);
      bad += !same_tiling(&pr[k].t, &ser) || pr[k].counts.nodes != ser.count.nodes;
      tiling_free(&ser);
    }
    CHECK(bad == 0, "prostate_2 P=%d: %d of %d pairs differ from serial", procs[c], bad, np);
    CHECK(rcode != 0 || (st.unread == 0 && st.messages == st.received && st.deadlock == 0),
          "prostate_2 P=%d: messages lost", procs[c]);
    for (int k = 0; k < np; k++) tiling_free(&pr[k].t);
    free(pr);
  }
  contour_stack_free(&s);
}

int main(void) {
  test_pingpong();
  test_fifo();
  test_causal();
  test_channels();
  test_probe_trunc_unread();
  test_bad_args();
  test_deadlock();
  test_many();
  test_random();
  rng g;
  rng_seed(&g, 1993);
  test_par_random(&g);
  test_par_real();
  return check_done("test_threads");
}
