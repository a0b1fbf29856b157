/* follow.h -- the pair a 1-1 band is tiled on, so that the band follows the
 * structure whatever the sampling of its two contours.
 *
 * The minimum-area band between two contours as they lie is not the
 * structure's surface: between two sections side by side (a tilted tube, a
 * sheared prism) the least area folds inward, and the more points a contour
 * carries the further (two 4.17 mm squares 1.5 mm apart, shifted 3.13 mm:
 * 26.083 mm^3 with 4 points each, 20.649 with 16).  So a 1-1 band is tiled
 * on another pair, and its triangles join the contours where they lie:
 *
 *   - each contour's corners only: a point on the line of its two neighbours
 *     (geom_corners, exact) is set aside, so the correspondence does not
 *     depend on how many collinear points a contour carries;
 *   - the upper contour moved onto the lower's area centroid and scaled
 *     about it to the lower's area (Christiansen and Sederberg's
 *     normalisation, 1978).
 *
 * Why this is exact for prisms and frustums.  Tiled on a pair of the same
 * shape, one over the other at height h, a tile on an edge e has area at
 * least |e| h / 2, with equality exactly when its apex lies over the line of
 * e; every edge of both contours is the base of one tile, so no path costs
 * less than h (perimeter + perimeter) / 2, and the paths that cost that much
 * keep every tile in the vertical plane of its side.  Joined where they lie,
 * those tiles lie in the planes of the solid's faces: a sheared prism, an
 * oblique cylinder of n-gons or a frustum (the upper section a scaled copy
 * of the lower, anywhere) gets its exact volume, whatever collinear points
 * either section carries.
 *
 * The tiler's optimum (the band's cost) is that of the pair it saw; a tile
 * on an edge of the pair whose contour set points aside becomes a fan of
 * tiles on the contour's edges, in one plane, to the same apex: the path is
 * still acceptable on the contours (every edge once from each side, no span
 * twice unless the pair's path uses one twice). */
#ifndef FOLLOW_H
#define FOLLOW_H

#include "geom/geom.h"
#include "algo/tiling.h"

typedef struct {
  int n;        /* points the tiler sees (the contour's corners) */
  vec2 *pt;     /* where it sees them */
  int *at;      /* at[k]: the contour's point that point k is; increasing */
  int full;     /* the contour's points */
} follow_side;

/* The pair for the band from lo[0..nlo-1] (below) to hi[0..nhi-1] (above),
 * both simple, of one orientation: a and b (free with follow_free). */
void follow_pair(const vec2 *lo, int nlo, const vec2 *hi, int nhi, follow_side *a, follow_side *b);

/* The tiles of t (solved on the pair a, b) on the contours: as
 * tiling_tiles, indices into lo and hi, a->full + b->full of them. */
void follow_tiles(const tiling *t, const follow_side *a, const follow_side *b, int (*tile)[3],
                  unsigned char *on);

/* The shadow's weight (weights_new_shadow) for the band from lo (at z0) to
 * hi (at z1, above), a and b their pair (follow_pair), and in *t the pair's
 * solution with it (free with tiling_free).  0 when the band of the plain
 * areas closes, with the two slices' regions, a volume within
 * FOLLOW_TOLERANCE of the frustum's over their areas,
 * h (A0 + A1 + sqrt(A0 A1)) / 3 (signed, as the areas); else the weight,
 * |w| <= FOLLOW_SHADOW_MAX, whose band comes nearest to it: a search of at
 * most FOLLOW_STEPS more solves (follow.c), since the volume never falls
 * as the weight rises.  Prisms and frustums keep 0: their band is exact already.
 * COST_SPAN: 0. */
#define FOLLOW_TOLERANCE 0.002
#define FOLLOW_SHADOW_MAX 0.9375
#define FOLLOW_STEPS 14
double follow_shadow(const follow_side *a, const follow_side *b, const vec2 *lo, const vec2 *hi, double z0,
                     double z1, cost_kind kind, tiling *t);

void follow_free(follow_side *s);

#endif
