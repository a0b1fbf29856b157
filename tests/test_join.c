/* test_join.c -- the joining rules (surface/match.h), their notes and counts,
 * and the slab of one slice, against independent references:
 *   overlap_closed  against the separating axis theorem on convex integer
 *                   polygons (closed and open), and hand-made contacts;
 *   gap_between     against every vertex-segment pair (exactly) and the
 *                   segments' distances in doubles;
 *   stacks          the tilted tube (one component, closed, its volume
 *                   within 2 % of area x height), the staircases (edge and
 *                   corner), the Y (--join nearest: one component, one note),
 *                   stacked disjoint squares (default: joined with a note;
 *                   overlap: two components), a tie (the canonically first,
 *                   and one 2^-40 nearer wins), a join no bridge can make
 *                   (dropped with a note), one slice as a slab (its volume
 *                   area x thickness), each judged by the independent mesh
 *                   checker (tests/meshcheck.c); every case shuffled,
 *                   restarted and reversed gives the same mesh, report and
 *                   notes (line numbers aside); random stacks under every
 *                   rule give closed outward manifolds through their input. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/contour.h"
#include "geom/exact.h"
#include "geom/exactdist.h"
#include "surface/gap.h"
#include "surface/inside.h"
#include "tests/meshcheck.h"
#include "tests/reference.h"
#include "surface/overlap.h"
#include "surface/report.h"
#include "util/rng.h"
#include "surface/slices.h"
#include "surface/stack.h"
#include "tests/stackgen.h"
#include "util/xmem.h"

/* ------------------------------------------------------ overlap_closed -- */

static int rand_convex(rng *g, vec2 *out, int cx, int cy) {
  vec2 p[12];
  int n = rng_int(g, 3, 12), h = 0, start = 0;
  for (int i = 0; i < n; i++) p[i] = (vec2){cx + rng_int(g, -4, 4), cy + rng_int(g, -4, 4)};
  for (int i = 1; i < n; i++)
    if (p[i].x < p[start].x || (p[i].x == p[start].x && p[i].y < p[start].y)) start = i;
  int cur = start;
  do {   /* gift wrapping, strictly convex */
    out[h++] = p[cur];
    int nx = cur == 0 ? 1 : 0;
    for (int i = 0; i < n; i++) {
      if (i == cur) continue;
      int o = exact_orient(p[cur], p[nx], p[i]);
      double dn = hypot(p[nx].x - p[cur].x, p[nx].y - p[cur].y), di = hypot(p[i].x - p[cur].x, p[i].y - p[cur].y);
      if (o < 0 || (o == 0 && di > dn)) nx = i;
    }
    cur = nx;
  } while (cur != start && h < 12);
  return h;
}

static int closed_of(const vec2 *p, int np, const vec2 *q, int nq) {
  return ref_symmetric(overlap_closed, "overlap_closed", p, np, q, nq);
}

