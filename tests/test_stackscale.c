/* test_stackscale.c -- the stack surface (surface/stack.h), several
 * contours a slice, at every scale.
 *
 * Stacks: tinypatient_0 and prostate stacks (tests/data/slicerrt), the
 * analytic solids (tests/solids.h: branching, holes, cavities, islands) and
 * random multi-contour stacks (tests/stackgen.h), the last two rounded to a
 * grid of 2^-14 so that they stay exact down to 2^-1060.  Each is scaled by
 * 2^k, k from -1070 to +1016 (wherever every scaled coordinate is exact and
 * finite), written as text and read back (so the reader's slice grouping is
 * in it too), tiled, and compared with the same stack at unit scale:
 *   - the same rows (junctions, contours, m, n, bridges, nodes, spans), the
 *     same mesh triangles (vertex indices) and components (V, E, F, Euler
 *     characteristic, genus), bit for bit;
 *   - z, coordinates, costs, areas and volumes exactly 2^k, 2^(dk), 2^2k,
 *     2^3k times the unit-scale ones (d: the cost's degree), as ldexp gives
 *     them: inf or 0 where they lie beyond a double, never NaN;
 *   - the scaled mesh judged by the independent checker (tests/meshcheck.h):
 *     closed, outward, the same components and Euler characteristics, its
 *     volume exactly 2^3k times the unit mesh's, every input point a vertex
 *     and every input segment an edge, no stray vertex, nothing across a
 *     plane (where every vertex of the scaled mesh is an exact scaling);
 *   - by 1e300 and 1e-300 (not powers of two): with the paper's plain bands
 *     the same triangles (but for exact ties the rounding breaks), and the
 *     aligned bands' mesh (other corners where rounding made collinear points
 *     not collinear) the same components, by the checker;
 *   - the paper's parallel algorithm (simulated) at 2^-1000 gives the serial
 *     unit-scale result scaled;
 *   - messages (a crossing, a bridge that cannot be made, a bridge across
 *     the other slice, a pinched band, snapped z values) name the file's own
 *     values: every number in them 2^k (2^dk for a cost) times the unit one. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/contour.h"
#include "tests/meshcheck.h"
#include "tests/reference.h"
#include "util/rng.h"
#include "tests/parmachine.h"
#include "tests/solids.h"
#include "surface/stack.h"
#include "tests/stackgen.h"
#include "util/xmem.h"

/* ------------------------------------------------------------ helpers -- */

typedef struct {
  int caps, apex;
  cost_kind kind;
  par_machine *rc;
} how;

/* How tile() tiles a 1-1 band: aligned (the default), or plain for the
 * stacks scaled by decimal factors (below). */
static stack_band band_mode = STACK_BAND_ALIGNED;

static stack_surface *tile(const contour_stack *s, how h, char *notes, size_t nlen, char *err, size_t errlen,
                           int *res) {
  stack_tiler tl = h.rc ? par_machine_tiler(h.rc) : (stack_tiler){NULL, NULL};
  stack_options o = {h.kind, h.caps, h.apex, 2, h.rc ? &tl : NULL, NULL, "test", NULL, NULL, MATCH_SINGLE, INFINITY, 0, band_mode};
  return sg_tile(s, o, notes, nlen, err, errlen, res);
}

/* The stack s times f (= 2^k when pow2), through the writer and the reader.
 * 0, 1 when some scaled value is inexact or not finite (skip), -1 on a
 * failure to read it back (a failed CHECK). */
