/* coll_transport.c -- point-to-point on a communicator's collective context, for the
 * collectives and the other parts of the MPI layer (core.h). */
#include "mpi/core.h"

#include <stdio.h>
#include <stdlib.h>

#include "mpi/comm.h"
#include "mpi/engine.h"
#include "mpi/err.h"
#include "mpi/pt2pt.h"

int tsmpi_p2p_send(const void *buf, int count, MPI_Datatype dt, int dst, int tag, MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_p2p_send");
  tsm_comm *c = tsm_comm_must(R, comm, "tsmpi_p2p_send");
  if (dst == MPI_PROC_NULL) return MPI_SUCCESS;
  tsm_req q;
  tsm_req_stack(&q);
  tsm_send_fill(&q, c, 1, SM_STANDARD, buf, count, dt, dst, tag, comm, "tsmpi_p2p_send");
  return tsm_send_start(R, &q, c);
}

int tsmpi_p2p_recv(void *buf, int count, MPI_Datatype dt, int src, int tag, MPI_Comm comm,
                   MPI_Status *st) {
  tsm *R = tsm_need("tsmpi_p2p_recv");
  tsm_comm *c = tsm_comm_must(R, comm, "tsmpi_p2p_recv");
  tsm_req q;
  tsm_req_stack(&q);
  tsm_recv_fill(&q, c, 1, buf, count, dt, src, tag, comm, "tsmpi_p2p_recv");
  tsm_recv_block(R, &q);
  tsm_status_out(st, &q.st, 1);
  return q.st.MPI_ERROR;
}

int tsmpi_p2p_sendrecv(const void *sbuf, int scount, MPI_Datatype sdt, int dst, int stag,
                       void *rbuf, int rcount, MPI_Datatype rdt, int src, int rtag, MPI_Comm comm,
                       MPI_Status *st) {
  tsm *R = tsm_need("tsmpi_p2p_sendrecv");
  tsm_comm *c = tsm_comm_must(R, comm, "tsmpi_p2p_sendrecv");
  tsm_req s;
  tsm_req_stack(&s);
  tsm_send_fill(&s, c, 1, SM_STANDARD, sbuf, scount, sdt, dst, stag, comm, "tsmpi_p2p_sendrecv");
  s.byref = 1;   /* sbuf stays the call's until the receive is done */
  int rc = tsm_send_start(R, &s, c);
  if (rc) return rc;
  rc = tsmpi_p2p_recv(rbuf, rcount, rdt, src, rtag, comm, st);
  eng_settle(R, &s);
  return rc;
}

int tsmpi_p2p_isend(const void *buf, int count, MPI_Datatype dt, int dst, int tag, MPI_Comm comm,
                    MPI_Request *req) {
  tsm *R = tsm_need("tsmpi_p2p_isend");
  tsm_comm *c = tsm_comm_must(R, comm, "tsmpi_p2p_isend");
  tsm_req *q = tsm_req_new(R);
  tsm_send_fill(q, c, 1, SM_STANDARD, buf, count, dt, dst, tag, comm, "tsmpi_p2p_isend");
  tsm_send_start(R, q, c);
  *req = tsm_req_handle(q);
  return MPI_SUCCESS;
}

int tsmpi_p2p_irecv(void *buf, int count, MPI_Datatype dt, int src, int tag, MPI_Comm comm,
                    MPI_Request *req) {
  tsm *R = tsm_need("tsmpi_p2p_irecv");
  tsm_comm *c = tsm_comm_must(R, comm, "tsmpi_p2p_irecv");
  tsm_req *q = tsm_req_new(R);
  tsm_recv_fill(q, c, 1, buf, count, dt, src, tag, comm, "tsmpi_p2p_irecv");
  tsmpi_type_hold(dt);
  q->held = 1;
  tsm_recv_start(R, q);
  *req = tsm_req_handle(q);
  return MPI_SUCCESS;
}

