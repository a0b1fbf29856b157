/* test_faithful.c -- surfaces people can measure: volumes right
 * whatever the sampling, closed by default, real exports tiled.
 *
 *   - Analytic solids sampled sparsely and densely, tiled with the default
 *     options (aligned bands, caps): the shifted squares of the issue (4 and
 *     16 points each, 3 an edge, 4 against 16), oblique cylinders of 8- and
 *     64-gons, sheared ellipses, frustums of squares with collinear points,
 *     of 12- and 64-gons, of a star and an L, a cone stack: the volume by
 *     formula to 1e-12; the mesh closed and outward by the independent
 *     checker (tests/meshcheck.h), whose volume is the report's; the bands'
 *     and caps' volumes sum to the mesh's.  Without caps the mesh is open.
 *   - Every ROI of the real structure sets in tests/data (and the slicerrt
 *     stacks), default options: closed and outward by the checker, and the
 *     volume between the frustum rule (h/3 (A0 + A1 + sqrt(A0 A1)) a band:
 *     exact for similar sections) and the trapezoid rule (h (A0 + A1) / 2),
 *     to 2 %, the slices' areas summed here by shoelace and nesting by
 *     crossing number, with no code of the tiler's.
 *   - Forty structures drawn as planning systems draw them (ellipsoid
 *     profiles, elongated, drifting, turning, noisy, rounded to 0.01 mm):
 *     closed, and within 2 % of the trapezoid rule; the paper's algorithm
 *     on the simulator gives the same meshes, bit for bit.
 *   - What planning systems export, written by the tests' own DICOM writer
 *     (tests/rtwriter.c) with two decimals: cylinders in planes tilted 6 and
 *     35 degrees (tiled; the volume by formula to 0.3 %), one contour bent
 *     0.3 mm off its plane (refused, naming it); a Pinnacle-like tube with 84
 *     single points, two-point and collinear contours among its 12 (dropped,
 *     counted; the mesh the clean tube's, vertex for vertex); a hole sharing
 *     an edge with its outer contour, and one touching it at a point (the
 *     region's volume to 1e-9, with and without --union); two squares a
 *     slice touching at a corner (--union: split, the volume to 1e-9;
 *     without: refused); a lower contour under six squares in a row and in
 *     a grid (one closed component); a branching no bridge can join (a
 *     wall between two squares under a U: tiled, one join dropped, closed);
 *     and a set of ROIs of which some are refused, for --roi all.
 * With --write DIR the sets are written there as files, for
 * tests/cli_faithful.sh. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/contour.h"
#include "tests/meshcheck.h"
#include "tests/parmachine.h"
#include "tests/reference.h"
#include "input/rtstruct.h"
#include "tests/rtwriter.h"
#include "surface/stack.h"
#include "tests/stackgen.h"
#include "util/rng.h"
#include "util/xmem.h"

static const double PI = 3.14159265358979323846;

/* ------------------------------------------------------------ helpers -- */

static stack_surface *tile(const contour_stack *s, int caps, stack_band band, char *notes, size_t nlen, char *err,
                           size_t errlen, int *res) {
  stack_options o = {COST_AREA, caps, 0, 2, NULL, NULL, "test", NULL, NULL, MATCH_SINGLE, INFINITY, 0, band};
  return sg_tile(s, o, notes, nlen, err, errlen, res);
}

/* The checker's verdict on the mesh: 1 when closed and outward; its volume
 * and components. */
static int judge(const stack_surface *ss, double *vol, int *ncomp, char *why, size_t whylen) {
  const mesh *me = stack_mesh(ss);
  mc_mesh m;
  ref_mc_mesh(&m, me);
  mc_report r;
  mc_check(&m, &r);
  int ok = r.manifold && r.outward && me->nt > 0;
  *vol = r.volume, *ncomp = r.ncomp;
  snprintf(why, whylen, "%s", r.first);
  mc_report_free(&r);
  mc_free(&m);
  return ok;
}

static double rel(double a, double b) { return fabs(a / b - 1); }

/* ------------------------------------------------------ analytic solids -- */

enum { MAXP = 512, MAXS = 12 };

typedef struct {
  int n;
  double z;
  vec2 p[MAXP];
  double bend;   /* written: point 0 this far off the plane (along its normal) */
} poly;

/* A square of side s from (x0, y0), k points an edge. */
static void square(poly *q, double x0, double y0, double s, int k, double z) {
  vec2 c[4] = {{x0, y0}, {x0 + s, y0}, {x0 + s, y0 + s}, {x0, y0 + s}};
  q->n = 0, q->z = z;
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < k; j++)
      q->p[q->n++] = (vec2){c[i].x + (c[(i + 1) % 4].x - c[i].x) * j / k, c[i].y + (c[(i + 1) % 4].y - c[i].y) * j / k};
}

static void ngon(poly *q, double cx, double cy, double rx, double ry, int n, double z) {
  q->n = n, q->z = z;
  for (int i = 0; i < n; i++) q->p[i] = (vec2){cx + rx * cos(2 * PI * i / n), cy + ry * sin(2 * PI * i / n)};
}

/* A star of 2n points, radii r and f r; an L of 6 corners, k points an edge, scale s. */
static void star(poly *q, double cx, double cy, double r, int n, double f, double z) {
  q->n = 2 * n, q->z = z;
  for (int i = 0; i < 2 * n; i++) {
    double rr = i % 2 ? r * f : r;
    q->p[i] = (vec2){cx + rr * cos(PI * i / n), cy + rr * sin(PI * i / n)};
  }
}

