/* geom.h -- plane geometry of contours: points, polygon area, orientation. */
#ifndef GEOM_H
#define GEOM_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

typedef struct { double x, y; } vec2;

/* Twice the signed area of the closed polygon p[0..n-1] (shoelace, about
 * its first point): positive when counter-clockwise seen from +z.  Computed
 * on the points scaled by a power of two that brings the largest coordinate
 * into [1/2, 1), then scaled back: never NaN; +-inf when the area is beyond a
 * double's range (coordinates near 1e300), 0 below it (near 1e-300), so use
 * geom_orientation for the sign. */
double geom_area2(const vec2 *p, int n);

/* The same for the points multiplied by 2^-e (exactly, before any
 * arithmetic): for sums kept at one scale, e.g. e = geom_scale_exp(...). */
double geom_area2_at(const vec2 *p, int n, int e);

/* The e for which m 2^-e lies in [1/2, 1) (0 for m = 0): the scale that makes
 * coordinates of magnitude at most m safe to multiply.
 * Inline, as frexp's, read from the bits where m is a positive normal double:
 * areas and volumes take it once a triangle. */
static inline int geom_scale_exp(double m) {
  uint64_t b;
  memcpy(&b, &m, sizeof b);
  int x = (int)(b >> 52);   /* sign and exponent */
  if (x > 0 && x < 0x7ff) return x - 1022;
  int e = 0;
  if (m > 0) frexp(m, &e);
  return e;
}

/* ldexp(x, e), the same bits, inline: where 2^e is a normal double, x times
 * 2^e, which is the exact product rounded once, as ldexp's result is (a
 * multiplication by a power of two is exact unless it overflows or leaves a
 * subnormal, and then both round the exact value to nearest).  The scaled
 * areas and volumes take it for every coordinate. */
static inline double geom_ldexp(double x, int e) {
#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
  return ldexp(x, e);   /* x87: a product held wider would round twice into a subnormal */
#endif
  if (e < -1022 || e > 1023) return ldexp(x, e);
  uint64_t b = (uint64_t)(e + 1023) << 52;
  double f;
  memcpy(&f, &b, sizeof f);
  return x * f;
}

/* 1 if every point of p[0..n-1] lies exactly on one line (or all coincide),
 * else 0.  Exact for any finite coordinates (exact.h): no tolerance. */
int geom_collinear(const vec2 *p, int n);

/* The corners of the simple polygon p[0..n-1]: the points that do not lie
 * on the line of their two neighbours (exact orientation; a simple polygon
 * has no spike, so a point on that line lies between them).  Their indices,
 * increasing, go to keep[]; returns how many (>= 3 unless p is degenerate).
 * Removing the others changes no edge's line and no region. */
int geom_corners(const vec2 *p, int n, int *keep);

/* The area centroid of the polygon p[0..n-1] (computed about p[0]); p[0]
 * when its area is 0. */
vec2 geom_centroid(const vec2 *p, int n);

/* +1 if the polygon p[0..n-1] runs counter-clockwise seen from +z, -1 if
 * clockwise, 0 if degenerate.  Exact for a simple polygon (crossing.h): the
 * turn at its lexicographically lowest vertex, which is convex.  For one that
 * is not simple (where the orientation is not defined) the sign of its area,
 * computed on a copy scaled by a power of two so it cannot overflow. */
int geom_orientation(const vec2 *p, int n);

/* An interval of one coordinate that item i covers, for sweeps that pair
 * the items whose intervals overlap. */
typedef struct {
  double lo, hi;
  int i;
} geom_span;

/* Sort s[0..n-1] by lo, ties by i: the same order on every machine. */
void geom_span_sort(geom_span *s, int n);

/* A weight and two indices, for choices taken cheapest first (bridges,
 * cuts): geom_pick_sort orders them by w, then a, then b, the same on
 * every machine. */
typedef struct {
  double w;
  int a, b;
} geom_pick;

void geom_pick_sort(geom_pick *p, size_t n);

/* Reverse p[0..n-1] in place, keeping p[0] first. */
void geom_reverse(vec2 *p, int n);

#endif
