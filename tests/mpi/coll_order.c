/* coll_order.c -- the order in which tilesim's reductions add floating-point numbers, bit for
 * bit, against the orders doc/mpi-support.md states for each algorithm (written again here as
 * formulas over the ranks' values): MPI_Reduce (binomial from two roots, Rabenseifner's,
 * linear), MPI_Allreduce (recursive doubling, Rabenseifner's, linear), MPI_Scan and
 * MPI_Exscan (recursive doubling, linear), MPI_Reduce_scatter_block (recursive halving,
 * pairwise, linear), on doubles whose sums depend on the order.
 *
 * argv[1] is the run's --coll setting ("mpich", "linear", "allreduce=recursive_doubling"; the
 * test driver passes it), from which the program knows the algorithm each call runs (MPICH's
 * choice written again too).  Under another MPI library the orders are that library's: there
 * each result is only checked to be near the exact sum, so the program prints the same number
 * of checks everywhere. */
#include <math.h>
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

/* Rank r's element i: mixed signs and exponents, so that the order of the
 * additions shows in the result. */
static double x(int r, int i) {
  double m = 1.0 + (double)(((long long)r * 7919 + (long long)i * 104729) % 1000) / 1000.0;
  return ((r + i) % 2 ? -1 : 1) * ldexp(m, (r * 31 + i * 17) % 41 - 20);
}

/* ==== the orders ========================================================== */

/* ((x_lo + x_lo+1) + ...) + x_hi-1 */
static double fold(int lo, int hi, int i) {
  double s = x(lo, i);
  for (int r = lo + 1; r < hi; r++) s += x(r, i);
  return s;
}

/* Binomial reduce to root: relative rank q's partial is its value with each
 * child's partial (q + 1, q + 2, q + 4, ... below its lowest set bit)
 * added on the left, nearest child first. */
static double binomial(int q, int size, int root, int i) {
  double acc = x((q + root) % size, i);
  for (int mask = 1; mask < size && !(q & mask); mask <<= 1)
    if ((q | mask) < size) acc = binomial(q | mask, size, root, i) + acc;
  return acc;
}

/* The value of new rank k after the fold of the first 2 rem ranks in pairs. */
static double folded(int k, int rem, int i) { return k < rem ? x(2 * k, i) + x(2 * k + 1, i) : x(k + rem, i); }

/* Recursive doubling and Rabenseifner's over the pof2 new ranks: aligned
 * halves added, (T(lo, mid) + T(mid, hi)). */
static double halves(int lo, int hi, int rem, int i) {
  if (hi - lo == 1) return folded(lo, rem, i);
  int mid = lo + (hi - lo) / 2;
  return halves(lo, mid, rem, i) + halves(mid, hi, rem, i);
}

/* Recursive halving (reduce-scatter): new ranks are added along the
 * highest bit first, so the last addition joins the even and odd new
 * ranks: G(b, bits) over the new ranks whose low `bits` bits are b. */
static double by_low_bits(int b, int bits, int pof2, int rem, int i) {
  if ((1 << bits) == pof2) return folded(b, rem, i);
  return by_low_bits(b, bits + 1, pof2, rem, i) + by_low_bits(b | 1 << bits, bits + 1, pof2, rem, i);
}

/* The recursive-doubling scan of rank r: the aligned blocks below r, from
 * the largest (left) to the smallest, then x_r (scan) or nothing (exscan):
 * B_1 + (B_2 + (... + x_r)); each block its aligned halves. */
static double block(int lo, int len, int i) {
  if (len == 1) return x(lo, i);
  return block(lo, len / 2, i) + block(lo + len / 2, len / 2, i);
}
static double prefix(int r, int inclusive, int i) {
  int lows[32], n = 0;
  for (int bit = 30; bit >= 0; bit--)
    if (r & (1 << bit)) lows[n++] = bit;
  double acc = 0;
  int have = 0, base = r;
  /* from the smallest block up, each added on the left */
  if (inclusive) acc = x(r, i), have = 1;
  for (int k = n - 1; k >= 0; k--) {
    int len = 1 << lows[k];
    base -= len;
    acc = have ? block(base, len, i) + acc : block(base, len, i);
    have = 1;
  }
  return acc;
}

/* Pairwise reduce-scatter: rank r's block, x_r with x_r-1, x_r-2, ...
 * (around the ring) each added on the left. */
static double pairwise(int r, int size, int i) {
  double acc = x(r, i);
  for (int k = 1; k < size; k++) acc = x((r - k + size) % size, i) + acc;
  return acc;
}

/* ==== which algorithm runs ================================================ */

/* The algorithm the setting gives collective c ("reduce"), or NULL for
 * MPICH's choice. */
static const char *forced(const char *setting, const char *c) {
  if (!setting) return NULL;
  if (!strcmp(setting, "linear")) return "linear";
  size_t n = strlen(c);
  if (!strncmp(setting, c, n) && setting[n] == '=') return setting + n + 1;
  return NULL;
}

