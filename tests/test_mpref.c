/* test_mpref.c -- mp.h's messages without copies (mp_send_ref, mp_settle,
 * mp_withdraw, mp_recv_msg, mp_recv_msg_into, mp_msg_read, mp_msg_gone, mp_promise_make,
 * mp_promise_drop) on the simulator and on threads, against oracles of the
 * test's own:
 *   - small fixed programs, each with what must come out: bytes, statuses,
 *     the clock of a receiver woken for a withdrawn message (closed form),
 *     a promised buffer filled before its receive (the simulator);
 *   - random matching programs where every message goes a random way (a
 *     copy or by reference, settled at once or steps later, the sender's
 *     buffer overwritten as soon as it is settled; received into a buffer,
 *     held and read later, or into a promised buffer), each payload checked
 *     against what its sender wrote, each message delivered exactly once;
 *     on the simulator the same program with mp_send and mp_recv alone must
 *     give the same statistics and the same trace, byte for byte;
 *   - the same with withdrawals: a sender takes back a message it has just
 *     sent and sends a replacement; whatever mp_withdraw answers, the
 *     withdrawn message is never received and the one not withdrawn is,
 *     once (on threads the receiver races the withdrawal).
 * TILESIM_MPREF=N runs N random programs a backend instead of 60. */
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "mp/mp.h"
#include "util/rng.h"
#include "sim/sim.h"
#include "mp/threads.h"
#include "util/xmem.h"

enum { BACK_SIM, BACK_THREADS };

/* A quiet simulator with exact costs: m = 1/4, 1/16 s a byte (ideal). */
static sim_config quiet(void) {
  sim_config cfg;
  sim_config_init(&cfg);
  cfg.procs = 8;
  cfg.net = SIM_NET_IDEAL;
  cfg.m = 0.25;
  cfg.per_byte = 0.0625;
  cfg.warn = NULL;
  return cfg;
}

/* Run n ranks of fn(ud) on a backend; 0 or the run's failure (err). */
static int run(int back, int n, mp_main fn, void *ud, char *err, size_t errlen) {
  mp_proc *pr = xmallocarray((size_t)n, sizeof *pr);
  for (int i = 0; i < n; i++) pr[i] = (mp_proc){fn, ud};
  int rc;
  if (back == BACK_SIM) {
    sim_config cfg = quiet();
    sim *s = sim_new(&cfg, n, err, errlen);
    XASSERT(s);
    rc = sim_run(s, pr, err, errlen);
    sim_free(s);
  } else {
    mpt_config cfg;
    mpt_config_init(&cfg);
    cfg.warn = NULL;
    mpt *t = mpt_new(&cfg, n, err, errlen);
    XASSERT(t);
    rc = mpt_run(t, pr, err, errlen);
    mpt_free(t);
  }
  free(pr);
  return rc;
}

static void pattern(unsigned char *b, size_t n, int seed) {
  for (size_t i = 0; i < n; i++) b[i] = (unsigned char)(seed * 131 + (int)i * 7 + 1);
}

static int is_pattern(const unsigned char *b, size_t n, int seed) {
  for (size_t i = 0; i < n; i++)
    if (b[i] != (unsigned char)(seed * 131 + (int)i * 7 + 1)) return 0;
  return 1;
}

/* ==== fixed programs ====================================================== */

typedef struct {
  int back;
  _Atomic int bad;
  char why[160];
  double t;          /* a clock the program reports */
  int flag;          /* an answer the program reports */
} fixed;

static void fail(fixed *f, const char *why) {
  if (f->bad++ == 0) snprintf(f->why, sizeof f->why, "%s", why);
}

/* s seconds of sleep on the simulator, s milliseconds on threads. */
static double nap(const fixed *f, double s) { return f->back == BACK_SIM ? s : s * 1e-3; }

enum { BIG = 5000 };

/* A send by reference settled before the receive: the receiver gets what
 * was there at the settle, though the sender then overwrites its buffer;
 * one read by the receiver before the settle gets it too. */
