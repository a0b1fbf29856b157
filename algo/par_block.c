/* par_block.c -- the blocked wavefront (--block k): blocks of diagonals,
 * staircase boundaries, cones of ghost nodes, one exchange per block (see
 * par_block.h; the paper's sections 5, 7.2, 8 and 9). */
#include "algo/par_block.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "algo/kernel.h"
#include "algo/par_slave.h"
#include "algo/split.h"
#include "util/xmem.h"

enum { FAR = INT_MAX / 4 };   /* the boundary left of slave 0 and right of the last */

typedef struct {
  int t0, t1;   /* its diagonals, all normal */
  int q;        /* the slaves that own its nodes: 0 .. q-1 */
  int off;      /* its boundaries 1 .. q-1 at bs[off .. off+q-2] */
} blk;

struct par_block {
  int *of;             /* diagonal t -> its block (normal diagonals only) */
  blk *b;
  int nb, bcap;
  int *bs;             /* boundary j (slave j's first column), extended back
                          to diagonal t0-1 */
  unsigned char *st;   /* 1: it moves one column a diagonal (a row boundary),
                          0: it stays (a column boundary) */
  int nbs, bscap;
  int *x, *y;          /* my columns on each diagonal of the current block */
};

#define TRY(call) PAR_TRY(par_slave_fail, S, call)

par_block *par_block_new(int m, int n) {
  par_block *B = xcalloc(1, sizeof *B);
  size_t T1 = (size_t)m + n + 1;
  B->of = xmallocarray(T1, sizeof *B->of);
  B->x = xmallocarray(T1, sizeof *B->x);
  B->y = xmallocarray(T1, sizeof *B->y);
  return B;
}

void par_block_free(par_block *B) {
  if (!B) return;
  free(B->of), free(B->b), free(B->bs), free(B->st), free(B->x), free(B->y);
  free(B);
}

/* Boundary j of block k on diagonal t (t0-1 <= t <= t1): slave j's first
 * column, slave j-1's last plus one. */
static int bnd(const par_block *B, const blk *k, int j, int t) {
  if (j <= 0) return -FAR;
  if (j >= k->q) return FAR;
  int i = k->off + j - 1;
  return B->bs[i] + B->st[i] * (t - k->t0 + 1);
}

/* The columns slave i owns on diagonal t, [*u0, *u1] (empty: *u0 > *u1).
 * A pinch or the start node is the group's first slave's (par_slave.c). */
static void own(const par_slave_ctx *S, int t, int i, int *u0, int *u1) {
  const par_block *B = S->blk;
  if (S->type[t] != PAR_D_NORMAL) {
    *u0 = i == 0 ? S->a[t] : 1, *u1 = i == 0 ? S->a[t] : 0;
    return;
  }
  const blk *k = &B->b[B->of[t]];
  if (i >= k->q) {
    *u0 = 1, *u1 = 0;
    return;
  }
  int lo = bnd(B, k, i, t), hi = bnd(B, k, i + 1, t) - 1;
  *u0 = lo > S->a[t] ? lo : S->a[t];
  *u1 = hi < S->b[t] ? hi : S->b[t];
}

