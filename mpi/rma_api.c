/* rma_api.c -- MPI's one-sided operations (MPI 3.1 section 11.3): MPI_Put,
 * MPI_Get, MPI_Accumulate, MPI_Get_accumulate, MPI_Fetch_and_op,
 * MPI_Compare_and_swap and the request-based MPI_Rput, MPI_Rget,
 * MPI_Raccumulate, MPI_Rget_accumulate: their arguments checked, the
 * target's memory found, the operation issued (rma.c).
 *
 * The origin's and the target's elements may be of any datatypes whose
 * type signatures agree (the same number of bytes: tilesim checks the
 * sizes); an accumulate's are all of one predefined type (a pair type for
 * MPI_MINLOC and MPI_MAXLOC), the same on both sides, and its operation is
 * predefined, MPI_REPLACE or MPI_NO_OP.  An operation of no bytes, and one
 * to MPI_PROC_NULL, does nothing.  The target's elements must lie inside
 * its window (a dynamic window: inside a region attached there), or the
 * call fails with MPI_ERR_RMA_RANGE; an operation outside an access epoch
 * to the target fails with MPI_ERR_RMA_SYNC. */
#include "mpi/win.h"

#include <stdint.h>
#include <stdlib.h>

#include "mpi/dtype.h"
#include "mpi/err.h"
#include "mpi/op.h"
#include "mpi/pt2pt.h"

/* ==== checks ============================================================== */

/* What one call gives: the window, the target's displacement, and the
 * operation (win.h: its taddr is found from disp once the call is checked). */
typedef struct {
  const char *fn;
  st_rank *R;
  rma_window *w;
  MPI_Aint disp;
  rma_args a;
} call;

static int type_ok(const call *c, const char *what, MPI_Datatype dt) {
  char why[128] = "";
  if (dtype_check(dt, why, sizeof why) == MPI_SUCCESS) return MPI_SUCCESS;
  return rma_win_raise(c->R, c->w, MPI_ERR_TYPE, c->fn, "invalid %s datatype: %s", what, why);
}

static int count_ok(const call *c, const char *what, int n) {
  if (n >= 0) return MPI_SUCCESS;
  return rma_win_raise(c->R, c->w, MPI_ERR_COUNT, c->fn, "invalid %s count %d (must be >= 0)", what, n);
}

static int buf_ok(const call *c, const char *what, const void *buf, int n, MPI_Datatype dt) {
  if (buf || dtype_bottom_ok(dt, n)) return MPI_SUCCESS;
  return rma_win_raise(c->R, c->w, MPI_ERR_BUFFER, c->fn, "NULL %s buffer for %d element%s", what, n, n == 1 ? "" : "s");
}

static size_t bytes(int n, MPI_Datatype dt) { return (size_t)n * dtype_size(dt); }

/* The target's elements inside its memory: their address in *taddr, or
 * MPI_ERR_RMA_RANGE raised. */
static int target_at(const call *c, char **taddr) {
  rma_window *w = c->w;
  rma_part *p = &w->sh->part[c->a.target];
  MPI_Aint lb = dtype_true_lb(c->a.tdt), ext = dtype_extent(c->a.tdt), tex = dtype_true_extent(c->a.tdt);
  MPI_Aint lo = lb, hi = c->a.tcount ? (MPI_Aint)(c->a.tcount - 1) * ext + lb + tex : lb;
  if (ext < 0) lo += (MPI_Aint)(c->a.tcount - 1) * ext, hi = lb + tex;
  if (w->flavor == MPI_WIN_FLAVOR_DYNAMIC) {
    char *a = (char *)(intptr_t)c->disp;
    int in = 0;
    pthread_mutex_lock(&w->sh->mu);
    for (int i = 0; i < p->nregs && !in; i++)
      in = a + lo >= p->regs[i].base && a + hi <= p->regs[i].base + p->regs[i].size;
    pthread_mutex_unlock(&w->sh->mu);
    *taddr = a;
    if (in) return MPI_SUCCESS;
    return rma_win_raise(c->R, w, MPI_ERR_RMA_RANGE, c->fn, "address %p (%td bytes) is not in a region attached at rank %d",
                         (void *)(a + lo), (ptrdiff_t)(hi - lo), c->a.target);
  }
  MPI_Aint off = c->disp * p->disp_unit;
  *taddr = p->base + off;
  if (off + lo >= 0 && off + hi <= p->size) return MPI_SUCCESS;
  return rma_win_raise(c->R, w, MPI_ERR_RMA_RANGE, c->fn,
                       "bytes %td to %td of rank %d's window, which has %td", (ptrdiff_t)(off + lo),
                       (ptrdiff_t)(off + hi), c->a.target, (ptrdiff_t)p->size);
}