static void settle_main(mp *self, void *ud) {
  fixed *f = ud;
  unsigned char *b = xmalloc(BIG);
  if (mp_rank(self) == 0) {
    mp_ref *r;
    pattern(b, BIG, 1);
    if (mp_send_ref(self, 1, 3, b, BIG, &r) != MP_OK) fail(f, "send_ref 1");
    mp_settle(self, r);
    memset(b, 0xee, BIG);   /* the sender's buffer is its own again */
    pattern(b, BIG, 2);
    if (mp_send_ref(self, 1, 4, b, BIG, &r) != MP_OK) fail(f, "send_ref 2");
    mp_sleep(self, nap(f, 100));   /* the receiver reads it meanwhile (the simulator) */
    mp_settle(self, r);
    memset(b, 0xdd, BIG);
  } else if (mp_rank(self) == 1) {
    mp_status st;
    if (mp_recv(self, 0, 3, b, BIG, &st) != MP_OK || st.len != BIG || !is_pattern(b, BIG, 1))
      fail(f, "the first message, settled before its receive");
    if (mp_recv(self, 0, 4, b, BIG, &st) != MP_OK || !is_pattern(b, BIG, 2))
      fail(f, "the second message, read before its settle");
  }
  free(b);
}

/* Held messages: read later, truncated, released unread. */
static void hold_main(mp *self, void *ud) {
  fixed *f = ud;
  unsigned char b[BIG], c[BIG];
  if (mp_rank(self) == 0) {
    for (int k = 0; k < 3; k++) {
      pattern(b, BIG, 10 + k);
      mp_ref *r;
      if (k == 1) {
        if (mp_send(self, 1, k, b, 40) != MP_OK) fail(f, "send");
      } else {
        if (mp_send_ref(self, 1, k, b, BIG, &r) != MP_OK) fail(f, "send_ref");
        mp_settle(self, r);
      }
    }
  } else if (mp_rank(self) == 1) {
    mp_msg *h[3];
    mp_status st;
    for (int k = 0; k < 3; k++) {
      if (mp_recv_msg(self, 0, MP_ANY, &h[k], &st) != MP_OK || st.tag != k || st.len != (k == 1 ? 40u : BIG))
        fail(f, "recv_msg's status");
      if (mp_msg_gone(self, h[k])) fail(f, "a message gone that nobody withdrew");
    }
    memset(c, 0, sizeof c);
    if (mp_msg_read(self, h[2], c, BIG) != MP_OK || !is_pattern(c, BIG, 12)) fail(f, "read of the third");
    if (mp_msg_read(self, h[0], c, 100) != MP_ETRUNC || !is_pattern(c, 100, 10) || c[100] != (unsigned char)(12 * 131 + 700 + 1))
      fail(f, "a truncated read: the first 100 bytes, nothing beyond");
    if (mp_msg_read(self, h[1], NULL, 0) != MP_OK) fail(f, "a release unread");
  }
}

/* Promises (the simulator copies into them when the sender settles): three
 * messages from rank 0 with tag 5, settled in reverse order, land in the
 * three buffers promised for them, in order, before their receives; a
 * message of another tag is not taken by them; a receive into a promised
 * buffer of another rank's message moves out the one delivered there. */
