/* gen.c -- generated contours for tests, benchmarks and the glass figure. */
#include "input/gen.h"

#include <math.h>
#include <stdlib.h>

#include "util/xmem.h"

static const double PI = 3.14159265358979323846;

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

void gen_star(rng *g, vec2 *p, int n, double cx, double cy, double r, double jitter) {
  double *ang = xmallocarray((size_t)n, sizeof *ang);
  /* Evenly spaced angles, each moved by up to a third of the spacing: sorted,
   * distinct, and never a gap wide enough to make the polygon degenerate. */
  for (int i = 0; i < n; i++) ang[i] = 2 * PI * (i + (rng_uniform(g) - 0.5) * 0.66) / n;
  qsort(ang, (size_t)n, sizeof *ang, cmp_double);
  for (int i = 0; i < n; i++) {
    double rr = r * (1 + jitter * (2 * rng_uniform(g) - 1));
    p[i].x = cx + rr * cos(ang[i]);
    p[i].y = cy + rr * sin(ang[i]);
  }
  free(ang);
}

void gen_regular(vec2 *p, int n, double cx, double cy, double r, double phase) {
  for (int i = 0; i < n; i++) {
    p[i].x = cx + r * cos(phase + 2 * PI * i / n);
    p[i].y = cy + r * sin(phase + 2 * PI * i / n);
  }
}

int gen_grid(rng *g, vec2 *p, int n, int size) {
  gen_star(g, p, n, 0, 0, size * 0.7, 0.4);
  int k = 0;
  for (int i = 0; i < n; i++) {
    vec2 q = {floor(p[i].x + 0.5), floor(p[i].y + 0.5)};
    if (k > 0 && q.x == p[k - 1].x && q.y == p[k - 1].y) continue;
    p[k++] = q;
  }
  while (k > 1 && p[k - 1].x == p[0].x && p[k - 1].y == p[0].y) k--;
  return k;
}

/* The glass's radius at height t in [0, 1]: a foot, a stem, a bowl. */
static double glass_radius(double t) {
  if (t < 0.06) return 0.55 - 0.2 * t / 0.06;             /* the foot */
  if (t < 0.12) return 0.35 - 0.27 * (t - 0.06) / 0.06;   /* into the stem */
  if (t < 0.45) return 0.08;                              /* the stem */
  double u = (t - 0.45) / 0.55;                           /* the bowl */
  return 0.08 + 0.55 * sin(u * PI * 0.62) * (1 - 0.15 * u);
}

void gen_glass(contour_stack *s, int slices, int points) {
  s->n = slices;
  s->nslices = slices;
  s->c = xcalloc((size_t)slices, sizeof *s->c);
  for (int i = 0; i < slices; i++) {
    double t = (double)i / (slices - 1);
    contour *c = &s->c[i];
    c->z = 2.0 * t;
    c->n = points;
    c->line = 0;
    c->slice = i;
    c->pt = xmallocarray((size_t)points, sizeof *c->pt);
    /* A slightly oval section, turning a little with height, so the tiler
     * has real choices to make. */
    double r = glass_radius(t);
    for (int j = 0; j < points; j++) {
      double a = 2 * PI * j / points + 0.3 * t;
      c->pt[j].x = r * 1.05 * cos(a);
      c->pt[j].y = r * 0.95 * sin(a);
    }
  }
}
