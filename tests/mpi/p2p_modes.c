/* p2p_modes.c -- the send modes, checked by themselves on any number of
 * ranks >= 2: a synchronous send is not complete before its receive has
 * started (and is once a posted receive takes it), buffered sends through
 * an attached buffer (MPI_Buffer_detach gives it back), ready sends to
 * receives posted before, and the nonblocking and persistent forms. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

/* Rank 1 starts an Issend to rank 0, which first waits for another message
 * that rank 1 sends only after testing the Issend: the receive has not
 * started, so the test must be false. */
static void mode_sync(mtest *t) {
  if (t->rank == 0) {
    int a = 0, b = 0;
    MPI_Recv(&b, 1, MPI_INT, 1, 71, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Recv(&a, 1, MPI_INT, 1, 70, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MCHECK(t, a == 1 && b == 2, "sync: %d %d", a, b);
  } else if (t->rank == 1) {
    int a = 1, b = 2, flag = 1;
    MPI_Request r;
    MPI_Issend(&a, 1, MPI_INT, 0, 70, MPI_COMM_WORLD, &r);
    MPI_Test(&r, &flag, MPI_STATUS_IGNORE);
    MCHECK(t, flag == 0, "an Issend was complete before its receive started");
    MPI_Send(&b, 1, MPI_INT, 0, 71, MPI_COMM_WORLD);
    MPI_Wait(&r, MPI_STATUS_IGNORE);
  }
  /* A blocking Ssend to a receive posted before: rank 0 posts, says so,
   * and the Ssend completes. */
  if (t->rank == 0) {
    int a = 0, ready = 1;
    MPI_Request r;
    MPI_Irecv(&a, 1, MPI_INT, 1, 72, MPI_COMM_WORLD, &r);
    MPI_Send(&ready, 1, MPI_INT, 1, 73, MPI_COMM_WORLD);
    MPI_Wait(&r, MPI_STATUS_IGNORE);
    MCHECK(t, a == 3, "ssend to a posted receive: %d", a);
  } else if (t->rank == 1) {
    int a = 3, ready = 0;
    MPI_Recv(&ready, 1, MPI_INT, 0, 73, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Ssend(&a, 1, MPI_INT, 0, 72, MPI_COMM_WORLD);
  }
  /* To itself, with the receive posted first. */
  int v = t->rank, w = -1;
  MPI_Request r;
  MPI_Irecv(&w, 1, MPI_INT, t->rank, 74, MPI_COMM_WORLD, &r);
  MPI_Ssend(&v, 1, MPI_INT, t->rank, 74, MPI_COMM_WORLD);
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  MCHECK(t, w == t->rank, "ssend to itself: %d", w);
}

/* Buffered sends of K messages of N ints to the right, through a buffer
 * sized for all of them; then detached. */
static void mode_buffered(mtest *t) {
  enum { K = 4, N = 100 };
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size;
  int size = K * (N * (int)sizeof(int) + MPI_BSEND_OVERHEAD);
  char *buf = malloc((size_t)size);
  MPI_Buffer_attach(buf, size);
  int v[N];
  for (int k = 0; k < K; k++) {
    for (int i = 0; i < N; i++) v[i] = 1000 * t->rank + 10 * k + i % 10;
    if (k % 2)
      MPI_Bsend(v, N, MPI_INT, right, 80, MPI_COMM_WORLD);
    else {
      MPI_Request r;
      MPI_Ibsend(v, N, MPI_INT, right, 80, MPI_COMM_WORLD, &r);
      MPI_Wait(&r, MPI_STATUS_IGNORE);
    }
  }
  for (int k = 0; k < K; k++) {
    int in[N], bad = 0;
    MPI_Recv(in, N, MPI_INT, left, 80, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    for (int i = 0; i < N; i++) bad += in[i] != 1000 * left + 10 * k + i % 10;
    MCHECK(t, bad == 0, "bsend message %d: %d wrong", k, bad);
  }
  void *back = NULL;
  int bsize = 0;
  MPI_Buffer_detach(&back, &bsize);
  MCHECK(t, back == buf && bsize == size, "detach: %p %d (%p %d due)", back, bsize, (void *)buf, size);
  free(buf);
}

/* Ready sends: the receiver posts, then tells the sender to go. */
static void mode_ready(mtest *t) {
  if (t->rank == 0) {
    int a = 0, b = 0, go = 1;
    MPI_Request r[2];
    MPI_Irecv(&a, 1, MPI_INT, 1, 90, MPI_COMM_WORLD, &r[0]);
    MPI_Irecv(&b, 1, MPI_INT, 1, 91, MPI_COMM_WORLD, &r[1]);
    MPI_Send(&go, 1, MPI_INT, 1, 92, MPI_COMM_WORLD);
    MPI_Waitall(2, r, MPI_STATUSES_IGNORE);
    MCHECK(t, a == 8 && b == 9, "rsend: %d %d", a, b);
  } else if (t->rank == 1) {
    int a = 8, b = 9, go = 0;
    MPI_Request r;
    MPI_Recv(&go, 1, MPI_INT, 0, 92, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Rsend(&a, 1, MPI_INT, 0, 90, MPI_COMM_WORLD);
    MPI_Irsend(&b, 1, MPI_INT, 0, 91, MPI_COMM_WORLD, &r);
    MPI_Wait(&r, MPI_STATUS_IGNORE);
  }
}

/* Persistent synchronous, buffered and ready sends around the ring, three
 * rounds: the receive is started before the sends each round, and a
 * round's end is everyone's (a ready send needs its receive posted: each
 * rank tells its left neighbour when it has posted). */
static void mode_persistent(mtest *t) {
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size;
  int out[3], in[3] = {0, 0, 0}, go = 0;
  int size = 3 * ((int)sizeof(int) + MPI_BSEND_OVERHEAD);
  char *buf = malloc((size_t)size);
  MPI_Buffer_attach(buf, size);
  MPI_Request rr[3], sr[3];
  for (int i = 0; i < 3; i++) MPI_Recv_init(&in[i], 1, MPI_INT, left, 100 + i, MPI_COMM_WORLD, &rr[i]);
  MPI_Ssend_init(&out[0], 1, MPI_INT, right, 100, MPI_COMM_WORLD, &sr[0]);
  MPI_Bsend_init(&out[1], 1, MPI_INT, right, 101, MPI_COMM_WORLD, &sr[1]);
  MPI_Rsend_init(&out[2], 1, MPI_INT, right, 102, MPI_COMM_WORLD, &sr[2]);
  for (int round = 0; round < 3; round++) {
    for (int i = 0; i < 3; i++) out[i] = 100 * round + 10 * i + t->rank;
    MPI_Startall(3, rr);
    MPI_Sendrecv(&go, 1, MPI_INT, left, 103, &go, 1, MPI_INT, right, 103, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Startall(3, sr);
    MPI_Waitall(3, sr, MPI_STATUSES_IGNORE);
    MPI_Waitall(3, rr, MPI_STATUSES_IGNORE);
    for (int i = 0; i < 3; i++)
      MCHECK(t, in[i] == 100 * round + 10 * i + left, "persistent mode %d round %d: %d", i, round, in[i]);
  }
  for (int i = 0; i < 3; i++) {
    MPI_Request_free(&rr[i]);
    MPI_Request_free(&sr[i]);
  }
  void *back;
  int bsize;
  MPI_Buffer_detach(&back, &bsize);
  free(buf);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {mode_sync, mode_buffered, mode_ready, mode_persistent, NULL};
  return mtest_main(&argc, &argv, "p2p_modes", 2, 0, checks);
}
