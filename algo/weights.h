/* weights.h -- tile weights between two contours, as exact fixed-point numbers.
 *
 * The graph (paper, section 3): node (i, j) is the span R_i C_j between the
 * rows contour R (m points) and the columns contour C (n points).  The edge
 * (i,j)->(i+1,j) is the tile R_i R_{i+1} C_j (weight V(i,j)); the edge
 * (i,j)->(i,j+1) is the tile R_i C_j C_{j+1} (weight H(i,j)).  Indices are
 * taken modulo m and n, so the periodic copies of the 2m x n planar graph
 * (section 3.1) carry identical weights.
 *
 * Weights: `area` (Fuchs, Kedem, Uselton: the triangle's area) or `span` (the
 * length of the span the tile adds, R_{i+1}C_j or R_iC_{j+1}).
 *
 * Exactness.  Every weight is rounded once to an integer multiple of a
 * quantum 2^-k (k chosen per pair so that any path's sum stays below 2^52)
 * and kept in a double.  Sums of such numbers are exact, so path costs do not
 * depend on the order of addition: the divide and conquer, the naive
 * reference and every parallel run see bit-identical costs, and the
 * non-crossing argument of section 3.2 holds exactly, ties included.  The
 * quantum comes from the largest weight of the pair's graph, computed exactly
 * (weights.c), so it is about 2^-52 / (m + n + 1) of the largest tile, e.g.
 * 2^-39 for two 5000-point contours and 2^-49 for two 4-point ones: far below
 * the weights' own rounding.
 *
 * Scale.  Before any arithmetic the pair (points and height) is scaled by a
 * power of two into [-1, 1): coordinates from subnormals to 1e308 give the
 * same weights in quanta as the same shapes at unit scale, and the quantum is
 * kept as its exponent too (weights_qexp), since a cost may lie beyond
 * double's range (an area of 1e300-wide contours). */
#ifndef WEIGHTS_H
#define WEIGHTS_H

#include <math.h>
#include <stdint.h>

#include "geom/geom.h"

typedef enum { COST_AREA, COST_SPAN } cost_kind;

typedef struct weights weights;

/* Weights between R (m >= 1 points, plane zr) and C (n points, plane zc).
 * table: 1 precomputes per-diagonal tables (2 m (n+1) doubles), 0 computes
 * weights on the fly, -1 decides by size.  The caller keeps R and C. */
weights *weights_new(const vec2 *R, int m, double zr, const vec2 *C, int n, double zc,
                     cost_kind kind, int table);

/* The same with each tile's shadow added to its area: the weight of the
 * tile with edge A -> B on one contour and apex P on the other is its area
 * plus `shadow` times the signed area of A B P projected on the slices'
 * plane (positive when P lies left of A -> B), |shadow| <= 15/16, so that no
 * weight is negative.  shadow = 0 gives weights_new's weights, bit for bit.
 * Over an acceptable path the shadows sum, up to a constant of the pair, to
 * a multiple of the volume the band closes with its two slices' regions, so
 * `shadow` trades area for volume: a larger one gives a band of no less
 * signed volume (surface/follow.h).  COST_AREA only (span ignores it). */
weights *weights_new_shadow(const vec2 *R, int m, double zr, const vec2 *C, int n, double zc,
                            cost_kind kind, double shadow, int table);
void weights_free(weights *w);

double weights_v(const weights *w, int i, int j);   /* tile R_i R_{i+1} C_j, in quanta */
double weights_h(const weights *w, int i, int j);   /* tile R_i C_j C_{j+1}, in quanta */
double weights_quantum(const weights *w);           /* one quantum in the caller's units: 2^qexp */
int    weights_qexp(const weights *w);              /* its exponent (the quantum may lie beyond
                                                       double's range: ldexp(quanta, qexp)) */
int    weights_has_table(const weights *w);
const char *cost_name(cost_kind k);
int    cost_parse(const char *s, cost_kind *k);     /* 0, or -1 for an unknown name */

/* Tables are used when 2 m (n+1) doubles fit in this many bytes. */
#define WEIGHTS_TABLE_BYTES (48u << 20)

/* --- private part: visible for the diagonal kernel (kernel.c) ------------- */

struct weights {
  int m, n;
  cost_kind kind;
  double h2;        /* (zc - zr)^2, scaled as the points (weights.c) */
  double sc;        /* scale: S/2 for area, S for span, S = 2^k */
  double quantum;   /* 2^qexp: one quantum in the caller's units (may be 0 or inf) */
  int qexp;
  double shadow;    /* weights_new_shadow's; 0 for weights_new */
  /* The points, scaled by a power of two into [-1, 1) (weights.c), so the
   * weights' arithmetic cannot overflow.
   * Rows r = -1 .. 2m+1 stored reversed at index 2m+1-r, so that along a
   * diagonal (r falling as the column c rises) both arrays run forwards.
   * rx,ry: R_{r mod m}; rex,rey: R_{r+1}-R_r; ree: h2*|R_{r+1}-R_r|^2. */
  double *rx, *ry, *rex, *rey, *ree;
  /* Columns c = -1 .. n+1 at index c+1: C_{c mod n}, C_{c+1}-C_c, h2*|.|^2. */
  double *cx, *cy, *cfx, *cfy, *cff;
  /* Per-diagonal tables, or NULL.  Node (k-c, c) of diagonal k takes
   * tv[((k-1) mod m)(n+1) + c] on its vertical in-edge and
   * th[(k mod m)(n+1) + c] on its horizontal one (span: ts for both). */
  double *tv, *th;
};

/* One rounding for every weight, whoever computes it: q = round(x * sc),
 * exact for 0 <= x * sc < 2^52 (the scale guarantees it). */
static inline double weights_round(double q) { return (q + 0x1p52) - 0x1p52; }

/* The tile with edge A -> A+e on one contour and apex P on the other:
 * area = |e x (P - A)| / 2 in 3D = sqrt(h^2 |e|^2 + (e x d)^2) / 2, where
 * ee = h^2 |e|^2 and d = P - A in the plane; plus `shadow` times the
 * tile's shadow cz / 2 (weights_new_shadow); with shadow = 0 the area
 * alone, as before there were shadows. */
static inline double weights_tri(double ee, double ex, double ey, double ax, double ay,
                                 double px, double py, double sc, double shadow) {
  double dx = px - ax, dy = py - ay;
  double cz = ex * dy - ey * dx, r = sqrt(ee + cz * cz);
  if (shadow != 0) r += shadow * cz;   /* (a loop's invariant: unswitched) */
  return weights_round(r * sc);
}

/* The span from A to P: sqrt(|P - A|^2 + h^2). */
static inline double weights_len(double ax, double ay, double px, double py, double h2,
                                 double sc) {
  double dx = px - ax, dy = py - ay;
  return weights_round(sqrt((dx * dx + dy * dy) + h2) * sc);
}

/* The weight of the in-edge of node (k-c, c) on diagonal k: from (k-c-1, c)
 * (vertical, V(k-c-1, c)) or from (k-c, c-1) (horizontal, H(k-c, c-1)).
 * From the tables when there are some. */
double weights_in(const weights *w, int k, int c, int vertical);

#endif
