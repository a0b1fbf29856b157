/* geom.c -- plane geometry of contours. */
#include "geom.h"

#include <math.h>

double geom_area2(const vec2 *p, int n) {
  double s = 0;
  for (int i = 1; i + 1 < n; i++) {
    double ax = p[i].x - p[0].x, ay = p[i].y - p[0].y;
    double bx = p[i + 1].x - p[0].x, by = p[i + 1].y - p[0].y;
    s += ax * by - ay * bx;
  }
  return s;
}

int geom_collinear(const vec2 *p, int n) {
  /* The point farthest from p[0] fixes the line; all others must be on it. */
  int far = 0;
  double best = 0;
  for (int i = 1; i < n; i++) {
    double dx = p[i].x - p[0].x, dy = p[i].y - p[0].y, d = dx * dx + dy * dy;
    if (d > best) best = d, far = i;
  }
  if (best == 0) return 1;
  double ux = p[far].x - p[0].x, uy = p[far].y - p[0].y;
  for (int i = 1; i < n; i++) {
    double cr = ux * (p[i].y - p[0].y) - uy * (p[i].x - p[0].x);
    if (fabs(cr) > 1e-12 * best) return 0;
  }
  return 1;
}

void geom_reverse(vec2 *p, int n) {
  for (int i = 1, j = n - 1; i < j; i++, j--) {
    vec2 t = p[i];
    p[i] = p[j];
    p[j] = t;
  }
}
