/* overlap.h -- do the regions of two simple polygons overlap?  Exact.
 *
 * The correspondence between slices (surface/match.h) links two contours of
 * neighbouring slices when their regions, projected on one plane, share an
 * interior point: an exact test on the polygons themselves, not on bounding
 * boxes (SlicerRT) or on vertices alone (DICOMautomaton); see the design note
 * shared/design/contours.md, section 2, step 5. */
#ifndef OVERLAP_H
#define OVERLAP_H

#include "inside.h"

/* 1 if the open regions of the simple polygons P and Q (indexed by ip and
 * iq, either orientation) have a common point, else 0.  Boundaries that only
 * touch, or run along each other, do not make an overlap; two equal
 * polygons overlap.  Thread-safe (the indexes are only read). */
int overlap_regions(const inside_index *ip, const inside_index *iq);

#endif
