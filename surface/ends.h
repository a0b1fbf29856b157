/* ends.h -- where the surface ends: the regions of a slice that have no band
 * on one side, and their caps (flat, surface/flatcap.h, or apex,
 * surface/apex.h).
 *
 * On slice k, let U be the contours with no band above (for the caps on top)
 * or below (for the bottom).  A contour's children are in U whenever it is
 * (surface/match.h: a contour is linked only if its parent is), so U is a
 * union of subtrees of the nesting forest, and its regions are: each contour
 * of U whose parent is not in U (or is a hole of another region), less its
 * children.  So a hole that ends caps the hole less the islands in it (which
 * end there too, their tops merging into the material above), an outer
 * boundary that ends caps itself less its holes, and a region never gets two
 * caps.  A top cap faces +z over material (the region's own orientation), a
 * bottom cap -z; holes' caps face into the cavity by the same rule, their
 * contours running clockwise. */
#ifndef ENDS_H
#define ENDS_H

#include "surface/mesh.h"
#include "surface/slices.h"

typedef struct {
  int slice;
  int up;           /* 1: the top of the slice's material (no band above), 0: the bottom */
  int outer;        /* the region's boundary (index into sl->c) */
  int nholes;
  int *holes;       /* its holes, increasing */
  int isolated;     /* the boundary has no band on either side */
} end_region;

/* The regions, slice by slice, bottoms before tops, by boundary index.
 * band_up[c], band_down[c]: contour c has a band above / below. */
int ends_plan(const slices *sl, const unsigned char *band_up, const unsigned char *band_down,
              end_region **out);
void ends_free(end_region *r, int n);

typedef struct {
  int ntri;
  int (*tri)[3];    /* mesh vertex ids; -1-k is the cap's new vertex k */
  int nnew;         /* new vertices: 1 for an apex, more for a slab */
  vec3 *at;         /* their positions */
} end_cap;

/* The cap of region r: an apex cap when `apex` or the region is isolated
 * (a single-slice piece), where the region has no holes and is star-shaped;
 * else flat.  An isolated region that cannot have apex caps becomes a slab
 * instead: two flat caps in one plane would share their diagonals (edges of
 * four triangles) and enclose nothing.  Its contours are copied a sixth of
 * the slice spacing above and below (the lens's volume, A spacing / 3),
 * joined to the copies by strips of two triangles an edge, and the copies
 * capped flat; the whole slab goes with the top region, the bottom one gets
 * no triangles.  A stack of one slice has no spacing: every region becomes
 * such a slab, its copies `half` above and below (the slab's volume: the
 * region's area times 2 half).  Thread-safe. */
void ends_cap(const slices *sl, const end_region *r, int apex, double half, end_cap *out);
void ends_cap_free(end_cap *c);

#endif
