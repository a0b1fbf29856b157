/* pt2pt.c -- MPI's point-to-point calls: the four send modes, blocking and
 * nonblocking and persistent, receives, Sendrecv, probes, MPI_Get_count,
 * the attached buffer. */
#include "mpi/pt2pt.h"

#include <stdlib.h>
#include <string.h>

#include "mpi/engine.h"
#include "mpi/init.h"
#include "mpi/err.h"
#include "mpi/label.h"
#include "mpi/spin.h"
#include "util/xmem.h"

/* ==== starting sends and receives ========================================= */

void pt2pt_send_fill(st_req *q, const st_comm *c, int coll, int mode, const void *buf, int count,
                     MPI_Datatype dt, int dst, int tag, MPI_Comm comm, const char *fn) {
  q->next = q->prev = NULL;
  q->kind = RQ_SEND;
  q->mode = (unsigned char)mode;
  q->state = RS_INACTIVE;
  q->persistent = q->freed = 0;
  q->msglen = q->cap = 0;
  q->contig = NULL;
  q->g = NULL;
  q->buf = (void *)buf;
  q->count = count;
  q->dt = dt;
  q->peer = dst;
  q->tag = tag;
  q->comm = comm;
  q->pair = c->pair;
  q->fn = fn;
  q->wpeer = dst >= 0 ? st_world_of(c, dst) : -1;
  q->ctx = 2 * c->pair + coll;
  /* A request's send goes by reference, settled when the request ends (a
   * buffered one is copied into the attached buffer, which the next one
   * reuses). */
  q->byref = q->slot >= 0 && mode != SM_BUFFERED;
  q->ref = NULL;
  q->tmp = NULL;
  q->prom = NULL;
}

void pt2pt_status_empty(MPI_Status *st) {
  *st = (MPI_Status){.MPI_SOURCE = MPI_ANY_SOURCE, .MPI_TAG = MPI_ANY_TAG, .MPI_ERROR = MPI_SUCCESS};
}

int pt2pt_send_start(st_rank *R, st_req *q, const st_comm *c) {
  if (q->peer == MPI_PROC_NULL) {
    pt2pt_status_empty(&q->st);
    q->state = RS_DONE;
    return MPI_SUCCESS;
  }
  size_t len = (size_t)q->count * dtype_size(q->dt);
  if (q->mode == SM_BUFFERED) {
    /* The message is copied into the attached buffer and leaves at once
     * (eager): the space is free again when the call returns. */
    size_t need = len + MPI_BSEND_OVERHEAD;
    if (!R->bbuf || need > (size_t)R->bsize) {
      pt2pt_status_empty(&q->st);
      q->state = RS_DONE;
      if (!R->bbuf)
        return err_raise(R, c, MPI_ERR_BUFFER, q->fn,
                         "no buffer attached (MPI_Buffer_attach) for a %zu-byte message", len);
      return err_raise(R, c, MPI_ERR_BUFFER, q->fn,
                       "a %zu-byte message needs %zu bytes of the attached buffer "
                       "(MPI_BSEND_OVERHEAD = %d more), which has %d",
                       len, need, MPI_BSEND_OVERHEAD, R->bsize);
    }
    /* A request's (MPI_Ibsend, MPI_Bsend_init) goes by reference from a
     * copy of its own, freed when the request ends: it can be cancelled
     * (withdrawn) until a receive reads it, as MPICH's can. */
    void *to = q->slot >= 0 ? xmalloc(len ? len : 1) : R->bbuf;
    const void *p = dtype_contig(q->buf, q->count, q->dt);
    if (p)
      memcpy(to, p, len);
    else
      dtype_pack(q->buf, q->count, q->dt, to);
    q->byref = q->slot >= 0;
    eng_send(R, q, to, len);
    if (q->slot >= 0) q->tmp = to;
    return MPI_SUCCESS;
  }
  const void *p = len ? dtype_contig(q->buf, q->count, q->dt) : NULL;
  if (p || len == 0) {
    eng_send(R, q, p, len);
  } else {
    void *tmp = xmalloc(len);
    dtype_pack(q->buf, q->count, q->dt, tmp);
    eng_send(R, q, tmp, len);
    if (q->ref)
      q->tmp = tmp;   /* the message refers to it until settled */
    else
      free(tmp);
  }
  if (q->slot < 0 && q->ref) eng_hold(R, q);   /* a blocking call's: the rank's end settles it */
  return MPI_SUCCESS;
}

