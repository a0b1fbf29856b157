/* coll_frame.c -- what every MPI collective does around its algorithm: the start and the end
 * (blocking: the rank's label for a deadlock report, the schedule run; nonblocking: the
 * schedule started), argument checks, packing (coll.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/dtype.h"
#include "mp/mp.h"
#include "mpi/op.h"
#include "mpi/nbc.h"
#include "mpi/core.h"
#include "mpi/coll_sched.h"

static void describe(void *ud, char *buf, size_t len) {
  const coll_label *l = ud;
  if (l->root >= 0)
    snprintf(buf, len, "%s(root=%d, %s)", l->fn, l->root, l->comm_name);
  else
    snprintf(buf, len, "%s(%s)", l->fn, l->comm_name);
}

/* A call's frame, in its schedule's memory. */
typedef struct {
  coll_label l;
  MPI_Request *req;   /* nonblocking: the program's request */
} frame;

coll_sched *coll_start(const char *fn, MPI_Comm comm, coll_id which, int root, MPI_Request *req) {
  coll_cg g = {comm, comm_rank(comm), comm_size(comm), 1 + (int)which, fn};
  if (req) g.tag = comm_nbc_tag(comm);
  coll_sched *s = coll_sched_new(&g, NULL, req == NULL);
  frame *f = coll_sched_mem(s, sizeof *f);
  f->req = req;
  f->l.fn = fn;
  f->l.comm = comm;
  f->l.comm_name = comm_get_name(comm);   /* now: the report is made outside the rank */
  f->l.root = root;
  coll_sched_set_frame(s, f);
  mp *self = mp_self();
  mp_call_begin(self, fn);   /* the trace shows the call as one slice */
  if (!req) mp_label(self, describe, &f->l);
  return s;
}

static int end(int rc) {
  mp *self = mp_self();
  mp_label(self, NULL, NULL);
  mp_call_end(self);
  return rc;
}

int coll_finish(coll_sched *s) {
  frame *f = coll_sched_frame(s);
  if (f->req) {
    MPI_Request *req = f->req;
    nbc_start(s, f->l.fn, f->l.comm, f->l.root, req);
    return end(MPI_SUCCESS);
  }
  return end(coll_sched_run(s));
}

int coll_ran(const char *fn, MPI_Comm comm, int rc, MPI_Request *req) {
  if (!req) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL request argument");
  *req = MPI_REQUEST_NULL;
  if (rc) return rc;
  *req = coll_req(fn, comm, -1);
  coll_req_complete(*req, MPI_SUCCESS);
  return MPI_SUCCESS;
}

int coll_fail(coll_sched *s, int rc) {
  coll_sched_free(s);
  return end(rc);
}

/* ==== argument checks ===================================================== */

int coll_type_ok(MPI_Comm comm, const char *fn, const char *what, MPI_Datatype dt) {
  char why[96];
  if (dtype_check(dt, why, sizeof why) == MPI_SUCCESS) return MPI_SUCCESS;
  return err_comm_raise(comm, MPI_ERR_TYPE, fn, "invalid %s: %s", what, why);
}

int coll_op_ok(MPI_Comm comm, const char *fn, MPI_Op op, MPI_Datatype dt) {
  char why[128];
  if (op_valid(op, why, sizeof why) != MPI_SUCCESS)
    return err_comm_raise(comm, MPI_ERR_OP, fn, "invalid operation: %s", why);
  if (op_check(op, dt, why, sizeof why) != MPI_SUCCESS) return err_comm_raise(comm, MPI_ERR_OP, fn, "%s", why);
  return MPI_SUCCESS;
}

/* count elements of dt in buf (count and dt checked). */
int coll_data_ok(MPI_Comm comm, const char *fn, const char *what, const void *buf, int count, MPI_Datatype dt) {
  int rc;
  if ((rc = err_comm_check_count(comm, fn, count)) || (rc = coll_type_ok(comm, fn, what, dt))) return rc;
  if (buf == MPI_IN_PLACE) return MPI_SUCCESS;
  return err_comm_check_buf(comm, fn, buf, count, dt);
}

/* Counts and displacements of a v collective (counts >= 0). */
int coll_counts_ok(MPI_Comm comm, const char *fn, const char *what, const int *counts, const int *displs, int n) {
  if (!counts || (displs == NULL && what[0] != 'r'))
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "%s is NULL", counts ? "a displacement array" : what);
  for (int i = 0; i < n; i++)
    if (counts[i] < 0) return err_comm_raise(comm, MPI_ERR_COUNT, fn, "%s[%d] = %d < 0", what, i, counts[i]);
  return MPI_SUCCESS;
}

int coll_in_place_bad(MPI_Comm comm, const char *fn, const char *which) {
  return err_comm_raise(comm, MPI_ERR_BUFFER, fn, "MPI_IN_PLACE is not allowed as %s here", which);
}

int coll_req_ok(MPI_Comm comm, const char *fn, const MPI_Request *req) {
  return req ? MPI_SUCCESS : err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL request argument");
}

/* ==== packing ============================================================= */

char *coll_pack(coll_sched *s, const void *buf, int count, MPI_Datatype dt) {
  size_t n = dtype_size(dt) * (size_t)count;
  char *p = coll_sched_mem(s, n);
  if (n) dtype_pack(buf, count, dt, p);
  return p;
}

const char *coll_view(coll_sched *s, const void *buf, int count, MPI_Datatype dt) {
  const char *p = dtype_contig(buf, count, dt);
  return p ? p : coll_pack(s, buf, count, dt);
}

char *coll_place(coll_sched *s, void *buf, int count, MPI_Datatype dt, int fill) {
  char *p = (char *)dtype_contig(buf, count, dt);
  if (p) return p;
  return fill ? coll_pack(s, buf, count, dt) : coll_sched_mem(s, dtype_size(dt) * (size_t)count);
}

/* Block i's bytes where they lie contiguous, else NULL (coll_vdirect's blocks). */
static const char *vblock(const void *buf, const int *counts, const int *displs, const MPI_Datatype *types,
                          MPI_Datatype dt, int i) {
  if (types) return dtype_contig((const char *)buf + displs[i], counts[i], types[i]);
  return dtype_contig(coll_at(buf, displs[i], dt), counts[i], dt);
}

char *coll_vdirect(const void *buf, const int *counts, const int *displs, const MPI_Datatype *types, MPI_Datatype dt,
                   int n, const size_t *bytes, size_t *off) {
  const char *base = NULL;
  for (int i = 0; i < n; i++) {
    if (!bytes[i]) continue;
    const char *p = vblock(buf, counts, displs, types, dt, i);
    if (!p) return NULL;
    if (!base || p < base) base = p;
  }
  if (!base) return NULL;
  for (int i = 0; i < n; i++)
    off[i] = bytes[i] ? (size_t)(vblock(buf, counts, displs, types, dt, i) - base) : 0;
  return (char *)base;
}

/* Element i of dt at buf (i * extent bytes on). */
void *coll_at(const void *buf, MPI_Aint i, MPI_Datatype dt) {
  return (char *)buf + i * dtype_extent(dt);
}