int tsmpi_p2p_waitall(int n, MPI_Request *reqs, MPI_Status *sts) {
  tsm *R = tsm_need("tsmpi_p2p_waitall");
  int first = MPI_SUCCESS;
  for (int i = 0; i < n; i++) {
    MPI_Status *st = sts == MPI_STATUSES_IGNORE ? MPI_STATUS_IGNORE : &sts[i];
    if (reqs[i] == MPI_REQUEST_NULL) {
      if (st != MPI_STATUS_IGNORE) tsm_status_empty(st);
      continue;
    }
    tsm_req *q = tsm_req_get(R, reqs[i]);
    if (!q) {
      fprintf(stderr, "tilesim MPI: internal error: rank %d: tsmpi_p2p_waitall of request 0x%x\n", R->wrank,
              (unsigned)reqs[i]);
      abort();
    }
    if (q->state == RS_ACTIVE) eng_wait(R, q);
    tsm_status_out(st, &q->st, 1);
    if (q->st.MPI_ERROR && !first) first = q->st.MPI_ERROR;
    tsm_req_free(R, q);
    reqs[i] = MPI_REQUEST_NULL;
  }
  if (first && sts != MPI_STATUSES_IGNORE) return MPI_ERR_IN_STATUS;
  return first;
}

/* ==== the nonblocking collectives' requests and progress ================== */

static tsm_req *req_of(tsm *R, MPI_Request h, const char *fn) {
  tsm_req *q = tsm_req_get(R, h);
  if (q) return q;
  fprintf(stderr, "tilesim MPI: internal error: rank %d: %s of request 0x%x\n", R->wrank, fn, (unsigned)h);
  abort();
}

void tsmpi_p2p_watch(MPI_Request req) {
  tsm *R = tsm_need("tsmpi_p2p_watch");
  req_of(R, req, "tsmpi_p2p_watch")->watch = 1;
}

int tsmpi_p2p_done(MPI_Request *req, MPI_Status *st) {
  if (*req == MPI_REQUEST_NULL) {
    if (st != MPI_STATUS_IGNORE) tsm_status_empty(st);
    return 1;
  }
  tsm *R = tsm_need("tsmpi_p2p_done");
  tsm_req *q = req_of(R, *req, "tsmpi_p2p_done");
  if (q->state == RS_ACTIVE) return 0;
  tsm_status_out(st, &q->st, 1);
  tsm_req_free(R, q);
  *req = MPI_REQUEST_NULL;
  return 1;
}

void tsmpi_p2p_drop(MPI_Request *req) {
  tsm *R = tsm_need("tsmpi_p2p_drop");
  if (*req == MPI_REQUEST_NULL) return;
  tsm_req *q = req_of(R, *req, "tsmpi_p2p_drop");
  if (q->state == RS_ACTIVE && q->kind == RQ_RECV) eng_unpost(R, q);
  tsm_req_free(R, q);
  *req = MPI_REQUEST_NULL;
}

/* mp's progress while the rank computes: at each arrival, act on what came
 * (the progress function runs from the engine; requests of a kind of their
 * own advance in MPI calls only, core.h). */
static void computing(mp *self, void *ud) {
  (void)ud;
  tsm *R = mp_user(self);
  eng_take(R);
}

void tsmpi_set_progress(void (*fn)(void), int live) {
  tsm *R = tsm_need("tsmpi_set_progress");
  R->progress = fn;
  mp_set_progress(R->self, fn && live ? computing : NULL, NULL);
}

MPI_Request tsmpi_req_coll(const char *fn, MPI_Comm comm, int root) {
  tsm *R = tsm_need(fn);
  tsm_comm *c = tsm_comm_must(R, comm, fn);
  tsm_req *q = tsm_req_new(R);
  q->kind = RQ_COLL;
  q->state = RS_ACTIVE;
  q->fn = fn;
  q->comm = comm;
  q->pair = c->pair;
  q->peer = root;
  q->tag = MPI_ANY_TAG;
  tsm_status_empty(&q->st);
  return tsm_req_handle(q);
}

void tsmpi_req_coll_complete(MPI_Request req, int err) {
  tsm *R = tsm_need("tsmpi_req_coll_complete");
  tsm_req *q = req_of(R, req, "tsmpi_req_coll_complete");
  q->st.MPI_ERROR = err;
  q->state = RS_DONE;
  if (q->freed) tsm_req_free(R, q);
}