static void ell(poly *q, double cx, double cy, double s, int k, double z) {
  static const vec2 c[6] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  q->n = 0, q->z = z;
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < k; j++)
      q->p[q->n++] = (vec2){cx + s * (c[i].x + (c[(i + 1) % 6].x - c[i].x) * j / k),
                            cy + s * (c[i].y + (c[(i + 1) % 6].y - c[i].y) * j / k)};
}

static double area(const poly *q) {
  double a = 0;
  for (int i = 0; i < q->n; i++) a += q->p[i].x * q->p[(i + 1) % q->n].y - q->p[(i + 1) % q->n].x * q->p[i].y;
  return a / 2;
}

/* The stack of ps[0..n-1] with the default options: the volume by formula
 * (want) to 1e-12, closed and outward, the checker's volume the report's,
 * the rows' volumes summing to the mesh's. */
static void solid(const char *what, const poly *ps, int n, double want) {
  sg_poly sp[MAXS];
  for (int i = 0; i < n; i++) sp[i] = (sg_poly){ps[i].n, ps[i].z, (vec2 *)ps[i].p};
  contour_stack s;
  if (sg_make_stack(sp, n, NULL, NULL, NULL, &s) != 0) {
    CHECK(0, "%s: not a stack", what);
    return;
  }
  char err[512], why[256];
  int res, nc;
  stack_surface *ss = tile(&s, 1, STACK_BAND_ALIGNED, NULL, 0, err, sizeof err, &res);
  CHECK(res == 0, "%s: %s", what, err);
  if (res == 0) {
    double cost, ar, vol, cv, sum = 0;
    stack_totals(ss, &cost, &ar, &vol);
    CHECK(judge(ss, &cv, &nc, why, sizeof why), "%s: not a closed outward mesh: %s", what, why);
    CHECK(rel(vol, want) < 1e-12, "%s: volume %.17g, by formula %.17g (%.3g)", what, vol, want, vol / want - 1);
    CHECK(rel(cv, vol) < 1e-12, "%s: the checker's volume %.17g, the report's %.17g", what, cv, vol);
    for (int i = 0; i < stack_nrows(ss); i++) sum += stack_rows(ss)[i].volume;
    CHECK(rel(sum, vol) < 1e-12, "%s: the rows' volumes sum to %.17g, the mesh's %.17g", what, sum, vol);
  }
  stack_free(ss);
  /* Without caps: open, no volume to speak of. */
  ss = tile(&s, 0, STACK_BAND_ALIGNED, NULL, 0, err, sizeof err, &res);
  if (res == 0) {
    double cv;
    CHECK(!judge(ss, &cv, &nc, why, sizeof why), "%s: closed without caps", what);
  }
  stack_free(ss);
  contour_stack_free(&s);
}

static double frustum(double h, double a0, double a1) { return h / 3 * (a0 + a1 + sqrt(a0 * a1)); }

static void solids(void) {
  static poly p[MAXS];
  const double s = 4.17;
  char what[120];
  for (int k = 1; k <= 4; k++) {   /* the shifted squares: 4, 8, 12, 16 points */
    square(&p[0], 0, 0, s, k, 0), square(&p[1], 3.13, 0, s, k, 1.5);
    snprintf(what, sizeof what, "shifted squares, %d points an edge", k);
    solid(what, p, 2, s * s * 1.5);
  }
  square(&p[0], 0, 0, s, 1, 0), square(&p[1], 3.13, 0, s, 4, 1.5);
  solid("shifted squares, 4 points against 16", p, 2, s * s * 1.5);
  for (int n = 8; n <= 64; n *= 8) {   /* oblique cylinders: 5 bands */
    for (int z = 0; z < 6; z++) ngon(&p[z], 0.7 * z, 0.3 * z, 5, 5, n, z);
    snprintf(what, sizeof what, "oblique cylinder of %d-gons", n);
    solid(what, p, 6, area(&p[0]) * 5);
  }
  for (int n = 16; n <= 64; n *= 4) {   /* sheared ellipses */
    for (int z = 0; z < 5; z++) ngon(&p[z], 1.1 * z, -0.4 * z, 6, 3, n, 2 * z);
    snprintf(what, sizeof what, "sheared ellipse of %d points", n);
    solid(what, p, 5, area(&p[0]) * 8);
  }
  for (int k = 1; k <= 5; k += 2) {   /* frustums of squares, the top off centre */
    square(&p[0], -3, -3, 6, k, 0), square(&p[1], 0, -0.5, 2, k, 3);
    snprintf(what, sizeof what, "frustum of squares, %d points an edge", k);
    solid(what, p, 2, frustum(3, 36, 4));
  }
  square(&p[0], -3, -3, 6, 1, 0), square(&p[1], 0, -0.5, 2, 5, 3);
  solid("frustum of squares, 4 points against 20", p, 2, frustum(3, 36, 4));
  for (int n = 12; n <= 64; n += 52) {
    ngon(&p[0], 0, 0, 5, 5, n, 0), ngon(&p[1], 0.5, 0.2, 2, 2, n, 4);
    snprintf(what, sizeof what, "frustum of %d-gons", n);
    solid(what, p, 2, frustum(4, area(&p[0]), area(&p[1])));
  }
  double v = 0;
  for (int z = 0; z < 5; z++) ngon(&p[z], 0.3 * z, 0, 6 - z, 6 - z, 32, z);
  for (int z = 0; z < 4; z++) v += frustum(1, area(&p[z]), area(&p[z + 1]));
  solid("cone stack of 32-gons", p, 5, v);
  star(&p[0], 0, 0, 6, 5, 0.4, 0), star(&p[1], 1, 1, 3, 5, 0.4, 2);
  solid("frustum of stars", p, 2, frustum(2, area(&p[0]), area(&p[1])));
  for (int k = 1; k <= 4; k += 3) {
    ell(&p[0], 0, 0, 3, k, 0), ell(&p[1], 2, 1, 1.5, k, 1.5);
    snprintf(what, sizeof what, "frustum of Ls, %d points an edge", k);
    solid(what, p, 2, frustum(1.5, area(&p[0]), area(&p[1])));
  }
}

