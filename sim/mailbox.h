/* mailbox.h -- the simulator's messages and each rank's mailbox (sim.c's
 * data): a message's envelope, times and payload, the mailbox that holds a
 * rank's messages sent and not yet received, in the order a receive takes
 * them (arrival, then send order), the rank's promises (mp_promise), and
 * its channels out (the latest arrival on each, for the order of sends).
 *
 * WHERE A PAYLOAD LIVES.  A message's payload is, at any time, in one
 * place, and a receive copies it from there into its buffer:
 *   inline    in the message itself (up to MSG_INLINE bytes);
 *   pooled    in a block of the machine's payload pool (blocks by powers of
 *             two, reused: no allocation, zeroing or page fault a message
 *             once the pool has warmed up);
 *   sender    still in its sender's buffer (mp_send_ref, until settled);
 *   promised  already in the receive buffer a promise named (the receive
 *             that takes it copies nothing).
 * A send copies the payload once: into a promise that certainly receives it
 * (box_place says when), else into the message or a pooled block.  A send
 * by reference copies nothing; when its sender settles it (msg_settle), a
 * payload still unread goes to a promise that certainly receives it, else
 * into the pool.  So a payload is copied once when its receive was promised
 * before the sender needed its buffer back, or when the receive takes it
 * first; twice only when it must wait for a receive nobody has posted.
 *
 * A MESSAGE'S LIFE.  In a mailbox (M_BOX) until a receive takes it: read
 * at once (mp_recv: M_READ) or held (mp_recv_msg: M_HELD, read later).  A
 * sender's withdrawal (mp_withdraw) takes it out of the mailbox, or marks a
 * held one M_GONE.  The message is freed when both sides are done with it:
 * the receiver (read, or released) and its sender (settled or withdrawn). */
#ifndef MAILBOX_H
#define MAILBOX_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "util/dlist.h"

enum { MSG_INLINE = 64 };   /* payloads up to this many bytes live in the message */

enum { P_INLINE, P_POOL, P_SENDER, P_PROMISE };   /* where a payload lives */
enum { M_BOX, M_HELD, M_READ, M_GONE };           /* a message's state */

typedef struct promise promise;
typedef struct msg msg;
typedef struct mbox mbox;

struct msg {
  msg *prev, *next;        /* in the receiver's mailbox, by (arrival, seq) */
  double sent;             /* the sender's clock at mp_send */
  double arrival;          /* when it can be received */
  uint64_t seq;            /* send order, machine-wide; the message id in traces */
  int src, tag;
  size_t len;
  unsigned char *data;     /* where the payload is now (P_*) */
  unsigned char where;     /* P_* */
  unsigned char state;     /* M_* */
  unsigned char ref;       /* its sender holds a reference (mp_send_ref, not settled) */
  mbox *box;               /* the receiver's mailbox */
  promise *at;             /* P_PROMISE: the promise it was delivered into */
  unsigned char inl[MSG_INLINE];
};

/* A promise (mp_promise): the first message from src whose tag t has
 * (t & mask) == tag, among those the rank has not received, is to be
 * received into buf (cap bytes). */
struct promise {
  promise *prev, *next;    /* the rank's promises, in the order made */
  int src, tag, mask;
  unsigned char *buf;
  size_t cap;
  msg *held;               /* a message delivered into buf and not yet received */
  unsigned char done;      /* its message was received */
  unsigned char mark;      /* taken in promise_for's reckoning (mailbox.c) */
};

struct mbox {
  msg *head, *tail;        /* messages not yet received, by (arrival, seq) */
  promise *phead, *ptail;  /* promises, in the order made */
  int nheld;               /* promises holding a delivered message */
};

enum { POOL_CLASSES = 48 };

/* The machine's spent messages and payload blocks, for reuse, and the
 * messages out of every mailbox but not yet done with (held, withdrawn
 * while held, or read but not yet settled). */
typedef struct {
  msg *free;
  msg *live;
  void *blocks[POOL_CLASSES];   /* free blocks of 2^k bytes, linked through their first word */
  size_t cached;                /* bytes in blocks */
  long long pooled;             /* payload bytes copied into blocks (sim_stats) */
  promise *pfree;
} mstore;

void mstore_free(mstore *st);

/* A message to b of len bytes with its payload copied from buf
 * (box_place: into a promise, the message or a pooled block), and one that
 * refers to buf (P_SENDER, ref set).  The caller fills the envelope and
 * times first (box_place reads src and tag), then inserts it (box_insert).
 * The common cases are inline (a short message, no promises): the rest is
 * in mailbox.c. */
msg *msg_alloc(mstore *st);
static inline msg *msg_new(mstore *st, mbox *b, size_t len) {
  msg *m = st->free;
  if (m)
    st->free = m->next;
  else
    m = msg_alloc(st);
  m->len = len;
  m->box = b;
  m->state = M_BOX;
  m->ref = 0;
  m->at = NULL;
  return m;
}

/* n bytes (at most MSG_INLINE) between a buffer and a message's own
 * payload, which never overlap: eight at a time (the last eight overlapping
 * the ones before), or four, or one by one, without a call to memcpy. */
static inline void msg_copy_short(void *to, const void *from, size_t n) {
  unsigned char *d = to;
  const unsigned char *f = from;
  if (n >= 8) {
    size_t i = 0;
    for (; i + 8 <= n; i += 8) memcpy(d + i, f + i, 8);
    if (i < n) memcpy(d + n - 8, f + n - 8, 8);
  } else if (n >= 4) {
    memcpy(d, f, 4);
    memcpy(d + n - 4, f + n - 4, 4);
  } else if (n) {
    d[0] = f[0];
    d[n / 2] = f[n / 2];
    d[n - 1] = f[n - 1];
  }
}

