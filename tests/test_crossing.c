/* test_crossing.c -- segment contacts against a rational parametric solution,
 * the sweep against brute force on thousands of random (very degenerate)
 * polygon sets, at every scale, and large simple and nearly simple polygons. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "geom/crossing.h"
#include "geom/exact.h"
#include "input/gen.h"
#include "util/rng.h"
#include "util/xmem.h"

/* --- the reference: integers, parameters as exact fractions --------------- */

typedef struct { long long x, y; } ip;
static ip isub(ip a, ip b) { return (ip){a.x - b.x, a.y - b.y}; }
static long long icross(ip a, ip b) { return a.x * b.y - a.y * b.x; }
static long long idot(ip a, ip b) { return a.x * b.x + a.y * b.y; }

/* The contact of closed segments ab and cd: solve a + t(b-a) = c + u(d-c)
 * (Cramer's rule, t = tn/den, u = un/den); collinear ones by the parameters
 * of c and d along ab. */
static crossing_kind ref_segments(ip a, ip b, ip c, ip d) {
  ip e = isub(b, a), f = isub(d, c), g = isub(c, a);
  long long den = icross(e, f);
  if (den != 0) {
    long long tn = icross(g, f), un = icross(g, e);
    if (den < 0) den = -den, tn = -tn, un = -un;
    if (tn < 0 || tn > den || un < 0 || un > den) return CROSSING_NONE;
    if (tn > 0 && tn < den && un > 0 && un < den) return CROSSING_CROSS;
    return CROSSING_TOUCH;
  }
  if (icross(g, e) != 0) return CROSSING_NONE;   /* parallel lines */
  long long ee = idot(e, e), tc = idot(g, e), td = idot(isub(d, a), e);
  long long lo = tc < td ? tc : td, hi = tc < td ? td : tc;
  long long L = lo > 0 ? lo : 0, H = hi < ee ? hi : ee;
  if (L > H) return CROSSING_NONE;
  return L == H ? CROSSING_TOUCH : CROSSING_OVERLAP;
}

static int ion(ip p, ip c, ip d) {   /* p on the closed segment cd */
  if (icross(isub(d, c), isub(p, c)) != 0) return 0;
  return (p.x - c.x) * (p.x - d.x) <= 0 && (p.y - c.y) * (p.y - d.y) <= 0;
}

/* Polygons with integer points. */
typedef struct {
  int n;
  ip *p;
} ipoly;

/* Does segment s of polygon k offend segment t of polygon l (reference)? */
static crossing_kind ref_pair(const ipoly *P, int k, int s, int l, int t) {
  int n = P[k].n;
  ip a = P[k].p[s], b = P[k].p[(s + 1) % n], c = P[l].p[t], d = P[l].p[(t + 1) % P[l].n];
  crossing_kind kind = ref_segments(a, b, c, d);
  int adj = k == l && ((t == s + 1) || (s == t + 1) || (s == 0 && t == n - 1) || (t == 0 && s == n - 1));
  if (adj) return kind == CROSSING_OVERLAP ? CROSSING_OVERLAP : CROSSING_NONE;
  return kind;
}

/* The first offending pair in (k, s, l, t) order, or 0. */
static int ref_find(const ipoly *P, int np, int *out) {
  for (int k = 0; k < np; k++)
    for (int s = 0; s < P[k].n; s++)
      for (int l = k; l < np; l++)
        for (int t = l == k ? s + 1 : 0; t < P[l].n; t++)
          if (ref_pair(P, k, s, l, t)) {
            out[0] = k, out[1] = s, out[2] = l, out[3] = t;
            return 1;
          }
  return 0;
}

/* --- two segments --------------------------------------------------------- */

static vec2 dv(ip p) { return (vec2){(double)p.x, (double)p.y}; }