static void promise_main(mp *self, void *ud) {
  fixed *f = ud;
  int me = mp_rank(self);
  unsigned char *b[4];
  for (int k = 0; k < 4; k++) b[k] = xcalloc(BIG, 1);
  if (me == 0) {
    mp_ref *r[3];
    mp_sleep(self, nap(f, 1));   /* after rank 1's promises */
    for (int k = 0; k < 3; k++) {
      pattern(b[k], BIG, 20 + k);
      if (mp_send_ref(self, 1, 5, b[k], BIG - k, &r[k]) != MP_OK) fail(f, "send_ref");
    }
    pattern(b[3], 100, 30);
    if (mp_send(self, 1, 6, b[3], 100) != MP_OK) fail(f, "send");
    for (int k = 2; k >= 0; k--) mp_settle(self, r[k]);
    for (int k = 0; k < 4; k++) memset(b[k], 0xee, BIG);
    pattern(b[0], BIG, 40);   /* for rank 1's second part */
    if (mp_send_ref(self, 1, 7, b[0], BIG, &r[0]) != MP_OK) fail(f, "send_ref 7");
    mp_settle(self, r[0]);
    memset(b[0], 0xee, BIG);
  } else if (me == 1) {
    mp_promise *p[3], *q6;
    for (int k = 0; k < 3; k++) p[k] = mp_promise_make(self, 0, 5, -1, b[k], BIG);
    q6 = mp_promise_make(self, 0, 6, -1, b[3], 50);   /* too small: never filled */
    mp_status st;
    if (mp_wait(self, 0, 6, &st) != MP_OK) fail(f, "wait");
    if (f->back == BACK_SIM) {
      /* Every message has arrived: those promised are in place already. */
      int early = 1;
      for (int k = 0; k < 3; k++) early &= is_pattern(b[k], BIG - (size_t)k, 20 + k);
      if (!early) fail(f, "the promised buffers were not filled at the settles");
      if (b[3][0] != 0) fail(f, "a buffer too small was filled");
    }
    for (int k = 0; k < 3; k++) {
      if (mp_recv(self, 0, 5, b[k], BIG, &st) != MP_OK || st.len != BIG - (size_t)k ||
          !is_pattern(b[k], BIG - (size_t)k, 20 + k))
        fail(f, "a promised receive");
      if (mp_promise_drop(self, p[k], 0) != 0) fail(f, "drop of a received promise");
    }
    if (mp_recv(self, 0, 6, b[3], 100, &st) != MP_OK || !is_pattern(b[3], 100, 30)) fail(f, "tag 6");
    mp_promise_drop(self, q6, 0);
    /* A promise for tag 7 into b[0]; rank 2's message received into b[0]
     * first (the promise broken): tag 7's payload must survive. */
    mp_promise *p7 = mp_promise_make(self, 0, 7, -1, b[0], BIG);
    if (mp_wait(self, 0, 7, &st) != MP_OK || mp_wait(self, 2, 8, &st) != MP_OK) fail(f, "wait 7, 8");
    if (mp_recv(self, 2, 8, b[0], BIG, &st) != MP_OK || !is_pattern(b[0], BIG, 50)) fail(f, "rank 2's message");
    if (mp_recv(self, 0, 7, b[1], BIG, &st) != MP_OK || !is_pattern(b[1], BIG, 40))
      fail(f, "a message delivered into a promised buffer another receive then used");
    mp_promise_drop(self, p7, 0);
  } else if (me == 2) {
    mp_sleep(self, nap(f, 50));
    pattern(b[0], BIG, 50);
    if (mp_send(self, 1, 8, b[0], BIG) != MP_OK) fail(f, "send 8");
  }
  for (int k = 0; k < 4; k++) free(b[k]);
}

/* keep = 1: a promise holding a delivered message stands (1), one that
 * holds none goes (0). */
static void keep_main(mp *self, void *ud) {
  fixed *f = ud;
  unsigned char *b = xcalloc(BIG, 1), *c = xcalloc(BIG, 1);
  if (mp_rank(self) == 0) {
    mp_ref *r;
    pattern(b, BIG, 60);
    mp_sleep(self, nap(f, 1));
    if (mp_send_ref(self, 1, 1, b, BIG, &r) != MP_OK) fail(f, "send_ref");
    mp_settle(self, r);
    memset(b, 0, BIG);
  } else if (mp_rank(self) == 1) {
    mp_promise *p = mp_promise_make(self, 0, 1, -1, b, BIG), *q = mp_promise_make(self, 0, 2, -1, c, BIG);
    mp_status st;
    if (mp_wait(self, 0, 1, &st) != MP_OK) fail(f, "wait");
    if (mp_promise_drop(self, q, 1) != 0) fail(f, "a promise holding nothing stands");
    int stands = mp_promise_drop(self, p, 1);
    if (f->back == BACK_SIM && stands != 1) fail(f, "a promise holding its message went");
    if (mp_recv(self, 0, 1, b, BIG, &st) != MP_OK || !is_pattern(b, BIG, 60)) fail(f, "its message");
    if (stands) mp_promise_drop(self, p, 0);
  }
  free(b);
  free(c);
}