/* An accumulate's elements and operation. */
static int acc_ok(const call *c) {
  char why[128];
  if (op_valid(c->a.op, why, sizeof why) != MPI_SUCCESS)
    return rma_win_raise(c->R, c->w, MPI_ERR_OP, c->fn, "%s", why);
  if (!op_is_predefined(c->a.op))
    return rma_win_raise(c->R, c->w, MPI_ERR_OP, c->fn, "a user operation (accumulates take predefined ones)");
  MPI_Count per;
  int te = dtype_elem(c->a.tdt, &per);
  if (!te && bytes(c->a.tcount, c->a.tdt))
    return rma_win_raise(c->R, c->w, MPI_ERR_TYPE, c->fn, "the target datatype's elements are of several predefined types");
  int carries = c->a.op != MPI_NO_OP && c->a.kind != OP_GET;
  if (carries && bytes(c->a.ocount, c->a.odt)) {
    int oe = dtype_elem(c->a.odt, &per);
    if (oe != te)
      return rma_win_raise(c->R, c->w, MPI_ERR_TYPE, c->fn,
                           "the origin's and the target's elements are not of one predefined type");
  }
  if (te && c->a.op != MPI_REPLACE && c->a.op != MPI_NO_OP &&
      op_check(c->a.op, (MPI_Datatype)(3 << 24 | te), why, sizeof why) != MPI_SUCCESS)
    return rma_win_raise(c->R, c->w, MPI_ERR_OP, c->fn, "%s", why);
  return MPI_SUCCESS;
}

/* Check a call; MPI_SUCCESS and *go = 1 if it moves anything. */
static int check(call *c, MPI_Win win, int *go) {
  *go = 0;
  st_rank *R = c->R = st_need(c->fn);
  int rc = rma_win_check(R, win, c->fn, &c->w);
  if (rc) return rc;
  rma_window *w = c->w;
  int carries = c->a.kind == OP_PUT || c->a.kind == OP_ACC || c->a.kind == OP_CAS ||
                (c->a.kind == OP_GACC && c->a.op != MPI_NO_OP);
  int fetches = c->a.kind == OP_GET || c->a.kind == OP_GACC || c->a.kind == OP_CAS;
  if (carries && ((rc = count_ok(c, "origin", c->a.ocount)) || (rc = type_ok(c, "origin", c->a.odt)))) return rc;
  if (c->a.kind == OP_GACC && (rc = count_ok(c, "result", c->a.rcount))) return rc;
  if (c->a.kind != OP_GET && c->a.kind != OP_PUT && c->a.kind != OP_ACC && (rc = type_ok(c, "result", c->a.rdt))) return rc;
  if (c->a.kind == OP_GET && ((rc = count_ok(c, "origin", c->a.rcount)) || (rc = type_ok(c, "origin", c->a.rdt)))) return rc;
  if ((rc = count_ok(c, "target", c->a.tcount)) || (rc = type_ok(c, "target", c->a.tdt))) return rc;
  if (c->a.target != MPI_PROC_NULL && (c->a.target < 0 || c->a.target >= w->size))
    return rma_win_raise(R, w, MPI_ERR_RANK, c->fn, "invalid target rank %d (the window has %d rank%s)", c->a.target,
                         w->size, w->size == 1 ? "" : "s");
  if ((c->a.kind == OP_ACC || c->a.kind == OP_GACC) && (rc = acc_ok(c))) return rc;
  size_t tb = bytes(c->a.tcount, c->a.tdt);
  if (carries && bytes(c->a.ocount, c->a.odt) != tb)
    return rma_win_raise(R, w, MPI_ERR_SIZE, c->fn, "the origin's %zu bytes and the target's %zu differ",
                         bytes(c->a.ocount, c->a.odt), tb);
  if (fetches && bytes(c->a.rcount, c->a.rdt) != tb)
    return rma_win_raise(R, w, MPI_ERR_SIZE, c->fn, "the %s %zu bytes and the target's %zu differ",
                         c->a.kind == OP_GET ? "origin's" : "result's", bytes(c->a.rcount, c->a.rdt), tb);
  if (c->a.target == MPI_PROC_NULL || tb == 0) return MPI_SUCCESS;
  if (carries && (rc = buf_ok(c, "origin", c->a.obuf, c->a.ocount, c->a.odt))) return rc;
  if (fetches && (rc = buf_ok(c, c->a.kind == OP_GET ? "origin" : "result", c->a.rbuf, c->a.rcount, c->a.rdt))) return rc;
  if (c->a.kind == OP_CAS && (rc = buf_ok(c, "compare", c->a.compare, 1, c->a.tdt))) return rc;
  if (!w->fence && !w->lockall && !rma_locked(w, c->a.target) && !rma_access_has(w, c->a.target))
    return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, c->fn, "rank %d is in no access epoch of this rank's", c->a.target);
  *go = 1;
  return MPI_SUCCESS;
}

