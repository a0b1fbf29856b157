/* mailbox.c -- the simulator's messages, mailboxes and promises
 * (mailbox.h).
 *
 * When a message certainly goes to a promise.  A promise P of rank d names
 * a source s: the first message from s that fits P, among those d has not
 * received, is to land in P's buffer.  Messages from one source are
 * received in send order, and each takes the first promise it fits that no
 * message has taken; so a message m from s certainly goes to P when
 *   - P is the first promise of d, in the order made, that m fits and that
 *     is left open once each earlier message from s still in d's mailbox
 *     (not yet delivered into a promise) has taken the first open one it
 *     fits;
 *   - m fits P's buffer, and that buffer overlaps none holding another
 *     source's delivered message (two sources' receives into one buffer
 *     would otherwise end in the order of the senders' settles rather than
 *     of the receives).
 * Then the payload is copied into P's buffer now, and the receive that
 * takes m copies nothing.  Nothing but the host's copying changes: the
 * message stays in the mailbox with its times and envelope, and is
 * received when and where it would have been. */
#define _DEFAULT_SOURCE   /* madvise's MADV_HUGEPAGE, where there is one */
#include "sim/mailbox.h"

#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "util/bigcopy.h"
#include "util/xmem.h"

enum {
  POOL_MIN_CLASS = 7,              /* the smallest pooled block: 128 bytes */
  POOL_HUGE_CLASS = 21,            /* blocks of 2 MiB and more: on huge pages */
  POOL_CACHE_MAX = 64 << 20        /* bytes of free blocks kept for reuse */
};

/* ==== the payload pool ===================================================== */

static int size_class(size_t len) {
  int k = POOL_MIN_CLASS;
  while (((size_t)1 << k) < len) k++;
  return k;
}

/* A new block of 2^k bytes.  From 2 MiB on, aligned to 2 MiB and advised
 * onto huge pages where the system has them: a 4 MiB payload then costs two
 * page faults instead of 1024. */
static void *block_new(int k) {
  size_t n = (size_t)1 << k;
#ifdef MADV_HUGEPAGE
  if (k >= POOL_HUGE_CLASS) {
    void *p = NULL;
    if (posix_memalign(&p, (size_t)1 << POOL_HUGE_CLASS, n) != 0) xpanic("out of memory for a message of %zu bytes", n);
    madvise(p, n, MADV_HUGEPAGE);   /* advice: nothing is lost where it is refused */
    return p;
  }
#endif
  return xmalloc(n);
}

static void *pool_get(mstore *st, size_t len) {
  int k = size_class(len);
  XASSERT(k < POOL_CLASSES);
  void *p = st->blocks[k];
  if (!p) return block_new(k);
  memcpy(&st->blocks[k], p, sizeof(void *));
  st->cached -= (size_t)1 << k;
  return p;
}

static void pool_put(mstore *st, void *p, size_t len) {
  int k = size_class(len);
  if (st->cached + ((size_t)1 << k) > POOL_CACHE_MAX) {
    free(p);
    return;
  }
  memcpy(p, &st->blocks[k], sizeof(void *));
  st->blocks[k] = p;
  st->cached += (size_t)1 << k;
}

void mstore_free(mstore *st) {
  mstore_sweep(st);
  while (st->free) {
    msg *m = st->free;
    st->free = m->next;
    free(m);
  }
  for (int k = 0; k < POOL_CLASSES; k++) {
    while (st->blocks[k]) {
      void *p = st->blocks[k];
      memcpy(&st->blocks[k], p, sizeof(void *));
      free(p);
    }
  }
  st->cached = 0;
  while (st->pfree) {
    promise *p = st->pfree;
    st->pfree = p->next;
    free(p);
  }
}

/* ==== messages ============================================================= */

msg *msg_alloc(mstore *st) {
  (void)st;
  return xmalloc(sizeof(msg));
}

/* m's payload into memory of the message's own (inline or pooled). */
static void own_payload(mstore *st, msg *m, const void *from) {
  if (m->len <= MSG_INLINE) {
    m->data = m->inl;
    m->where = P_INLINE;
  } else {
    m->data = pool_get(st, m->len);
    m->where = P_POOL;
    st->pooled += (long long)m->len;
  }
  bigcopy(m->data, from, m->len);
}