static int scaled(const contour_stack *s, int k, double f, int pow2, contour_stack *out, char *notes, size_t nlen) {
  contour_stack t = *s;
  t.c = xmallocarray((size_t)s->n, sizeof *t.c);
  int exact = 1;
  for (int i = 0; i < s->n; i++) {
    t.c[i] = s->c[i];
    t.c[i].pt = xmallocarray((size_t)s->c[i].n, sizeof(vec2));
    double z = pow2 ? ldexp(s->c[i].z, k) : s->c[i].z * f;
    exact &= isfinite(z) && (!pow2 || ldexp(z, -k) == s->c[i].z);
    t.c[i].z = z;
    for (int j = 0; j < s->c[i].n; j++) {
      vec2 p = s->c[i].pt[j], q = pow2 ? (vec2){ldexp(p.x, k), ldexp(p.y, k)} : (vec2){p.x * f, p.y * f};
      exact &= isfinite(q.x) && isfinite(q.y) && (!pow2 || (ldexp(q.x, -k) == p.x && ldexp(q.y, -k) == p.y));
      t.c[i].pt[j] = q;
    }
  }
  int rc = 1;
  if (exact) {
    char *text = NULL, err[512], *nb = NULL;
    size_t len = 0, nl = 0;
    FILE *w = open_memstream(&text, &len), *nf = open_memstream(&nb, &nl);
    contour_write(w, &t);
    fclose(w);
    rc = contour_parse(text, len, "t.contours", out, nf, "test", err, sizeof err);
    fclose(nf);
    CHECK(rc == 0, "2^%d: the scaled stack is not read back: %s", k, err);
    if (notes) snprintf(notes, nlen, "%s", nb ? nb : "");
    free(nb);
    free(text);
  }
  for (int i = 0; i < s->n; i++) free(t.c[i].pt);
  free(t.c);
  return rc;
}

static int ties;   /* bands that took another, equally cheap path (decimal factors) */

static double tri_area(const mesh *me, const int *t) {
  vec3 a = me->v[t[0]], b = me->v[t[1]], c = me->v[t[2]];
  double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  double x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
  return 0.5 * sqrt(x * x + y * y + z * z);
}

/* got is unit times 2^(d k), as one ldexp gives it (no NaN). */
static int at(double got, double unit, int d, int k) { return got == ldexp(unit, d * k) && !isnan(got); }

static int same_ints(const int *a, const int *b, int n) { return n == 0 || memcmp(a, b, (size_t)n * sizeof *a) == 0; }

/* Everything of s against its unit-scale u, with values exactly scaled by
 * 2^k (values = 0: structure only, for decimal factors).  Returns the
 * number of differences, naming the first. */
