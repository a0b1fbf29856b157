/* coll_reduce.c -- MPI_Reduce (to three roots) and MPI_Allreduce at sizes on both sides of
 * MPICH's thresholds (2048 bytes; count against the power of two below the rank count; user
 * operations): integer sums, integer-valued doubles (exact in any order), MINLOC with ties, a
 * commutative user operation, a non-commutative one (2x2 matrices: the result shows the ranks'
 * order) on a contiguous type and on a type with gaps, MPI_IN_PLACE.  Every rank computes the
 * expected result from the values of all ranks.  Plain MPI C (mtest.h): the same line under
 * Open MPI and tilesim. */
#include <mpi.h>
#include <string.h>

#include "colldata.h"
#include "mtest.h"

/* The matrix operation on elements with gaps: element k is 8 ints, the
 * matrix in ints 0, 2, 4, 6. */
static void matmul_gap_fn(void *in, void *inout, int *len, MPI_Datatype *dt) {
  int *a = in, *b = inout;
  (void)dt;
  for (int k = 0; k < *len; k++) {
    int x[4] = {a[8 * k], a[8 * k + 2], a[8 * k + 4], a[8 * k + 6]};
    int y[4] = {b[8 * k], b[8 * k + 2], b[8 * k + 4], b[8 * k + 6]}, z[4];
    matmul(x, y, z);
    for (int e = 0; e < 4; e++) b[8 * k + 2 * e] = z[e];
  }
}

