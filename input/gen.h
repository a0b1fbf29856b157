/* gen.h -- generated contours: random star-shaped contours (the paper's
 * "generated in a somewhat random fashion", section 6), regular polygons,
 * integer grids (many ties), and the stack of a glass (Fig. 17). */
#ifndef GEN_H
#define GEN_H

#include "input/contour.h"
#include "geom/geom.h"
#include "util/rng.h"

/* n points, counter-clockwise, star-shaped about (cx, cy): sorted random
 * angles, radius r times a random factor in [1 - jitter, 1 + jitter]. */
void gen_star(rng *g, vec2 *p, int n, double cx, double cy, double r, double jitter);

/* A regular n-gon of radius r about (cx, cy), first vertex at angle phase. */
void gen_regular(vec2 *p, int n, double cx, double cy, double r, double phase);

/* Star-shaped with integer coordinates in [-size, size]; consecutive
 * duplicates removed, so it may have fewer than n points: returns the count. */
int gen_grid(rng *g, vec2 *p, int n, int size);

/* The contours of a wine glass: `slices` contours of `points` points each,
 * z from 0 up.  The caller frees with contour_stack_free. */
void gen_glass(contour_stack *s, int slices, int points);

#endif
