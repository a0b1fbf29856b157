/* cap.c -- ear clipping (Meisters' two-ears theorem: a simple polygon always
 * has an ear, so clipping one at a time ends after n-2 ears). */
#include "surface/cap.h"

#include <math.h>
#include <stdlib.h>

#include "geom/exact.h"
#include "util/xmem.h"

static double cross(vec2 a, vec2 b, vec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

static int same(vec2 a, vec2 b) { return a.x == b.x && a.y == b.y; }

/* Is vertex b (between a and c) an ear: convex, not a sliver, and no other
 * vertex of the remaining polygon inside, on or within a hair of triangle
 * abc?  A sliver (a vertex on a straight run of the contour, its triangle's
 * area below 1e-9 of its squared sides) is left for later, when a
 * neighbour's ear has changed its neighbours: clipping it would make a
 * degenerate triangle.  Every vertex is tested, not only the reflex ones:
 * on a straight run (mask-derived contours have them) rounding calls some
 * collinear vertices convex, and a diagonal along the run through them
 * would leave a polygon of no area to clip. */
static int is_ear(const vec2 *p, const int *next, const int *prev, int ib) {
  int ia = prev[ib], ic = next[ib];
  vec2 a = p[ia], b = p[ib], c = p[ic];
  double cr = cross(a, b, c);
  double s2 = (b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) + (c.x - b.x) * (c.x - b.x) +
              (c.y - b.y) * (c.y - b.y) + (a.x - c.x) * (a.x - c.x) + (a.y - c.y) * (a.y - c.y);
  if (cr <= 1e-9 * s2) return 0;
  double tol = -1e-9 * s2;
  for (int j = next[ic]; j != ia; j = next[j]) {
    vec2 q = p[j];
    if (same(q, a) || same(q, b) || same(q, c)) continue;
    if (cross(a, b, q) >= tol && cross(b, c, q) >= tol && cross(c, a, q) >= tol) return 0;
  }
  return 1;
}

/* The same test with exact orientations and no tolerance: b strictly convex,
 * no other vertex (by coordinates) inside or on triangle abc.  A sliver
 * passes.  Used when a full turn found no ear by is_ear: around a hole a
 * millionth of its region's size every ear that touches the hole is a
 * sliver by the relative test, and clipping without any test would overlap
 * triangles. */
static int is_ear_exact(const vec2 *p, const int *next, const int *prev, int ib) {
  int ia = prev[ib], ic = next[ib];
  vec2 a = p[ia], b = p[ib], c = p[ic];
  if (exact_orient(a, b, c) <= 0) return 0;
  for (int j = next[ic]; j != ia; j = next[j]) {
    vec2 q = p[j];
    if (same(q, a) || same(q, b) || same(q, c)) continue;
    if (exact_orient(a, b, q) >= 0 && exact_orient(b, c, q) >= 0 && exact_orient(c, a, q) >= 0)
      return 0;
  }
  return 1;
}

/* The polygon is clipped as scaled by the power of two that brings its
 * largest coordinate into [1/2, 1): exact, and every test here is
 * homogeneous, so the ears are those of the unscaled polygon wherever its
 * products neither overflow nor underflow, and the same at 1e300 or among
 * subnormals. */
int cap_triangulate(const vec2 *p_in, int n, int (*tri)[3]) {
  double mx = 0;
  for (int i = 0; i < n; i++) mx = fmax(mx, fmax(fabs(p_in[i].x), fabs(p_in[i].y)));
  int e = geom_scale_exp(mx);
  vec2 *p = xmallocarray((size_t)n, sizeof *p);
  for (int i = 0; i < n; i++) p[i] = (vec2){ldexp(p_in[i].x, -e), ldexp(p_in[i].y, -e)};
  int *next = xmallocarray((size_t)n, sizeof *next), *prev = xmallocarray((size_t)n, sizeof *prev);
  for (int i = 0; i < n; i++) next[i] = (i + 1) % n, prev[i] = (i + n - 1) % n;
  int left = n, nt = 0, i = 0, miss = 0;
  while (left > 3) {
    /* After a full turn without an ear, the exact test (slivers allowed);
     * after another (a polygon that is not simple), clip the vertex anyway:
     * convex ones first, then any. */
    int ear = is_ear(p, next, prev, i);
    if (!ear && miss >= left && miss < 2 * left) ear = is_ear_exact(p, next, prev, i);
    if (!ear && miss >= 2 * left && miss < 3 * left) ear = cross(p[prev[i]], p[i], p[next[i]]) > 0;
    if (!ear && miss >= 3 * left) ear = 1;
    if (ear) {
      tri[nt][0] = prev[i], tri[nt][1] = i, tri[nt][2] = next[i];
      nt++;
      next[prev[i]] = next[i];
      prev[next[i]] = prev[i];
      i = prev[i];   /* the neighbours may have become ears */
      left--;
      miss = 0;
    } else {
      i = next[i];
      miss++;
    }
  }
  tri[nt][0] = prev[i], tri[nt][1] = i, tri[nt][2] = next[i];
  nt++;
  free(next);
  free(prev);
  free(p);
  return nt;
}