/* ------------------------------------------------------------ real ROIs -- */

/* Twice a contour's area (long double shoelace), and whether q lies inside
 * it (crossing number): the tiler's own code is not used. */
static long double area2(const contour *c) {
  long double a = 0;
  for (int i = 0; i < c->n; i++) {
    vec2 p = c->pt[i], q = c->pt[(i + 1) % c->n];
    a += (long double)p.x * q.y - (long double)q.x * p.y;
  }
  return a;
}

static int inside(const contour *c, vec2 q) {
  int in = 0;
  for (int i = 0; i < c->n; i++) {
    vec2 a = c->pt[i], b = c->pt[(i + 1) % c->n];
    if ((a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y)) in = !in;
  }
  return in;
}

/* The stack's volume by the trapezoid and the frustum rules over its slices'
 * areas (each contour's taken out or put back by how many of its slice lie
 * around it). */
static void rules(const contour_stack *s, double *trap, double *frus) {
  double *a = xcalloc((size_t)s->nslices + 1, sizeof *a), *z = xcalloc((size_t)s->nslices + 1, sizeof *z);
  for (int i = 0; i < s->n; i++) {
    int d = 0;
    for (int j = 0; j < s->n; j++) d += j != i && s->c[j].slice == s->c[i].slice && inside(&s->c[j], s->c[i].pt[0]);
    a[s->c[i].slice] += (double)(fabsl(area2(&s->c[i])) / 2 * (d % 2 ? -1 : 1));
    z[s->c[i].slice] = s->c[i].z;
  }
  *trap = *frus = 0;
  for (int k = 0; k + 1 < s->nslices; k++) {
    double h = z[k + 1] - z[k];
    *trap += h * (a[k] + a[k + 1]) / 2;
    *frus += frustum(h, a[k], a[k + 1]);
  }
  free(a), free(z);
}

static void real_roi(const char *what, const contour_stack *s) {
  char err[1024], why[256];
  int res, nc;
  if (s->nslices < 2) return;
  stack_surface *ss = tile(s, 1, STACK_BAND_ALIGNED, NULL, 0, err, sizeof err, &res);
  CHECK(res == 0, "%s: %s", what, err);
  if (res == 0) {
    double cost, ar, vol, cv, trap, frus;
    stack_totals(ss, &cost, &ar, &vol);
    CHECK(judge(ss, &cv, &nc, why, sizeof why), "%s: not closed and outward with the default options: %s", what, why);
    rules(s, &trap, &frus);
    double lo = fmin(trap, frus), hi = fmax(trap, frus);
    CHECK(vol >= 0.98 * lo && vol <= 1.02 * hi,
          "%s: volume %.17g outside the frustum rule's %.17g and the trapezoid rule's %.17g, to 2 %%", what, vol, frus,
          trap);
    printf("test_faithful: %-44s %3d planes: volume %+.2f %% of the trapezoid rule, %+.2f %% of the frustum rule\n",
           what, s->nslices, (vol / trap - 1) * 100, (vol / frus - 1) * 100);
  }
  stack_free(ss);
}

static void real(void) {
  static const char *dcm[] = {"dicompyler_rtss.dcm", "pydicom_rtstruct.dcm", "rtutils_dummy_rt.dcm", "rtutils_rt.dcm"};
  static const char *stacks[] = {"prostate_0", "prostate_1", "prostate_2", "prostate_3", "prostate_4", "prostate_5",
                                 "tinypatient_0", "tinypatient_1"};
  char path[256], err[4096], what[200];
  for (size_t f = 0; f < sizeof dcm / sizeof *dcm; f++) {
    snprintf(path, sizeof path, "tests/data/rtstruct/%s", dcm[f]);
    rtstruct r;
    if (rtstruct_read(path, &r, err, sizeof err) != 0) {
      CHECK(0, "%s", err);
      continue;
    }
    for (int i = 0; i < r.nroi; i++) {
      if (r.roi[i].nc == 0) continue;
      contour_stack s;
      snprintf(what, sizeof what, "%s ROI %d '%s'", dcm[f], r.roi[i].number, r.roi[i].name);
      if (rtstruct_roi_stack(&r, i, CONTOUR_DROP_DEGENERATE | CONTOUR_ONE_SLICE, &s, NULL, "t", err, sizeof err) != 0) {
        CHECK(0, "%s: %s", what, err);
        continue;
      }
      real_roi(what, &s);
      contour_stack_free(&s);
    }
    rtstruct_free(&r);
  }
  for (size_t f = 0; f < sizeof stacks / sizeof *stacks; f++) {
    snprintf(path, sizeof path, "tests/data/slicerrt/%s.contours", stacks[f]);
    contour_stack s;
    if (contour_read(path, &s, NULL, "t", err, sizeof err) != 0) {
      CHECK(0, "%s", err);
      continue;
    }
    real_roi(stacks[f], &s);
    contour_stack_free(&s);
  }
}