/* Check and issue; the request-based forms (req not NULL) get a request
 * that completes with the operation locally. */
static int run(call *c, MPI_Win win, MPI_Request *req) {
  if (req) *req = MPI_REQUEST_NULL;
  int go, rc = check(c, win, &go);
  if (rc) return rc;
  rma_done d = {.applied = 1, .at = -1};
  if (go) {
    if ((rc = target_at(c, &c->a.taddr))) return rc;
    int fetches = c->a.kind == OP_GET || c->a.kind == OP_GACC || c->a.kind == OP_CAS;
    rma_issue(c->R, c->w, &c->a, req && fetches ? &d : NULL);
    if (req && fetches) rma_wait_done(c->R, c->w, &d);
  }
  if (req) {
    st_req *q = st_req_new(c->R);
    q->kind = RQ_SEND;
    q->state = RS_DONE;
    q->fn = c->fn;
    q->comm = c->w->comm;
    q->peer = MPI_PROC_NULL;
    pt2pt_status_empty(&q->st);
    *req = st_req_handle(q);
  }
  return MPI_SUCCESS;
}

static int request_arg(const char *fn, MPI_Win win, MPI_Request *request) {
  if (request) return MPI_SUCCESS;
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  return rc ? rc : rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL request argument");
}

/* ==== the calls =========================================================== */

#define PUT_CALL(name, kindv)                                                                                   \
  call c = {.fn = name, .disp = target_disp, .a.kind = kindv, .a.target = target_rank, .a.tcount = target_count, \
            .a.tdt = target_datatype}

int PMPI_Put(const void *origin_addr, int origin_count, MPI_Datatype origin_datatype, int target_rank,
             MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Win win) {
  PUT_CALL("MPI_Put", OP_PUT);
  c.a.obuf = origin_addr, c.a.ocount = origin_count, c.a.odt = origin_datatype;
  return run(&c, win, NULL);
}

int PMPI_Rput(const void *origin_addr, int origin_count, MPI_Datatype origin_datatype, int target_rank,
              MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Win win,
              MPI_Request *request) {
  PUT_CALL("MPI_Rput", OP_PUT);
  c.a.obuf = origin_addr, c.a.ocount = origin_count, c.a.odt = origin_datatype;
  int rc = request_arg(c.fn, win, request);
  return rc ? rc : run(&c, win, request);
}

int PMPI_Get(void *origin_addr, int origin_count, MPI_Datatype origin_datatype, int target_rank,
             MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Win win) {
  PUT_CALL("MPI_Get", OP_GET);
  c.a.rbuf = origin_addr, c.a.rcount = origin_count, c.a.rdt = origin_datatype;
  return run(&c, win, NULL);
}

