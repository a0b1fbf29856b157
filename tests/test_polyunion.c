/* test_polyunion.c -- the exact union of overlapping polygons
 * (geom/polyunion.h) and its big integers (geom/bigz.h), against references
 * of their own:
 *   - bigz: products against unsigned __int128, quotients against IEEE
 *     division (correctly rounded) where both operands are doubles, and
 *     quotients into the subnormals against ldexp;
 *   - axis-parallel rectangles (1,500 sets, on an integer grid and on a grid of
 *     0.1, with shared edges, corners and collinear overlaps): the union's
 *     area against coordinate compression (an exact sum of grid cells), and
 *     every cell centre inside the loops (even-odd) exactly when it is inside
 *     a rectangle;
 *   - convex polygons (rotated regular polygons, three at a time): the area
 *     against inclusion-exclusion with the pairwise and triple intersections
 *     clipped independently (Sutherland-Hodgman), to 1e-12;
 *   - random star polygons: membership on a 120 x 120 grid of points, and the
 *     area against that rasterisation within its resolution;
 *   - holes and islands: a ring of four rectangles has an outer loop and a
 *     hole; an island inside the hole meets nothing and stays apart; a group
 *     of three overlapping holes-to-be;
 *   - a pinch (squares touching at a corner) refused at that point; copies
 *     of one polygon give that polygon;
 *   - any order, start point and direction: the same loops. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/bigz.h"
#include "tests/check.h"
#include "geom/exact.h"
#include "input/gen.h"
#include "geom/polyunion.h"
#include "tests/reference.h"
#include "util/rng.h"
#include "util/xmem.h"

/* ---------------------------------------------------------------- bigz */

__extension__ typedef unsigned __int128 u128;   /* the compiler's, as a reference */

static void test_bigz(void) {
  rng g;
  rng_seed(&g, 11);
  int bad = 0;
  for (int i = 0; i < 20000; i++) {
    uint64_t a = rng_next(&g), b = rng_next(&g);
    long long sa = (long long)(a >> 2) * (i % 2 ? -1 : 1), sb = (long long)(b >> 3) * (i % 3 ? 1 : -1);
    bigz x, y, z, w;
    bigz_set_int(&x, sa), bigz_set_int(&y, sb);
    bigz_mul(&z, &x, &y);
    u128 p = (u128)(a >> 2) * (b >> 3);
    int neg = (sa < 0) != (sb < 0) && p != 0;
    uint32_t want[4] = {(uint32_t)p, (uint32_t)(p >> 32), (uint32_t)(p >> 64), (uint32_t)(p >> 96)};
    int n = 4;
    while (n > 0 && want[n - 1] == 0) n--;
    if (z.n != n || z.neg != neg || memcmp(z.l, want, (size_t)n * 4) != 0) bad++;
    /* a + b - b == a, and the order */
    bigz_add(&w, &x, &y), bigz_sub(&w, &w, &y);
    if (bigz_cmp(&w, &x) != 0 || bigz_cmp(&x, &y) != (sa > sb) - (sa < sb)) bad++;
    /* quotients of doubles: IEEE division is correctly rounded */
    double u = (double)(rng_next(&g) >> 11) * (i % 5 ? 1 : -1), v = (double)((rng_next(&g) >> 11) | 1);
    int e = i % 40 - 20;
    bigz_from_double(&x, u, 0), bigz_from_double(&y, v, 0);
    if (bigz_ratio(&x, &y, e) != ldexp(u / v, e)) bad++;
  }
  CHECK(bad == 0, "bigz: %d of 20000 products, sums or quotients wrong", bad);
  /* into the subnormals: 1 / 2^k, and 3 / 2^k (ties to even) */
  bigz one, three, den;
  bigz_set_int(&one, 1), bigz_set_int(&three, 3);
  bad = 0;
  for (int k = 1; k < 62; k++) {
    bigz_set_int(&den, 1LL << k);
    for (int e = -1100; e < -1000; e++) {
      if (bigz_ratio(&one, &den, e) != ldexp(1, e - k)) bad++;
      if (bigz_ratio(&three, &den, e) != ldexp(3, e - k)) bad++;
    }
  }
  CHECK(bad == 0, "bigz: %d quotients into the subnormals wrong", bad);
  /* from doubles at their least bit */
  double xs[] = {1, -0.1, 123.45, 4e-323, -1e300, 0x1p-1074};
  for (int i = 0; i < 6; i++) {
    bigz q, d1;
    int e = bigz_lsb_exp(xs[i]);
    bigz_from_double(&q, xs[i], e);
    bigz_set_int(&d1, 1);
    CHECK(bigz_ratio(&q, &d1, e) == xs[i] && (q.l[0] & 1), "bigz: %g at its least bit", xs[i]);
  }
}