static int compare(const char *what, const stack_surface *u, const stack_surface *s, int k, int deg, int values) {
  int bad = 0;
  char first[1024] = "";
#define DIFF(...) \
  do { \
    if (!bad++) snprintf(first, sizeof first, __VA_ARGS__); \
  } while (0)
  int nr = stack_nrows(u);
  if (stack_nrows(s) != nr) DIFF("%d rows, at unit scale %d", stack_nrows(s), nr);
  for (int i = 0; i < nr && !bad; i++) {
    const stack_row *a = &stack_rows(u)[i], *b = &stack_rows(s)[i];
    if (a->kind != b->kind || a->slice0 != b->slice0 || a->slice1 != b->slice1 || a->depth != b->depth ||
        a->nlo != b->nlo || a->nhi != b->nhi || !same_ints(a->lo, b->lo, a->nlo) || !same_ints(a->hi, b->hi, a->nhi) ||
        a->m != b->m || a->n != b->n || a->bridges != b->bridges || (values && a->nodes != b->nodes) || a->spans != b->spans)
      DIFF("row %d: junction %d-%d, m %d, n %d, %d bridges, %llu nodes, %d spans; at unit scale %d-%d, %d, %d, %d, "
           "%llu, %d", i, b->nlo, b->nhi, b->m, b->n, b->bridges, b->nodes, b->spans, a->nlo, a->nhi, a->m, a->n,
           a->bridges, a->nodes, a->spans);
    else if (values && (!at(b->z0, a->z0, 1, k) || !at(b->z1, a->z1, 1, k) ||
                        (a->kind == STACK_BAND && !at(b->cost, a->cost, deg, k)) || !at(b->area, a->area, 2, k) ||
                        !at(b->volume, a->volume, 3, k)))
      DIFF("row %d: z %.17g %.17g, cost %.17g, area %.17g, volume %.17g; at unit scale %.17g %.17g %.17g %.17g %.17g", i,
           b->z0, b->z1, b->cost, b->area, b->volume, a->z0, a->z1, a->cost, a->area, a->volume);
  }
  const mesh *mu = stack_mesh(u), *ms = stack_mesh(s);
  if (mu->nv != ms->nv || mu->nt != ms->nt)
    DIFF("%d vertices, %d triangles; at unit scale %d, %d", ms->nv, ms->nt, mu->nv, mu->nt);
  /* Band by band (the tiles, m + n, then 4 fill triangles a bridge); then
   * the caps.  A stack not scaled exactly is another input, rounded: where
   * the unit-scale one has an exact tie (a grid's equal tiles, equally near
   * points of a hole to cut a flat cap at), the rounding may break it the
   * other way.  So a band may take another path only of the same area (on
   * the unit-scale vertices, to 1e-12), and the caps other triangles of the
   * same area; the checker judges the result. */
  for (int i = 0, t0 = 0; i < nr && !bad; i++) {
    const stack_row *a = &stack_rows(u)[i];
    int nt = a->kind == STACK_BAND ? a->m + a->n + 4 * a->bridges : mu->nt - t0;
    if (memcmp(mu->t + t0, ms->t + t0, (size_t)nt * sizeof *mu->t) != 0) {
      double au = 0, as = 0;
      for (int t = t0; t < t0 + nt; t++) au += tri_area(mu, mu->t[t]), as += tri_area(mu, ms->t[t]);
      if (values || fabs(as - au) > 1e-12 * au)
        DIFF("row %d: other triangles (from %d of %d), of area %.17g at unit scale, the unit-scale ones %.17g", i, t0,
             nt, as, au);
      else
        ties++;
    }
    if (a->kind == STACK_BAND) t0 += nt;
    else break;
  }
  for (int v = 0; v < mu->nv && values && !bad; v++)
    if (!at(ms->v[v].x, mu->v[v].x, 1, k) || !at(ms->v[v].y, mu->v[v].y, 1, k) || !at(ms->v[v].z, mu->v[v].z, 1, k))
      DIFF("vertex %d at (%.17g %.17g %.17g), at unit scale (%.17g %.17g %.17g)", v, ms->v[v].x, ms->v[v].y,
           ms->v[v].z, mu->v[v].x, mu->v[v].y, mu->v[v].z);
  int nc = stack_ncomponents(u);
  if (stack_ncomponents(s) != nc) DIFF("%d components, at unit scale %d", stack_ncomponents(s), nc);
  for (int i = 0; i < nc && !bad; i++) {
    const manifold_component *a = &stack_components(u)[i], *b = &stack_components(s)[i];
    if (a->nv != b->nv || a->ne != b->ne || a->nt != b->nt || a->closed != b->closed || a->manifold != b->manifold ||
        a->euler != b->euler || a->genus != b->genus || a->first != b->first)
      DIFF("component %d: another size, Euler characteristic or genus", i);
    else if (values && (!at(b->zmin, a->zmin, 1, k) || !at(b->zmax, a->zmax, 1, k) || !at(b->area, a->area, 2, k) ||
                        !at(b->volume, a->volume, 3, k)))
      DIFF("component %d: z %.17g..%.17g, area %.17g, volume %.17g; at unit scale %.17g..%.17g %.17g %.17g", i,
           b->zmin, b->zmax, b->area, b->volume, a->zmin, a->zmax, a->area, a->volume);
  }
  double cu, au, vu, cs, as, vs;
  stack_totals(u, &cu, &au, &vu);
  stack_totals(s, &cs, &as, &vs);
  if (values && !bad && (!at(cs, cu, deg, k) || !at(as, au, 2, k) || !at(vs, vu, 3, k)))
    DIFF("totals: cost %.17g, area %.17g, volume %.17g; at unit scale %.17g %.17g %.17g", cs, as, vs, cu, au, vu);
#undef DIFF
  CHECK(bad == 0, "%s: %d differences from unit scale; the first: %s", what, bad, first);
  return bad;
}

/* The independent checker on the mesh of s (tiled from the stack st): a
 * closed, outward 2-manifold (when closed) through every input segment.  *vol, *ncomp,
 * chi[] (up to 8) get its measures for comparison. */
