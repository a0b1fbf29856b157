/* test_oblique.c -- oblique stacks: an RT structure set whose
 * contours lie in parallel planes tilted from every axis, written by the
 * tests' own writer (tests/rtwriter.c), against the same set written axial.
 *
 * The set is Varian-like: planes 2 mm apart, an outline of one contour a
 * slice, and a structure of two pieces a slice, one with a hole on some
 * slices; the tilt 6 degrees about an axis in the axial plane (and, for the
 * second case, a sagittal set tilted alike).  The reader must find the
 * tilt's normal, turn the contours into z by the smallest rotation, and the
 * mesh back: the same triangles as the axial set's, and every vertex the
 * axial vertex rotated, within 1e-12 of the set's size.  The same set
 * re-encoded -- contours shuffled, start points rotated, directions
 * reversed -- gives a bit-identical mesh.  A contour tilted 2 degrees more,
 * and one not planar, are refused, naming it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/gen.h"
#include "surface/mesh.h"
#include "util/rng.h"
#include "input/rtstruct.h"
#include "tests/rtwriter.h"
#include "surface/stack.h"
#include "util/xmem.h"

enum { SLICES = 14, MAXC = 4 * SLICES, MAXP = 80 };

/* The axial set: contours (points x y, plane z) of two ROIs. */
typedef struct {
  int nc[2];
  int n[2][MAXC];
  double z[2][MAXC];
  vec2 p[2][MAXC][MAXP];
} axial_set;

static void make_axial(axial_set *a) {
  rng r;
  rng_seed(&r, 2206);
  memset(a, 0, sizeof *a);
  for (int k = 0; k < SLICES; k++) {
    double z = -13 + 2.0 * k;
    int i = a->nc[0]++;   /* the outline */
    a->n[0][i] = 60, a->z[0][i] = z;
    gen_star(&r, a->p[0][i], 60, 3 * sin(k), 2, 90 - 2 * fabs(k - 7.0), 0.08);
    for (int side = -1; side <= 1; side += 2) {   /* two pieces */
      i = a->nc[1]++;
      a->n[1][i] = 40 + side * 7, a->z[1][i] = z;
      gen_star(&r, a->p[1][i], a->n[1][i], side * 40.0 + k, -5, 22 - fabs(k - 6.5), 0.15);
    }
    if (k >= 4 && k <= 9) {   /* a hole in the right piece */
      i = a->nc[1]++;
      a->n[1][i] = 9, a->z[1][i] = z;
      gen_star(&r, a->p[1][i], 9, 40.0 + k, -5, 5, 0.1);
    }
  }
  /* Full doubles, not two decimals as planning systems write: on a 0.01 mm
   * grid many quads of a band are exactly planar (an edge below exactly
   * parallel to one above), so the band has several optima of exactly equal
   * cost, and the rotated stack, a rounding away, may take another of them
   * (found with two decimals: same cost, other triangles in 2 bands of 42).
   * Without exact ties the optimum is the same path. */
}

/* Rotation by `deg` degrees about the unit axis (ax, ay, az) (Rodrigues). */
static void rotation(double ax, double ay, double az, double deg, double R[3][3]) {
  double t = deg * 3.14159265358979323846 / 180, c = cos(t), s = sin(t), C = 1 - c;
  double M[3][3] = {{c + ax * ax * C, ax * ay * C - az * s, ax * az * C + ay * s},
                    {ay * ax * C + az * s, c + ay * ay * C, ay * az * C - ax * s},
                    {az * ax * C - ay * s, az * ay * C + ax * s, c + az * az * C}};
  memcpy(R, M, sizeof M);
}

static void apply(double R[3][3], const double p[3], double o[3]) {
  for (int i = 0; i < 3; i++) o[i] = R[i][0] * p[0] + R[i][1] * p[1] + R[i][2] * p[2];
}

/* How a contour is written: its place in the file, its start point, its
 * direction. */
typedef struct {
  int order[2][MAXC];
  int start[2][MAXC], rev[2][MAXC];
} encoding;

static void plain(const axial_set *a, encoding *e) {
  memset(e, 0, sizeof *e);
  for (int q = 0; q < 2; q++)
    for (int i = 0; i < a->nc[q]; i++) e->order[q][i] = i;
}

