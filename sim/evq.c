/* evq.c -- an indexed binary min-heap keyed by (time, sequence number). */
#include "sim/evq.h"

#include <stdlib.h>

#include "util/xmem.h"

evq *evq_new(int n) {
  XASSERT(n >= 0);
  size_t m = n ? (size_t)n : 1;
  /* One block: the queue, its heap, its positions. */
  evq *q = xmalloc(sizeof *q + m * (sizeof *q->heap + sizeof *q->pos));
  *q = (evq){.heap = (evq_entry *)(q + 1), .n = n};
  q->pos = (int *)(q->heap + m);
  for (int i = 0; i < n; i++) q->pos[i] = -1;
  return q;
}

void evq_free(evq *q) { free(q); }

static inline int less(const evq_entry *a, const evq_entry *b) {
  return a->t < b->t || (a->t == b->t && a->seq < b->seq);
}

static void place(evq *q, int i, evq_entry e) {
  q->heap[i] = e;
  q->pos[e.id] = i;
}

static inline void sift_up(evq *q, int i) {
  evq_entry e = q->heap[i];
  while (i > 0) {
    int p = (i - 1) / 2;
    if (!less(&e, &q->heap[p])) break;
    place(q, i, q->heap[p]);
    i = p;
  }
  place(q, i, e);
}

static void sift_down(evq *q, int i) {
  evq_entry e = q->heap[i];
  for (;;) {
    int c = 2 * i + 1;
    if (c >= q->size) break;
    if (c + 1 < q->size && less(&q->heap[c + 1], &q->heap[c])) c++;
    if (!less(&q->heap[c], &e)) break;
    place(q, i, q->heap[c]);
    i = c;
  }
  place(q, i, e);
}

void evq_set(evq *q, int id, double t, uint64_t seq) {
  XASSERT(id >= 0 && id < q->n);
  evq_entry e = {t, seq, id};
  int i = q->pos[id];
  if (i < 0) {
    i = q->size++;
    q->heap[i] = e;
    q->pos[id] = i;
    sift_up(q, i);
  } else if (less(&e, &q->heap[i])) {
    q->heap[i] = e;
    sift_up(q, i);
  } else {
    q->heap[i] = e;
    sift_down(q, i);
  }
}

int evq_pop(evq *q, double *t) {
  if (!q->size) return -1;
  evq_entry top = q->heap[0];
  q->pos[top.id] = -1;
  if (--q->size > 0) {
    q->heap[0] = q->heap[q->size];
    sift_down(q, 0);
  }
  *t = top.t;
  return top.id;
}

void evq_remove(evq *q, int id) {
  XASSERT(id >= 0 && id < q->n);
  int i = q->pos[id];
  if (i < 0) return;
  q->pos[id] = -1;
  if (i == --q->size) return;
  evq_entry last = q->heap[q->size];
  evq_entry old = q->heap[i];
  q->heap[i] = last;
  if (less(&last, &old))
    sift_up(q, i);
  else
    sift_down(q, i);
}

int evq_contains(const evq *q, int id) { return id >= 0 && id < q->n && q->pos[id] >= 0; }

int evq_size(const evq *q) { return q->size; }