static void judge(const char *what, const stack_surface *s, const contour_stack *st, int closed, double *vol,
                  int *ncomp, int *chi) {
  const mesh *me = stack_mesh(s);
  mc_mesh m;
  ref_mc_mesh(&m, me);
  mc_report r;
  mc_check(&m, &r);
  CHECK(!closed || (r.manifold && r.outward), "%s: the checker: not a closed outward manifold: %s", what, r.first);
  *vol = r.volume, *ncomp = r.ncomp;
  for (int c = 0; c < r.ncomp && c < 8; c++) chi[c] = r.chi[c];
  mc_poly *cp = xmallocarray((size_t)st->n, sizeof *cp);
  double **xs = xmallocarray((size_t)st->n, sizeof *xs), **ys = xmallocarray((size_t)st->n, sizeof *ys);
  for (int i = 0; i < st->n; i++) {
    xs[i] = xmallocarray((size_t)st->c[i].n, sizeof **xs), ys[i] = xmallocarray((size_t)st->c[i].n, sizeof **ys);
    for (int k = 0; k < st->c[i].n; k++) xs[i][k] = st->c[i].pt[k].x, ys[i][k] = st->c[i].pt[k].y;
    cp[i] = (mc_poly){st->c[i].n, st->c[i].z, xs[i], ys[i]};
  }
  mc_fidelity fd;
  mc_check_input(&m, cp, st->n, &fd);
  CHECK(fd.missing == 0 && fd.absent == 0 && fd.strays == 0 && fd.crossing == 0,
        "%s: the checker: %d segments missing, %d points absent, %d strays, %d crossing", what, fd.missing,
        fd.absent, fd.strays, fd.crossing);
  for (int i = 0; i < st->n; i++) free(xs[i]), free(ys[i]);
  free(xs), free(ys), free(cp);
  mc_fidelity_free(&fd);
  mc_report_free(&r);
  mc_free(&m);
}

/* Every vertex of s is exactly 2^k times u's (so the checker sees the same
 * shape, and its volume must be exactly scaled). */
static int exact_mesh(const stack_surface *u, const stack_surface *s, int k) {
  const mesh *a = stack_mesh(u), *b = stack_mesh(s);
  for (int v = 0; v < a->nv; v++)
    if (!isfinite(b->v[v].x) || !isfinite(b->v[v].y) || !isfinite(b->v[v].z) || ldexp(b->v[v].x, -k) != a->v[v].x ||
        ldexp(b->v[v].y, -k) != a->v[v].y || ldexp(b->v[v].z, -k) != a->v[v].z)
      return 0;
  return 1;
}

static const int KS[] = {-1070, -1066, -1062, -1060, -1055, -1050, -1040, -1030, -1024, -1023, -1022, -1021, -1000,
                         -999,  -900,  -700,  -601,  -600,  -540,  -512,  -511,  -500,  -400,  -300,  -200,  -100,
                         -37,   -1,    1,     2,     29,    100,   200,   300,   340,   341,   400,   500,   511,
                         512,   513,   600,   700,   900,   1000,  1005,  1010,  1016};
enum { NKS = sizeof KS / sizeof KS[0] };

static int tested_low, tested_high, judged_low, judged_high;

