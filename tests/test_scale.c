/* test_scale.c -- the tiler at any scale, and its quantum:
 * pairs scaled by 2^k (into subnormals and up to 2^1000) give the
 * unit-scale path bit for bit and costs exactly 2^2k (area) or 2^k (span)
 * apart; scaled by 1e300 or 1e-300 the same path; every weight of the graph
 * fits the room the quantum leaves (brute force over all tiles), and the
 * largest fills at least a quarter of it; the spike pair's cost equals its
 * area to 1e-12, against an independent area. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/gen.h"
#include "algo/par.h"
#include "util/rng.h"
#include "tests/parmachine.h"
#include "geom/geom.h"
#include "algo/tiling.h"
#include "util/xmem.h"

static void scaled(const vec2 *p, int n, double s, vec2 *out) {
  for (int i = 0; i < n; i++) out[i] = (vec2){p[i].x * s, p[i].y * s};
}

static int same_path(const tiling *a, const tiling *b) {
  return a->start == b->start && a->m == b->m && a->n == b->n && a->transposed == b->transposed &&
         memcmp(a->col, b->col, sizeof *a->col * (size_t)(a->m + a->n + 1)) == 0;
}

/* Power-of-two scales: bit for bit.  Integer stars (exact at every scale,
 * subnormals included) and real-valued stars (exact away from subnormals). */
static void powers_of_two(rng *g) {
  static const int ks[] = {-1070, -1060, -1000, -600, -1, 1, 300, 600, 1000};
  int fails = 0, runs = 0;
  vec2 P[64], Q[64], Ps[64], Qs[64];
  for (int trial = 0; trial < 60; trial++) {
    int integer = trial % 2, np, nq;
    if (integer) {
      np = gen_grid(g, P, rng_int(g, 6, 40), 300);
      nq = gen_grid(g, Q, rng_int(g, 6, 40), 200);
    } else {
      np = rng_int(g, 3, 40), nq = rng_int(g, 3, 40);
      gen_star(g, P, np, 0, 0, 10, 0.4);
      gen_star(g, Q, nq, 1, -2, 6, 0.4);
    }
    cost_kind kind = trial % 3 ? COST_AREA : COST_SPAN;
    double zp = integer ? 0 : 0.25, zq = integer ? 3 : 1.75;
    tiling t0;
    tiling_solve(P, np, zp, Q, nq, zq, kind, -1, &t0);
    for (size_t s = 0; s < sizeof ks / sizeof *ks; s++) {
      int k = ks[s];
      if (!integer && k < -1000) continue;   /* real values would lose bits as subnormals */
      double f = ldexp(1, k);
      scaled(P, np, f, Ps);
      scaled(Q, nq, f, Qs);
      tiling t;
      tiling_solve(Ps, np, zp * f, Qs, nq, zq * f, kind, -1, &t);
      int sh = kind == COST_AREA ? 2 * k : k;
      double want = ldexp(t0.cost, sh);   /* inf or 0 where beyond range */
      int ok = same_path(&t, &t0) && t.quanta == t0.quanta && t.qexp == t0.qexp + sh &&
               (t.cost == want || (isinf(want) && isinf(t.cost)));
      runs++;
      if (!ok && fails++ < 5)
        CHECK(0, "%s %s pair %dx%d at 2^%d: start %d/%d, quanta %.17g/%.17g, qexp %d/%d, cost %g/%g",
              integer ? "integer" : "real", cost_name(kind), np, nq, k, t.start, t0.start, t.quanta,
              t0.quanta, t.qexp, t0.qexp + sh, t.cost, want);
      tiling_free(&t);
    }
    tiling_free(&t0);
  }
  CHECK(fails == 0, "%d of %d power-of-two scalings differ from unit scale", fails, runs);
}