/* ----------------------------------------------- structures like real ones -- */

/* Forty structures of 5 to 25 slices 3 apart, as planning systems draw
 * them: ellipsoid profiles, 8 to 120 points a slice, elongated, drifting,
 * turning, with three harmonics of noise of their own a slice, rounded to
 * 0.01 mm.  Between dissimilar sections nothing is exact, but the volume
 * must lie within 2 % of the trapezoid rule over the slices' areas (the
 * minimum-area band on the aligned pair alone lost up to 5.4 %). */
static void blobs(void) {
  static poly p[25];
  static const int planes[] = {5, 6, 7, 8, 10, 15, 25}, npts[] = {8, 16, 40, 120};
  static const double size[] = {3, 6, 15, 40}, elong[] = {1, 1.5, 3, 5}, shift[] = {0, 0.5, 2, 4};
  static const double turn[] = {0, 0.1, 0.3}, noise[] = {0, 0.05, 0.15};
  rng g;
  rng_seed(&g, 20261202);
  double worst = 0;
  for (int b = 0; b < 40; b++) {
    int n = planes[rng_int(&g, 0, 6)], np = npts[rng_int(&g, 0, 3)];
    double sz = size[rng_int(&g, 0, 3)], el = elong[rng_int(&g, 0, 3)], sh = shift[rng_int(&g, 0, 3)];
    double rot = turn[rng_int(&g, 0, 2)], nz = noise[rng_int(&g, 0, 2)];
    sg_poly sp[25];
    for (int k = 0; k < n; k++) {
      double t = (k + 0.5) / n, a = sz * sqrt(fmax(1e-3, 1 - (2 * t - 1) * (2 * t - 1))), bb = a / el;
      double cx = sh * k + rng_uniform(&g) - 0.5, cy = 0.3 * sh * k, th = rot * k, amp[3], ph[3];
      for (int h = 0; h < 3; h++) amp[h] = (2 * rng_uniform(&g) - 1) * nz, ph[h] = 6.28 * rng_uniform(&g);
      p[k].n = np, p[k].z = 3.0 * k;
      for (int i = 0; i < np; i++) {
        double u = 2 * PI * i / np, rr = 1;
        for (int h = 0; h < 3; h++) rr += amp[h] * cos((h + 2) * u + ph[h]);
        double x = a * rr * cos(u), y = bb * rr * sin(u);
        p[k].p[i] = (vec2){round((cx + x * cos(th) - y * sin(th)) * 100) / 100,
                           round((cy + x * sin(th) + y * cos(th)) * 100) / 100};
      }
      sp[k] = (sg_poly){p[k].n, p[k].z, p[k].p};
    }
    char what[80], err[512], why[256];
    snprintf(what, sizeof what, "structure %d (%d slices of %d points)", b, n, np);
    contour_stack s;
    if (sg_make_stack(sp, n, NULL, NULL, NULL, &s) != 0) {
      CHECK(0, "%s: not a stack", what);
      continue;
    }
    int res, nc;
    stack_surface *ss = tile(&s, 1, STACK_BAND_ALIGNED, NULL, 0, err, sizeof err, &res);
    CHECK(res == 0, "%s: %s", what, err);
    if (res == 0) {
      double cost, ar, vol, cv, trap, frus;
      stack_totals(ss, &cost, &ar, &vol);
      CHECK(judge(ss, &cv, &nc, why, sizeof why), "%s: not closed and outward: %s", what, why);
      rules(&s, &trap, &frus);
      CHECK(rel(vol, trap) < 0.02, "%s: volume %.17g, %+.2f %% of the trapezoid rule's %.17g", what, vol,
            (vol / trap - 1) * 100, trap);
      worst = fmax(worst, rel(vol, trap));
      if (b < 4) {   /* the paper's algorithm on the simulator tiles the same bands */
        par_machine pm;
        par_machine_init(&pm);
        pm.mc.procs = 3;
        stack_tiler tl = par_machine_tiler(&pm);
        stack_options o = {COST_AREA, 1, 0, 2, &tl, NULL, "test", NULL, NULL, MATCH_SINGLE, INFINITY, 0,
                           STACK_BAND_ALIGNED};
        stack_surface *sp2 = sg_tile(&s, o, NULL, 0, err, sizeof err, &res);
        const mesh *m1 = stack_mesh(ss), *m2 = res == 0 ? stack_mesh(sp2) : NULL;
        CHECK(m2 && m1->nv == m2->nv && m1->nt == m2->nt &&
                  memcmp(m1->v, m2->v, (size_t)m1->nv * sizeof *m1->v) == 0 &&
                  memcmp(m1->t, m2->t, (size_t)m1->nt * sizeof *m1->t) == 0,
              "%s: --procs 3 on the simulator: %s", what, res ? err : "another mesh");
        stack_free(sp2);
      }
    }
    stack_free(ss);
    contour_stack_free(&s);
  }
  printf("test_faithful: 40 structures like real ones: volumes within %.2f %% of the trapezoid rule\n", worst * 100);
}

/* ------------------------------------------------------ exported sets -- */

enum { MAXR = 8, MAXC = 160 };

/* An ROI as a planning system writes it: contours in the set's frame, each
 * point through the rotation R (patient = R p), written with `digits`
 * decimals (-1: full precision). */
