/* rtframe.c -- least-squares normals and frames (rtframe.h). */
#include "input/rtframe.h"

#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "util/args.h"
#include "input/decimal.h"
#include "util/strbuf.h"
#include "util/xmem.h"

/* Patient axis a (0 x, 1 y, 2 z) into the stack's z by the cyclic
 * permutation that keeps the axes right-handed: axial (x, y, z), sagittal
 * (y, z, x), coronal (z, x, y).  perm[k]: the patient axis of stack axis k. */
static const int perm_of[3][3] = {{1, 2, 0}, {2, 0, 1}, {0, 1, 2}};

/* The frame of the standard plane of patient axis `axis`. */
static rtstruct_frame standard_frame(int axis) {
  rtstruct_frame f;
  memset(&f, 0, sizeof f);
  const int *pm = perm_of[axis];
  f.u[pm[0]] = 1, f.v[pm[1]] = 1, f.n[pm[2]] = 1;
  return f;
}

typedef struct {
  double p[3];
} pt3;

static int by_xyz(const void *a, const void *b) {
  const double *p = ((const pt3 *)a)->p, *q = ((const pt3 *)b)->p;
  for (int k = 0; k < 3; k++)
    if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
  return 0;
}

static int by_six(const void *a, const void *b) {
  const double *p = a, *q = b;
  for (int k = 0; k < 6; k++)
    if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
  return 0;
}

/* The scatter of the contour's points about their mean, xx xy xz yy yz zz,
 * summed over the points sorted (x, y, z): a function of the point set,
 * whatever the start point and direction. */
static void scatter(const rtstruct_contour *c, double s[6]) {
  pt3 *q = xmallocarray((size_t)c->n, sizeof *q);
  memcpy(q, c->p, (size_t)c->n * sizeof *q);
  qsort(q, (size_t)c->n, sizeof *q, by_xyz);
  double m[3] = {0, 0, 0};
  for (int j = 0; j < c->n; j++)
    for (int k = 0; k < 3; k++) m[k] += q[j].p[k];
  for (int k = 0; k < 3; k++) m[k] /= c->n;
  memset(s, 0, 6 * sizeof *s);
  for (int j = 0; j < c->n; j++) {
    double d[3] = {q[j].p[0] - m[0], q[j].p[1] - m[1], q[j].p[2] - m[2]};
    s[0] += d[0] * d[0], s[1] += d[0] * d[1], s[2] += d[0] * d[2];
    s[3] += d[1] * d[1], s[4] += d[1] * d[2], s[5] += d[2] * d[2];
  }
  free(q);
}

/* The unit eigenvector of the least eigenvalue of the symmetric matrix s
 * (xx xy xz yy yz zz): cyclic Jacobi rotations (Numerical Recipes 11.1)
 * until the off-diagonal is zero, at most 64 sweeps.  Deterministic. */
static void least_eigenvector(const double s[6], double n[3]) {
  double a[3][3] = {{s[0], s[1], s[2]}, {s[1], s[3], s[4]}, {s[2], s[4], s[5]}};
  double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  static const int pq[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int sweep = 0; sweep < 64; sweep++) {
    if (a[0][1] == 0 && a[0][2] == 0 && a[1][2] == 0) break;
    for (int r = 0; r < 3; r++) {
      int p = pq[r][0], q = pq[r][1];
      if (a[p][q] == 0) continue;
      double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
      double t = fabs(theta) > 1e150 ? 1 / (2 * theta)
                                      : (theta >= 0 ? 1 : -1) / (fabs(theta) + sqrt(theta * theta + 1));
      double c = 1 / sqrt(t * t + 1), sn = t * c;
      double P[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, b[3][3], w[3][3];
      P[p][p] = c, P[q][q] = c, P[p][q] = sn, P[q][p] = -sn;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) b[i][j] = a[i][0] * P[0][j] + a[i][1] * P[1][j] + a[i][2] * P[2][j];
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) a[i][j] = P[0][i] * b[0][j] + P[1][i] * b[1][j] + P[2][i] * b[2][j];
      a[p][q] = a[q][p] = 0;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) w[i][j] = v[i][0] * P[0][j] + v[i][1] * P[1][j] + v[i][2] * P[2][j];
      memcpy(v, w, sizeof v);
    }
  }
  int k = 0;
  for (int i = 1; i < 3; i++)
    if (a[i][i] < a[k][k]) k = i;
  double len = sqrt(v[0][k] * v[0][k] + v[1][k] * v[1][k] + v[2][k] * v[2][k]);
  for (int i = 0; i < 3; i++) n[i] = v[i][k] / len;
}

/* The smallest rotation that takes z to the unit normal n (its axis z x n),
 * after the permutation that brings n's largest component into z: the
 * frame's u, v and n in patient coordinates (u, v the images of x and y). */
