/* test_slicemerge.c -- contours of a slice that repeat or overlap,
 * through the reader (input/slicemerge.h) and the stack tiler:
 *   - three copies of one region on every slice, as Monaco writes an
 *     outline (other start points, extra collinear points, reversed): one
 *     kept, the one with fewest points; the mesh byte for byte the mesh of
 *     the stack with one copy, whatever the copies' order in the file;
 *   - overlapping pieces with --union: five pieces a slice, three of them
 *     overlapping (rectangles, and rotated squares), the union's area on
 *     each slice against coordinate compression (rectangles) and against
 *     inclusion-exclusion with clipped intersections (squares); holes and
 *     islands (a ring of pieces around a hole, an island in it); the mesh a
 *     closed, outward 2-manifold (tests/meshcheck, independent); shuffled,
 *     start-rotated, reversed re-encodings give the same mesh bytes;
 *   - without --union the same union and mesh, with one note a slice;
 *   - notes: one line for the duplicates, one for the unions (--union); -v
 *     one each. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/contour.h"
#include "tests/meshcheck.h"
#include "tests/reference.h"
#include "util/rng.h"
#include "tests/rtwriter.h"
#include "surface/stack.h"
#include "util/strbuf.h"
#include "util/xmem.h"

typedef struct {
  int n;
  vec2 p[64];
  double z;
} poly;

/* The stack as text: contours in the order given, each from point `start`
 * (mod n), reversed when rev. */
static char *text_of(const poly *ps, int np, const int *order, const int *start, const int *rev, size_t *len) {
  strbuf b = {0};
  for (int k = 0; k < np; k++) {
    const poly *c = &ps[order ? order[k] : k];
    int s = start ? start[k] : 0, r = rev ? rev[k] : 0;
    strbuf_add(&b, "C %d %.17g\n", c->n, c->z);
    for (int j = 0; j < c->n; j++) {
      int i = r ? ((s - j) % c->n + c->n) % c->n : (s + j) % c->n;
      strbuf_add(&b, "%.17g %.17g\n", c->p[i].x, c->p[i].y);
    }
  }
  *len = b.len;
  return b.buf;
}

typedef struct {
  int rc;
  char err[4096];
  char *notes;
  int nv, nt;
  vec3 *v;
  int (*t)[3];
  contour_stack s;
} result;

/* Read (flags) and tile with flat caps. */
static void run(const char *text, size_t len, int flags, result *r) {
  memset(r, 0, sizeof *r);
  size_t nl = 0;
  FILE *f = open_memstream(&r->notes, &nl);
  r->rc = contour_parse_flags(text, len, "m.contours", flags, &r->s, f, "tile", r->err, sizeof r->err);
  fclose(f);
  if (r->rc != 0) return;
  stack_options o = {COST_AREA, 1, 0, 2, NULL, NULL, "tile", NULL, NULL, MATCH_SINGLE, INFINITY, 0, STACK_BAND_ALIGNED};
  stack_surface *ss = NULL;
  r->rc = stack_tile(&r->s, "m.contours", &o, &ss, r->err, sizeof r->err);
  if (r->rc == 0) {
    mesh me;
    stack_take_mesh(ss, &me);
    r->nv = me.nv, r->nt = me.nt;
    r->v = xmallocarray((size_t)me.nv + 1, sizeof *r->v);
    r->t = xmallocarray((size_t)me.nt + 1, sizeof *r->t);
    memcpy(r->v, me.v, (size_t)me.nv * sizeof *r->v);
    memcpy(r->t, me.t, (size_t)me.nt * sizeof *r->t);
    mesh_free(&me);
  }
  stack_free(ss);
}

static void done(result *r) {
  free(r->notes), free(r->v), free(r->t);
  if (r->s.c) contour_stack_free(&r->s);
}