typedef struct {
  const char *name, *geom;   /* geom: NULL CLOSED_PLANAR, or "POINT" */
  int nc;
  poly *c;
} roi_def;

typedef struct {
  const char *file;
  int nroi;
  roi_def r[MAXR];
  double R[3][3];
  int digits;
} set_def;

static void rotation(double ax, double ay, double az, double deg, double R[3][3]) {
  double l = sqrt(ax * ax + ay * ay + az * az);
  ax /= l, ay /= l, az /= l;
  double t = deg * PI / 180, c = cos(t), s = sin(t), C = 1 - c;
  double M[3][3] = {{c + ax * ax * C, ax * ay * C - az * s, ax * az * C + ay * s},
                    {ay * ax * C + az * s, c + ay * ay * C, ay * az * C - ax * s},
                    {az * ax * C - ay * s, az * ay * C + ax * s, c + az * az * C}};
  memcpy(R, M, sizeof M);
}

static unsigned char *write_set(const set_def *d, size_t *len) {
  rtw_roi roi[MAXR];
  rtw_contour *cs[MAXR];
  char **texts[MAXR];
  for (int q = 0; q < d->nroi; q++) {
    const roi_def *r = &d->r[q];
    cs[q] = xcalloc((size_t)r->nc + 1, sizeof *cs[q]);
    texts[q] = xcalloc((size_t)r->nc + 1, sizeof *texts[q]);
    for (int i = 0; i < r->nc; i++) {
      const poly *c = &r->c[i];
      size_t cap = (size_t)c->n * 3 * 32 + 8, at = 0;
      char *t = texts[q][i] = xmalloc(cap);
      t[0] = 0;
      for (int j = 0; j < c->n; j++) {
        double p[3] = {c->p[j].x, c->p[j].y, c->z + (j == 0 ? c->bend : 0)}, o[3];
        for (int a = 0; a < 3; a++) o[a] = d->R[a][0] * p[0] + d->R[a][1] * p[1] + d->R[a][2] * p[2];
        for (int a = 0; a < 3; a++) {
          if (d->digits >= 0) at += (size_t)snprintf(t + at, cap - at, "%s%.*f", at ? "\\" : "", d->digits, o[a] + 0.0);
          else at += (size_t)snprintf(t + at, cap - at, "%s%.17g", at ? "\\" : "", o[a]);
        }
      }
      cs[q][i] = (rtw_contour){r->geom, c->n, NULL, t, -1};
    }
    roi[q] = (rtw_roi){q + 1, r->name, NULL, r->nc, cs[q], 0, 0};
  }
  rtw_opts o = {1, 0, 0, 0, NULL, NULL, 0};
  unsigned char *b = rtw_write(&o, roi, d->nroi, len);
  for (int q = 0; q < d->nroi; q++) {
    for (int i = 0; i < d->r[q].nc; i++) free(texts[q][i]);
    free(texts[q]);
    free(cs[q]);
  }
  return b;
}

static poly pool[MAXR * MAXC * 6];
static int npool;

static poly *take(int n) {
  XASSERT(npool + n <= (int)(sizeof pool / sizeof *pool));
  poly *p = &pool[npool];
  npool += n;
  return p;
}

static void identity(double R[3][3]) {
  memset(R, 0, 9 * sizeof **R);
  R[0][0] = R[1][1] = R[2][2] = 1;
}

/* The sets.  sets[k] for k = 0 .. NSETS-1. */
enum { NSETS = 7 };
static set_def sets[NSETS];
static double cyl_area;   /* the 64-gon of radius 20 */

static void cylinder(roi_def *r, const char *name, double cx, double cy, int planes) {
  r->name = name, r->nc = planes, r->c = take(planes);
  for (int k = 0; k < planes; k++) ngon(&r->c[k], cx, cy, 20, 20, 64, 2.0 * k);
  cyl_area = area(&r->c[0]);
}