static int pof2_of(int n) {
  int p = 1;
  while (p * 2 <= n) p *= 2;
  return p;
}

/* The expected result for element i under algorithm alg. */
typedef enum { REDUCE, ALLREDUCE, SCAN, EXSCAN, REDSCAT } kind;

static double expect(kind k, const char *alg, int rank, int size, int root, int count, int i) {
  int pof2 = pof2_of(size), rem = size - pof2;
  size_t bytes = (size_t)count * sizeof(double);
  switch (k) {
  case REDUCE:
    if (!alg) alg = bytes > 2048 && count >= pof2 ? "reduce_scatter_gather" : "binomial";
    if (!strcmp(alg, "linear")) return fold(0, size, i);
    if (!strcmp(alg, "reduce_scatter_gather") && count >= pof2) return halves(0, pof2, rem, i);
    return binomial(0, size, root, i);
  case ALLREDUCE:
    if (!alg) alg = bytes <= 2048 || count < pof2 ? "recursive_doubling" : "reduce_scatter_allgather";
    if (!strcmp(alg, "linear")) return fold(0, size, i);
    return halves(0, pof2, rem, i);
  case SCAN:
  case EXSCAN:
    if (alg && !strcmp(alg, "linear")) return fold(0, rank + (k == SCAN), i);
    return prefix(rank, k == SCAN, i);
  default:   /* reduce_scatter_block: count elements for each rank, element i of this rank's block */
    if (!alg) alg = bytes * (size_t)size < 524288 ? "recursive_halving" : "pairwise";
    if (!strcmp(alg, "linear")) return fold(0, size, i);
    if (!strcmp(alg, "pairwise")) return pairwise(rank, size, i);
    return by_low_bits(0, 0, pof2, rem, i);
  }
}

static double exact(int lo, int hi, int i) {
  long double s = 0;
  for (int r = lo; r < hi; r++) s += x(r, i);
  return (double)s;
}

/* One result against the expectation: bit for bit under tilesim, within
 * rounding elsewhere. */
static int good(double got, double want, double near) {
  if (TILESIM) return memcmp(&got, &want, sizeof got) == 0;
  return fabs(got - near) <= 1e-9 * (fabs(near) + ldexp(1.0, 21));
}

static void check(mtest *t, kind k, const char *name, const char *setting, int count, int root) {
  int me = t->rank, size = t->size, n = k == REDSCAT ? count * size : count;
  double *in = malloc((size_t)n * sizeof *in + 8), *out = malloc((size_t)n * sizeof *in + 8);
  if (!in || !out) MPI_Abort(MPI_COMM_WORLD, 3);
  for (int i = 0; i < n; i++) in[i] = x(me, i), out[i] = 0;
  int rc;
  if (k == REDUCE) rc = MPI_Reduce(in, out, count, MPI_DOUBLE, MPI_SUM, root, MPI_COMM_WORLD);
  else if (k == ALLREDUCE) rc = MPI_Allreduce(in, out, count, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  else if (k == SCAN) rc = MPI_Scan(in, out, count, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  else if (k == EXSCAN) rc = MPI_Exscan(in, out, count, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  else rc = MPI_Reduce_scatter_block(in, out, count, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const char *alg = forced(setting, name);
  int bad = rc != MPI_SUCCESS, first = -1;
  if ((k != REDUCE || me == root) && (k != EXSCAN || me > 0))
    for (int i = 0; i < count && !bad; i++) {
      int e = k == REDSCAT ? me * count + i : i;
      int lo = 0, hi = k == SCAN ? me + 1 : k == EXSCAN ? me : size;
      bad = !good(out[i], expect(k, alg, me, size, root, count, e), exact(lo, hi, e));
      if (bad) first = i;
    }
  MCHECK(t, !bad, "%s of %d doubles (root %d) on %d ranks under --coll %s: rc %d, element %d not in the documented order",
         name, count, root, size, setting ? setting : "(none)", rc, first);
  free(in);
  free(out);
}

/* The reductions' order of operands under the --coll setting given (argv[1]). */
static void orders(mtest *t) {
  const char *setting = t->arg;
  int size = t->size;
  check(t, REDUCE, "reduce", setting, 100, 0);
  check(t, REDUCE, "reduce", setting, 100, size - 1);
  check(t, REDUCE, "reduce", setting, 1000, size / 2);
  check(t, ALLREDUCE, "allreduce", setting, 100, 0);
  check(t, ALLREDUCE, "allreduce", setting, 1000, 0);
  check(t, SCAN, "scan", setting, 50, 0);
  check(t, EXSCAN, "exscan", setting, 50, 0);
  check(t, REDSCAT, "reduce_scatter_block", setting, 20, 0);
  check(t, REDSCAT, "reduce_scatter_block", setting, 524288 / 8 / size + 1, 0);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {orders, NULL};
  return mtest_main(&argc, &argv, "coll_order", 1, 0, checks);
}
