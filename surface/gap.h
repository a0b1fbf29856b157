/* gap.h -- how far apart two contours of neighbouring slices lie in the
 * plane: the least distance between their boundaries, exactly comparable
 * (geom/exactdist.h), for the joins of surface/match.h and their notes.
 *
 * For two simple polygons whose boundaries do not cross, the least distance
 * between them is that from a vertex of one to a segment of the other, so it
 * is the least of those (a segment's distance to a point decided exactly);
 * boundaries that touch give 0.  The witness is the first least pair in a
 * fixed order on the canonical contours (slices.h), so the result does not
 * depend on the file's order, start points or winding. */
#ifndef GAP_H
#define GAP_H

#include "geom/exactdist.h"
#include "surface/slices.h"

/* The least distance between the boundaries of A and B (their regions must
 * not overlap: contours of one slice, or of neighbouring slices that were
 * not linked).  Thread-safe. */
void gap_between(const slice_contour *A, const slice_contour *B, exactdist *out);

/* A lower bound on it from the two bounding boxes, squared: 0 when they meet. */
double gap_box_bound(const slice_contour *A, const slice_contour *B);

#endif
