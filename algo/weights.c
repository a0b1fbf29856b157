/* weights.c -- per-pair weight data: the quantum, per-point arrays, tables. */
#include "weights.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "kernel.h"
#include "xmem.h"

const char *cost_name(cost_kind k) { return k == COST_SPAN ? "span" : "area"; }

int cost_parse(const char *s, cost_kind *k) {
  if (strcmp(s, "area") == 0) *k = COST_AREA;
  else if (strcmp(s, "span") == 0) *k = COST_SPAN;
  else return -1;
  return 0;
}

static int mod(int a, int m) {
  int r = a % m;
  return r < 0 ? r + m : r;
}

/* An upper bound on every weight: a tile's area is at most half its contour
 * edge times the farthest distance between the contours; a span at most that
 * distance.  Symmetric in R and C, so a transposed pair gets the same scale. */
static double bound(const vec2 *R, int m, const vec2 *C, int n, double h2, cost_kind kind) {
  double x0 = R[0].x, x1 = R[0].x, y0 = R[0].y, y1 = R[0].y, e2 = 0;
  for (int s = 0; s < 2; s++) {
    const vec2 *p = s ? C : R;
    int k = s ? n : m;
    for (int i = 0; i < k; i++) {
      const vec2 *a = &p[i], *b = &p[(i + 1) % k];
      double dx = b->x - a->x, dy = b->y - a->y;
      if (dx * dx + dy * dy > e2) e2 = dx * dx + dy * dy;
      if (a->x < x0) x0 = a->x;
      if (a->x > x1) x1 = a->x;
      if (a->y < y0) y0 = a->y;
      if (a->y > y1) y1 = a->y;
    }
  }
  double d = sqrt((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0) + h2);
  return kind == COST_AREA ? 0.5 * sqrt(e2) * d : d;
}

weights *weights_new(const vec2 *R, int m, double zr, const vec2 *C, int n, double zc,
                     cost_kind kind, int table) {
  weights *w = xcalloc(1, sizeof *w);
  w->m = m;
  w->n = n;
  w->kind = kind;
  w->h2 = (zc - zr) * (zc - zr);

  /* The scale S = 2^k: (m+n+1) weights of at most bound*S + 1 quanta each
   * stay below 2^52, so every path sum is an exact integer. */
  double wb = bound(R, m, C, n, w->h2, kind) * 1.001 + DBL_MIN;
  double room = (0x1p52 / (double)(m + n + 1) - 1) / wb;
  int e;
  frexp(room, &e);   /* room = f 2^e, f in [0.5, 1): 2^(e-1) <= room */
  double S = ldexp(1.0, e - 1);
  w->quantum = 1 / S;
  w->sc = kind == COST_AREA ? S / 2 : S;

  size_t nr = (size_t)2 * m + 3, nc = (size_t)n + 3;
  double *a = xmallocarray(5 * (nr + nc), sizeof *a);
  w->rx = a, w->ry = a + nr, w->rex = a + 2 * nr, w->rey = a + 3 * nr, w->ree = a + 4 * nr;
  a += 5 * nr;
  w->cx = a, w->cy = a + nc, w->cfx = a + 2 * nc, w->cfy = a + 3 * nc, w->cff = a + 4 * nc;
  for (int r = -1; r <= 2 * m + 1; r++) {
    size_t i = (size_t)(2 * m + 1 - r);
    const vec2 *p = &R[mod(r, m)], *q = &R[mod(r + 1, m)];
    w->rx[i] = p->x, w->ry[i] = p->y;
    w->rex[i] = q->x - p->x, w->rey[i] = q->y - p->y;
    w->ree[i] = w->h2 * (w->rex[i] * w->rex[i] + w->rey[i] * w->rey[i]);
  }
  for (int c = -1; c <= n + 1; c++) {
    size_t i = (size_t)(c + 1);
    const vec2 *p = &C[mod(c, n)], *q = &C[mod(c + 1, n)];
    w->cx[i] = p->x, w->cy[i] = p->y;
    w->cfx[i] = q->x - p->x, w->cfy[i] = q->y - p->y;
    w->cff[i] = w->h2 * (w->cfx[i] * w->cfx[i] + w->cfy[i] * w->cfy[i]);
  }

  size_t cells = (size_t)m * (size_t)(n + 1);
  if (table < 0) table = 2 * cells * sizeof(double) <= WEIGHTS_TABLE_BYTES;
  if (table) {
    int nt = kind == COST_AREA ? 2 : 1;
    w->tv = xmallocarray(nt * cells, sizeof(double));
    w->th = kind == COST_AREA ? w->tv + cells : w->tv;
    for (int s = 0; s < m; s++)
      kernel_table_row(w, s, w->tv + (size_t)s * (n + 1),
                       kind == COST_AREA ? w->th + (size_t)s * (n + 1) : NULL);
  }
  return w;
}

void weights_free(weights *w) {
  if (!w) return;
  free(w->rx);
  free(w->tv);
  free(w);
}

double weights_v(const weights *w, int i, int j) {
  int m = w->m;
  size_t ri = (size_t)(2 * m + 1 - mod(i, m)), ci = (size_t)mod(j, w->n) + 1;
  if (w->kind == COST_SPAN)   /* the span R_{i+1} C_j */
    return weights_len(w->rx[ri - 1], w->ry[ri - 1], w->cx[ci], w->cy[ci], w->h2, w->sc);
  return weights_tri(w->ree[ri], w->rex[ri], w->rey[ri], w->rx[ri], w->ry[ri], w->cx[ci],
                     w->cy[ci], w->sc);
}

double weights_h(const weights *w, int i, int j) {
  int m = w->m;
  size_t ri = (size_t)(2 * m + 1 - mod(i, m)), ci = (size_t)mod(j, w->n) + 1;
  if (w->kind == COST_SPAN)   /* the span R_i C_{j+1} */
    return weights_len(w->rx[ri], w->ry[ri], w->cx[ci + 1], w->cy[ci + 1], w->h2, w->sc);
  return weights_tri(w->cff[ci], w->cfx[ci], w->cfy[ci], w->cx[ci], w->cy[ci], w->rx[ri],
                     w->ry[ri], w->sc);
}

double weights_quantum(const weights *w) { return w->quantum; }
int weights_has_table(const weights *w) { return w->tv != NULL; }

double weights_in(const weights *w, int k, int c, int vertical) {
  if (w->tv) {
    if (w->kind == COST_SPAN) return w->tv[(size_t)mod(k, w->m) * ((size_t)w->n + 1) + (size_t)c];
    if (vertical) return w->tv[(size_t)mod(k - 1, w->m) * ((size_t)w->n + 1) + (size_t)c];
    return w->th[(size_t)mod(k, w->m) * ((size_t)w->n + 1) + (size_t)c];
  }
  return vertical ? weights_v(w, k - c - 1, c) : weights_h(w, k - c, c - 1);
}