static void shuffled(const axial_set *a, encoding *e, uint64_t seed) {
  rng r;
  rng_seed(&r, seed);
  plain(a, e);
  for (int q = 0; q < 2; q++) {
    for (int i = a->nc[q] - 1; i > 0; i--) {
      int j = rng_int(&r, 0, i), t = e->order[q][i];
      e->order[q][i] = e->order[q][j], e->order[q][j] = t;
    }
    for (int i = 0; i < a->nc[q]; i++) e->start[q][i] = rng_int(&r, 0, a->n[q][i] - 1), e->rev[q][i] = rng_int(&r, 0, 1);
  }
}

/* The set as a file: each point (x, y, z) through `perm` (patient axis k
 * takes the set's axis perm[k]: the plane the set is drawn in) and then R. */
static unsigned char *write_set(const axial_set *a, const int perm[3], double R[3][3], const encoding *e,
                                size_t *len) {
  static double xyz[2][MAXC][3 * MAXP];
  rtw_contour c[2][MAXC];
  rtw_roi roi[2];
  for (int q = 0; q < 2; q++) {
    for (int f = 0; f < a->nc[q]; f++) {
      int i = e->order[q][f], n = a->n[q][i];
      for (int j = 0; j < n; j++) {
        int s = e->rev[q][i] ? (e->start[q][i] - j + 2 * n) % n : (e->start[q][i] + j) % n;
        double set[3] = {a->p[q][i][s].x, a->p[q][i][s].y, a->z[q][i]}, pt[3];
        for (int k = 0; k < 3; k++) pt[k] = set[perm[k]];
        apply(R, pt, xyz[q][f] + 3 * j);
      }
      c[q][f] = (rtw_contour){NULL, n, xyz[q][f], NULL, -1};
    }
    roi[q] = (rtw_roi){q + 1, q ? "Lungs" : "Body", q ? "ORGAN" : "EXTERNAL", a->nc[q], c[q], 0, 0};
  }
  rtw_opts o = {0, 0, 0, 0, NULL, NULL, 0};
  return rtw_write(&o, roi, 2, len);
}

/* The ROI tiled with caps, its mesh turned back into patient coordinates. */
static int tile_roi(const rtstruct *s, int q, mesh *me, char *err, size_t errlen) {
  contour_stack st;
  memset(me, 0, sizeof *me);
  if (rtstruct_roi_stack(s, q, 0, &st, NULL, "t", err, errlen) != 0) return -1;
  stack_options o = {COST_AREA, 1, 0, 2, NULL, NULL, "t", NULL, NULL, MATCH_SINGLE, INFINITY, 0, STACK_BAND_ALIGNED};
  stack_surface *ss = NULL;
  int rc = stack_tile(&st, "t", &o, &ss, err, errlen);
  if (rc == 0) {
    stack_take_mesh(ss, me);
    for (int v = 0; v < me->nv; v++) rtstruct_to_patient(&s->roi[q], &me->v[v].x, &me->v[v].y, &me->v[v].z);
  }
  stack_free(ss);
  contour_stack_free(&st);
  return rc;
}

static int parse(const unsigned char *b, size_t len, rtstruct *s) {
  char err[1024];
  if (rtstruct_parse(b, len, "oblique.dcm", s, err, sizeof err) == 0) return 0;
  CHECK(0, "%s", err);
  return -1;
}

/* The set drawn in `perm`'s plane, tilted by R, against the same set
 * untilted: plane, normal, angle, the same triangles, vertices rotated. */
