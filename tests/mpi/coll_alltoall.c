/* coll_alltoall.c -- MPI_Alltoall with blocks on both sides of MPICH's thresholds (256 bytes
 * on 8 ranks or more; 32768 bytes), send and receive types that differ but carry the same
 * data, MPI_IN_PLACE; MPI_Alltoallv with uneven and zero counts at displacements out of order,
 * MPI_IN_PLACE.  Every rank checks each block against the sender's values, computed locally.
 * Plain MPI C (mtest.h): the same line under Open MPI and tilesim. */
#include <mpi.h>
#include <string.h>

#include "colldata.h"
#include "mtest.h"

/* Element i of the block rank `from` sends rank `to`. */
static int blk(int from, int to, int i) { return val(from, i) ^ (to * 65537); }

static void alltoall(mtest *t, int count, int as_block, int in_place) {
  int me = t->rank, size = t->size;
  int *s = xmalloc_or_abort((size_t)count * (size_t)size * sizeof(int) + 4), *r = xmalloc_or_abort((size_t)count * (size_t)size * sizeof(int) + 4);
  MPI_Datatype b = MPI_INT;
  if (as_block && count > 0) {
    MPI_Type_contiguous(count, MPI_INT, &b);
    MPI_Type_commit(&b);
  }
  for (int d = 0; d < size; d++)
    for (int i = 0; i < count; i++) {
      s[d * count + i] = blk(me, d, i);
      r[d * count + i] = in_place ? blk(me, d, i) : -1;
    }
  int rc = MPI_Alltoall(in_place ? MPI_IN_PLACE : s, count, MPI_INT, r, b == MPI_INT ? count : 1, b, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  for (int f = 0; f < size && !bad; f++)
    for (int i = 0; i < count && !bad; i++) bad = r[f * count + i] != blk(f, me, i);
  MCHECK(t, !bad, "alltoall of %d ints a block%s%s on %d ranks: rc %d or a wrong element", count,
         as_block ? " as one block" : "", in_place ? " in place" : "", size, rc);
  if (b != MPI_INT) MPI_Type_free(&b);
  free(s);
  free(r);
}

/* Rank f sends rank d ((f + 2d) % 4) * scale ints. */
static int vcount(int f, int d, int scale) { return ((f + 2 * d) % 4) * scale; }

static void alltoallv(mtest *t, int scale) {
  int me = t->rank, size = t->size, stot = 0, rtot = 0;
  int *sc = xmalloc_or_abort(4 * (size_t)size * sizeof(int)), *sd = sc + size, *rcn = sc + 2 * size, *rd = sc + 3 * size;
  /* Displacements in reverse rank order with a gap of 2 after each block. */
  for (int d = size - 1; d >= 0; d--) {
    sc[d] = vcount(me, d, scale);
    sd[d] = stot;
    stot += sc[d] + 2;
    rcn[d] = vcount(d, me, scale);
    rd[d] = rtot;
    rtot += rcn[d] + 2;
  }
  int *s = xmalloc_or_abort((size_t)stot * sizeof(int) + 4), *r = xmalloc_or_abort((size_t)rtot * sizeof(int) + 4);
  for (int d = 0; d < size; d++)
    for (int i = 0; i < sc[d]; i++) s[sd[d] + i] = blk(me, d, i);
  for (int i = 0; i < rtot; i++) r[i] = -6;
  int rc = MPI_Alltoallv(s, sc, sd, MPI_INT, r, rcn, rd, MPI_INT, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  for (int f = 0; f < size && !bad; f++) {
    for (int i = 0; i < rcn[f] && !bad; i++) bad = r[rd[f] + i] != blk(f, me, i);
    bad = bad || r[rd[f] + rcn[f]] != -6;
  }
  MCHECK(t, !bad, "alltoallv (scale %d) on %d ranks: rc %d or a wrong element", scale, size, rc);
  free(sc);
  free(s);
  free(r);
}

/* Alltoall and alltoallv at sizes around the thresholds, then alltoallv in place. */
static void alltoalls(mtest *t) {
  static const int counts[] = {0, 1, 64, 65, 8192, 8193};
  for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) alltoall(t, counts[c], 0, 0);
  alltoall(t, 64, 1, 0);
  alltoall(t, 3, 0, 1);
  alltoall(t, 8193, 0, 1);
  alltoallv(t, 1);
  alltoallv(t, 900);
  /* In place, each block goes back where the other's came from: counts
   * symmetric in the pair ((me + f) % 3 + 1). */
  int me = t->rank, size = t->size, tot = 0;
  int *c = xmalloc_or_abort(2 * (size_t)size * sizeof(int)), *d = c + size;
  for (int f = 0; f < size; f++) c[f] = 1 + (me + f) % 3, d[f] = tot, tot += c[f];
  int *buf = xmalloc_or_abort((size_t)tot * sizeof(int));
  for (int f = 0; f < size; f++)
    for (int i = 0; i < c[f]; i++) buf[d[f] + i] = blk(me, f, i);
  int rc = MPI_Alltoallv(MPI_IN_PLACE, c, d, MPI_INT, buf, c, d, MPI_INT, MPI_COMM_WORLD), bad = rc != MPI_SUCCESS;
  for (int f = 0; f < size && !bad; f++)
    for (int i = 0; i < c[f] && !bad; i++) bad = buf[d[f] + i] != blk(f, me, i);
  MCHECK(t, !bad, "alltoallv in place (symmetric counts) on %d ranks: rc %d or a wrong element", size, rc);
  free(c);
  free(buf);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {alltoalls, NULL};
  return mtest_main(&argc, &argv, "coll_alltoall", 1, 0, checks);
}