int par_block_owner(const par_slave_ctx *S, int t, int c) {
  const par_block *B = S->blk;
  if (S->type[t] != PAR_D_NORMAL) return 0;
  const blk *k = &B->b[B->of[t]];
  int lo = 0, hi = k->q - 1;   /* the last slave whose boundary is <= c */
  while (lo < hi) {
    int mid = (lo + hi + 1) / 2;
    if (bnd(B, k, mid, t) <= c) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

/* Slave i's cone in block k: on each diagonal, the columns it owns and those
 * its later nodes in the block depend on (column c needs c and c-1 of the
 * diagonal before, Fig. 11), within the band; into x[], y[] when not NULL.
 * Returns in [*n0, *n1] the columns of diagonal t0-1 it needs. */
static void cone(const par_slave_ctx *S, const blk *k, int i, int *x, int *y, int *n0, int *n1) {
  int cx = 1, cy = 0;
  for (int t = k->t1; t >= k->t0; t--) {
    int lo, hi;
    own(S, t, i, &lo, &hi);
    if (cx <= cy) {
      if (lo > hi) lo = cx - 1, hi = cy;
      else {
        if (cx - 1 < lo) lo = cx - 1;
        if (cy > hi) hi = cy;
      }
    }
    if (lo < S->a[t]) lo = S->a[t];
    if (hi > S->b[t]) hi = S->b[t];
    cx = lo, cy = hi;
    if (x) x[t - k->t0] = lo, y[t - k->t0] = hi;
  }
  int tp = k->t0 - 1;
  *n0 = cx - 1 < S->a[tp] ? S->a[tp] : cx - 1;
  *n1 = cy > S->b[tp] ? S->b[tp] : cy;
  if (cx > cy) *n0 = 1, *n1 = 0;
}

/* Diagonals t0..t1 as a new block: q slaves under --min-diag, boundaries
 * continued from the block before (when it ends at t0-1 with the same q) or
 * started afresh at the paper's even split (section 5, N_i), each then a
 * column or a row boundary, whichever ends nearer the even split of t1.
 * Decided right to left, so that no two boundaries cross. */
static const blk *new_block(par_slave_ctx *S, int t0, int t1, int p) {
  par_block *B = S->blk;
  int kk = t1 - t0 + 1, minlen = S->b[t0] - S->a[t0] + 1;
  for (int t = t0 + 1; t <= t1; t++)
    if (S->b[t] - S->a[t] + 1 < minlen) minlen = S->b[t] - S->a[t] + 1;
  int q = split_active(minlen, p, S->d);
  if (B->nb == B->bcap) {
    B->bcap = B->bcap ? 2 * B->bcap : 64;
    B->b = xreallocarray(B->b, (size_t)B->bcap, sizeof *B->b);
  }
  if (B->nbs + q > B->bscap) {
    B->bscap = 2 * (B->nbs + q) + 256;
    B->bs = xreallocarray(B->bs, (size_t)B->bscap, sizeof *B->bs);
    B->st = xreallocarray(B->st, (size_t)B->bscap, sizeof *B->st);
  }
  const blk *pk = B->nb > 0 ? &B->b[B->nb - 1] : NULL;
  int fresh = !pk || pk->t1 != t0 - 1 || pk->q != q;
  blk *k = &B->b[B->nb];
  *k = (blk){t0, t1, q, B->nbs};
  for (int j = 1; j < q; j++)
    B->bs[k->off + j - 1] = fresh ? S->a[t0] + split_n(S->b[t0] - S->a[t0] + 1, q, j)
                                  : bnd(B, pk, j, t0 - 1);
  for (int j = q - 1; j >= 1; j--) {
    int i = k->off + j - 1;
    int target = S->a[t1] + split_n(S->b[t1] - S->a[t1] + 1, q, j);
    int row = 2 * (target - B->bs[i]) >= kk + 1;
    if (row && j < q - 1 && !B->st[i + 1] && B->bs[i] + kk > B->bs[i + 1]) row = 0;
    B->st[i] = (unsigned char)row;
  }
  B->nbs += q - 1;
  for (int t = t0; t <= t1; t++) B->of[t] = B->nb;
  B->nb++;
  return k;
}

/* At the block's first diagonal: send each slave the costs of diagonal t0-1
 * its cone needs from my nodes, then receive what mine needs (sends never
 * block).  Leaves my columns of each diagonal of the block in B->x, B->y. */
static int exchange(par_slave_ctx *S, const blk *k, int j) {
  par_block *B = S->blk;
  int t = k->t0, tp = t - 1, kk = k->t1 - k->t0 + 1, sends = 0, recvs = 0;
  int u0, u1;
  own(S, tp, j, &u0, &u1);
  if (u0 <= u1) {
    /* Slave i's cone lies within [bs_i - kk, bs_{i+1} + kk - 1]: only those
     * that reach [u0, u1] can need my nodes (both ends grow with i). */
    int lo = 0, hi = k->q - 1;
    while (lo < hi) {   /* the first i whose cone can reach u0 */
      int mid = (lo + hi) / 2;
      if (bnd(B, k, mid + 1, tp) + kk - 1 >= u0) hi = mid;
      else lo = mid + 1;
    }
    int first = lo;
    lo = 0, hi = k->q - 1;
    while (lo < hi) {   /* the last i whose cone can reach u1 */
      int mid = (lo + hi + 1) / 2;
      if (bnd(B, k, mid, tp) - kk <= u1) lo = mid;
      else hi = mid - 1;
    }
    for (int i = first; i <= lo; i++) {
      if (i == j) continue;
      int n0, n1;
      cone(S, k, i, NULL, NULL, &n0, &n1);
      if (n0 < u0) n0 = u0;
      if (n1 > u1) n1 = u1;
      if (n0 > n1) continue;
      TRY(par_slave_send_boundary(S, i, t, n0, n1));
      sends++;
    }
  }
  int n0, n1;
  cone(S, k, j, B->x, B->y, &n0, &n1);
  if (n0 <= n1) {
    int lo = par_block_owner(S, tp, n0), hi = par_block_owner(S, tp, n1);
    for (int o = lo; o <= hi; o++) {
      if (o == j) continue;
      int v0, v1;
      own(S, tp, o, &v0, &v1);
      if (v0 < n0) v0 = n0;
      if (v1 > n1) v1 = n1;
      if (v0 > v1) continue;
      if (par_slave_recv_boundary(S, o, t, v0, v1, "block boundary") != 0) return -1;
      recvs++;
    }
  }
  par_slave_count_diag(S, t, sends, recvs);
  return 0;
}

int par_block_sweep(par_slave_ctx *S, int s, const gpath *U, const gpath *L, int j, int p) {
  par_block *B = S->blk;
  int m = S->m, n = S->n, T = m + n, K = S->k;
  int64_t wo = 0;
  B->nb = B->nbs = 0;
  S->type[0] = PAR_D_SINGLE, S->a[0] = S->b[0] = 0, S->q[0] = 1;
  S->prev[-1] = S->prev[0] = S->prev[1] = HUGE_VAL;
  if (j == 0) S->prev[0] = 0;
  int pa = 0, pb = 0;
  for (int t = 1; t <= T;) {
    int a, b;
    band_range(m, n, s, U, L, s + t, &a, &b);
    if (a == b && pa == pb) {   /* a pinch: the first slave joins it */
      t = par_slave_pinch(S, s, U, L, j, t, a, &pa, &pb) + 1;
      continue;
    }
    /* A block: up to K normal diagonals; a one-node diagonal is one alone,
     * so that a pinch after it finds its node with the first slave. */
    S->type[t] = PAR_D_NORMAL, S->a[t] = a, S->b[t] = b;
    int t1 = t;
    while (a != b && t1 < T && t1 - t + 1 < K) {
      int a2, b2;
      band_range(m, n, s, U, L, s + t1 + 1, &a2, &b2);
      if (a2 == b2) break;
      t1++;
      S->type[t1] = PAR_D_NORMAL, S->a[t1] = a2, S->b[t1] = b2;
    }
    const blk *k = new_block(S, t, t1, p);
    if (exchange(S, k, j) != 0) return -1;
    for (int u = t; u <= t1; u++) {
      int x = B->x[u - t], y = B->y[u - t];
      if (x <= y) {
        /* Outside the band of the diagonal before: +inf (kernel.h). */
        if (x - 1 < S->a[u - 1]) S->prev[x - 1] = HUGE_VAL;
        if (y > S->b[u - 1]) S->prev[y] = HUGE_VAL;
        int64_t words = kernel_words(y - x + 1);
        if (wo + words > S->bitcap) {
          S->bitcap = 2 * (wo + words) + 1024;
          S->bits = xreallocarray(S->bits, (size_t)S->bitcap, sizeof *S->bits);
        }
        kernel_diag(S->w, s + u, x, y, S->prev, S->cur, S->bits + wo);
        S->c0[u] = x;
        S->woff[u] = wo;
        wo += words;
        S->arg->counts.nodes += (uint64_t)(y - x + 1);
        TRY(par_compute(S->mp, &S->arg->counts, (uint64_t)(y - x + 1)));
      }
      double *sw = S->prev;
      S->prev = S->cur;
      S->cur = sw;
    }
    pa = S->a[t1], pb = S->b[t1];
    t = t1 + 1;
  }
  return 0;
}