void pt2pt_recv_fill(st_req *q, const st_comm *c, int coll, void *buf, int count, MPI_Datatype dt,
                     int src, int tag, MPI_Comm comm, const char *fn) {
  q->next = q->prev = NULL;
  q->kind = RQ_RECV;
  q->mode = SM_STANDARD;
  q->state = RS_INACTIVE;
  q->persistent = q->freed = 0;
  q->msglen = 0;
  q->buf = buf;
  q->count = count;
  q->dt = dt;
  q->peer = src;
  q->tag = tag;
  q->comm = comm;
  q->pair = c->pair;
  q->fn = fn;
  q->wpeer = src >= 0 ? st_world_of(c, src) : MP_ANY;
  q->ctx = 2 * c->pair + coll;
  q->cap = (size_t)count * dtype_size(dt);
  q->contig = q->cap ? (void *)dtype_contig(buf, count, dt) : NULL;
  q->g = c->g;
  q->byref = 0;
  q->ref = NULL;
  q->tmp = NULL;
  q->prom = NULL;
}

static void proc_null(st_req *q) {
  q->st = (MPI_Status){.MPI_SOURCE = MPI_PROC_NULL, .MPI_TAG = MPI_ANY_TAG, .MPI_ERROR = MPI_SUCCESS};
  q->msglen = 0;
  q->g = NULL;
  q->state = RS_DONE;
}

void pt2pt_recv_start(st_rank *R, st_req *q) {
  if (q->peer == MPI_PROC_NULL)
    proc_null(q);
  else
    eng_recv_start(R, q);
}

void pt2pt_recv_block(st_rank *R, st_req *q) {
  if (q->peer == MPI_PROC_NULL)
    proc_null(q);
  else
    eng_recv(R, q);
}

void pt2pt_status_out(MPI_Status *out, const MPI_Status *in, int with_error) {
  if (out == MPI_STATUS_IGNORE) return;
  out->MPI_SOURCE = in->MPI_SOURCE;
  out->MPI_TAG = in->MPI_TAG;
  if (with_error) out->MPI_ERROR = in->MPI_ERROR;
  out->tsmpi_cancelled = in->tsmpi_cancelled;
  out->tsmpi_count = in->tsmpi_count;
}

/* ==== argument checks ===================================================== */

/* A predefined type whose elements lie back to back (its size is its
 * extent): that size; 0 for any other type (created ones, the pair types
 * with padding, MPI_DATATYPE_NULL), which the datatype module answers for.
 * One call where check, size and contig would be five. */
static inline size_t dense_predef(MPI_Datatype dt) {
  if (((unsigned)dt & 0xff800000u) != 0x03000000u) return 0;
  const dtype_predef *p = dtype_predef_get((int)((unsigned)dt & 0x7fffffu));
  return p && p->size == p->extent ? (size_t)p->size : 0;
}

/* A call's path out of its common case's code (no registers saved there). */
#if defined(__GNUC__)
#define SIDE __attribute__((noinline))
#else
#define SIDE
#endif

/* dt passes dtype_check (out of line: not the fast paths' own case). */
static SIDE int type_fine(MPI_Datatype dt) {
  char why[64];
  return dtype_check(dt, why, sizeof why) == MPI_SUCCESS;
}

/* Every argument but the type fine, in a few compares (c NULL: the
 * communicator is not). */
static inline int args_plain(const st_comm *c, const void *buf, int count, int peer, int tag, int any_ok) {
  if (!c || count < 0) return 0;
  if ((unsigned)tag > ST_TAG_UB && !(any_ok && tag == MPI_ANY_TAG)) return 0;
  if ((unsigned)peer >= (unsigned)c->size && peer != MPI_PROC_NULL && !(any_ok && peer == MPI_ANY_SOURCE))
    return 0;
  return buf || !count;
}

/* The common case: args_plain and the type; anything odd goes through the
 * checks one by one, which say what is wrong.  *es: dense_predef(dt). */
static inline int args_fine(st_comm *c, const void *buf, int count, MPI_Datatype dt, int peer, int tag,
                            int any_ok, size_t *es) {
  *es = 0;
  if (!args_plain(c, buf, count, peer, tag, any_ok)) return 0;
  if ((*es = dense_predef(dt))) return 1;
  return type_fine(dt);
}