static void make_sets(void) {
  npool = 0;
  memset(sets, 0, sizeof sets);
  /* Oblique planes, two decimals. */
  set_def *d = &sets[0];
  d->file = "faithful_oblique.dcm", d->nroi = 3, d->digits = 2;
  rotation(cos(0.5), sin(0.5), 0, 6, d->R);
  cylinder(&d->r[0], "Cyl", 5, -3, 10);
  cylinder(&d->r[1], "Cyl again", 80, 40, 10);
  cylinder(&d->r[2], "Bent", -60, 0, 10);
  d->r[2].c[5].bend = 0.3;
  d = &sets[1];
  d->file = "faithful_oblique35.dcm", d->nroi = 1, d->digits = 2;
  rotation(0.48, 0.6, 0.64, 35, d->R);
  cylinder(&d->r[0], "Cyl", 0, 0, 10);
  /* Pinnacle-like: a tube with single points, two-point and collinear
   * contours on its planes; and the same tube clean. */
  d = &sets[2];
  d->file = "faithful_pinnacle.dcm", d->nroi = 2, d->digits = 2;
  identity(d->R);
  roi_def *u = &d->r[0], *v = &d->r[1];
  u->name = "Urethra", v->name = "Urethra clean";
  u->c = take(12 * 8), v->c = take(12);
  for (int k = 0; k < 12; k++) {
    double z = 2.5 * k, cx = 0.4 * k, cy = 0.2 * k;
    ngon(&v->c[v->nc++], cx, cy, 3, 3, 8, z);
    for (int j = 0; j < 8; j++) {
      poly *q = &u->c[u->nc++];
      if (j == 3) {
        ngon(q, cx, cy, 3, 3, 8, z);
        continue;
      }
      q->z = z;
      q->n = j % 3 + 1;   /* a point, two points, three on a line */
      for (int i = 0; i < q->n; i++) q->p[i] = (vec2){cx - 1 + i * 0.5 + j, cy + 0.25 * i};
    }
  }
  /* Holes drawn on their outer contour's boundary: along an edge, at a point. */
  d = &sets[3];
  d->file = "faithful_holes.dcm", d->nroi = 2, d->digits = -1;
  identity(d->R);
  for (int q = 0; q < 2; q++) {
    roi_def *r = &d->r[q];
    r->name = q ? "Pinched" : "Notched", r->nc = 12, r->c = take(12);
    for (int k = 0; k < 6; k++) {
      square(&r->c[2 * k], 0, 0, 40, 1, 3.0 * k);
      poly *h = &r->c[2 * k + 1];
      h->z = 3.0 * k, h->n = 4;
      if (q == 0) h->p[0] = (vec2){0, 14}, h->p[1] = (vec2){10, 14}, h->p[2] = (vec2){10, 26}, h->p[3] = (vec2){0, 26};
      else h->p[0] = (vec2){0, 20}, h->p[1] = (vec2){5, 15}, h->p[2] = (vec2){10, 20}, h->p[3] = (vec2){5, 25};
    }
  }
  /* Two squares a slice touching at a corner. */
  d = &sets[4];
  d->file = "faithful_corner.dcm", d->nroi = 1, d->digits = -1;
  identity(d->R);
  d->r[0].name = "Corner", d->r[0].nc = 12, d->r[0].c = take(12);
  for (int k = 0; k < 6; k++) square(&d->r[0].c[2 * k], 0, 0, 10, 1, 3.0 * k), square(&d->r[0].c[2 * k + 1], 10, 10, 10, 1, 3.0 * k);
  /* Branchings: one contour under six in a row, in a grid; and two squares
   * under a U with a wall between them, which no bridge can cross. */
  d = &sets[5];
  d->file = "faithful_branch.dcm", d->nroi = 3, d->digits = 2;
  identity(d->R);
  for (int q = 0; q < 2; q++) {
    roi_def *r = &d->r[q];
    r->name = q ? "Grid" : "Row", r->c = take(16);
    for (int k = 0; k < 2; k++) square(&r->c[r->nc++], -16, -8, 32, 1, 3.0 * k);
    for (int k = 2; k < 4; k++)
      for (int i = 0; i < 6; i++)
        square(&r->c[r->nc++], q ? -10 + 8 * (i % 3) : -14.5 + 5 * i, q ? -6 + 7 * (i / 3) : -1.5, 3, 1, 3.0 * k);
  }
  roi_def *w = &d->r[2];
  w->name = "Walled", w->nc = 0, w->c = take(6);
  square(&w->c[w->nc++], 0, 0, 1, 1, 0), square(&w->c[w->nc++], 10, 0, 1, 1, 0);
  poly *wall = &w->c[w->nc++];
  wall->z = 0, wall->n = 4;
  wall->p[0] = (vec2){5, -10}, wall->p[1] = (vec2){6, -10}, wall->p[2] = (vec2){6, 11}, wall->p[3] = (vec2){5, 11};
  poly *U = &w->c[w->nc++];
  static const vec2 up[8] = {{-1, 2}, {-1, -12}, {12, -12}, {12, 2}, {9, 2}, {9, -11}, {2, -11}, {2, 2}};
  U->z = 3, U->n = 8;
  memcpy(U->p, up, sizeof up);
  /* A keyhole contour (a square with a hole, joined by a channel) whose
   * outer loop overlaps another contour: --union names its loop by the loop's
   * first point, in full. */
  d = &sets[6];
  d->file = "faithful_names.dcm", d->nroi = 1, d->digits = -1;
  identity(d->R);
  roi_def *kh = &d->r[0];
  kh->name = "Keyhole", kh->nc = 3, kh->c = take(3);
  static const vec2 key[10] = {{0, 0}, {3, 3}, {3, 7}, {7, 7}, {7, 3}, {3, 3}, {0, 0}, {10, 0}, {10, 10}, {0, 10}};
  kh->c[0].n = 10, kh->c[0].z = 0;
  memcpy(kh->c[0].p, key, sizeof key);
  square(&kh->c[1], 8, 2, 6, 1, 0);
  square(&kh->c[2], 0, 0, 14, 1, 2);
}

static int parse(const set_def *d, rtstruct *r) {
  size_t len;
  unsigned char *b = write_set(d, &len);
  char err[1024];
  int rc = rtstruct_parse(b, len, d->file, r, err, sizeof err);
  CHECK(rc == 0, "%s: refused: %s", d->file, err);
  free(b);
  return rc;
}

/* The ROI's stack read (default flags and extra), tiled with the defaults:
 * res, and the surface (or NULL), its notes and the refusal. */
static stack_surface *roi_tile(const rtstruct *r, int roi, int flags, char *notes, size_t nlen, char *err,
                               size_t errlen, int *res) {
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  contour_stack s;
  *res = rtstruct_roi_stack(r, roi, CONTOUR_DROP_DEGENERATE | CONTOUR_ONE_SLICE | flags, &s, f, "t", err, errlen);
  fclose(f);
  stack_surface *ss = NULL;
  char more[4096] = "";
  if (*res == 0) {
    ss = tile(&s, 1, STACK_BAND_ALIGNED, more, sizeof more, err, errlen, res);
    contour_stack_free(&s);
  }
  snprintf(notes, nlen, "%s%s", buf ? buf : "", more);
  free(buf);
  return ss;
}

