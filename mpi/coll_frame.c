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
  const tsmpi_label *l = ud;
  if (l->root >= 0)
    snprintf(buf, len, "%s(root=%d, %s)", l->fn, l->root, l->comm_name);
  else
    snprintf(buf, len, "%s(%s)", l->fn, l->comm_name);
}

/* A call's frame, in its schedule's memory. */
typedef struct {
  tsmpi_label l;
  MPI_Request *req;   /* nonblocking: the program's request */
} frame;

tsmpi_sched *tsmpi_coll_start(const char *fn, MPI_Comm comm, tsmpi_coll which, int root, MPI_Request *req) {
  tsmpi_cg g = {comm, tsmpi_comm_rank(comm), tsmpi_comm_size(comm), 1 + (int)which, fn};
  if (req) g.tag = tsmpi_comm_nbc_tag(comm);
  tsmpi_sched *s = tsmpi_sched_new(&g, NULL, req == NULL);
  frame *f = tsmpi_sched_mem(s, sizeof *f);
  f->req = req;
  f->l.fn = fn;
  f->l.comm = comm;
  f->l.comm_name = tsmpi_comm_name(comm);   /* now: the report is made outside the rank */
  f->l.root = root;
  tsmpi_sched_set_frame(s, f);
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

int tsmpi_coll_finish(tsmpi_sched *s) {
  frame *f = tsmpi_sched_frame(s);
  if (f->req) {
    MPI_Request *req = f->req;
    tsmpi_nbc_start(s, f->l.fn, f->l.comm, f->l.root, req);
    return end(MPI_SUCCESS);
  }
  return end(tsmpi_sched_run(s));
}

int tsmpi_coll_ran(const char *fn, MPI_Comm comm, int rc, MPI_Request *req) {
  if (!req) return tsmpi_raise(comm, MPI_ERR_ARG, fn, "NULL request argument");
  *req = MPI_REQUEST_NULL;
  if (rc) return rc;
  *req = tsmpi_req_coll(fn, comm, -1);
  tsmpi_req_coll_complete(*req, MPI_SUCCESS);
  return MPI_SUCCESS;
}

int tsmpi_coll_fail(tsmpi_sched *s, int rc) {
  tsmpi_sched_free(s);
  return end(rc);
}

/* ==== argument checks ===================================================== */

int tsmpi_coll_type_ok(MPI_Comm comm, const char *fn, const char *what, MPI_Datatype dt) {
  char why[96];
  if (tsmpi_type_check(dt, why, sizeof why) == MPI_SUCCESS) return MPI_SUCCESS;
  return tsmpi_raise(comm, MPI_ERR_TYPE, fn, "invalid %s: %s", what, why);
}

int tsmpi_coll_op_ok(MPI_Comm comm, const char *fn, MPI_Op op, MPI_Datatype dt) {
  char why[128];
  if (tsmpi_op_valid(op, why, sizeof why) != MPI_SUCCESS)
    return tsmpi_raise(comm, MPI_ERR_OP, fn, "invalid operation: %s", why);
  if (tsmpi_op_check(op, dt, why, sizeof why) != MPI_SUCCESS) return tsmpi_raise(comm, MPI_ERR_OP, fn, "%s", why);
  return MPI_SUCCESS;
}

/* count elements of dt in buf (count and dt checked). */
int tsmpi_coll_data_ok(MPI_Comm comm, const char *fn, const char *what, const void *buf, int count, MPI_Datatype dt) {
  int rc;
  if ((rc = tsmpi_check_count(comm, fn, count)) || (rc = tsmpi_coll_type_ok(comm, fn, what, dt))) return rc;
  if (buf == MPI_IN_PLACE) return MPI_SUCCESS;
  return tsmpi_check_buf(comm, fn, buf, count, dt);
}

/* Counts and displacements of a v collective (counts >= 0). */
int tsmpi_coll_counts_ok(MPI_Comm comm, const char *fn, const char *what, const int *counts, const int *displs, int n) {
  if (!counts || (displs == NULL && what[0] != 'r'))
    return tsmpi_raise(comm, MPI_ERR_ARG, fn, "%s is NULL", counts ? "a displacement array" : what);
  for (int i = 0; i < n; i++)
    if (counts[i] < 0) return tsmpi_raise(comm, MPI_ERR_COUNT, fn, "%s[%d] = %d < 0", what, i, counts[i]);
  return MPI_SUCCESS;
}

int tsmpi_coll_in_place_bad(MPI_Comm comm, const char *fn, const char *which) {
  return tsmpi_raise(comm, MPI_ERR_BUFFER, fn, "MPI_IN_PLACE is not allowed as %s here", which);
}

int tsmpi_coll_req_ok(MPI_Comm comm, const char *fn, const MPI_Request *req) {
  return req ? MPI_SUCCESS : tsmpi_raise(comm, MPI_ERR_ARG, fn, "NULL request argument");
}

/* ==== packing ============================================================= */

char *tsmpi_coll_pack(tsmpi_sched *s, const void *buf, int count, MPI_Datatype dt) {
  size_t n = tsmpi_type_size(dt) * (size_t)count;
  char *p = tsmpi_sched_mem(s, n);
  if (n) tsmpi_type_pack(buf, count, dt, p);
  return p;
}

/* Element i of dt at buf (i * extent bytes on). */
void *tsmpi_coll_at(const void *buf, MPI_Aint i, MPI_Datatype dt) {
  return (char *)buf + i * tsmpi_type_extent(dt);
}
