/* hull.h -- the convex hull of a point set, and its extreme point in a
 * direction: what bounds the largest tile weight (weights.c). */
#ifndef HULL_H
#define HULL_H

#include "geom/geom.h"

typedef struct hull hull;

/* The convex hull of p[0..n-1] (n >= 1, finite), by Andrew's monotone chain
 * with exact orientations (exact.h): its vertices counter-clockwise, no three
 * collinear.  O(n log n).  The caller keeps p. */
hull *hull_new(const vec2 *p, int n);
void hull_free(hull *h);

int hull_size(const hull *h);
vec2 hull_vertex(const hull *h, int i);   /* 0 <= i < hull_size */

/* A hull vertex v maximizing dx v.x + dy v.y, found in O(log n) by the
 * angles of the hull's edges.  Up to rounding: where several vertices come
 * within a few ulp of the maximum, any of them (it checks the neighbours of
 * the one the angles give). */
vec2 hull_extreme(const hull *h, double dx, double dy);

#endif