/* 1e300 and 1e-300 (rounded, not exact): the same path, the cost scaled. */
static void decimal_scales(rng *g) {
  static const double fs[] = {1e300, 1e-300, 1e150, 3e-310};
  int fails = 0;
  vec2 P[64], Q[64], Ps[64], Qs[64];
  for (int trial = 0; trial < 40; trial++) {
    int np = rng_int(g, 5, 50), nq = rng_int(g, 5, 50);
    gen_star(g, P, np, 0, 0, 100, 0.3);   /* the star polygons */
    gen_star(g, Q, nq, 5, 5, 80, 0.3);
    cost_kind kind = trial % 2 ? COST_AREA : COST_SPAN;
    tiling t0;
    tiling_solve(P, np, 0, Q, nq, 1, kind, -1, &t0);
    for (size_t s = 0; s < sizeof fs / sizeof *fs; s++) {
      double f = fs[s];
      scaled(P, np, f, Ps);
      scaled(Q, nq, f, Qs);
      tiling t;
      tiling_solve(Ps, np, 0, Qs, nq, f, kind, -1, &t);
      /* The cost over unit scale's, over f (span) or f^2 (area), from quanta
       * and exponents (the cost itself may lie beyond double's range). */
      int ef;
      double mf = frexp(f, &ef), p = kind == COST_AREA ? 2 : 1;
      double d = ldexp(t.quanta / t0.quanta / pow(mf, p), t.qexp - t0.qexp - (int)p * ef) - 1;
      /* 3e-310 is subnormal: its shapes keep only about 40 bits */
      double tol = f < 1e-305 ? 1e-9 : 1e-13;
      int ok = same_path(&t, &t0) && fabs(d) < tol;
      if (!ok && fails++ < 5)
        CHECK(0, "%s pair %dx%d at %g: start %d/%d, cost off by %g relative", cost_name(kind), np, nq, f,
              t.start, t0.start, d);
      tiling_free(&t);
    }
    tiling_free(&t0);
  }
  CHECK(fails == 0, "%d decimal scalings differ from unit scale", fails);
}

/* Every weight of the graph, in quanta, below the room 2^52/(m+n+1) - 1 the
 * quantum was chosen for; the largest at least a quarter of it (the bound is
 * tight).  Brute force over all 2mn tiles. */
static void room(rng *g) {
  int fails = 0, loose = 0, runs = 0;
  vec2 P[80], Q[80];
  for (int trial = 0; trial < 300; trial++) {
    int np, nq;
    switch (trial % 5) {
    case 0:   /* the spike: 3e11 long, 1 wide */
      np = 4, nq = 4;
      P[0] = (vec2){0, 0}, P[1] = (vec2){1, 0}, P[2] = (vec2){0.5, ldexp(rng_uniform(g) + 1, rng_int(g, 10, 60))}, P[3] = (vec2){0, 1};
      Q[0] = (vec2){0, 0}, Q[1] = (vec2){1, 0}, Q[2] = (vec2){1, 1}, Q[3] = (vec2){0, 1};
      break;
    case 1:   /* the sliver of item 8 */
      np = 51, nq = rng_int(g, 5, 60);
      for (int i = 0; i < 50; i++) P[i] = (vec2){1e8 + i, 1e8 + i};
      P[50] = (vec2){1e8, 1e8 + 1e-8};
      gen_star(g, Q, nq, 1e8 + 25, 1e8 + 25, 100, 0.3);
      break;
    case 2:   /* integer grids: many equal weights */
      np = gen_grid(g, P, rng_int(g, 5, 60), 6);
      nq = gen_grid(g, Q, rng_int(g, 5, 60), 9);
      if (np < 3) continue;
      if (nq < 3) continue;
      break;
    default:   /* stars, far apart or nested, at random scales */
      np = rng_int(g, 3, 70), nq = rng_int(g, 3, 70);
      gen_star(g, P, np, 0, 0, ldexp(1, rng_int(g, -20, 20)), 0.9);
      gen_star(g, Q, nq, rng_uniform(g) * 100, 0, ldexp(1, rng_int(g, -20, 20)), 0.9);
      break;
    }
    double zq = trial % 7 == 0 ? 1e-9 : trial % 7 == 1 ? 1e9 : 1;
    for (int kind = 0; kind < 2; kind++) {
      weights *w = weights_new(P, np, 0, Q, nq, zq, (cost_kind)kind, 0);
      double lim = 0x1p52 / (double)(np + nq + 1) - 1, mx = 0;
      for (int i = 0; i < np; i++)
        for (int j = 0; j < nq; j++) mx = fmax(mx, fmax(weights_v(w, i, j), weights_h(w, i, j)));
      runs++;
      if (!(mx <= lim) && fails++ < 5)
        CHECK(0, "%s trial %d: a weight of %.17g quanta over the room %.17g", cost_name((cost_kind)kind), trial, mx, lim);
      if (kind == COST_AREA && mx < lim / 4 && loose++ < 5)
        CHECK(0, "area trial %d (%dx%d): the largest weight %.17g quanta, under a quarter of the room %.17g",
              trial, np, nq, mx, lim);
      weights_free(w);
    }
  }
  CHECK(fails == 0, "%d of %d pairs have a weight beyond the room", fails, runs);
  CHECK(loose == 0, "%d pairs have a loose area quantum", loose);
}

/* The triangle's area by Kahan's stable formula on the sorted side lengths
 * (Miscalculating area and angles of a needle-like triangle, 2014), in long
 * double: a reference independent of the weights and the mesh. */
