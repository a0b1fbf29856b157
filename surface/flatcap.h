/* flatcap.h -- a flat cap: a region of one slice (an outer contour less its
 * holes) triangulated in its plane.
 *
 * Each hole is joined to the boundary by one cut, the shortest segment from
 * a hole vertex to a boundary vertex that meets no contour of the region
 * (exact, geom/crossing.h); the cut is walked both ways, so the region
 * becomes one weakly simple polygon, and ear clipping (surface/cap.h)
 * triangulates it.  VTK's vtkContourTriangulator cuts each hole twice
 * (vtkCCSCutHoleyPolys); one cut is enough for ear clipping (Eberly,
 * "Triangulation by Ear Clipping", 2002, section 4), and an exact test
 * chooses it instead of Eberly's visibility by angles. */
#ifndef FLATCAP_H
#define FLATCAP_H

#include "surface/slices.h"

/* Triangulate the region of contour `outer` less the contours holes[0..
 * nholes-1] (its children on the slice).  Writes triangles of mesh vertex
 * ids to *tri (allocated; free it), oriented like the outer contour (the
 * material on the left of every edge: facing +z at even depth), and returns
 * their number: the region's points + 2 (holes - 1).  Every contour edge is
 * used by exactly one triangle, in its own direction. */
int flatcap_region(const slices *sl, int outer, const int *holes, int nholes, int (**tri)[3]);

#endif
