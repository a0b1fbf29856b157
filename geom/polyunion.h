/* polyunion.h -- the union of overlapping simple polygons, exactly.
 *
 * The polygons of one slice whose boundaries meet (cross, touch, overlap)
 * form groups; each group of two or more is replaced by the boundary of the
 * union of its polygons' closed regions: outer loops counter-clockwise, the
 * holes the union encloses clockwise.  Polygons that meet no other are left
 * alone (one inside another stays a hole or an island, by nesting).
 *
 * What "exact" means.  Every decision is exact for any finite doubles, with
 * no tolerance: which segments meet and how (crossing.h), where the points
 * on a segment come in order, which points coincide, the order of the edges
 * around a point, and so which pieces of which edges bound the union.  The
 * points are the input vertices and the crossings of two input edges; a
 * crossing is a rational point, computed as one (big integers at the scale of
 * the group's least significant bit, bigz.h), never rounded for a decision.
 * The boundary is the arrangement's edges with covered faces on one side and
 * the uncovered plane on the other: the faces' winding numbers (each polygon
 * counter-clockwise, so a point's winding number is how many polygons cover
 * it) from the unbounded face across edges that several polygons may share,
 * in either direction (shared edges inside the union drop out exactly).
 * Only then is each new vertex rounded, once, to the nearest double
 * (correctly rounded: within half an ulp of the exact crossing in each
 * coordinate; an input vertex is kept as it is).
 *
 * Keeping the result valid.  Before rounding the loops are simple and
 * disjoint by construction, unless the union pinches: a point where it
 * touches itself (two regions meeting at a corner, a hole touching the outer
 * boundary at one point), which no set of simple, disjoint contours can
 * describe -- refused (POLYUNION_PINCH, with the point).  After rounding,
 * consecutive vertices that became equal are merged, and the loops are
 * checked with the exact crossing test: if rounding made a loop degenerate
 * or two pieces of boundary cross or touch (crossings within an ulp of
 * another edge), the union is refused (POLYUNION_ROUNDING, with the point)
 * rather than returned invalid.
 *
 * Cost: O(N log N + K) segment pairs whose boxes overlap in x (a sweep) for
 * N points, then O((N + C) log (N + C)) for C crossings, big-integer work
 * only at the crossings and where rounded values tie. */
#ifndef POLYUNION_H
#define POLYUNION_H

#include "geom/crossing.h"
#include "geom/geom.h"

typedef enum { POLYUNION_OK = 0, POLYUNION_PINCH, POLYUNION_ROUNDING } polyunion_status;

typedef struct {
  int ngroups;       /* groups of two or more polygons whose boundaries meet */
  int *group;        /* per input polygon: its group, or -1 when it meets no other */
  int *members;      /* per group: its polygons (how many: members_of) */
  int *gfirst;       /* ngroups + 1: group g's loops are gfirst[g] .. gfirst[g+1]-1 */
  int nloops;
  int *first;        /* nloops + 1: loop k is pt[first[k] .. first[k+1]-1] */
  vec2 *pt;
  int *hole;         /* per loop: 1 for a hole of the union (clockwise), 0 outer */
  int *src;          /* per loop: the least input polygon along whose edges it runs */
  int *newpts;       /* per group: its loops' vertices that are crossings (new) */
  int *gmember;      /* ngroups + 1: group g's polygons are members[gmember[g] ..] */
  polyunion_status status;
  int bad_group;     /* on failure: the first group that failed, and a point where it fails */
  vec2 at;
  polyunion_status *gstatus;   /* per group (a failed group has no loops) */
  vec2 *gat;         /* per group: where it failed */
  int *nested;       /* per group, POLYUNION_NEST: 1 when every two of its polygons in
                        contact lie one inside the other (a hole on its outer boundary) */
  int *pinches;      /* per group, POLYUNION_SPLIT: points where its region touched
                        itself, split (the first at pinch_at[g]) */
  vec2 *pinch_at;
} polyunion_result;

/* The union of the groups of p[0..np-1] (each simple, n >= 3, consecutive
 * points distinct, either orientation; crossing.h's preconditions).  0 and
 * *out (free with polyunion_free), or -1 with out->status, bad_group and at
 * (and the groups filled, every group tried, each with its gstatus; free it
 * too). */
int polyunion(const crossing_poly *p, int np, polyunion_result *out);

/* The same with flags:
 *   POLYUNION_NEST   a polygon that lies inside another of its group (every
 *                    point of its closed region in the other's: a hole drawn
 *                    on its outer contour's boundary) and meets only
 *                    polygons around it or inside it is not merged but
 *                    nests as on a slice without contacts: its depth is the
 *                    longest chain of the group's polygons around it, and
 *                    the region is where the deepest polygon covering a
 *                    point lies at even depth (a hole takes its region out,
 *                    an island in it puts it back).  A polygon that meets
 *                    one neither around nor inside it is a piece of a union
 *                    (depth 0): overlapping pieces still give their union,
 *                    and a hole drawn across its outer contour is filled.
 *                    Decided on the arrangement's faces, exactly.
 *                    nested[g] says whether the group has no such pieces.
 *   POLYUNION_SPLIT  where the region touches itself at a point (two pieces
 *                    meeting at a corner, a hole touching its outer boundary)
 *                    it is split there into loops that keep to one wedge
 *                    each, instead of refused; the loops that met at the
 *                    point are then kept apart: each but one has its corner
 *                    there cut 2^-20 of the way along its two edges, inside
 *                    the free sector between them (an area of about 2^-41
 *                    of the edges' product: nothing a double can miss is
 *                    lost), and the whole group is checked exactly as after
 *                    rounding.  pinches[g] counts those points. */
enum { POLYUNION_NEST = 1, POLYUNION_SPLIT = 2 };
int polyunion_flags(const crossing_poly *p, int np, int flags, polyunion_result *out);

void polyunion_free(polyunion_result *u);

#endif
