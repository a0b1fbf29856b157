/* band.h -- a minimum-cost path inside a band of the planar graph
 * (the paper's findonepath, sections 3.2 and 4; cut edges, section 8).
 *
 * The planar graph G' (section 3.1) has rows 0..2m and columns 0..n.  A path
 * for start row s runs from (s, 0) to (s+m, n) with m vertical and n
 * horizontal steps; its t-th node lies on anti-diagonal s+t.  We store a path
 * as the column of its node on each diagonal:
 *
 *        c=0 1 2 3 4          col[] = {0, 1, 1, 2, 3, 4, 4}
 *   r=s   o-o                 (vertical step: column stays,
 *   s+1     o                  horizontal step: column + 1)
 *   s+2     o-o-o-o
 *   s+3           o
 *
 * Non-crossing (section 3.2): the optimal path for s lies between the optimal
 * paths of any lo < s < hi.  The band for s is the region on or below the
 * upper path U = mu(lo) and on or above the lower path L = mu(hi); on diagonal
 * k it is a run of columns [a_k, b_k].  Where the band pinches to one node on
 * two consecutive diagonals, the edge between them is a cut edge that every
 * path takes (section 8, Fig. 23): it is joined without being evaluated.
 * Where U and L run together for many diagonals, the whole run is joined at
 * once: its cost is the difference of U's prefix sums (exact: weights.h), its
 * nodes are U's. */
#ifndef BAND_H
#define BAND_H

#include <stdint.h>

#include "algo/weights.h"

typedef struct {
  int start;     /* the path runs from (start, 0) to (start+m, n) */
  int *col;      /* col[t] for t = 0..m+n: column of its node on diagonal start+t */
  double *cum;   /* cum[t]: its cost in quanta from (start, 0) to that node */
} gpath;

/* Columns [*a, *b] of the band for start row s on diagonal k (s <= k <= s+m+n),
 * bounded above by U (U->start < s) and below by L (L->start > s); either may be
 * NULL for the edge of the graph. */
static inline void band_range(int m, int n, int s, const gpath *U, const gpath *L, int k,
                              int *a, int *b) {
  int hi = k - s < n ? k - s : n;          /* row >= s */
  int lo = k - s - m > 0 ? k - s - m : 0;  /* row <= s+m */
  if (U) {
    int t = k - U->start, uc = t <= m + n ? U->col[t] : n;
    if (uc < hi) hi = uc;
  }
  if (L) {
    int t = k - L->start, lc = t >= 0 ? L->col[t] : 0;
    if (lc > lo) lo = lc;
  }
  *a = lo;
  *b = hi;
}

/* Work counts of one or more path computations. */
typedef struct {
  uint64_t nodes;    /* node evaluations (the kernel's work) */
  uint64_t forced;   /* cut edges joined without evaluation */
  uint64_t paths;    /* paths computed */
} band_count;

typedef struct band_ws band_ws;   /* DP arrays and edge bits, reused */

band_ws *band_ws_new(int m, int n);
void band_ws_free(band_ws *ws);

/* The minimum-cost path for start row s inside the band (U, L): fills
 * P->col[0..m+n] and P->cum[0..m+n] (the caller owns both arrays), sets
 * P->start = s and returns its cost in quanta.  Ties: the vertical in-edge.
 * U and L need col and cum.  Adds to *count. */
double band_solve(const weights *w, band_ws *ws, int s, const gpath *U, const gpath *L,
                  gpath *P, band_count *count);

/* The last t' >= t such that U and L share their nodes on diagonals
 * s+t-1 .. s+t' (a run every path for s takes, joined from U's prefix sums),
 * or t-1 if they do not share s+t-1 and s+t. */
int band_shared_until(int m, int n, int s, const gpath *U, const gpath *L, int t);

/* The number of nodes the band's dynamic program evaluates (cut edges
 * excluded): the size |W| of section 7.1. */
int64_t band_size(int m, int n, int s, const gpath *U, const gpath *L);

/* 1 if the single in-band edge into the pinch node on diagonal k is
 * vertical: the band is one node wide on diagonals k-1 and k. */
static inline int band_cut_vertical(int a_prev, int a) { return a == a_prev; }

#endif
