/* test_exact.c -- the exact orientation against integer determinants at every
 * scale from subnormals to 1e300, under exact translations, one ulp off a
 * line, and the floating-point filter against the big-integer sum. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "tests/check.h"
#include "geom/exact.h"
#include "util/rng.h"

/* The sign of the integer determinant (b-a) x (c-a): the reference. */
static int isign(const long long *v) {
  long long d = (v[2] - v[0]) * (v[5] - v[1]) - (v[3] - v[1]) * (v[4] - v[0]);
  return d > 0 ? 1 : d < 0 ? -1 : 0;
}

/* Integer points (|v| < 2^20) scaled by 2^k and shifted by c 2^(k+21), with
 * |c| < 2^30: every coordinate is exact, so the sign must be the integers'. */
static void integers(rng *g) {
  static const int scales[] = {-1074, -1070, -1060, -1022, -1000, -600, -300, -53, -1, 0, 1,
                               40, 300, 600, 900, 950, 980};
  int fails = 0, runs = 0;
  for (int trial = 0; trial < 20000; trial++) {
    long long v[6];
    int R = trial % 3 == 0 ? 3 : trial % 3 == 1 ? 1000 : (1 << 20) - 1;   /* small: many zeros */
    for (int i = 0; i < 6; i++) v[i] = rng_int(g, -R, R);
    if (trial % 7 == 0) {   /* c on the line ab */
      long long t = rng_int(g, -3, 3);
      v[4] = v[0] + t * (v[2] - v[0]), v[5] = v[1] + t * (v[3] - v[1]);
      if (llabs(v[4]) >= (1 << 20) || llabs(v[5]) >= (1 << 20)) continue;
    }
    int want = isign(v);
    for (size_t s = 0; s < sizeof scales / sizeof *scales; s++) {
      int k = scales[s];
      long long cx = 0, cy = 0;
      if (k <= 980 - 21 - 31 && trial % 2) cx = rng_int(g, -(1 << 29), 1 << 29), cy = rng_int(g, -(1 << 29), 1 << 29);
      double ox = ldexp((double)cx, k + 21), oy = ldexp((double)cy, k + 21);
      vec2 p[3];
      for (int i = 0; i < 3; i++)
        p[i] = (vec2){ldexp((double)v[2 * i], k) + ox, ldexp((double)v[2 * i + 1], k) + oy};
      int got = exact_orient(p[0], p[1], p[2]), slow = exact_orient_slow(p[0], p[1], p[2]);
      /* The same for every cyclic order, and reversed for the mirror order. */
      int rot = exact_orient(p[1], p[2], p[0]), mir = exact_orient(p[1], p[0], p[2]);
      runs++;
      if (got != want || slow != want || rot != want || mir != -want) {
        if (fails++ < 5)
          CHECK(0, "orient of (%lld %lld) (%lld %lld) (%lld %lld) at 2^%d: %d, slow %d, rotated %d, "
                   "mirrored %d, want %d", v[0], v[1], v[2], v[3], v[4], v[5], k, got, slow, rot, mir, want);
      }
    }
  }
  CHECK(fails == 0, "%d of %d integer orientations wrong", fails, runs);
}

/* c exactly on the line ab, then one ulp above it: a tiny determinant that
 * any rounding would lose, at every scale. */
static void one_ulp(rng *g) {
  int fails = 0, runs = 0;
  for (int trial = 0; trial < 5000; trial++) {
    long long ax = rng_int(g, -1000, 1000), ay = rng_int(g, -1000, 1000);
    long long dx = rng_int(g, 1, 1000), dy = rng_int(g, -1000, 1000);
    int k = rng_int(g, -1074, 960);
    vec2 a = {ldexp((double)ax, k), ldexp((double)ay, k)};
    vec2 b = {ldexp((double)(ax + dx), k), ldexp((double)(ay + dy), k)};
    vec2 c = {ldexp((double)(ax + 2 * dx), k), ldexp((double)(ay + 2 * dy), k)};
    vec2 up = {c.x, nextafter(c.y, HUGE_VAL)}, down = {c.x, nextafter(c.y, -HUGE_VAL)};
    runs++;
    int on = exact_orient(a, b, c), u = exact_orient(a, b, up), d = exact_orient(a, b, down);
    if (on != 0 || u != 1 || d != -1)
      if (fails++ < 5) CHECK(0, "one ulp at 2^%d: on %d (want 0), above %d (1), below %d (-1)", k, on, u, d);
  }
  CHECK(fails == 0, "%d of %d one-ulp cases wrong", fails, runs);
}