/* A send's (any_ok 0: dst) or a receive's (any_ok 1: src, wildcards
 * allowed) arguments: MPI_SUCCESS and *cp, or the first error raised. */
static int peer_args(st_rank *R, const char *fn, const void *buf, int count, MPI_Datatype dt, int peer, int tag,
                     MPI_Comm comm, int any_ok, st_comm **cp) {
  st_comm *c = comm == MPI_COMM_WORLD ? &R->world : st_comm_get(R, comm);
  *cp = c;
  size_t es;
  if (args_fine(c, buf, count, dt, peer, tag, any_ok, &es)) return MPI_SUCCESS;
  int rc;
  if ((rc = err_check_comm(R, comm, fn, cp))) return rc;
  if ((rc = err_check_count(R, c, fn, count))) return rc;
  if ((rc = err_check_type(R, c, fn, dt))) return rc;
  if ((rc = err_check_tag(R, c, fn, tag, any_ok))) return rc;
  if ((rc = err_check_peer(R, c, fn, peer, any_ok))) return rc;
  return err_check_buf(R, c, fn, buf, count, dt);
}

static int send_args(st_rank *R, const char *fn, const void *buf, int count, MPI_Datatype dt, int dst,
                     int tag, MPI_Comm comm, st_comm **cp) {
  return peer_args(R, fn, buf, count, dt, dst, tag, comm, 0, cp);
}

static int recv_args(st_rank *R, const char *fn, const void *buf, int count, MPI_Datatype dt, int src,
                     int tag, MPI_Comm comm, st_comm **cp) {
  return peer_args(R, fn, buf, count, dt, src, tag, comm, 1, cp);
}

static int recv_result(st_rank *R, const st_comm *c, const st_req *q) {
  if (q->st.MPI_ERROR == MPI_SUCCESS) return MPI_SUCCESS;
  return pt2pt_req_error(R, c, q, q->fn);
}

int pt2pt_req_error(st_rank *R, const st_comm *c, const st_req *q, const char *fn) {
  int other = fn != q->fn;   /* completed by MPI_Wait*, MPI_Test* */
  return err_raise(R, c, MPI_ERR_TRUNCATE, fn,
                   "%s%sa %zu-byte message from rank %d (tag %d) is longer than the receive buffer "
                   "(%d elements, %zu bytes): truncated",
                   other ? q->fn : "", other ? ": " : "", q->msglen,
                   q->st.MPI_SOURCE, q->st.MPI_TAG, q->count, q->cap);
}

/* ==== blocking sends ====================================================== */

static int send_block(const char *fn, int mode, const void *buf, int count, MPI_Datatype dt, int dst,
                      int tag, MPI_Comm comm) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = send_args(R, fn, buf, count, dt, dst, tag, comm, &c);
  if (rc || dst == MPI_PROC_NULL) return rc;
  st_req q;
  st_req_stack(&q);
  pt2pt_send_fill(&q, c, 0, mode, buf, count, dt, dst, tag, comm, fn);
  if ((rc = pt2pt_send_start(R, &q, c))) return rc;
  if (q.state == RS_ACTIVE) {   /* synchronous: until the receive starts */
    label_rec l = {.fn = fn, .what = L_SEND, .peer = dst, .tag = tag, .pair = c->pair};
    label_set(R, &l);
    eng_wait(R, &q);
    label_clear(R);
  }
  return MPI_SUCCESS;
}

/* MPI_Send but its commonest case: a contiguous message leaves from the
 * buffer, anything else by send_block. */
static SIDE int send_general(st_rank *R, const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
                             MPI_Comm comm) {
  static const char fn[] = "MPI_Send";
  st_comm *c = comm == MPI_COMM_WORLD ? &R->world : st_comm_get(R, comm);
  size_t es;
  if (args_fine(c, buf, count, datatype, dest, tag, 0, &es) && dest != MPI_PROC_NULL) {
    size_t len = (size_t)count * (es ? es : dtype_size(datatype));
    const void *p = !len ? NULL : es ? buf : dtype_contig(buf, count, datatype);
    if (p || !len) return eng_send_data(R, st_world_of(c, dest), 2 * c->pair, tag, p, len);
  }
  return send_block(fn, SM_STANDARD, buf, count, datatype, dest, tag, comm);
}

