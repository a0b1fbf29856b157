/* coll_transport.c -- point-to-point on a communicator's collective context, for the
 * collectives and the other parts of the MPI layer (core.h). */
#include "mpi/core.h"

#include <stdio.h>
#include <stdlib.h>

#include "mpi/comm.h"
#include "mpi/engine.h"
#include "mpi/err.h"
#include "mpi/pt2pt.h"

int coll_p2p_send(const void *buf, int count, MPI_Datatype dt, int dst, int tag, MPI_Comm comm) {
  st_rank *R = st_need("coll_p2p_send");
  st_comm *c = st_comm_must(R, comm, "coll_p2p_send");
  if (dst == MPI_PROC_NULL) return MPI_SUCCESS;
  st_req q;
  st_req_stack(&q);
  pt2pt_send_fill(&q, c, 1, SM_STANDARD, buf, count, dt, dst, tag, comm, "coll_p2p_send");
  return pt2pt_send_start(R, &q, c);
}

int coll_p2p_recv(void *buf, int count, MPI_Datatype dt, int src, int tag, MPI_Comm comm,
                  MPI_Status *st) {
  st_rank *R = st_need("coll_p2p_recv");
  st_comm *c = st_comm_must(R, comm, "coll_p2p_recv");
  st_req q;
  st_req_stack(&q);
  pt2pt_recv_fill(&q, c, 1, buf, count, dt, src, tag, comm, "coll_p2p_recv");
  pt2pt_recv_block(R, &q);
  pt2pt_status_out(st, &q.st, 1);
  return q.st.MPI_ERROR;
}

int coll_p2p_sendrecv(const void *sbuf, int scount, MPI_Datatype sdt, int dst, int stag,
                      void *rbuf, int rcount, MPI_Datatype rdt, int src, int rtag, MPI_Comm comm,
                      MPI_Status *st) {
  st_rank *R = st_need("coll_p2p_sendrecv");
  st_comm *c = st_comm_must(R, comm, "coll_p2p_sendrecv");
  st_req s;
  st_req_stack(&s);
  pt2pt_send_fill(&s, c, 1, SM_STANDARD, sbuf, scount, sdt, dst, stag, comm, "coll_p2p_sendrecv");
  s.byref = 1;   /* sbuf stays the call's until the receive is done */
  int rc = pt2pt_send_start(R, &s, c);
  if (rc) return rc;
  rc = coll_p2p_recv(rbuf, rcount, rdt, src, rtag, comm, st);
  eng_settle(R, &s);
  return rc;
}

int coll_p2p_isend(const void *buf, int count, MPI_Datatype dt, int dst, int tag, MPI_Comm comm,
                   MPI_Request *req) {
  st_rank *R = st_need("coll_p2p_isend");
  st_comm *c = st_comm_must(R, comm, "coll_p2p_isend");
  st_req *q = st_req_new(R);
  pt2pt_send_fill(q, c, 1, SM_STANDARD, buf, count, dt, dst, tag, comm, "coll_p2p_isend");
  pt2pt_send_start(R, q, c);
  *req = st_req_handle(q);
  return MPI_SUCCESS;
}

int coll_p2p_irecv(void *buf, int count, MPI_Datatype dt, int src, int tag, MPI_Comm comm,
                   MPI_Request *req) {
  st_rank *R = st_need("coll_p2p_irecv");
  st_comm *c = st_comm_must(R, comm, "coll_p2p_irecv");
  st_req *q = st_req_new(R);
  pt2pt_recv_fill(q, c, 1, buf, count, dt, src, tag, comm, "coll_p2p_irecv");
  dtype_hold(dt);
  q->held = 1;
  pt2pt_recv_start(R, q);
  *req = st_req_handle(q);
  return MPI_SUCCESS;
}