static void test_closed(rng *g) {
  vec2 sq[4] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  vec2 right[4] = {{2, 0}, {4, 0}, {4, 2}, {2, 2}};           /* an edge */
  vec2 part[4] = {{2, 1}, {4, 1}, {4, 5}, {2, 5}};            /* part of an edge */
  vec2 corner[4] = {{2, 2}, {3, 2}, {3, 3}, {2, 3}};          /* a corner */
  vec2 tip[3] = {{2, 1}, {3, 0}, {3, 2}};                     /* a vertex on an edge */
  vec2 apart[4] = {{2.5, 0}, {3, 0}, {3, 1}, {2.5, 1}};
  vec2 inner[4] = {{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}};
  vec2 inside_touch[3] = {{0, 0}, {1, 0.5}, {0.5, 1}};        /* inside, a vertex on the corner */
  CHECK(closed_of(sq, 4, right, 4) == OVERLAP_TOUCH, "squares sharing an edge touch");
  CHECK(closed_of(sq, 4, part, 4) == OVERLAP_TOUCH, "squares sharing part of an edge touch");
  CHECK(closed_of(sq, 4, corner, 4) == OVERLAP_TOUCH, "squares sharing a corner touch");
  CHECK(closed_of(sq, 4, tip, 3) == OVERLAP_TOUCH, "a triangle's vertex on an edge touches");
  CHECK(closed_of(sq, 4, apart, 4) == OVERLAP_APART, "squares 0.5 apart");
  CHECK(closed_of(sq, 4, inner, 4) == OVERLAP_INTERIOR, "nested squares overlap");
  CHECK(closed_of(sq, 4, inside_touch, 3) == OVERLAP_INTERIOR, "a triangle inside, touching at a corner, overlaps");
  CHECK(closed_of(sq, 4, sq, 4) == OVERLAP_INTERIOR, "equal squares overlap");
  int bad = 0, touch = 0;
  for (int trial = 0; trial < 4000; trial++) {
    vec2 p[12], q[12];
    int np = rand_convex(g, p, 0, 0), nq = rand_convex(g, q, rng_int(g, -8, 8), rng_int(g, -8, 8));
    if (np < 3 || nq < 3) continue;
    int want = ref_convex_apart(p, np, q, nq, 1) ? OVERLAP_APART : ref_convex_apart(p, np, q, nq, 0) ? OVERLAP_TOUCH : OVERLAP_INTERIOR;
    touch += want == OVERLAP_TOUCH;
    bad += closed_of(p, np, q, nq) != want;
  }
  CHECK(bad == 0, "%d of 4000 convex pairs disagree with the separating axis theorem", bad);
  CHECK(touch > 100, "only %d touching pairs: the test does not test touching", touch);
}

/* ---------------------------------------------------------------- gap --- */

static double seg_point(vec2 p, vec2 a, vec2 b) {
  double ux = b.x - a.x, uy = b.y - a.y, t = ((p.x - a.x) * ux + (p.y - a.y) * uy) / (ux * ux + uy * uy);
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  return hypot(p.x - a.x - t * ux, p.y - a.y - t * uy);
}

static slice_contour contour_of(vec2 *p, int n) {
  slice_contour c;
  memset(&c, 0, sizeof c);
  c.n = n, c.pt = p, c.ix = inside_new(p, n);
  return c;
}

static void test_gap(rng *g) {
  int bad = 0, badd = 0, runs = 0;
  for (int trial = 0; trial < 1500; trial++) {
    vec2 p[40], q[40];
    int np, nq;
    if (trial % 2) {
      np = rand_convex(g, p, 0, 0), nq = rand_convex(g, q, rng_int(g, -14, 14), rng_int(g, -14, 14));
      if (np < 3 || nq < 3 || !ref_convex_apart(p, np, q, nq, 0)) continue;
    } else {
      np = rng_int(g, 3, 40), nq = rng_int(g, 3, 40);
      double r = 1 + 2 * rng_uniform(g), a = 6.3 * rng_uniform(g), d = 2 * r + 3 * rng_uniform(g);
      sg_circle(p, np, 0, 0, r, r * (0.3 + rng_uniform(g)), rng_uniform(g));
      sg_circle(q, nq, d * cos(a) * 1.5, d * sin(a) * 1.5, 1, 1 + rng_uniform(g), rng_uniform(g));
    }
    slice_contour A = contour_of(p, np), B = contour_of(q, nq);
    exactdist got, best;
    gap_between(&A, &B, &got);
    /* Every vertex against every segment, both ways: the least, exactly. */
    int any = 0;
    double dd = INFINITY;
    for (int pass = 0; pass < 2; pass++) {
      const vec2 *x = pass ? q : p, *y = pass ? p : q;
      int nx = pass ? nq : np, ny = pass ? np : nq;
      for (int i = 0; i < nx; i++)
        for (int j = 0; j < ny; j++) {
          exactdist d;
          exactdist_segment(x[i], y[j], y[(j + 1) % ny], &d);
          if (!any || exactdist_cmp(&d, &best) < 0) best = d, any = 1;
          dd = fmin(dd, seg_point(x[i], y[j], y[(j + 1) % ny]));
        }
    }
    runs++;
    bad += exactdist_cmp(&got, &best) != 0;
    badd += fabs(exactdist_value(&got) - dd) > 1e-12 * (1 + dd);
    inside_free(A.ix);
    inside_free(B.ix);
  }
  CHECK(bad == 0, "%d of %d gaps differ from the least vertex-segment distance", bad, runs);
  CHECK(badd == 0, "%d of %d gaps differ from the segments' distance in doubles", badd, runs);
}

