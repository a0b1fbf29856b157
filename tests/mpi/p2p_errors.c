/* p2p_errors.c -- errors under MPI_ERRORS_RETURN, checked by themselves on
 * any number of ranks >= 2: each bad argument gives its error class and
 * the call does nothing (the ranks go on talking correctly after), a
 * message longer than the receive is MPI_ERR_TRUNCATE (and
 * MPI_ERR_IN_STATUS with the status's error among several); MPI_Error_class
 * and MPI_Error_string.  (A buffered send without room in the attached
 * buffer is MPI_ERR_BUFFER on tilesim, but Open MPI sends a message that
 * can go at once without the buffer: tests/test_mpi_p2p.c checks it.) */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

static int err_class(int rc) {
  int cls = -1;
  MPI_Error_class(rc, &cls);
  return cls;
}

#define EXPECT(t, call, cls)                                                                    \
  do {                                                                                          \
    int rc_ = (call);                                                                           \
    MCHECK(t, rc_ != MPI_SUCCESS && err_class(rc_) == (cls), "%s gave %d (class %d, %d due)", #call, \
           rc_, err_class(rc_), cls);                                                          \
  } while (0)

static void err_args(mtest *t) {
  int v[4] = {1, 2, 3, 4};
  MPI_Request r = MPI_REQUEST_NULL;
  EXPECT(t, MPI_Send(v, 1, MPI_INT, t->size, 0, MPI_COMM_WORLD), MPI_ERR_RANK);
  EXPECT(t, MPI_Send(v, 1, MPI_INT, -7, 0, MPI_COMM_WORLD), MPI_ERR_RANK);
  EXPECT(t, MPI_Recv(v, 1, MPI_INT, t->size + 3, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE), MPI_ERR_RANK);
  EXPECT(t, MPI_Send(v, -1, MPI_INT, 0, 0, MPI_COMM_WORLD), MPI_ERR_COUNT);
  EXPECT(t, MPI_Irecv(v, -2, MPI_INT, 0, 0, MPI_COMM_WORLD, &r), MPI_ERR_COUNT);
  EXPECT(t, MPI_Send(v, 1, MPI_INT, 0, -5, MPI_COMM_WORLD), MPI_ERR_TAG);
  EXPECT(t, MPI_Send(v, 1, MPI_INT, 0, MPI_ANY_TAG, MPI_COMM_WORLD), MPI_ERR_TAG);
  EXPECT(t, MPI_Send(v, 1, MPI_DATATYPE_NULL, 0, 0, MPI_COMM_WORLD), MPI_ERR_TYPE);
  EXPECT(t, MPI_Send(v, 1, MPI_INT, 0, 0, MPI_COMM_NULL), MPI_ERR_COMM);
  EXPECT(t, MPI_Probe(t->size, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE), MPI_ERR_RANK);
  EXPECT(t, MPI_Request_free(&r), MPI_ERR_REQUEST);
  /* An uncommitted type. */
  MPI_Datatype pair;
  MPI_Type_contiguous(2, MPI_INT, &pair);
  EXPECT(t, MPI_Send(v, 1, pair, 0, 0, MPI_COMM_WORLD), MPI_ERR_TYPE);
  MPI_Type_free(&pair);
  /* (A freed communicator's handle: another MPI may not catch it; tilesim's
   * own test does, tests/test_mpi_p2p.c.) */
  /* Nothing was sent: the ring still carries exactly its own message. */
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size, in = -1;
  int rc = MPI_Sendrecv(&t->rank, 1, MPI_INT, right, 1, &in, 1, MPI_INT, left, 1, MPI_COMM_WORLD,
                        MPI_STATUS_IGNORE);
  MCHECK(t, rc == MPI_SUCCESS && in == left, "after the errors: %d from %d", in, left);
}

/* Rank 0 sends rank 1 messages of 4 ints; rank 1 receives them into room
 * for 2: MPI_ERR_TRUNCATE (the first 2 stored), and the next message is
 * received whole. */
static void err_truncate(mtest *t) {
  int v[4] = {1, 2, 3, 4};
  if (t->rank == 0) {
    for (int i = 0; i < 5; i++) MPI_Send(v, 4, MPI_INT, 1, 10 + i, MPI_COMM_WORLD);
  } else if (t->rank == 1) {
    int in[4] = {0, 0, 0, 0};
    MPI_Status st;
    EXPECT(t, MPI_Recv(in, 2, MPI_INT, 0, 10, MPI_COMM_WORLD, &st), MPI_ERR_TRUNCATE);
    MCHECK(t, in[0] == 1 && in[1] == 2 && in[2] == 0, "truncated: %d %d %d", in[0], in[1], in[2]);
    int rc = MPI_Recv(in, 4, MPI_INT, 0, 11, MPI_COMM_WORLD, &st);
    MCHECK(t, rc == MPI_SUCCESS && in[3] == 4, "after a truncation: %d", rc);
    /* Nonblocking: the error in the status among several. */
    int a[4], b[4];
    MPI_Request r[2];
    MPI_Status sts[2];
    MPI_Irecv(a, 4, MPI_INT, 0, 12, MPI_COMM_WORLD, &r[0]);
    MPI_Irecv(b, 3, MPI_INT, 0, 13, MPI_COMM_WORLD, &r[1]);
    rc = MPI_Waitall(2, r, sts);
    MCHECK(t, err_class(rc) == MPI_ERR_IN_STATUS && sts[0].MPI_ERROR == MPI_SUCCESS &&
                  err_class(sts[1].MPI_ERROR) == MPI_ERR_TRUNCATE,
           "waitall with a truncation: %d, statuses %d %d", rc, sts[0].MPI_ERROR, sts[1].MPI_ERROR);
    MPI_Irecv(a, 1, MPI_INT, 0, 14, MPI_COMM_WORLD, &r[0]);
    EXPECT(t, MPI_Wait(&r[0], &st), MPI_ERR_TRUNCATE);
  }
}

static void err_strings(mtest *t) {
  char s[MPI_MAX_ERROR_STRING];
  int len = -1;
  MPI_Error_string(MPI_ERR_TRUNCATE, s, &len);
  MCHECK(t, len > 0 && len < MPI_MAX_ERROR_STRING && (int)strlen(s) == len, "error string: %d", len);
  MPI_Error_string(MPI_SUCCESS, s, &len);
  MCHECK(t, len > 0, "success's string");
  MCHECK(t, err_class(MPI_ERR_RANK) == MPI_ERR_RANK && err_class(MPI_SUCCESS) == MPI_SUCCESS, "classes");
  /* A duplicate keeps the handler. */
  MPI_Comm dup;
  MPI_Comm_dup(MPI_COMM_WORLD, &dup);
  int v = 0;
  EXPECT(t, MPI_Send(&v, 1, MPI_INT, t->size, 0, dup), MPI_ERR_RANK);
  MPI_Errhandler eh;
  MPI_Comm_get_errhandler(dup, &eh);
  MCHECK(t, eh == MPI_ERRORS_RETURN, "a dup's handler");
  MPI_Errhandler_free(&eh);
  MPI_Comm_free(&dup);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {err_args, err_truncate, err_strings, NULL};
  return mtest_main(&argc, &argv, "p2p_errors", 2, MTEST_ERRORS_RETURN, checks);
}
