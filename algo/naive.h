/* naive.h -- reference solvers: simple, slow, and independent of the band and
 * kernel code.  Tests check the real solver against them; the tiler's
 * benchmark measures how much faster the real solver is.
 * Both walk the toroidal graph of section 3 directly (weights modulo m, n). */
#ifndef NAIVE_H
#define NAIVE_H

#include "algo/weights.h"

/* Every acceptable path from every start row: C(m+n, m) paths per start.
 * For m, n <= 8 or so.  Returns the optimum in quanta, *start its first
 * start row. */
double naive_brute(const weights *w, int *start);

/* One full dynamic program per start row (m DPs of (m+1)(n+1) nodes), row by
 * row, with the weights tabulated first. */
double naive_dp(const weights *w, int *start);

#endif
