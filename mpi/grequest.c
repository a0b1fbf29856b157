/* grequest.c -- generalized requests (MPI 3.1 section 12.2: MPI_Grequest_start,
 * MPI_Grequest_complete) and the status setters their query functions
 * call (MPI_Status_set_cancelled, MPI_Status_set_elements,
 * MPI_Status_set_elements_x).
 *
 * A generalized request is a request of a kind of its own (core.h) without
 * progress: MPI_Grequest_complete makes it done.  Its status is query_fn's
 * (called by the Wait or Test that completes it and by
 * MPI_Request_get_status), its end free_fn's (after query_fn; or at the
 * later of MPI_Request_free and MPI_Grequest_complete), MPI_Cancel calls
 * cancel_fn with whether it is complete; each callback's return is the
 * error the call that ran it returns.  A rank's ranks run one thread each
 * (MPI_THREAD_FUNNELED at most): a Wait on a request that the program
 * completes only after it waits for ever, which the simulator reports as
 * a deadlock naming MPI_Grequest_start. */
#include <stdlib.h>

#include "mpi/err.h"
#include "util/xmem.h"

typedef struct {
  MPI_Grequest_query_function *query;
  MPI_Grequest_free_function *free;
  MPI_Grequest_cancel_function *cancel;
  void *extra;
} greq;

static int greq_status(void *state, MPI_Status *st) {
  greq *g = state;
  return g->query(g->extra, st);
}

static int greq_cancel(void *state, int done) {
  greq *g = state;
  return g->cancel(g->extra, done);
}

static int greq_free(void *state) {
  greq *g = state;
  int err = g->free(g->extra);
  free(g);
  return err;
}

static const req_kind greq_kind = {"MPI_Grequest_start", NULL, greq_cancel, greq_status, greq_free, free};

int PMPI_Grequest_start(MPI_Grequest_query_function *query_fn, MPI_Grequest_free_function *free_fn,
                        MPI_Grequest_cancel_function *cancel_fn, void *extra_state, MPI_Request *request) {
  static const char fn[] = "MPI_Grequest_start";
  st_rank *R = st_need(fn);
  if (!query_fn || !free_fn || !cancel_fn || !request)
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL %s argument",
                     !request ? "request" : !query_fn ? "query_fn" : !free_fn ? "free_fn" : "cancel_fn");
  greq *g = xmalloc(sizeof *g);
  *g = (greq){query_fn, free_fn, cancel_fn, extra_state};
  return req_start(&greq_kind, g, request);
}

int PMPI_Grequest_complete(MPI_Request request) {
  static const char fn[] = "MPI_Grequest_complete";
  st_rank *R = st_need(fn);
  st_req *q = st_req_get(R, request);
  if (!q || q->kind != RQ_KIND || q->ops != &greq_kind || q->state != RS_ACTIVE)
    return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "request 0x%x is %s", (unsigned)request,
                     !q ? "not a request of this rank's"
                        : q->ops != &greq_kind || q->kind != RQ_KIND ? "not a generalized request"
                                                                      : "complete already");
  int err = req_complete(request);
  return err ? err_raise(R, NULL, err, fn, "its free_fn failed (error %d)", err) : MPI_SUCCESS;
}

/* ==== the status setters ================================================== */

/* MPI_Status_set_elements(_x): dtype_api.c, beside MPI_Get_elements. */

int PMPI_Status_set_cancelled(MPI_Status *status, int flag) {
  static const char fn[] = "MPI_Status_set_cancelled";
  st_rank *R = st_need(fn);
  if (!status || status == MPI_STATUS_IGNORE) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL status argument");
  status->tsmpi_cancelled = flag != 0;
  return MPI_SUCCESS;
}
