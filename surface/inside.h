/* inside.h -- where a point lies against a simple polygon (inside, on its
 * boundary, outside), exactly, through a row index of its segments.
 *
 * The index cuts the polygon's y extent into rows and lists in each row the
 * segments whose y range meets it, so a query looks at the few segments of
 * one row (about O(1) for a contour of short segments, O(n) at worst).  The
 * rows only filter; every decision is an exact orientation (geom/exact.h), so
 * the answers hold for any finite doubles.  An index is read-only once built:
 * any number of threads may query it at once. */
#ifndef INSIDE_H
#define INSIDE_H

#include "geom/geom.h"

typedef struct inside_index inside_index;

enum { INSIDE_OUT = -1, INSIDE_ON = 0, INSIDE_IN = 1 };

/* Index the polygon p[0..n-1] (n >= 3, closing point not repeated; kept by
 * the caller, not copied).  Either orientation. */
inside_index *inside_new(const vec2 *p, int n);
void inside_free(inside_index *ix);

/* INSIDE_IN, INSIDE_ON or INSIDE_OUT for the point q (crossing number of the
 * ray from q to +x, half-open in y; ON when q lies on a segment). */
int inside_point(const inside_index *ix, vec2 q);

/* Call fn(ud, s) once for every segment s (p[s] to p[s+1 mod n]) whose
 * bounding box meets that of the segment ab (closed boxes); in increasing
 * row order, so the same query gives the same order. */
void inside_near(const inside_index *ix, vec2 a, vec2 b, void (*fn)(void *ud, int s), void *ud);

/* 1 if the segment ab meets the polygon's boundary anywhere but exactly at
 * the points ok1 and ok2 (a contact there is allowed: a bridge's own end on
 * its own contour; NaN for none), including a collinear run; else 0.  Exact
 * (geom/crossing.h). */
int inside_segment_meets(const inside_index *ix, vec2 a, vec2 b, vec2 ok1, vec2 ok2);

/* The polygon's bounding box. */
void inside_box(const inside_index *ix, vec2 *lo, vec2 *hi);

const vec2 *inside_points(const inside_index *ix, int *n);

#endif
