/* chan.c -- the threads backend's channels (chan.h). */
#include "mp/chan.h"

#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

chunk *chunk_new(void) {
  chunk *c = aligned_alloc(LINE, CHUNK);
  if (!c) xpanic("threads: out of memory for a channel's chunk of %d bytes", CHUNK);
  memset(c, 0, CHUNK);
  return c;
}

/* Room for a record of `data` bytes after its header, at the writer's end
 * (the next chunk if need be); the record, its size in *need. */
static rec *room(chan *q, size_t data, size_t *need) {
  *need = (sizeof(rec) + data + LINE - 1) / LINE * LINE;
  if (q->woff + *need + LINE > CHUNK_DATA) {   /* room for a record and a jump, always */
    chunk *c = chunk_new();
    q->wc->next = c;
    atomic_store_explicit(&rec_at(q->wc, q->woff)->size, REC_JUMP, memory_order_seq_cst);
    q->wc = c;
    q->woff = 0;
  }
  return rec_at(q->wc, q->woff);
}

/* Publish x, of need bytes (see Sleeping in threads.c). */
static void publish(chan *q, rec *x, size_t need) {
  atomic_store_explicit(&x->size, (uint32_t)need, memory_order_seq_cst);
  q->woff += need;
}

rec *chan_put(chan *q, int src, int tag, uint64_t stamp, const void *buf, size_t len) {
  int big = len > INLINE_MAX;
  size_t need;
  rec *x = room(q, big ? sizeof(void *) : len, &need);
  x->tag = tag;
  x->flags = big ? REC_BIG : 0;
  x->src = (uint32_t)src;
  x->stamp = stamp;
  x->len = len;
  if (big) {
    void *copy = xmalloc(len);
    memcpy(copy, buf, len);
    memcpy(rec_data(x), &copy, sizeof copy);
  } else if (len) {
    memcpy(rec_data(x), buf, len);
  }
  publish(q, x, need);
  return x;
}

rec *chan_put_ref(chan *q, int src, int tag, uint64_t stamp, const void *buf, size_t len, ticket **tp) {
  int inl = len <= INLINE_MAX - sizeof(ticket *);
  size_t need;
  rec *x = room(q, sizeof(ticket *) + (inl ? len : 0), &need);
  ticket *t = xmalloc(sizeof *t);
  atomic_init(&t->state, T_REF);
  atomic_init(&t->refs, 2);
  t->buf = inl ? NULL : buf;
  t->copy = NULL;
  t->len = len;
  x->tag = tag;
  x->flags = REC_REF;
  x->src = (uint32_t)src;
  x->stamp = stamp;
  x->len = len;
  memcpy(rec_data(x), &t, sizeof t);
  if (inl && len) memcpy(rec_data(x) + sizeof t, buf, len);
  publish(q, x, need);
  *tp = t;
  return x;
}

/* ==== tickets ============================================================== */

static inline void relax(void) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  __builtin_ia32_pause();
#endif
}

int ticket_read(ticket *t, const unsigned char *inl, void *buf, size_t n) {
  for (;;) {
    int s = atomic_load(&t->state);
    if (s == T_GONE) return -1;
    if (s == T_MOVING) {   /* the sender copies out: a moment */
      relax();
      continue;
    }
    if (s == T_OWN) {
      if (n) memcpy(buf, t->copy, n);
      return 0;
    }
    if (atomic_compare_exchange_weak(&t->state, &s, T_BUSY)) {
      if (n) memcpy(buf, t->buf ? t->buf : inl, n);
      atomic_store(&t->state, T_READ);
      return 0;
    }
  }
}

void ticket_settle(ticket *t) {
  while (t->buf) {   /* (a payload in the record needs nothing) */
    int s = atomic_load(&t->state);
    if (s == T_BUSY) {   /* the reader copies from the buffer: a moment */
      relax();
      continue;
    }
    if (s != T_REF && s != T_SEEN) break;
    if (atomic_compare_exchange_weak(&t->state, &s, T_MOVING)) {
      t->copy = xmalloc(t->len ? t->len : 1);
      memcpy(t->copy, t->buf, t->len);
      atomic_store(&t->state, T_OWN);
      break;
    }
  }
  ticket_drop(t);
}