/* The stack at every k of KS (every `step`-th), and by 1e300 and 1e-300. */
static void sweep(const char *name, const contour_stack *s, how h, int step) {
  char err[512], what[160];
  int res, deg = h.kind == COST_SPAN ? 1 : 2;
  stack_surface *u = tile(s, h, NULL, 0, err, sizeof err, &res);
  CHECK(res == 0, "%s at unit scale: %s", name, err);
  if (res != 0) return;
  double uvol;
  int unc, uchi[8];
  snprintf(what, sizeof what, "%s at unit scale", name);
  judge(what, u, s, h.caps, &uvol, &unc, uchi);
  for (int i = 0; i < NKS + 2; i++) {
    if (i < NKS && i % step != 0 && KS[i] > -1060 && KS[i] < 1000) continue;
    int k = i < NKS ? KS[i] : 0, pow2 = i < NKS;
    double f = i == NKS ? 1e300 : 1e-300;
    if (pow2) snprintf(what, sizeof what, "%s at 2^%d", name, k);
    else snprintf(what, sizeof what, "%s times %g", name, f);
    contour_stack t;
    if (scaled(s, k, f, pow2, &t, NULL, 0) != 0) continue;
    stack_surface *ss = tile(&t, h, NULL, 0, err, sizeof err, &res);
    CHECK(res == 0, "%s: %s", what, err);
    if (res == 0 && !pow2) {
      /* Rounded, a point exactly on its neighbours' line may no longer be
       * (and the other way): the aligned band sees other corners, so the
       * triangles are compared on the plain bands; the aligned mesh is
       * judged by the checker below. */
      band_mode = STACK_BAND_PLAIN;
      int r1, r2;
      stack_surface *up = tile(s, h, NULL, 0, err, sizeof err, &r1), *sp = tile(&t, h, NULL, 0, err, sizeof err, &r2);
      band_mode = STACK_BAND_ALIGNED;
      CHECK(r1 == 0 && r2 == 0, "%s, plain bands: %s", what, err);
      if (r1 == 0 && r2 == 0) compare(what, up, sp, k, deg, 0);
      stack_free(up);
      stack_free(sp);
    }
    if (res == 0) {
      if (pow2) compare(what, u, ss, k, deg, pow2);
      if (pow2) tested_low += k <= -1060, tested_high += k >= 1000;
      if (!pow2 || exact_mesh(u, ss, k)) {
        double vol;
        int nc, chi[8];
        judge(what, ss, &t, h.caps, &vol, &nc, chi);
        CHECK(nc == unc && memcmp(chi, uchi, (size_t)(nc < 8 ? nc : 8) * sizeof *chi) == 0,
              "%s: the checker finds %d components (%d at unit scale) or other Euler characteristics", what, nc, unc);
        CHECK(!pow2 || at(vol, uvol, 3, k), "%s: the checker's volume %.17g, at unit scale %.17g", what, vol, uvol);
        if (pow2) judged_low += k <= -1000, judged_high += k >= 500;
      }
    }
    stack_free(ss);
    contour_stack_free(&t);
  }
  stack_free(u);
}

/* ------------------------------------------------------------- stacks -- */

/* Round every value of s to a multiple of 2^-q (exact at scales down to
 * 2^(q-1074)). */
static void round_to(contour_stack *s, int q) {
  for (int i = 0; i < s->n; i++) {
    s->c[i].z = ldexp(nearbyint(ldexp(s->c[i].z, q)), -q);
    for (int j = 0; j < s->c[i].n; j++)
      s->c[i].pt[j] = (vec2){ldexp(nearbyint(ldexp(s->c[i].pt[j].x, q)), -q),
                             ldexp(nearbyint(ldexp(s->c[i].pt[j].y, q)), -q)};
  }
}

/* A stack from polygons, rounded to 2^-14, read back through the reader (which
 * drops what the rounding repeated). */
static int gridded(const sg_poly *ps, int np, contour_stack *out) {
  contour_stack s;
  if (sg_make_stack(ps, np, NULL, NULL, NULL, &s) != 0) return -1;
  round_to(&s, 14);
  int rc = scaled(&s, 0, 1, 1, out, NULL, 0);
  contour_stack_free(&s);
  return rc;
}