int PMPI_Send(const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm) {
  st_rank *R = st_need("MPI_Send");
  /* The fast path: a dense predefined type on MPI_COMM_WORLD, the same
   * message send_general sends. */
  size_t es;
  if (comm == MPI_COMM_WORLD && dest != MPI_PROC_NULL && args_plain(&R->world, buf, count, dest, tag, 0) &&
      (es = dense_predef(datatype))) {
    size_t len = (size_t)count * es;
    return eng_send_data(R, st_world_of(&R->world, dest), 2 * R->world.pair, tag, len ? buf : NULL, len);
  }
  return send_general(R, buf, count, datatype, dest, tag, comm);
}

int PMPI_Ssend(const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm) {
  return send_block("MPI_Ssend", SM_SYNC, buf, count, datatype, dest, tag, comm);
}

int PMPI_Rsend(const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm) {
  return send_block("MPI_Rsend", SM_READY, buf, count, datatype, dest, tag, comm);
}

int PMPI_Bsend(const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm) {
  return send_block("MPI_Bsend", SM_BUFFERED, buf, count, datatype, dest, tag, comm);
}

/* ==== nonblocking and persistent sends ==================================== */

static int send_req(const char *fn, int mode, int persistent, const void *buf, int count,
                    MPI_Datatype dt, int dst, int tag, MPI_Comm comm, MPI_Request *request) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = send_args(R, fn, buf, count, dt, dst, tag, comm, &c);
  if (rc) return rc;
  if (!request) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL request argument");
  st_req *q = st_req_new(R);
  pt2pt_send_fill(q, c, 0, mode, buf, count, dt, dst, tag, comm, fn);
  if (persistent) {
    dtype_hold(dt);   /* MPI_Type_free may come before the last MPI_Start */
    q->held = 1;
    q->persistent = 1;
    q->state = RS_INACTIVE;
    pt2pt_status_empty(&q->st);
  } else if ((rc = pt2pt_send_start(R, q, c))) {
    st_req_free(R, q);
    *request = MPI_REQUEST_NULL;
    return rc;
  }
  *request = st_req_handle(q);
  return MPI_SUCCESS;
}

int PMPI_Isend(const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm,
              MPI_Request *request) {
  return send_req("MPI_Isend", SM_STANDARD, 0, buf, count, datatype, dest, tag, comm, request);
}

int PMPI_Issend(const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm,
               MPI_Request *request) {
  return send_req("MPI_Issend", SM_SYNC, 0, buf, count, datatype, dest, tag, comm, request);
}

int PMPI_Irsend(const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm,
               MPI_Request *request) {
  return send_req("MPI_Irsend", SM_READY, 0, buf, count, datatype, dest, tag, comm, request);
}

int PMPI_Ibsend(const void *buf, int count, MPI_Datatype datatype, int dest, int tag, MPI_Comm comm,
               MPI_Request *request) {
  return send_req("MPI_Ibsend", SM_BUFFERED, 0, buf, count, datatype, dest, tag, comm, request);
}

int PMPI_Send_init(const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
                  MPI_Comm comm, MPI_Request *request) {
  return send_req("MPI_Send_init", SM_STANDARD, 1, buf, count, datatype, dest, tag, comm, request);
}

int PMPI_Ssend_init(const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
                   MPI_Comm comm, MPI_Request *request) {
  return send_req("MPI_Ssend_init", SM_SYNC, 1, buf, count, datatype, dest, tag, comm, request);
}

int PMPI_Rsend_init(const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
                   MPI_Comm comm, MPI_Request *request) {
  return send_req("MPI_Rsend_init", SM_READY, 1, buf, count, datatype, dest, tag, comm, request);
}

int PMPI_Bsend_init(const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
                   MPI_Comm comm, MPI_Request *request) {
  return send_req("MPI_Bsend_init", SM_BUFFERED, 1, buf, count, datatype, dest, tag, comm, request);
}

/* ==== receives ============================================================ */

static const char recv_fn[] = "MPI_Recv";

/* A blocking receive by a request on the stack, matched by the engine (its
 * label set by the caller, cleared here). */
static SIDE int recv_queued(st_rank *R, st_comm *c, void *buf, int count, MPI_Datatype datatype, int source,
                            int tag, MPI_Comm comm, MPI_Status *status) {
  st_req q;
  st_req_stack(&q);
  pt2pt_recv_fill(&q, c, 0, buf, count, datatype, source, tag, comm, recv_fn);
  pt2pt_recv_block(R, &q);
  label_clear(R);
  pt2pt_status_out(status, &q.st, 0);
  return recv_result(R, c, &q);
}