/* ---------------------------------------------------------------- helpers */

static double area2(const vec2 *p, int n) {
  double a = 0;
  for (int i = 0; i < n; i++) {
    vec2 u = p[i], v = p[(i + 1) % n];
    a += (u.x - p[0].x) * (v.y - p[0].y) - (v.x - p[0].x) * (u.y - p[0].y);
  }
  return a;
}

/* Twice the union's area from its loops (holes clockwise, negative). */
static double loops_area2(const polyunion_result *u, int g) {
  double a = 0;
  for (int k = u->gfirst[g]; k < u->gfirst[g + 1]; k++) a += area2(u->pt + u->first[k], u->first[k + 1] - u->first[k]);
  return a;
}

/* q strictly inside polygon p (even-odd, exact; q on no edge assumed). */
static int inside(const vec2 *p, int n, vec2 q) {
  int in = 0;
  for (int i = 0; i < n; i++) {
    vec2 a = p[i], b = p[(i + 1) % n];
    if ((a.y > q.y) != (b.y > q.y)) {
      int o = exact_orient(a, b, q);
      if ((b.y > a.y) == (o > 0)) in = !in;
    }
  }
  return in;
}

static int in_loops(const polyunion_result *u, int g, vec2 q) {
  int in = 0;
  for (int k = u->gfirst[g]; k < u->gfirst[g + 1]; k++) in ^= inside(u->pt + u->first[k], u->first[k + 1] - u->first[k], q);
  return in;
}

/* ---------------------------------------------------------------- rectangles */

static void rect_poly(const double r[4], vec2 *p) {
  p[0] = (vec2){r[0], r[1]}, p[1] = (vec2){r[2], r[1]}, p[2] = (vec2){r[2], r[3]}, p[3] = (vec2){r[0], r[3]};
}

static void test_rectangles(void) {
  rng g;
  rng_seed(&g, 7);
  int tried = 0, bad_area = 0, bad_in = 0, pinched = 0, holes = 0;
  for (int t = 0; t < 1500; t++) {
    int n = 2 + t % 5;
    double unit = t % 2 ? 1 : 0.1, r[8][4];
    vec2 pts[8][4];
    crossing_poly cp[8];
    for (int i = 0; i < n; i++) {
      int x0 = rng_int(&g, 0, 8), y0 = rng_int(&g, 0, 8);
      r[i][0] = x0 * unit, r[i][1] = y0 * unit;
      r[i][2] = (x0 + rng_int(&g, 1, 6)) * unit, r[i][3] = (y0 + rng_int(&g, 1, 6)) * unit;
      rect_poly(r[i], pts[i]);
      if (rng_int(&g, 0, 1)) {   /* clockwise, another start */
        vec2 q[4];
        for (int k = 0; k < 4; k++) q[k] = pts[i][(5 - k + t) % 4];
        memcpy(pts[i], q, sizeof q);
      }
      cp[i] = (crossing_poly){pts[i], 4};
    }
    polyunion_result u;
    int rc = polyunion(cp, n, &u);
    if (rc != 0) {
      pinched += u.status == POLYUNION_PINCH;
      CHECK(u.status == POLYUNION_PINCH, "rectangles %d: refused %d", t, u.status);
      polyunion_free(&u);
      continue;
    }
    /* One group of all, or rectangles apart: compare per group. */
    for (int gi = 0; gi < u.ngroups; gi++) {
      double rr[8][4];
      int m = 0;
      for (int k = u.gmember[gi]; k < u.gmember[gi + 1]; k++) memcpy(rr[m++], r[u.members[k]], sizeof rr[0]);
      double want = ref_rects_area((const double (*)[4])rr, m), got = loops_area2(&u, gi) / 2;
      if (fabs(got - want) > 1e-12 * want) bad_area++;
      for (int k = u.gfirst[gi]; k < u.gfirst[gi + 1]; k++) holes += u.hole[k];
      /* cell centres on a grid of unit/2 offset by unit/4: never on an edge */
      for (int i = 0; i < 56; i++)
        for (int j = 0; j < 56; j++) {
          vec2 q = {(i * 0.25 + 0.125) * unit * 1.0, (j * 0.25 + 0.125) * unit};
          int any = 0;
          for (int k = 0; k < m; k++) any |= rr[k][0] < q.x && q.x < rr[k][2] && rr[k][1] < q.y && q.y < rr[k][3];
          if (any != in_loops(&u, gi, q)) bad_in++;
        }
      tried++;
    }
    polyunion_free(&u);
  }
  CHECK(bad_area == 0 && bad_in == 0 && tried > 600 && holes >= 5,
        "rectangles: %d groups, %d areas wrong, %d points misplaced, %d pinched, %d holes", tried, bad_area, bad_in,
        pinched, holes);
  CHECK(pinched > 5, "rectangles: only %d pinches: corners are not tested", pinched);
}