/* Withdrawals.  A message withdrawn before anyone read it is gone; the
 * receiver blocked on it wakes and waits on for the next (its clock: the
 * next one's arrival, 5 + m + 8 per_byte = 5.75); a held message withdrawn
 * reads MP_EGONE; a message read is not withdrawn (0).  On threads the
 * receivers race the withdrawals: either answer, and the receives that go
 * with it. */
typedef struct {
  fixed f;
  int w0, v1, w2;
} wfixed;

static void withdraw_main(mp *self, void *ud) {
  wfixed *w = ud;
  fixed *f = &w->f;
  int me = mp_rank(self);
  double v = 0;
  if (me == 0) {
    mp_ref *r;
    double x = 1;
    if (mp_send_ref(self, 1, 7, &x, sizeof x, &r) != MP_OK) fail(f, "send_ref");
    w->w0 = mp_withdraw(self, r);
    if (!w->w0) mp_settle(self, r);
    mp_sleep(self, nap(f, 5));
    x = 2;
    if (mp_send(self, 1, 7, &x, sizeof x) != MP_OK) fail(f, "send");
  } else if (me == 1) {
    mp_status st;
    if (mp_recv(self, 0, 7, &v, sizeof v, &st) != MP_OK) fail(f, "recv");
    w->v1 = (int)v;
    f->t = mp_time(self);
    if (v == 1 && (mp_recv(self, 0, 7, &v, sizeof v, &st) != MP_OK || v != 2)) fail(f, "the second");
  } else if (me == 2) {
    mp_ref *r;
    double x = 3;
    if (mp_send_ref(self, 3, 1, &x, sizeof x, &r) != MP_OK) fail(f, "send_ref to 3");
    mp_sleep(self, nap(f, 10));   /* rank 3 holds it meanwhile */
    w->w2 = mp_withdraw(self, r);
    if (!w->w2) mp_settle(self, r);
    if (mp_send(self, 3, 2, &x, sizeof x) != MP_OK) fail(f, "send to 3");
  } else if (me == 3) {
    mp_msg *h;
    mp_status st;
    if (mp_recv_msg(self, 2, 1, &h, &st) != MP_OK) fail(f, "recv_msg");
    if (mp_recv(self, 2, 2, &v, sizeof v, &st) != MP_OK) fail(f, "recv 2");   /* after the withdrawal */
    f->flag = mp_msg_gone(self, h);
    int rc = mp_msg_read(self, h, &v, sizeof v);
    if (rc != (f->flag ? MP_EGONE : MP_OK) || (!f->flag && v != 3)) fail(f, "a held message's read");
  }
}

static void withdraw_case(int back) {
  wfixed w = {.f = {.back = back}};
  char err[300];
  int rc = run(back, 4, withdraw_main, &w, err, sizeof err);
  const char *b = back == BACK_SIM ? "sim" : "threads";
  CHECK(rc == 0 && w.f.bad == 0, "withdraw (%s): %s", b, rc ? err : w.f.why);
  CHECK((w.w0 == 1 && w.v1 == 2) || (w.w0 == 0 && w.v1 == 1), "withdraw (%s): withdrawn %d, received %d first", b,
        w.w0, w.v1);
  CHECK(w.w2 == w.f.flag, "withdraw (%s): a held message withdrawn %d, gone %d", b, w.w2, w.f.flag);
  if (back == BACK_SIM) {
    CHECK(w.w0 == 1 && w.f.t == 5.75, "withdraw: withdrawn %d, the receiver's clock %.17g, want 5.75", w.w0, w.f.t);
    CHECK(w.w2 == 1, "withdraw: a held message could not be withdrawn");
  }
}

