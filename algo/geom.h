/* geom.h -- plane geometry of contours: points, polygon area, orientation. */
#ifndef GEOM_H
#define GEOM_H

typedef struct { double x, y; } vec2;

/* Twice the signed area of the closed polygon p[0..n-1] (shoelace, about
 * its first point): positive when counter-clockwise seen from +z.  Floating
 * point: it overflows to inf (or NaN) for coordinates near 1e154 and beyond
 * and loses all precision among subnormals; use geom_orientation for the sign. */
double geom_area2(const vec2 *p, int n);

/* 1 if every point of p[0..n-1] lies exactly on one line (or all coincide),
 * else 0.  Exact for any finite coordinates (exact.h): no tolerance. */
int geom_collinear(const vec2 *p, int n);

/* +1 if the polygon p[0..n-1] runs counter-clockwise seen from +z, -1 if
 * clockwise, 0 if degenerate.  Exact for a simple polygon (crossing.h): the
 * turn at its lexicographically lowest vertex, which is convex.  For one that
 * is not simple (where the orientation is not defined) the sign of its area,
 * computed on a copy scaled by a power of two so it cannot overflow. */
int geom_orientation(const vec2 *p, int n);

/* Reverse p[0..n-1] in place, keeping p[0] first. */
void geom_reverse(vec2 *p, int n);

#endif