/* m (out of its mailbox) is on the live list until both sides are done. */
static void live_add(mstore *st, msg *m) {
  m->prev = NULL;
  m->next = st->live;
  if (st->live) st->live->prev = m;
  st->live = m;
}

static void live_remove(mstore *st, msg *m) {
  DLIST_UNLINK_HEAD(st->live, m);
}

/* Both sides are done with m: its memory goes back. */
static void msg_end(mstore *st, msg *m) {
  if (m->where == P_POOL) pool_put(st, m->data, m->len);
  m->next = st->free;
  st->free = m;
}

msg *msg_new_ref(mstore *st, mbox *b, const void *buf, size_t len) {
  msg *m = msg_new(st, b, len);
  m->data = (unsigned char *)buf;
  m->where = P_SENDER;
  m->ref = 1;
  return m;
}

/* ==== promises ============================================================= */

static inline int fits(const promise *p, const msg *m) {
  return p->src == m->src && (m->tag & p->mask) == p->tag;
}

static inline int overlap(const unsigned char *a, size_t na, const unsigned char *b, size_t nb) {
  return na && nb && a < b + nb && b < a + na;
}

/* The first promise of b that x fits, open (no message delivered or
 * received) and not marked, or NULL. */
static promise *first_open(const mbox *b, const msg *x) {
  promise *p = b->phead;
  while (p && (p->done || p->held || p->mark || !fits(p, x))) p = p->next;
  return p;
}

/* The promise m certainly goes to (the head comment's rule), or NULL.  m is
 * not in the mailbox, or is and was sent after every message before it
 * from its source.  The messages from m's source before it that were not
 * delivered take, in order, the first open promise each fits (marked
 * meanwhile); m's is the first open one left that it fits. */
static promise *promise_for(const mbox *b, const msg *m) {
  promise *p;
  for (const msg *x = b->head; x && x != m; x = x->next)
    if (x->src == m->src && x->seq < m->seq && !x->at && (p = first_open(b, x))) p->mark = 1;
  promise *mine = first_open(b, m);
  for (p = b->phead; p; p = p->next) p->mark = 0;
  if (!mine || m->len > mine->cap) return NULL;
  if (b->nheld)
    for (const promise *q = b->phead; q; q = q->next)
      if (q->held && q->held->src != m->src && overlap(q->buf, q->held->len, mine->buf, m->len)) return NULL;
  return mine;
}

static void deliver(mbox *b, msg *m, promise *p, const void *from) {
  bigcopy(p->buf, from, m->len);
  m->data = p->buf;
  m->where = P_PROMISE;
  m->at = p;
  p->held = m;
  b->nheld++;
}

/* m no longer holds the promise it was delivered into (which is open
 * again). */
static void unhold(msg *m) {
  m->at->held = NULL;
  m->box->nheld--;
  m->at = NULL;
}

/* m's payload leaves the promised buffer it was delivered into (which is
 * the promise's owner's again): into memory of its own. */
static void evict(mstore *st, msg *m) {
  const unsigned char *from = m->at->buf;
  unhold(m);
  own_payload(st, m, from);
}

void box_place_any(mstore *st, msg *m, const void *buf) {
  promise *p = m->box->phead ? promise_for(m->box, m) : NULL;
  if (p)
    deliver(m->box, m, p, buf);
  else
    own_payload(st, m, buf);
}

promise *promise_add(mstore *st, mbox *b, int src, int tag, int mask, void *buf, size_t cap) {
  promise *p = st->pfree;
  if (p)
    st->pfree = p->next;
  else
    p = xmalloc(sizeof *p);
  p->src = src;
  p->tag = tag & mask;
  p->mask = mask;
  p->buf = buf;
  p->cap = cap;
  p->held = NULL;
  p->done = 0;
  p->mark = 0;
  DLIST_APPEND(b->phead, b->ptail, p);
  return p;
}

int promise_drop(mstore *st, mbox *b, promise *p, int keep) {
  if (p->held) {
    if (keep) return 1;
    evict(st, p->held);
  }
  DLIST_UNLINK(b->phead, b->ptail, p);
  p->next = st->pfree;
  st->pfree = p;
  return 0;
}