static void test_real(void) {
  const char *files[] = {"tinypatient_0", "prostate_3", "prostate_1"};
  for (int f = 0; f < 3; f++) {
    char path[256], err[512];
    snprintf(path, sizeof path, "tests/data/slicerrt/%s.contours", files[f]);
    contour_stack s;
    int rc = contour_read(path, &s, NULL, "test", err, sizeof err);
    CHECK(rc == 0, "%s", err);
    if (rc != 0) continue;
    if (f == 0) {
      sweep("tinypatient_0", &s, (how){1, 0, COST_AREA, NULL}, 1);
      sweep("tinypatient_0 apex", &s, (how){1, 1, COST_AREA, NULL}, 3);
      sweep("tinypatient_0 span, open", &s, (how){0, 0, COST_SPAN, NULL}, 4);
      /* The paper's parallel algorithm on the simulator, at 2^-1000: the
       * serial unit-scale result, scaled. */
      par_machine rc3;
      par_machine_init(&rc3);
      rc3.mc.procs = 3;
      int res, r2;
      stack_surface *u = tile(&s, (how){1, 0, COST_AREA, NULL}, NULL, 0, err, sizeof err, &res);
      contour_stack t;
      if (res == 0 && scaled(&s, -1000, 1, 1, &t, NULL, 0) == 0) {
        stack_surface *p = tile(&t, (how){1, 0, COST_AREA, &rc3}, NULL, 0, err, sizeof err, &r2);
        CHECK(r2 == 0, "tinypatient_0 at 2^-1000, --procs 3: %s", err);
        if (r2 == 0) {
          compare("tinypatient_0 at 2^-1000, --procs 3 on the simulator", u, p, -1000, 2, 1);
          CHECK(stack_pairs(p)[0].t.cost == stack_rows(p)[0].cost, "the parallel run's cost %.17g, the row's %.17g",
                stack_pairs(p)[0].t.cost, stack_rows(p)[0].cost);
        }
        stack_free(p);
        contour_stack_free(&t);
      }
      stack_free(u);
      /* Rounded to 2^-6 (exact down to 2^-1068). */
      round_to(&s, 6);
      sweep("tinypatient_0 on a 2^-6 grid", &s, (how){1, 0, COST_AREA, NULL}, 5);
    } else {
      sweep(files[f], &s, (how){1, f == 1, COST_AREA, NULL}, 6);
    }
    contour_stack_free(&s);
  }
}

static void test_solids(void) {
  enum { K = 11 };
  int n = 0;
  for (int i = 0; i < solid_count(); i++) {
    const solid_info *in = solid_get(i);
    if (!in->multi) continue;
    double z[K];
    solid_planes(i, K, 1, z);
    sl_stack st;
    solid_slice(i, z, K, 14, 1, &st);
    sg_poly *ps = xmallocarray((size_t)st.n, sizeof *ps);
    vec2 **pts = xmallocarray((size_t)st.n, sizeof *pts);
    for (int c = 0; c < st.n; c++) {
      pts[c] = xmallocarray((size_t)st.c[c].n, sizeof **pts);
      for (int j = 0; j < st.c[c].n; j++) pts[c][j] = (vec2){st.c[c].x[j], st.c[c].y[j]};
      ps[c] = (sg_poly){st.c[c].n, st.c[c].z, pts[c]};
    }
    contour_stack s;
    if (gridded(ps, st.n, &s) == 0) {
      char name[64];
      snprintf(name, sizeof name, "solid %s", in->name);
      sweep(name, &s, (how){1, n % 2, COST_AREA, NULL}, 4);
      contour_stack_free(&s);
      n++;
    }
    for (int c = 0; c < st.n; c++) free(pts[c]);
    free(pts), free(ps);
    sl_stack_free(&st);
  }
  CHECK(n >= 6, "only %d multi-contour solids", n);
}

static void test_random(void) {
  static vec2 buf[SG_MAXP][SG_N];
  sg_poly ps[SG_MAXP];
  rng g;
  rng_seed(&g, 1414);
  int branching = 0;
  for (int trial = 0; trial < 8; trial++) {
    int np = sg_random(&g, buf, ps);
    contour_stack s;
    if (gridded(ps, np, &s) != 0) continue;
    branching += s.n > s.nslices;
    char name[64];
    snprintf(name, sizeof name, "random stack %d", trial);
    sweep(name, &s, (how){1, trial % 2, COST_AREA, NULL}, 5);
    contour_stack_free(&s);
  }
  CHECK(branching >= 6, "only %d random stacks with several contours on a slice", branching);
}

/* ----------------------------------------------------------- messages -- */

/* Every number of msg (scaled by 2^k) is 2^k times the one in the same place
 * of unit (2^(dk) after the word "cost"); other words the same. */
static int same_message(const char *unit, const char *msg, int k, int deg) {
  const char *sep = " ()=,;:\n";
  char *a = xstrdup(unit), *b = xstrdup(msg), *sa, *sb;
  char *x = strtok_r(a, sep, &sa), *y = strtok_r(b, sep, &sb);
  int ok = 1, d = 1;
  while (ok && x && y) {
    if (strcmp(x, y) != 0) {
      char *ex, *ey;
      double u = strtod(x, &ex), v = strtod(y, &ey);
      ok = *ex == 0 && *ey == 0 && at(v, u, d, k);
    }
    d = strcmp(x, "cost") == 0 ? deg : 1;
    x = strtok_r(NULL, sep, &sa), y = strtok_r(NULL, sep, &sb);
  }
  ok &= !x && !y;
  free(a), free(b);
  return ok;
}

