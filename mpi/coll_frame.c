/* coll_frame.c -- what every MPI collective does around its algorithm: the rank's label for a
 * deadlock report, argument checks, packing (coll.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "coll.h"
#include "dtype.h"
#include "mp.h"
#include "op.h"
#include "p2p.h"

static void describe(void *ud, char *buf, size_t len) {
  const tsmpi_label *l = ud;
  if (l->root >= 0)
    snprintf(buf, len, "%s(root=%d, %s)", l->fn, l->root, l->comm_name);
  else
    snprintf(buf, len, "%s(%s)", l->fn, l->comm_name);
}

/* The group and the label of a call on a checked communicator. */
void tsmpi_coll_begin(tsmpi_cg *g, tsmpi_label *l, const char *fn, MPI_Comm comm, tsmpi_coll which, int root) {
  g->comm = comm;
  g->rank = tsmpi_comm_rank(comm);
  g->size = tsmpi_comm_size(comm);
  g->tag = 1 + (int)which;
  g->fn = fn;
  l->fn = fn;
  l->comm = comm;
  l->comm_name = tsmpi_comm_name(comm);   /* now: the report is made outside the rank */
  l->root = root;
  mp *self = mp_self();
  mp_call_begin(self, fn);   /* the trace shows the call as one slice */
  mp_label(self, describe, l);
}

int tsmpi_coll_end(int rc) {
  mp *self = mp_self();
  mp_label(self, NULL, NULL);
  mp_call_end(self);
  return rc;
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

/* ==== packing ============================================================= */

char *tsmpi_coll_pack(const tsmpi_cg *g, const void *buf, int count, MPI_Datatype dt) {
  size_t n = tsmpi_type_size(dt) * (size_t)count;
  char *p = tsmpi_cg_alloc(g, n);
  if (n) tsmpi_type_pack(buf, count, dt, p);
  return p;
}

void tsmpi_coll_unpack(const char *p, void *buf, int count, MPI_Datatype dt) {
  size_t n = tsmpi_type_size(dt) * (size_t)count;
  if (n) tsmpi_type_unpack(p, n, buf, count, dt);
}

/* Element i of dt at buf (i * extent bytes on). */
void *tsmpi_coll_at(const void *buf, MPI_Aint i, MPI_Datatype dt) {
  return (char *)buf + i * tsmpi_type_extent(dt);
}
