/* overlap.h -- do the regions of two simple polygons overlap?  Exact.
 *
 * The correspondence between slices (surface/match.h) links two contours of
 * neighbouring slices when their regions, projected on one plane, share an
 * interior point: an exact test on the polygons themselves, not on bounding
 * boxes (SlicerRT) or on vertices alone (DICOMautomaton); doc/surface.md,
 * "Several contours per slice". */
#ifndef OVERLAP_H
#define OVERLAP_H

#include "surface/inside.h"

/* 1 if the open regions of the simple polygons P and Q (indexed by ip and
 * iq, either orientation) have a common point, else 0.  Boundaries that only
 * touch, or run along each other, do not make an overlap; two equal
 * polygons overlap.  Thread-safe (the indexes are only read). */
int overlap_regions(const inside_index *ip, const inside_index *iq);

/* Do the closed regions of P and Q meet?  OVERLAP_APART when they have no
 * common point, OVERLAP_TOUCH when they share only boundary points (an edge
 * or a corner: the open regions are apart), OVERLAP_INTERIOR when the open
 * regions overlap (overlap_regions).  Exact; thread-safe.  Cheaper than
 * overlap_regions where the boundaries do not meet: a contour inside the
 * other, or apart, is decided by one point each and a scan of the segments,
 * and only boundaries that touch take overlap_regions' further tests. */
enum { OVERLAP_APART, OVERLAP_TOUCH, OVERLAP_INTERIOR };
int overlap_closed(const inside_index *ip, const inside_index *iq);

#endif
