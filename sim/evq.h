/* evq.h -- the simulator's event queue: an indexed binary heap of (time, seq) keys.
 *
 * Each entry is an id in 0..n-1 (a rank) with a key (t, seq): earlier t
 * first, and among equal t the smaller seq.  Sequence numbers are unique, so
 * the order is total and every run pops the same ids in the same order.  An
 * id is in the queue at most once; evq_set inserts it or moves it to a new
 * key.  All operations are O(log size) except evq_min, which is O(1). */
#ifndef EVQ_H
#define EVQ_H

#include <math.h>
#include <stdint.h>

typedef struct evq evq;

evq *evq_new(int n);     /* ids 0..n-1, empty */
void evq_free(evq *q);   /* NULL is fine */

/* Insert id with key (t, seq), or re-key it if it is queued already. */
void evq_set(evq *q, int id, double t, uint64_t seq);

/* Remove and return the id with the least key, its time in *t; -1 if empty. */
int evq_pop(evq *q, double *t);

/* Remove id if it is queued. */
void evq_remove(evq *q, int id);

int evq_contains(const evq *q, int id);
int evq_size(const evq *q);

/* --- private part: the body, so that evq_min can be inlined in the hot path */

typedef struct {
  double t;
  uint64_t seq;
  int id;
} evq_entry;

struct evq {
  evq_entry *heap;  /* heap[0] is the least key */
  int *pos;         /* pos[id] = index in heap, or -1 */
  int n, size;      /* ids, entries */
};

/* The least time queued, or +infinity when the queue is empty. */
static inline double evq_min(const evq *q) {
  return q->size ? q->heap[0].t : INFINITY;
}

#endif