static void segments(rng *g) {
  int fails = 0, counts[4] = {0, 0, 0, 0};
  for (int trial = 0; trial < 200000; trial++) {
    int G = trial % 2 ? 3 : 8;
    ip q[4];
    for (int i = 0; i < 4; i++) q[i] = (ip){rng_int(g, 0, G), rng_int(g, 0, G)};
    if ((q[0].x == q[1].x && q[0].y == q[1].y) || (q[2].x == q[3].x && q[2].y == q[3].y)) continue;
    crossing_kind want = ref_segments(q[0], q[1], q[2], q[3]);
    vec2 at;
    crossing_kind got = crossing_segments(dv(q[0]), dv(q[1]), dv(q[2]), dv(q[3]), &at);
    crossing_kind sym = crossing_segments(dv(q[3]), dv(q[2]), dv(q[1]), dv(q[0]), NULL);
    counts[want]++;
    int ok = got == want && sym == want;
    /* The common point given for a touch or an overlap is on both. */
    if (ok && (want == CROSSING_TOUCH || want == CROSSING_OVERLAP)) {
      ip a = {(long long)at.x, (long long)at.y};
      ok = at.x == (double)a.x && at.y == (double)a.y && ion(a, q[0], q[1]) && ion(a, q[2], q[3]);
    }
    if (!ok && fails++ < 5)
      CHECK(0, "(%lld %lld)-(%lld %lld) against (%lld %lld)-(%lld %lld): %s / %s, want %s",
            q[0].x, q[0].y, q[1].x, q[1].y, q[2].x, q[2].y, q[3].x, q[3].y, crossing_verb(got),
            crossing_verb(sym), crossing_verb(want));
  }
  CHECK(fails == 0, "%d segment pairs wrong", fails);
  CHECK(counts[0] > 1000 && counts[1] > 1000 && counts[2] > 1000 && counts[3] > 1000,
        "every kind of contact drawn (%d none, %d cross, %d touch, %d overlap)", counts[0],
        counts[1], counts[2], counts[3]);
}

/* --- sets of polygons ----------------------------------------------------- */

/* Random polygons on a G x G grid: consecutive points distinct, n >= 3. */
static int random_polys(rng *g, ipoly *P, int maxp, int G, int maxn) {
  int np = rng_int(g, 1, maxp);
  for (int k = 0; k < np; k++) {
    int n = rng_int(g, 3, maxn);
    P[k].p = xmallocarray((size_t)n, sizeof(ip));
    int m = 0;
    for (int tries = 0; m < n && tries < 100 * n; tries++) {
      ip q = {rng_int(g, 0, G), rng_int(g, 0, G)};
      if (m > 0 && q.x == P[k].p[m - 1].x && q.y == P[k].p[m - 1].y) continue;
      if (m == n - 1 && q.x == P[k].p[0].x && q.y == P[k].p[0].y) continue;
      P[k].p[m++] = q;
    }
    P[k].n = m;
  }
  return np;
}

/* As doubles: x 2^e + shift (every value exact). */
static crossing_poly *as_double(const ipoly *P, int np, int e, double sx, double sy) {
  crossing_poly *C = xmallocarray((size_t)np, sizeof *C);
  for (int k = 0; k < np; k++) {
    vec2 *v = xmallocarray((size_t)P[k].n, sizeof *v);
    for (int i = 0; i < P[k].n; i++) v[i] = (vec2){ldexp((double)P[k].p[i].x, e) + sx, ldexp((double)P[k].p[i].y, e) + sy};
    C[k] = (crossing_poly){v, P[k].n};
  }
  return C;
}

static void free_double(crossing_poly *C, int np) {
  for (int k = 0; k < np; k++) free((void *)C[k].pt);
  free(C);
}

static int same_hit(const crossing_hit *a, const crossing_hit *b) {
  return a->kind == b->kind && a->poly[0] == b->poly[0] && a->seg[0] == b->seg[0] &&
         a->poly[1] == b->poly[1] && a->seg[1] == b->seg[1];
}

