/* stackgen.h -- stacks of several contours per slice for the tests: polygons
 * (circles and ellipses), a stack of them as ./tile reads it, and random
 * stacks of discs (branching, merging, ends, holes, islands). */
#ifndef STACKGEN_H
#define STACKGEN_H

#include "input/contour.h"
#include "geom/geom.h"
#include "surface/stack.h"
#include "util/rng.h"

typedef struct {
  int n;
  double z;
  vec2 *p;
} sg_poly;

/* n points on the ellipse about (cx, cy) with radii rx, ry, from the angle
 * phase, counter-clockwise. */
void sg_circle(vec2 *p, int n, double cx, double cy, double rx, double ry, double phase);

/* The stack of polys as a parsed contour_stack (through the reader, as text
 * with %.17g: exact), the contours in the order `order` (NULL: as given),
 * each from `start[i] % n` and reversed by rev[i] (NULL: from 0, as given).
 * 0, or -1 (a failed CHECK says why). */
int sg_make_stack(const sg_poly *ps, int np, const int *order, const int *start, const int *rev,
                  contour_stack *s);

enum { SG_MAXP = 48, SG_N = 40 };

/* A random stack: 2 to 5 slices, on each up to 6 discs placed at random and
 * apart (so that neighbouring slices overlap at random: branching, merging,
 * ends), some with a hole and some holes with an island; 8 to SG_N points
 * each.  The polygons' points go to buf; returns the number of polygons. */
int sg_random(rng *g, vec2 (*buf)[SG_N], sg_poly *ps);

/* stack_tile of s (named "t.contours") with o; where notes is not NULL, the
 * notes go there (nlen bytes at most) rather than to o.notes.  The surface
 * (stack_free it), stack_tile's answer in *res, its message in err. */
stack_surface *sg_tile(const contour_stack *s, stack_options o, char *notes, size_t nlen, char *err, size_t errlen,
                       int *res);

#endif