static void fixed_case(int back, const char *name, int n, mp_main fn) {
  fixed f = {.back = back};
  char err[300];
  int rc = run(back, n, fn, &f, err, sizeof err);
  CHECK(rc == 0 && f.bad == 0, "%s (%s): %s", name, back == BACK_SIM ? "sim" : "threads", rc ? err : f.why);
}

/* ==== random programs ===================================================== */

enum { RP_MSGS = 200, RP_RANKS = 6, RP_LEN = 6000, RP_LAG = 4 };

typedef struct {
  int src, dst, tag, len;
  unsigned char byref;     /* sent by reference (else mp_send) */
  unsigned char lag;       /* ... settled after this many more steps of its sender */
  unsigned char how;       /* received: 0 mp_recv, 1 held and read at once, 2 held and read later,
                              3 mp_recv_msg_into (read at once where it fits, else held and read) */
  unsigned char withdraw;  /* taken back at once (the withdrawal variant) */
} rp_msg;

typedef struct {
  int n, nm, back, plain, with_withdraw;
  rp_msg m[RP_MSGS];
  int mode[RP_RANKS];        /* 0 (src, tag), 1 (any, any), 2 (src, any) */
  int promise[RP_RANKS];     /* mode 0 ranks: promise every receive's buffer */
  /* Each field written by one rank. */
  int delivered[RP_MSGS];    /* by the message's receiver */
  int replaced[RP_MSGS];     /* by the message's sender: withdrawn, a replacement sent */
  int bad[RP_RANKS];
  char why[RP_RANKS][200];
} rprog;

static void rwrong(rprog *p, int me, const char *what, int i) {
  if (!p->bad[me]++) snprintf(p->why[me], sizeof p->why[me], "rank %d: %s (message %d)", me, what, i);
}

/* A payload: its id (bytes 0-3), replacement flag (4), a pattern. */
static void rfill(unsigned char *b, int i, int repl, size_t len) {
  for (size_t j = 0; j < len; j++) b[j] = (unsigned char)(i * 37 + (int)j * 11 + repl);
  if (len >= 8) {
    memcpy(b, &i, sizeof i);
    b[4] = (unsigned char)repl;
  }
}

static int rcheck(const unsigned char *b, int i, int repl, size_t len) {
  unsigned char *want = xmalloc(len ? len : 1);
  rfill(want, i, repl, len);
  int ok = memcmp(b, want, len) == 0;
  free(want);
  return ok;
}

static void rmake(rprog *p, uint64_t seed, int back, int with_withdraw) {
  rng r;
  rng_seed(&r, seed);
  memset(p, 0, sizeof *p);
  p->back = back;
  p->with_withdraw = with_withdraw;
  p->n = rng_int(&r, 2, RP_RANKS);
  p->nm = rng_int(&r, 1, RP_MSGS);
  for (int i = 0; i < p->nm; i++) {
    rp_msg *m = &p->m[i];
    m->src = rng_int(&r, 0, p->n - 1);
    m->dst = rng_int(&r, 0, p->n - 1);
    m->tag = rng_int(&r, 0, 3);
    int k = rng_int(&r, 0, 9);
    m->len = k < 3 ? rng_int(&r, 8, 64) : k < 5 ? rng_int(&r, 65, 1100) : rng_int(&r, 1100, RP_LEN);
    m->byref = rng_int(&r, 0, 2) > 0;
    m->lag = (unsigned char)rng_int(&r, 0, RP_LAG);
    m->how = (unsigned char)rng_int(&r, 0, 3);
    m->withdraw = with_withdraw && m->byref && m->src != m->dst && rng_int(&r, 0, 3) == 0;
  }
  for (int k = 0; k < p->n; k++) {
    p->mode[k] = rng_int(&r, 0, 2);
    p->promise[k] = p->mode[k] == 0 && rng_int(&r, 0, 1);
  }
}

