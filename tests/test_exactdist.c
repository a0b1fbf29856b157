/* test_exactdist.c -- squared point-segment distances compared exactly
 * (geom/exactdist.h) against integer arithmetic: small integer points at
 * every scale from subnormals to 1e290, shifted by large exact offsets (so
 * that the interval filter fails and the big integers decide), ties by the
 * thousand, comparisons against a length, one-ulp moves that any rounding
 * would lose, and the filter against the big integers alone. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "tests/check.h"
#include "geom/exactdist.h"
#include "util/rng.h"

/* The reference: the squared distance from p to the segment ab as the exact
 * fraction num / den, in integers (|coordinates| <= 400: den < 2^21, num <
 * 2^41, their cross products < 2^62). */
typedef struct { int64_t num, den; } frac;

static frac ref_dist(const int64_t *p, const int64_t *a, const int64_t *b) {
  int64_t ux = b[0] - a[0], uy = b[1] - a[1], wx = p[0] - a[0], wy = p[1] - a[1];
  int64_t vx = p[0] - b[0], vy = p[1] - b[1];
  if (wx * ux + wy * uy <= 0) return (frac){wx * wx + wy * wy, 1};
  if (-(vx * ux + vy * uy) <= 0) return (frac){vx * vx + vy * vy, 1};
  int64_t c = ux * wy - uy * wx;
  return (frac){c * c, ux * ux + uy * uy};
}

static int ref_cmp(frac x, frac y) {
  int64_t l = x.num * y.den, r = y.num * x.den;
  return l < r ? -1 : l > r;
}

static vec2 at(const int64_t *v, int k, double ox, double oy) {
  return (vec2){ldexp((double)v[0], k) + ox, ldexp((double)v[1], k) + oy};
}

static void integers(rng *g) {
  static const int scales[] = {-1074, -1060, -1022, -900, -300, -60, 0, 1, 60, 300, 900, 960};
  int fails = 0, runs = 0, ties = 0, slow_fails = 0, len_fails = 0;
  for (int trial = 0; trial < 6000; trial++) {
    int R = trial % 3 == 0 ? 3 : trial % 3 == 1 ? 20 : 200;   /* small: many ties and zeros */
    int64_t v[12];
    for (int i = 0; i < 12; i++) v[i] = rng_int(g, -R, R);
    if (v[2] == v[4] && v[3] == v[5]) v[4]++;
    if (trial % 4 == 1)   /* the first configuration moved and mirrored: a tie */
      for (int i = 0; i < 6; i += 2) v[6 + i] = -v[i] + v[0], v[7 + i] = v[i + 1] - v[1];
    if (v[8] == v[10] && v[9] == v[11]) v[11]++;
    frac fx = ref_dist(v, v + 2, v + 4), fy = ref_dist(v + 6, v + 8, v + 10);
    int want = ref_cmp(fx, fy);
    ties += want == 0;
    int64_t r = rng_int(g, 0, R);   /* a length to compare with */
    int want_len = ref_cmp(fx, (frac){r * r, 1});
    for (size_t s = 0; s < sizeof scales / sizeof *scales; s++) {
      int k = scales[s];
      double ox = 0, oy = 0;
      if (k <= 900 && k >= -1000 && trial % 2) {   /* an exact shift, far larger than the points */
        ox = ldexp((double)rng_int(g, -(1 << 28), 1 << 28), k + 24);
        oy = ldexp((double)rng_int(g, -(1 << 28), 1 << 28), k + 24);
      }
      exactdist x, y;
      exactdist_segment(at(v, k, ox, oy), at(v + 2, k, ox, oy), at(v + 4, k, ox, oy), &x);
      exactdist_segment(at(v + 6, k, ox, oy), at(v + 8, k, ox, oy), at(v + 10, k, ox, oy), &y);
      int got = exactdist_cmp(&x, &y), back = exactdist_cmp(&y, &x), slow = exactdist_cmp_slow(&x, &y);
      int len = exactdist_cmp_len(&x, ldexp((double)r, k));
      runs++;
      if (got != want || back != -want) {
        if (fails++ < 5)
          CHECK(0, "trial %d at 2^%d: cmp %d, reversed %d, want %d", trial, k, got, back, want);
      }
      slow_fails += slow != want;
      if (len != want_len && len_fails++ < 5)
        CHECK(0, "trial %d at 2^%d: against length %lld: %d, want %d", trial, k, (long long)r, len, want_len);
      /* The interval holds the value: scaled back, the integers' fraction. */
      if (k == 0 && !ox) {
        double want_v = (double)fx.num / (double)fx.den;
        CHECK(x.lo <= want_v * (1 + 1e-15) && x.hi >= want_v * (1 - 1e-15),
              "trial %d: value %.17g outside [%.17g, %.17g]", trial, want_v, x.lo, x.hi);
        CHECK(fabs(exactdist_value(&x) - sqrt(want_v)) <= 1e-12 * (1 + sqrt(want_v)), "trial %d: value %.17g, want %.17g",
              trial, exactdist_value(&x), sqrt(want_v));
      }
    }
  }
  CHECK(fails == 0, "%d of %d comparisons wrong", fails, runs);
  CHECK(slow_fails == 0, "%d of %d comparisons by the big integers alone wrong", slow_fails, runs);
  CHECK(len_fails == 0, "%d comparisons against a length wrong", len_fails);
  CHECK(ties > 200, "only %d ties among the trials: the test does not test them", ties);
}