/* ------------------------------------------------------------- stacks --- */

/* The polygons as text (%.17g), in `order`, each from start[i] and reversed
 * by rev[i] (NULLs: as given), read as ./tile reads a file. */
static int make_stack(const sg_poly *ps, int np, const int *order, const int *start, const int *rev, contour_stack *s) {
  char *text = NULL, err[512];
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  for (int k = 0; k < np; k++) {
    int i = order ? order[k] : k, n = ps[i].n, st = start ? start[i] % n : 0;
    fprintf(f, "C %d %.17g\n", n, ps[i].z);
    for (int j = 0; j < n; j++) {
      int x = rev && rev[i] ? (st - j + n) % n : (st + j) % n;
      fprintf(f, "%.17g %.17g\n", ps[i].p[x].x, ps[i].p[x].y);
    }
  }
  fclose(f);
  int rc = contour_parse_flags(text, len, "t.contours", CONTOUR_ONE_SLICE, s, NULL, "test", err, sizeof err);
  CHECK(rc == 0, "stack: %s", err);
  free(text);
  return rc;
}

typedef struct {
  match_rule rule;
  double dist;
  int caps, apex;
  double thickness;
} how;

typedef struct {
  int res;
  char err[600];
  stack_surface *ss;
  char *notes, *report;
} outcome;

static void run(const sg_poly *ps, int np, const int *order, const int *start, const int *rev, how h, outcome *o) {
  memset(o, 0, sizeof *o);
  contour_stack s;
  if (make_stack(ps, np, order, start, rev, &s) != 0) {
    o->res = -9;
    return;
  }
  size_t nl = 0, rl = 0;
  FILE *nf = open_memstream(&o->notes, &nl);
  stack_options so = {COST_AREA, h.caps, h.apex, 2, NULL, nf, "test", NULL, NULL, h.rule, h.dist, h.thickness, STACK_BAND_ALIGNED};
  o->res = stack_tile(&s, "t.contours", &so, &o->ss, o->err, sizeof o->err);
  fclose(nf);
  FILE *rf = open_memstream(&o->report, &rl);
  if (o->res == 0) report_header(rf, "", NULL), report_rows(rf, "", o->ss, NULL);
  fclose(rf);
  contour_stack_free(&s);
}

static void done(outcome *o) {
  stack_free(o->ss);
  free(o->notes);
  free(o->report);
}

static int count_lines(const char *text, const char *needle) {
  int n = 0;
  for (const char *p = text; p && *p;) {
    const char *e = strchr(p, '\n');
    size_t len = e ? (size_t)(e - p) : strlen(p);
    char *line = xmalloc(len + 1);
    memcpy(line, p, len);
    line[len] = 0;
    n += strstr(line, needle) != NULL;
    free(line);
    p = e ? e + 1 : p + len;
  }
  return n;
}

/* The mesh judged by the independent checker: a closed outward 2-manifold
 * of `comps` components (-1: any) through every input point and segment.
 * Returns the checker's volume. */