typedef struct {
  int id;
  mp_ref *ref;
  unsigned char *buf;
  int due;   /* the step of its sender's at which it is settled */
} pending;

typedef struct {
  mp_msg *h;
  int id;
  mp_status st;
} heldmsg;

/* Settle what is due (all: at the end), then poison and free its buffer. */
static void settle_due(mp *self, pending *pd, int *np, int step, int all) {
  for (int k = 0; k < *np;) {
    if (!all && pd[k].due > step) {
      k++;
      continue;
    }
    mp_settle(self, pd[k].ref);
    memset(pd[k].buf, 0xa5, RP_LEN);
    free(pd[k].buf);
    pd[k] = pd[--*np];
  }
}

/* A message received (id from its payload): checked. */
static void got(rprog *p, int me, int i, const mp_status *st, const unsigned char *b, size_t len) {
  int id = -1, repl = b[4];   /* every message has 8 bytes or more */
  memcpy(&id, b, sizeof id);
  if (id < 0 || id >= p->nm) {
    rwrong(p, me, "an id out of range", id);
    return;
  }
  const rp_msg *m = &p->m[id];
  if (m->dst != me || st->source != m->src || st->tag != m->tag || st->len != (size_t)m->len || len != st->len)
    rwrong(p, me, "the wrong envelope", id);
  if (p->mode[me] != 1 && id != i) rwrong(p, me, "out of order", id);
  if (!rcheck(b, id, repl, (size_t)m->len)) rwrong(p, me, "corrupted", id);
  if (repl == 0 && p->with_withdraw && m->withdraw && p->replaced[id] == 1)
    rwrong(p, me, "a withdrawn message was received", id);
  p->delivered[id]++;
}

