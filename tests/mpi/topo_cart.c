/* topo_cart.c -- Cartesian topologies and MPI_Dims_create: for every count of nodes up to 128
 * and 1 to 4 dimensions (some fixed), MPI_Dims_create's answer is a non-increasing
 * factorization that keeps the fixed ones (on tilesim also the most balanced, against a brute
 * force search, with MPICH's choice among equals); grids of 1, 2 and 3 dimensions over the
 * ranks (periodic or not, and one rank short), every rank's coordinates, ranks and shifts
 * against row-major formulas, MPI_Cart_get, MPI_Cartdim_get, MPI_Topo_test, MPI_Cart_map, a
 * duplicate keeping the topology, MPI_Cart_sub in every way of keeping dimensions, the
 * zero-dimensional grid; errors under MPI_ERRORS_RETURN.  Plain MPI C (mtest.h): the same
 * "topo_cart: P passed, F failed" line under Open MPI and tilesim. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

/* ==== MPI_Dims_create ===================================================== */

/* The most balanced non-increasing factorization of n into k factors, each
 * at most hi (brute force): the least max - min, ties to the larger last
 * factor, then the one before ... Its balance, or -1 if none; best[] gets it. */
static int search(int n, int k, int hi, int *cur, int depth, int *best, int bestbal) {
  if (depth == k - 1) {
    if (n > hi) return bestbal;
    cur[depth] = n;
    int bal = cur[0] - n, better = bestbal < 0 || bal < bestbal;
    for (int i = k - 1; !better && bal == bestbal && i >= 0; i--) {
      if (cur[i] != best[i]) {
        better = cur[i] > best[i];
        break;
      }
    }
    if (better) {
      memcpy(best, cur, (size_t)k * sizeof *cur);
      return bal;
    }
    return bestbal;
  }
  for (int f = 1; f <= hi && f <= n; f++) {
    if (n % f) continue;
    cur[depth] = f;
    bestbal = search(n / f, k, f, cur, depth + 1, best, bestbal);
  }
  return bestbal;
}

static void dims(mtest *t) {
  int bad = 0, worse = 0;
  for (int n = 1; n <= 128; n++)
    for (int k = 1; k <= 4; k++)
      for (int fix = 0; fix < 2; fix++) {
        int d[4] = {0, 0, 0, 0}, cur[4], best[4];
        if (fix && k > 1) d[1] = n % 2 == 0 ? 2 : 1;   /* a fixed dimension */
        if (MPI_Dims_create(n, k, d) != MPI_SUCCESS) {
          bad++;
          continue;
        }
        int prod = 1;
        for (int i = 0; i < k; i++) prod *= d[i];
        if (prod != n || (fix && k > 1 && d[1] != (n % 2 == 0 ? 2 : 1))) bad++;
        /* the free ones, non-increasing, and (tilesim) the most balanced */
        int free_[4], nf = 0;
        for (int i = 0; i < k; i++)
          if (!(fix && i == 1)) free_[nf++] = d[i];
        for (int i = 1; i < nf; i++) bad += free_[i] > free_[i - 1];
        int m = fix && k > 1 ? n / (n % 2 == 0 ? 2 : 1) : n;
        search(m, nf, m, cur, 0, best, -1);
        if (TILESIM && memcmp(best, free_, (size_t)nf * sizeof *best) != 0) worse++;
      }
  MCHECK(t, bad == 0, "MPI_Dims_create: %d answers not a factorization, or increasing, or the fixed one changed", bad);
  MCHECK(t, worse == 0, "MPI_Dims_create: %d answers not the most balanced one", worse);
  int a[3] = {0, 0, 0}, b[2] = {0, 0}, c[4] = {0, 0, 0, 0};
  MPI_Dims_create(1000 * 1000 * 1000, 3, a);
  MPI_Dims_create(12, 2, b);
  MPI_Dims_create(6, 4, c);
  MCHECK(t, a[0] == 1000 && a[1] == 1000 && a[2] == 1000 && b[0] == 4 && b[1] == 3 && c[0] == 3 && c[1] == 2 &&
                c[2] == 1 && c[3] == 1,
         "MPI_Dims_create: 10^9 in 3 is %dx%dx%d, 12 in 2 is %dx%d, 6 in 4 is %dx%dx%dx%d", a[0], a[1], a[2], b[0],
         b[1], c[0], c[1], c[2], c[3]);
  int e[2] = {5, 0}, z[1] = {0};
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  int rc = MPI_Dims_create(12, 2, e);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_ARE_FATAL);
  MCHECK(t, rc != MPI_SUCCESS && MPI_Dims_create(4, 1, z) == MPI_SUCCESS && z[0] == 4,
         "MPI_Dims_create: 12 with a fixed 5 must fail (rc %d), 4 in one dimension is 4 (got %d)", rc, z[0]);
}

