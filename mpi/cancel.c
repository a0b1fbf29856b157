/* cancel.c -- MPI_Cancel and MPI_Test_cancelled (MPI 3.1 section 3.8.4).
 *
 * A receive is cancelled while it is posted and no message is in its
 * buffer (not even one its sender copied there early: engine.h); a send,
 * standard, synchronous or ready, nonblocking or persistent, while no
 * receive has read its message: the message is taken back from wherever
 * it waits (mp's mailbox, or the receiver's unexpected queue), as MPICH
 * takes back an eager message it finds unmatched (a nonblocking or
 * persistent buffered send's too: its message is a copy of its own until
 * the request ends).
 * A request of a kind of its own calls its kind's cancel (a generalized
 * request's cancel_fn); a nonblocking collective's is refused (MPI 3.1
 * section 5.12: erroneous).  Whether a request was cancelled is its status's
 * to say, once the Wait or Test that completes it has it. */
#include "mpi/engine.h"
#include "mpi/err.h"

int PMPI_Cancel(MPI_Request *request) {
  static const char fn[] = "MPI_Cancel";
  st_rank *R = st_need(fn);
  if (!request || *request == MPI_REQUEST_NULL)
    return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "%s", request ? "MPI_REQUEST_NULL" : "NULL request argument");
  st_req *q = st_req_get(R, *request);
  if (!q)
    return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "invalid request handle 0x%x (%s)", (unsigned)*request,
                     H_KIND(*request) == HK_REQ ? "freed, or not this rank's" : "not a request");
  if (q->state == RS_INACTIVE) return MPI_SUCCESS;   /* an inactive persistent request: nothing to do */
  switch (q->kind) {
  case RQ_RECV:
    if (q->state == RS_ACTIVE) eng_cancel_recv(R, q);
    return MPI_SUCCESS;
  case RQ_SEND:
    eng_cancel_send(R, q);
    return MPI_SUCCESS;
  case RQ_COLL:   /* erroneous (MPI 3.1 section 5.12) */
    return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "the request of %s: a nonblocking collective cannot be cancelled",
                     q->fn);
  default: {
    int err = q->ops->cancel ? q->ops->cancel(q->ext, q->state == RS_DONE) : MPI_SUCCESS;
    return err ? err_raise(R, NULL, err, fn, "the request of %s: its cancel callback failed (error %d)", q->fn, err)
               : MPI_SUCCESS;
  }
  }
}

int PMPI_Test_cancelled(const MPI_Status *status, int *flag) {
  static const char fn[] = "MPI_Test_cancelled";
  st_rank *R = st_need(fn);
  if (!status || status == MPI_STATUS_IGNORE || !flag)
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL status or flag argument");
  *flag = status->tsmpi_cancelled != 0;
  return MPI_SUCCESS;
}