int ticket_withdraw(ticket *t) {
  int s = T_REF;
  if (atomic_compare_exchange_strong(&t->state, &s, T_GONE)) {
    ticket_drop(t);
    return 1;
  }
  return 0;
}

void ticket_drop(ticket *t) {
  if (atomic_fetch_sub(&t->refs, 1) != 1) return;
  free(t->copy);
  free(t);
}

/* A receive has looked at x: a record by reference can no longer be
 * withdrawn (T_REF -> T_SEEN); one withdrawn already is taken (skipped
 * from now on): 0. */
static int seen(rec *x) {
  if (!(x->flags & REC_REF)) return 1;
  ticket *t = rec_ticket(x);
  int s = T_REF;
  if (atomic_compare_exchange_strong(&t->state, &s, T_SEEN) || s != T_GONE) return 1;
  x->flags = (x->flags & ~(uint32_t)REC_REF) | REC_TAKEN;
  ticket_drop(t);
  return 0;
}

rec *chan_find(chan *q, int tag) {
  chunk *c = q->hc;
  size_t off = q->hoff;
  for (;;) {
    rec *x = rec_at(c, off);
    if (c == q->sc && off == q->soff) {   /* beyond what was seen: published since? */
      uint32_t sz = atomic_load_explicit(&x->size, memory_order_seq_cst);
      if (sz == 0) return NULL;
      if (sz == REC_JUMP) {
        c = q->sc = c->next;
        off = q->soff = 0;
        continue;
      }
      q->soff = off + sz;
      if (tag_ok(tag, x->tag) && seen(x)) return x;
      off += sz;
      continue;
    }
    uint32_t sz = atomic_load_explicit(&x->size, memory_order_relaxed);
    if (sz == REC_JUMP) {
      c = c->next;
      off = 0;
      continue;
    }
    if (!(x->flags & REC_TAKEN) && tag_ok(tag, x->tag) && seen(x)) return x;
    off += sz;
  }
}

/* Move q's head over the records taken out of order and the jumps (freeing
 * the chunks left behind), up to the first record not taken or what the
 * reader has not seen. */
static void chan_settle(chan *q) {
  while (q->hc != q->sc || q->hoff != q->soff) {
    rec *y = rec_at(q->hc, q->hoff);
    uint32_t sz = atomic_load_explicit(&y->size, memory_order_relaxed);
    if (sz == REC_JUMP) {
      chunk *old = q->hc;
      q->hc = old->next;
      q->hoff = 0;
      free(old);
    } else if (y->flags & REC_TAKEN) {
      q->hoff += sz;
    } else {
      break;
    }
  }
}

void chan_take(chan *q, rec *x) {
  if (x->flags & REC_BIG) {
    void *copy;
    memcpy(&copy, rec_data(x), sizeof copy);
    free(copy);
  }
  if (x->flags & REC_REF) ticket_drop(rec_ticket(x));
  chan_settle(q);
  if (x != rec_at(q->hc, q->hoff)) {
    x->flags |= REC_TAKEN;
    return;
  }
  q->hoff += atomic_load_explicit(&x->size, memory_order_relaxed);
  chan_settle(q);
}

void chan_free(chan *q) {
  chunk *c = q->hc;
  size_t off = q->hoff;
  while (c) {
    rec *x = rec_at(c, off);
    uint32_t sz = atomic_load_explicit(&x->size, memory_order_relaxed);
    if (sz == 0 || sz == REC_JUMP) {
      chunk *next = sz == REC_JUMP ? c->next : NULL;
      free(c);
      c = next;
      off = 0;
      continue;
    }
    if ((x->flags & (REC_BIG | REC_TAKEN)) == REC_BIG) {
      void *copy;
      memcpy(&copy, rec_data(x), sizeof copy);
      free(copy);
    }
    if ((x->flags & (REC_REF | REC_TAKEN)) == REC_REF) ticket_drop(rec_ticket(x));
    off += sz;
  }
  free(q);
}
