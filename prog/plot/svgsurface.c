/* svgsurface.c -- orthographic view, painter's algorithm, Lambert shading. */
#include "prog/plot/svgsurface.h"

#include <math.h>
#include <stdlib.h>

#include "prog/plot/svgchart.h"
#include "util/xmem.h"

enum { W = 900, H = 520, PANEL = 420 };

/* The view: turn about z by az, then look down from el above the horizon:
 * the eye looks along (0, cos el, -sin el) in the turned frame, screen up is
 * (0, sin el, cos el). */
typedef struct { double ca, sa, ce, se; } view;

static void project(const view *v, double x, double y, double z, double *u, double *w, double *depth) {
  double x1 = v->ca * x - v->sa * y, y1 = v->sa * x + v->ca * y;   /* about z */
  *u = x1;
  *w = v->ce * z + v->se * y1;                                      /* screen up */
  *depth = v->ce * y1 - v->se * z;                                  /* away from the eye */
}

typedef struct { int t; double depth; } order;
static int by_depth(const void *a, const void *b) {
  const order *p = a, *q = b;
  if (p->depth != q->depth) return p->depth < q->depth ? 1 : -1;   /* far first */
  return p->t - q->t;
}

void svgsurface_write(FILE *f, const char *title, const contour_stack *s, const mesh *me) {
  view v = {cos(-0.6), sin(-0.6), cos(0.45), sin(0.45)};
  /* Bounds of the projection, for one scale in both panels. */
  double u0 = INFINITY, u1 = -INFINITY, w0 = INFINITY, w1 = -INFINITY;
  for (int i = 0; i < me->nv; i++) {
    double u, w, d;
    project(&v, me->v[i].x, me->v[i].y, me->v[i].z, &u, &w, &d);
    u0 = fmin(u0, u), u1 = fmax(u1, u), w0 = fmin(w0, w), w1 = fmax(w1, w);
  }
  double sc = fmin((PANEL - 40) / (u1 - u0), (H - 110) / (w1 - w0));
#define SX(u, off) ((off) + 20 + ((u) - u0) * sc + ((PANEL - 40) - (u1 - u0) * sc) / 2)
#define SY(w) (H - 50 - ((w) - w0) * sc)
  fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
             "font-family=\"Helvetica, Arial, sans-serif\" font-size=\"13\">\n", W, H, W, H);
  fprintf(f, "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n", W, H);
  fputs("<text x=\"20\" y=\"28\" font-size=\"16\" font-weight=\"bold\">", f);
  svg_text(f, title);
  fputs("</text>\n", f);
  fprintf(f, "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\">%d contours (input)</text>\n", 20 + PANEL / 2, H - 16, s->n);
  fprintf(f, "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\">the surface tilesim derives (%d triangles)</text>\n",
          40 + PANEL + PANEL / 2, H - 16, me->nt);
  /* Left: the contours. */
  for (int i = 0; i < s->n; i++) {
    const contour *c = &s->c[i];
    fputs("<polygon fill=\"none\" stroke=\"#1f4e79\" stroke-width=\"1.2\" points=\"", f);
    for (int j = 0; j < c->n; j++) {
      double u, w, d;
      project(&v, c->pt[j].x, c->pt[j].y, c->z, &u, &w, &d);
      fprintf(f, "%s%.2f,%.2f", j ? " " : "", SX(u, 0), SY(w));
    }
    fputs("\"/>\n", f);
  }
  /* Right: the triangles facing the eye, far to near, shaded. */
  order *o = xmallocarray((size_t)me->nt, sizeof *o);
  int n = 0;
  double lx = -0.45, ly = -0.55, lz = 0.70;   /* light, from the upper left front */
  double ex = 0, ey = -v.ce, ez = v.se;        /* towards the eye, in the turned frame */
  for (int t = 0; t < me->nt; t++) {
    double d = 0, u, w, dd;
    for (int k = 0; k < 3; k++) {
      vec3 p = me->v[me->t[t][k]];
      project(&v, p.x, p.y, p.z, &u, &w, &dd);
      d += dd;
    }
    o[n++] = (order){t, d / 3};
  }
  qsort(o, (size_t)n, sizeof *o, by_depth);
  for (int i = 0; i < n; i++) {
    const int *tr = me->t[o[i].t];
    vec3 a = me->v[tr[0]], b = me->v[tr[1]], c = me->v[tr[2]];
    double nx = (b.y - a.y) * (c.z - a.z) - (b.z - a.z) * (c.y - a.y);
    double ny = (b.z - a.z) * (c.x - a.x) - (b.x - a.x) * (c.z - a.z);
    double nz = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    double len = sqrt(nx * nx + ny * ny + nz * nz);
    if (len == 0) continue;
    nx /= len, ny /= len, nz /= len;
    double rx = v.ca * nx - v.sa * ny, ry = v.sa * nx + v.ca * ny;   /* normal, rotated */
    int back = rx * ex + ry * ey + nz * ez < 0;   /* the inside, seen through an opening */
    if (back) rx = -rx, ry = -ry, nz = -nz;
    double lam = rx * lx + ry * ly + nz * lz;
    double k = (back ? 0.55 : 1) * (0.28 + 0.72 * (lam > 0 ? lam : 0));
    int R = (int)(70 + 150 * k), G = (int)(110 + 130 * k), B = (int)(150 + 105 * k);
    fputs("<polygon points=\"", f);
    for (int q = 0; q < 3; q++) {
      vec3 p = me->v[tr[q]];
      double u, w, d;
      project(&v, p.x, p.y, p.z, &u, &w, &d);
      fprintf(f, "%s%.2f,%.2f", q ? " " : "", SX(u, PANEL + 20), SY(w));
    }
    fprintf(f, "\" fill=\"rgb(%d,%d,%d)\" stroke=\"rgb(%d,%d,%d)\" stroke-width=\"0.4\"/>\n", R, G, B, R, G, B);
  }
  free(o);
  fputs("</svg>\n", f);
#undef SX
#undef SY
}