/* ---------------------------------------------------------------- convex */

/* Clip polygon p by the half-plane left of ab (Sutherland-Hodgman). */
static int clip(const vec2 *p, int n, vec2 a, vec2 b, vec2 *out) {
  int m = 0;
  for (int i = 0; i < n; i++) {
    vec2 c = p[i], d = p[(i + 1) % n];
    double sc = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    double sd = (b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x);
    if (sc >= 0) out[m++] = c;
    if ((sc >= 0) != (sd >= 0)) {
      double t = sc / (sc - sd);
      out[m++] = (vec2){c.x + t * (d.x - c.x), c.y + t * (d.y - c.y)};
    }
  }
  return m;
}

static double inter_area(const vec2 *const *ps, const int *ns, int k) {
  vec2 a[256], b[256];
  int n = ns[0];
  memcpy(a, ps[0], (size_t)n * sizeof *a);
  for (int j = 1; j < k; j++)
    for (int e = 0; e < ns[j] && n > 0; e++) {
      n = clip(a, n, ps[j][e], ps[j][(e + 1) % ns[j]], b);
      memcpy(a, b, (size_t)n * sizeof *a);
    }
  return n >= 3 ? area2(a, n) / 2 : 0;
}

static void test_convex(void) {
  rng g;
  rng_seed(&g, 5);
  int bad = 0, tried = 0;
  double worst = 0;
  for (int t = 0; t < 400; t++) {
    static vec2 p[3][64];
    int n[3];
    crossing_poly cp[3];
    for (int i = 0; i < 3; i++) {
      n[i] = rng_int(&g, 3, 60);
      gen_regular(p[i], n[i], 10 * rng_uniform(&g), 10 * rng_uniform(&g), 4 + 6 * rng_uniform(&g),
                  6.3 * rng_uniform(&g));
      cp[i] = (crossing_poly){p[i], n[i]};
    }
    polyunion_result u;
    if (polyunion(cp, 3, &u) != 0) {
      CHECK(0, "convex %d: refused %d at %g %g", t, u.status, u.at.x, u.at.y);
      polyunion_free(&u);
      continue;
    }
    if (u.ngroups == 1 && u.gmember[1] == 3) {
      const vec2 *ps[3] = {p[0], p[1], p[2]};
      double want = 0;
      for (int i = 0; i < 3; i++) want += area2(p[i], n[i]) / 2;
      for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++) {
          const vec2 *q[2] = {ps[i], ps[j]};
          int m[2] = {n[i], n[j]};
          want -= inter_area(q, m, 2);
        }
      want += inter_area(ps, n, 3);
      double got = loops_area2(&u, 0) / 2, d = fabs(got - want) / want;
      if (d > worst) worst = d;
      if (d > 1e-12) bad++;
      tried++;
    }
    polyunion_free(&u);
  }
  CHECK(bad == 0 && tried > 100, "convex: %d of %d unions' areas off inclusion-exclusion (worst %.3g)", bad, tried,
        worst);
}

/* ---------------------------------------------------------------- stars */

