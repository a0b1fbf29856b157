/* stack.h -- one closed, outward surface from a whole stack of contours,
 * any number per slice, with the exact tiler doing every band.
 *
 * The pipeline (doc/surface.md, "Several contours per slice"; each step in
 * its own file):
 *   slices.c   canonical slices, nesting forests, holes by depth
 *   match.c    correspondence between neighbouring slices: junctions, by
 *              the joining rule (gap.c: how far apart contours lie)
 *   bridge.c   n-m junctions: composite contours joined by bridges
 *   tiling.h   every band: the exact minimum-cost tiling (Fuchs, Kedem,
 *              Uselton 1977), or the caller's tiler of pairs (stack_tiler:
 *              the paper's parallel algorithm on a machine)
 *   ends.c     the ends: caps, flat (flatcap.c) or apex (apex.c)
 *   manifold.c the components of the result: closed, manifold, genus
 * The bands are independent (the paper, section 6), and so are the slices
 * and the caps: each step runs on a pool of threads (pool.h), with results
 * kept by index, so the output is byte-identical on any number of threads.
 *
 * Mesh vertices: the contours' points in canonical order (slices.h), then
 * the bridges' vertices band by band, then the caps' apexes.  Triangles:
 * band by band (the tiles in path order, then the bridges' fill), then the
 * caps.  Every triangle faces outward.
 *
 * Scale.  The whole stack -- x, y and z -- is multiplied
 * once by the power of two 2^-e that brings its largest coordinate into
 * [1/2, 1) (slices_build_at), and every step above works there: no product
 * of coordinates (squared distances choosing bridges, areas, the apex's
 * centroid, volumes) can overflow, none that matters can underflow, and
 * distances that depend on the spacing (the bridges' lift, the apex's height,
 * the slab's thickness) scale with it.  Multiplying by a power of two is exact
 * (for a value that stays above 2^-1022: the lowest stacks are scaled up),
 * so a stack scaled by 2^k is worked on in bit-identical form: the same
 * triangles, junctions, bridges, caps and components; the results come back
 * in the file's units by one ldexp each (lengths 2^e, areas 2^2e, volumes
 * 2^3e), so they are exactly 2^k, 2^2k, 2^3k times the unit-scale ones, or
 * inf or 0 where those lie beyond a double.  Input vertices are the file's
 * own points.  Messages give the file's values. */
#ifndef STACK_H
#define STACK_H

#include <stddef.h>
#include <stdio.h>

#include "input/contour.h"
#include "surface/match.h"
#include "surface/mesh.h"
#include "algo/par_master.h"
#include "surface/manifold.h"

/* How a 1-1 band is tiled.  STACK_BAND_ALIGNED: on its contours' corners,
 * the upper moved and scaled onto the lower (surface/follow.h), so that the
 * band follows the structure (prisms, oblique cylinders and frustums exact,
 * whatever their sampling); STACK_BAND_PLAIN: the paper's minimum-cost band
 * of the two contours as they lie, every point counted.  n-m bands (with
 * bridges) are tiled as they lie either way. */
typedef enum { STACK_BAND_ALIGNED = 0, STACK_BAND_PLAIN } stack_band;

/* A tiler of bands given by the caller (the paper's parallel algorithm on
 * its machine): tile pairs[0 .. npairs-1], every band of the stack in one
 * call, each pair's in-fields set (P, np, zp, Q, nq, zq), its out-fields
 * (t, time, counts) to fill.  0, or -1 and a message. */
typedef struct {
  int (*pairs)(void *ud, par_pair *pairs, int npairs, char *err, size_t errlen);
  void *ud;
} stack_tiler;

typedef struct {
  cost_kind kind;
  int caps;            /* 1: close every end (watertight); 0: leave them open */
  int apex;            /* cap style: 0 flat, 1 apex */
  int threads;         /* >= 1 */
  const stack_tiler *tiler;   /* non-NULL: the bands are tiled by it (not on the
                                 threads); else by the exact tiler */
  FILE *notes;         /* notes (reoriented contours, flat single-slice parts), or NULL */
  const char *prefix;  /* of the notes: "tile" */
  void (*progress)(void *ud, int done, int total);   /* after each band tiled (any thread), or NULL */
  void *progress_ud;
  match_rule join;     /* which contours of neighbouring slices are joined (match.h);
                          0 is the default, MATCH_SINGLE */
  double join_dist;    /* MATCH_NEAREST: the largest gap joined, in the file's units;
                          INFINITY: any */
  double thickness;    /* a stack of one slice: > 0 makes it a slab this thick, closed
                          (half above, half below); 0 refuses it */
  stack_band band;     /* how a 1-1 band is tiled; 0 is the default, STACK_BAND_ALIGNED */
} stack_options;

