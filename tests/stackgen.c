/* stackgen.c -- stacks of several contours per slice for the tests (stackgen.h). */
#include "tests/stackgen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/check.h"

#define PI 3.14159265358979323846

void sg_circle(vec2 *p, int n, double cx, double cy, double rx, double ry, double phase) {
  for (int i = 0; i < n; i++) {
    double a = phase + 2 * PI * i / n;
    p[i] = (vec2){cx + rx * cos(a), cy + ry * sin(a)};
  }
}

/* A contour as text, from point `start`, reversed if asked. */
static void put(FILE *f, const vec2 *p, int n, double z, int start, int rev) {
  fprintf(f, "C %d %.17g\n", n, z);
  for (int k = 0; k < n; k++) {
    int i = rev ? (start - k + n) % n : (start + k) % n;
    fprintf(f, "%.17g %.17g\n", p[i].x, p[i].y);
  }
}

int sg_make_stack(const sg_poly *ps, int np, const int *order, const int *start, const int *rev,
                  contour_stack *s) {
  char *text = NULL, err[512];
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  for (int k = 0; k < np; k++) {
    int i = order ? order[k] : k;
    put(f, ps[i].p, ps[i].n, ps[i].z, start ? start[i] % ps[i].n : 0, rev ? rev[i] : 0);
  }
  fclose(f);
  int rc = contour_parse(text, len, "t.contours", s, NULL, "test", err, sizeof err);
  CHECK(rc == 0, "stack: %s", err);
  free(text);
  return rc;
}

int sg_random(rng *g, vec2 (*buf)[SG_N], sg_poly *ps) {
  int np = 0, K = rng_int(g, 2, 5);
  for (int k = 0; k < K; k++) {
    double placed[6][3];
    int nd = 0;
    for (int t = 0; t < 6 && np + 3 <= SG_MAXP; t++) {
      double r = 0.5 + 2.5 * rng_uniform(g), cx = 12 * rng_uniform(g) - 6, cy = 12 * rng_uniform(g) - 6;
      int clear = 1;
      for (int d = 0; d < nd; d++)
        if (hypot(cx - placed[d][0], cy - placed[d][1]) < r + placed[d][2] + 0.05) clear = 0;
      if (!clear) continue;
      placed[nd][0] = cx, placed[nd][1] = cy, placed[nd++][2] = r;
      int n = rng_int(g, 8, SG_N);
      sg_circle(buf[np], n, cx, cy, r, r, 6 * rng_uniform(g)), ps[np] = (sg_poly){n, k, buf[np]}, np++;
      if (r > 1.2 && rng_int(g, 0, 1)) {
        double hr = r * (0.2 + 0.4 * rng_uniform(g));
        double hx = cx + (rng_uniform(g) - 0.5) * (r - hr), hy = cy + (rng_uniform(g) - 0.5) * (r - hr);
        n = rng_int(g, 8, SG_N);
        sg_circle(buf[np], n, hx, hy, hr, hr, 6 * rng_uniform(g)), ps[np] = (sg_poly){n, k, buf[np]}, np++;
        if (hr > 0.6 && rng_int(g, 0, 1)) {
          n = rng_int(g, 8, SG_N);
          sg_circle(buf[np], n, hx, hy, 0.4 * hr, 0.4 * hr, 6 * rng_uniform(g)), ps[np] = (sg_poly){n, k, buf[np]}, np++;
        }
      }
    }
  }
  return np;
}

stack_surface *sg_tile(const contour_stack *s, stack_options o, char *notes, size_t nlen, char *err, size_t errlen,
                       int *res) {
  char *buf = NULL;
  size_t len = 0;
  if (notes) o.notes = open_memstream(&buf, &len);
  stack_surface *ss = NULL;
  *res = stack_tile(s, "t.contours", &o, &ss, err, errlen);
  if (notes) {
    fclose(o.notes);
    snprintf(notes, nlen, "%s", buf ? buf : "");
    free(buf);
  }
  return ss;
}