static double judge(const char *what, const outcome *o, const sg_poly *ps, int np, int comps) {
  if (o->res != 0) {
    CHECK(0, "%s: refused: %s", what, o->err);
    return NAN;
  }
  return ref_judge_mesh(what, stack_mesh(o->ss), ps, np, comps, NULL);
}

/* The notes with their line numbers ("t.contours:N:", "line N") masked, and
 * without the count of contours whose winding the file got wrong. */
static char *masked(const char *t) {
  size_t n = strlen(t);
  char *r = xmalloc(n + 1), *w = r;
  for (size_t i = 0; i < n;) {
    if ((i == 0 || t[i - 1] == '\n') && strncmp(t + i, "test: t.contours: ", 18) == 0 &&
        strstr(t + i, "ran against their nesting") < strchr(t + i, '\n')) {
      i = (size_t)(strchr(t + i, '\n') - t) + 1;
      continue;
    }
    int after = (i > 0 && t[i - 1] == ':') || (i >= 5 && strncmp(t + i - 5, "line ", 5) == 0);
    if (after && t[i] >= '0' && t[i] <= '9') {
      *w++ = '#';
      while (i < n && t[i] >= '0' && t[i] <= '9') i++;
    } else {
      *w++ = t[i++];
    }
  }
  *w = 0;
  return r;
}

/* Shuffled, restarted and reversed encodings: the same mesh and report,
 * the same notes but for line numbers. */
static void invariant(const char *what, const sg_poly *ps, int np, how h, rng *g) {
  outcome ref;
  run(ps, np, NULL, NULL, NULL, h, &ref);
  char *rn = masked(ref.notes ? ref.notes : "");
  int bad = 0;
  for (int trial = 0; trial < 8; trial++) {
    int order[SG_MAXP], start[SG_MAXP], rev[SG_MAXP];
    for (int i = 0; i < np; i++) order[i] = i, start[i] = rng_int(g, 0, ps[i].n - 1), rev[i] = rng_int(g, 0, 1);
    for (int i = np - 1; i > 0; i--) {
      int j = rng_int(g, 0, i), t = order[i];
      order[i] = order[j], order[j] = t;
    }
    outcome o;
    run(ps, np, order, start, rev, h, &o);
    char *on = masked(o.notes ? o.notes : "");
    int same = o.res == ref.res && strcmp(on, rn) == 0;
    if (same && o.res == 0) {
      const mesh *a = stack_mesh(ref.ss), *b = stack_mesh(o.ss);
      same = strcmp(o.report, ref.report) == 0 && a->nv == b->nv && a->nt == b->nt &&
             memcmp(a->v, b->v, (size_t)a->nv * sizeof *a->v) == 0 &&
             memcmp(a->t, b->t, (size_t)a->nt * sizeof *a->t) == 0;
    }
    if (!same && bad++ == 0)
      CHECK(0, "%s: an encoding differs:\n%s%s---\n%s%s", what, ref.report, rn, o.report ? o.report : "", on);
    free(on);
    done(&o);
  }
  CHECK(bad == 0, "%s: %d of 8 encodings differ", what, bad);
  free(rn);
  done(&ref);
}

static const how DEFAULT = {MATCH_SINGLE, INFINITY, 1, 0, 0};

static how rule(match_rule r) {
  how h = DEFAULT;
  h.rule = r;
  return h;
}

static vec2 sqbuf[SG_MAXP][4];

/* The unit square (w by 1) with its lower left corner at (x, y). */
static sg_poly square(int i, double x, double y, double w, double z) {
  vec2 *p = sqbuf[i];
  p[0] = (vec2){x, y}, p[1] = (vec2){x + w, y}, p[2] = (vec2){x + w, y + 1}, p[3] = (vec2){x, y + 1};
  return (sg_poly){4, z, p};
}

static double area_of(const sg_poly *p) { return fabs(geom_area2(p->p, p->n)) / 2; }

/* A thin tube at an angle: squares, then circles, each slice's section
 * beside the one below (0.5 apart), one per slice. */
