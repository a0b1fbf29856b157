/* coll_bcast.c -- MPI_Bcast from three roots at sizes on both sides of MPICH's thresholds
 * (12288 bytes; 524288 bytes on a power of two ranks; 8 ranks: one root for the long
 * ones), of MPI_INT, MPI_BYTE, MPI_DOUBLE and a non-contiguous type (every other int: the rest of the buffer must stay as
 * it was), and MPI_Barrier between them.  Every rank checks its buffer against the root's
 * values, computed locally.  Plain MPI C (mtest.h): the same "coll_bcast: P passed, F
 * failed" line under Open MPI and tilesim. */
#include <mpi.h>
#include <string.h>

#include "colldata.h"
#include "mtest.h"

static void one(mtest *t, MPI_Datatype dt, const char *name, int isize, int count, int stride, int root) {
  int n = count * stride;
  int *buf = xmalloc_or_abort((size_t)n * 8 + 8);   /* room for doubles too */
  unsigned char *b = (unsigned char *)buf;
  if (isize == 1) {
    for (int i = 0; i < count; i++) b[i] = (unsigned char)(t->rank == root ? val(root, i) : 0xee);
  } else if (isize == 8) {
    double *d = (double *)buf;
    for (int i = 0; i < count; i++) d[i] = t->rank == root ? dval(root, i) : -1e300;
  } else {
    for (int i = 0; i < n; i++) buf[i] = t->rank == root ? val(root, i) : i % stride ? -9 : -7;
  }
  int rc = MPI_Bcast(buf, count, dt, root, MPI_COMM_WORLD), bad = rc != MPI_SUCCESS;
  if (isize == 1) {
    for (int i = 0; i < count && !bad; i++) bad = b[i] != (unsigned char)val(root, i);
  } else if (isize == 8) {
    const double *d = (const double *)buf;
    for (int i = 0; i < count && !bad; i++) bad = d[i] != dval(root, i);
  } else {
    for (int i = 0; i < n && !bad; i++) bad = buf[i] != (t->rank != root && i % stride ? -9 : val(root, i));
  }
  MCHECK(t, !bad, "bcast of %d %s from root %d on %d ranks: rc %d or a wrong element", count, name, root, t->size, rc);
  free(buf);
}

/* Broadcasts of small sizes from three roots; the long-message ones from one. */
static void bcasts(mtest *t) {
  int size = t->size, roots[3] = {0, size - 1, size / 2};
  MPI_Datatype evens;   /* an int, then a gap of one int */
  MPI_Type_create_resized(MPI_INT, 0, 2 * (MPI_Aint)sizeof(int), &evens);
  MPI_Type_commit(&evens);
  /* Small sizes from three roots; the long-message ones from one. */
  static const int ints[] = {0, 1, 5, 3071, 3072};
  for (int k = 0; k < 3; k++) {
    int root = roots[k];
    if (k > 0 && (root == roots[0] || (k == 2 && root == roots[1]))) continue;
    for (size_t i = 0; i < sizeof ints / sizeof ints[0]; i++) one(t, MPI_INT, "MPI_INT", 4, ints[i], 1, root);
    one(t, MPI_BYTE, "MPI_BYTE", 1, 12287, 1, root);
    one(t, MPI_BYTE, "MPI_BYTE", 1, 12288, 1, root);
    one(t, MPI_DOUBLE, "MPI_DOUBLE", 8, 1537, 1, root);
    one(t, evens, "evens", 4, 3, 2, root);
    one(t, evens, "evens", 4, 3072, 2, root);
    MCHECK(t, MPI_Barrier(MPI_COMM_WORLD) == MPI_SUCCESS, "MPI_Barrier failed");
  }
  one(t, MPI_INT, "MPI_INT", 4, 131071, 1, size - 1);
  one(t, MPI_INT, "MPI_INT", 4, 131072, 1, size - 1);
  one(t, evens, "evens", 4, 70000, 2, size / 2);
  MPI_Type_free(&evens);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {bcasts, NULL};
  return mtest_main(&argc, &argv, "coll_bcast", 1, 0, checks);
}
