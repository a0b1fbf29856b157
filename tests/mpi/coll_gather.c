/* coll_gather.c -- MPI_Gather, MPI_Gatherv, MPI_Scatter, MPI_Scatterv (three roots), and
 * MPI_Allgather, MPI_Allgatherv at totals on both sides of MPICH's thresholds (81920 and 524288
 * bytes, a power of two ranks or not; blocks over 32 KiB, which MPICH's allgatherv ring
 * pipelines): empty, uneven and zero counts, displacements out of order, send and receive
 * types that differ but carry the same data, MPI_IN_PLACE.  Every rank checks what it
 * received against the senders' values, computed locally.  Plain MPI C (mtest.h): the same
 * line under Open MPI and tilesim. */
#include <mpi.h>
#include <string.h>

#include "colldata.h"
#include "mtest.h"

/* Gather count ints from every rank to root (received as one contiguous
 * type of count ints per rank when as_block), then scatter them back. */
static void gather_scatter(mtest *t, int count, int root, int as_block, int in_place) {
  int me = t->rank, size = t->size;
  int *all = xmalloc_or_abort((size_t)count * (size_t)size * sizeof(int)), *mine = xmalloc_or_abort((size_t)count * sizeof(int));
  MPI_Datatype blk = MPI_INT;
  if (as_block && count > 0) {
    MPI_Type_contiguous(count, MPI_INT, &blk);
    MPI_Type_commit(&blk);
  }
  int rcount = blk == MPI_INT ? count : 1;
  for (int i = 0; i < count; i++) mine[i] = val(me, i);
  for (int i = 0; i < count * size; i++) all[i] = in_place && me == root && i / (count ? count : 1) == root ? val(root, i % count) : -1;
  int rc = MPI_Gather(in_place && me == root ? MPI_IN_PLACE : mine, count, MPI_INT, all, rcount, blk, root, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  if (me == root)
    for (int r = 0; r < size && !bad; r++)
      for (int i = 0; i < count && !bad; i++) bad = all[r * count + i] != val(r, i);
  MCHECK(t, !bad, "gather of %d ints%s%s to root %d on %d ranks: rc %d or a wrong element", count,
         as_block ? " as one block" : "", in_place ? " in place" : "", root, size, rc);
  /* Scatter: the root's blocks (rank r's: 2 val(r, i) + 1) back out. */
  for (int i = 0; i < count * size; i++) all[i] = 2 * val(i / count, i % count) + 1;
  for (int i = 0; i < count; i++) mine[i] = -1;
  rc = MPI_Scatter(all, rcount, blk, in_place && me == root ? MPI_IN_PLACE : mine, count, MPI_INT, root, MPI_COMM_WORLD);
  bad = rc != MPI_SUCCESS;
  for (int i = 0; i < count && !bad && !(in_place && me == root); i++) bad = mine[i] != 2 * val(me, i) + 1;
  MCHECK(t, !bad, "scatter of %d ints%s%s from root %d on %d ranks: rc %d or a wrong element", count,
         as_block ? " as one block" : "", in_place ? " in place" : "", root, size, rc);
  if (blk != MPI_INT) MPI_Type_free(&blk);
  free(all);
  free(mine);
}

/* Uneven counts (rank r: (r * 5) % 7 ints, some 0) at displacements in
 * reverse rank order with gaps of 3 ints. */
static void gatherv_scatterv(mtest *t, int root, int in_place, int scale) {
  int me = t->rank, size = t->size, total = 0;
  int *counts = xmalloc_or_abort((size_t)size * sizeof(int)), *displs = xmalloc_or_abort((size_t)size * sizeof(int));
  for (int r = 0; r < size; r++) counts[r] = ((r * 5) % 7) * scale;
  for (int r = size - 1; r >= 0; r--) displs[r] = total, total += counts[r] + 3;
  int *buf = xmalloc_or_abort((size_t)total * sizeof(int) + 4), *mine = xmalloc_or_abort((size_t)counts[me] * sizeof(int) + 4);
  for (int i = 0; i < counts[me]; i++) mine[i] = val(me, i);
  for (int i = 0; i < total; i++) buf[i] = -2;
  if (in_place && me == root)
    for (int i = 0; i < counts[me]; i++) buf[displs[me] + i] = val(me, i);
  int rc = MPI_Gatherv(in_place && me == root ? MPI_IN_PLACE : mine, counts[me], MPI_INT, buf, counts, displs, MPI_INT,
                       root, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  if (me == root)
    for (int r = 0; r < size && !bad; r++) {
      for (int i = 0; i < counts[r] && !bad; i++) bad = buf[displs[r] + i] != val(r, i);
      for (int g = 0; g < 3 && !bad; g++) bad = buf[displs[r] + counts[r] + g] != -2;   /* the gaps untouched */
    }
  MCHECK(t, !bad, "gatherv%s to root %d on %d ranks: rc %d or a wrong element", in_place ? " in place" : "", root, size,
         rc);
  for (int r = 0; r < size; r++)
    for (int i = 0; i < counts[r]; i++) buf[displs[r] + i] = 3 * val(r, i);
  for (int i = 0; i < counts[me]; i++) mine[i] = -1;
  rc = MPI_Scatterv(buf, counts, displs, MPI_INT, in_place && me == root ? MPI_IN_PLACE : mine, counts[me], MPI_INT,
                    root, MPI_COMM_WORLD);
  bad = rc != MPI_SUCCESS;
  for (int i = 0; i < counts[me] && !bad && !(in_place && me == root); i++) bad = mine[i] != 3 * val(me, i);
  MCHECK(t, !bad, "scatterv%s from root %d on %d ranks: rc %d or a wrong element", in_place ? " in place" : "", root,
         size, rc);
  free(counts);
  free(displs);
  free(buf);
  free(mine);
}

/* Allgather of count ints per rank (sent as ints, received as one block
 * type when as_block). */
static void allgather(mtest *t, int count, int as_block, int in_place) {
  int me = t->rank, size = t->size;
  int *all = xmalloc_or_abort((size_t)count * (size_t)size * sizeof(int) + 4), *mine = xmalloc_or_abort((size_t)count * sizeof(int) + 4);
  MPI_Datatype blk = MPI_INT;
  if (as_block && count > 0) {
    MPI_Type_contiguous(count, MPI_INT, &blk);
    MPI_Type_commit(&blk);
  }
  for (int i = 0; i < count; i++) mine[i] = val(me, i);
  for (int i = 0; i < count * size; i++) all[i] = in_place && i / count == me ? val(me, i % count) : -1;
  int rc = MPI_Allgather(in_place ? MPI_IN_PLACE : mine, in_place ? 0 : count, MPI_INT, all, blk == MPI_INT ? count : 1,
                         blk, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  for (int r = 0; r < size && !bad; r++)
    for (int i = 0; i < count && !bad; i++) bad = all[r * count + i] != val(r, i);
  MCHECK(t, !bad, "allgather of %d ints (%d bytes in all)%s%s on %d ranks: rc %d or a wrong element", count,
         4 * count * size, as_block ? " as one block" : "", in_place ? " in place" : "", size, rc);
  if (blk != MPI_INT) MPI_Type_free(&blk);
  free(all);
  free(mine);
}

/* Allgatherv with uneven counts ((r * 3) % 5 * scale ints, rank 0 big ones
 * when big) at displacements in reverse order. */
static void allgatherv(mtest *t, int scale, int big, int in_place) {
  int me = t->rank, size = t->size, total = 0;
  int *counts = xmalloc_or_abort((size_t)size * sizeof(int)), *displs = xmalloc_or_abort((size_t)size * sizeof(int));
  for (int r = 0; r < size; r++) counts[r] = ((r * 3) % 5) * scale + (r == 0 ? big : 0);
  for (int r = size - 1; r >= 0; r--) displs[r] = total, total += counts[r] + 1;
  int *all = xmalloc_or_abort((size_t)total * sizeof(int) + 4), *mine = xmalloc_or_abort((size_t)counts[me] * sizeof(int) + 4);
  for (int i = 0; i < counts[me]; i++) mine[i] = val(me, i);
  for (int i = 0; i < total; i++) all[i] = -4;
  if (in_place)
    for (int i = 0; i < counts[me]; i++) all[displs[me] + i] = val(me, i);
  int rc = MPI_Allgatherv(in_place ? MPI_IN_PLACE : mine, counts[me], MPI_INT, all, counts, displs, MPI_INT, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  for (int r = 0; r < size && !bad; r++) {
    for (int i = 0; i < counts[r] && !bad; i++) bad = all[displs[r] + i] != val(r, i);
    bad = bad || all[displs[r] + counts[r]] != -4;
  }
  MCHECK(t, !bad, "allgatherv (scale %d, %d more at rank 0)%s on %d ranks: rc %d or a wrong element", scale, big,
         in_place ? " in place" : "", size, rc);
  free(counts);
  free(displs);
  free(all);
  free(mine);
}

/* Gathers and scatters from three roots; allgathers around 81920 and 524288 bytes. */
static void gathers(mtest *t) {
  int size = t->size, roots[3] = {0, size - 1, size / 2};
  for (int k = 0; k < 3; k++) {
    if (k > 0 && (roots[k] == roots[0] || (k == 2 && roots[2] == roots[1]))) continue;
    gather_scatter(t, 0, roots[k], 0, 0);
    gather_scatter(t, 1, roots[k], 0, 0);
    gather_scatter(t, 700, roots[k], 1, 0);
    gather_scatter(t, 33, roots[k], 0, 1);
    gatherv_scatterv(t, roots[k], 0, 1);
    gatherv_scatterv(t, roots[k], 1, 40);
  }
  /* Totals just below and at 81920 and 524288 bytes. */
  int c81 = 81920 / (4 * size), c524 = 524288 / (4 * size);
  allgather(t, 1, 0, 0);
  allgather(t, 3, 0, 1);
  allgather(t, c81 * 4 * size == 81920 ? c81 - 1 : c81, 0, 0);
  allgather(t, c81 + 1, 1, 0);
  allgather(t, c524 * 4 * size == 524288 ? c524 - 1 : c524, 0, 0);
  allgather(t, c524 + 1, 0, 1);
  allgatherv(t, 1, 0, 0);
  allgatherv(t, 700, 0, 1);
  allgatherv(t, 3, 9000, 0);   /* rank 0's block: 36000 bytes, past the 32 KiB pipeline size */
  allgatherv(t, 0, 0, 0);      /* nothing at all but rank 0's empty block */
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {gathers, NULL};
  return mtest_main(&argc, &argv, "coll_gather", 1, 0, checks);
}