static void exports(void) {
  make_sets();
  rtstruct r;
  char notes[8192], err[4096], why[256];
  int res, nc;
  double cost, ar, vol, cv;
  /* Oblique, two decimals: tiled, the cylinder's volume to 0.3 %; bent: refused. */
  for (int k = 0; k < 2; k++) {
    if (parse(&sets[k], &r) != 0) continue;
    for (int q = 0; q < sets[k].nroi; q++) {
      const char *name = sets[k].r[q].name;
      if (strcmp(name, "Bent") == 0) {
        CHECK(r.roi[q].error && strstr(r.roi[q].error, "contour item 6: not planar"), "%s %s: '%s'", sets[k].file,
              name, r.roi[q].error ? r.roi[q].error : "accepted");
        continue;
      }
      CHECK(!r.roi[q].error && r.roi[q].plane == RTSTRUCT_OBLIQUE, "%s %s: '%s'", sets[k].file, name,
            r.roi[q].error ? r.roi[q].error : "not oblique");
      stack_surface *ss = roi_tile(&r, q, 0, notes, sizeof notes, err, sizeof err, &res);
      CHECK(res == 0, "%s %s: %s", sets[k].file, name, err);
      if (res == 0) {
        stack_totals(ss, &cost, &ar, &vol);
        CHECK(judge(ss, &cv, &nc, why, sizeof why) && nc == 1, "%s %s: %s", sets[k].file, name, why);
        CHECK(rel(vol, cyl_area * 18) < 3e-3, "%s %s: volume %.17g, the cylinder's %.17g", sets[k].file, name, vol,
              cyl_area * 18);
      }
      stack_free(ss);
    }
    rtstruct_free(&r);
  }
  /* Pinnacle-like: the degenerate contours dropped, counted, the mesh the
   * clean tube's. */
  if (parse(&sets[2], &r) == 0) {
    char n2[4096];
    stack_surface *a = roi_tile(&r, 0, 0, notes, sizeof notes, err, sizeof err, &res);
    CHECK(res == 0 && strstr(notes, "dropped 84 degenerate contours of 96 (168 points"), "Pinnacle-like: %d '%s' '%s'",
          res, err, notes);
    int res2;
    stack_surface *b = roi_tile(&r, 1, 0, n2, sizeof n2, err, sizeof err, &res2);
    if (res == 0 && res2 == 0) {
      const mesh *ma = stack_mesh(a), *mb = stack_mesh(b);
      CHECK(ma->nv == mb->nv && ma->nt == mb->nt && memcmp(ma->v, mb->v, (size_t)ma->nv * sizeof *ma->v) == 0 &&
                memcmp(ma->t, mb->t, (size_t)ma->nt * sizeof *ma->t) == 0,
            "Pinnacle-like: another mesh than the clean tube's");
      CHECK(judge(a, &cv, &nc, why, sizeof why), "Pinnacle-like: %s", why);
    }
    stack_free(a), stack_free(b);
    rtstruct_free(&r);
  }
  /* Holes on their outer contour's boundary: the region's volume, with and
   * without --union. */
  if (parse(&sets[3], &r) == 0) {
    const double want[2] = {(1600 - 120) * 15.0, (1600 - 50) * 15.0};
    for (int q = 0; q < 2; q++)
      for (int un = 0; un < 2; un++) {
        stack_surface *ss = roi_tile(&r, q, un ? CONTOUR_UNION : 0, notes, sizeof notes, err, sizeof err, &res);
        CHECK(res == 0, "%s%s: %s", sets[3].r[q].name, un ? " --union" : "", err);
        if (res == 0) {
          stack_totals(ss, &cost, &ar, &vol);
          CHECK(judge(ss, &cv, &nc, why, sizeof why), "%s: %s", sets[3].r[q].name, why);
          CHECK(rel(vol, want[q]) < 1e-9 && rel(cv, want[q]) < 1e-9, "%s%s: volume %.17g, the region's %.17g",
                sets[3].r[q].name, un ? " --union" : "", vol, want[q]);
          CHECK(strstr(notes, q ? "touches itself, split" : "holes on their outer contours' boundaries") || un,
                "%s: notes '%s'", sets[3].r[q].name, notes);
        }
        stack_free(ss);
      }
    rtstruct_free(&r);
  }
  /* Two squares touching at a corner: split where they touch, with --union or without. */
  if (parse(&sets[4], &r) == 0) {
    stack_surface *ss = roi_tile(&r, 0, CONTOUR_UNION, notes, sizeof notes, err, sizeof err, &res);
    CHECK(res == 0 && strstr(notes, "6 points where a region touches itself, split"), "corner --union: %d '%s' '%s'",
          res, err, notes);
    if (res == 0) {
      stack_totals(ss, &cost, &ar, &vol);
      CHECK(judge(ss, &cv, &nc, why, sizeof why) && nc == 2, "corner --union: %s, %d components", why, nc);
      CHECK(rel(vol, 3000) < 1e-9, "corner --union: volume %.17g, the squares' 3000", vol);
    }
    stack_free(ss);
    /* without --union the same union, a note a slice */
    ss = roi_tile(&r, 0, 0, notes, sizeof notes, err, sizeof err, &res);
    CHECK(res == 0 && strstr(notes, "overlapping contours on slice z=") && strstr(notes, "touches itself at"),
          "corner: %d '%s' '%s'", res, err, notes);
    if (res == 0) {
      stack_totals(ss, &cost, &ar, &vol);
      CHECK(judge(ss, &cv, &nc, why, sizeof why) && nc == 2, "corner: %s, %d components", why, nc);
      CHECK(rel(vol, 3000) < 1e-9, "corner: volume %.17g, the squares' 3000", vol);
    }
    stack_free(ss);
    rtstruct_free(&r);
  }
  /* Branchings: one closed component each; the walled one with a join
   * dropped, named. */
  if (parse(&sets[5], &r) == 0) {
    for (int q = 0; q < 3; q++) {
      stack_surface *ss = roi_tile(&r, q, 0, notes, sizeof notes, err, sizeof err, &res);
      CHECK(res == 0, "%s: %s", sets[5].r[q].name, err);
      if (res == 0) {
        CHECK(judge(ss, &cv, &nc, why, sizeof why) && nc == (q == 2 ? 3 : 1), "%s: %s, %d components",
              sets[5].r[q].name, why, nc);
        CHECK(q < 2 || (stack_join_counts(ss)->dropped == 1 && strstr(notes, "(their regions overlap): no bridges can "
                                                                             "join")),
              "%s: notes '%s'", sets[5].r[q].name, notes);
      }
      stack_free(ss);
    }
    rtstruct_free(&r);
  }
}

