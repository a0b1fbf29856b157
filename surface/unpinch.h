/* unpinch.h -- a band whose optimal path uses one span twice, and the best
 * path that does not.
 *
 * An acceptable path (the paper, section 3) may take all m vertical steps at
 * one column: one vertex of the upper contour then fans the whole lower
 * contour (R^j D^m R^(n-j)), and the span from it to the run's row appears
 * at both ends of the run; or all n horizontal steps at one row.  The band
 * is then two cones sharing an edge of four triangles, not a tube: the mesh
 * is not a 2-manifold there.  The exact tiler can choose
 * such a path when one contour is small and far offset from the other (two
 * 4-point vessels in dicompyler's Lt Lung).  These are exactly the paths
 * with at most one run of vertical, or of horizontal, steps around the
 * cycle; every other path uses each span once.  unpinch_solve finds the
 * cheapest path with at least two runs of each, over all start rows, by a
 * dynamic program that counts runs (64 states a node, O(m^2 n)), with the
 * tiler's exact weights (algo/weights.h): the minimum-cost manifold band. */
#ifndef UNPINCH_H
#define UNPINCH_H

#include "algo/tiling.h"

/* How many spans the path of t uses twice: 1 when it has at most one run of
 * vertical or of horizontal steps around the cycle (the full run's two ends
 * are one span), else 0. */
int unpinch_repeats(const tiling *t);

/* The cheapest path of the pair (as tiling_solve_shadow: rows the smaller
 * contour, P when equal) that uses no span twice, in *out (free with
 * tiling_free).
 * Returns 0, or -1 when the pair is too large for the O(m^2 n) program
 * (m^2 n > 2^22 nodes; out untouched) or no such path exists (m or n < 2). */
int unpinch_solve(const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq, cost_kind kind,
                  double shadow, tiling *out);

#endif
