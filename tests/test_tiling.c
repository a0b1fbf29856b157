/* test_tiling.c -- the exact solver against brute force and the naive
 * one-DP-per-start reference, on thousands of random pairs, with areas,
 * spans and areas with their shadows weighted (weights_new_shadow); path
 * invariants; the weights against an independent 3D computation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/gen.h"
#include "algo/kernel.h"
#include "algo/naive.h"
#include "util/rng.h"
#include "algo/tiling.h"
#include "util/xmem.h"

/* Independent 3D geometry: the triangle's area by the cross product; its
 * shadow, the signed area of its projection (a, b, c in this order). */
static double area3(vec2 a, double za, vec2 b, double zb, vec2 c, double zc) {
  double ux = b.x - a.x, uy = b.y - a.y, uz = zb - za;
  double vx = c.x - a.x, vy = c.y - a.y, vz = zc - za;
  double x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
  return 0.5 * sqrt(x * x + y * y + z * z);
}

static double shadow2(vec2 a, vec2 b, vec2 c) {
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

/* A weight of the shadows: 0 for a third of the calls, else k / 16 in
 * [-15/16, 15/16]. */
static double some_shadow(rng *g) { return rng_int(g, 0, 2) ? rng_int(g, -15, 15) / 16.0 : 0; }

static void check_weights(rng *g) {
  for (int trial = 0; trial < 50; trial++) {
    int m = rng_int(g, 3, 30), n = rng_int(g, 3, 30);
    vec2 *R = xmallocarray((size_t)m, sizeof *R), *C = xmallocarray((size_t)n, sizeof *C);
    gen_star(g, R, m, 0, 0, 10, 0.3);
    gen_star(g, C, n, 1, -1, 7, 0.3);
    double zr = 0.5, zc = 2.75;
    for (int way = 0; way < 3; way++) {   /* area, span, area with shadows */
      cost_kind kind = way == 1 ? COST_SPAN : COST_AREA;
      double sw = way == 2 ? rng_int(g, -15, 15) / 16.0 : 0;
      weights *w = weights_new_shadow(R, m, zr, C, n, zc, kind, sw, 0);
      weights *wt = weights_new_shadow(R, m, zr, C, n, zc, kind, sw, 1);
      double q = weights_quantum(w);
      int bad = 0, badt = 0;
      for (int i = -m; i < 2 * m; i++)
        for (int j = -n; j < 2 * n; j++) {
          int ii = ((i % m) + m) % m, jj = ((j % n) + n) % n;
          vec2 r0 = R[ii], r1 = R[(ii + 1) % m], c0 = C[jj], c1 = C[(jj + 1) % n];
          double ev, eh;
          if (kind == COST_AREA) {
            ev = area3(r0, zr, r1, zr, c0, zc) + sw * shadow2(r0, r1, c0);
            eh = area3(r0, zr, c0, zc, c1, zc) + sw * shadow2(c0, c1, r0);
          } else {
            ev = sqrt((r1.x - c0.x) * (r1.x - c0.x) + (r1.y - c0.y) * (r1.y - c0.y) + 2.25 * 2.25);
            eh = sqrt((r0.x - c1.x) * (r0.x - c1.x) + (r0.y - c1.y) * (r0.y - c1.y) + 2.25 * 2.25);
          }
          double v = weights_v(w, i, j), h = weights_h(w, i, j);
          if (v != floor(v) || h != floor(h)) bad++;
          if (fabs(v * q - ev) > 1e-12 * ev + q || fabs(h * q - eh) > 1e-12 * eh + q) bad++;
          if (weights_v(wt, i, j) != v || weights_h(wt, i, j) != h) badt++;
        }
      CHECK(bad == 0, "%s weights (shadow %g): %d disagree with the 3D formula (m=%d n=%d)",
            cost_name(kind), sw, bad, m, n);
      /* The tables, entry by entry, against the weights computed on the fly. */
      for (int k = 1; k <= 2 * m + n; k++)
        for (int c = 0; c <= n; c++) {
          if (k - c < 0 || k - c > 2 * m) continue;
          for (int vert = 0; vert < 2; vert++) {
            if ((vert && k - c < 1) || (!vert && c < 1)) continue;
            double x = weights_in(wt, k, c, vert);
            double y = vert ? weights_v(w, k - c - 1, c) : weights_h(w, k - c, c - 1);
            if (x != y) badt++;
          }
        }
      CHECK(badt == 0, "table and on-the-fly weights differ in %d places", badt);
      CHECK(q > 0 && q < 1e-6, "quantum %g", q);
      weights_free(w);
      weights_free(wt);
    }
    free(R);
    free(C);
  }
}

/* The invariants of an acceptable path (section 3). */
static void check_path(const tiling *t, const weights *w, const char *what) {
  int m = t->m, n = t->n, vert = 0, horiz = 0, ok = 1;
  ok &= t->col[0] == 0 && t->col[m + n] == n;
  for (int i = 1; i <= m + n; i++) {
    int d = t->col[i] - t->col[i - 1];
    if (d == 0) vert++;
    else if (d == 1) horiz++;
    else ok = 0;
  }
  CHECK(ok && vert == m && horiz == n, "%s: path has %d vertical and %d horizontal steps (m=%d n=%d)",
        what, vert, horiz, m, n);
  CHECK(t->start >= 0 && t->start < m, "%s: start row %d", what, t->start);
  /* Its cost, summed along it, is the reported optimum. */
  double sum = 0;
  int r = t->start, c = 0;
  for (int i = 1; i <= m + n; i++) {
    if (t->col[i] == t->col[i - 1]) sum += weights_v(w, r++, c);
    else sum += weights_h(w, r, c++);
  }
  CHECK(sum == t->quanta, "%s: path sums to %.17g, reported %.17g", what, sum, t->quanta);
  CHECK(r == t->start + m && c == n, "%s: path does not close", what);
  /* Every contour segment is used by exactly one tile. */
  int (*tile)[3] = xmallocarray((size_t)(m + n), sizeof *tile);
  unsigned char *on = xmalloc((size_t)(m + n));
  tiling_tiles(t, tile, on);
  int *usedr = xcalloc((size_t)m, sizeof *usedr), *usedc = xcalloc((size_t)n, sizeof *usedc);
  int rows = t->transposed;   /* `on` value of a tile whose edge is on the rows */
  for (int i = 0; i < m + n; i++) {
    if (on[i] == rows) usedr[tile[i][0]]++;
    else usedc[tile[i][0]]++;
  }
  int once = 1;
  for (int i = 0; i < m; i++) once &= usedr[i] == 1;
  for (int i = 0; i < n; i++) once &= usedc[i] == 1;
  CHECK(once, "%s: some contour segment is not used exactly once", what);
  free(tile), free(on), free(usedr), free(usedc);
}

typedef enum { STAR, GRID, REGULAR, CLOCKWISE, TRIANGLE, SHIFTED } shape;
static const char *shape_name[] = {"star", "grid", "regular", "clockwise", "m=3", "shifted"};

/* A random pair of contours of the given shape; returns their sizes. */
static void make_pair(rng *g, shape sh, int maxn, vec2 *P, int *np, vec2 *Q, int *nq) {
  *np = rng_int(g, 3, maxn);
  *nq = rng_int(g, 3, maxn);
  switch (sh) {
  case STAR:
  case CLOCKWISE:
    gen_star(g, P, *np, 0, 0, 10, 0.4);
    gen_star(g, Q, *nq, rng_uniform(g) * 4 - 2, rng_uniform(g) * 4 - 2, 4 + 8 * rng_uniform(g), 0.4);
    if (sh == CLOCKWISE) geom_reverse(P, *np), geom_reverse(Q, *nq);
    break;
  case GRID:
    *np = gen_grid(g, P, *np + 3, 3 + rng_int(g, 0, 4));
    *nq = gen_grid(g, Q, *nq + 3, 3 + rng_int(g, 0, 4));
    if (*np < 3 || geom_collinear(P, *np)) *np = 4, P[0] = (vec2){0, 0}, P[1] = (vec2){2, 0}, P[2] = (vec2){2, 2}, P[3] = (vec2){0, 2};
    if (*nq < 3 || geom_collinear(Q, *nq)) *nq = 4, Q[0] = (vec2){1, 1}, Q[1] = (vec2){3, 1}, Q[2] = (vec2){3, 3}, Q[3] = (vec2){1, 3};
    break;
  case REGULAR:   /* same polygon twice, or multiples: exact ties */
    *nq = rng_int(g, 0, 1) ? *np : *np * rng_int(g, 1, 2);
    gen_regular(P, *np, 0, 0, 5, 0);
    gen_regular(Q, *nq, 0, 0, 5, rng_int(g, 0, 1) ? 0 : 0.5);
    break;
  case TRIANGLE:
    *np = 3;
    gen_star(g, P, 3, 0, 0, 10, 0.2);
    gen_star(g, Q, *nq, 0, 0, 6, 0.4);
    if (rng_int(g, 0, 1)) {   /* the triangle second */
      vec2 t[3] = {P[0], P[1], P[2]};
      memcpy(P, Q, sizeof *P * (size_t)*nq);
      memcpy(Q, t, sizeof t);
      *np = *nq, *nq = 3;
    }
    break;
  case SHIFTED:   /* the same contour, translated: long shared path pieces */
    gen_star(g, P, *np, 0, 0, 10, 0.5);
    *nq = *np;
    for (int i = 0; i < *np; i++) Q[i] = (vec2){P[i].x + 0.3, P[i].y - 0.2};
    break;
  }
}

/* Solve (P, Q) every way and compare with the references. */
static void compare(rng *g, shape sh, int maxn, int brute, int count) {
  vec2 *P = xmallocarray((size_t)maxn * 2 + 8, sizeof *P), *Q = xmallocarray((size_t)maxn * 2 + 8, sizeof *Q);
  int mism = 0;
  for (int trial = 0; trial < count; trial++) {
    int np, nq;
    make_pair(g, sh, maxn, P, &np, Q, &nq);
    cost_kind kind = rng_int(g, 0, 3) ? COST_AREA : COST_SPAN;
    double sw = kind == COST_AREA ? some_shadow(g) : 0;
    double zp = 0, zq = 1 + rng_uniform(g);
    /* The reference in the pair's own orientation (P = rows), which is the
     * transpose of the solver's whenever np > nq. */
    weights *wr = weights_new_shadow(P, np, zp, Q, nq, zq, kind, sw, 0);
    int rs;
    double ref = brute ? naive_brute(wr, &rs) : naive_dp(wr, &rs);
    tiling t, tt, tg;
    tiling_solve_shadow(P, np, zp, Q, nq, zq, kind, sw, 0, &t);
    tiling_solve_shadow(P, np, zp, Q, nq, zq, kind, sw, 1, &tt);
    /* The portable kernel against the SIMD one, when there is one. */
    int simd = kernel_simd(-1);
    kernel_simd(!simd);
    tiling_solve_shadow(P, np, zp, Q, nq, zq, kind, sw, trial & 1, &tg);
    kernel_simd(simd);
    char what[120];
    snprintf(what, sizeof what, "%s %s (shadow %g) m=%d n=%d trial %d", shape_name[sh], cost_name(kind), sw, np, nq,
             trial);
    if (t.quanta != ref) mism++;
    CHECK(t.quanta == ref, "%s: solver %.17g, %s %.17g", what, t.quanta, brute ? "brute force" : "naive", ref);
    CHECK(t.quanta == tt.quanta && t.start == tt.start &&
              memcmp(t.col, tt.col, sizeof *t.col * (size_t)(t.m + t.n + 1)) == 0,
          "%s: table and on-the-fly kernels differ", what);
    tiling *same = trial & 1 ? &tt : &t;
    CHECK(tg.quanta == same->quanta && tg.start == same->start &&
              memcmp(tg.col, same->col, sizeof *t.col * (size_t)(t.m + t.n + 1)) == 0,
          "%s: portable and SIMD kernels differ", what);
    CHECK(t.transposed == (nq < np) && t.m == (np < nq ? np : nq), "%s: orientation", what);
    weights *ws = t.transposed ? weights_new_shadow(Q, nq, zq, P, np, zp, kind, sw, 0) : wr;
    check_path(&t, ws, what);
    CHECK(t.cost == t.quanta * weights_quantum(ws), "%s: cost is not quanta * quantum", what);
    if (ws != wr) weights_free(ws);
    weights_free(wr);
    tiling_free(&t);
    tiling_free(&tt);
    tiling_free(&tg);
    if (mism > 5) break;   /* enough said */
  }
  free(P);
  free(Q);
}

int main(void) {
  rng g;
  printf("test_tiling: SIMD kernel %s\n", kernel_simd(-1) ? "available" : "not available");
  rng_seed(&g, 20261121);
  check_weights(&g);
  for (int sh = STAR; sh <= SHIFTED; sh++) {
    compare(&g, (shape)sh, 7, 1, 400);     /* brute force, m, n <= 7 */
    compare(&g, (shape)sh, 40, 0, 300);    /* naive DP */
    compare(&g, (shape)sh, 200, 0, 6);     /* naive DP, up to 200 points */
  }
  return check_done("test_tiling");
}