/* The joins of a surface (notes on `notes`, counts in the report's joins row). */
typedef struct {
  const char *rule;    /* "overlap", "touch", "single", "nearest" or the distance */
  int apart;           /* joins made without overlap (single or nearest) */
  int unjoined;        /* contour ends left without a partner though the
                          neighbouring slice has candidates for them */
  int dropped;         /* joins not made: no bridges could join their junction */
} stack_joins;

typedef enum { STACK_BAND, STACK_CAP } stack_row_kind;

typedef struct {
  stack_row_kind kind;
  int slice0, slice1;  /* band: slices k, k+1; cap: its slice twice */
  double z0, z1;       /* band: their z; cap: the slice's z and the apex's (z when flat) */
  int depth;           /* 0 outer boundaries, 1 holes, ... */
  int nlo, nhi;        /* contours on slice0 and on slice1 (cap: on one side only) */
  int *lo, *hi;        /* their places on their slices (slices.h: canonical order) */
  int m, n;            /* band: points of the two contours (with bridge vertices;
                          the band has m + n tiles); cap: the region's points, 0 */
  int bridges;         /* band: bridges on both sides */
  double cost;         /* band: the true cost of the tiler's optimal path (bridge
                          vertices in the plane; tiling_path_cost) */
  double area;         /* the triangles' area (band: with the bridges' fill) */
  double volume;       /* band: the slab closed by it and the slices' regions;
                          cap: what it adds beyond the flat region (0 flat) */
  unsigned long long nodes;   /* band: the tiler's node evaluations */
  int spans;           /* band: spans the tiler's optimum used twice (a pinched
                          band, unpinch.h): then the band is the cheapest path
                          that uses none (cost is its cost) unless too large */
  int pair;            /* band: its run in stack_pairs (with a tiler), else -1 */
} stack_row;

typedef struct stack_surface stack_surface;

/* Tile the stack s, read from the file `name` (for messages).  Returns 0
 * and *out; -1 for input it refuses, with "NAME:LINE: what (value)" in err
 * (contours crossing on a slice, a bridge that cannot be made, one slice
 * without a thickness); -2 when the tiler failed, with its message in
 * err.  Nothing is left allocated on failure.
 *
 * Notes (on o->notes, each one line "PREFIX: NAME:LINE: ..."): joins made
 * without overlap (a run of single joins in one line), joins dropped for
 * want of a bridge, each contour left without a partner on a neighbouring
 * slice that has candidates for it (its nearest there and the gap, both
 * ends in one line), an empty mesh; then the bands' and caps' notes. */
int stack_tile(const contour_stack *s, const char *name, const stack_options *o,
               stack_surface **out, char *err, size_t errlen);

const mesh *stack_mesh(const stack_surface *ss);
/* Move the mesh out to *me (the caller frees it with mesh_free); the
 * surface keeps an empty one. */
void stack_take_mesh(stack_surface *ss, mesh *me);
int stack_nrows(const stack_surface *ss);
const stack_row *stack_rows(const stack_surface *ss);
/* With a tiler: the bands' runs (par_pair.time, counts), indexed by
 * stack_row.pair (else NULL). */
const par_pair *stack_pairs(const stack_surface *ss);
int stack_ncomponents(const stack_surface *ss);
/* The whole surface: the bands' costs summed, the mesh's area and volume,
 * each at the working scale, then in the file's units (see Scale above). */
void stack_totals(const stack_surface *ss, double *cost, double *area, double *volume);
const manifold_component *stack_components(const stack_surface *ss);
const stack_joins *stack_join_counts(const stack_surface *ss);

/* --join's value (OPT, for the message): overlap, single, touch, nearest or
 * a distance >= 0 (MATCH_NEAREST within it; *dist INFINITY for the words).
 * 0, or -1 with "OPT takes overlap, single, touch, nearest or a distance
 * from 0 to 1e300 (VALUE)" in err. */
int stack_parse_join(const char *opt, const char *val, match_rule *rule, double *dist, char *err, size_t errlen);

/* --thickness's value: a length > 0.  0, or -1 with "OPT takes a length
 * above 0, at most 1e300 (VALUE)" in err. */
int stack_parse_thickness(const char *opt, const char *val, double *t, char *err, size_t errlen);

/* The refusal of a stack of one slice without a thickness, in err (as
 * stack_tile gives it): 0 if s has two slices or more, or thickness > 0;
 * else -1.  For callers that refuse stacks before tiling any. */
int stack_check_slices(const contour_stack *s, const char *name, double thickness, char *err, size_t errlen);

void stack_free(stack_surface *ss);

#endif
