/* cap.h -- closing a contour with a triangulated polygon (ear clipping). */
#ifndef CAP_H
#define CAP_H

#include "geom/geom.h"

/* Triangulate the counter-clockwise polygon p[0..n-1] (n >= 3) by ear
 * clipping: writes n-2 triangles of indices into p, each counter-clockwise,
 * and returns n-2.  Every polygon edge is used by exactly one triangle.  A
 * polygon that is not simple still gets n-2 triangles (then some may overlap);
 * it never fails.  O(n^2) for the usual contour. */
int cap_triangulate(const vec2 *p, int n, int (*tri)[3]);

#endif