static long double kahan_area(const double *a, const double *b, const double *c) {
  long double s[3];
  const double *v[3] = {a, b, c};
  for (int i = 0; i < 3; i++) {
    const double *p = v[i], *q = v[(i + 1) % 3];
    long double dx = (long double)q[0] - p[0], dy = (long double)q[1] - p[1], dz = (long double)q[2] - p[2];
    s[i] = sqrtl(dx * dx + dy * dy + dz * dz);
  }
  for (int i = 0; i < 3; i++)   /* s[0] >= s[1] >= s[2] */
    for (int j = i + 1; j < 3; j++)
      if (s[j] > s[i]) {
        long double t = s[i];
        s[i] = s[j], s[j] = t;
      }
  long double A = s[0], B = s[1], C = s[2];
  return 0.25L * sqrtl((A + (B + C)) * (C - (A - B)) * (C + (A - B)) * (A + (B - C)));
}

/* The spike of item 9: cost within 1e-12 of the path's area (it was 3.4e-4 off). */
static void spike(void) {
  vec2 P[4] = {{0, 0}, {1, 0}, {0.5, 3e11}, {0, 1}}, Q[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int par = 0; par < 2; par++) {
    tiling t;
    if (par) {   /* the parallel algorithm gets the same quantum */
      par_machine rc;
      par_machine_init(&rc);
      rc.mc.procs = 3;
      par_pair pr;
      memset(&pr, 0, sizeof pr);
      pr.P = P, pr.np = 4, pr.zp = 0, pr.Q = Q, pr.nq = 4, pr.zq = 1;
      char err[256];
      CHECK(par_machine_run(&rc, &pr, 1, err, sizeof err) == 0, "parallel run: %s", err);
      t = pr.t;
    } else {
      tiling_solve(P, 4, 0, Q, 4, 1, COST_AREA, -1, &t);
    }
    int (*tile)[3] = xmallocarray(8, sizeof *tile);
    unsigned char on[8];
    tiling_tiles(&t, tile, on);
    long double area = 0;
    for (int k = 0; k < 8; k++) {
      const vec2 *X = on[k] ? Q : P, *Y = on[k] ? P : Q;
      double zx = on[k] ? 1 : 0, zy = on[k] ? 0 : 1;
      double a[3] = {X[tile[k][0]].x, X[tile[k][0]].y, zx}, b[3] = {X[tile[k][1]].x, X[tile[k][1]].y, zx};
      double c[3] = {Y[tile[k][2]].x, Y[tile[k][2]].y, zy};
      area += kahan_area(a, b, c);
    }
    double rel = fabs((double)((t.cost - area) / area));
    CHECK(rel < 1e-12, "%s spike: cost %.17g, area %.17Lg, %.3g apart", par ? "parallel" : "serial", t.cost, area, rel);
    /* the quantum: about 2^-52 / 9 of the largest tile (about 2.2e11) */
    CHECK(t.quantum < 1e-3 && t.quantum > 1e-5, "spike quantum %g", t.quantum);
    free(tile);
    tiling_free(&t);
  }
}

/* geom_ldexp and geom_scale_exp, the inline forms the areas and volumes use,
 * against libm's ldexp and frexp bit for bit: every exponent from -1100 to
 * 1100 on normal, subnormal, huge, signed, zero, infinite and NaN values. */
static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static void inline_scaling(rng *g) {
  double xs[64] = {0.0, -0.0, 1.0, -1.0, 0.75, DBL_MIN, -DBL_MIN, DBL_TRUE_MIN, 3 * DBL_TRUE_MIN, DBL_MAX, -DBL_MAX,
                   DBL_MIN * 0.75, DBL_MIN * (1 - DBL_EPSILON), 1 + DBL_EPSILON, INFINITY, -INFINITY, NAN};
  int nx = 17;
  while (nx < 64) {
    double m = rng_uniform(g) + 0.5, e = floor(rng_uniform(g) * 2140) - 1070;
    double sign = nx % 2 ? -1 : 1;
    xs[nx++] = sign * ldexp(m, (int)e);
  }
  int bad = 0, badexp = 0;
  for (int i = 0; i < nx; i++) {
    for (int e = -1100; e <= 1100; e++)
      if (!same_bits(geom_ldexp(xs[i], e), ldexp(xs[i], e)) && !(isnan(xs[i]) && isnan(geom_ldexp(xs[i], e)))) bad++;
    int want = 0;
    if (xs[i] > 0) frexp(xs[i], &want);
    if (geom_scale_exp(xs[i]) != want) badexp++;
  }
  CHECK(bad == 0, "geom_ldexp differs from ldexp in %d of %d cases", bad, nx * 2201);
  CHECK(badexp == 0, "geom_scale_exp differs from frexp's exponent for %d of %d values", badexp, nx);
}

int main(void) {
  rng g;
  rng_seed(&g, 314159);
  inline_scaling(&g);
  powers_of_two(&g);
  decimal_scales(&g);
  room(&g);
  spike();
  return check_done("test_scale");
}