/* The receive's fast way: the source's next message, straight into a
 * contiguous buffer of cap bytes at p, when it is the one (1, the status
 * filled); else 0, the message left to the engine. */
static inline int recv_next(st_rank *R, const st_comm *c, void *p, size_t cap, int source, int tag,
                            MPI_Status *status) {
  mp_status got;
  if (!eng_recv_data(R, source >= 0 ? st_world_of(c, source) : MP_ANY, 2 * c->pair, tag, p, cap, &got)) return 0;
  label_clear(R);
  if (status != MPI_STATUS_IGNORE) {
    status->MPI_SOURCE = c->g->world ? st_comm_rank_of(c, got.source) : got.source;
    status->MPI_TAG = got.tag;
    status->tsmpi_cancelled = 0;
    status->tsmpi_count = (MPI_Count)got.len;
  }
  return 1;
}

/* MPI_Recv but its commonest case. */
static SIDE int recv_general(st_rank *R, void *buf, int count, MPI_Datatype datatype, int source, int tag,
                             MPI_Comm comm, MPI_Status *status) {
  const char *fn = recv_fn;
  st_comm *c = comm == MPI_COMM_WORLD ? &R->world : st_comm_get(R, comm);
  int rc;
  size_t es;
  if (!args_fine(c, buf, count, datatype, source, tag, 1, &es) &&
      (rc = recv_args(R, fn, buf, count, datatype, source, tag, comm, &c)))
    return rc;
  label_rec l = {.fn = fn, .what = L_RECV, .peer = source, .tag = tag, .pair = c->pair};
  label_set(R, &l);
  if (source != MPI_PROC_NULL && !R->nunexp && !R->posted) {
    /* The fast way, when the buffer is contiguous. */
    size_t cap = (size_t)count * (es ? es : dtype_size(datatype));
    void *p = !cap ? NULL : es ? buf : (void *)dtype_contig(buf, count, datatype);
    if ((p || !cap) && recv_next(R, c, p, cap, source, tag, status)) return MPI_SUCCESS;
  }
  return recv_queued(R, c, buf, count, datatype, source, tag, comm, status);
}

int PMPI_Recv(void *buf, int count, MPI_Datatype datatype, int source, int tag, MPI_Comm comm,
             MPI_Status *status) {
  st_rank *R = st_need(recv_fn);
  /* The fast path: a dense predefined type on MPI_COMM_WORLD, nothing
   * posted or unexpected; what recv_general does then. */
  size_t es;
  if (comm == MPI_COMM_WORLD && source != MPI_PROC_NULL && !R->nunexp && !R->posted &&
      args_plain(&R->world, buf, count, source, tag, 1) && (es = dense_predef(datatype))) {
    st_comm *c = &R->world;
    size_t cap = (size_t)count * es;
    label_rec l = {.fn = recv_fn, .what = L_RECV, .peer = source, .tag = tag, .pair = c->pair};
    label_set(R, &l);
    if (recv_next(R, c, cap ? buf : NULL, cap, source, tag, status)) return MPI_SUCCESS;
    return recv_queued(R, c, buf, count, datatype, source, tag, comm, status);
  }
  return recv_general(R, buf, count, datatype, source, tag, comm, status);
}

static int recv_req(const char *fn, int persistent, void *buf, int count, MPI_Datatype dt, int src,
                    int tag, MPI_Comm comm, MPI_Request *request) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = recv_args(R, fn, buf, count, dt, src, tag, comm, &c);
  if (rc) return rc;
  if (!request) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL request argument");
  st_req *q = st_req_new(R);
  pt2pt_recv_fill(q, c, 0, buf, count, dt, src, tag, comm, fn);
  dtype_hold(dt);   /* MPI_Type_free may come before the receive completes */
  q->held = 1;
  if (persistent) {
    q->persistent = 1;
    q->state = RS_INACTIVE;
    q->g = NULL;
    pt2pt_status_empty(&q->st);
  } else {
    pt2pt_recv_start(R, q);
  }
  *request = st_req_handle(q);
  return MPI_SUCCESS;
}

int PMPI_Irecv(void *buf, int count, MPI_Datatype datatype, int source, int tag, MPI_Comm comm,
              MPI_Request *request) {
  return recv_req("MPI_Irecv", 0, buf, count, datatype, source, tag, comm, request);
}

