/* manifold.h -- the connected components of a mesh and what they are: closed,
 * 2-manifold, Euler characteristic, genus, area and volume.
 *
 * Closed: every directed edge used as often as its reverse (no border, the
 * triangles consistently oriented).  Manifold: closed, every directed edge
 * used once (so every edge has exactly two triangles), and the triangles
 * around every vertex form one fan (no pinched vertex).  Then
 * V - E + F = 2 - 2 genus.  Closed but not manifold is "pinched". */
#ifndef MANIFOLD_H
#define MANIFOLD_H

#include "surface/mesh.h"

typedef struct {
  int nv, ne, nt;     /* vertices (used by a triangle), edges, triangles */
  int closed;         /* see above: no border */
  int manifold;       /* closed and no pinched vertex */
  int euler;          /* V - E + F */
  int genus;          /* (2 - euler) / 2 when manifold, else -1 */
  double area, volume;
  double zmin, zmax;
  int first;          /* its least vertex */
} manifold_component;

/* The components, ordered by their least vertex.  *out is allocated (free
 * it); returns their number. */
int manifold_components(const mesh *me, manifold_component **out);

#endif
