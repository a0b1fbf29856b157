/* geom.c -- plane geometry of contours. */
#include "geom/geom.h"

#include <math.h>
#include <stdlib.h>

#include "geom/exact.h"

double geom_area2_at(const vec2 *p, int n, int e) {
  if (n < 3) return 0;
  double s = 0, x0 = geom_ldexp(p[0].x, -e), y0 = geom_ldexp(p[0].y, -e);
  for (int i = 1; i + 1 < n; i++) {
    double ax = geom_ldexp(p[i].x, -e) - x0, ay = geom_ldexp(p[i].y, -e) - y0;
    double bx = geom_ldexp(p[i + 1].x, -e) - x0, by = geom_ldexp(p[i + 1].y, -e) - y0;
    s += ax * by - ay * bx;
  }
  return s;
}

double geom_area2(const vec2 *p, int n) {
  double m = 0;
  for (int i = 0; i < n; i++) m = fmax(m, fmax(fabs(p[i].x), fabs(p[i].y)));
  int e = geom_scale_exp(m);
  return ldexp(geom_area2_at(p, n, e), 2 * e);
}

int geom_collinear(const vec2 *p, int n) {
  /* The first point apart from p[0] fixes the line; all must be on it. */
  int b = 1;
  while (b < n && exact_lex(p[b], p[0]) == 0) b++;
  for (int i = b + 1; i < n; i++)
    if (exact_orient(p[0], p[b], p[i]) != 0) return 0;
  return 1;
}

int geom_corners(const vec2 *p, int n, int *keep) {
  int m = 0;
  for (int i = 0; i < n; i++)
    if (exact_orient(p[i == 0 ? n - 1 : i - 1], p[i], p[i + 1 == n ? 0 : i + 1]) != 0) keep[m++] = i;
  return m;
}

vec2 geom_centroid(const vec2 *p, int n) {
  double a = 0, cx = 0, cy = 0;
  for (int i = 1; i + 1 < n; i++) {
    double ux = p[i].x - p[0].x, uy = p[i].y - p[0].y, vx = p[i + 1].x - p[0].x, vy = p[i + 1].y - p[0].y;
    double w = ux * vy - uy * vx;
    a += w;
    cx += w * (ux + vx);
    cy += w * (uy + vy);
  }
  if (a == 0) return p[0];
  return (vec2){p[0].x + cx / (3 * a), p[0].y + cy / (3 * a)};
}

int geom_orientation(const vec2 *p, int n) {
  if (n < 3) return 0;
  int v = 0;
  for (int i = 1; i < n; i++)
    if (exact_lex(p[i], p[v]) < 0) v = i;
  int o = exact_orient(p[v == 0 ? n - 1 : v - 1], p[v], p[v + 1 == n ? 0 : v + 1]);
  if (o) return o;
  /* Not simple: the area's sign (computed at a safe scale). */
  double a = geom_area2(p, n);
  return (a > 0) - (a < 0);
}

void geom_reverse(vec2 *p, int n) {
  for (int i = 1, j = n - 1; i < j; i++, j--) {
    vec2 t = p[i];
    p[i] = p[j];
    p[j] = t;
  }
}

static int span_by_lo(const void *a, const void *b) {
  const geom_span *p = a, *q = b;
  if (p->lo != q->lo) return p->lo < q->lo ? -1 : 1;
  return p->i - q->i;
}

void geom_span_sort(geom_span *s, int n) { qsort(s, (size_t)n, sizeof *s, span_by_lo); }

static int pick_order(const void *p, const void *q) {
  const geom_pick *x = p, *y = q;
  if (x->w != y->w) return x->w < y->w ? -1 : 1;
  if (x->a != y->a) return x->a - y->a;
  return x->b - y->b;
}

void geom_pick_sort(geom_pick *p, size_t n) { qsort(p, n, sizeof *p, pick_order); }
