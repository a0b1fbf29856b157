/* hull.c -- convex hull (monotone chain) and extreme points by edge angles. */
#include "geom/hull.h"

#include <math.h>
#include <stdlib.h>

#include "geom/exact.h"
#include "util/xmem.h"

struct hull {
  int n;
  vec2 *v;       /* counter-clockwise from the lexicographically lowest vertex */
  double *ang;   /* ang[i]: the angle of edge v[i] -> v[i+1], increasing (unwrapped) */
};

static const double TWO_PI = 6.283185307179586476925;

static int by_lex(const void *a, const void *b) { return exact_lex(*(const vec2 *)a, *(const vec2 *)b); }

hull *hull_new(const vec2 *p, int n) {
  XASSERT(n >= 1);
  vec2 *s = xmallocarray((size_t)n, sizeof *s);
  for (int i = 0; i < n; i++) s[i] = p[i];
  qsort(s, (size_t)n, sizeof *s, by_lex);
  int k = 0;
  for (int i = 0; i < n; i++)
    if (k == 0 || exact_lex(s[i], s[k - 1]) != 0) s[k++] = s[i];
  /* One block: the hull, its vertices (at most 2k + 1 while the chains are
   * built) and its edges' angles. */
  size_t cap = (size_t)2 * k + 1;
  hull *h = xmalloc(sizeof *h + cap * sizeof *h->v + (cap + 1) * sizeof *h->ang);
  h->v = (vec2 *)(h + 1);
  h->ang = (double *)(h->v + cap);
  int m = 0;
  if (k < 3) {
    for (int i = 0; i < k; i++) h->v[m++] = s[i];
  } else {
    for (int i = 0; i < k; i++) {   /* lower chain, left to right */
      while (m >= 2 && exact_orient(h->v[m - 2], h->v[m - 1], s[i]) <= 0) m--;
      h->v[m++] = s[i];
    }
    for (int i = k - 2, lo = m + 1; i >= 0; i--) {   /* upper chain, right to left */
      while (m >= lo && exact_orient(h->v[m - 2], h->v[m - 1], s[i]) <= 0) m--;
      h->v[m++] = s[i];
    }
    m--;   /* the last is the first again */
  }
  free(s);
  h->n = m;
  for (int i = 0; i < m; i++) {
    vec2 a = h->v[i], b = h->v[(i + 1) % m];
    /* Differences of huge coordinates may overflow; halve them first. */
    double gx = 0.5 * b.x - 0.5 * a.x, gy = 0.5 * b.y - 0.5 * a.y;
    h->ang[i] = atan2(gy, gx);
    if (i > 0)
      while (h->ang[i] < h->ang[i - 1]) h->ang[i] += TWO_PI;
  }
  return h;
}

void hull_free(hull *h) { free(h); }

int hull_size(const hull *h) { return h->n; }
vec2 hull_vertex(const hull *h, int i) { return h->v[i]; }

/* d . (v - v0): relative to the first vertex, so its rounding is relative to
 * the hull's size, not to how far it lies from the origin. */
static double dot(const hull *h, int i, double dx, double dy) {
  return dx * (h->v[i].x - h->v[0].x) + dy * (h->v[i].y - h->v[0].y);
}

vec2 hull_extreme(const hull *h, double dx, double dy) {
  int n = h->n, best = 0;
  if (n <= 8) {   /* few: look at all */
    for (int i = 1; i < n; i++)
      if (dot(h, i, dx, dy) > dot(h, best, dx, dy)) best = i;
    return h->v[best];
  }
  /* The maximum is where the edges turn from rising (angle within a quarter
   * turn of d's) to falling: at the first edge whose angle is at least d's
   * plus a quarter turn, taken into [ang[0], ang[0] + 2 pi). */
  double t = atan2(dy, dx) + 0.25 * TWO_PI;
  while (t < h->ang[0]) t += TWO_PI;
  while (t >= h->ang[0] + TWO_PI) t -= TWO_PI;
  int lo = 0, hi = n;   /* first i with ang[i] >= t, or n */
  while (lo < hi) {
    int mid = lo + (hi - lo) / 2;
    if (h->ang[mid] >= t) hi = mid;
    else lo = mid + 1;
  }
  best = lo % n;
  for (int d = -1; d <= 1; d += 2) {
    int j = (lo + d + n) % n;
    if (dot(h, j, dx, dy) > dot(h, best, dx, dy)) best = j;
  }
  return h->v[best];
}