/* ==== grids =============================================================== */

/* Row-major coordinates of r in dims. */
static void coords_of(int r, int nd, const int *dims, int *c) {
  for (int i = nd - 1; i >= 0; i--) {
    c[i] = r % dims[i];
    r /= dims[i];
  }
}

static int rank_of(int nd, const int *dims, const int *c) {
  int r = 0;
  for (int i = 0; i < nd; i++) r = r * dims[i] + c[i];
  return r;
}

/* A grid of nd dimensions over n of the ranks (n = size or size - 1). */
static void grid(mtest *t, int nd, int n, const int *periods) {
  int me = t->rank, d[3] = {0, 0, 0}, bad = 0;
  MPI_Dims_create(n, nd, d);
  MPI_Comm cart;
  int rc = MPI_Cart_create(MPI_COMM_WORLD, nd, d, periods, 0, &cart);
  if (me >= n) {
    MCHECK(t, rc == MPI_SUCCESS && cart == MPI_COMM_NULL, "rank %d beyond a grid of %d: rc %d, not MPI_COMM_NULL", me,
           n, rc);
    return;
  }
  int size, r, status, ndims = -1, gd[3], gp[3], gc[3], c[3], mine[3];
  MPI_Comm_size(cart, &size);
  MPI_Comm_rank(cart, &r);
  MPI_Topo_test(cart, &status);
  MPI_Cartdim_get(cart, &ndims);
  MPI_Cart_get(cart, 3, gd, gp, gc);
  coords_of(me, nd, d, mine);
  bad += size != n || r != me || status != MPI_CART || ndims != nd;
  for (int i = 0; i < nd; i++) bad += gd[i] != d[i] || !gp[i] != !periods[i] || gc[i] != mine[i];
  MCHECK(t, rc == MPI_SUCCESS && !bad, "a %d-D grid of %d: its size, rank, status, dims, periods or coordinates", nd, n);
  /* every rank's coordinates and back */
  bad = 0;
  for (int q = 0; q < n; q++) {
    int back = -1, want[3];
    MPI_Cart_coords(cart, q, 3, c);
    coords_of(q, nd, d, want);
    MPI_Cart_rank(cart, c, &back);
    bad += back != q || memcmp(c, want, (size_t)nd * sizeof *c) != 0;
  }
  MCHECK(t, !bad, "a %d-D grid of %d: %d ranks' coordinates are not row-major", nd, n, bad);
  /* shifts by -2 .. 2 in each dimension */
  bad = 0;
  for (int dim = 0; dim < nd; dim++)
    for (int disp = -2; disp <= 2; disp++) {
      int src, dst, want[2];
      MPI_Cart_shift(cart, dim, disp, &src, &dst);
      for (int k = 0; k < 2; k++) {
        memcpy(c, mine, sizeof c);
        c[dim] += k ? disp : -disp;
        if (c[dim] < 0 || c[dim] >= d[dim]) {
          if (!periods[dim]) {
            want[k] = MPI_PROC_NULL;
            continue;
          }
          c[dim] = ((c[dim] % d[dim]) + d[dim]) % d[dim];
        }
        want[k] = rank_of(nd, d, c);
      }
      bad += src != want[0] || dst != want[1];
    }
  MCHECK(t, !bad, "a %d-D grid of %d: %d shifts wrong", nd, n, bad);
  /* a periodic dimension takes coordinates round; the duplicate keeps it all */
  MPI_Comm dup;
  MPI_Comm_dup(cart, &dup);
  int dstatus, dd[3], dp[3], dc[3], wrapped = -1;
  MPI_Topo_test(dup, &dstatus);
  MPI_Cart_get(dup, 3, dd, dp, dc);
  memcpy(c, mine, sizeof c);
  c[0] += periods[0] ? d[0] : 0;
  MPI_Cart_rank(dup, c, &wrapped);
  bad = dstatus != MPI_CART || wrapped != me;
  for (int i = 0; i < nd; i++) bad += dd[i] != d[i] || dc[i] != mine[i];
  MCHECK(t, !bad, "a duplicate of a %d-D grid of %d: status %d, its dims, coordinates or wrapped rank %d", nd, n,
         dstatus, wrapped);
  /* sub-grids: every choice of dimensions to keep */
  bad = 0;
  for (int keep = 0; keep < 1 << nd; keep++) {
    int remain[3], kd = 0, subsize, subrank, subnd = -1, want_size = 1, want_rank = 0;
    for (int i = 0; i < nd; i++) {
      remain[i] = keep >> i & 1;
      if (remain[i]) {
        want_size *= d[i];
        want_rank = want_rank * d[i] + mine[i];
        kd++;
      }
    }
    MPI_Comm sub;
    MPI_Cart_sub(cart, remain, &sub);
    if (sub == MPI_COMM_NULL) {   /* no dimension kept: MPICH and tilesim give one rank a grid, */
      bad += kd != 0 || me == 0;   /* Open MPI every rank its own */
      continue;
    }
    MPI_Comm_size(sub, &subsize);
    MPI_Comm_rank(sub, &subrank);
    MPI_Cartdim_get(sub, &subnd);
    bad += subsize != want_size || subrank != want_rank || subnd != kd;
    MPI_Comm_free(&sub);
  }
  MCHECK(t, !bad, "a %d-D grid of %d: %d sub-grids wrong", nd, n, bad);
  int newrank = -5;
  MPI_Cart_map(MPI_COMM_WORLD, nd, d, periods, &newrank);
  MCHECK(t, newrank == me, "MPI_Cart_map of a grid of %d gives rank %d %d", n, me, newrank);
  MPI_Comm_free(&dup);
  MPI_Comm_free(&cart);
}