static void sets(rng *g) {
  int fails = 0, found = 0, clean = 0, trials = 6000;
  for (int trial = 0; trial < trials; trial++) {
    ipoly P[4];
    int G = trial % 3 == 0 ? 2 : trial % 3 == 1 ? 5 : 40;
    int np = random_polys(g, P, trial % 4 == 0 ? 1 : 4, G, trial % 5 == 0 ? 4 : 12);
    int ref[4], want = ref_find(P, np, ref);
    crossing_poly *C = as_double(P, np, 0, 0, 0);
    crossing_hit hs, hb;
    int s = crossing_find(C, np, &hs), b = crossing_find_brute(C, np, &hb);
    int ok = s == want && b == want;
    if (ok && want) {
      /* The brute force gives the reference's first pair; the sweep some
       * offending pair, of the kind the reference says. */
      ok = hb.poly[0] == ref[0] && hb.seg[0] == ref[1] && hb.poly[1] == ref[2] && hb.seg[1] == ref[3] &&
           hb.kind == ref_pair(P, ref[0], ref[1], ref[2], ref[3]);
      ok = ok && (hs.poly[0] < hs.poly[1] || (hs.poly[0] == hs.poly[1] && hs.seg[0] < hs.seg[1])) &&
           hs.kind == ref_pair(P, hs.poly[0], hs.seg[0], hs.poly[1], hs.seg[1]) && hs.kind != CROSSING_NONE;
    }
    /* Scaled into subnormals or near 1e300 and shifted: the same pair. */
    if (ok) {
      static const int es[] = {-1074, -1060, -300, 40, 900, 960};
      int e = es[trial % 6];
      double sh = e <= 900 ? ldexp(3, e + 30) : 0;
      crossing_poly *D = as_double(P, np, e, sh, -sh);
      crossing_hit hd;
      int d = crossing_find(D, np, &hd);
      ok = d == s && (!d || same_hit(&hd, &hs));
      free_double(D, np);
    }
    if (!ok && fails++ < 5) {
      CHECK(0, "trial %d: sweep %d, brute %d, reference %d (sweep pair %d:%d %d:%d %s, reference %d:%d %d:%d)",
            trial, s, b, want, hs.poly[0], hs.seg[0], hs.poly[1], hs.seg[1], crossing_verb(hs.kind),
            ref[0], ref[1], ref[2], ref[3]);
      for (int k = 0; k < np; k++) {
        fprintf(stderr, "  polygon %d:", k);
        for (int i = 0; i < P[k].n; i++) fprintf(stderr, " (%lld %lld)", P[k].p[i].x, P[k].p[i].y);
        fputc('\n', stderr);
      }
    }
    found += want, clean += !want;
    free_double(C, np);
    for (int k = 0; k < np; k++) free(P[k].p);
  }
  CHECK(fails == 0, "%d of %d polygon sets wrong", fails, trials);
  CHECK(found > 1000 && clean > 500, "both answers drawn (%d offending, %d clean)", found, clean);
}

/* --- the cases of the issue ----------------------------------------------- */

typedef struct {
  const char *name;
  int n;
  double xy[20];
  crossing_kind kind;   /* NONE: simple */
  int seg0, seg1;       /* the pair the brute force names first */
} shape;

static const shape shapes[] = {
    {"square", 4, {0, 0, 1, 0, 1, 1, 0, 1}, CROSSING_NONE, 0, 0},
    {"bowtie", 4, {0, 0, 1, 1, 1, 0, 0, 1}, CROSSING_CROSS, 0, 2},
    {"figure eight", 6, {0, 0, 1, 1, 2, 0, 2, 1, 1, 0, 0, 1}, CROSSING_CROSS, 0, 4},
    {"touching vertex", 6, {0, 0, 2, 0, 1, 1, 2, 2, 0, 2, 1, 1}, CROSSING_TOUCH, 1, 4},
    {"edge through a vertex", 5, {0, 0, 2, 0, 2, 2, 1, 0, 0, 2}, CROSSING_TOUCH, 0, 2},
    {"collinear overlap", 6, {0, 0, 3, 0, 3, 1, -1, 1, -1, 0, 1, 0}, CROSSING_OVERLAP, 0, 4},
    {"spike back over itself", 4, {0, 0, 2, 0, 1, 0, 1, 1}, CROSSING_OVERLAP, 0, 1},
    {"triangle", 3, {0, 0, 1e-300, 0, 0, 1e-300}, CROSSING_NONE, 0, 0},
    {"sliver", 4, {1e8, 1e8, 1e8 + 50, 1e8 + 50, 1e8 + 25, 1e8 + 25 + 1e-8, 1e8, 1e8 + 1e-8}, CROSSING_NONE, 0, 0},
};

