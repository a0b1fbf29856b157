/* crossing.h -- where closed polygons cross or touch: exact predicates and a
 * sweep that finds one offending pair of segments in O(N log N).
 *
 * A polygon is its points p[0..n-1] (closing point not repeated); segment s
 * runs from p[s] to p[(s+1) % n].  Two segments of a polygon are neighbours
 * when one ends where the other starts (s and s+1 mod n).
 *
 * What counts.  Two segments OFFEND when they share any point, except two
 * neighbours of one polygon whose only common point is their shared vertex.
 * So a set of polygons has no offending pair exactly when every polygon is
 * simple (no self-crossing, no vertex on another edge, no repeated vertex, no
 * edge running back over its neighbour) and no two polygons' boundaries meet
 * (one may lie inside another: nesting is not an offence).
 *
 * Everything is exact for any finite doubles (exact.h): no tolerance, so a
 * vertex 1e-300 off a segment is off it, and the answer does not change when
 * all points are scaled by a power of two.
 *
 * Preconditions (the contour reader guarantees them): n >= 3; consecutive
 * points differ (p[n-1] != p[0] too); points finite.  A violation is a bug in
 * the caller and aborts (xmem.h's XASSERT). */
#ifndef CROSSING_H
#define CROSSING_H

#include "geom/geom.h"

typedef struct {
  const vec2 *pt;   /* the points (not copied, not freed) */
  int n;            /* >= 3 */
} crossing_poly;

typedef enum {
  CROSSING_NONE = 0,   /* no common point (or neighbours meeting at their vertex) */
  CROSSING_CROSS,      /* the interiors cross at one point, no endpoint on the other */
  CROSSING_TOUCH,      /* one common point, an endpoint of one or both */
  CROSSING_OVERLAP     /* collinear, sharing more than one point */
} crossing_kind;

/* An offending pair: segment seg[0] of polygon poly[0] and segment seg[1] of
 * polygon poly[1], with (poly[0], seg[0]) < (poly[1], seg[1]) in lexicographic
 * order.  at: a point both share -- exact for TOUCH and OVERLAP (a vertex),
 * the rounded intersection for CROSS. */
typedef struct {
  crossing_kind kind;
  int poly[2], seg[2];
  vec2 at;
} crossing_hit;

/* The contact of the closed segments ab and cd (a != b, c != d), exactly.
 * *at (may be NULL) gets a common point as in crossing_hit. */
crossing_kind crossing_segments(vec2 a, vec2 b, vec2 c, vec2 d, vec2 *at);

/* Find an offending pair among the np polygons p[0..np-1] (self and mutual).
 * Returns 1 and fills *hit, or 0 when there is none.  O(N log N) time and
 * O(N) memory for N points in all (a Shamos-Hoey sweep).  Deterministic: the
 * same polygons in the same order give the same pair; which pair, when there
 * are several, is otherwise unspecified (often the leftmost contact). */
int crossing_find(const crossing_poly *p, int np, crossing_hit *hit);

/* The same by checking every pair of segments, O(N^2): the reference the
 * tests hold crossing_find to.  Reports the first offending pair in
 * (poly[0], seg[0], poly[1], seg[1]) order. */
int crossing_find_brute(const crossing_poly *p, int np, crossing_hit *hit);

/* Does the segment ab (a != b) cross or touch any segment of the polygons?
 * Contacts at exactly the point a are allowed when allow & CROSSING_ALLOW_A,
 * at exactly b when allow & CROSSING_ALLOW_B (a bridge from a vertex: its own
 * polygon's two segments at that vertex touch it there); any other common
 * point, and any collinear overlap, is not.  Returns 1 and fills *hit with the
 * first offending polygon segment in (poly, seg) order in poly[0], seg[0]
 * (poly[1] = seg[1] = -1), or 0.  O(N). */
enum { CROSSING_ALLOW_A = 1, CROSSING_ALLOW_B = 2 };
int crossing_segment(const crossing_poly *p, int np, vec2 a, vec2 b, int allow,
                     crossing_hit *hit);

/* "crosses", "touches", "overlaps" (or "meets nothing" for NONE): a verb for
 * messages such as "the segment from line 3 to line 4 crosses the segment ...". */
const char *crossing_verb(crossing_kind k);

#endif