static rtstruct_frame oblique_frame(const double nin[3]) {
  int axis = 2;   /* z, then x, then y on a tie, as the standard planes */
  if (fabs(nin[0]) > fabs(nin[axis])) axis = 0;
  if (fabs(nin[1]) > fabs(nin[axis])) axis = 1;
  const int *pm = perm_of[axis];
  double sg = nin[pm[2]] < 0 ? -1 : 1;
  double a = sg * nin[pm[0]], b = sg * nin[pm[1]], c = sg * nin[pm[2]];
  double u[3] = {1 - a * a / (1 + c), -a * b / (1 + c), -a}, v[3] = {-a * b / (1 + c), 1 - b * b / (1 + c), -b};
  double w[3] = {a, b, c};
  rtstruct_frame f;
  memset(&f, 0, sizeof f);
  for (int k = 0; k < 3; k++) f.u[pm[k]] = u[k], f.v[pm[k]] = v[k], f.n[pm[k]] = w[k];
  f.angle = atan2(sqrt(a * a + b * b), c) * (180 / 3.14159265358979323846);
  return f;
}

double rtframe_dot(const double a[3], const double *p) { return a[0] * p[0] + a[1] * p[1] + a[2] * p[2]; }

static int by_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/* The spread of the contour's points along the unit vector n. */
static double spread_along(const rtstruct_contour *c, const double n[3]) {
  double lo = 0, hi = 0;
  for (int j = 0; j < c->n; j++) {
    double d = rtframe_dot(n, c->p + 3 * j);
    if (j == 0 || d < lo) lo = d;
    if (j == 0 || d > hi) hi = d;
  }
  return hi - lo;
}

/* How finely the ROI's coordinates were written: the least over its values
 * of the last digit's place value in each one's shortest decimal form
 * (decimal_quantum: an exporter that trims trailing zeros still writes
 * most values to its full precision).  Found once an ROI needs it: one not
 * exactly flat. */
static double quantum(const rtstruct_roi *roi) {
  double q = INFINITY;
  for (int i = 0; i < roi->nc; i++) {
    const rtstruct_contour *c = &roi->c[i];
    for (int v = 0; v < 3 * c->n; v++) {
      double d = decimal_quantum(c->p[v]);
      if (d > 0 && d < q) q = d;
    }
  }
  return q;
}

/* How far apart along the unit vector n points may lie and still be in one
 * plane, for coordinates rounded to the quantum q: each is within q/2 of
 * the number it stands for in x, y and z, so a point within (q/2)(|nx| +
 * |ny| + |nz|) of the plane it lies in, two points within twice that; a
 * quarter more for the least-squares normal's own error.  At least
 * RTFRAME_FLAT, at most RTFRAME_BENT. */
static double tolerance(double q, const double n[3]) {
  double t = 1.25 * q * (fabs(n[0]) + fabs(n[1]) + fabs(n[2]));
  return t < RTFRAME_FLAT ? RTFRAME_FLAT : t > RTFRAME_BENT ? RTFRAME_BENT : t;
}

/* Contours in parallel planes of a common normal that is none of the axes.
 * Each contour must be planar by itself: within the tolerance
 * of its coordinates' precision (tolerance()) of the least-squares plane of
 * its points (the least eigenvector of their
 * scatter).  The common normal is the least-squares normal of all the ROI's
 * points to a plane per contour: the least eigenvector of the summed
 * scatters, summed in sorted order, so that neither the file's order of the
 * contours nor their start points and directions change a bit of it.  Each
 * contour's height is the lower median of its points' (an input's own,
 * whatever the order), and each must lie within the tolerance of it.  0, or
 * -1 naming the first contour that is not planar, else the one most tilted
 * to the others. */