int PMPI_Recv_init(void *buf, int count, MPI_Datatype datatype, int source, int tag, MPI_Comm comm,
                  MPI_Request *request) {
  return recv_req("MPI_Recv_init", 1, buf, count, datatype, source, tag, comm, request);
}

/* ==== send and receive ==================================================== */

/* Both calls: the send is eager, so it leaves before the receive waits;
   Sendrecv's goes by reference, settled when the call returns (the
   receiver may copy it straight from sendbuf), Sendrecv_replace's is
   copied out at once, so that its buffer is free to receive into. */
static int sendrecv(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype,
                    int dest, int sendtag, void *recvbuf, int recvcount, MPI_Datatype recvtype,
                    int source, int recvtag, MPI_Comm comm, MPI_Status *status) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = send_args(R, fn, sendbuf, sendcount, sendtype, dest, sendtag, comm, &c);
  if (rc) return rc;
  if ((rc = recv_args(R, fn, recvbuf, recvcount, recvtype, source, recvtag, comm, &c))) return rc;
  st_req s, q;
  st_req_stack(&s);
  st_req_stack(&q);
  pt2pt_send_fill(&s, c, 0, SM_STANDARD, sendbuf, sendcount, sendtype, dest, sendtag, comm, fn);
  s.byref = sendbuf != recvbuf;   /* Sendrecv_replace's send is copied out before the receive */
  pt2pt_send_start(R, &s, c);
  pt2pt_recv_fill(&q, c, 0, recvbuf, recvcount, recvtype, source, recvtag, comm, fn);
  label_rec l = {.fn = fn, .what = L_SENDRECV, .peer = dest, .tag = sendtag, .peer2 = source,
                 .tag2 = recvtag, .pair = c->pair};
  label_set(R, &l);
  pt2pt_recv_block(R, &q);
  label_clear(R);
  eng_settle(R, &s);
  pt2pt_status_out(status, &q.st, 0);
  return recv_result(R, c, &q);
}

int PMPI_Sendrecv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, int dest, int sendtag,
                 void *recvbuf, int recvcount, MPI_Datatype recvtype, int source, int recvtag,
                 MPI_Comm comm, MPI_Status *status) {
  return sendrecv("MPI_Sendrecv", sendbuf, sendcount, sendtype, dest, sendtag, recvbuf, recvcount,
                  recvtype, source, recvtag, comm, status);
}

int PMPI_Sendrecv_replace(void *buf, int count, MPI_Datatype datatype, int dest, int sendtag,
                         int source, int recvtag, MPI_Comm comm, MPI_Status *status) {
  return sendrecv("MPI_Sendrecv_replace", buf, count, datatype, dest, sendtag, buf, count, datatype,
                  source, recvtag, comm, status);
}

/* MPI-4's MPI_Isendrecv and MPI_Isendrecv_replace: the send leaves at once
 * (eager), the receive is posted; the request is the receive's and
 * completes with it, its status the receive's.  Isendrecv's send goes by
 * reference, settled when the request ends; Isendrecv_replace's is copied
 * out first (its buffer receives). */
static int isendrecv(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype, int dest,
                     int sendtag, void *recvbuf, int recvcount, MPI_Datatype recvtype, int source, int recvtag,
                     MPI_Comm comm, MPI_Request *request) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = send_args(R, fn, sendbuf, sendcount, sendtype, dest, sendtag, comm, &c);
  if (rc) return rc;
  if ((rc = recv_args(R, fn, recvbuf, recvcount, recvtype, source, recvtag, comm, &c))) return rc;
  if (!request) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL request argument");
  st_req s, *q = st_req_new(R);
  st_req_stack(&s);
  pt2pt_send_fill(&s, c, 0, SM_STANDARD, sendbuf, sendcount, sendtype, dest, sendtag, comm, fn);
  s.byref = sendbuf != recvbuf;
  pt2pt_send_start(R, &s, c);
  pt2pt_recv_fill(q, c, 0, recvbuf, recvcount, recvtype, source, recvtag, comm, fn);
  eng_unhold(R, &s);
  q->ref = s.ref;   /* the send's, settled when the request ends */
  q->tmp = s.tmp;
  dtype_hold(recvtype);
  q->held = 1;
  pt2pt_recv_start(R, q);
  *request = st_req_handle(q);
  return MPI_SUCCESS;
}

