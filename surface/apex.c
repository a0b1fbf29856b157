/* apex.c -- kernel points: the centroid, else the kernel by clipping.
 *
 * The kernel of a polygon of n edges is clipped from its bounding box by
 * each edge's inner half-plane in turn (Sutherland-Hodgman against one line),
 * O(n k) for a kernel of k sides; rounding can only shrink or grow it by a
 * hair, and the candidate point is then checked exactly. */
#include "surface/apex.h"

#include <math.h>
#include <stdlib.h>

#include "geom/exact.h"
#include "util/xmem.h"

int apex_sees_all(const vec2 *p, int n, vec2 q) {
  int sign = geom_area2(p, n) > 0 ? 1 : -1;
  for (int i = 0; i < n; i++)
    if (exact_orient(p[i], p[(i + 1) % n], q) != sign) return 0;
  return 1;
}

/* A finite point that sees all of p (the exact orientations take finite
 * points only; a centroid of a sliver whose area cancelled may not be). */
static int sees_all(const vec2 *p, int n, vec2 c) { return isfinite(c.x) && isfinite(c.y) && apex_sees_all(p, n, c); }

int apex_point(const vec2 *p, int n, vec2 *at) {
  vec2 c = geom_centroid(p, n);
  if (sees_all(p, n, c)) {
    *at = c;
    return 1;
  }
  int sign = geom_area2(p, n) > 0 ? 1 : -1;
  double lx = p[0].x, hx = p[0].x, ly = p[0].y, hy = p[0].y;
  for (int i = 1; i < n; i++) {
    if (p[i].x < lx) lx = p[i].x;
    if (p[i].x > hx) hx = p[i].x;
    if (p[i].y < ly) ly = p[i].y;
    if (p[i].y > hy) hy = p[i].y;
  }
  int cap = 2 * n + 8, k = 4;
  vec2 *kr = xmallocarray((size_t)cap, sizeof *kr), *nx = xmallocarray((size_t)cap, sizeof *nx);
  kr[0] = (vec2){lx, ly}, kr[1] = (vec2){hx, ly}, kr[2] = (vec2){hx, hy}, kr[3] = (vec2){lx, hy};
  for (int e = 0; e < n && k > 0; e++) {
    vec2 a = p[e], b = p[(e + 1) % n];
    double ex = b.x - a.x, ey = b.y - a.y;
    int m = 0;
    for (int i = 0; i < k; i++) {
      vec2 u = kr[i], v = kr[(i + 1) % k];
      double su = sign * (ex * (u.y - a.y) - ey * (u.x - a.x));
      double sv = sign * (ex * (v.y - a.y) - ey * (v.x - a.x));
      if (su >= 0) nx[m++] = u;
      if ((su >= 0) != (sv >= 0) && su != sv) {
        double t = su / (su - sv);
        nx[m++] = (vec2){u.x + t * (v.x - u.x), u.y + t * (v.y - u.y)};
      }
      if (m + 2 >= cap) break;   /* cannot happen for a convex clip; guard anyway */
    }
    vec2 *t = kr;
    kr = nx, nx = t;
    k = m;
  }
  int ok = 0;
  if (k >= 3) {
    c = geom_centroid(kr, k);
    if (sees_all(p, n, c)) *at = c, ok = 1;
  }
  free(kr);
  free(nx);
  return ok;
}
