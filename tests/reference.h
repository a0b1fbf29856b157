/* reference.h -- independent references several tests share: brute-force
 * answers to compare the code's with, written without its algorithms. */
#ifndef REFERENCE_H
#define REFERENCE_H

#include "geom/geom.h"
#include "surface/inside.h"
#include "surface/mesh.h"
#include "tests/meshcheck.h"
#include "tests/stackgen.h"

/* The area of the union of n axis-aligned rectangles r[i] = {x0, y0, x1,
 * y1} (n <= 32), by brute force over the grid of their coordinates: each
 * cell whose centre some rectangle holds counts whole. */
double ref_rects_area(const double (*r)[4], int n);

/* Convex polygons: apart (closed: no common point; open: no common interior
 * point) exactly when an edge's line has the other strictly (closed) or
 * weakly (open) on its outer side (the separating axis theorem); exact for
 * integer points. */
int ref_convex_apart(const vec2 *p, int np, const vec2 *q, int nq, int closed);

/* f (an overlap test) on p and q, checked to give the same answer on q and
 * p (a failed check names what). */
int ref_symmetric(int (*f)(const inside_index *, const inside_index *), const char *what, const vec2 *p, int np,
                  const vec2 *q, int nq);

/* The mesh checker's copy of a mesh under test (mc_free it). */
void ref_mc_mesh(mc_mesh *m, const mesh *me);

/* A mesh under test judged by the checker against the polygons it was tiled
 * from: a closed outward 2-manifold of comps components (-1: any), of
 * Euler characteristics chi[0..comps) where chi is not NULL, through every
 * input point and segment with no other vertex on the input planes and no
 * triangle across one; each a check naming what.  The checker's volume. */
double ref_judge_mesh(const char *what, const mesh *me, const sg_poly *ps, int np, int comps, const int *chi);

#endif