static int same_mesh(const result *a, const result *b) {
  return a->rc == 0 && b->rc == 0 && a->nv == b->nv && a->nt == b->nt &&
         memcmp(a->v, b->v, (size_t)a->nv * sizeof *a->v) == 0 && memcmp(a->t, b->t, (size_t)a->nt * sizeof *a->t) == 0;
}

static int lines(const char *s) {
  int n = 0;
  for (; s && *s; s++) n += *s == '\n';
  return n;
}

/* A closed, outward 2-manifold by the independent checker. */
static int closed(const result *r, char *why, size_t cap) {
  mesh me = {.nv = r->nv, .nt = r->nt, .v = r->v, .t = r->t};
  mc_mesh m;
  ref_mc_mesh(&m, &me);
  mc_report rep;
  mc_check(&m, &rep);
  int ok = rep.manifold && rep.outward;
  snprintf(why, cap, "%s", rep.first);
  mc_report_free(&rep);
  mc_free(&m);
  return ok;
}

/* ---------------------------------------------------------------- copies */

/* An outline (a 12-gon, integer points) on 4 slices, three times on each:
 * as it is; from another start, reversed; with a point added in the middle
 * of every other edge.  Against the stack of one copy. */
static void copies(void) {
  static poly ps[12];
  int np = 0;
  vec2 base[12];
  for (int i = 0; i < 12; i++) base[i] = (vec2){round(100 * cos(i * 0.5236) + i), round(80 * sin(i * 0.5236))};
  for (int k = 0; k < 4; k++)
    for (int c = 0; c < 3; c++) {
      poly *p = &ps[np++];
      p->z = 2.5 * k, p->n = 0;
      for (int i = 0; i < 12; i++) {
        int j = c == 1 ? (5 - i + 12) % 12 : i;
        p->p[p->n++] = (vec2){base[j].x + k, base[j].y};
        if (c == 2 && i % 2 == 0) {
          vec2 a = base[i], b = base[(i + 1) % 12];
          if (fmod(a.x + b.x, 2) == 0 && fmod(a.y + b.y, 2) == 0)
            p->p[p->n++] = (vec2){(a.x + b.x) / 2 + k, (a.y + b.y) / 2};
        }
      }
    }
  int one_order[4] = {0, 3, 6, 9};
  size_t l1, l3;
  char *t1 = text_of(ps, 4, one_order, NULL, NULL, &l1);
  result r1, r3;
  run(t1, l1, 0, &r1);
  CHECK(r1.rc == 0, "one copy: %s", r1.err);
  rng g;
  rng_seed(&g, 3);
  int order[12], start[12], rev[12];
  for (int trial = 0; trial < 6; trial++) {
    for (int i = 0; i < 12; i++) order[i] = i, start[i] = trial ? rng_int(&g, 0, 11) : 0, rev[i] = trial ? rng_int(&g, 0, 1) : 0;
    for (int i = 11; trial && i > 0; i--) {
      int j = rng_int(&g, 0, i), t = order[i];
      order[i] = order[j], order[j] = t;
    }
    char *t3 = text_of(ps, 12, order, start, rev, &l3);
    run(t3, l3, 0, &r3);
    CHECK(r3.rc == 0 && r3.s.n == 4, "three copies (%d): %d contours: %s", trial, r3.s.n, r3.err);
    CHECK(same_mesh(&r1, &r3), "three copies (%d): another mesh than one copy's", trial);
    CHECK(lines(r3.notes) >= 1 && strstr(r3.notes, "dropped 8 contours that repeat another of their slice exactly"),
          "three copies (%d): notes '%s'", trial, r3.notes);
    done(&r3);
    if (trial == 0) {   /* -v: one line each */
      run(t3, l3, CONTOUR_VERBOSE, &r3);
      int each = 0;
      for (const char *q = r3.notes; (q = strstr(q, "dropped the contour: it repeats the contour at line")); q++) each++;
      CHECK(each == 8, "three copies, -v: %d notes for 8 copies: %s", each, r3.notes);
      done(&r3);
    }
    free(t3);
  }
  done(&r1);
  free(t1);
}