/* The stack of ps times 2^k (exactly; counter-clockwise, slices in
 * increasing z) as the readers never make it: contours of a slice that
 * cross kept as they are (the readers merge them into their union), lines
 * as the text would have them.  Free with contour_stack_free. */
static void raw_stack(const sg_poly *ps, int np, int k, contour_stack *s) {
  s->n = np, s->c = xcalloc((size_t)np, sizeof *s->c), s->nslices = 0;
  for (int i = 0, line = 1; i < np; line += ps[i].n + 1, i++) {
    contour *c = &s->c[i];
    c->z = ldexp(ps[i].z, k), c->n = ps[i].n, c->line = line;
    c->pt = xmallocarray((size_t)c->n, sizeof *c->pt);
    for (int j = 0; j < c->n; j++) c->pt[j] = (vec2){ldexp(ps[i].p[j].x, k), ldexp(ps[i].p[j].y, k)};
    c->slice = i == 0 ? 0 : s->c[i - 1].slice + (ps[i].z != ps[i - 1].z);
    s->nslices = c->slice + 1;
  }
}

/* The stack ps, unit and at 2^k: the refusal (want -1: of the stack as the
 * readers never make it, the surface's) or the notes. */
static void message_case(const char *what, const sg_poly *ps, int np, how h, int want, const char *needle) {
  contour_stack s;
  if (want < 0) raw_stack(ps, np, 0, &s);
  else if (sg_make_stack(ps, np, NULL, NULL, NULL, &s) != 0) return;
  char ue[512], un[2048];
  int res;
  stack_surface *u = tile(&s, h, un, sizeof un, ue, sizeof ue, &res);
  const char *umsg = want < 0 ? ue : un;
  CHECK(res == want && strstr(umsg, needle), "%s at unit scale: %d, '%s'", what, res, umsg);
  stack_free(u);
  int ks[] = {-1060, -1000, -500, 300, 1000};
  for (int i = 0; i < 5; i++) {
    contour_stack t;
    if (want < 0) raw_stack(ps, np, ks[i], &t);
    else if (scaled(&s, ks[i], 1, 1, &t, NULL, 0) != 0) continue;
    char e[512], n[2048];
    stack_surface *ss = tile(&t, h, n, sizeof n, e, sizeof e, &res);
    const char *msg = want < 0 ? e : n;
    CHECK(res == want && same_message(umsg, msg, ks[i], h.kind == COST_SPAN ? 1 : 2),
          "%s at 2^%d: %d, '%s'; at unit scale '%s'", what, ks[i], res, msg, umsg);
    stack_free(ss);
    contour_stack_free(&t);
  }
  contour_stack_free(&s);
}

