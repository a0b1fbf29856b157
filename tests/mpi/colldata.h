/* colldata.h -- what the collective tests of tests/mpi/ share: the values every rank's buffers
 * hold (a function of rank and index, so any rank computes what a collective must give without
 * communicating), a non-commutative user operation with its rank-order reference, and the
 * sizes that straddle MPICH's algorithm thresholds.  Plain MPI C, no globals. */
#ifndef COLLDATA_H
#define COLLDATA_H

#include <mpi.h>
#include <stdlib.h>

/* Element i of rank r's data: distinct across ranks and indices. */
static inline int val(int r, int i) { return (r + 1) * 1000003 + i * 7; }

/* Integer values in doubles, small enough that every sum of 16 of them is
 * exact whatever the order. */
static inline double dval(int r, int i) { return (double)((r * 37 + i * 11) % 1000) - 300.0; }

/* Rank r's 2x2 matrix for element i, entries mod 97: the operation
 * MATMUL (in op inout: inout = in x inout, in on the left) is associative,
 * not commutative, so the result shows the order of the ranks. */
enum { MOD = 97 };
static inline void mat(int r, int i, int m[4]) {
  m[0] = (r + i) % MOD;
  m[1] = (2 * r + 1) % MOD;
  m[2] = (3 + i) % MOD;
  m[3] = (r * i + 5) % MOD;
}
static inline void matmul(const int a[4], const int b[4], int out[4]) {
  int c[4] = {(a[0] * b[0] + a[1] * b[2]) % MOD, (a[0] * b[1] + a[1] * b[3]) % MOD,
              (a[2] * b[0] + a[3] * b[2]) % MOD, (a[2] * b[1] + a[3] * b[3]) % MOD};
  for (int k = 0; k < 4; k++) out[k] = c[k];
}
/* The user function: each element is 4 ints (a contiguous type). */
static inline void matmul_fn(void *in, void *inout, int *len, MPI_Datatype *dt) {
  int *a = in, *b = inout;
  (void)dt;
  for (int k = 0; k < *len; k++) matmul(a + 4 * k, b + 4 * k, b + 4 * k);
}
/* The product of ranks lo .. hi-1's matrices for element i, in rank order. */
static inline void matprod(int lo, int hi, int i, int out[4]) {
  int m[4];
  out[0] = out[3] = 1;
  out[1] = out[2] = 0;
  for (int r = lo; r < hi; r++) {
    mat(r, i, m);
    matmul(out, m, out);
  }
}

/* A commutative user operation: integer sum, as a function. */
static inline void isum_fn(void *in, void *inout, int *len, MPI_Datatype *dt) {
  int *a = in, *b = inout;
  (void)dt;
  for (int k = 0; k < *len; k++) b[k] = (int)((unsigned)a[k] + (unsigned)b[k]);
}

static inline void *xmalloc_or_abort(size_t n) {
  void *p = malloc(n ? n : 1);
  if (!p) MPI_Abort(MPI_COMM_WORLD, 3);
  return p;
}

#endif
