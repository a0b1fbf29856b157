/* p2p_isendrecv.c -- MPI-4's MPI_Isendrecv and MPI_Isendrecv_replace,
 * checked by themselves on any number of ranks >= 2: a ring in both
 * directions (each rank's request completes with its left neighbour's
 * values and status), in place, with MPI_PROC_NULL ends, a derived type,
 * several at once in MPI_Waitall, one polled with MPI_Test.  An MPI 3.1
 * library (Open MPI 4.1) has neither: there the test's own equivalent
 * (MPI_Irecv and MPI_Isend, MPI_Isendrecv_replace's send from a copy)
 * gives the line the real calls must give. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

#if MPI_VERSION >= 4 || defined(TSMPI_MPI_H)
#define HAVE_ISENDRECV 1
#endif

/* A send-receive in flight: the real request, or the two of the
 * equivalent (and the replace's copy). */
typedef struct {
  MPI_Request r[2];
  void *copy;
} sr;

static void isr(sr *x, const void *sbuf, int sc, MPI_Datatype st, int dst, int stag, void *rbuf, int rc,
                MPI_Datatype rt, int src, int rtag, MPI_Comm comm) {
  x->copy = NULL;
  x->r[1] = MPI_REQUEST_NULL;
#ifdef HAVE_ISENDRECV
  MPI_Isendrecv(sbuf, sc, st, dst, stag, rbuf, rc, rt, src, rtag, comm, &x->r[0]);
#else
  MPI_Irecv(rbuf, rc, rt, src, rtag, comm, &x->r[0]);
  MPI_Isend(sbuf, sc, st, dst, stag, comm, &x->r[1]);
#endif
}

static void isr_replace(sr *x, void *buf, int count, MPI_Datatype dt, int dst, int stag, int src, int rtag,
                        MPI_Comm comm) {
  x->copy = NULL;
  x->r[1] = MPI_REQUEST_NULL;
#ifdef HAVE_ISENDRECV
  MPI_Isendrecv_replace(buf, count, dt, dst, stag, src, rtag, comm, &x->r[0]);
#else
  int size;
  MPI_Pack_size(count, dt, comm, &size);
  x->copy = malloc((size_t)size);
  int pos = 0;
  MPI_Pack(buf, count, dt, x->copy, size, &pos, comm);
  MPI_Isend(x->copy, pos, MPI_PACKED, dst, stag, comm, &x->r[1]);
  MPI_Irecv(buf, count, dt, src, rtag, comm, &x->r[0]);
#endif
}

static void isr_wait(sr *x, MPI_Status *st) {
  MPI_Wait(&x->r[0], st);
  MPI_Wait(&x->r[1], MPI_STATUS_IGNORE);
  free(x->copy);
}

/* 1 when done (x's status in *st). */
static int isr_test(sr *x, MPI_Status *st) {
  int f0 = 1, f1 = 1;
  if (x->r[0] != MPI_REQUEST_NULL) MPI_Test(&x->r[0], &f0, st);
  if (x->r[1] != MPI_REQUEST_NULL) MPI_Test(&x->r[1], &f1, MPI_STATUS_IGNORE);
  if (f0 && f1) free(x->copy);
  return f0 && f1;
}

/* Each rank sends n ints (rank * 1000 + i) right and receives from the
 * left, tag = the receiver's rank; and the other way, polled with MPI_Test
 * for a short message (a long one takes long on a slow simulated network:
 * waited for). */
static void ring(mtest *t, int n) {
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size;
  int *out = malloc((size_t)n * sizeof *out), *in = malloc((size_t)n * sizeof *in);
  for (int i = 0; i < n; i++) out[i] = t->rank * 1000 + i, in[i] = -1;
  sr x;
  MPI_Status st;
  int count = -1, bad = 0;
  isr(&x, out, n, MPI_INT, right, right, in, n, MPI_INT, left, t->rank, MPI_COMM_WORLD);
  isr_wait(&x, &st);
  MPI_Get_count(&st, MPI_INT, &count);
  for (int i = 0; i < n; i++) bad += in[i] != left * 1000 + i;
  MCHECK(t, bad == 0 && count == n && st.MPI_SOURCE == left && st.MPI_TAG == t->rank,
         "ring of %d ints: %d wrong, count %d, source %d", n, bad, count, st.MPI_SOURCE);
  isr(&x, out, n, MPI_INT, left, 500 + left, in, n, MPI_INT, right, 500 + t->rank, MPI_COMM_WORLD);
  if (n > 1)
    isr_wait(&x, &st);
  else
    while (!isr_test(&x, &st)) {
    }
  bad = 0;
  for (int i = 0; i < n; i++) bad += in[i] != right * 1000 + i;
  MCHECK(t, bad == 0 && st.MPI_SOURCE == right, "the other way (MPI_Test): %d wrong", bad);
  free(out);
  free(in);
}