int PMPI_Rget(void *origin_addr, int origin_count, MPI_Datatype origin_datatype, int target_rank,
              MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Win win,
              MPI_Request *request) {
  PUT_CALL("MPI_Rget", OP_GET);
  c.a.rbuf = origin_addr, c.a.rcount = origin_count, c.a.rdt = origin_datatype;
  int rc = request_arg(c.fn, win, request);
  return rc ? rc : run(&c, win, request);
}

int PMPI_Accumulate(const void *origin_addr, int origin_count, MPI_Datatype origin_datatype, int target_rank,
                    MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Op op, MPI_Win win) {
  PUT_CALL("MPI_Accumulate", OP_ACC);
  c.a.obuf = origin_addr, c.a.ocount = origin_count, c.a.odt = origin_datatype, c.a.op = op;
  return run(&c, win, NULL);
}

int PMPI_Raccumulate(const void *origin_addr, int origin_count, MPI_Datatype origin_datatype, int target_rank,
                     MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Op op, MPI_Win win,
                     MPI_Request *request) {
  PUT_CALL("MPI_Raccumulate", OP_ACC);
  c.a.obuf = origin_addr, c.a.ocount = origin_count, c.a.odt = origin_datatype, c.a.op = op;
  int rc = request_arg(c.fn, win, request);
  return rc ? rc : run(&c, win, request);
}

int PMPI_Get_accumulate(const void *origin_addr, int origin_count, MPI_Datatype origin_datatype,
                        void *result_addr, int result_count, MPI_Datatype result_datatype, int target_rank,
                        MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Op op,
                        MPI_Win win) {
  PUT_CALL("MPI_Get_accumulate", OP_GACC);
  c.a.obuf = origin_addr, c.a.ocount = origin_count, c.a.odt = origin_datatype, c.a.op = op;
  c.a.rbuf = result_addr, c.a.rcount = result_count, c.a.rdt = result_datatype;
  return run(&c, win, NULL);
}

int PMPI_Rget_accumulate(const void *origin_addr, int origin_count, MPI_Datatype origin_datatype,
                         void *result_addr, int result_count, MPI_Datatype result_datatype, int target_rank,
                         MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Op op,
                         MPI_Win win, MPI_Request *request) {
  PUT_CALL("MPI_Rget_accumulate", OP_GACC);
  c.a.obuf = origin_addr, c.a.ocount = origin_count, c.a.odt = origin_datatype, c.a.op = op;
  c.a.rbuf = result_addr, c.a.rcount = result_count, c.a.rdt = result_datatype;
  int rc = request_arg(c.fn, win, request);
  return rc ? rc : run(&c, win, request);
}

int PMPI_Fetch_and_op(const void *origin_addr, void *result_addr, MPI_Datatype datatype, int target_rank,
                      MPI_Aint target_disp, MPI_Op op, MPI_Win win) {
  call c = {.fn = "MPI_Fetch_and_op", .disp = target_disp, .a.kind = OP_GACC, .a.target = target_rank,
            .a.tcount = 1, .a.tdt = datatype, .a.obuf = origin_addr, .a.ocount = 1, .a.odt = datatype,
            .a.rbuf = result_addr, .a.rcount = 1, .a.rdt = datatype, .a.op = op};
  return run(&c, win, NULL);
}

int PMPI_Compare_and_swap(const void *origin_addr, const void *compare_addr, void *result_addr,
                          MPI_Datatype datatype, int target_rank, MPI_Aint target_disp, MPI_Win win) {
  call c = {.fn = "MPI_Compare_and_swap", .disp = target_disp, .a.kind = OP_CAS, .a.target = target_rank,
            .a.tcount = 1, .a.tdt = datatype, .a.obuf = origin_addr, .a.ocount = 1, .a.odt = datatype,
            .a.rbuf = result_addr, .a.rcount = 1, .a.rdt = datatype, .a.op = MPI_REPLACE, .a.compare = compare_addr};
  return run(&c, win, NULL);
}
