/* reference.c -- independent references several tests share (reference.h). */
#include "tests/reference.h"

#include <stdlib.h>

#include "tests/check.h"
#include "util/xmem.h"

static void sort(double *x, int n) {
  for (int i = 1; i < n; i++)
    for (int j = i; j > 0 && x[j - 1] > x[j]; j--) {
      double t = x[j];
      x[j] = x[j - 1], x[j - 1] = t;
    }
}

double ref_rects_area(const double (*r)[4], int n) {
  double xs[64], ys[64];
  int nx = 0, ny = 0;
  for (int i = 0; i < n; i++) xs[nx++] = r[i][0], xs[nx++] = r[i][2], ys[ny++] = r[i][1], ys[ny++] = r[i][3];
  sort(xs, nx);
  sort(ys, ny);
  double a = 0;
  for (int i = 0; i + 1 < nx; i++)
    for (int j = 0; j + 1 < ny; j++) {
      double cx = (xs[i] + xs[i + 1]) / 2, cy = (ys[j] + ys[j + 1]) / 2;
      for (int k = 0; k < n; k++)
        if (r[k][0] < cx && cx < r[k][2] && r[k][1] < cy && cy < r[k][3]) {
          a += (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]);
          break;
        }
    }
  return a;
}

int ref_convex_apart(const vec2 *p, int np, const vec2 *q, int nq, int closed) {
  for (int pass = 0; pass < 2; pass++) {
    const vec2 *a = pass ? q : p, *b = pass ? p : q;
    int na = pass ? nq : np, nb = pass ? np : nq;
    double s = geom_area2(a, na) > 0 ? 1 : -1;
    for (int i = 0; i < na; i++) {
      vec2 u = a[i], v = a[(i + 1) % na];
      int out = 1;
      for (int j = 0; j < nb && out; j++) {
        double c = s * ((v.x - u.x) * (b[j].y - u.y) - (v.y - u.y) * (b[j].x - u.x));
        if (closed ? c >= 0 : c > 0) out = 0;
      }
      if (out) return 1;
    }
  }
  return 0;
}

int ref_symmetric(int (*f)(const inside_index *, const inside_index *), const char *what, const vec2 *p, int np,
                  const vec2 *q, int nq) {
  inside_index *a = inside_new(p, np), *b = inside_new(q, nq);
  int r = f(a, b), r2 = f(b, a);
  CHECK(r == r2, "%s is not symmetric (%d, %d)", what, r, r2);
  inside_free(a);
  inside_free(b);
  return r;
}

void ref_mc_mesh(mc_mesh *m, const mesh *me) {
  double *v = xmallocarray(3 * (size_t)me->nv + 1, sizeof *v);
  for (int i = 0; i < me->nv; i++) v[3 * i] = me->v[i].x, v[3 * i + 1] = me->v[i].y, v[3 * i + 2] = me->v[i].z;
  mc_make(m, v, me->nv, me->nt ? &me->t[0][0] : NULL, me->nt);
  free(v);
}

double ref_judge_mesh(const char *what, const mesh *me, const sg_poly *ps, int np, int comps, const int *chi) {
  mc_mesh m;
  ref_mc_mesh(&m, me);
  mc_report r;
  mc_check(&m, &r);
  CHECK(r.manifold && r.outward, "%s: not a closed outward manifold: %s", what, r.first);
  CHECK(comps < 0 || r.ncomp == comps, "%s: %d components, want %d", what, r.ncomp, comps);
  for (int c = 0; c < r.ncomp && c < comps && chi; c++)
    CHECK(r.chi[c] == chi[c], "%s: component %d: Euler characteristic %d, want %d", what, c, r.chi[c], chi[c]);
  mc_poly *cp = xmallocarray((size_t)np + 1, sizeof *cp);
  double *xy = xmallocarray(2 * (size_t)np * SG_N + 1, sizeof *xy);
  double *x = xy, *y = xy + (size_t)np * SG_N;
  for (int i = 0; i < np; i++) {
    for (int k = 0; k < ps[i].n; k++) x[i * SG_N + k] = ps[i].p[k].x, y[i * SG_N + k] = ps[i].p[k].y;
    cp[i] = (mc_poly){ps[i].n, ps[i].z, x + i * SG_N, y + i * SG_N};
  }
  mc_fidelity fd;
  mc_check_input(&m, cp, np, &fd);
  CHECK(fd.missing == 0 && fd.absent == 0 && fd.strays == 0 && fd.crossing == 0,
        "%s: %d segments missing, %d points absent, %d strays, %d crossing", what, fd.missing, fd.absent,
        fd.strays, fd.crossing);
  double vol = r.volume;
  mc_fidelity_free(&fd);
  mc_report_free(&r);
  mc_free(&m);
  free(xy), free(cp);
  return vol;
}
