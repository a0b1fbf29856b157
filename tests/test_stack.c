/* test_stack.c -- the stack tiler's modules (surface/) against independent
 * references:
 *   overlap    against the separating-axis test on convex integer polygons,
 *              and hand-made touching and degenerate cases;
 *   slices     nesting depth, parents, orientation by depth, and the same
 *              canonical slices whatever the file's order, starts, windings;
 *   unpinch    against every path of small pairs, enumerated;
 *   stack      one contour per slice: the same band triangles as the pair
 *              tiler (tiling_solve + mesh_add_band); branching, holes,
 *              islands, apex caps: closed outward manifolds by the
 *              independent checker (tests/meshcheck.c), every input segment
 *              an edge, the report's volumes summing to the mesh's, and the
 *              mesh's volume against the integral of its own sections (cut
 *              exactly, integrated by Milne's rule between vertex heights,
 *              exact for the piecewise quadratic areas); -j 1 against -j 4,
 *              the parallel algorithm on the simulator against the serial
 *              tiler, bit for bit; the refusals' messages.
 * The stacks: tests/stackgen.h. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/contour.h"
#include "geom/exact.h"
#include "geom/geom.h"
#include "surface/inside.h"
#include "surface/mesh.h"
#include "tests/meshcheck.h"
#include "tests/reference.h"
#include "surface/overlap.h"
#include "surface/pool.h"
#include "util/rng.h"
#include "tests/parmachine.h"
#include "surface/slices.h"
#include "surface/stack.h"
#include "tests/stackgen.h"
#include "algo/tiling.h"
#include "surface/unpinch.h"
#include "util/xmem.h"

/* ------------------------------------------------------------- overlap -- */

static int ov(const vec2 *p, int np, const vec2 *q, int nq) {
  return ref_symmetric(overlap_regions, "overlap", p, np, q, nq);
}

/* A random convex polygon with integer points: the hull of a few points. */
static int rand_convex(rng *g, vec2 *out, int cx, int cy) {
  vec2 p[12];
  int n = rng_int(g, 3, 12), h = 0;
  for (int i = 0; i < n; i++) p[i] = (vec2){cx + rng_int(g, -6, 6), cy + rng_int(g, -6, 6)};
  /* gift wrapping, strictly convex */
  int start = 0;
  for (int i = 1; i < n; i++)
    if (p[i].x < p[start].x || (p[i].x == p[start].x && p[i].y < p[start].y)) start = i;
  int cur = start;
  do {
    out[h++] = p[cur];
    int nx = cur == 0 ? 1 : 0;
    for (int i = 0; i < n; i++) {
      if (i == cur) continue;
      int o = exact_orient(p[cur], p[nx], p[i]);
      double dn = (p[nx].x - p[cur].x) * (p[nx].x - p[cur].x) + (p[nx].y - p[cur].y) * (p[nx].y - p[cur].y);
      double di = (p[i].x - p[cur].x) * (p[i].x - p[cur].x) + (p[i].y - p[cur].y) * (p[i].y - p[cur].y);
      if (o < 0 || (o == 0 && di > dn)) nx = i;
    }
    cur = nx;
  } while (cur != start && h < 12);
  return h;
}

static void test_overlap(rng *g) {
  vec2 sq[4] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  vec2 right[4] = {{2, 0}, {4, 0}, {4, 2}, {2, 2}};          /* shares an edge */
  vec2 corner[4] = {{2, 2}, {3, 2}, {3, 3}, {2, 3}};         /* shares a vertex */
  vec2 inner[4] = {{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}};
  vec2 cross[4] = {{1, -1}, {3, -1}, {3, 1}, {1, 1}};
  vec2 tri_in[3] = {{0, 0}, {2, 0}, {0, 2}};                 /* all points on the square's boundary */
  vec2 tri_on[3] = {{1, 0}, {2, 1}, {1, 2}};                 /* a triangle inscribed in its sides */
  vec2 ell[6] = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
  vec2 notch[4] = {{1.5, 1.5}, {3, 1.5}, {3, 3}, {1.5, 3}};  /* in the L's notch, boxes overlap */
  vec2 notch_t[4] = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};        /* touching the notch's two sides */
  vec2 half[4] = {{1, -2}, {3, -2}, {3, 0}, {1, 0}};         /* runs along the square's bottom, outside */
  CHECK(ov(sq, 4, sq, 4) == 1, "equal squares overlap");
  CHECK(ov(sq, 4, right, 4) == 0, "squares sharing an edge do not overlap");
  CHECK(ov(sq, 4, corner, 4) == 0, "squares sharing a vertex do not overlap");
  CHECK(ov(sq, 4, inner, 4) == 1, "nested squares overlap");
  CHECK(ov(sq, 4, cross, 4) == 1, "crossing squares overlap");
  CHECK(ov(sq, 4, tri_in, 3) == 1, "a half square overlaps its square (all its points on it)");
  CHECK(ov(sq, 4, tri_on, 3) == 1, "an inscribed triangle overlaps");
  CHECK(ov(ell, 6, notch, 4) == 0, "a square in the L's notch does not overlap it");
  CHECK(ov(ell, 6, notch_t, 4) == 0, "a square touching the L's notch does not overlap it");
  CHECK(ov(sq, 4, half, 4) == 0, "a square along another's side, outside it, does not overlap");
  int bad = 0;
  for (int trial = 0; trial < 3000; trial++) {
    vec2 p[12], q[12];
    int np = rand_convex(g, p, 0, 0), nq = rand_convex(g, q, rng_int(g, -8, 8), rng_int(g, -8, 8));
    if (np < 3 || nq < 3) continue;
    if (ov(p, np, q, nq) != !ref_convex_apart(p, np, q, nq, 0)) bad++;
  }
  CHECK(bad == 0, "%d of 3000 random convex pairs disagree with the separating axis test", bad);
}

