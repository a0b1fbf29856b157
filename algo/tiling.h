/* tiling.h -- the exact optimal tiling between two contours: the minimum-cost
 * acceptable path over ALL start rows, in O(mn log m) (Fuchs, Kedem, Uselton;
 * the paper's serial algorithm, section 3.2).
 *
 *   shortestpath(G): mu(0) by one DP on the 2m x n planar graph; mu(m) is its
 *   copy m rows down; then findallpaths(0, m): mu(mid), mid = (lo+hi)/2, is
 *   computed only inside the band between mu(lo) and mu(hi), and the two
 *   halves recurse.  The answer is the cheapest mu(i), ties to the smaller i.
 *
 * The smaller contour is doubled (its points are the rows), so the recursion
 * runs over its points. */
#ifndef TILING_H
#define TILING_H

#include <stdint.h>

#include "algo/band.h"
#include "algo/weights.h"

typedef struct {
  double cost;       /* the optimum: quanta * quantum */
  double quanta;     /* the optimum in quanta, an exact integer */
  double quantum;    /* see weights.h: 2^qexp */
  int qexp;          /* cost = ldexp(quanta, qexp): inf or 0 beyond double's range */
  int start;         /* its start row in the rows contour */
  int m, n;          /* rows and columns of the graph, m <= n */
  int transposed;    /* 0: the rows are the first contour of the pair; 1: the second */
  double shadow;     /* the weights' (weights_new_shadow); 0 for plain areas */
  int *col;          /* the optimal path, col[t] for t = 0..m+n (band.h) */
  band_count count;  /* work done */
} tiling;

/* Solve with the rows and columns of w as they are (no transposition).
 * Fills *out; free with tiling_free. */
void tiling_solve_w(const weights *w, tiling *out);

/* Solve the pair (P: np points at zp, Q: nq points at zq), rows = the smaller
 * contour (P when np == nq).  table as in weights_new. */
void tiling_solve(const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq,
                  cost_kind kind, int table, tiling *out);

/* The same on weights_new_shadow's weights. */
void tiling_solve_shadow(const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq,
                         cost_kind kind, double shadow, int table, tiling *out);

void tiling_free(tiling *t);

/* The best of mu(i), U->start < i < L->start, between U and L, by the same
 * divide and conquer (findallpaths): what a group of one slave solves on its
 * own (paper, section 5).  best->col must hold m+n+1 ints; best->quanta must
 * be set by the caller (HUGE_VAL, or a best already known: a path replaces
 * it only if cheaper, or as cheap with a smaller start). */
typedef struct {
  double quanta;   /* in quanta */
  int start;
  int *col;
} tiling_best;

void tiling_range(const weights *w, band_ws *ws, const gpath *U, const gpath *L,
                  tiling_best *best, band_count *count);

/* The tiles of the path, in path order: for t = 1..m+n, tile[t-1] gets the
 * indices (into P and Q of the pair, not rows/columns) of the triangle the
 * t-th step adds: {edge start, edge end, apex} and on[t-1] = 0 when the edge
 * lies on P, 1 when on Q. */
void tiling_tiles(const tiling *t, int (*tile)[3], unsigned char *on);

/* The cost of t's path in the pair's own numbers: every tile's weight (the
 * triangle's area, or the span it adds, as weights.h defines them) computed
 * without rounding to quanta and summed in path order, at any scale (the
 * pair is scaled by a power of two first, as weights.c scales it).
 * t->cost sums the weights rounded to the pair's quantum, exact as a whole
 * number of quanta, and a quantum is about 2^-52 (m + n) of the largest tile
 * of the graph: next to that tile the path's own can be small (slices very
 * close for the contours' width), and t->cost then lies far from the path's
 * true cost (2.25e15 for 3.41e15 at 1e15 wide and 1 apart; 0 at 1e20).
 * This is the true one, to the tiles' own rounding, with t->shadow times
 * the tiles' shadows added when it is not 0.  P, np, zp, Q, nq, zq, kind as
 * given to tiling_solve (or the weights t was solved on). */
double tiling_path_cost(const tiling *t, const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq,
                        cost_kind kind);

/* The spans the path uses twice.  The paper allows it
 * (section 3: an acceptable path may be "two vertex-simple cycles that share
 * one vertex"): when the path takes all m vertical steps at one column, one
 * point of one contour fans the whole other contour and the span at both ends
 * of that run is the same; likewise all n horizontal steps at one row.  The
 * band's mesh then has that edge in four triangles: pinched, not a 2-manifold
 * (surface/unpinch.h replaces such a path).  Writes up to max spans as
 * {index into P, index into Q} (the pair as given to tiling_solve, like
 * tiling_tiles), each once, in path order of first use, and returns how many
 * there are: 0 for a path that uses every span once (span may be NULL with
 * max 0 to count).  O(m + n) time and memory. */
int tiling_repeated_spans(const tiling *t, int (*span)[2], int max);

/* The start row the divide and conquer gives the two halves of (lo, hi). */
static inline int tiling_mid(int lo, int hi) { return lo + (hi - lo) / 2; }

#endif