static void test_messages(void) {
  /* Contours crossing on a slice, handed to the surface as they are. */
  vec2 a[3] = {{0, 0}, {1, 0}, {0, 1}}, b[3] = {{0.5, -1}, {3, -1}, {0.5, 0.5}};
  sg_poly p1[3] = {{3, 1.25, a}, {3, 1.25, b}, {3, 2.5, a}};
  message_case("crossing", p1, 3, (how){1, 0, COST_AREA, NULL}, -1, "crosses the contour at line 1 on slice z=1.25 (0.5 0)");
  /* No bridge: a wall between two squares under a U. */
  vec2 s1[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, s2[4] = {{10, 0}, {11, 0}, {11, 1}, {10, 1}};
  vec2 wall[4] = {{5, -10}, {6, -10}, {6, 11}, {5, 11}};
  vec2 u[8] = {{-1, 2}, {-1, -12}, {12, -12}, {12, 2}, {9, 2}, {9, -11}, {2, -11}, {2, 2}};
  sg_poly p2[4] = {{4, 0.5, s1}, {4, 0.5, s2}, {4, 0.5, wall}, {8, 1.75, u}};
  message_case("no bridge", p2, 4, (how){0, 0, COST_AREA, NULL}, 0,
               "not joined to the contour at line 16 on slice z=1.75 (their regions overlap): no bridges can join");
  /* A bridge across the other slice's contour: two squares under a U whose
   * wall lies between them (on the other slice), and a pinched band: two
   * offset diamonds (test_stack's), whose optimum fans from one vertex. */
  sg_poly p3[3] = {{4, 0.5, s1}, {4, 0.5, s2}, {8, 1.75, u}};
  message_case("relaxed bridge", p3, 3, (how){1, 0, COST_AREA, NULL}, 0, "crosses them in projection");
  vec2 d1[4] = {{54.25, -232.35}, {52.74, -231.28}, {54.25, -230.2}, {55.44, -231.28}};
  vec2 d2[4] = {{56.4, -232.35}, {54.38, -231.28}, {56.4, -230.2}, {57.47, -231.28}};
  sg_poly p4[2] = {{4, -23.44, d1}, {4, -20.44, d2}};
  band_mode = STACK_BAND_PLAIN;   /* aligned, the two diamonds do not pinch */
  message_case("pinched band", p4, 2, (how){1, 0, COST_AREA, NULL}, 0, "uses the span from");
  message_case("pinched band, span", p4, 2, (how){1, 0, COST_SPAN, NULL}, 0, "uses the span from");
  band_mode = STACK_BAND_ALIGNED;

  /* The reader's slices: z jittered by 2^-7 on slice 1 (two contours), at
   * 2^-1067 the z values are subnormal.  The same grouping and note. */
  vec2 q[4][4] = {{{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{0, 0}, {1, 0}, {1, 1}, {0, 1}},
                  {{2, 0}, {3, 0}, {3, 1}, {2, 1}}, {{0, 2}, {1, 2}, {1, 3}, {0, 3}}};
  sg_poly p5[6] = {{4, 0, q[0]}, {4, 1, q[1]}, {4, 1.0078125, q[2]}, {4, 1.015625, q[3]}, {4, 2, q[0]}, {4, 3, q[0]}};
  contour_stack s;
  if (sg_make_stack(p5, 6, NULL, NULL, NULL, &s) == 0) {
    CHECK(s.nslices == 4, "the jittered stack: %d slices, want 4", s.nslices);
    /* Unsnapped: the stack as written, before the reader. */
    for (int i = 0; i < 6; i++) s.c[i].z = p5[i].z;
    int ks[] = {0, -1067, -1000, 1000};
    for (int i = 0; i < 4; i++) {
      contour_stack t;
      char notes[512], want[512];
      if (scaled(&s, ks[i], 1, 1, &t, notes, sizeof notes) != 0) continue;
      snprintf(want, sizeof want,
               "test: t.contours:6: snapped the z of 2 contours to their slice's (at most %.3g away; slices are "
               "about %.3g apart)\n", ldexp(1, ks[i] - 7), ldexp(1, ks[i]));
      CHECK(t.nslices == 4 && strcmp(notes, want) == 0, "the jittered stack at 2^%d: %d slices, notes '%s', want '%s'",
            ks[i], t.nslices, notes, want);
      int same = 1;
      for (int c = 0; c < t.n; c++) same &= t.c[c].slice == s.c[c].slice;
      CHECK(same, "the jittered stack at 2^%d: other slices", ks[i]);
      contour_stack_free(&t);
    }
    contour_stack_free(&s);
  }
}

int main(void) {
  test_messages();
  test_real();
  test_solids();
  test_random();
  CHECK(tested_low >= 10 && tested_high >= 10, "only %d stacks tested at 2^-1060 and below, %d at 2^1000 and above",
        tested_low, tested_high);
  printf("test_stackscale: stacks exact at 2^-1060 and below %d, at 2^1000 and above %d; judged by the checker at "
         "2^-1000 and below %d, at 2^500 and above %d; %d bands or caps of stacks times 1e300 or 1e-300 broke a "
         "unit-scale tie the other way\n", tested_low, tested_high, judged_low, judged_high, ties);
  CHECK(judged_low >= 10 && judged_high >= 10, "only %d stacks judged by the checker at 2^-1000 and below, %d at "
        "2^500 and above", judged_low, judged_high);
  return check_done("test_stackscale");
}