static void cases(void) {
  for (size_t i = 0; i < sizeof shapes / sizeof *shapes; i++) {
    const shape *s = &shapes[i];
    vec2 v[10];
    for (int k = 0; k < s->n; k++) v[k] = (vec2){s->xy[2 * k], s->xy[2 * k + 1]};
    crossing_poly P = {v, s->n};
    crossing_hit h, hb;
    int f = crossing_find(&P, 1, &h), b = crossing_find_brute(&P, 1, &hb);
    CHECK(f == (s->kind != CROSSING_NONE) && b == f, "%s: sweep %d, brute %d", s->name, f, b);
    if (b) CHECK(hb.kind == s->kind && hb.seg[0] == s->seg0 && hb.seg[1] == s->seg1,
                 "%s: brute %s %d %d, want %s %d %d", s->name, crossing_verb(hb.kind), hb.seg[0],
                 hb.seg[1], crossing_verb(s->kind), s->seg0, s->seg1);
    if (f) CHECK(h.kind == s->kind, "%s: sweep says %s", s->name, crossing_verb(h.kind));
  }
  /* The {7/3} star: every edge crosses four others. */
  vec2 st[7];
  for (int k = 0; k < 7; k++) st[k] = (vec2){cos(2 * 3.14159265358979323846 * 3 * k / 7), sin(2 * 3.14159265358979323846 * 3 * k / 7)};
  crossing_poly P = {st, 7};
  crossing_hit h;
  CHECK(crossing_find(&P, 1, &h) && h.kind == CROSSING_CROSS, "the {7/3} star crosses itself");
  /* A crossing point: near (0.5, 0.5) for the bowtie. */
  vec2 bt[4] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  P = (crossing_poly){bt, 4};
  CHECK(crossing_find(&P, 1, &h) && fabs(h.at.x - 0.5) < 1e-15 && fabs(h.at.y - 0.5) < 1e-15,
        "the bowtie crosses at (0.5 0.5), not (%g %g)", h.at.x, h.at.y);
  /* Two polygons: nested is fine, touching is not. */
  vec2 outer[4] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, inner[4] = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  vec2 touch[4] = {{4, 1}, {5, 1}, {5, 2}, {4, 2}};
  crossing_poly two[2] = {{outer, 4}, {inner, 4}};
  CHECK(!crossing_find(two, 2, &h), "nested squares do not offend");
  two[1] = (crossing_poly){touch, 4};
  CHECK(crossing_find(two, 2, &h) && h.poly[0] == 0 && h.seg[0] == 1 && h.poly[1] == 1 &&
            h.kind != CROSSING_NONE,
        "squares sharing part of an edge: %d:%d %d:%d %s", h.poly[0], h.seg[0], h.poly[1], h.seg[1],
        crossing_verb(h.kind));
}

/* --- large polygons ------------------------------------------------------- */