/* ------------------------------------------------------------- stacks --- */

static stack_band band_mode = STACK_BAND_ALIGNED;   /* how tile() tiles a 1-1 band */

static stack_surface *tile(const contour_stack *s, int caps, int apex, int threads, par_machine *rc,
                           char *err, size_t errlen, int *res) {
  stack_tiler tl = rc ? par_machine_tiler(rc) : (stack_tiler){NULL, NULL};
  stack_options o = {COST_AREA, caps, apex, threads, rc ? &tl : NULL, NULL, "test", NULL, NULL, MATCH_SINGLE, INFINITY, 0, band_mode};
  stack_surface *ss = NULL;
  *res = stack_tile(s, "t.contours", &o, &ss, err, errlen);
  return ss;
}

/* The section of the mesh at height z: twice its signed area, from the
 * triangles it cuts (each cut oriented so the material is on its left). */
static double section2(const mesh *me, double z) {
  double a2 = 0;
  for (int t = 0; t < me->nt; t++) {
    vec3 v[3];
    for (int k = 0; k < 3; k++) v[k] = me->v[me->t[t][k]];
    vec2 pts[2];
    int np = 0;
    for (int k = 0; k < 3 && np < 2; k++) {
      vec3 a = v[k], b = v[(k + 1) % 3];
      if ((a.z < z) != (b.z < z)) {
        double u = (z - a.z) / (b.z - a.z);
        pts[np++] = (vec2){a.x + u * (b.x - a.x), a.y + u * (b.y - a.y)};
      }
    }
    if (np < 2) continue;
    /* outward normal N; the cut runs along ez x N */
    double ux = v[1].x - v[0].x, uy = v[1].y - v[0].y, uz = v[1].z - v[0].z;
    double wx = v[2].x - v[0].x, wy = v[2].y - v[0].y, wz = v[2].z - v[0].z;
    double nx = uy * wz - uz * wy, ny = uz * wx - ux * wz;
    double dx = -ny, dy = nx;
    if ((pts[1].x - pts[0].x) * dx + (pts[1].y - pts[0].y) * dy < 0) {
      vec2 t2 = pts[0];
      pts[0] = pts[1], pts[1] = t2;
    }
    a2 += pts[0].x * pts[1].y - pts[1].x * pts[0].y;
  }
  return a2;
}

