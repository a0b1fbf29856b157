/* exactdist.h -- distances from points to segments, compared exactly.
 *
 * The squared distance from a point p to a segment ab is either the squared
 * distance to an end, |p - a|^2, or, where p projects into the segment's
 * interior, the squared distance to its line,
 *     ((b - a) x (p - a))^2 / |b - a|^2,
 * a ratio of polynomials in the coordinates.  An exactdist holds which of the
 * two it is (decided exactly: the sign of (p - a).(b - a), by the same filter
 * and big-integer fallback as exact.h) and an interval of doubles that
 * certainly holds the value.  Two of them are compared by their intervals
 * where those are apart, and otherwise exactly: the coordinates, each an
 * integer times a power of two, are brought to one power of two and the
 * cross-multiplied polynomials (degree 6 at most) formed in big integers.  So
 * the answers hold for any finite doubles, with no tolerance, and do not
 * change when every point is scaled by a power of two.  Used to find the
 * nearest contour of a neighbouring slice (surface/gap.h). */
#ifndef EXACTDIST_H
#define EXACTDIST_H

#include "geom/geom.h"

enum { EXACTDIST_POINT, EXACTDIST_LINE };

typedef struct {
  vec2 p, a, b;     /* POINT: |p - a|^2 (b unused); LINE: to the line ab, squared */
  int kind;
  double lo, hi;    /* the value lies in [lo, hi] (hi may be inf) */
  double approx;    /* the value, rounded: for messages */
} exactdist;

/* |p - a|^2. */
void exactdist_points(vec2 p, vec2 a, exactdist *d);

/* The squared distance from p to the closed segment ab (a != b). */
void exactdist_segment(vec2 p, vec2 a, vec2 b, exactdist *d);

/* -1, 0 or +1 as x's value is less than, equal to or greater than y's. */
int exactdist_cmp(const exactdist *x, const exactdist *y);

/* The same against r^2 (r >= 0, finite): -1, 0 or +1. */
int exactdist_cmp_len(const exactdist *x, double r);

/* The same as exactdist_cmp, always through the big integers (no interval
 * filter): slower; for tests that check the filter against it. */
int exactdist_cmp_slow(const exactdist *x, const exactdist *y);

/* The distance itself (the square root of approx). */
double exactdist_value(const exactdist *d);

#endif