static int oblique(rtstruct_roi *roi, double q, char **warn, int *badc, char *why, size_t whylen) {
  double *sc = xmallocarray((size_t)roi->nc * 6, sizeof *sc), sum[6] = {0, 0, 0, 0, 0, 0}, nrm[3];
  const double deg = 180 / 3.14159265358979323846;
  for (int i = 0; i < roi->nc; i++) {
    const rtstruct_contour *c = &roi->c[i];
    double n1[3], sp;
    scatter(c, sc + 6 * i);
    least_eigenvector(sc + 6 * i, n1);
    if ((sp = spread_along(c, n1)) > tolerance(q, n1)) {
      snprintf(why, whylen, "contour item %d: not planar (its points spread %.3g mm off their best plane, more than "
               "the %.3g mm their precision allows): contours must lie in parallel planes", c->item, sp,
               tolerance(q, n1));
      *badc = i;
      free(sc);
      return -1;
    }
  }
  qsort(sc, (size_t)roi->nc, 6 * sizeof *sc, by_six);
  for (int i = 0; i < roi->nc; i++)
    for (int k = 0; k < 6; k++) sum[k] += sc[6 * i + k];
  free(sc);
  least_eigenvector(sum, nrm);
  rtstruct_frame f = oblique_frame(nrm);
  double worst = 0, tol = tolerance(q, f.n);
  int bad = -1;
  for (int i = 0; i < roi->nc; i++) {
    rtstruct_contour *c = &roi->c[i];
    double *h = xmallocarray((size_t)c->n, sizeof *h);
    for (int j = 0; j < c->n; j++) h[j] = rtframe_dot(f.n, c->p + 3 * j);
    qsort(h, (size_t)c->n, sizeof *h, by_double);
    double spread = h[c->n - 1] - h[0];
    c->h = h[(c->n - 1) / 2];
    free(h);
    if (spread > worst) worst = spread, bad = spread > tol ? i : -1;
  }
  if (bad >= 0) {
    const rtstruct_contour *c = &roi->c[bad];
    double s1[6], n1[3];
    scatter(c, s1);
    least_eigenvector(s1, n1);
    double cosang = fabs(rtframe_dot(n1, f.n));
    snprintf(why, whylen,
             "contour item %d: planar, but tilted %.3g degrees to the plane of the ROI's other contours "
             "(their normal %.6f %.6f %.6f; its points spread %.3g mm along it): contours must lie in "
             "parallel planes", c->item, acos(cosang > 1 ? 1 : cosang) * deg, f.n[0], f.n[1], f.n[2], worst);
    *badc = bad;
    return -1;
  }
  roi->plane = RTSTRUCT_OBLIQUE;
  roi->frame = f;
  roi->flat = tol;
  int axis = fabs(f.n[2]) >= fabs(f.n[0]) && fabs(f.n[2]) >= fabs(f.n[1]) ? 2 : fabs(f.n[0]) >= fabs(f.n[1]) ? 0 : 1;
  strbuf b = {0};
  strbuf_add(&b, "oblique contours: parallel planes tilted %.6g degrees from the %s plane (normal %s %s "
             "%s; each point within %.3g mm of its contour's plane): turned into z to be tiled, and the mesh "
             "turned back", f.angle, axis == 2 ? "axial" : axis == 0 ? "sagittal" : "coronal", ARGS_G(f.n[0]),
             ARGS_G(f.n[1]), ARGS_G(f.n[2]), worst);
  *warn = b.buf;
  return 0;
}

/* The spread of contour c's points along axis a. */
static double axis_spread(const rtstruct_contour *c, int a) {
  double lo = c->p[a], hi = c->p[a];
  for (int j = 1; j < c->n; j++) {
    double v = c->p[3 * j + a];
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  return hi - lo;
}

int rtframe_fit(rtstruct_roi *roi, char **warn, int *bad, char *why, size_t whylen) {
  *warn = NULL;
  int axis = -1, first[3] = {-1, -1, -1}, nc = roi->nc;
  double worst[3] = {0, 0, 0}, most[3] = {0, 0, 0}, q = 0, tol = RTFRAME_FLAT;
  double *sp = xmallocarray(3 * (size_t)nc + 1, sizeof *sp);   /* each contour's spread along x, y, z */
  for (int i = 0; i < nc; i++) sp[3 * i + 2] = axis_spread(&roi->c[i], 2), most[2] = fmax(most[2], sp[3 * i + 2]);
  if (most[2] > RTFRAME_FLAT) {   /* not flat in z to RTFRAME_FLAT: the other axes, and perhaps the precision */
    for (int i = 0; i < nc; i++)
      for (int a = 0; a < 2; a++) sp[3 * i + a] = axis_spread(&roi->c[i], a), most[a] = fmax(most[a], sp[3 * i + a]);
    if (most[0] > RTFRAME_FLAT && most[1] > RTFRAME_FLAT) q = quantum(roi), tol = tolerance(q, (const double[3]){1, 0, 0});
  }
  for (int a = 2; a >= 0 && (a == 2 || most[2] > RTFRAME_FLAT); a--)   /* z (axial), then x (sagittal), then y */
    for (int i = 0; i < nc; i++) {
      double d = sp[3 * i + a];
      if (d > tol) {
        if (first[a] < 0) first[a] = i;
      } else if (d > worst[a]) {
        worst[a] = d;
      }
    }
  free(sp);
  if (first[2] < 0) axis = 2;
  else if (first[0] < 0) axis = 0;
  else if (first[1] < 0) axis = 1;
  if (axis < 0) return oblique(roi, q, warn, bad, why, whylen);
  roi->plane = axis == 2 ? RTSTRUCT_AXIAL : axis == 0 ? RTSTRUCT_SAGITTAL : RTSTRUCT_CORONAL;
  roi->flat = tol;
  roi->frame = standard_frame(axis);
  if (worst[axis] > 0) {
    strbuf b = {0};
    strbuf_add(&b, "some contours are not exactly flat (%s spread up to %.3g mm); each lies in its first point's "
               "plane", axis == 2 ? "z" : axis == 0 ? "x" : "y", worst[axis]);
    *warn = b.buf;
  }
  for (int i = 0; i < roi->nc; i++) roi->c[i].h = roi->c[i].p[axis];
  return 0;
}