/* ---------------------------------------------------------------- union */

static double area(const vec2 *p, int n) {
  double a = 0;
  for (int i = 0; i < n; i++) a += (p[i].x - p[0].x) * (p[(i + 1) % n].y - p[0].y) - (p[(i + 1) % n].x - p[0].x) * (p[i].y - p[0].y);
  return a / 2;
}

/* The slice's region area from the stack read: holes (cw: made clockwise
 * by the union) subtract; no other contour here lies inside another. */
static double slice_area(const contour_stack *s, double z) {
  double a = 0;
  for (int i = 0; i < s->n; i++)
    if (s->c[i].z == z) a += (s->c[i].cw ? -1 : 1) * area(s->c[i].pt, s->c[i].n);
  return a;
}

static void rect(poly *p, double x0, double y0, double x1, double y1, double z) {
  p->n = 4, p->z = z;
  p->p[0] = (vec2){x0, y0}, p->p[1] = (vec2){x1, y0}, p->p[2] = (vec2){x1, y1}, p->p[3] = (vec2){x0, y1};
}

/* Five rectangles a slice, three overlapping, on 6 slices 1 apart; the
 * second slice's three form a ring round a hole with an island in it. */
static void rectangles(void) {
  rng g;
  rng_seed(&g, 21);
  static poly ps[64];
  double rr[6][5][4];
  int np = 0;
  for (int k = 0; k < 6; k++)
    for (int i = 0; i < 5; i++) {
      double x0, y0, x1, y1;
      if (i < 3 && k != 1) {   /* three overlapping about (20, 20) */
        x0 = 10 + rng_int(&g, 0, 8), y0 = 10 + rng_int(&g, 0, 8);
        x1 = x0 + rng_int(&g, 6, 14) + 0.25, y1 = y0 + rng_int(&g, 6, 14) + 0.5;
      } else if (i < 3) {      /* a U and a bar: a ring round (18..22, 18..22) */
        static const double ring[3][4] = {{10, 10, 30, 18}, {10, 10, 18, 30}, {14, 22, 30, 30.5}};
        static const double bar[4] = {22, 10, 30, 30};
        const double *q = i < 2 ? ring[i] : ring[2];
        x0 = q[0], y0 = q[1], x1 = q[2], y1 = q[3];
        (void)bar;
      } else {                 /* apart */
        x0 = 50 + 20 * (i - 3), y0 = 5, x1 = x0 + 8, y1 = 12;
      }
      rr[k][i][0] = x0, rr[k][i][1] = y0, rr[k][i][2] = x1, rr[k][i][3] = y1;
      rect(&ps[np++], x0, y0, x1, y1, k);
    }
  /* the ring's right side, and the island */
  rr[1][3][0] = 22, rr[1][3][1] = 10, rr[1][3][2] = 30, rr[1][3][3] = 30;
  rect(&ps[5 + 3], 22, 10, 30, 30, 1);
  rect(&ps[np++], 19, 19, 21, 21, 1);
  size_t len;
  char *t = text_of(ps, np, NULL, NULL, NULL, &len);
  result r, r0;
  run(t, len, 0, &r0);
  run(t, len, CONTOUR_UNION, &r);
  CHECK(r.rc == 0, "rectangles: %s", r.err);
  if (r.rc == 0) {
    int bad = 0;
    for (int k = 0; k < 6; k++) {
      double want = ref_rects_area((const double (*)[4])rr[k], 4) + (rr[k][4][2] - rr[k][4][0]) * (rr[k][4][3] - rr[k][4][1]);
      double got = slice_area(&r.s, k);
      if (k == 1) want += 4;   /* the island */
      if (fabs(got - want) > 1e-12 * want) {
        bad++;
        CHECK(0, "rectangles, slice %d: area %.17g, want %.17g", k, got, want);
      }
    }
    int holes = 0;
    for (int i = 0; i < r.s.n; i++) holes += r.s.c[i].cw;
    char why[300];
    CHECK(bad == 0 && holes == 1 && closed(&r, why, sizeof why), "rectangles: %d holes; mesh %s", holes, why);
    CHECK(lines(r.notes) == 1 && strstr(r.notes, "--union: merged 19 overlapping contours in 6 groups on 6 slices"),
          "rectangles: notes '%s'", r.notes);
  }
  /* without --union: the same union, one note a slice naming its contours */
  int per_slice = 0;
  for (const char *p = r0.notes; p && (p = strstr(p, "overlapping contours on slice z=")); p++) per_slice++;
  CHECK(r0.rc == 0 && same_mesh(&r, &r0) && lines(r0.notes) == 6 && per_slice == 6 &&
            strstr(r0.notes, "(as --union does): the contours at line "),
        "rectangles without --union: %d '%s' '%s'", r0.rc, r0.err, r0.notes);
  done(&r0);
  /* re-encoded: the same mesh */
  rng_seed(&g, 4);
  int order[64], start[64], rev[64];
  for (int trial = 0; trial < 4; trial++) {
    for (int i = 0; i < np; i++) order[i] = i, start[i] = rng_int(&g, 0, 3), rev[i] = rng_int(&g, 0, 1);
    for (int i = np - 1; i > 0; i--) {
      int j = rng_int(&g, 0, i), tt = order[i];
      order[i] = order[j], order[j] = tt;
    }
    size_t l2;
    char *t2 = text_of(ps, np, order, start, rev, &l2);
    result r2;
    run(t2, l2, CONTOUR_UNION, &r2);
    CHECK(same_mesh(&r, &r2), "rectangles re-encoded (%d): another mesh", trial);
    done(&r2);
    free(t2);
  }
  done(&r);
  free(t);
}

