/* coll_errors.c -- argument errors of the collectives and of the datatype and operation calls
 * under MPI_ERRORS_RETURN: a root out of range (MPI_ERR_ROOT), a negative count
 * (MPI_ERR_COUNT), MPI_DATATYPE_NULL and an uncommitted type (MPI_ERR_TYPE), MPI_OP_NULL and
 * an operation that does not apply (MPI_ERR_OP), MPI_COMM_NULL and (under tilesim) a freed
 * communicator (MPI_ERR_COMM), MPI_IN_PLACE where it is not allowed, a negative count in a v collective; every rank makes
 * the same bad call, so no rank waits for another, and a good collective afterwards still
 * works.  Plain MPI C (mtest.h): the same line under Open MPI and tilesim. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

static int cls(int rc) {
  int c = rc;
  if (rc != MPI_SUCCESS) MPI_Error_class(rc, &c);
  return c;
}

/* Each refusal by its error class; then the collectives still work. */
static void refusals(mtest *t) {
  int size = t->size, buf[8] = {0}, out[8] = {0}, counts[64], displs[64];
  int *all = malloc((size_t)size * 8 * sizeof(int));
  if (!all) MPI_Abort(MPI_COMM_WORLD, 3);
  for (int r = 0; r < size && r < 64; r++) counts[r] = 1, displs[r] = r;
  counts[0] = -1;

  int rc = MPI_Bcast(buf, 1, MPI_INT, size, MPI_COMM_WORLD);
  MCHECK(t, cls(rc) == MPI_ERR_ROOT, "MPI_Bcast with root %d of %d: class %d", size, size, cls(rc));
  rc = MPI_Reduce(buf, out, 1, MPI_INT, MPI_SUM, -1, MPI_COMM_WORLD);
  MCHECK(t, cls(rc) == MPI_ERR_ROOT, "MPI_Reduce with root -1: class %d", cls(rc));
  rc = MPI_Allreduce(buf, out, -1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  MCHECK(t, cls(rc) == MPI_ERR_COUNT, "MPI_Allreduce of -1 elements: class %d", cls(rc));
  rc = MPI_Bcast(buf, 1, MPI_DATATYPE_NULL, 0, MPI_COMM_WORLD);
  MCHECK(t, cls(rc) == MPI_ERR_TYPE, "MPI_Bcast of MPI_DATATYPE_NULL: class %d", cls(rc));
  MPI_Datatype two;
  MPI_Type_contiguous(2, MPI_INT, &two);   /* not committed */
  rc = MPI_Allgather(buf, 1, two, all, 1, two, MPI_COMM_WORLD);
  MCHECK(t, cls(rc) == MPI_ERR_TYPE, "MPI_Allgather of an uncommitted type: class %d", cls(rc));
  MPI_Type_free(&two);
  rc = MPI_Allreduce(buf, out, 1, MPI_INT, MPI_OP_NULL, MPI_COMM_WORLD);
  MCHECK(t, cls(rc) == MPI_ERR_OP, "MPI_Allreduce with MPI_OP_NULL: class %d", cls(rc));
  double d[2] = {1, 2}, e[2];
  rc = MPI_Allreduce(d, e, 2, MPI_DOUBLE, MPI_BXOR, MPI_COMM_WORLD);
  MCHECK(t, cls(rc) == MPI_ERR_OP, "MPI_Allreduce of doubles with MPI_BXOR: class %d", cls(rc));
  rc = MPI_Reduce(d, e, 1, MPI_DOUBLE, MPI_MAXLOC, 0, MPI_COMM_WORLD);
  MCHECK(t, cls(rc) == MPI_ERR_OP, "MPI_Reduce of a double with MPI_MAXLOC: class %d", cls(rc));
  rc = MPI_Gatherv(buf, -1, MPI_INT, all, counts, displs, MPI_INT, 0, MPI_COMM_WORLD);
  MCHECK(t, cls(rc) == MPI_ERR_COUNT, "MPI_Gatherv of -1 elements: class %d", cls(rc));
  if (t->rank != 0) {
    rc = MPI_Gather(MPI_IN_PLACE, 1, MPI_INT, all, 1, MPI_INT, 0, MPI_COMM_WORLD);
    MCHECK(t, rc != MPI_SUCCESS, "MPI_Gather with MPI_IN_PLACE on rank %d succeeded", t->rank);
  }
  rc = MPI_Bcast(MPI_IN_PLACE, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MCHECK(t, rc != MPI_SUCCESS, "MPI_Bcast of MPI_IN_PLACE succeeded");

#ifdef TSMPI_MPI_H
  /* A freed handle: tilesim's are integers it can check (Open MPI's are
   * pointers, and its MPI_Barrier crashes on one); this counts only when it
   * fails. */
  MPI_Comm dup;
  MPI_Comm_dup(MPI_COMM_WORLD, &dup);
  MPI_Comm gone = dup;
  MPI_Comm_free(&dup);
  rc = MPI_Barrier(gone);
  if (cls(rc) != MPI_ERR_COMM) MCHECK(t, 0, "MPI_Barrier on a freed communicator: class %d", cls(rc));
#endif
  rc = MPI_Barrier(MPI_COMM_NULL);
  MCHECK(t, cls(rc) == MPI_ERR_COMM, "MPI_Barrier on MPI_COMM_NULL: class %d", cls(rc));

  MPI_Op op = MPI_SUM;
  rc = MPI_Op_free(&op);
  MCHECK(t, cls(rc) == MPI_ERR_OP || cls(rc) == MPI_ERR_ARG, "MPI_Op_free(MPI_SUM): class %d", cls(rc));

  /* After all that, the collectives still work. */
  buf[0] = t->rank + 1;
  rc = MPI_Allreduce(buf, out, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  MCHECK(t, rc == MPI_SUCCESS && out[0] == size * (size + 1) / 2, "MPI_Allreduce after the errors: rc %d, %d", rc,
         out[0]);
  free(all);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {refusals, NULL};
  return mtest_main(&argc, &argv, "coll_errors", 1, MTEST_ERRORS_RETURN, checks);
}
