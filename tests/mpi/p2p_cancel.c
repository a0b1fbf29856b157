/* p2p_cancel.c -- MPI_Cancel and MPI_Test_cancelled, checked by themselves
 * on any number of ranks >= 2.  A posted receive is cancelled (by MPI_Wait
 * and by MPI_Test, several in any order, the one not cancelled still
 * taking its message); a receive that has its message already is not.  A
 * send: MPI lets an implementation cancel one no receive has taken, or
 * not (Open MPI never does, tilesim and MPICH take an unmatched message
 * back); whichever it does, the receiver must then find the message or
 * must not, which the sender tells it, and a send whose message was
 * received is never cancelled.  Standard, persistent and buffered sends
 * of messages short enough to go eagerly everywhere (a rendezvous send
 * that is not cancelled would wait for a receive the test posts only
 * after it). */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

static void fill(char *b, int n, int seed) {
  for (int i = 0; i < n; i++) b[i] = (char)(seed * 7 + i * 13);
}

static int filled(const char *b, int n, int seed) {
  for (int i = 0; i < n; i++)
    if (b[i] != (char)(seed * 7 + i * 13)) return 0;
  return 1;
}

/* Four receives posted from rank 0 (tags 0..3, sizes 1 to 10^6 bytes);
 * rank 0 sends only tag 1; receives 2, 3 and 0 are cancelled in that
 * order, receive 1 gets its message. */
static void cancel_posted(mtest *t) {
  static const int size[4] = {1, 100, 10000, 1000000};
  int last = t->size - 1;
  if (t->rank == 0) {
    MPI_Send(NULL, 0, MPI_CHAR, last, 1, MPI_COMM_WORLD);
  } else if (t->rank == last) {
    char *b[4];
    MPI_Request r[4];
    for (int i = 0; i < 4; i++) {
      b[i] = malloc((size_t)size[i]);
      MPI_Irecv(b[i], size[i], MPI_CHAR, 0, i, MPI_COMM_WORLD, &r[i]);
    }
    static const int order[3] = {2, 3, 0};
    for (int k = 0; k < 3; k++) {
      MPI_Status st;
      int flag = -1;
      MPI_Cancel(&r[order[k]]);
      MPI_Wait(&r[order[k]], &st);
      MPI_Test_cancelled(&st, &flag);
      MCHECK(t, flag == 1 && r[order[k]] == MPI_REQUEST_NULL, "receive %d: cancelled %d", order[k], flag);
    }
    MPI_Status st;
    int flag = -1, count = -1;
    MPI_Wait(&r[1], &st);
    MPI_Test_cancelled(&st, &flag);
    MPI_Get_count(&st, MPI_CHAR, &count);
    MCHECK(t, flag == 0 && count == 0 && st.MPI_SOURCE == 0 && st.MPI_TAG == 1,
           "the receive left: cancelled %d, count %d, from %d tag %d", flag, count, st.MPI_SOURCE, st.MPI_TAG);
    for (int i = 0; i < 4; i++) free(b[i]);
  }
}

/* A receive nobody sends to, cancelled, completed by MPI_Test; one from
 * MPI_ANY_SOURCE on a communicator of its own too. */
static void cancel_tested(mtest *t) {
  MPI_Comm comm;
  MPI_Comm_dup(MPI_COMM_WORLD, &comm);
  int v = 0, flag = 0, cancelled = -1;
  MPI_Request r;
  MPI_Status st;
  MPI_Irecv(&v, 1, MPI_INT, (t->rank + 1) % t->size, 40, MPI_COMM_WORLD, &r);
  MPI_Cancel(&r);
  while (!flag) MPI_Test(&r, &flag, &st);
  MPI_Test_cancelled(&st, &cancelled);
  MCHECK(t, cancelled == 1 && r == MPI_REQUEST_NULL, "a tested cancel: cancelled %d", cancelled);
  MPI_Irecv(&v, 1, MPI_INT, MPI_ANY_SOURCE, MPI_ANY_TAG, comm, &r);
  MPI_Cancel(&r);
  MPI_Wait(&r, &st);
  MPI_Test_cancelled(&st, &cancelled);
  MCHECK(t, cancelled == 1, "a cancel from any source: cancelled %d", cancelled);
  MPI_Comm_free(&comm);
}

/* A receive whose message has come (the barrier lets it in: the library
 * makes progress there) is not cancelled: it completes with the message. */