/* In place: the buffer sent right is replaced by the left neighbour's. */
static void ring_replace(mtest *t, int n) {
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size;
  int *b = malloc((size_t)n * sizeof *b);
  for (int i = 0; i < n; i++) b[i] = t->rank * 7 + i;
  sr x;
  MPI_Status st;
  isr_replace(&x, b, n, MPI_INT, right, 30, left, 30, MPI_COMM_WORLD);
  isr_wait(&x, &st);
  int bad = 0;
  for (int i = 0; i < n; i++) bad += b[i] != left * 7 + i;
  MCHECK(t, bad == 0 && st.MPI_SOURCE == left && st.MPI_TAG == 30, "replace of %d ints: %d wrong", n, bad);
  free(b);
}

/* MPI_PROC_NULL ends: the first rank receives from nobody, the last sends
 * to nobody (a line, not a ring). */
static void line(mtest *t) {
  int right = t->rank + 1 < t->size ? t->rank + 1 : MPI_PROC_NULL;
  int left = t->rank > 0 ? t->rank - 1 : MPI_PROC_NULL;
  int v = t->rank + 100, w = -1, count = -1;
  sr x;
  MPI_Status st;
  isr(&x, &v, 1, MPI_INT, right, 8, &w, 1, MPI_INT, left, 8, MPI_COMM_WORLD);
  isr_wait(&x, &st);
  MPI_Get_count(&st, MPI_INT, &count);
  if (left == MPI_PROC_NULL)
    MCHECK(t, w == -1 && st.MPI_SOURCE == MPI_PROC_NULL && count == 0, "from MPI_PROC_NULL: %d", w);
  else
    MCHECK(t, w == left + 100 && st.MPI_SOURCE == left && count == 1, "along the line: %d", w);
}

/* A vector type each way (every other int), and four at once: to every
 * rank of a four-rank neighbourhood, in one MPI_Waitall. */
static void vector_and_many(mtest *t) {
  MPI_Datatype vec;
  MPI_Type_vector(4, 1, 2, MPI_INT, &vec);
  MPI_Type_commit(&vec);
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size;
  int out[8], in[8], bad = 0;
  for (int i = 0; i < 8; i++) out[i] = t->rank * 10 + i, in[i] = -1;
  sr x;
  isr(&x, out, 1, vec, right, 9, in, 1, vec, left, 9, MPI_COMM_WORLD);
  isr_wait(&x, MPI_STATUS_IGNORE);
  for (int i = 0; i < 8; i++) bad += in[i] != (i % 2 ? -1 : left * 10 + i);
  MCHECK(t, bad == 0, "a vector type: %d wrong", bad);
  MPI_Type_free(&vec);
  enum { K = 4 };
  sr xs[K];
  int outs[K], ins[K];
  MPI_Request all[2 * K];
  for (int k = 0; k < K; k++) {
    int d = (t->rank + k + 1) % t->size, s = (t->rank + t->size * K - k - 1) % t->size;
    outs[k] = t->rank * 100 + k;
    ins[k] = -1;
    isr(&xs[k], &outs[k], 1, MPI_INT, d, 70 + k, &ins[k], 1, MPI_INT, s, 70 + k, MPI_COMM_WORLD);
    all[2 * k] = xs[k].r[0];
    all[2 * k + 1] = xs[k].r[1];
  }
  MPI_Waitall(2 * K, all, MPI_STATUSES_IGNORE);
  bad = 0;
  for (int k = 0; k < K; k++) {
    int s = (t->rank + t->size * K - k - 1) % t->size;
    bad += ins[k] != s * 100 + k;
  }
  MCHECK(t, bad == 0, "four at once: %d wrong", bad);
}

/* Rings, lines and vectors by MPI_Isendrecv and MPI_Isendrecv_replace. */
static void isendrecvs(mtest *t) {
  ring(t, 1);
  ring(t, 3000);
  ring_replace(t, 5);
  ring_replace(t, 5000);
  line(t);
  vector_and_many(t);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {isendrecvs, NULL};
  return mtest_main(&argc, &argv, "p2p_isendrecv", 1, MTEST_BARRIER, checks);
}