void box_place_any(mstore *st, msg *m, const void *buf);
static inline void box_place(mstore *st, msg *m, const void *buf) {
  if (m->len <= MSG_INLINE && !m->box->phead) {
    m->data = m->inl;
    m->where = P_INLINE;
    msg_copy_short(m->inl, buf, m->len);
  } else {
    box_place_any(st, m, buf);
  }
}

msg *msg_new_ref(mstore *st, mbox *b, const void *buf, size_t len);

/* Insert m into its mailbox by (arrival, seq); its seq is the largest yet. */
static inline void box_insert(msg *m) {
  mbox *b = m->box;
  msg *p = b->tail;
  while (p && p->arrival > m->arrival) p = p->prev;
  m->prev = p;
  m->next = p ? p->next : b->head;
  if (m->next)
    m->next->prev = m;
  else
    b->tail = m;
  if (p)
    p->next = m;
  else
    b->head = m;
}

static inline void box_unlink(msg *m) {
  DLIST_UNLINK(m->box->head, m->box->tail, m);
}

/* m's envelope fits a receive from src with tag (MP_ANY = -1: any). */
static inline int msg_matches(const msg *m, int src, int tag) {
  return (src < 0 || m->src == src) && (tag < 0 || m->tag == tag);
}

/* The earliest (arrival, seq) message of b matching src and tag, or NULL. */
static inline msg *box_find(const mbox *b, int src, int tag) {
  for (msg *m = b->head; m; m = m->next)
    if (msg_matches(m, src, tag)) return m;
  return NULL;
}

/* A receive takes m out of its mailbox: copies its first n bytes into buf
 * (nothing if they are there already) and is done with it (msg_read); or
 * holds it (msg_hold: a payload in a promised buffer moves to the pool)
 * and later copies its first n bytes out with msg_take (n = 0: nothing,
 * as for a withdrawn message). */
void msg_read_any(mstore *st, msg *m, void *buf, size_t n);
static inline void msg_read(mstore *st, msg *m, void *buf, size_t n) {
  if (m->where == P_INLINE && !m->ref && !m->box->phead) {
    box_unlink(m);
    msg_copy_short(buf, m->data, n);
    m->next = st->free;
    st->free = m;
  } else {
    msg_read_any(st, m, buf, n);
  }
}
void msg_hold_any(mstore *st, msg *m);
static inline void msg_hold(mstore *st, msg *m) {
  if (m->where != P_PROMISE && !m->box->phead) {
    box_unlink(m);
    m->state = M_HELD;
    m->prev = NULL;   /* onto the live list */
    m->next = st->live;
    if (st->live) st->live->prev = m;
    st->live = m;
  } else {
    msg_hold_any(st, m);
  }
}
void msg_take_any(mstore *st, msg *m, void *buf, size_t n);
static inline void msg_take(mstore *st, msg *m, void *buf, size_t n) {
  if (m->where == P_INLINE && !m->ref && m->state == M_HELD) {
    msg_copy_short(buf, m->data, n);
    if (m->prev)   /* off the live list */
      m->prev->next = m->next;
    else
      st->live = m->next;
    if (m->next) m->next->prev = m->prev;
    m->next = st->free;
    st->free = m;
  } else {
    msg_take_any(st, m, buf, n);
  }
}

/* The sender is done with its reference: msg_settle copies a payload still
 * in its buffer out first (box_place's rule; with promises = 0, never into
 * a promise: a stopped run's); msg_withdraw takes the
 * message back if no receive has read it: 1 (gone from the mailbox, or a
 * held one M_GONE), or 0 (read: the reference is still to be settled). */
void msg_settle(mstore *st, msg *m, int promises);
int msg_withdraw(mstore *st, msg *m);

/* Promises: made, and withdrawn (keep = 1 and a message delivered into it
 * and not received: nothing changes, 1; else it goes, and a message
 * delivered into it moves to the pool first: 0). */
promise *promise_add(mstore *st, mbox *b, int src, int tag, int mask, void *buf, size_t cap);
int promise_drop(mstore *st, mbox *b, promise *p, int keep);

/* A rank's channels out: the latest arrival on each of its channels
 * src -> dst (a message never arrives before one sent earlier on its
 * channel), open addressing by dst. */
typedef struct {
  int dst;                 /* -1: empty slot */
  double last;             /* the latest arrival sent on src -> dst */
} chan;

typedef struct {
  chan *t;
  int n, cap;
} chanset;

static inline unsigned chan_hash(int dst, int cap) {
  return ((unsigned)dst * 2654435761u) & (unsigned)(cap - 1);
}

/* The latest arrival on the channel to dst: found, or made (chan_add,
 * -infinity: none yet). */
double *chan_add(chanset *c, int dst);
static inline double *chan_last(chanset *c, int dst) {
  if (c->cap) {
    for (unsigned h = chan_hash(dst, c->cap); c->t[h].dst >= 0; h = (h + 1) & (unsigned)(c->cap - 1))
      if (c->t[h].dst == dst) return &c->t[h].last;
  }
  return chan_add(c, dst);
}

/* Free every message of b into st (the run's end; references are void)
 * and its promises. */
void box_clear(mbox *b, mstore *st);

/* Free the messages still live (the run's end: their holders and senders
 * are gone). */
void mstore_sweep(mstore *st);

#endif