/* Convex polygon p clipped by the half-plane left of ab (Sutherland-Hodgman). */
static int clip(const vec2 *p, int n, vec2 a, vec2 b, vec2 *out) {
  int m = 0;
  for (int i = 0; i < n; i++) {
    vec2 c = p[i], d = p[(i + 1) % n];
    double sc = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x), sd = (b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x);
    if (sc >= 0) out[m++] = c;
    if ((sc >= 0) != (sd >= 0)) {
      double u = sc / (sc - sd);
      out[m++] = (vec2){c.x + u * (d.x - c.x), c.y + u * (d.y - c.y)};
    }
  }
  return m;
}

static double inter(const poly *const *ps, int k) {
  vec2 a[256], b[256];
  int n = ps[0]->n;
  memcpy(a, ps[0]->p, (size_t)n * sizeof *a);
  for (int j = 1; j < k; j++)
    for (int e = 0; e < ps[j]->n && n > 0; e++) {
      n = clip(a, n, ps[j]->p[e], ps[j]->p[(e + 1) % ps[j]->n], b);
      memcpy(a, b, (size_t)n * sizeof *a);
    }
  return n >= 3 ? area(a, n) : 0;
}

/* Three rotated squares overlapping, two apart, on 5 slices: the union's
 * area against inclusion-exclusion (to 1e-12: new vertices are rounded). */
