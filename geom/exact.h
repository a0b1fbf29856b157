/* exact.h -- exact orientation of three points, for any finite doubles.
 *
 * exact_orient(a, b, c) is the sign of the determinant
 *     | bx-ax  by-ay |
 *     | cx-ax  cy-ay |
 * computed as if in exact arithmetic: +1 when c lies to the left of the
 * directed line a->b (a, b, c counter-clockwise), -1 to its right, 0 when the
 * three points are exactly collinear.  It holds for every finite double,
 * from subnormals (2^-1074) to DBL_MAX, and is unchanged by scaling all
 * three points by a power of two: no tolerance, no overflow, no underflow.
 *
 * How: a floating-point evaluation with Shewchuk's error bound (Adaptive
 * Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates,
 * 1997, the bound of orient2dfast) decides whenever its result is safely away
 * from zero and no intermediate overflowed or underflowed; otherwise the six
 * products of the expanded determinant
 *     bx cy - bx ay - ax cy - by cx + by ax + ay cx
 * are each an exact 106-bit integer times a power of two (every double is
 * M 2^E with |M| < 2^53), and their sum is formed exactly in a big integer as
 * wide as the exponents' spread (at most 4,300 bits) and its sign read off. */
#ifndef EXACT_H
#define EXACT_H

#include "geom/geom.h"

/* +1, 0 or -1 (see above).  The points must be finite. */
int exact_orient(vec2 a, vec2 b, vec2 c);

/* The same, always through the big-integer sum (no floating-point filter):
 * slower; for tests that check the filter against it. */
int exact_orient_slow(vec2 a, vec2 b, vec2 c);

/* Lexicographic order of points (x, then y): -1, 0 or +1.  Exact. */
static inline int exact_lex(vec2 a, vec2 b) {
  if (a.x != b.x) return a.x < b.x ? -1 : 1;
  if (a.y != b.y) return a.y < b.y ? -1 : 1;
  return 0;
}

#endif
