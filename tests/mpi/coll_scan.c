/* coll_scan.c -- MPI_Scan, MPI_Exscan, MPI_Reduce_scatter and MPI_Reduce_scatter_block: integer
 * sums (commutative) with totals on both sides of MPICH's 524288-byte threshold, the
 * non-commutative matrix product (rank order: Traff's butterfly on a power of two ranks with
 * equal blocks, recursive doubling otherwise), uneven and zero block counts, MPI_IN_PLACE.
 * Every rank checks its result against the prefix or the full reduction of the values of all
 * ranks, computed locally.  Plain MPI C (mtest.h): the same line under Open MPI and tilesim. */
#include <mpi.h>
#include <string.h>

#include "colldata.h"
#include "mtest.h"

static void scans(mtest *t, int count, int exclusive, int in_place) {
  int me = t->rank;
  int *in = xmalloc_or_abort((size_t)count * sizeof(int) + 4), *out = xmalloc_or_abort((size_t)count * sizeof(int) + 4);
  for (int i = 0; i < count; i++) in[i] = val(me, i), out[i] = in_place ? in[i] : -1;
  int rc = exclusive ? MPI_Exscan(in_place ? MPI_IN_PLACE : in, out, count, MPI_INT, MPI_SUM, MPI_COMM_WORLD)
                     : MPI_Scan(in_place ? MPI_IN_PLACE : in, out, count, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  for (int i = 0; i < count && !bad && (me > 0 || !exclusive); i++) {
    unsigned s = 0;
    for (int r = 0; r < me + !exclusive; r++) s += (unsigned)val(r, i);
    bad = out[i] != (int)s;
  }
  MCHECK(t, !bad, "%s of %d ints%s on %d ranks: rc %d or a wrong element", exclusive ? "exscan" : "scan", count,
         in_place ? " in place" : "", t->size, rc);
  free(in);
  free(out);
}

/* The matrix product over ranks 0..me (exscan: 0..me-1). */
static void mat_scans(mtest *t, int count, MPI_Op op, MPI_Datatype m4, int exclusive) {
  int me = t->rank;
  int *in = xmalloc_or_abort((size_t)count * 4 * sizeof(int) + 4), *out = xmalloc_or_abort((size_t)count * 4 * sizeof(int) + 4);
  for (int i = 0; i < count; i++) mat(me, i, in + 4 * i);
  int rc = exclusive ? MPI_Exscan(in, out, count, m4, op, MPI_COMM_WORLD) : MPI_Scan(in, out, count, m4, op, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  for (int i = 0; i < count && !bad && (me > 0 || !exclusive); i++) {
    int p[4];
    matprod(0, me + !exclusive, i, p);
    bad = memcmp(out + 4 * i, p, sizeof p) != 0;
  }
  MCHECK(t, !bad, "%s of %d matrices on %d ranks: rc %d or a wrong element", exclusive ? "exscan" : "scan", count,
         t->size, rc);
  free(in);
  free(out);
}

/* Reduce_scatter of ints with rank r's block counts[r] = ((r * 3) % 4) *
 * scale (+ extra at rank 0), or _block with scale each. */
static void redscat(mtest *t, int scale, int extra, int block, int in_place) {
  int me = t->rank, size = t->size, total = 0, off = 0;
  int *counts = xmalloc_or_abort((size_t)size * sizeof(int));
  for (int r = 0; r < size; r++) {
    counts[r] = block ? scale : ((r * 3) % 4) * scale + (r == 0 ? extra : 0);
    if (r < me) off += counts[r];
    total += counts[r];
  }
  int *in = xmalloc_or_abort((size_t)total * sizeof(int) + 4), *out = xmalloc_or_abort((size_t)total * sizeof(int) + 4);
  for (int i = 0; i < total; i++) in[i] = val(me, i), out[i] = in_place ? in[i] : -1;
  int rc = block ? MPI_Reduce_scatter_block(in_place ? MPI_IN_PLACE : in, out, scale, MPI_INT, MPI_SUM, MPI_COMM_WORLD)
                 : MPI_Reduce_scatter(in_place ? MPI_IN_PLACE : in, out, counts, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  for (int i = 0; i < counts[me] && !bad; i++) {
    unsigned s = 0;
    for (int r = 0; r < size; r++) s += (unsigned)val(r, off + i);
    bad = out[i] != (int)s;
  }
  MCHECK(t, !bad, "reduce_scatter%s (%d ints in all)%s on %d ranks: rc %d or a wrong element", block ? "_block" : "",
         total, in_place ? " in place" : "", size, rc);
  free(counts);
  free(in);
  free(out);
}

/* The same with the matrix product: every element the product in rank order. */
static void mat_redscat(mtest *t, int scale, int block, MPI_Op op, MPI_Datatype m4) {
  int me = t->rank, size = t->size, total = 0, off = 0;
  int *counts = xmalloc_or_abort((size_t)size * sizeof(int));
  for (int r = 0; r < size; r++) {
    counts[r] = block ? scale : ((r * 3) % 4) * scale;
    if (r < me) off += counts[r];
    total += counts[r];
  }
  int *in = xmalloc_or_abort((size_t)total * 4 * sizeof(int) + 4), *out = xmalloc_or_abort((size_t)total * 4 * sizeof(int) + 4);
  for (int i = 0; i < total; i++) mat(me, i, in + 4 * i);
  int rc = block ? MPI_Reduce_scatter_block(in, out, scale, m4, op, MPI_COMM_WORLD)
                 : MPI_Reduce_scatter(in, out, counts, m4, op, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  for (int i = 0; i < counts[me] && !bad; i++) {
    int p[4];
    matprod(0, size, off + i, p);
    bad = memcmp(out + 4 * i, p, sizeof p) != 0;
  }
  MCHECK(t, !bad, "reduce_scatter%s of matrices (%d in all) on %d ranks: rc %d or a wrong element", block ? "_block" : "",
         total, size, rc);
  free(counts);
  free(in);
  free(out);
}

/* The scans and reduce-scatters, at sizes on both sides of MPICH's thresholds. */
static void scans_and_reduce_scatters(mtest *t) {
  MPI_Op mprod;
  MPI_Op_create(matmul_fn, 0, &mprod);
  MPI_Datatype m4;
  MPI_Type_contiguous(4, MPI_INT, &m4);
  MPI_Type_commit(&m4);
  static const int counts[] = {0, 1, 300};
  for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++)
    for (int ex = 0; ex < 2; ex++) scans(t, counts[c], ex, 0);
  scans(t, 17, 0, 1);
  scans(t, 17, 1, 1);
  mat_scans(t, 7, mprod, m4, 0);
  mat_scans(t, 7, mprod, m4, 1);
  /* Totals just below and at 524288 bytes (131072 ints). */
  int s = t->size;
  redscat(t, 1, 0, 0, 0);
  redscat(t, 50, 3, 0, 1);
  redscat(t, 0, 5, 0, 0);   /* only rank 0 gets a block */
  redscat(t, 131072 / s, 0, 1, 0);
  redscat(t, 131072 / s - (131072 % s == 0), 0, 1, 1);
  redscat(t, 131071 / (3 * s) + 1, 0, 0, 0);
  redscat(t, 3, 0, 1, 0);
  mat_redscat(t, 2, 1, mprod, m4);
  mat_redscat(t, 3, 0, mprod, m4);
  MPI_Op_free(&mprod);
  MPI_Type_free(&m4);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {scans_and_reduce_scatters, NULL};
  return mtest_main(&argc, &argv, "coll_scan", 1, 0, checks);
}