static void squares(void) {
  static poly ps[32];
  int np = 0;
  for (int k = 0; k < 5; k++)
    for (int i = 0; i < 5; i++) {
      poly *p = &ps[np++];
      p->n = 4, p->z = 1.5 * k;
      double cx = i < 3 ? 20 + 6 * cos(2.1 * i + k) : 60 + 25 * (i - 3), cy = i < 3 ? 20 + 6 * sin(2.1 * i + k) : 10;
      double r = i < 3 ? 9 + i : 5, ph = 0.3 * i + 0.17 * k;
      for (int j = 0; j < 4; j++) p->p[j] = (vec2){cx + r * cos(ph + j * 1.5707963267948966), cy + r * sin(ph + j * 1.5707963267948966)};
    }
  size_t len;
  char *t = text_of(ps, np, NULL, NULL, NULL, &len);
  result r;
  run(t, len, CONTOUR_UNION, &r);
  CHECK(r.rc == 0, "squares: %s", r.err);
  if (r.rc == 0) {
    double worst = 0;
    for (int k = 0; k < 5; k++) {
      const poly *q[3] = {&ps[5 * k], &ps[5 * k + 1], &ps[5 * k + 2]};
      double want = area(q[0]->p, 4) + area(q[1]->p, 4) + area(q[2]->p, 4) + area(ps[5 * k + 3].p, 4) + area(ps[5 * k + 4].p, 4);
      for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++) {
          const poly *pp[2] = {q[i], q[j]};
          want -= inter(pp, 2);
        }
      want += inter(q, 3);
      double d = fabs(slice_area(&r.s, 1.5 * k) - want) / want;
      if (d > worst) worst = d;
    }
    char why[300];
    CHECK(worst < 1e-12 && closed(&r, why, sizeof why), "squares: the union's area %.3g off inclusion-exclusion; mesh %s",
          worst, why);
  }
  done(&r);
  free(t);
}

/* ---------------------------------------------------------------- fixtures */

/* The structure sets tests/cli_readers.sh runs ./tile on, written by the
 * tests' DICOM writer (tests/rtwriter.c):
 *   cerr.dcm    ROI 1 'GTV': 13 slices of two contours; 3 contours cross
 *               themselves, 5 touch themselves at a point (pinch points):
 *               8 bad of 26, as CERR's phantom GTV; 3 have zero-width spurs
 *               (repaired: not bad);
 *   monaco.dcm  ROI 1 'External': an outline written three times a slice
 *               (other start points, direction, extra collinear points);
 *               ROI 2 'GTV': five pieces a slice, three overlapping;
 *   monaco_reenc.dcm  the same, every contour list shuffled, start points
 *               rotated, every other contour reversed. */
typedef struct {
  int n;
  double xyz[3 * 80];
} dcontour;

static void put_poly(dcontour *c, const vec2 *p, int n, double z, int start, int rev) {
  c->n = n;
  for (int j = 0; j < n; j++) {
    int i = rev ? ((start - j) % n + n) % n : (start + j) % n;
    c->xyz[3 * j] = p[i].x, c->xyz[3 * j + 1] = p[i].y, c->xyz[3 * j + 2] = z;
  }
}

static int write_file(const char *dir, const char *name, rtw_roi *roi, int nroi) {
  rtw_opts o = {0, 0, 0, 0, NULL, NULL, 0};
  size_t len;
  unsigned char *b = rtw_write(&o, roi, nroi, &len);
  int bad = rtw_save(dir, name, b, len);
  free(b);
  return bad;
}

