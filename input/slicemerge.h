/* slicemerge.h -- contours of one slice that repeat or overlap each other.
 *
 * Planning systems export the same region several times on a slice (Monaco
 * writes the outline three times, from other start points, with extra
 * collinear points) and regions drawn in overlapping pieces.
 *
 * Duplicates (always).  Two contours of a slice are the same region when
 * they have the same points up to start point, direction and collinear
 * points: each with every point that lies exactly between its neighbours on
 * their line removed (exact_orient), from its least point, counter-clockwise,
 * is the same sequence.  One is kept -- the one with fewest points, then the
 * least sequence from its least point, then the first in the file: so the
 * stack does not depend on the file's order -- and the others are dropped
 * with a note.
 *
 * Union (always).  Contours of a slice whose boundaries meet (cross, touch,
 * overlap) are replaced by the boundary of the union of their regions
 * (geom/polyunion.h: exact; holes the union encloses included, a hole drawn
 * on its outer contour's boundary kept as a hole, a union that touches
 * itself at a point split there); contours that meet no other keep their
 * role by nesting (surface/slices.h), so a contour inside a union's boundary
 * is a hole of it.  A union whose rounded new vertices would make contours of
 * the slice meet is refused.  SLICEMERGE_UNION (--union) changes the notes
 * only: the merges said as --union's (one line for all, -v one a group);
 * without it one line for the holes on their outer contours' boundaries and
 * one a slice whose overlapping pieces were merged. */
#ifndef SLICEMERGE_H
#define SLICEMERGE_H

#include <stddef.h>

#include "input/contour.h"
#include "util/strbuf.h"

enum { SLICEMERGE_UNION = 1, SLICEMERGE_VERBOSE = 2 };

/* The contours cs[0..*ncs-1] (points counter-clockwise, each with its
 * slice, the slices' z snapped), their places named by pl: duplicates
 * dropped and overlapping ones merged; cs may be reallocated and
 * reordered.  Notes ("PREFIX: NAME:LINE: ...", as pl names places) are
 * appended to notes: one line for all
 * duplicates and one for all unions (without SLICEMERGE_UNION: one for the
 * nested groups, and one a slice for its overlapping pieces), or with
 * SLICEMERGE_VERBOSE one for each.  0, or -1 with "NAME:LINE: ..." in err
 * (the contours are then still the caller's to free). */
int slicemerge(contour **cs, int *ncs, int flags, const contour_places *pl, const char *prefix, strbuf *notes,
               char *err, size_t errlen);

#endif