static void against_axial(const char *what, const int perm[3], double R[3][3], double angle,
                          rtstruct_plane untilted) {
  static axial_set a;
  make_axial(&a);
  double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  encoding e;
  plain(&a, &e);
  size_t la, lt;
  unsigned char *ba = write_set(&a, perm, I, &e, &la), *bt = write_set(&a, perm, R, &e, &lt);
  rtstruct sa, st;
  if (parse(ba, la, &sa) != 0 || parse(bt, lt, &st) != 0) return;
  /* The untilted set's normal, tilted, is the tilted set's. */
  double n0[3] = {0, 0, 0}, n[3];
  n0[untilted == RTSTRUCT_AXIAL ? 2 : untilted == RTSTRUCT_SAGITTAL ? 0 : 1] = 1;
  apply(R, n0, n);
  for (int q = 0; q < 2; q++) {
    const rtstruct_roi *ra = &sa.roi[q], *rt = &st.roi[q];
    CHECK(!ra->error && !rt->error && ra->plane == untilted && rt->plane == RTSTRUCT_OBLIQUE,
          "%s ROI %d: planes %s and %s (%s)", what, q + 1, rtstruct_plane_name(ra->plane),
          rtstruct_plane_name(rt->plane), rt->error ? rt->error : "");
    if (ra->error || rt->error) continue;
    double dn = fabs(rt->frame.n[0] - n[0]) + fabs(rt->frame.n[1] - n[1]) + fabs(rt->frame.n[2] - n[2]);
    CHECK(dn < 1e-14 && fabs(rt->frame.angle - angle) < 1e-10 && rt->slices == SLICES && ra->slices == SLICES,
          "%s ROI %d: normal %.17g %.17g %.17g (want %.17g %.17g %.17g), angle %.17g, %d slices", what, q + 1,
          rt->frame.n[0], rt->frame.n[1], rt->frame.n[2], n[0], n[1], n[2], rt->frame.angle, rt->slices);
    CHECK(rt->warnings && strstr(rt->warnings, "oblique contours: parallel planes tilted 6 degrees"),
          "%s ROI %d: the note: %s", what, q + 1, rt->warnings ? rt->warnings : "none");
    mesh ma, mt;
    char err[1024];
    if (tile_roi(&sa, q, &ma, err, sizeof err) != 0 || tile_roi(&st, q, &mt, err, sizeof err) != 0) {
      CHECK(0, "%s ROI %d: %s", what, q + 1, err);
      mesh_free(&ma), mesh_free(&mt);
      continue;
    }
    int same = ma.nv == mt.nv && ma.nt == mt.nt && ma.nt > 0 &&
               memcmp(ma.t, mt.t, (size_t)ma.nt * sizeof *ma.t) == 0;
    double worst = 0, size = 0;
    for (int v = 0; same && v < ma.nv; v++) {
      double p[3] = {ma.v[v].x, ma.v[v].y, ma.v[v].z}, w[3];
      apply(R, p, w);
      worst = fmax(worst, fmax(fabs(w[0] - mt.v[v].x), fmax(fabs(w[1] - mt.v[v].y), fabs(w[2] - mt.v[v].z))));
      size = fmax(size, fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2]))));
    }
    int first = -1;
    for (int t = 0; t < ma.nt && t < mt.nt && first < 0; t++)
      if (memcmp(ma.t[t], mt.t[t], sizeof *ma.t) != 0) first = t;
    CHECK(same, "%s ROI %d: meshes of %d and %d vertices, %d and %d triangles, other triangles from %d", what, q + 1,
          ma.nv, mt.nv, ma.nt, mt.nt, first);
    CHECK(same && worst <= 1e-12 * size, "%s ROI %d: a vertex %.3g from the axial one rotated (size %g)", what,
          q + 1, worst, size);
    mesh_free(&ma), mesh_free(&mt);
  }
  rtstruct_free(&sa), rtstruct_free(&st);
  free(ba), free(bt);
}

/* Re-encoded (shuffled, rotated start points, reversed): the same bytes. */
static void reencoded(void) {
  static axial_set a;
  make_axial(&a);
  double R[3][3];
  rotation(cos(0.5), sin(0.5), 0, 6, R);
  static const int axial[3] = {0, 1, 2};
  encoding e;
  plain(&a, &e);
  size_t l0;
  unsigned char *b0 = write_set(&a, axial, R, &e, &l0);
  rtstruct s0;
  if (parse(b0, l0, &s0) != 0) return;
  mesh m0[2];
  char err[1024];
  for (int q = 0; q < 2; q++)
    if (tile_roi(&s0, q, &m0[q], err, sizeof err) != 0) CHECK(0, "re-encoding, ROI %d: %s", q + 1, err);
  for (uint64_t seed = 1; seed <= 4; seed++) {
    shuffled(&a, &e, seed);
    size_t l;
    unsigned char *b = write_set(&a, axial, R, &e, &l);
    rtstruct s;
    if (parse(b, l, &s) == 0) {
      for (int q = 0; q < 2; q++) {
        mesh m;
        if (tile_roi(&s, q, &m, err, sizeof err) != 0) {
          CHECK(0, "re-encoding %d, ROI %d: %s", (int)seed, q + 1, err);
          continue;
        }
        CHECK(memcmp(&s.roi[q].frame, &s0.roi[q].frame, sizeof s.roi[q].frame) == 0 && m.nv == m0[q].nv &&
                  m.nt == m0[q].nt && memcmp(m.v, m0[q].v, (size_t)m.nv * sizeof *m.v) == 0 &&
                  memcmp(m.t, m0[q].t, (size_t)m.nt * sizeof *m.t) == 0,
              "re-encoding %d, ROI %d: another frame or mesh", (int)seed, q + 1);
        mesh_free(&m);
      }
      rtstruct_free(&s);
    }
    free(b);
  }
  for (int q = 0; q < 2; q++) mesh_free(&m0[q]);
  rtstruct_free(&s0);
  free(b0);
}