/* The zero-dimensional grid: rank 0 alone in it. */
static void zero(mtest *t) {
  MPI_Comm cart;
  MPI_Cart_create(MPI_COMM_WORLD, 0, NULL, NULL, 0, &cart);
  if (t->rank != 0) {
    MCHECK(t, cart == MPI_COMM_NULL, "a zero-dimensional grid on rank %d", t->rank);
    return;
  }
  int size = -1, nd = -1, r = -1;
  if (cart != MPI_COMM_NULL) {
    MPI_Comm_size(cart, &size);
    MPI_Cartdim_get(cart, &nd);
    MPI_Cart_rank(cart, NULL, &r);
    MPI_Comm_free(&cart);
  }
  MCHECK(t, size == 1 && nd == 0 && r == 0, "a zero-dimensional grid: size %d, ndims %d, rank %d", size, nd, r);
}

/* Errors under MPI_ERRORS_RETURN: their classes. */
static void errors(mtest *t) {
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  int big[2] = {t->size + 1, 1}, neg[1] = {-1}, per[2] = {0, 0}, cls = 0, status = 0;
  MPI_Comm c = MPI_COMM_NULL;
  int rc1 = MPI_Cart_create(MPI_COMM_WORLD, 2, big, per, 0, &c);
  int rc2 = MPI_Cart_create(MPI_COMM_WORLD, 1, neg, per, 0, &c);
  int rc3 = MPI_Cartdim_get(MPI_COMM_WORLD, &status);
  MPI_Error_class(rc3, &cls);
  MCHECK(t, rc1 != MPI_SUCCESS && rc2 != MPI_SUCCESS && cls == MPI_ERR_TOPOLOGY,
         "errors: a grid bigger than the ranks (rc %d), a negative dimension (rc %d), MPI_Cartdim_get without a "
         "topology (class %d)", rc1, rc2, cls);
  MPI_Topo_test(MPI_COMM_WORLD, &status);
  MCHECK(t, status == MPI_UNDEFINED, "MPI_Topo_test of MPI_COMM_WORLD: %d", status);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_ARE_FATAL);
}

/* Dims_create, then grids of one to three dimensions, open, periodic and mixed. */
static void cartesian(mtest *t) {
  dims(t);
  static const int periodic[3] = {1, 1, 1}, open[3] = {0, 0, 0}, mixed[3] = {1, 0, 1};
  for (int nd = 1; nd <= 3; nd++) {
    grid(t, nd, t->size, open);
    grid(t, nd, t->size, periodic);
    grid(t, nd, t->size, mixed);
    if (t->size > 1) grid(t, nd, t->size - 1, mixed);
  }
  zero(t);
  errors(t);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {cartesian, NULL};
  return mtest_main(&argc, &argv, "topo_cart", 1, 0, checks);
}