static void cancel_matched(mtest *t) {
  int v = -1;
  if (t->rank == 0) {
    v = 77;
    MPI_Send(&v, 1, MPI_INT, 1, 41, MPI_COMM_WORLD);
  }
  MPI_Request r = MPI_REQUEST_NULL;
  if (t->rank == 1) MPI_Irecv(&v, 1, MPI_INT, 0, 41, MPI_COMM_WORLD, &r);
  MPI_Barrier(MPI_COMM_WORLD);
  if (t->rank != 1) return;
  MPI_Status st;
  MPI_Cancel(&r);
  MPI_Wait(&r, &st);
  int cancelled = -1;
  MPI_Test_cancelled(&st, &cancelled);
  MCHECK(t, cancelled == 0 && v == 77, "a received message: cancelled %d, value %d", cancelled, v);
}

enum { S_ISEND, S_PERSISTENT, S_BUFFERED };

/* Rank 0 sends rank 1 a message of n bytes (kind S_*) and cancels it before
 * rank 1 looks; rank 1 then learns whether it was cancelled, and finds it
 * (intact) or finds nothing. */
static void cancel_send(mtest *t, int kind, int n, int tag) {
  char *b = malloc((size_t)n + 1);
  int was = -1;
  if (t->rank == 0) {
    MPI_Request r;
    MPI_Status st;
    void *attached = NULL;
    fill(b, n, tag);
    if (kind == S_BUFFERED) {
      attached = malloc((size_t)n + MPI_BSEND_OVERHEAD);
      MPI_Buffer_attach(attached, n + MPI_BSEND_OVERHEAD);
      MPI_Ibsend(b, n, MPI_CHAR, 1, tag, MPI_COMM_WORLD, &r);
    } else if (kind == S_PERSISTENT) {
      MPI_Send_init(b, n, MPI_CHAR, 1, tag, MPI_COMM_WORLD, &r);
      MPI_Start(&r);
    } else {
      MPI_Isend(b, n, MPI_CHAR, 1, tag, MPI_COMM_WORLD, &r);
    }
    MPI_Cancel(&r);
    MPI_Wait(&r, &st);
    MPI_Test_cancelled(&st, &was);
    memset(b, 0, (size_t)n);   /* the buffer is the program's again */
    if (kind == S_PERSISTENT) MPI_Request_free(&r);
    MCHECK(t, was == 0 || was == 1, "Test_cancelled gave %d", was);
    MPI_Send(&was, 1, MPI_INT, 1, tag + 1, MPI_COMM_WORLD);
    if (kind == S_BUFFERED) {   /* (a detach waits for the buffered messages) */
      int size;
      void *p;
      MPI_Buffer_detach(&p, &size);
      free(attached);
    }
  } else if (t->rank == 1) {
    MPI_Recv(&was, 1, MPI_INT, 0, tag + 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (was) {
      int flag = -1;
      MPI_Iprobe(0, tag, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
      MCHECK(t, flag == 0, "a cancelled send's message (kind %d, %d bytes) arrived", kind, n);
    } else {
      MPI_Status st;
      int count = -1;
      memset(b, 0, (size_t)n);
      MPI_Recv(b, n, MPI_CHAR, 0, tag, MPI_COMM_WORLD, &st);
      MPI_Get_count(&st, MPI_CHAR, &count);
      MCHECK(t, count == n && filled(b, n, tag), "a send not cancelled (kind %d, %d bytes): count %d", kind, n,
             count);
    }
  }
  free(b);
}

/* A send whose message rank 1 has received is not cancelled. */
static void cancel_received(mtest *t) {
  int v = 5, was = -1;
  MPI_Request r = MPI_REQUEST_NULL;
  if (t->rank == 0) MPI_Isend(&v, 1, MPI_INT, 1, 50, MPI_COMM_WORLD, &r);
  if (t->rank == 1) MPI_Recv(&v, 1, MPI_INT, 0, 50, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Barrier(MPI_COMM_WORLD);
  if (t->rank != 0) return;
  MPI_Status st;
  MPI_Cancel(&r);
  MPI_Wait(&r, &st);
  MPI_Test_cancelled(&st, &was);
  MCHECK(t, was == 0, "a received send was cancelled");
}

/* Cancels of posted, tested and matched receives, of sends of each mode, of a received message. */
static void cancels(mtest *t) {
  cancel_posted(t);
  cancel_tested(t);
  cancel_matched(t);
  static const int sizes[2] = {8, 1000};
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < 2; i++) cancel_send(t, k, sizes[i], 100 + 10 * k + 2 * i);
  cancel_received(t);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {cancels, NULL};
  return mtest_main(&argc, &argv, "p2p_cancel", 1, MTEST_BARRIER, checks);
}
