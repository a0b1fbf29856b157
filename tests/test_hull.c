/* test_hull.c -- the convex hull against its definition (every point on the
 * inner side of every edge, the vertices strictly convex and among the
 * points) and the extreme-point search against a scan of all points. */
#include <math.h>
#include <stdlib.h>

#include "tests/check.h"
#include "geom/exact.h"
#include "input/gen.h"
#include "geom/hull.h"
#include "util/rng.h"
#include "util/xmem.h"

int main(void) {
  rng g;
  rng_seed(&g, 4242);
  int bad_hull = 0, bad_ext = 0, trials = 1200;
  vec2 *p = xmallocarray(4000, sizeof *p);
  for (int trial = 0; trial < trials; trial++) {
    int n;
    switch (trial % 4) {
    case 0:   /* a small grid: duplicates and collinear points */
      n = rng_int(&g, 1, 40);
      for (int i = 0; i < n; i++) p[i] = (vec2){rng_int(&g, 0, 4), rng_int(&g, 0, 4)};
      break;
    case 1:   /* a star, far from the origin */
      n = rng_int(&g, 3, 1000);
      gen_star(&g, p, n, 1e8, -1e8, 3, 0.5);
      break;
    case 2:   /* a regular polygon: every point on the hull */
      n = rng_int(&g, 3, 300);
      gen_regular(p, n, 0, 0, 1, 0.1);
      break;
    default:   /* random points in a thin box */
      n = rng_int(&g, 1, 500);
      for (int i = 0; i < n; i++) p[i] = (vec2){rng_uniform(&g), 1e-9 * rng_uniform(&g)};
      break;
    }
    hull *h = hull_new(p, n);
    int k = hull_size(h), ok = k >= 1 && k <= n;
    for (int i = 0; ok && i < k; i++) {
      vec2 a = hull_vertex(h, i), b = hull_vertex(h, (i + 1) % k), c = hull_vertex(h, (i + 2) % k);
      if (k >= 3 && exact_orient(a, b, c) <= 0) ok = 0;   /* strictly convex, counter-clockwise */
      int among = 0;
      for (int j = 0; j < n && !among; j++) among = p[j].x == a.x && p[j].y == a.y;
      if (!among) ok = 0;
      if (k >= 3 && (trial % 4 != 1 || i % 37 == 0))   /* every point inside (sampled edges for big stars) */
        for (int j = 0; j < n && ok; j++)
          if (exact_orient(a, b, p[j]) < 0) ok = 0;
    }
    if (!ok && bad_hull++ < 5) CHECK(0, "trial %d: a hull of %d vertices for %d points is wrong", trial, k, n);
    /* Extremes in random directions: within rounding of the best point. */
    for (int q = 0; q < 20 && ok; q++) {
      double a = rng_uniform(&g) * 6.283185307179586;
      double dx = cos(a), dy = sin(a);
      if (q == 0) dx = 1, dy = 0;
      vec2 e = hull_extreme(h, dx, dy), o = p[0];
      double best = -HUGE_VAL, ext = dx * (e.x - o.x) + dy * (e.y - o.y), scale = 0;
      for (int j = 0; j < n; j++) {
        best = fmax(best, dx * (p[j].x - o.x) + dy * (p[j].y - o.y));
        scale = fmax(scale, fabs(p[j].x - o.x) + fabs(p[j].y - o.y));
      }
      if (ext < best - 1e-14 * scale && bad_ext++ < 5)
        CHECK(0, "trial %d: the extreme in (%g %g) gives %.17g, the best point %.17g", trial, dx, dy, ext, best);
    }
    hull_free(h);
  }
  CHECK(bad_hull == 0, "%d of %d hulls wrong", bad_hull, trials);
  CHECK(bad_ext == 0, "%d extreme points wrong", bad_ext);
  free(p);
  return check_done("test_hull");
}
