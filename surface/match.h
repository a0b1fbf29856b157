/* match.h -- correspondence: which contours of two neighbouring slices belong
 * to one piece of surface (design note shared/design/contours.md, section 2,
 * step 5).
 *
 * A contour on slice k is linked to a contour on slice k+1 when
 *   - both have the same nesting depth (outer with outer, hole with hole),
 *   - their parents are in one junction (or both are outer boundaries), and
 *   - their regions overlap (surface/overlap.h: exact).
 * The parents' rule is IMOD's "outer levels first, then inner ones"
 * (imeshSkinObject): an island whose hole closes above it does not reach
 * across the hole to the outer boundary above; it ends inside the hole's
 * cap (surface/ends.h).  It also gives: a hole is linked only if its parent
 * is, and a contour whose parent has no partner has none either.
 *
 * Junctions are the connected groups of links (union-find): 1-1 (a band),
 * n-m (branching and merging: bridges, surface/bridge.h), and the contours
 * left alone, 1-0 and 0-1 (ends: caps). */
#ifndef MATCH_H
#define MATCH_H

#include "slices.h"

typedef struct {
  int depth;        /* of all its contours */
  int nlo, nhi;     /* contours on slice k and on slice k+1 */
  int *lo, *hi;     /* their indices into slices.c, increasing */
} junction;

typedef struct {
  int n;
  junction *j;      /* by their least contour index: the order is canonical */
} junctions;

/* The junctions between slice k and slice k+1, every contour of the two
 * slices in exactly one.  Thread-safe for different k. */
void match_slices(const slices *sl, int k, junctions *out);

void match_free(junctions *js);

#endif