static void test_tube(rng *g) {
  enum { K = 6, N = 24 };
  static vec2 cb[K][N];
  for (int shape = 0; shape < 2; shape++) {
    sg_poly ps[K];
    for (int k = 0; k < K; k++) {
      if (shape == 0) ps[k] = square(k, 1.5 * k, 0.25 * k, 1, k);
      else sg_circle(cb[k], N, 2.5 * k, 0, 1, 1, 0.1 * k), ps[k] = (sg_poly){N, k, cb[k]};
    }
    const char *what = shape ? "tilted tube of circles" : "tilted tube of squares";
    outcome o;
    run(ps, K, NULL, NULL, NULL, DEFAULT, &o);
    double vol = judge(what, &o, ps, K, 1), want = area_of(&ps[0]) * (K - 1);
    CHECK(fabs(vol - want) <= 0.02 * want, "%s: volume %.17g, want %.17g within 2%%", what, vol, want);
    if (o.res == 0) {
      const stack_joins *j = stack_join_counts(o.ss);
      CHECK(j->apart == K - 1 && j->unjoined == 0 && j->dropped == 0 && strcmp(j->rule, "single") == 0,
            "%s: joins %s %d %d %d", what, j->rule, j->apart, j->unjoined, j->dropped);
      CHECK(count_lines(o.notes, "") == 1 && count_lines(o.notes, "t.contours:1: joined to the contour above, and so on "
                                                                    "up to line") == 1 &&
                count_lines(o.notes, "(5 joins, slices z=0 to z=5) without overlap: one outer contour on each slice") == 1,
            "%s: notes:\n%s", what, o.notes);
      CHECK(strstr(o.report, "\njoins,,,,,,single,5,0,0,,,,,,,\nmesh,") != NULL, "%s: report:\n%s", what, o.report);
    }
    done(&o);
    for (int r = 0; r < 2; r++) {   /* overlap and touch: K lenses, each contour named */
      run(ps, K, NULL, NULL, NULL, rule(r ? MATCH_TOUCH : MATCH_OVERLAP), &o);
      judge(what, &o, ps, K, K);
      CHECK(o.res == 0 && stack_join_counts(o.ss)->unjoined == 2 * (K - 1) && count_lines(o.notes, "no partner") == K,
            "%s, rule %d: notes:\n%s", what, r, o.notes);
      done(&o);
    }
    invariant(what, ps, K, DEFAULT, g);
  }
  /* Without caps the tube is open: no "empty mesh"; overlap gives nothing. */
  sg_poly ps[3] = {square(0, 0, 0, 1, 0), square(1, 1.5, 0, 1, 1), square(2, 3, 0, 1, 2)};
  how open = rule(MATCH_OVERLAP);
  open.caps = 0;
  outcome o;
  run(ps, 3, NULL, NULL, NULL, open, &o);
  CHECK(o.res == 0 && stack_mesh(o.ss)->nt == 0 && count_lines(o.notes, "t.contours: the mesh is empty") == 1,
        "the empty mesh is not said: %s", o.notes);
  done(&o);
}

/* Pixel staircases: squares that share only an edge (left) or a corner
 * (right) with the square below; two per slice, so the single rule cannot
 * join them. */