static void test_stars(void) {
  rng g;
  rng_seed(&g, 3);
  int bad_in = 0, bad_area = 0, tried = 0;
  for (int t = 0; t < 40; t++) {
    static vec2 p[5][200];
    int n[5], np = 2 + t % 4;
    crossing_poly cp[5];
    for (int i = 0; i < np; i++) {
      n[i] = rng_int(&g, 10, 200);
      gen_star(&g, p[i], n[i], 20 * rng_uniform(&g), 20 * rng_uniform(&g), 5 + 8 * rng_uniform(&g), 0.5);
      cp[i] = (crossing_poly){p[i], n[i]};
    }
    polyunion_result u;
    if (polyunion(cp, np, &u) != 0) {
      CHECK(0, "stars %d: refused %d at %g %g", t, u.status, u.at.x, u.at.y);
      polyunion_free(&u);
      continue;
    }
    for (int gi = 0; gi < u.ngroups; gi++) {
      int cnt = 0, N = 120;
      double x0 = -15, y0 = -15, h = 50.0 / N;
      for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
          vec2 q = {x0 + (i + 0.5) * h + 1e-7, y0 + (j + 0.5) * h + 3e-7};
          int any = 0;
          for (int k = u.gmember[gi]; k < u.gmember[gi + 1]; k++) any |= inside(p[u.members[k]], n[u.members[k]], q);
          cnt += any;
          if (any != in_loops(&u, gi, q)) bad_in++;
        }
      /* the rasterisation's error: at most the cells the boundary crosses */
      double per = 0;
      for (int k = u.gfirst[gi]; k < u.gfirst[gi + 1]; k++)
        for (int i = u.first[k]; i < u.first[k + 1]; i++) {
          vec2 a = u.pt[i], b = u.pt[i + 1 < u.first[k + 1] ? i + 1 : u.first[k]];
          per += hypot(b.x - a.x, b.y - a.y);
        }
      double got = loops_area2(&u, gi) / 2, want = cnt * h * h;
      if (fabs(got - want) > 2 * per * h) bad_area++;
      tried++;
    }
    polyunion_free(&u);
  }
  CHECK(bad_in == 0 && bad_area == 0 && tried > 30, "stars: %d groups, %d points misplaced, %d areas off", tried,
        bad_in, bad_area);
}

/* ---------------------------------------------------------------- cases */

static int run(const vec2 *const *ps, const int *ns, int np, polyunion_result *u) {
  crossing_poly cp[8];
  for (int i = 0; i < np; i++) cp[i] = (crossing_poly){ps[i], ns[i]};
  return polyunion(cp, np, u);
}