static void rmain(mp *self, void *ud) {
  rprog *p = ud;
  int me = mp_rank(self), np = 0, nh = 0, steps = 0, nmine = 0;
  pending pd[RP_MSGS];
  heldmsg hd[RP_MSGS];
  unsigned char *rb = xmalloc(RP_LEN);
  /* Promises for every receive, in order (mode 0 ranks that promise). */
  unsigned char **pbuf = xcalloc(RP_MSGS, sizeof *pbuf);
  mp_promise **prom = xcalloc(RP_MSGS, sizeof *prom);
  int promising = p->promise[me] && !p->plain && !p->with_withdraw;
  for (int i = 0; i < p->nm && promising; i++) {
    if (p->m[i].dst != me) continue;
    pbuf[i] = xmalloc(RP_LEN);
    prom[i] = mp_promise_make(self, p->m[i].src, p->m[i].tag, -1, pbuf[i], RP_LEN);
  }
  for (int i = 0; i < p->nm; i++) {
    const rp_msg *m = &p->m[i];
    if (m->src != me && m->dst != me) continue;
    steps++;
    if (m->src == me) {
      unsigned char *b = xmalloc(RP_LEN);
      rfill(b, i, 0, (size_t)m->len);
      if (p->plain || !m->byref) {
        if (mp_send(self, m->dst, m->tag, b, (size_t)m->len) != MP_OK) rwrong(p, me, "send", i);
        memset(b, 0x5a, RP_LEN);
        free(b);
      } else {
        mp_ref *ref;
        if (mp_send_ref(self, m->dst, m->tag, b, (size_t)m->len, &ref) != MP_OK) rwrong(p, me, "send_ref", i);
        if (m->withdraw && mp_withdraw(self, ref)) {
          p->replaced[i] = 1;
          memset(b, 0x3c, RP_LEN);
          rfill(b, i, 1, (size_t)m->len);
          if (mp_send(self, m->dst, m->tag, b, (size_t)m->len) != MP_OK) rwrong(p, me, "replacement", i);
          free(b);
        } else {
          pd[np++] = (pending){i, ref, b, steps + m->lag};
        }
      }
      nmine++;
    }
    if (m->dst == me) {
      int mode = p->mode[me], src = mode == 1 ? MP_ANY : m->src, tag = mode == 0 ? m->tag : MP_ANY;
      mp_status st;
      if (prom[i]) {
        if (mp_recv(self, src, tag, pbuf[i], RP_LEN, &st) != MP_OK) rwrong(p, me, "promised recv", i);
        got(p, me, i, &st, pbuf[i], st.len);
        mp_promise_drop(self, prom[i], 0);
      } else if (p->plain || m->how == 0) {
        if (mp_recv(self, src, tag, rb, RP_LEN, &st) != MP_OK) rwrong(p, me, "recv", i);
        got(p, me, i, &st, rb, st.len);
      } else {
        for (;;) {   /* a held message withdrawn meanwhile: the next one */
          mp_msg *h;
          if (m->how == 3) {
            /* It fits when it is this step's tag and at most cap bytes (a
             * receive of any tag may take another message first): cap one
             * byte short of the message, its length, or room to spare. */
            size_t cap = i % 3 == 0 ? (size_t)m->len - 1 : i % 3 == 1 ? (size_t)m->len : RP_LEN;
            memset(rb, 0, RP_LEN);
            if (mp_recv_msg_into(self, src, tag, -1, m->tag, rb, cap, &h, &st) != MP_OK) {
              rwrong(p, me, "recv_msg_into", i);
              break;
            }
            int fits = st.tag == m->tag && st.len <= cap;
            if (fits != !h) rwrong(p, me, fits ? "recv_msg_into held a fit" : "recv_msg_into read a misfit", i);
            if (!h) {
              got(p, me, i, &st, rb, st.len);
              break;
            }
          } else if (mp_recv_msg(self, src, tag, &h, &st) != MP_OK) {
            rwrong(p, me, "recv_msg", i);
            break;
          }
          if (m->how == 2 && !p->with_withdraw) {   /* read later */
            hd[nh++] = (heldmsg){h, i, st};
            break;
          }
          memset(rb, 0, RP_LEN);
          int rc = mp_msg_read(self, h, rb, RP_LEN);
          if (rc == MP_EGONE) continue;
          if (rc != MP_OK) rwrong(p, me, "msg_read", i);
          got(p, me, i, &st, rb, st.len);
          break;
        }
      }
    }
    settle_due(self, pd, &np, steps, 0);
    if (nh && (steps % 3 == 0 || i == p->nm - 1)) {   /* read the held ones, latest first */
      while (nh) {
        heldmsg *x = &hd[--nh];
        memset(rb, 0, RP_LEN);
        if (mp_msg_read(self, x->h, rb, RP_LEN) != MP_OK) rwrong(p, me, "a late msg_read", x->id);
        got(p, me, x->id, &x->st, rb, x->st.len);
      }
    }
  }
  settle_due(self, pd, &np, steps, 1);
  while (nh) {
    heldmsg *x = &hd[--nh];
    if (mp_msg_read(self, x->h, rb, RP_LEN) != MP_OK) rwrong(p, me, "a last msg_read", x->id);
    got(p, me, x->id, &x->st, rb, x->st.len);
  }
  for (int i = 0; i < p->nm; i++) free(pbuf[i]);
  free(pbuf);
  free(prom);
  free(rb);
  (void)nmine;
}

static int rfailures(const rprog *p, const char **why) {
  int n = 0;
  *why = "";
  for (int k = 0; k < p->n; k++) {
    if (p->bad[k] && !**why) *why = p->why[k];
    n += p->bad[k];
  }
  for (int i = 0; i < p->nm; i++) {
    if (p->delivered[i] != 1) {
      if (!**why) *why = "a message not delivered exactly once";
      n++;
    }
  }
  return n;
}