int PMPI_Isendrecv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, int dest, int sendtag,
                   void *recvbuf, int recvcount, MPI_Datatype recvtype, int source, int recvtag, MPI_Comm comm,
                   MPI_Request *request) {
  return isendrecv("MPI_Isendrecv", sendbuf, sendcount, sendtype, dest, sendtag, recvbuf, recvcount, recvtype,
                   source, recvtag, comm, request);
}

int PMPI_Isendrecv_replace(void *buf, int count, MPI_Datatype datatype, int dest, int sendtag, int source,
                           int recvtag, MPI_Comm comm, MPI_Request *request) {
  return isendrecv("MPI_Isendrecv_replace", buf, count, datatype, dest, sendtag, buf, count, datatype, source,
                   recvtag, comm, request);
}

/* ==== probes ============================================================== */

/* MPI_Probe and MPI_Iprobe, and with message, MPI_Mprobe and MPI_Improbe:
 * the message shown is taken out of matching into *message. */
static int probe(const char *fn, int block, int source, int tag, MPI_Comm comm, int *flag,
                 MPI_Message *message, int matched, MPI_Status *status) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc;
  if ((rc = err_check_comm(R, comm, fn, &c))) return rc;
  if ((rc = err_check_tag(R, c, fn, tag, 1))) return rc;
  if ((rc = err_check_peer(R, c, fn, source, 1))) return rc;
  if (!block && !flag) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL flag argument");
  if (matched && !message) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL message argument");
  if (source == MPI_PROC_NULL) {
    if (flag) *flag = 1;
    if (matched) *message = MPI_MESSAGE_NO_PROC;
    if (status != MPI_STATUS_IGNORE) {
      st_req q;
      st_req_stack(&q);
      proc_null(&q);
      pt2pt_status_out(status, &q.st, 0);
    }
    return MPI_SUCCESS;
  }
  int wsrc = source >= 0 ? st_world_of(c, source) : MP_ANY, src, mtag;
  size_t len;
  int found;
  st_msg *m = NULL;
  if (block) {
    label_rec l = {.fn = fn, .what = L_PROBE, .peer = source, .tag = tag, .pair = c->pair};
    label_set(R, &l);
    found = eng_probe(R, wsrc, 2 * c->pair, tag, 1, &src, &mtag, &len, matched ? &m : NULL);
    label_clear(R);
  } else {
    found = eng_probe(R, wsrc, 2 * c->pair, tag, 0, &src, &mtag, &len, matched ? &m : NULL);
  }
  if (flag) *flag = found;
  if (!found) {
    if (matched) *message = MPI_MESSAGE_NULL;
    double cost = init_poll_cost();
    if (cost > 0 && mp_busy(R->self, cost) != MP_OK) st_stopped(R);
    spin_count(R, fn);
    return MPI_SUCCESS;
  }
  spin_reset(R);
  if (matched) {
    m->comm = comm;
    *message = st_msg_handle(R, m);
  }
  if (status != MPI_STATUS_IGNORE) {
    status->MPI_SOURCE = st_comm_rank_of(c, src);
    status->MPI_TAG = mtag;
    status->tsmpi_cancelled = 0;
    status->tsmpi_count = (MPI_Count)len;
  }
  return MPI_SUCCESS;
}

int PMPI_Probe(int source, int tag, MPI_Comm comm, MPI_Status *status) {
  return probe("MPI_Probe", 1, source, tag, comm, NULL, NULL, 0, status);
}

int PMPI_Iprobe(int source, int tag, MPI_Comm comm, int *flag, MPI_Status *status) {
  return probe("MPI_Iprobe", 0, source, tag, comm, flag, NULL, 0, status);
}

int PMPI_Mprobe(int source, int tag, MPI_Comm comm, MPI_Message *message, MPI_Status *status) {
  return probe("MPI_Mprobe", 1, source, tag, comm, NULL, message, 1, status);
}

int PMPI_Improbe(int source, int tag, MPI_Comm comm, int *flag, MPI_Message *message, MPI_Status *status) {
  return probe("MPI_Improbe", 0, source, tag, comm, flag, message, 1, status);
}

/* MPI_Mrecv (request NULL) and MPI_Imrecv: the message a matched probe
 * took, received into buf (the request done at once). */