/* One contour tilted 2 degrees more, or bent out of its plane: refused,
 * naming it. */
static void refusals(void) {
  static axial_set a;
  make_axial(&a);
  double R[3][3], R2[3][3];
  rotation(cos(0.5), sin(0.5), 0, 6, R);
  rotation(cos(0.5), sin(0.5), 0, 8, R2);
  static const int axial[3] = {0, 1, 2};
  encoding e;
  plain(&a, &e);
  for (int k = 0; k < 2; k++) {
    size_t len;
    unsigned char *b = write_set(&a, axial, R, &e, &len);
    /* Rewrite the outline's contour 5 (item 6) in the file: parse it,
     * change it, write again. */
    rtstruct s;
    if (parse(b, len, &s) != 0) {
      free(b);
      continue;
    }
    rtstruct_free(&s);
    free(b);
    static double xyz[2][MAXC][3 * MAXP];
    rtw_contour c[2][MAXC];
    rtw_roi roi[2];
    for (int q = 0; q < 2; q++) {
      for (int i = 0; i < a.nc[q]; i++) {
        for (int j = 0; j < a.n[q][i]; j++) {
          double p[3] = {a.p[q][i][j].x, a.p[q][i][j].y, a.z[q][i]};
          if (q == 0 && i == 5 && k == 1 && j == 7) p[2] += 0.01;   /* bent */
          apply(q == 0 && i == 5 && k == 0 ? R2 : R, p, xyz[q][i] + 3 * j);
        }
        c[q][i] = (rtw_contour){NULL, a.n[q][i], xyz[q][i], NULL, -1};
      }
      roi[q] = (rtw_roi){q + 1, q ? "Lungs" : "Body", NULL, a.nc[q], c[q], 0, 0};
    }
    rtw_opts o = {0, 0, 0, 0, NULL, NULL, 0};
    b = rtw_write(&o, roi, 2, &len);
    if (parse(b, len, &s) == 0) {
      const char *want = k == 0 ? "ROI 1 'Body', contour item 6: planar, but tilted "
                                : "ROI 1 'Body', contour item 6: not planar (its points spread 0.01 mm off their best plane, more than the 0.001 "
                                  "mm their precision allows)";
      CHECK(s.roi[0].error && strstr(s.roi[0].error, want) && !s.roi[1].error && s.roi[1].plane == RTSTRUCT_OBLIQUE,
            "%s: '%s'", k ? "bent" : "tilted", s.roi[0].error ? s.roi[0].error : "accepted");
      rtstruct_free(&s);
    }
    free(b);
  }
}

/* The files tests/cli_readers.sh runs ./tile on: the set untilted, tilted 6
 * degrees, and tilted and re-encoded. */
static int write_fixtures(const char *dir) {
  static axial_set a;
  make_axial(&a);
  static const int axial[3] = {0, 1, 2};
  double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, R[3][3];
  rotation(cos(0.5), sin(0.5), 0, 6, R);
  encoding e;
  int bad = 0;
  for (int k = 0; k < 3; k++) {
    if (k == 2) shuffled(&a, &e, 7);
    else plain(&a, &e);
    size_t len;
    unsigned char *b = write_set(&a, axial, k ? R : I, &e, &len);
    bad |= rtw_save(dir, k == 0 ? "axial.dcm" : k == 1 ? "oblique.dcm" : "oblique_reenc.dcm", b, len);
    free(b);
  }
  return bad;
}

int main(int argc, char **argv) {
  if (argc == 3 && strcmp(argv[1], "--write") == 0) return write_fixtures(argv[2]);
  static const int axial[3] = {0, 1, 2}, sagittal[3] = {2, 0, 1};
  double R[3][3];
  rotation(cos(3.14159265358979323846 / 6), sin(3.14159265358979323846 / 6), 0, 6, R);   /* about an axis in the axial plane */
  against_axial("axial set tilted 6 degrees", axial, R, 6, RTSTRUCT_AXIAL);
  rotation(0, cos(0.3), sin(0.3), 6, R);              /* about an axis in the sagittal plane */
  against_axial("sagittal set tilted 6 degrees", sagittal, R, 6, RTSTRUCT_SAGITTAL);
  reencoded();
  refusals();
  return check_done("test_oblique");
}