static int by_dbl(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/* The volume as the integral of the section areas: between consecutive
 * vertex heights the area is quadratic in z, and Milne's rule is exact. */
static double section_volume(const mesh *me) {
  double *z = xmallocarray((size_t)me->nv + 1, sizeof *z);
  for (int i = 0; i < me->nv; i++) z[i] = me->v[i].z;
  qsort(z, (size_t)me->nv, sizeof *z, by_dbl);
  double vol = 0;
  for (int i = 0; i + 1 < me->nv; i++) {
    if (z[i + 1] == z[i]) continue;
    double h = z[i + 1] - z[i];
    vol += h / 3 * (2 * section2(me, z[i] + h / 4) - section2(me, z[i] + h / 2) + 2 * section2(me, z[i] + 3 * h / 4)) / 2;
  }
  free(z);
  return vol;
}

/* The invariants of a good surface: closed outward manifold with `comps`
 * components of Euler characteristics chi[], every input segment an edge,
 * the report's bands and caps summing to the mesh's volume, and that volume
 * equal to its sections' integral. */
static void check_surface(const char *what, const stack_surface *ss, const sg_poly *ps, int np, int comps,
                          const int *chi) {
  const mesh *me = stack_mesh(ss);
  double cv = ref_judge_mesh(what, me, ps, np, comps, chi);
  double rows = 0;
  for (int i = 0; i < stack_nrows(ss); i++) rows += stack_rows(ss)[i].volume;
  double vol = mesh_volume(me), sv = section_volume(me);
  CHECK(fabs(rows - vol) <= 1e-9 * fabs(vol), "%s: rows' volumes sum to %.17g, the mesh's %.17g", what, rows, vol);
  CHECK(fabs(sv - vol) <= 1e-9 * fabs(vol), "%s: sections integrate to %.17g, the mesh's volume %.17g", what, sv, vol);
  CHECK(fabs(cv - vol) <= 1e-9 * fabs(vol), "%s: the checker's volume %.17g, the mesh's %.17g", what, cv, vol);
}

static int same_mesh(const mesh *a, const mesh *b) {
  return a->nv == b->nv && a->nt == b->nt && memcmp(a->v, b->v, (size_t)a->nv * sizeof *a->v) == 0 &&
         memcmp(a->t, b->t, (size_t)a->nt * sizeof *a->t) == 0;
}

/* Branching (two ellipses into one and back: a torus across the slices),
 * holes (an annulus whose hole closes), islands (in a hole), and a
 * single-slice blob, with flat and apex caps. */
static void test_shapes(void) {
  enum { N = 24 };
  static vec2 buf[40][N];
  sg_poly ps[40];
  int np = 0;
  /* A ring lying across the slices: 1, 2, 2, 1 contours. */
  sg_circle(buf[np], N, 0, 0, 3, 1, 0), ps[np] = (sg_poly){N, 0, buf[np]}, np++;
  sg_circle(buf[np], N, -2, 0, 1, 1, 0.1), ps[np] = (sg_poly){N, 1, buf[np]}, np++;
  sg_circle(buf[np], N, 2, 0, 1, 1, 0.2), ps[np] = (sg_poly){N, 1, buf[np]}, np++;
  sg_circle(buf[np], N, -2, 0.2, 1, 1.1, 0.3), ps[np] = (sg_poly){N, 2, buf[np]}, np++;
  sg_circle(buf[np], N, 2, -0.1, 1, 0.9, 0.4), ps[np] = (sg_poly){N, 2, buf[np]}, np++;
  sg_circle(buf[np], N, 0, 0, 3.2, 1.1, 0.5), ps[np] = (sg_poly){N, 3, buf[np]}, np++;
  for (int apex = 0; apex < 2; apex++) {
    contour_stack s;
    if (sg_make_stack(ps, np, NULL, NULL, NULL, &s) != 0) return;
    char err[512];
    int res;
    stack_surface *ss = tile(&s, 1, apex, 2, NULL, err, sizeof err, &res);
    CHECK(res == 0, "ring: %s", err);
    int chi[1] = {0};
    if (res == 0) check_surface(apex ? "ring, apex caps" : "ring", ss, ps, np, 1, chi);
    int bridges = 0, caps = 0;
    for (int i = 0; res == 0 && i < stack_nrows(ss); i++) {
      const stack_row *r = &stack_rows(ss)[i];
      bridges += r->kind == STACK_BAND ? r->bridges : 0;
      if (r->kind == STACK_CAP) {
        caps++;
        /* an apex cap adds a pyramid over the region: A h / 3 */
        double a = 0;
        for (int k = 0; k < np; k++)
          if (ps[k].z == r->z0) a = fabs(0.5 * geom_area2(ps[k].p, ps[k].n));
        double want = apex ? a * fabs(r->z1 - r->z0) / 3 : 0;
        CHECK(fabs(r->volume - want) <= 1e-9 * a, "ring cap at z=%g: volume %.17g, want %.17g", r->z0, r->volume, want);
        CHECK(!apex || fabs(r->z1 - r->z0) == 0.5, "apex half a slice out: %g", r->z1 - r->z0);
      }
    }
    CHECK(bridges == 2 && caps == 2, "ring: %d bridges, %d caps", bridges, caps);
    stack_free(ss);
    contour_stack_free(&s);
  }

  /* A cup whose hole closes, then a hole with an island that ends inside
   * the hole's cap, and a blob alone on one slice (a lens). */
  np = 0;
  sg_circle(buf[np], N, 0, 0, 5, 5, 0), ps[np] = (sg_poly){N, 0, buf[np]}, np++;
  sg_circle(buf[np], N, 0, 0, 5, 5, 0.1), ps[np] = (sg_poly){N, 1, buf[np]}, np++;
  sg_circle(buf[np], N, 0, 0, 3, 3, 0.2), ps[np] = (sg_poly){N, 1, buf[np]}, np++;      /* hole starts */
  sg_circle(buf[np], N, 0, 0, 5, 5, 0.3), ps[np] = (sg_poly){N, 2, buf[np]}, np++;
  sg_circle(buf[np], N, 0, 0, 3.2, 3.2, 0.4), ps[np] = (sg_poly){N, 2, buf[np]}, np++;
  sg_circle(buf[np], N, 0.2, 0, 1, 1, 0.5), ps[np] = (sg_poly){N, 2, buf[np]}, np++;    /* island starts */
  sg_circle(buf[np], N, 0, 0, 5, 5, 0.6), ps[np] = (sg_poly){N, 3, buf[np]}, np++;
  sg_circle(buf[np], N, 0, 0, 3.1, 3.1, 0.7), ps[np] = (sg_poly){N, 3, buf[np]}, np++;
  sg_circle(buf[np], N, 0, 0.1, 1.1, 1, 0.8), ps[np] = (sg_poly){N, 3, buf[np]}, np++;  /* ends: hole closes */
  sg_circle(buf[np], N, 0, 0, 5, 5, 0.9), ps[np] = (sg_poly){N, 4, buf[np]}, np++;
  sg_circle(buf[np], N, 9, 0, 1, 1, 1.0), ps[np] = (sg_poly){N, 2, buf[np]}, np++;      /* alone on slice 2 */
  for (int apex = 0; apex < 2; apex++) {
    contour_stack s;
    if (sg_make_stack(ps, np, NULL, NULL, NULL, &s) != 0) return;
    char err[512];
    int res;
    stack_surface *ss = tile(&s, 1, apex, 3, NULL, err, sizeof err, &res);
    CHECK(res == 0, "cup: %s", err);
    /* the solid, the cavity (with the island inside it, one surface: the
     * island's top merges into the cavity's roof) and the lens */
    int chi[3] = {2, 2, 2};
    if (res == 0) check_surface(apex ? "cup with an island, apex caps" : "cup with an island", ss, ps, np, 3, chi);
    stack_free(ss);
    contour_stack_free(&s);
  }
}

/* One contour per slice, the paper's plain bands: the same band triangles
 * as the pair tiler on the same (canonically started) contours. */
static void test_pairs(rng *g) {
  int bad = 0;
  band_mode = STACK_BAND_PLAIN;
  for (int trial = 0; trial < 40; trial++) {
    int k = rng_int(g, 2, 6);
    sg_poly ps[6];
    vec2 buf[6][40];
    for (int i = 0; i < k; i++) {
      int n = rng_int(g, 3, 40);
      sg_circle(buf[i], n, rng_uniform(g), rng_uniform(g), 3 + rng_uniform(g), 2 + rng_uniform(g), rng_uniform(g) * 6);
      ps[i] = (sg_poly){n, 1.5 * i, buf[i]};
    }
    contour_stack s;
    if (sg_make_stack(ps, k, NULL, NULL, NULL, &s) != 0) continue;
    char err[512];
    int res;
    stack_surface *ss = tile(&s, 0, 0, 1, NULL, err, sizeof err, &res);
    if (res != 0) {
      bad++;
      contour_stack_free(&s);
      continue;
    }
    /* the pair tiler on the contours from their least points */
    for (int i = 0; i < s.n; i++) {
      contour *c = &s.c[i];
      int least = 0;
      for (int j = 1; j < c->n; j++)
        if (exact_lex(c->pt[j], c->pt[least]) < 0) least = j;
      vec2 *t = xmallocarray((size_t)c->n, sizeof *t);
      for (int j = 0; j < c->n; j++) t[j] = c->pt[(least + j) % c->n];
      memcpy(c->pt, t, (size_t)c->n * sizeof *t);
      free(t);
    }
    mesh me;
    mesh_init(&me, &s);
    for (int i = 0; i + 1 < s.n; i++) {
      tiling t;
      double a, v;
      tiling_solve(s.c[i].pt, s.c[i].n, s.c[i].z, s.c[i + 1].pt, s.c[i + 1].n, s.c[i + 1].z, COST_AREA, -1, &t);
      mesh_add_band(&me, &s, i, &t, &a, &v);
      tiling_free(&t);
    }
    const mesh *m2 = stack_mesh(ss);
    if (!(me.nv == m2->nv && me.nt == m2->nt && memcmp(me.v, m2->v, (size_t)me.nv * sizeof *me.v) == 0 &&
          memcmp(me.t, m2->t, (size_t)me.nt * sizeof *me.t) == 0))
      bad++;
    mesh_free(&me);
    stack_free(ss);
    contour_stack_free(&s);
  }
  CHECK(bad == 0, "%d of 40 one-contour stacks tiled otherwise than by the pair tiler", bad);
  band_mode = STACK_BAND_ALIGNED;
}

/* tinypatient_0 and a branching stack: the same bytes whatever the file's
 * order, starts and windings; on 1 and 4 threads; and with the paper's
 * parallel algorithm on the simulator. */
static void test_invariance(rng *g) {
  enum { N = 16 };
  vec2 buf[8][N];
  sg_poly ps[8];
  int np = 0;
  sg_circle(buf[np], N, -2, 0, 1, 1, 0), ps[np] = (sg_poly){N, 0, buf[np]}, np++;
  sg_circle(buf[np], N, 2, 0, 1, 1, 0.3), ps[np] = (sg_poly){N, 0, buf[np]}, np++;
  sg_circle(buf[np], N, 0, 0, 3.5, 1.5, 0.1), ps[np] = (sg_poly){N, 1, buf[np]}, np++;
  sg_circle(buf[np], N, 0, 0, 3.5, 1.5, 0.2), ps[np] = (sg_poly){N, 2, buf[np]}, np++;
  sg_circle(buf[np], N, 0, 0, 1, 0.5, 0.7), ps[np] = (sg_poly){N, 2, buf[np]}, np++;   /* a hole */
  sg_circle(buf[np], N, -2, 0.5, 1, 1, 0.4), ps[np] = (sg_poly){N, 3, buf[np]}, np++;
  sg_circle(buf[np], N, 2, -0.5, 1, 1, 0.5), ps[np] = (sg_poly){N, 3, buf[np]}, np++;
  char err[512];
  int res;
  contour_stack s;
  if (sg_make_stack(ps, np, NULL, NULL, NULL, &s) != 0) return;
  stack_surface *ref = tile(&s, 1, 0, 1, NULL, err, sizeof err, &res);
  CHECK(res == 0, "branching: %s", err);
  contour_stack_free(&s);
  if (res != 0) return;
  /* Two legs into one body into two legs (genus 0), and the hole alone on
   * its slice: a lens-shaped cavity, a component of its own. */
  int chi[2] = {2, 2};
  check_surface("branches", ref, ps, np, 2, chi);
  int bad = 0;
  for (int trial = 0; trial < 20; trial++) {
    int order[8], start[8], rev[8];
    for (int i = 0; i < np; i++) order[i] = i, start[i] = rng_int(g, 0, N - 1), rev[i] = rng_int(g, 0, 1);
    for (int i = np - 1; i > 0; i--) {
      int j = rng_int(g, 0, i), t = order[i];
      order[i] = order[j], order[j] = t;
    }
    if (sg_make_stack(ps, np, order, start, rev, &s) != 0) continue;
    stack_surface *ss = tile(&s, 1, 0, trial % 4 + 1, NULL, err, sizeof err, &res);
    if (res != 0 || !same_mesh(stack_mesh(ref), stack_mesh(ss))) bad++;
    stack_free(ss);
    contour_stack_free(&s);
  }
  CHECK(bad == 0, "%d of 20 shuffled, restarted, reversed stacks (on 1-4 threads) differ", bad);
  /* The paper's parallel algorithm on the simulated machine: the same mesh. */
  if (sg_make_stack(ps, np, NULL, NULL, NULL, &s) == 0) {
    par_machine rc;
    par_machine_init(&rc);
    rc.mc.procs = 3;
    stack_surface *ss = tile(&s, 1, 0, 2, &rc, err, sizeof err, &res);
    CHECK(res == 0 && same_mesh(stack_mesh(ref), stack_mesh(ss)), "--procs 3 on the simulator: %s", res ? err : "differs");
    CHECK(res != 0 || stack_pairs(ss)[0].time > 0, "no simulated time");
    stack_free(ss);
    contour_stack_free(&s);
  }
  stack_free(ref);
}

/* Nesting: depth, parents and winding by depth, whatever the file says. */
static void test_nesting(rng *g) {
  enum { N = 12 };
  vec2 buf[6][N];
  sg_poly ps[6];
  double r[6] = {10, 6, 3, 2, 1, 0.5}, cx[6] = {0, 0, 0, 20, 20, 0};
  /* O > H > I on the left, O2 > H2 on the right, and a second slice. */
  int depth[6] = {0, 1, 2, 0, 1, 0};
  for (int i = 0; i < 6; i++) sg_circle(buf[i], N, cx[i], 0, r[i], r[i], 0.1 * i), ps[i] = (sg_poly){N, i == 5 ? 1 : 0, buf[i]};
  slices ref;
  char err[512];
  int bad = 0;
  for (int trial = 0; trial < 30; trial++) {
    int order[6], start[6], rev[6];
    for (int i = 0; i < 6; i++) order[i] = i, start[i] = rng_int(g, 0, N - 1), rev[i] = rng_int(g, 0, 1);
    for (int i = 5; i > 0; i--) {
      int j = rng_int(g, 0, i), t = order[i];
      order[i] = order[j], order[j] = t;
    }
    contour_stack s;
    if (sg_make_stack(ps, 6, trial ? order : NULL, trial ? start : NULL, trial ? rev : NULL, &s) != 0) continue;
    slices sl;
    if (slices_build(&s, "t.contours", 2, &sl, err, sizeof err) != 0) {
      bad++;
      contour_stack_free(&s);
      continue;
    }
    if (trial == 0) {
      ref = sl;
      CHECK(sl.nslices == 2 && sl.first[1] == 5, "slices: %d, first %d", sl.nslices, sl.first[1]);
      for (int c = 0; c < 5; c++) {
        const slice_contour *x = &sl.c[c];
        int want = -1;   /* which input contour: by its least point's x */
        for (int i = 0; i < 5; i++)
          if (fabs(x->pt[0].x - (cx[i] - r[i])) < 1e-6 * r[i] + 0.5 && fabs(x->area2 / 2) > 2 * r[i] * r[i] &&
              fabs(x->area2 / 2) < 3.2 * r[i] * r[i])
            want = i;
        CHECK(want >= 0 && x->depth == depth[want], "contour %d: depth %d", c, x->depth);
        CHECK((x->area2 > 0) == (x->depth % 2 == 0), "contour %d at depth %d runs the wrong way", c, x->depth);
        CHECK((x->parent < 0) == (x->depth == 0) && (x->parent < 0 || sl.c[x->parent].depth == x->depth - 1),
              "contour %d: parent %d", c, x->parent);
        for (int k = 1; k < x->n; k++) CHECK(exact_lex(x->pt[0], x->pt[k]) < 0, "contour %d: not from its least point", c);
      }
    } else {
      int same = sl.ncontours == ref.ncontours;
      for (int c = 0; same && c < sl.ncontours; c++)
        same = sl.c[c].n == ref.c[c].n && sl.c[c].depth == ref.c[c].depth && sl.c[c].parent == ref.c[c].parent &&
               memcmp(sl.c[c].pt, ref.c[c].pt, (size_t)sl.c[c].n * sizeof(vec2)) == 0;
      bad += !same;
      slices_free(&sl);
    }
    contour_stack_free(&s);
  }
  CHECK(bad == 0, "%d of 29 reordered, restarted, reversed stacks gave other canonical slices", bad);
  slices_free(&ref);
}

/* Two small offset diamonds: the optimum fans one from a vertex of the other
 * (a span used twice); the surface uses the cheapest path that does not. */
static void test_pinched(void) {
  stack_band keep = band_mode;
  band_mode = STACK_BAND_PLAIN;   /* the pair as it lies (aligned, the diamonds do not pinch) */
  vec2 a[4] = {{54.25, -232.35}, {52.74, -231.28}, {54.25, -230.2}, {55.44, -231.28}};
  vec2 b[4] = {{56.4, -232.35}, {54.38, -231.28}, {56.4, -230.2}, {57.47, -231.28}};
  sg_poly ps[2] = {{4, -23.44, a}, {4, -20.44, b}};
  tiling t;
  tiling_solve(a, 4, -23.44, b, 4, -20.44, COST_AREA, -1, &t);
  CHECK(unpinch_repeats(&t), "the diamonds' optimum no longer uses a span twice: the test does not test");
  contour_stack s;
  char err[512];
  int res;
  if (sg_make_stack(ps, 2, NULL, NULL, NULL, &s) == 0) {
    stack_surface *ss = tile(&s, 1, 0, 1, NULL, err, sizeof err, &res);
    CHECK(res == 0, "diamonds: %s", err);
    int chi[1] = {2};
    if (res == 0) {
      check_surface("diamonds", ss, ps, 2, 1, chi);
      CHECK(stack_rows(ss)[0].cost > t.cost, "the manifold band costs %.17g, the optimum %.17g", stack_rows(ss)[0].cost, t.cost);
      CHECK(stack_rows(ss)[0].spans == 1, "the band's row reports %d spans used twice, want 1", stack_rows(ss)[0].spans);
    }
    stack_free(ss);
    contour_stack_free(&s);
  }
  tiling_free(&t);
  band_mode = keep;
}

/* Random stacks: discs placed at random on each slice (so that neighbouring
 * slices overlap at random: branching, merging, ends), some with a hole and
 * some holes with an island; flat and apex caps.  Every one must give a
 * good surface. */
static void test_random(rng *g) {
  static vec2 buf[SG_MAXP][SG_N];
  int bad = 0, bridges = 0, stacks = 0;
  for (int trial = 0; trial < 60; trial++) {
    sg_poly ps[SG_MAXP];
    int np = sg_random(g, buf, ps);
    contour_stack s;
    if (sg_make_stack(ps, np, NULL, NULL, NULL, &s) != 0) continue;
    for (int apex = 0; apex < 2; apex++) {
      char err[512], what[64];
      int res;
      stack_surface *ss = tile(&s, 1, apex, 2, NULL, err, sizeof err, &res);
      CHECK(res == 0, "random stack %d: %s", trial, err);
      if (res != 0) {
        bad++;
        continue;
      }
      snprintf(what, sizeof what, "random stack %d%s", trial, apex ? ", apex caps" : "");
      int before = check_failed;
      check_surface(what, ss, ps, np, -1, NULL);
      bad += check_failed > before;
      stacks++;
      for (int i = 0; i < stack_nrows(ss); i++) bridges += stack_rows(ss)[i].kind == STACK_BAND ? stack_rows(ss)[i].bridges : 0;
      stack_free(ss);
    }
    contour_stack_free(&s);
  }
  CHECK(bad == 0 && stacks > 100, "random stacks: %d of %d bad", bad, stacks);
  CHECK(bridges > 20, "only %d bridges in the random stacks: the test does not test branching", bridges);
}

static void test_refusals(void) {
  vec2 a[3] = {{0, 0}, {1, 0}, {0, 1}}, b[3] = {{0.5, -1}, {3, -1}, {0.5, 0.5}};
  sg_poly ps[3] = {{3, 1, a}, {3, 1, b}, {3, 2, a}};
  contour_stack s;
  char err[512];
  int res;
  /* Read from a file, the two crossing contours are merged into their union
   * (input/slicemerge.h); handed to the surface as they are, refused. */
  if (sg_make_stack(ps, 3, NULL, NULL, NULL, &s) == 0) {
    stack_surface *ss = tile(&s, 1, 0, 2, NULL, err, sizeof err, &res);
    CHECK(res == 0 && s.n == 2, "crossing, read: %d, %d contours '%s'", res, s.n, res ? err : "");
    stack_free(ss);
    contour_stack_free(&s);
  }
  vec2 pa[3] = {{0, 0}, {1, 0}, {0, 1}}, pb[3] = {{0.5, -1}, {3, -1}, {0.5, 0.5}}, pc[3] = {{0, 0}, {1, 0}, {0, 1}};
  contour raw[3] = {{1, 3, pa, 1, 0, 0}, {1, 3, pb, 5, 0, 0}, {2, 3, pc, 9, 1, 0}};
  contour_stack rs = {3, raw, 2};
  stack_surface *sr = tile(&rs, 1, 0, 2, NULL, err, sizeof err, &res);
  CHECK(res == -1 && sr == NULL && strcmp(err, "t.contours:5: contour crosses the contour at line 1 on slice z=1 (0.5 0)") == 0,
        "crossing: %d '%s'", res, err);
  stack_free(sr);
  /* Two squares, a wall between them, one U-shaped contour above: no bridge
   * can join the squares, so the U joins one of them (the first, in
   * canonical order), the other ends, capped (it was refused before): three
   * closed components, the join dropped counted. */
  vec2 s1[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, s2[4] = {{10, 0}, {11, 0}, {11, 1}, {10, 1}};
  vec2 wall[4] = {{5, -10}, {6, -10}, {6, 11}, {5, 11}};
  vec2 u[8] = {{-1, 2}, {-1, -12}, {12, -12}, {12, 2}, {9, 2}, {9, -11}, {2, -11}, {2, 2}};
  sg_poly q[4] = {{4, 0, s1}, {4, 0, s2}, {4, 0, wall}, {8, 1, u}};
  if (sg_make_stack(q, 4, NULL, NULL, NULL, &s) == 0) {
    stack_surface *ss = tile(&s, 1, 0, 1, NULL, err, sizeof err, &res);
    CHECK(res == 0, "no bridge: %d '%s'", res, err);
    if (res == 0) {
      int chi[3] = {2, 2, 2};
      check_surface("no bridge", ss, q, 4, 3, chi);
      const stack_row *r = stack_rows(ss);
      CHECK(stack_join_counts(ss)->dropped == 1 && r[0].kind == STACK_BAND && r[0].nlo == 1 && r[0].nhi == 1 &&
                r[0].lo[0] == 0 && (r[1].kind != STACK_BAND),
            "no bridge: not one band from the first square, one join dropped (%d)", stack_join_counts(ss)->dropped);
    }
    stack_free(ss);
    contour_stack_free(&s);
  }
}

/* ------------------------------------------------------------- unpinch -- */

/* Every path of the pair by brute force: the cheapest that uses no span
 * twice (checked on the spans themselves), in quanta. */
static double brute_unpinched(const weights *w) {
  int m = w->m, n = w->n, L = m + n;
  double best = HUGE_VAL;
  for (int s = 0; s < m; s++)
    for (unsigned mask = 0; mask < (1u << L); mask++) {   /* bit set: a vertical step */
      if (__builtin_popcount(mask) != m) continue;
      int r = s, c = 0, ok = 1;
      double cost = 0;
      char seen[8][8] = {{0}};
      seen[r % m][0] = 1;
      for (int t = 0; t < L; t++) {
        if (mask >> t & 1) cost += weights_v(w, r, c), r++;
        else cost += weights_h(w, r, c), c++;
        if (t + 1 < L) {
          if (seen[r % m][c % n]) ok = 0;
          seen[r % m][c % n] = 1;
        }
      }
      if (ok && cost < best) best = cost;
    }
  return best;
}

static void test_unpinch(rng *g) {
  int bad = 0, tried = 0, pinched = 0;
  for (int trial = 0; trial < 300; trial++) {
    int np = rng_int(g, 3, 6), nq = rng_int(g, 3, 6);
    vec2 p[6], q[6];
    double off = trial % 3 ? 4 * rng_uniform(g) : 0;
    sg_circle(p, np, 0, 0, 0.3 + rng_uniform(g), 0.3 + rng_uniform(g), rng_uniform(g));
    sg_circle(q, nq, off, 0, 0.3 + 2 * rng_uniform(g), 0.3 + rng_uniform(g), rng_uniform(g));
    tiling t, u;
    tiling_solve(p, np, 0, q, nq, 1, COST_AREA, -1, &t);
    pinched += unpinch_repeats(&t);
    if (unpinch_solve(p, np, 0, q, nq, 1, COST_AREA, 0, &u) != 0) {
      bad++;
      tiling_free(&t);
      continue;
    }
    tried++;
    int tr = nq < np;
    weights *w = tr ? weights_new(q, nq, 1, p, np, 0, COST_AREA, 0) : weights_new(p, np, 0, q, nq, 1, COST_AREA, 0);
    double want = brute_unpinched(w);
    if (u.quanta != want || unpinch_repeats(&u)) bad++;
    if (!unpinch_repeats(&t) && t.quanta != u.quanta) bad++;   /* a manifold optimum is kept */
    weights_free(w);
    tiling_free(&t);
    tiling_free(&u);
  }
  CHECK(bad == 0, "unpinch: %d of %d pairs disagree with brute force", bad, tried);
  CHECK(pinched > 5, "only %d of 300 pairs had a pinched optimum: the test does not test", pinched);
}

static void count_job(void *ud, int i) {
  int *hits = ud;
  __atomic_fetch_add(&hits[i], 1, __ATOMIC_RELAXED);
}

static void test_pool(void) {
  int hits[100] = {0}, order[100];
  double size[100];
  for (int i = 0; i < 100; i++) size[i] = (i * 37) % 11;
  pool_order(size, 100, order);
  int sorted = 1;
  for (int i = 1; i < 100; i++)
    sorted &= size[order[i - 1]] > size[order[i]] || (size[order[i - 1]] == size[order[i]] && order[i - 1] < order[i]);
  CHECK(sorted, "pool_order: not by decreasing size, ties by index");
  pool_run(7, 100, order, count_job, hits);
  int once = 1;
  for (int i = 0; i < 100; i++) once &= hits[i] == 1;
  CHECK(once, "pool_run: a job ran other than once");
  CHECK(pool_cores() >= 1, "pool_cores");
}

int main(void) {
  rng g;
  rng_seed(&g, 909);
  test_pool();
  test_overlap(&g);
  test_unpinch(&g);
  test_pairs(&g);
  test_shapes();
  test_invariance(&g);
  test_refusals();
  test_random(&g);
  test_nesting(&g);
  test_pinched();
  return check_done("test_stack");
}