static void large(rng *g) {
  /* A random star of 100,000 points is simple; swapping two neighbours
   * somewhere makes a local bowtie. */
  int n = 100000;
  vec2 *p = xmallocarray((size_t)n, sizeof *p);
  gen_star(g, p, n, 1e8, -3e7, 5e6, 0.5);
  crossing_poly P = {p, n};
  crossing_hit h;
  CHECK(!crossing_find(&P, 1, &h), "a %d-point star is simple (found %d:%d %s)", n, h.seg[0],
        h.seg[1], crossing_verb(h.kind));
  /* A comb: 20,000 teeth, so the sweep holds 40,000 segments at once. */
  int teeth = 20000, nc = 4 * teeth;
  vec2 *c = xmallocarray((size_t)nc + 2, sizeof *c);
  int k = 0;
  for (int t = 0; t < teeth; t++) {
    c[k++] = (vec2){0, 2.0 * t};
    c[k++] = (vec2){1000, 2.0 * t};
    c[k++] = (vec2){1000, 2.0 * t + 1};
    c[k++] = (vec2){0.5, 2.0 * t + 1};
  }
  c[k++] = (vec2){-1, 2.0 * teeth};
  c[k++] = (vec2){-1, 0};
  /* reversed order is irrelevant; teeth run right, the spine at x = 0 .. -1 */
  P = (crossing_poly){c, k};
  int f = crossing_find(&P, 1, &h);
  CHECK(!f, "the comb is simple (found %d %d %s)", h.seg[0], h.seg[1], crossing_verb(h.kind));
  /* One tooth's tip bent down onto the tooth below: found. */
  c[4 * 777 + 2].y = 2.0 * 776 + 1;
  f = crossing_find(&P, 1, &h);
  CHECK(f && h.seg[0] >= 4 * 776 && h.seg[1] <= 4 * 778, "the bent comb offends near tooth 777 (%d: %d %d)",
        f, h.seg[0], h.seg[1]);

  /* Medium sizes against the brute force: random stars with a few swaps. */
  for (int trial = 0; trial < 40; trial++) {
    int m = rng_int(g, 50, 1500);
    vec2 *q = xmallocarray((size_t)m, sizeof *q);
    gen_star(g, q, m, 0, 0, 100, 0.9);
    int swaps = trial % 3;
    for (int s = 0; s < swaps; s++) {
      int i = rng_int(g, 0, m - 2);
      vec2 t = q[i];
      q[i] = q[i + 1], q[i + 1] = t;
    }
    crossing_poly Q = {q, m};
    crossing_hit a, b;
    int fa = crossing_find(&Q, 1, &a), fb = crossing_find_brute(&Q, 1, &b);
    CHECK(fa == fb, "star of %d points, %d swaps: sweep %d, brute %d", m, swaps, fa, fb);
    free(q);
  }
  free(p);
  free(c);
}

/* --- one segment against polygons ---------------------------------------- */

static void one_segment(rng *g) {
  int fails = 0;
  for (int trial = 0; trial < 4000; trial++) {
    ipoly P[3];
    int np = random_polys(g, P, 3, 6, 8);
    ip a = {rng_int(g, 0, 6), rng_int(g, 0, 6)}, b = {rng_int(g, 0, 6), rng_int(g, 0, 6)};
    if (trial % 2) a = P[0].p[0];   /* from a vertex, as a bridge is */
    if (a.x == b.x && a.y == b.y) b.x++;
    int allow = rng_int(g, 0, 3);
    int want = 0, wk = -1, ws = -1;
    for (int k = 0; k < np && !want; k++)
      for (int s = 0; s < P[k].n && !want; s++) {
        ip c = P[k].p[s], d = P[k].p[(s + 1) % P[k].n];
        crossing_kind kind = ref_segments(a, b, c, d);
        if (kind == CROSSING_NONE) continue;
        if (kind == CROSSING_TOUCH && (((allow & CROSSING_ALLOW_A) && ion(a, c, d)) ||
                                       ((allow & CROSSING_ALLOW_B) && ion(b, c, d))))
          continue;
        want = 1, wk = k, ws = s;
      }
    crossing_poly *C = as_double(P, np, 0, 0, 0);
    crossing_hit h;
    int got = crossing_segment(C, np, dv(a), dv(b), allow, &h);
    if ((got != want || (got && (h.poly[0] != wk || h.seg[0] != ws))) && fails++ < 5)
      CHECK(0, "segment (%lld %lld)-(%lld %lld), allow %d: %d at %d:%d, want %d at %d:%d", a.x, a.y,
            b.x, b.y, allow, got, h.poly[0], h.seg[0], want, wk, ws);
    free_double(C, np);
    for (int k = 0; k < np; k++) free(P[k].p);
  }
  CHECK(fails == 0, "%d segment queries wrong", fails);
}

int main(void) {
  rng g;
  rng_seed(&g, 7301);
  segments(&g);
  cases();
  sets(&g);
  large(&g);
  one_segment(&g);
  return check_done("test_crossing");
}