static void test_staircase(rng *g) {
  enum { K = 5 };
  sg_poly ps[2 * K];
  for (int k = 0; k < K; k++) ps[2 * k] = square(2 * k, k, 0, 1, k), ps[2 * k + 1] = square(2 * k + 1, 20 + k, k, 1, k);
  outcome o;
  for (int r = 0; r < 3; r++) {
    match_rule mr = r == 0 ? MATCH_SINGLE : r == 1 ? MATCH_TOUCH : MATCH_OVERLAP;
    run(ps, 2 * K, NULL, NULL, NULL, rule(mr), &o);
    judge("staircases", &o, ps, 2 * K, mr == MATCH_OVERLAP ? 2 * K : 2);
    if (o.res == 0) {
      const stack_joins *j = stack_join_counts(o.ss);
      CHECK(j->apart == 0 && j->unjoined == (mr == MATCH_OVERLAP ? 4 * (K - 1) : 0), "staircases, rule %d: %d apart, %d unjoined",
            r, j->apart, j->unjoined);
      CHECK(count_lines(o.notes, "without overlap") == 0, "staircases: a touching join noted as without overlap");
    }
    done(&o);
  }
  invariant("staircases", ps, 2 * K, DEFAULT, g);
}

/* A trunk, then two branches: the left overlaps the trunk, the right starts
 * 0.5 beside it (its sections touch each other). */
static void test_y(rng *g) {
  sg_poly ps[7] = {square(0, 0, 0, 2, 0), square(1, 0, 0, 2, 1), square(2, 0, 0, 2, 2), square(3, 0, 0, 1, 3),
                   square(4, 2.5, 0, 1, 3), square(5, -0.5, 0, 1, 4), square(6, 3.5, 0, 1, 4)};
  outcome o;
  run(ps, 7, NULL, NULL, NULL, DEFAULT, &o);
  judge("Y, default", &o, ps, 7, 2);
  done(&o);
  run(ps, 7, NULL, NULL, NULL, rule(MATCH_NEAREST), &o);
  judge("Y, nearest", &o, ps, 7, 1);
  CHECK(o.res == 0 && count_lines(o.notes, "joined to its nearest contour") == 1 &&
            count_lines(o.notes, "t.contours:21: joined to its nearest contour on slice z=2, the contour at line 11, "
                                 "without overlap (--join nearest), gap 0.5") == 1 &&
            stack_join_counts(o.ss)->apart == 1 && stack_join_counts(o.ss)->unjoined == 0,
        "Y, nearest: notes:\n%s", o.notes);
  done(&o);
  how d = rule(MATCH_NEAREST);
  d.dist = 0.25;   /* the branch is 0.5 off */
  run(ps, 7, NULL, NULL, NULL, d, &o);
  judge("Y, --join 0.25", &o, ps, 7, 2);
  CHECK(o.res == 0 && stack_join_counts(o.ss)->apart == 0 && strcmp(stack_join_counts(o.ss)->rule, "0.25") == 0,
        "Y, --join 0.25: joined");
  done(&o);
  d.dist = 0.5;   /* exactly the gap: joined */
  run(ps, 7, NULL, NULL, NULL, d, &o);
  judge("Y, --join 0.5", &o, ps, 7, 1);
  done(&o);
  invariant("Y", ps, 7, rule(MATCH_NEAREST), g);
}

/* One square on two slices, another beside it on the two above. */
static void test_disjoint(rng *g) {
  sg_poly ps[4] = {square(0, 0, 0, 1, 0), square(1, 0, 0, 1, 1), square(2, 3, 0, 1, 2), square(3, 3, 0, 1, 3)};
  outcome o;
  run(ps, 4, NULL, NULL, NULL, DEFAULT, &o);
  judge("stacked squares, default", &o, ps, 4, 1);
  CHECK(o.res == 0 && count_lines(o.notes, "") == 1 &&
            count_lines(o.notes, "t.contours:6: joined to the contour at line 11 (slice z=1 to z=2) without overlap: one "
                                 "outer contour on each slice (--join single), gap 2") == 1,
        "stacked squares: notes:\n%s", o.notes);
  done(&o);
  run(ps, 4, NULL, NULL, NULL, rule(MATCH_OVERLAP), &o);
  judge("stacked squares, overlap", &o, ps, 4, 2);
  CHECK(o.res == 0 && stack_join_counts(o.ss)->unjoined == 2 &&
            count_lines(o.notes, "t.contours:6: no partner for this contour (slice z=1) on slice z=2; nearest there: the "
                                 "contour at line 11, gap 2") == 1,
        "stacked squares, overlap: notes:\n%s", o.notes);
  done(&o);
  invariant("stacked squares", ps, 4, DEFAULT, g);
  invariant("stacked squares, overlap", ps, 4, rule(MATCH_OVERLAP), g);
}

