/* bridge.h -- composite contours: several contours of one slice joined by
 * bridges into one closed polygon, so that an n-m junction is tiled by the
 * exact two-contour tiler (algo/tiling.h) like a 1-1 band.
 *
 * The idea is Christiansen and Sederberg's (1978) and Meyers, Skinner and
 * Sloan's (1992): a composite contour through a bridge whose middle sits
 * between the slices.  The construction here keeps the surface a closed
 * 2-manifold (doc/surface.md, "Several contours per slice", with one change,
 * below).  A bridge joins edge a0->a1 of one polygon to edge
 * b0->b1 of another, the two facing each other:
 *
 *        a1 ---- m2 ---- b0          composite: ... a0 m1 b1 ... b0 m2 a1 ...
 *        |                |          fill:  (a0 a1 m2) (a0 m2 m1)
 *        |   corridor     |                 (m2 b0 b1) (m2 b1 m1)
 *        a0 ---- m1 ---- b1          (reversed when the partner is below)
 *
 * m1 and m2 are new vertices over the middles of a0b1 and b0a1, lifted
 * toward the partner slice.  The band tiles the composite, using each of its
 * edges once; the four fill triangles use a0a1 and b0b1 (the two input edges
 * the composite skips) and the four bridge edges once more.  So every input
 * edge is still used once from this side, every edge at m1 and m2 twice, and
 * each of m1, m2 has one fan: a manifold.  The design note lifts ONE vertex
 * m and fills two triangles; m then appears twice in the composite, and a
 * tiling that spans m to the same vertex of the other contour from both
 * places makes that edge non-manifold (four triangles).  Two vertices cannot
 * repeat a span.
 *
 * A bridge is legal when (exactly, geom/crossing.h): its segments a0b1 and
 * b0a1 cross or touch no contour of either slice and no earlier bridge (but
 * at their own ends), the corridor a0 b1 b0 a1 runs the composite's way (it
 * lies outside both polygons) and holds no other contour of the slice.
 * Where no such bridge exists, one that crosses contours of the partner
 * slice in projection is taken (it lies between the planes and meets none
 * of them in space; real structures need it: composite.relaxed); one that
 * would cross its own slice's contours never is.
 * Contours are joined closest pairs first (Kruskal over the pairs' best
 * bridge lengths; IMOD's join_all_contours joins closest-first too), each
 * bridge the shortest legal one between the two polygons by
 * |a0 b1|^2 + |b0 a1|^2 (DICOMautomaton's criterion, squared). */
#ifndef BRIDGE_H
#define BRIDGE_H

#include <stddef.h>

#include "surface/mesh.h"
#include "surface/slices.h"

typedef struct {
  int n;              /* points of the composite */
  vec2 *pt;           /* their positions in the plane (the tiler's view) */
  int *id;            /* mesh vertex: >= 0 an input vertex, -1-s Steiner vertex s */
  int nsteiner;
  vec3 *steiner;      /* lifted off the slice's plane */
  int ntri;
  int (*tri)[3];      /* the fill triangles, ids as in id[], facing outward */
  int nbridges;
  int relaxed;        /* bridges that cross a contour of the partner slice (in
                         projection), where no bridge avoided it */
  int relaxed_line[2];   /* the first such bridge's two contours (file lines) */
} composite;

/* Join the contours cs[0..count-1] (indices into sl->c, all on slice k and
 * of one depth) into one composite.  The partner slice is `other`; the
 * Steiner vertices sit at z(k) + lift (lift > 0 when the partner is above).
 * One contour: the composite is that contour.  Returns 0, or -1 with
 * "NAME:LINE: no bridge can join the contour to the contour at line K ..."
 * in err.  Thread-safe. */
int bridge_join(const slices *sl, const int *cs, int count, int other, double lift,
                const char *name, composite *out, char *err, size_t errlen);

void bridge_free(composite *c);

#endif
