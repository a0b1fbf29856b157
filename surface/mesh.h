/* mesh.h -- the triangle mesh of a tiled contour stack.
 *
 * Vertices are the contours' points, each once, contour after contour, so
 * neighbouring bands share them.  Every triangle is oriented outward
 * (counter-clockwise seen from outside), and with caps the mesh is closed. */
#ifndef MESH_H
#define MESH_H

#include "input/contour.h"
#include "algo/tiling.h"

typedef struct { double x, y, z; } vec3;

typedef struct {
  int nv, nt;          /* vertices, triangles */
  vec3 *v;
  int (*t)[3];         /* vertex indices, outward */
  int *base;           /* base[i]: index of contour i's first vertex */
  int cap;             /* allocated triangles */
} mesh;

/* The vertices of the stack, no triangles yet. */
void mesh_init(mesh *me, const contour_stack *s);
void mesh_free(mesh *me);
/* Append the triangle of vertices a, b, c (indices into me->v), in that
 * order (its orientation). */
void mesh_add_tri(mesh *me, int a, int b, int c);

/* Add the band between contours i and i+1 from their tiling t.  Returns, in
 * *area, the sum of the band's triangle areas and, in *volume, the volume of
 * the slab closed by the band and the two contours' polygons. */
void mesh_add_band(mesh *me, const contour_stack *s, int i, const tiling *t, double *area,
                   double *volume);

/* Close the first and the last contour (ear clipping, facing outward).
 * Returns the area of the two caps. */
double mesh_add_caps(mesh *me, const contour_stack *s);

double mesh_area(const mesh *me);     /* sum of triangle areas */
double mesh_volume(const mesh *me);   /* signed volume (divergence theorem) */
double mesh_tri_area(const mesh *me, int t);

#endif
