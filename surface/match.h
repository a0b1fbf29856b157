/* match.h -- correspondence: which contours of two neighbouring slices belong
 * to one piece of surface (doc/surface.md, "Joining neighbouring slices").
 *
 * A contour on slice k is linked to a contour on slice k+1 when
 *   - both have the same nesting depth (outer with outer, hole with hole),
 *   - their parents are in one junction (or both are outer boundaries), and
 *   - the rule's test holds (MATCH_*, below; overlap tests are exact,
 *     surface/overlap.h).
 * The parents' rule is IMOD's "outer levels first, then inner ones"
 * (imeshSkinObject): an island whose hole closes above it does not reach
 * across the hole to the outer boundary above; it ends inside the hole's
 * cap (surface/ends.h).  It also gives: a hole is linked only if its parent
 * is, and a contour whose parent has no partner has none either.
 *
 * The rules, each joining all that the one before it joins:
 *   MATCH_OVERLAP  the open regions overlap (share an interior point);
 *   MATCH_TOUCH    the closed regions meet: touching along an edge or at a
 *                  corner counts (pixel-traced staircases);
 *   MATCH_SINGLE   (the default) also, at depth 0, when each of the two
 *                  slices has exactly one outer contour, those two, whether
 *                  or not they meet (the paper's case, libsr's shortcut);
 *   MATCH_NEAREST  also every contour still without a partner on the other
 *                  slice (after the links above at its depth) to its nearest
 *                  candidate there: same depth, parents in one junction,
 *                  least gap (surface/gap.h, exact), ties to the canonically
 *                  first; with dist finite, only if the gap is at most dist.
 *                  The candidate may have partners already, so a branch that
 *                  starts beside its trunk forms a Y.
 * Each level d's links are made from the state after level d-1's, in that
 * order (overlaps; touching; single; nearest from the strays after those),
 * so they depend only on the canonical slices: never on the file's order,
 * start points or winding.  A link the overlap rule would not make (touch,
 * single, nearest) that puts two or more contours on a side of a junction
 * is made only if bridges can join them (surface/bridge.h); otherwise it is
 * dropped (match_link.dropped), never a refusal of the stack.  With
 * careful, overlap links too (a branching that no bridges can join: the
 * contours it leaves out end, capped, and are named).
 *
 * Junctions are the connected groups of links (union-find): 1-1 (a band),
 * n-m (branching and merging: bridges, surface/bridge.h), and the contours
 * left alone, 1-0 and 0-1 (ends: caps). */
#ifndef MATCH_H
#define MATCH_H

#include "geom/exactdist.h"
#include "surface/slices.h"

typedef enum { MATCH_SINGLE = 0, MATCH_OVERLAP, MATCH_TOUCH, MATCH_NEAREST } match_rule;

typedef struct {
  match_rule rule;
  double dist;      /* MATCH_NEAREST: the largest gap joined, at the slices' scale
                       (slices.scale); INFINITY: any */
  int gaps;         /* 1: find the gaps of the links and each end's nearest
                       candidate (for notes); 0: only count the ends */
  int careful;      /* 1: an overlap link too is made only where bridges can join
                       the junction it makes (else dropped, MATCH_LINK_OVERLAP):
                       for the slices where the links as made cannot be bridged */
} match_opts;

typedef struct {
  int depth;        /* of all its contours */
  int nlo, nhi;     /* contours on slice k and on slice k+1 */
  int *lo, *hi;     /* their indices into slices.c, increasing */
  int apart;        /* 1-1, joined without overlap (MATCH_LINK_SINGLE or _NEAREST) */
} junction;

enum { MATCH_LINK_TOUCH = 1, MATCH_LINK_SINGLE, MATCH_LINK_NEAREST, MATCH_LINK_OVERLAP };

/* A link beyond an overlap of the open regions, made or dropped; with
 * careful, an overlap link dropped. */
typedef struct {
  int a, b;         /* the contours: a on slice k, b on slice k+1 */
  int how;          /* MATCH_LINK_TOUCH, _SINGLE or _NEAREST */
  int from;         /* _NEAREST: the contour that sought its nearest (a or b) */
  int dropped;      /* 1: no bridges could join its junction's contours: not made */
  int has_gap;
  exactdist gap;    /* with gaps (always for _NEAREST) */
} match_link;

/* A contour with no partner on the other slice though that slice has
 * candidates for it (same depth, parents in one junction). */
typedef struct {
  int c;            /* on slice k (no partner above) or k+1 (none below) */
  int nearest;      /* with gaps: the nearest candidate (ties: the first), else -1 */
  exactdist gap;    /* with gaps */
} match_end;

typedef struct {
  int n;
  junction *j;      /* by their least contour index: the order is canonical */
  int nlinks;
  match_link *links;   /* by level, then as made */
  int nends;
  match_end *ends;     /* by contour index */
} junctions;

/* The junctions between slice k and slice k+1, every contour of the two
 * slices in exactly one.  Thread-safe for different k. */
void match_slices(const slices *sl, int k, const match_opts *o, junctions *out);

/* The nearest candidate for contour c on the neighbouring slice `other`
 * among those of its depth that `ok` accepts (NULL: all): its index and
 * gap, or -1.  Ties go to the lower index. */
int match_nearest(const slices *sl, int c, int other, int (*ok)(void *ud, int cand), void *ud,
                  exactdist *gap);

void match_free(junctions *js);

#endif