int coll_p2p_waitall(int n, MPI_Request *reqs, MPI_Status *sts) {
  st_rank *R = st_need("coll_p2p_waitall");
  int first = MPI_SUCCESS;
  for (int i = 0; i < n; i++) {
    MPI_Status *st = sts == MPI_STATUSES_IGNORE ? MPI_STATUS_IGNORE : &sts[i];
    if (reqs[i] == MPI_REQUEST_NULL) {
      if (st != MPI_STATUS_IGNORE) pt2pt_status_empty(st);
      continue;
    }
    st_req *q = st_req_get(R, reqs[i]);
    if (!q) {
      fprintf(stderr, "tilesim MPI: internal error: rank %d: coll_p2p_waitall of request 0x%x\n", R->wrank,
              (unsigned)reqs[i]);
      abort();
    }
    if (q->state == RS_ACTIVE) eng_wait(R, q);
    pt2pt_status_out(st, &q->st, 1);
    if (q->st.MPI_ERROR && !first) first = q->st.MPI_ERROR;
    st_req_free(R, q);
    reqs[i] = MPI_REQUEST_NULL;
  }
  if (first && sts != MPI_STATUSES_IGNORE) return MPI_ERR_IN_STATUS;
  return first;
}

/* ==== the nonblocking collectives' requests and progress ================== */

static st_req *req_of(st_rank *R, MPI_Request h, const char *fn) {
  st_req *q = st_req_get(R, h);
  if (q) return q;
  fprintf(stderr, "tilesim MPI: internal error: rank %d: %s of request 0x%x\n", R->wrank, fn, (unsigned)h);
  abort();
}

void coll_p2p_watch(MPI_Request req) {
  st_rank *R = st_need("coll_p2p_watch");
  req_of(R, req, "coll_p2p_watch")->watch = 1;
}

int coll_p2p_done(MPI_Request *req, MPI_Status *st) {
  if (*req == MPI_REQUEST_NULL) {
    if (st != MPI_STATUS_IGNORE) pt2pt_status_empty(st);
    return 1;
  }
  st_rank *R = st_need("coll_p2p_done");
  st_req *q = req_of(R, *req, "coll_p2p_done");
  if (q->state == RS_ACTIVE) return 0;
  pt2pt_status_out(st, &q->st, 1);
  st_req_free(R, q);
  *req = MPI_REQUEST_NULL;
  return 1;
}

void coll_p2p_drop(MPI_Request *req) {
  st_rank *R = st_need("coll_p2p_drop");
  if (*req == MPI_REQUEST_NULL) return;
  st_req *q = req_of(R, *req, "coll_p2p_drop");
  if (q->state == RS_ACTIVE && q->kind == RQ_RECV) eng_unpost(R, q);
  st_req_free(R, q);
  *req = MPI_REQUEST_NULL;
}

/* mp's progress while the rank computes: at each arrival, act on what came
 * (the progress function runs from the engine; requests of a kind of their
 * own advance in MPI calls only, core.h). */
static void computing(mp *self, void *ud) {
  (void)ud;
  st_rank *R = mp_user(self);
  eng_take(R);
}

void coll_set_progress(void (*fn)(void), int live) {
  st_rank *R = st_need("coll_set_progress");
  R->progress = fn;
  mp_set_progress(R->self, fn && live ? computing : NULL, NULL);
}

MPI_Request coll_req(const char *fn, MPI_Comm comm, int root) {
  st_rank *R = st_need(fn);
  st_comm *c = st_comm_must(R, comm, fn);
  st_req *q = st_req_new(R);
  q->kind = RQ_COLL;
  q->state = RS_ACTIVE;
  q->fn = fn;
  q->comm = comm;
  q->pair = c->pair;
  q->peer = root;
  q->tag = MPI_ANY_TAG;
  pt2pt_status_empty(&q->st);
  return st_req_handle(q);
}

void coll_req_complete(MPI_Request req, int err) {
  st_rank *R = st_need("coll_req_complete");
  st_req *q = req_of(R, req, "coll_req_complete");
  q->st.MPI_ERROR = err;
  q->state = RS_DONE;
  if (q->freed) st_req_free(R, q);
}