/* A stray S between two contours at exactly the same gap: the canonically
 * first wins, mirrored too; moved 2^-40 toward the other, the other. */
static void test_tie(rng *g) {
  for (int v = 0; v < 3; v++) {
    double m = v == 1 ? -1 : 1, e = v == 2 ? 0x1p-40 : 0;
    /* slice 0: [0,1] and [4,5]; slice 1: the same and S = [2,3] (x mirrored by m) */
    sg_poly ps[5] = {square(0, m < 0 ? -1 : 0, 0, 1, 0), square(1, m < 0 ? -5 : 4, 0, 1, 0),
                     square(2, m < 0 ? -1 : 0, 0, 1, 1), square(3, m < 0 ? -5 : 4, 0, 1, 1), square(4, 2 + e, 0, 1, 1)};
    if (m < 0) ps[4] = square(4, -3, 0, 1, 1);
    outcome o;
    run(ps, 5, NULL, NULL, NULL, rule(MATCH_NEAREST), &o);
    judge("tie", &o, ps, 5, 2);
    /* The 1-2 band: S with the first contour of slice 0 (v < 2), or with
     * the second, which it is 2^-40 nearer (v = 2). */
    int found = 0, want = v < 2 ? 0 : 1;
    for (int i = 0; o.res == 0 && i < stack_nrows(o.ss); i++) {
      const stack_row *r = &stack_rows(o.ss)[i];
      if (r->kind != STACK_BAND || r->nhi != 2) continue;
      found++;
      CHECK(r->nlo == 1 && r->lo[0] == want && r->hi[0] == want && r->hi[1] == want + 1,
            "tie %d: the stray joined contour %d (%d+%d), want %d", v, r->lo[0], r->hi[0], r->hi[1], want);
    }
    CHECK(found == 1, "tie %d: %d branching bands", v, found);
    done(&o);
    if (v == 0) invariant("tie", ps, 5, rule(MATCH_NEAREST), g);
  }
}

/* A stray whose nearest (the U above) is joined to a square that no
 * bridge can reach past the wall between them: the join is dropped. */
static void test_dropped(rng *g) {
  static vec2 u[8] = {{-1, 2}, {-1, -12}, {14, -12}, {14, 2}, {11.5, 2}, {11.5, -11}, {2, -11}, {2, 2}};
  sg_poly ps[5] = {square(0, 0, 0, 1, 0), square(1, 10, 0, 1, 0), square(2, 5, -10, 1, 0), {8, 1, u},
                   square(3, 5, -10, 1, 1)};
  ps[2].p[2].y = ps[2].p[3].y = 11;   /* the wall, 21 high */
  ps[4].p[2].y = ps[4].p[3].y = 11;   /* and a copy above it */
  outcome o;
  run(ps, 5, NULL, NULL, NULL, rule(MATCH_NEAREST), &o);
  judge("dropped join", &o, ps, 5, -1);
  CHECK(o.res == 0 && stack_join_counts(o.ss)->dropped == 1 && stack_join_counts(o.ss)->unjoined == 1 &&
            count_lines(o.notes, "t.contours:6: not joined to the contour at line 16 on slice z=1 (its nearest there, gap "
                                 "0.5, --join nearest): no bridges can join") == 1,
        "dropped join: %s\n%s", o.err, o.notes);
  done(&o);
  invariant("dropped join", ps, 5, rule(MATCH_NEAREST), g);
}

/* One slice: a square with a square hole and an island in it, and a square
 * beside: slabs 2 thick, volume area x 2; refused without a thickness. */
