/* keyhole.h -- an exact repair of keyhole contours: one contour that runs out
 * along a zero-width channel, around a hole (or another piece), and back;
 * and of zero-width spurs: a spike walked out and back along itself.
 *
 * Treatment planning systems (MIM, Eclipse) export a region with holes or
 * several pieces as one such contour; SlicerRT's FixKeyholes splits them
 * with a tolerance.  Here
 * everything is exact: coordinates are compared bit for bit and collinearity
 * is exact_orient's (exact.h), so a channel whose two sides are 1e-6 apart is
 * no keyhole but a valid simple polygon, tiled as the narrow channel it is.
 *
 * The rule, on a polygon p[0..n-1] (consecutive points distinct):
 *   1. Where two edges run collinear and in opposite directions and overlap,
 *      each gets the other's endpoints that lie strictly inside it, until no
 *      such pair is left (one side of a channel may have extra vertices).
 *   2. The closed walk is split, recursively, at every pair of non-adjacent
 *      vertices with equal coordinates into loops (a stack walk: when a point
 *      comes back, the walk since its last visit is a loop).
 *   3. Loops whose points are all collinear (exact) enclose no area:
 *      dropped.  Joined where they meet off the loops kept, they form
 *      pieces: a piece that meets the loops at two or more points is a
 *      channel (between two loops, or two points of one), a piece that
 *      meets them at one point is a spur (a spike walked out and back
 *      along itself from there).
 *   4. What remains must be one loop or more, each simple, no two touching
 *      or crossing (crossing_find, exact); the pieces may meet the loops
 *      only at their ends on them, and each other only at common ends.
 * Anything else -- a figure eight sharing one vertex, a vertex on another
 * edge, a proper crossing, a spike that crosses or touches the contour
 * elsewhere, an edge walked over twice in one direction -- is no keyhole:
 * keyhole_repair returns 0 and the caller refuses the contour as before.
 * Whether a loop is a hole or a piece is left to nesting
 * (surface/slices.h), never to its winding. */
#ifndef KEYHOLE_H
#define KEYHOLE_H

#include "geom/geom.h"

typedef struct {
  int nloops;      /* loops kept, >= 1 (2 or more when channels > 0) */
  int *first;      /* nloops + 1: loop k is pt[first[k] .. first[k+1]-1] */
  vec2 *pt;        /* their points, each loop in the contour's direction */
  int *src;        /* for each point: the input point with those coordinates
                      that comes first in p (an index into p) */
  int channels;    /* channels dropped (connected out-and-back parts that
                      meet the loops at two or more points) */
  double length;   /* their total length (each counted once, not twice) */
  vec2 at;         /* where a channel meets a loop (the first such channel
                      piece the walk dropped); unset without channels */
  int spurs;       /* spurs dropped (out-and-back parts off one point) */
  double spur_length;   /* their total length (each counted once) */
  vec2 spur_at;    /* where the first spur meets its loop; unset without spurs */
} keyhole_split;

/* Repair the polygon p[0..n-1] (n >= 3, consecutive points distinct, p[n-1]
 * != p[0], finite) by the rule above: 1 and *out when it is a keyhole
 * contour or has spurs (free with keyhole_free), else 0 and nothing
 * allocated.  Call it
 * on a contour that crossing_find refused: a simple polygon returns 0.
 * O(N log N + K) for N points and K pairs of edges whose boxes overlap (per
 * round of step 1; rounds are few). */
int keyhole_repair(const vec2 *p, int n, keyhole_split *out);

void keyhole_free(keyhole_split *k);

#endif