/* One run on the simulator with its statistics and CSV trace. */
static int sim_traced(rprog *p, char **trace, size_t *tlen, sim_rank_stats *rs, sim_stats *st, char *err,
                      size_t errlen) {
  sim_config cfg = quiet();
  cfg.net = SIM_NET_LOGGP;
  cfg.L = 0.5;
  cfg.o = 0.125;
  cfg.g = 0.0625;
  cfg.G = 0.001953125;
  cfg.procs = 3;   /* some ranks share a processor */
  sim *s = sim_new(&cfg, p->n, err, errlen);
  XASSERT(s);
  FILE *f = open_memstream(trace, tlen);
  sim_trace(s, f, NULL);
  mp_proc pr[RP_RANKS];
  for (int i = 0; i < p->n; i++) pr[i] = (mp_proc){rmain, p};
  int rc = sim_run(s, pr, err, errlen);
  fclose(f);
  for (int i = 0; i < p->n; i++) rs[i] = *sim_rank(s, i);
  *st = *sim_stats_get(s);
  sim_free(s);
  return rc;
}

static void random_programs(int back, int count) {
  int failed = 0, withdrawn = 0;
  for (int k = 0; k < count && failed < 3; k++) {
    uint64_t seed = 7000 + (uint64_t)k;
    int ww = k % 3 == 2;
    rprog *p = xmalloc(sizeof *p);
    rmake(p, seed, back, ww);
    char err[300];
    const char *why;
    if (back == BACK_THREADS) {
      int rc = run(back, p->n, rmain, p, err, sizeof err);
      int bad = rfailures(p, &why);
      CHECK(rc == 0 && bad == 0, "threads: random program %llu: %s", (unsigned long long)seed, rc ? err : why);
      failed += rc != 0 || bad;
      for (int i = 0; i < p->nm; i++) withdrawn += p->replaced[i];
      free(p);
      continue;
    }
    /* The simulator: the copy-free run, then the same program plain. */
    char *t1 = NULL, *t2 = NULL;
    size_t l1 = 0, l2 = 0;
    sim_rank_stats r1[RP_RANKS], r2[RP_RANKS];
    sim_stats s1, s2;
    int rc = sim_traced(p, &t1, &l1, r1, &s1, err, sizeof err);
    int bad = rfailures(p, &why);
    CHECK(rc == 0 && bad == 0, "sim: random program %llu: %s", (unsigned long long)seed, rc ? err : why);
    failed += rc != 0 || bad;
    for (int i = 0; i < p->nm; i++) withdrawn += p->replaced[i];
    if (!ww) {
      rprog *q = xmalloc(sizeof *q);
      rmake(q, seed, back, 0);
      q->plain = 1;
      rc = sim_traced(q, &t2, &l2, r2, &s2, err, sizeof err);
      int same = rc == 0 && l1 == l2 && memcmp(t1, t2, l1) == 0 && s1.makespan == s2.makespan &&
                 s1.messages == s2.messages && s1.received == s2.received && s1.bytes == s2.bytes &&
                 s1.events == s2.events && s1.unread == s2.unread;
      for (int i = 0; i < p->n && same; i++)
        same = r1[i].finish == r2[i].finish && r1[i].recv_wait == r2[i].recv_wait &&
               r1[i].overhead == r2[i].overhead && r1[i].cpu_wait == r2[i].cpu_wait &&
               r1[i].received == r2[i].received && r1[i].bytes_received == r2[i].bytes_received;
      CHECK(same, "sim: random program %llu: the copy-free run's times, statistics or trace differ from mp_send "
                  "and mp_recv's",
            (unsigned long long)seed);
      failed += !same;
      free(q);
    }
    free(t1);
    free(t2);
    free(p);
  }
  if (back == BACK_SIM) CHECK(withdrawn > 0, "sim: no message was ever withdrawn in the random programs");
}

int main(void) {
  const char *env = getenv("TILESIM_MPREF");
  int count = env ? atoi(env) : 60;
  for (int back = BACK_SIM; back <= BACK_THREADS; back++) {
    fixed_case(back, "settle", 2, settle_main);
    fixed_case(back, "hold", 2, hold_main);
    fixed_case(back, "promise", 3, promise_main);
    fixed_case(back, "keep", 2, keep_main);
    withdraw_case(back);
    random_programs(back, count);
  }
  return check_done("test_mpref");
}