/* Kettner et al.'s classroom example (Classroom examples of robustness
 * problems in geometric computations, 2008): p = (0.5 + x u, 0.5 + y u) with
 * u = 2^-53, q = (12, 12), r = (24, 24).  In units of u the determinant is
 * 12 2^53 (y - x), so the sign is that of y - x; plain floating point gets
 * hundreds of these wrong.  At several scales 2^k. */
static void kettner(void) {
  static const int scales[] = {-1000, -500, 0, 500, 900};
  int fails = 0;
  for (size_t s = 0; s < sizeof scales / sizeof *scales; s++) {
    int k = scales[s];
    vec2 q = {ldexp(12, k), ldexp(12, k)}, r = {ldexp(24, k), ldexp(24, k)};
    for (int x = 0; x < 256; x++)
      for (int y = 0; y < 256; y++) {
        vec2 p = {ldexp(0.5 + x * 0x1p-53, k), ldexp(0.5 + y * 0x1p-53, k)};
        int want = (y > x) - (y < x);
        int got = exact_orient(p, q, r), slow = exact_orient_slow(p, q, r);
        int r1 = exact_orient(q, r, p), r2 = exact_orient(r, p, q);   /* each point as the pivot */
        if (got != want || slow != want || r1 != want || r2 != want)
          if (fails++ < 5) CHECK(0, "Kettner (%d, %d) at 2^%d: %d, slow %d, pivots %d %d, want %d", x, y, k, got,
                                slow, r1, r2, want);
      }
  }
  CHECK(fails == 0, "%d of the Kettner orientations wrong", fails);
}

/* Random doubles of wildly different magnitudes (1e-320 .. 1e300, signs):
 * the filter must agree with the big-integer sum whenever it decides. */
static void wide(rng *g) {
  int fails = 0;
  for (int trial = 0; trial < 20000; trial++) {
    vec2 p[3];
    for (int i = 0; i < 3; i++) {
      double m[2];
      for (int j = 0; j < 2; j++) {
        int e = trial % 4 == 0 ? rng_int(g, -1074, 1000) : rng_int(g, -30, 30);
        m[j] = ldexp(rng_uniform(g) + 0.5, e) * (rng_next(g) & 1 ? -1 : 1);
        if (rng_int(g, 0, 9) == 0) m[j] = 0;
      }
      p[i] = (vec2){m[0], m[1]};
    }
    if (trial % 5 == 0) p[2] = p[rng_int(g, 0, 1)];   /* a repeated point: 0 */
    int f = exact_orient(p[0], p[1], p[2]), s = exact_orient_slow(p[0], p[1], p[2]);
    int s2 = exact_orient_slow(p[2], p[0], p[1]);
    if (f != s || s != s2)
      if (fails++ < 5)
        CHECK(0, "filter %d, exact %d, rotated exact %d for (%a %a) (%a %a) (%a %a)", f, s, s2,
              p[0].x, p[0].y, p[1].x, p[1].y, p[2].x, p[2].y);
  }
  CHECK(fails == 0, "%d wide-range orientations disagree", fails);
  /* The extremes themselves. */
  vec2 o = {0, 0}, big = {DBL_MAX, DBL_MAX}, nbig = {-DBL_MAX, -DBL_MAX};
  CHECK(exact_orient(nbig, o, big) == 0, "-MAX, 0, MAX are collinear");
  CHECK(exact_orient(nbig, big, (vec2){-DBL_MAX, DBL_MAX}) == 1, "a left turn at DBL_MAX");
  vec2 t1 = {0x1p-1074, 0}, t2 = {0, 0x1p-1074};
  CHECK(exact_orient(o, t1, t2) == 1, "a left turn among subnormals");
  CHECK(exact_orient(o, t1, (vec2){0x1p-1073, 0}) == 0, "collinear subnormals");
  CHECK(exact_orient((vec2){1e300, 1e300}, (vec2){-1e300, 1e-300}, (vec2){1e-300, -1e300}) ==
            exact_orient_slow((vec2){1e300, 1e300}, (vec2){-1e300, 1e-300}, (vec2){1e-300, -1e300}),
        "mixed extremes");
  CHECK(exact_lex((vec2){1, 2}, (vec2){1, 3}) < 0 && exact_lex((vec2){2, 0}, (vec2){1, 3}) > 0 &&
            exact_lex((vec2){1, 2}, (vec2){1, 2}) == 0,
        "lexicographic order");
}

int main(void) {
  rng g;
  rng_seed(&g, 20240614);
  integers(&g);
  one_ulp(&g);
  kettner();
  wide(&g);
  return check_done("test_exact");
}