static int mrecv(const char *fn, void *buf, int count, MPI_Datatype dt, MPI_Message *message, MPI_Status *status,
                 MPI_Request *request, int nonblocking) {
  st_rank *R = st_need(fn);
  if (!message || (nonblocking && !request))
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL %s argument", message ? "request" : "message");
  st_req sq, *q = &sq;
  if (*message == MPI_MESSAGE_NO_PROC) {   /* from MPI_PROC_NULL: done, empty */
    if (nonblocking) {
      q = st_req_new(R);
      q->kind = RQ_RECV;
      q->fn = fn;
      q->comm = MPI_COMM_NULL;
      *request = st_req_handle(q);
    }
    proc_null(q);
    if (!nonblocking) pt2pt_status_out(status, &q->st, 0);
    *message = MPI_MESSAGE_NULL;
    return MPI_SUCCESS;
  }
  st_msg *m = st_msg_take(R, *message);
  if (!m)
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid message handle 0x%x (%s)", (unsigned)*message,
                     *message == MPI_MESSAGE_NULL ? "MPI_MESSAGE_NULL" : "received already, or not a message");
  st_comm *c = st_comm_get(R, m->comm);
  int rc = !c ? err_check_comm(R, m->comm, fn, &c) : err_check_count(R, c, fn, count);
  if (!rc) rc = err_check_type(R, c, fn, dt);
  if (!rc) rc = err_check_buf(R, c, fn, buf, count, dt);
  if (rc) {   /* the message stays the program's to receive */
    *message = st_msg_handle(R, m);
    return rc;
  }
  if (nonblocking) {
    q = st_req_new(R);
    *request = st_req_handle(q);
  } else {
    st_req_stack(q);
  }
  pt2pt_recv_fill(q, c, 0, buf, count, dt, st_comm_rank_of(c, m->src), m->tag, m->comm, fn);
  eng_msg_read(R, q, m);
  *message = MPI_MESSAGE_NULL;
  if (nonblocking) return MPI_SUCCESS;
  pt2pt_status_out(status, &q->st, 0);
  return recv_result(R, c, q);
}

int PMPI_Mrecv(void *buf, int count, MPI_Datatype datatype, MPI_Message *message, MPI_Status *status) {
  return mrecv("MPI_Mrecv", buf, count, datatype, message, status, NULL, 0);
}

int PMPI_Imrecv(void *buf, int count, MPI_Datatype datatype, MPI_Message *message, MPI_Request *request) {
  return mrecv("MPI_Imrecv", buf, count, datatype, message, MPI_STATUS_IGNORE, request, 1);
}

/* ==== counts ============================================================== */

int PMPI_Get_count(const MPI_Status *status, MPI_Datatype datatype, int *count) {
  static const char fn[] = "MPI_Get_count";
  st_rank *R = st_need(fn);
  int rc = err_check_type(R, NULL, fn, datatype);
  if (rc) return rc;
  if (!status || !count) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL status or count argument");
  size_t size = dtype_size(datatype);
  MPI_Count bytes = status->tsmpi_count;
  if (size == 0)
    *count = 0;   /* MPI 3.1 section 3.2.5: a type of size zero gives zero */
  else if (bytes % (MPI_Count)size)
    *count = MPI_UNDEFINED;
  else
    *count = (int)(bytes / (MPI_Count)size);
  return MPI_SUCCESS;
}

/* ==== the attached buffer ================================================= */

int PMPI_Buffer_attach(void *buffer, int size) {
  static const char fn[] = "MPI_Buffer_attach";
  st_rank *R = st_need(fn);
  if (R->bbuf)
    return err_raise(R, NULL, MPI_ERR_BUFFER, fn, "a buffer is attached already (%d bytes)", R->bsize);
  if (size < 0) return err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid size %d", size);
  if (!buffer && size > 0) return err_raise(R, NULL, MPI_ERR_BUFFER, fn, "NULL buffer of %d bytes", size);
  R->bbuf = buffer;
  R->bsize = size;
  return MPI_SUCCESS;
}

int PMPI_Buffer_detach(void *buffer_addr, int *size) {
  static const char fn[] = "MPI_Buffer_detach";
  st_rank *R = st_need(fn);
  if (!buffer_addr || !size) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL argument");
  /* Every buffered message has left already (they are eager). */
  void *b = R->bbuf;
  memcpy(buffer_addr, &b, sizeof b);
  *size = R->bbuf ? R->bsize : 0;
  R->bbuf = NULL;
  R->bsize = 0;
  return MPI_SUCCESS;
}