static int write_fixtures(const char *dir) {
  static dcontour dc[3][64];
  static rtw_contour rc[3][64];
  int bad = 0;
  /* cerr.dcm */
  int n = 0;
  for (int k = 0; k < 13; k++) {
    double z = 3.0 * k;
    for (int side = 0; side < 2; side++) {
      double x = side * 40.0;
      vec2 p[16];
      int m;
      int i = 2 * k + side;   /* 3 crossings, 5 pinch points, 3 spurs, the rest fine */
      int kind = i == 0 || i == 5 || i == 10 ? 0 : i == 2 || i == 7 || i == 12 || i == 17 || i == 22 ? 3
               : i == 4 || i == 9 || i == 14 ? 6 : 7;
      if (kind <= 2) {   /* a bow tie in the middle of a square's top edge */
        vec2 q[] = {{x, 0}, {x + 20, 0}, {x + 20, 20}, {x + 12, 20}, {x + 8, 25}, {x + 12, 25}, {x + 8, 20}, {x, 20}};
        m = 8, memcpy(p, q, sizeof q);
      } else if (kind <= 5) {   /* two loops sharing one point */
        vec2 q[] = {{x, 0}, {x + 20, 0}, {x + 10, 10}, {x + 20, 20}, {x, 20}, {x + 10, 10}};
        m = 6, memcpy(p, q, sizeof q);
      } else if (kind == 6) {   /* a spur walked out and back */
        vec2 q[] = {{x, 0}, {x + 20, 0}, {x + 20, 10}, {x + 27, 10}, {x + 20, 10}, {x + 20, 20}, {x, 20}};
        m = 7, memcpy(p, q, sizeof q);
      } else {
        vec2 q[] = {{x, 0}, {x + 20, 0}, {x + 20, 20}, {x, 20}};
        m = 4, memcpy(p, q, sizeof q);
      }
      put_poly(&dc[0][n], p, m, z, 0, 0);
      rc[0][n] = (rtw_contour){NULL, m, dc[0][n].xyz, NULL, -1};
      n++;
    }
  }
  rtw_roi gtv = {1, "GTV", "GTV", n, rc[0], 0, 0};
  bad |= write_file(dir, "cerr.dcm", &gtv, 1);
  /* monaco.dcm and its re-encoding */
  for (int enc = 0; enc < 2; enc++) {
    rng g;
    rng_seed(&g, 17);
    int ne = 0, ng = 0;
    for (int k = 0; k < 6; k++) {
      double z = -5 + 2.5 * k;
      vec2 out[12], p[24];
      for (int i = 0; i < 12; i++) out[i] = (vec2){round(120 * cos(i * 0.5236)) + k, round(90 * sin(i * 0.5236))};
      for (int c = 0; c < 3; c++) {
        int m = 0;
        for (int i = 0; i < 12; i++) {
          p[m++] = out[i];
          if (c == 2 && fmod(out[i].x + out[(i + 1) % 12].x, 2) == 0 && fmod(out[i].y + out[(i + 1) % 12].y, 2) == 0)
            p[m++] = (vec2){(out[i].x + out[(i + 1) % 12].x) / 2, (out[i].y + out[(i + 1) % 12].y) / 2};
        }
        put_poly(&dc[1][ne], p, m, z, enc ? rng_int(&g, 0, m - 1) : 3 * c, enc ? ne % 2 : c == 1);
        rc[1][ne] = (rtw_contour){NULL, m, dc[1][ne].xyz, NULL, -1};
        ne++;
      }
      for (int i = 0; i < 5; i++) {
        double cx = i < 3 ? 6 * cos(2.1 * i + k) : -60 + 120 * (i - 3), cy = i < 3 ? 6 * sin(2.1 * i + k) : 40;
        double r = i < 3 ? 14 + 2 * i : 10, ph = 0.3 * i + 0.2 * k;
        for (int j = 0; j < 8; j++) p[j] = (vec2){cx + r * cos(ph + j * 0.7853981633974483), cy + r * sin(ph + j * 0.7853981633974483)};
        put_poly(&dc[2][ng], p, 8, z, enc ? rng_int(&g, 0, 7) : 0, enc ? ng % 2 : 0);
        rc[2][ng] = (rtw_contour){NULL, 8, dc[2][ng].xyz, NULL, -1};
        ng++;
      }
    }
    if (enc)
      for (int q = 1; q < 3; q++) {   /* the contours' order shuffled */
        int cnt = q == 1 ? ne : ng;
        for (int i = cnt - 1; i > 0; i--) {
          int j = rng_int(&g, 0, i);
          rtw_contour t = rc[q][i];
          rc[q][i] = rc[q][j], rc[q][j] = t;
        }
      }
    rtw_roi rois[2] = {{1, "External", "EXTERNAL", ne, rc[1], 0, 0}, {2, "GTV", "GTV", ng, rc[2], 0, 0}};
    bad |= write_file(dir, enc ? "monaco_reenc.dcm" : "monaco.dcm", rois, 2);
  }
  return bad;
}

int main(int argc, char **argv) {
  if (argc == 3 && strcmp(argv[1], "--write") == 0) return write_fixtures(argv[2]);
  copies();
  rectangles();
  squares();
  return check_done("test_slicemerge");
}