/* A receive takes m: the promise it fulfils is done (the one it was
 * delivered into, or the first open one it fits: by the promise's terms,
 * m is its message). */
static void fulfil(msg *m) {
  promise *p = m->at;
  if (p) {
    p->held = NULL;
    m->box->nheld--;
    m->at = NULL;
  } else {
    p = first_open(m->box, m);
  }
  if (p) p->done = 1;
}

/* ==== receiving, settling, withdrawing ===================================== */

/* Copy m's first n bytes into buf, unless they are there already. */
static void copy_out(mstore *st, msg *m, void *buf, size_t n) {
  mbox *b = m->box;
  if (!n || m->data == buf) return;
  /* A buffer that holds another message delivered for a promise: that one
   * moves out first (a receive of the rank's own broke the promise). */
  if (b->nheld)
    for (promise *q = b->phead; q; q = q->next)
      if (q->held && q->held != m && overlap(q->buf, q->held->len, buf, n)) evict(st, q->held);
  bigcopy(buf, m->data, n);
}

void msg_read_any(mstore *st, msg *m, void *buf, size_t n) {
  box_unlink(m);
  copy_out(st, m, buf, n);
  if (m->box->phead) fulfil(m);
  m->state = M_READ;
  if (m->ref)
    live_add(st, m);
  else
    msg_end(st, m);
}

void msg_hold_any(mstore *st, msg *m) {
  box_unlink(m);
  if (m->where == P_PROMISE) evict(st, m);
  if (m->box->phead) fulfil(m);
  m->state = M_HELD;
  live_add(st, m);
}

void msg_take_any(mstore *st, msg *m, void *buf, size_t n) {
  if (m->state == M_HELD) copy_out(st, m, buf, n);
  m->state = M_READ;
  if (!m->ref) {
    live_remove(st, m);
    msg_end(st, m);
  }
}

void msg_settle(mstore *st, msg *m, int promises) {
  m->ref = 0;
  if (m->state == M_READ) {
    live_remove(st, m);
    msg_end(st, m);
    return;
  }
  if (m->where != P_SENDER || m->state == M_GONE) return;
  if (m->state == M_BOX && promises)
    box_place(st, m, m->data);
  else
    own_payload(st, m, m->data);
}

int msg_withdraw(mstore *st, msg *m) {
  if (m->state == M_READ) return 0;
  m->ref = 0;
  if (m->state == M_HELD) {   /* its holder releases it (msg_take) */
    m->state = M_GONE;
    return 1;
  }
  box_unlink(m);
  if (m->at) unhold(m);
  msg_end(st, m);
  return 1;
}

void box_clear(mbox *b, mstore *st) {
  while (b->head) {
    msg *m = b->head;
    b->head = m->next;
    if (m->at) unhold(m);
    m->ref = 0;
    msg_end(st, m);
  }
  b->tail = NULL;
  while (b->phead) promise_drop(st, b, b->phead, 0);
}

static void chans_grow(chanset *c) {
  int cap = c->cap ? 2 * c->cap : 4;
  chan *old = c->t, *t = xmallocarray((size_t)cap, sizeof *t);
  for (int i = 0; i < cap; i++) t[i].dst = -1;
  for (int i = 0; i < c->cap; i++) {
    if (old[i].dst < 0) continue;
    unsigned h = chan_hash(old[i].dst, cap);
    while (t[h].dst >= 0) h = (h + 1) & (unsigned)(cap - 1);
    t[h] = old[i];
  }
  free(old);
  c->t = t;
  c->cap = cap;
}

double *chan_add(chanset *c, int dst) {
  if (2 * (c->n + 1) > c->cap) chans_grow(c);
  unsigned h = chan_hash(dst, c->cap);
  while (c->t[h].dst >= 0) h = (h + 1) & (unsigned)(c->cap - 1);
  c->t[h].dst = dst;
  c->t[h].last = -INFINITY;
  c->n++;
  return &c->t[h].last;
}

void mstore_sweep(mstore *st) {
  while (st->live) {
    msg *m = st->live;
    live_remove(st, m);
    msg_end(st, m);
  }
}