/* Messages name the contours of a DICOM ROI in full: a keyhole's loop, named
 * by its first point, beside another contour (it was 'the contours at point 1
 * and contour item 57'). */
static void names(void) {
  rtstruct r;
  char notes[8192], err[4096];
  int res;
  if (parse(&sets[6], &r) != 0) return;
  stack_surface *ss = roi_tile(&r, 0, CONTOUR_UNION, notes, sizeof notes, err, sizeof err, &res);
  CHECK(res == 0 && strstr(notes, "--union: merged the contours at contour item 1, point 1 and contour item 2 on slice z=0") &&
            !strstr(notes, "contours at point"),
        "names: %d '%s' '%s'", res, err, notes);
  stack_free(ss);
  rtstruct_free(&r);
}

/* The sets as files in dir, and a set of ROIs of which some are refused:
 * 1 'Good', 2 'Crossing' (a contour crosses itself), 3 'Good too', 4
 * 'Overlap' (two contours of a slice overlap: merged), 5 'Flat' (one
 * slice), 6 'Marker' (a POINT); and overlapping pieces on every slice. */
static int write_files(const char *dir) {
  make_sets();
  set_def mixed;
  memset(&mixed, 0, sizeof mixed);
  mixed.file = "faithful_mixed.dcm", mixed.nroi = 6, mixed.digits = 2;
  identity(mixed.R);
  cylinder(&mixed.r[0], "Good", 0, 0, 4);
  roi_def *c = &mixed.r[1];
  c->name = "Crossing", c->nc = 3, c->c = take(3);
  for (int k = 0; k < 3; k++) square(&c->c[k], 0, 0, 5, 1, 2.0 * k);
  vec2 t = c->c[1].p[1];
  c->c[1].p[1] = c->c[1].p[2], c->c[1].p[2] = t;   /* a bow tie */
  cylinder(&mixed.r[2], "Good too", 50, 0, 3);
  roi_def *o = &mixed.r[3];
  o->name = "Overlap", o->nc = 3, o->c = take(3);
  square(&o->c[0], 0, 0, 5, 1, 0), square(&o->c[1], 3, 3, 5, 1, 0), square(&o->c[2], 0, 0, 5, 1, 2);
  roi_def *f = &mixed.r[4];
  f->name = "Flat", f->nc = 1, f->c = take(1);
  square(&f->c[0], 0, 0, 5, 1, 0);
  roi_def *m = &mixed.r[5];
  m->name = "Marker", m->geom = "POINT", m->nc = 1, m->c = take(1);
  m->c[0].n = 1, m->c[0].z = 0, m->c[0].p[0] = (vec2){1, 1};
  /* 'Pieces': two overlapping squares of side 4 on each of 4 slices 2 apart,
   * the second 2 right and 1 up of the first, both moving 1 right and 0.5
   * up a slice (tests/cli_faithful.sh has the union's volume in closed form). */
  set_def pieces;
  memset(&pieces, 0, sizeof pieces);
  pieces.file = "faithful_pieces.dcm", pieces.nroi = 1, pieces.digits = 2;
  identity(pieces.R);
  roi_def *pc = &pieces.r[0];
  pc->name = "Pieces", pc->nc = 8, pc->c = take(8);
  for (int k = 0; k < 4; k++)
    square(&pc->c[2 * k], k, 0.5 * k, 4, 1, 2.0 * k), square(&pc->c[2 * k + 1], k + 2, 0.5 * k + 1, 4, 1, 2.0 * k);
  int bad = 0;
  for (int k = 0; k <= NSETS + 1; k++) {
    const set_def *d = k < NSETS ? &sets[k] : k == NSETS ? &mixed : &pieces;
    size_t len;
    unsigned char *b = write_set(d, &len);
    bad |= rtw_save(dir, d->file, b, len);
    free(b);
  }
  return bad;
}

int main(int argc, char **argv) {
  if (argc == 3 && strcmp(argv[1], "--write") == 0) return write_files(argv[2]);
  solids();
  real();
  blobs();
  exports();
  names();
  return check_done("test_faithful");
}