static void test_cases(void) {
  /* a ring of four rectangles, an island in its hole */
  static const vec2 r1[] = {{0, 0}, {10, 0}, {10, 3}, {0, 3}}, r2[] = {{7, 0}, {10, 0}, {10, 10}, {7, 10}},
                    r3[] = {{0, 7}, {10, 7}, {10, 10}, {0, 10}}, r4[] = {{0, 0}, {3, 0}, {3, 10}, {0, 10}},
                    isl[] = {{4, 4}, {6, 4}, {6, 6}, {4, 6}};
  const vec2 *ring[] = {r1, r2, r3, r4, isl};
  int n4[] = {4, 4, 4, 4, 4};
  polyunion_result u;
  int rc = run(ring, n4, 5, &u);
  int holes = 0;
  if (rc == 0)
    for (int k = 0; k < u.nloops; k++) holes += u.hole[k];
  CHECK(rc == 0 && u.ngroups == 1 && u.group[4] == -1 && u.nloops == 2 && holes == 1 &&
            loops_area2(&u, 0) == 2 * (100 - 16),
        "ring: %d, %d groups, island in group %d, %d loops, %d holes, area %g", rc, u.ngroups, u.group[4], u.nloops,
        holes, loops_area2(&u, 0) / 2);
  polyunion_free(&u);
  /* two squares touching at a corner: a pinch */
  static const vec2 s1[] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, s2[] = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  const vec2 *pin[] = {s1, s2};
  rc = run(pin, n4, 2, &u);
  CHECK(rc == -1 && u.status == POLYUNION_PINCH && u.at.x == 1 && u.at.y == 1, "corner: %d %d at %g %g", rc, u.status,
        u.at.x, u.at.y);
  polyunion_free(&u);
  /* squares sharing an edge: one rectangle, the shared edge gone, its ends kept */
  static const vec2 s3[] = {{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  const vec2 *side[] = {s1, s3};
  rc = run(side, n4, 2, &u);
  CHECK(rc == 0 && u.nloops == 1 && u.first[1] == 6 && loops_area2(&u, 0) == 4 && u.newpts[0] == 0,
        "side by side: %d, %d loops of %d points, area %g", rc, u.nloops, u.nloops ? u.first[1] : 0,
        loops_area2(&u, 0) / 2);
  polyunion_free(&u);
  /* three copies: other starts, directions, collinear points: the polygon */
  static const vec2 c1[] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, c2[] = {{4, 4}, {4, 2}, {4, 0}, {0, 0}, {0, 4}},
                    c3[] = {{0, 4}, {0, 0}, {2, 0}, {4, 0}, {4, 4}, {2, 4}};
  const vec2 *cp3[] = {c1, c2, c3};
  int nc3[] = {4, 5, 6};
  rc = run(cp3, nc3, 3, &u);
  CHECK(rc == 0 && u.nloops == 1 && loops_area2(&u, 0) == 32 && u.first[1] == 7, "copies: %d, %d loops, %d points", rc,
        u.nloops, u.nloops ? u.first[1] : 0);
  polyunion_free(&u);
  /* a square inside another, touching it at one vertex: the outer one (with that vertex) */
  static const vec2 big[] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, in1[] = {{2, 0}, {3, 1}, {2, 2}, {1, 1}};
  const vec2 *ins[] = {big, in1};
  rc = run(ins, n4, 2, &u);
  CHECK(rc == 0 && u.nloops == 1 && loops_area2(&u, 0) == 32, "inside, touching: %d, %d loops, area %g", rc, u.nloops,
        loops_area2(&u, 0) / 2);
  polyunion_free(&u);
  /* crossings of irrational-free but inexact points: a thin X of two bars at
   * angles: the new vertices are within half an ulp of the exact ones
   * (recomputed here in long double where it has the bits) */
  static const vec2 b1[] = {{0, 0}, {10, 1}, {10, 1.3}, {0, 0.3}}, b2[] = {{0, 1}, {10, 0}, {10, 0.3}, {0, 1.3}};
  const vec2 *x2[] = {b1, b2};
  rc = run(x2, n4, 2, &u);
  CHECK(rc == 0 && u.nloops == 1 && u.newpts[0] == 4, "X: %d, %d loops, %d new points", rc, u.nloops, u.newpts[0]);
  polyunion_free(&u);
}

/* Any order, start point and direction: the same loops (each from its
 * least point, the loops by it). */
static int canon(const polyunion_result *u, vec2 *out) {
  int m = 0, nl = u->nloops, order[64];
  for (int k = 0; k < nl; k++) order[k] = k;
  for (int i = 1; i < nl; i++)
    for (int j = i; j > 0; j--) {
      const vec2 *a = u->pt + u->first[order[j]], *b = u->pt + u->first[order[j - 1]];
      int la = 0, lb = 0;
      for (int q = 1; q < u->first[order[j] + 1] - u->first[order[j]]; q++) if (exact_lex(a[q], a[la]) < 0) la = q;
      for (int q = 1; q < u->first[order[j - 1] + 1] - u->first[order[j - 1]]; q++) if (exact_lex(b[q], b[lb]) < 0) lb = q;
      if (exact_lex(a[la], b[lb]) >= 0) break;
      int t = order[j];
      order[j] = order[j - 1], order[j - 1] = t;
    }
  for (int k = 0; k < nl; k++) {
    const vec2 *a = u->pt + u->first[order[k]];
    int n = u->first[order[k] + 1] - u->first[order[k]], l = 0;
    for (int q = 1; q < n; q++) if (exact_lex(a[q], a[l]) < 0) l = q;
    for (int q = 0; q < n; q++) out[m++] = a[(l + q) % n];
  }
  return m;
}

static void test_order(void) {
  rng g;
  rng_seed(&g, 9);
  static vec2 p[4][120], q[4][120], c0[2000], c1[2000];
  int n[4], bad = 0;
  for (int t = 0; t < 30; t++) {
    for (int i = 0; i < 4; i++) {
      n[i] = rng_int(&g, 8, 120);
      gen_star(&g, p[i], n[i], 6 * rng_uniform(&g), 6 * rng_uniform(&g), 5, 0.4);
    }
    const vec2 *ps[4] = {p[0], p[1], p[2], p[3]};
    polyunion_result u0, u1;
    if (run(ps, n, 4, &u0) != 0) {
      polyunion_free(&u0);
      continue;
    }
    int perm[4] = {2, 0, 3, 1}, nn[4];
    const vec2 *qs[4];
    for (int i = 0; i < 4; i++) {
      int s = perm[i], st = rng_int(&g, 0, n[s] - 1), rev = rng_int(&g, 0, 1);
      for (int j = 0; j < n[s]; j++) q[i][j] = p[s][rev ? (st - j + 2 * n[s]) % n[s] : (st + j) % n[s]];
      qs[i] = q[i], nn[i] = n[s];
    }
    if (run(qs, nn, 4, &u1) != 0 || u0.nloops != u1.nloops || u0.nloops > 64) bad++;
    else {
      int m0 = canon(&u0, c0), m1 = canon(&u1, c1);
      if (m0 != m1 || memcmp(c0, c1, (size_t)m0 * sizeof *c0) != 0) bad++;
    }
    polyunion_free(&u0), polyunion_free(&u1);
  }
  CHECK(bad == 0, "order: %d of 30 unions differ when re-encoded", bad);
}

int main(void) {
  test_bigz();
  test_cases();
  test_rectangles();
  test_convex();
  test_stars();
  test_order();
  return check_done("test_polyunion");
}