static void test_slab(rng *g) {
  sg_poly ps[4] = {square(0, 0, 0, 8, 5), square(1, 2, 2, 4, 5), square(2, 3, 3, 2, 5), square(3, 10, 0, 1, 5)};
  for (int k = 0; k < 4; k++)   /* squares (w by w) */
    for (int c = 2; c < 4; c++) ps[k].p[c].y = ps[k].p[0].y + (ps[k].p[1].x - ps[k].p[0].x);
  double area = area_of(&ps[0]) - area_of(&ps[1]) + area_of(&ps[2]) + area_of(&ps[3]);
  for (int apex = 0; apex < 2; apex++)
    for (int caps = 0; caps < 2; caps++) {
      how h = DEFAULT;
      h.caps = caps, h.apex = apex && caps, h.thickness = 2;
      outcome o;
      run(ps, 4, NULL, NULL, NULL, h, &o);
      double vol = judge("slab", &o, ps, 4, 3);
      CHECK(fabs(vol - 2 * area) <= 1e-12 * area, "slab: the checker's volume %.17g, want %.17g", vol, 2 * area);
      if (o.res == 0) {
        double c, a, v;
        stack_totals(o.ss, &c, &a, &v);
        CHECK(fabs(v - 2 * area) <= 1e-12 * area, "slab: volume %.17g, want %.17g", v, 2 * area);
        CHECK(strstr(o.report, "\nmesh,4,6,") != NULL, "slab: not from z=4 to 6:\n%s", o.report);
      }
      done(&o);
    }
  outcome o;
  run(ps, 4, NULL, NULL, NULL, DEFAULT, &o);
  CHECK(o.res == -1 && strcmp(o.err, "t.contours:1: all 4 contours lie on one slice (z=5): a surface needs two slices, "
                                     "or --thickness T to make this one a slab T thick") == 0,
        "one slice without a thickness: %d '%s'", o.res, o.err);
  done(&o);
  how h = DEFAULT;
  h.thickness = 2;
  invariant("slab", ps, 4, h, g);
}

/* Random stacks (discs, holes, islands: branching, merging, ends) under
 * every rule: closed outward manifolds through every input segment. */
static void test_random(rng *g) {
  static vec2 buf[SG_MAXP][SG_N];
  static const how rules[] = {{MATCH_TOUCH, INFINITY, 1, 0, 0}, {MATCH_NEAREST, INFINITY, 1, 0, 0},
                              {MATCH_NEAREST, 1.0, 1, 1, 0}, {MATCH_SINGLE, INFINITY, 1, 1, 0}};
  int apart = 0, dropped = 0, stacks = 0;
  for (int trial = 0; trial < 40; trial++) {
    sg_poly ps[SG_MAXP];
    int np = sg_random(g, buf, ps);
    for (size_t r = 0; r < sizeof rules / sizeof *rules; r++) {
      outcome o;
      char what[64];
      snprintf(what, sizeof what, "random stack %d, rule %zu", trial, r);
      run(ps, np, NULL, NULL, NULL, rules[r], &o);
      judge(what, &o, ps, np, -1);
      if (o.res == 0) apart += stack_join_counts(o.ss)->apart, dropped += stack_join_counts(o.ss)->dropped, stacks++;
      done(&o);
    }
  }
  CHECK(stacks == 160 && apart > 40, "random stacks: %d tiled, %d joins without overlap", stacks, apart);
  printf("test_join: random stacks: %d joins without overlap, %d dropped\n", apart, dropped);
}

int main(void) {
  rng g;
  rng_seed(&g, 2222);
  test_closed(&g);
  test_gap(&g);
  test_tube(&g);
  test_staircase(&g);
  test_y(&g);
  test_disjoint(&g);
  test_tie(&g);
  test_dropped(&g);
  test_slab(&g);
  test_random(&g);
  return check_done("test_join");
}