/* Integer sums (MPI_SUM, or the commutative user operation). */
static void ints(mtest *t, int count, MPI_Op op, const char *name, int root, int all, int in_place) {
  int me = t->rank, size = t->size;
  int *in = xmalloc_or_abort((size_t)count * sizeof(int)), *out = xmalloc_or_abort((size_t)count * sizeof(int));
  for (int i = 0; i < count; i++) in[i] = val(me, i), out[i] = in_place ? in[i] : -1;
  int rc;
  if (all) rc = MPI_Allreduce(in_place ? MPI_IN_PLACE : in, out, count, MPI_INT, op, MPI_COMM_WORLD);
  else rc = MPI_Reduce(in_place && me == root ? MPI_IN_PLACE : in, out, count, MPI_INT, op, root, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  if (all || me == root)
    for (int i = 0; i < count && !bad; i++) {
      unsigned s = 0;
      for (int r = 0; r < size; r++) s += (unsigned)val(r, i);
      bad = out[i] != (int)s;
    }
  MCHECK(t, !bad, "%s of %d ints with %s%s (root %d) on %d ranks: rc %d or a wrong element",
         all ? "allreduce" : "reduce", count, name, in_place ? " in place" : "", root, size, rc);
  free(in);
  free(out);
}

/* Doubles: SUM and MAX of integer values, exact in any order. */
static void doubles(mtest *t, int count, MPI_Op op, const char *name, int root, int all) {
  int me = t->rank, size = t->size;
  double *in = xmalloc_or_abort((size_t)count * sizeof(double)), *out = xmalloc_or_abort((size_t)count * sizeof(double));
  for (int i = 0; i < count; i++) in[i] = dval(me, i), out[i] = -1;
  int rc = all ? MPI_Allreduce(in, out, count, MPI_DOUBLE, op, MPI_COMM_WORLD)
               : MPI_Reduce(in, out, count, MPI_DOUBLE, op, root, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  if (all || me == root)
    for (int i = 0; i < count && !bad; i++) {
      double w = dval(0, i);
      for (int r = 1; r < size; r++) w = op == MPI_SUM ? w + dval(r, i) : (dval(r, i) > w ? dval(r, i) : w);
      bad = out[i] != w;
    }
  MCHECK(t, !bad, "%s of %d doubles with %s (root %d) on %d ranks: rc %d or a wrong element",
         all ? "allreduce" : "reduce", count, name, root, size, rc);
  free(in);
  free(out);
}

/* MINLOC of (value, index) pairs with many ties: the smallest value, the
 * smallest index among equals. */
static void minloc(mtest *t, int count, int all) {
  int me = t->rank, size = t->size;
  struct di {
    double v;
    int i;
  } *in = xmalloc_or_abort((size_t)count * sizeof *in), *out = xmalloc_or_abort((size_t)count * sizeof *in);
  for (int i = 0; i < count; i++) in[i].v = (double)((me * 7 + i) % 5), in[i].i = (me * 3 + i) % 11;
  int rc = all ? MPI_Allreduce(in, out, count, MPI_DOUBLE_INT, MPI_MINLOC, MPI_COMM_WORLD)
               : MPI_Reduce(in, out, count, MPI_DOUBLE_INT, MPI_MINLOC, 0, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  if (all || me == 0)
    for (int i = 0; i < count && !bad; i++) {
      double wv = 1e9;
      int wi = 1 << 30;
      for (int r = 0; r < size; r++) {
        double v = (double)((r * 7 + i) % 5);
        int x = (r * 3 + i) % 11;
        if (v < wv || (v == wv && x < wi)) wv = v, wi = x;
      }
      bad = out[i].v != wv || out[i].i != wi;
    }
  MCHECK(t, !bad, "%s MINLOC of %d pairs on %d ranks: rc %d or a wrong pair", all ? "allreduce" : "reduce", count,
         size, rc);
  free(in);
  free(out);
}

/* The non-commutative operation: the product in rank order, element by
 * element; gaps: elements of 8 ints with the matrix in every other one. */
static void matrices(mtest *t, int count, MPI_Op op, MPI_Datatype dt, int gaps, int root, int all) {
  int me = t->rank, size = t->size, w = gaps ? 8 : 4;
  int *in = xmalloc_or_abort((size_t)count * (size_t)w * sizeof(int)), *out = xmalloc_or_abort((size_t)count * (size_t)w * sizeof(int));
  for (int i = 0; i < count; i++) {
    int m[4];
    mat(me, i, m);
    for (int e = 0; e < w; e++) in[w * i + e] = gaps ? (e % 2 ? -5 : m[e / 2]) : m[e], out[w * i + e] = -3;
  }
  int rc = all ? MPI_Allreduce(in, out, count, dt, op, MPI_COMM_WORLD) : MPI_Reduce(in, out, count, dt, op, root, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS;
  if (all || me == root)
    for (int i = 0; i < count && !bad; i++) {
      int p[4];
      matprod(0, size, i, p);
      for (int e = 0; e < w && !bad; e++) bad = out[w * i + e] != (gaps ? (e % 2 ? -3 : p[e / 2]) : p[e]);
    }
  MCHECK(t, !bad, "%s of %d matrices%s (root %d) on %d ranks: rc %d or a wrong element", all ? "allreduce" : "reduce",
         count, gaps ? " with gaps" : "", root, size, rc);
  free(in);
  free(out);
}

/* Reductions of each kind, from three roots and all-reduced. */
static void reductions(mtest *t) {
  int size = t->size, roots[3] = {0, size - 1, size / 2};
  MPI_Op isum, mprod, gprod;
  MPI_Op_create(isum_fn, 1, &isum);
  MPI_Op_create(matmul_fn, 0, &mprod);
  MPI_Op_create(matmul_gap_fn, 0, &gprod);
  MPI_Datatype m4, gap, gap8;
  MPI_Type_contiguous(4, MPI_INT, &m4);
  MPI_Type_commit(&m4);
  MPI_Type_vector(4, 1, 2, MPI_INT, &gap);
  MPI_Type_create_resized(gap, 0, 8 * (MPI_Aint)sizeof(int), &gap8);
  MPI_Type_commit(&gap8);
  int commute = -1;
  MPI_Op_commutative(mprod, &commute);
  MCHECK(t, commute == 0, "MPI_Op_commutative of a non-commutative operation: %d", commute);
  static const int counts[] = {0, 1, 3, 511, 512, 513, 2000};
  for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
    ints(t, counts[c], MPI_SUM, "MPI_SUM", 0, 1, 0);
    for (int k = 0; k < 3; k++)
      if (k == 0 || roots[k] != roots[0]) ints(t, counts[c], MPI_SUM, "MPI_SUM", roots[k], 0, 0);
  }
  ints(t, 700, MPI_SUM, "MPI_SUM", 0, 1, 1);
  ints(t, 700, MPI_SUM, "MPI_SUM", size - 1, 0, 1);
  ints(t, 5, MPI_SUM, "MPI_SUM", size / 2, 0, 1);
  ints(t, 600, isum, "a commutative user operation", size / 2, 0, 0);
  ints(t, 600, isum, "a commutative user operation", 0, 1, 0);
  doubles(t, 700, MPI_SUM, "MPI_SUM", size / 2, 0);
  doubles(t, 700, MPI_SUM, "MPI_SUM", 0, 1);
  doubles(t, 257, MPI_MAX, "MPI_MAX", size - 1, 0);
  doubles(t, 257, MPI_MAX, "MPI_MAX", 0, 1);
  minloc(t, 300, 0);
  minloc(t, 300, 1);
  minloc(t, 7, 1);
  for (int k = 0; k < 3; k++) {
    if (k > 0 && roots[k] == roots[0]) continue;
    matrices(t, 5, mprod, m4, 0, roots[k], 0);
    matrices(t, 130, mprod, m4, 0, roots[k], 0);
    matrices(t, 9, gprod, gap8, 1, roots[k], 0);
  }
  matrices(t, 5, mprod, m4, 0, 0, 1);
  matrices(t, 130, mprod, m4, 0, 0, 1);
  matrices(t, 9, gprod, gap8, 1, 0, 1);
  if (TILESIM) {
    /* A predefined operation on a derived type of one basic type: MPICH and
     * tilesim take it, Open MPI does not (so it counts only on failure). */
    int a[6], b[6];
    for (int i = 0; i < 6; i++) a[i] = val(t->rank, i);
    MPI_Datatype three;
    MPI_Type_contiguous(3, MPI_INT, &three);
    MPI_Type_commit(&three);
    int rc = MPI_Allreduce(a, b, 2, three, MPI_SUM, MPI_COMM_WORLD), bad = rc != MPI_SUCCESS;
    for (int i = 0; i < 6 && !bad; i++) {
      unsigned s = 0;
      for (int r = 0; r < size; r++) s += (unsigned)val(r, i);
      bad = b[i] != (int)s;
    }
    if (bad) MCHECK(t, 0, "MPI_SUM on contiguous(3, MPI_INT): rc %d or a wrong element", rc);
    MPI_Type_free(&three);
  }
  MPI_Op_free(&isum);
  MPI_Op_free(&mprod);
  MPI_Op_free(&gprod);
  MCHECK(t, isum == MPI_OP_NULL, "MPI_Op_free left the handle");
  MPI_Type_free(&m4);
  MPI_Type_free(&gap);
  MPI_Type_free(&gap8);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {reductions, NULL};
  return mtest_main(&argc, &argv, "coll_reduce", 1, 0, checks);
}