/* A point straight over a segment's interior at height h, against a point
 * h from a vertex: equal, whatever the shift; one ulp higher is farther. */
static void one_ulp(void) {
  static const double shifts[] = {0, 0x1p30, 0x1p52, -0x1p60, 0x1p200, 1e-300};
  int bad = 0;
  for (size_t s = 0; s < sizeof shifts / sizeof *shifts; s++) {
    double o = shifts[s], h = o ? ldexp(1, (int)fmin(fmax(log2(fabs(o)) - 40, -1070), 900)) : 5;
    vec2 a = {o - 3 * h, o}, b = {o + 3 * h, o}, p = {o, o + h};
    vec2 c = {o + 7 * h, o - 2 * h}, q = {o + 7 * h, o - 3 * h};   /* |q - c| = h */
    vec2 up = {p.x, nextafter(p.y, INFINITY)}, down = {p.x, nextafter(p.y, -INFINITY)};
    exactdist x, y, xu, xd;
    exactdist_segment(p, a, b, &x);
    exactdist_points(q, c, &y);
    exactdist_segment(up, a, b, &xu);
    exactdist_segment(down, a, b, &xd);
    bad += x.kind != EXACTDIST_LINE || exactdist_cmp(&x, &y) != 0 || exactdist_cmp(&xu, &y) != 1 ||
           exactdist_cmp(&xd, &y) != -1 || exactdist_cmp(&xu, &xd) != 1 || exactdist_cmp_len(&x, h) != 0 ||
           exactdist_cmp_len(&xu, h) != 1 || exactdist_cmp_len(&xd, h) != -1;
    /* The projection exactly at an end: the end's distance. */
    vec2 e = {o + 3 * h, o + h};
    exactdist z, ze;
    exactdist_segment(e, a, b, &z);
    exactdist_points(e, b, &ze);
    bad += exactdist_cmp(&z, &ze) != 0;
  }
  CHECK(bad == 0, "%d one-ulp comparisons wrong", bad);
}

/* The filter never decides against the big integers: random doubles. */
static void filter(rng *g) {
  int bad = 0;
  for (int trial = 0; trial < 20000; trial++) {
    vec2 v[6];
    double sc = ldexp(1, rng_int(g, -40, 40));
    for (int i = 0; i < 6; i++) v[i] = (vec2){sc * (rng_uniform(g) - 0.5), sc * (rng_uniform(g) - 0.5)};
    if (trial % 4 == 0) v[3] = (vec2){v[0].x + sc * 1e-9 * rng_uniform(g), v[0].y};   /* near ties */
    exactdist x, y;
    exactdist_segment(v[0], v[1], v[2], &x);
    exactdist_segment(v[3], v[4], v[5], &y);
    bad += exactdist_cmp(&x, &y) != exactdist_cmp_slow(&x, &y);
  }
  CHECK(bad == 0, "%d of 20000 filtered comparisons disagree with the big integers", bad);
}

int main(void) {
  rng g;
  rng_seed(&g, 2207);
  integers(&g);
  one_ulp();
  filter(&g);
  return check_done("test_exactdist");
}
