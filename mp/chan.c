/* chan.c -- the threads backend's channels (chan.h). */
#include "chan.h"

#include <stdlib.h>
#include <string.h>

#include "xmem.h"

chunk *chunk_new(void) {
  chunk *c = aligned_alloc(LINE, CHUNK);
  if (!c) xpanic("threads: out of memory for a channel's chunk of %d bytes", CHUNK);
  memset(c, 0, CHUNK);
  return c;
}

rec *chan_put(chan *q, int src, int tag, uint64_t stamp, const void *buf, size_t len) {
  int big = len > INLINE_MAX;
  size_t need = (sizeof(rec) + (big ? sizeof(void *) : len) + LINE - 1) / LINE * LINE;
  if (q->woff + need + LINE > CHUNK_DATA) {   /* room for a record and a jump, always */
    chunk *c = chunk_new();
    q->wc->next = c;
    atomic_store_explicit(&rec_at(q->wc, q->woff)->size, REC_JUMP, memory_order_seq_cst);
    q->wc = c;
    q->woff = 0;
  }
  rec *x = rec_at(q->wc, q->woff);
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
  atomic_store_explicit(&x->size, (uint32_t)need, memory_order_seq_cst);   /* publish (see Sleeping) */
  q->woff += need;
  return x;
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
      if (tag_ok(tag, x->tag)) return x;
      off += sz;
      continue;
    }
    uint32_t sz = atomic_load_explicit(&x->size, memory_order_relaxed);
    if (sz == REC_JUMP) {
      c = c->next;
      off = 0;
      continue;
    }
    if (!(x->flags & REC_TAKEN) && tag_ok(tag, x->tag)) return x;
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
    off += sz;
  }
  free(q);
}
