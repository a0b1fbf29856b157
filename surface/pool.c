/* pool.c -- a fixed set of POSIX threads taking job numbers from one atomic
 * counter. */
#include "surface/pool.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <unistd.h>

#include "util/xmem.h"

typedef struct {
  void (*fn)(void *ud, int job);
  void *ud;
  const int *order;
  int njobs;
  atomic_int next;
} pool;

static void *worker(void *arg) {
  pool *p = arg;
  for (;;) {
    int k = atomic_fetch_add(&p->next, 1);
    if (k >= p->njobs) break;
    p->fn(p->ud, p->order ? p->order[k] : k);
  }
  return NULL;
}

void pool_run(int threads, int njobs, const int *order, void (*fn)(void *ud, int job), void *ud) {
  pool p = {fn, ud, order, njobs, 0};
  if (threads > njobs) threads = njobs;
  if (threads <= 1) {
    worker(&p);
    return;
  }
  pthread_t *t = xmallocarray((size_t)threads - 1, sizeof *t);
  int started = 0;
  for (int i = 0; i < threads - 1; i++)
    if (pthread_create(&t[i], NULL, worker, &p) == 0) started++;
    else break;   /* fewer threads: the jobs still all run */
  worker(&p);
  for (int i = 0; i < started; i++) pthread_join(t[i], NULL);
  free(t);
}

int pool_cores(void) {
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n < 1 ? 1 : n > 1024 ? 1024 : (int)n;
}

typedef struct { double size; int i; } sized;

static int by_size(const void *a, const void *b) {
  const sized *x = a, *y = b;
  if (x->size != y->size) return x->size > y->size ? -1 : 1;
  return x->i - y->i;
}

void pool_order(const double *size, int n, int *order) {
  sized *s = xmallocarray((size_t)n + 1, sizeof *s);
  for (int i = 0; i < n; i++) s[i] = (sized){size[i], i};
  qsort(s, (size_t)n, sizeof *s, by_size);
  for (int i = 0; i < n; i++) order[i] = s[i].i;
  free(s);
}
