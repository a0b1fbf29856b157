/* weights.c -- per-pair weight data: the quantum, per-point arrays, tables. */
#include "algo/weights.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "geom/hull.h"
#include "algo/kernel.h"
#include "util/words.h"
#include "util/xmem.h"

static const char *const cost_names[] = {"area", "span"};

const char *cost_name(cost_kind k) { return cost_names[k == COST_SPAN]; }

int cost_parse(const char *s, cost_kind *k) {
  int i = words_find(cost_names, 2, s);
  return i < 0 ? -1 : (*k = (cost_kind)i, 0);
}

static int mod(int a, int m) {
  int r = a % m;
  return r < 0 ? r + m : r;
}

/* --- the scale --------------------------------------------------------------
 * Every coordinate and the height h = zc - zr are multiplied by one power of
 * two 2^-e, chosen so that the largest of them lies in [1/2, 1), before any
 * arithmetic: no difference, product or sum can then overflow, and nothing
 * that matters underflows.  Scaling by a power of two is exact and commutes
 * with every rounding (away from overflow and underflow), so a pair and the
 * same pair scaled by 2^k give bit-identical weights in quanta, the same path
 * and costs exactly 2^2k (area) or 2^k (span) apart; at unit scale nothing
 * changes.  The quantum, in the caller's units, is 2^qexp with
 * qexp = -s + 2e (area) or -s + e (span), S = 2^s the scale of the quanta. */
static int scale_exponent(const vec2 *R, int m, const vec2 *C, int n, double zr, double zc) {
  double mx = 0;
  for (int i = 0; i < m; i++) mx = fmax(mx, fmax(fabs(R[i].x), fabs(R[i].y)));
  for (int i = 0; i < n; i++) mx = fmax(mx, fmax(fabs(C[i].x), fabs(C[i].y)));
  int e = 0, eh = 0;
  if (mx > 0) frexp(mx, &e);
  double h = zc - zr;
  if (isfinite(h)) {
    if (h != 0) frexp(h, &eh);
  } else {   /* |zc - zr| > DBL_MAX: half of it is finite */
    frexp(0.5 * zc - 0.5 * zr, &eh);
    eh++;
  }
  if (mx == 0) return eh;
  return h == 0 ? e : (e > eh ? e : eh);
}

/* --- the bound on a weight --------------------------------------------------
 * The quantum must leave every path's sum below 2^52 quanta, so it is chosen
 * from a bound on the largest weight of the pair's graph (any tile, not only
 * those of the best path).  Area: the tile with edge A -> A+e on one contour
 * and apex P on the other is sqrt(h^2 |e|^2 + cz^2) / 2 with
 * cz = e x (P - A), linear in P, so over all apexes it is largest at a vertex
 * of the other contour's convex hull extreme in the direction (-e_y, e_x) or
 * its opposite (hull.h, O(log n) each): the exact largest weight, computed
 * with the kernel's own arithmetic, for O((m + n) log(m + n)) in all.  The
 * kernel's cz for another apex may exceed the one evaluated here by rounding
 * (and the hull's search by its own): a few ulp of |e_x| D_y + |e_y| D_x,
 * D_x and D_y the largest differences in x and y from A to the other
 * contour's bounding box; 2^-44 (|e_x| D_y + |e_y| D_x) is added for it.  (The former bound, longest edge
 * times the bounding box's diagonal, was 2^36 too large on a spike * 3e11 long and 1 wide.)  Span: the bounding box's diagonal with h, within a
 * factor sqrt 2 of the longest span.  Both are symmetric in R and C, so a
 * transposed pair gets the same quantum. */
typedef struct { double x0, x1, y0, y1; } box;

static box bbox(const double *x, const double *y, int k) {
  box b = {x[0], x[0], y[0], y[0]};
  for (int i = 1; i < k; i++) {
    b.x0 = fmin(b.x0, x[i]), b.x1 = fmax(b.x1, x[i]);
    b.y0 = fmin(b.y0, y[i]), b.y1 = fmax(b.y1, y[i]);
  }
  return b;
}

static double area_bound_side(const double *x, const double *y, int k, const hull *other,
                              box ob, double h2) {
  double best = 0;
  for (int i = 0; i < k; i++) {
    int j = i + 1 == k ? 0 : i + 1;
    double ex = x[j] - x[i], ey = y[j] - y[i];
    double ee = h2 * (ex * ex + ey * ey), cz = 0;
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      vec2 P = hull_extreme(other, -ey * sgn, ex * sgn);
      double dx = P.x - x[i], dy = P.y - y[i];
      cz = fmax(cz, fabs(ex * dy - ey * dx));
    }
    double Dx = fmax(fabs(ob.x0 - x[i]), fabs(ob.x1 - x[i]));
    double Dy = fmax(fabs(ob.y0 - y[i]), fabs(ob.y1 - y[i]));
    cz += 0x1p-44 * (fabs(ex) * Dy + fabs(ey) * Dx);
    best = fmax(best, sqrt(ee + cz * cz));
  }
  return 0.5 * best;
}

static double bound(const double *rx, const double *ry, int m, const double *cx, const double *cy,
                    int n, double h2, cost_kind kind) {
  if (kind == COST_AREA) {
    vec2 *pr = xmallocarray((size_t)m, sizeof *pr), *pc = xmallocarray((size_t)n, sizeof *pc);
    for (int i = 0; i < m; i++) pr[i] = (vec2){rx[i], ry[i]};
    for (int i = 0; i < n; i++) pc[i] = (vec2){cx[i], cy[i]};
    hull *hr = hull_new(pr, m), *hc = hull_new(pc, n);
    box br = bbox(rx, ry, m), bc = bbox(cx, cy, n);
    double b = fmax(area_bound_side(rx, ry, m, hc, bc, h2), area_bound_side(cx, cy, n, hr, br, h2));
    hull_free(hr), hull_free(hc), free(pr), free(pc);
    return b;
  }
  box a = bbox(rx, ry, m), b = bbox(cx, cy, n);
  double dx = fmax(a.x1, b.x1) - fmin(a.x0, b.x0), dy = fmax(a.y1, b.y1) - fmin(a.y0, b.y0);
  return sqrt(dx * dx + dy * dy + h2);
}

weights *weights_new(const vec2 *R, int m, double zr, const vec2 *C, int n, double zc,
                     cost_kind kind, int table) {
  return weights_new_shadow(R, m, zr, C, n, zc, kind, 0, table);
}

weights *weights_new_shadow(const vec2 *R, int m, double zr, const vec2 *C, int n, double zc,
                            cost_kind kind, double shadow, int table) {
  weights *w = xcalloc(1, sizeof *w);
  w->m = m;
  w->n = n;
  w->kind = kind;
  w->shadow = kind == COST_AREA ? shadow : 0;

  /* The pair scaled by 2^-e (see above). */
  int e = scale_exponent(R, m, C, n, zr, zc);
  double h = zc - zr;
  h = isfinite(h) ? ldexp(h, -e) : ldexp(0.5 * zc - 0.5 * zr, 1 - e);
  w->h2 = h * h;
  double *sx = xmallocarray(2 * ((size_t)m + (size_t)n), sizeof *sx);
  double *sy = sx + m, *tx = sx + 2 * m, *ty = tx + n;
  for (int i = 0; i < m; i++) sx[i] = ldexp(R[i].x, -e), sy[i] = ldexp(R[i].y, -e);
  for (int i = 0; i < n; i++) tx[i] = ldexp(C[i].x, -e), ty[i] = ldexp(C[i].y, -e);

  /* The scale S = 2^s: (m+n+1) weights of at most bound*S + 1 quanta each
   * stay below 2^52, so every path sum is an exact integer.  A shadow is
   * at most its tile's area: the bound grows by 1 + |shadow| (by 1 exactly
   * for shadow = 0). */
  double wb = bound(sx, sy, m, tx, ty, n, w->h2, kind) * (1 + fabs(w->shadow)) * 1.001 + DBL_MIN;
  double room = (0x1p52 / (double)(m + n + 1) - 1) / wb;
  int k;
  frexp(room, &k);   /* room = f 2^k, f in [0.5, 1): 2^(k-1) <= room */
  double S = ldexp(1.0, k - 1);
  w->qexp = -(k - 1) + (kind == COST_AREA ? 2 * e : e);
  w->quantum = ldexp(1.0, w->qexp);
  w->sc = kind == COST_AREA ? S / 2 : S;

  size_t nr = (size_t)2 * m + 3, nc = (size_t)n + 3;
  double *a = xmallocarray(5 * (nr + nc), sizeof *a);
  w->rx = a, w->ry = a + nr, w->rex = a + 2 * nr, w->rey = a + 3 * nr, w->ree = a + 4 * nr;
  a += 5 * nr;
  w->cx = a, w->cy = a + nc, w->cfx = a + 2 * nc, w->cfy = a + 3 * nc, w->cff = a + 4 * nc;
  for (int r = -1; r <= 2 * m + 1; r++) {
    size_t i = (size_t)(2 * m + 1 - r);
    int p = mod(r, m), q = mod(r + 1, m);
    w->rx[i] = sx[p], w->ry[i] = sy[p];
    w->rex[i] = sx[q] - sx[p], w->rey[i] = sy[q] - sy[p];
    w->ree[i] = w->h2 * (w->rex[i] * w->rex[i] + w->rey[i] * w->rey[i]);
  }
  for (int c = -1; c <= n + 1; c++) {
    size_t i = (size_t)(c + 1);
    int p = mod(c, n), q = mod(c + 1, n);
    w->cx[i] = tx[p], w->cy[i] = ty[p];
    w->cfx[i] = tx[q] - tx[p], w->cfy[i] = ty[q] - ty[p];
    w->cff[i] = w->h2 * (w->cfx[i] * w->cfx[i] + w->cfy[i] * w->cfy[i]);
  }

  free(sx);

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
                     w->cy[ci], w->sc, w->shadow);
}

double weights_h(const weights *w, int i, int j) {
  int m = w->m;
  size_t ri = (size_t)(2 * m + 1 - mod(i, m)), ci = (size_t)mod(j, w->n) + 1;
  if (w->kind == COST_SPAN)   /* the span R_i C_{j+1} */
    return weights_len(w->rx[ri], w->ry[ri], w->cx[ci + 1], w->cy[ci + 1], w->h2, w->sc);
  return weights_tri(w->cff[ci], w->cfx[ci], w->cfy[ci], w->cx[ci], w->cy[ci], w->rx[ri],
                     w->ry[ri], w->sc, w->shadow);
}

double weights_quantum(const weights *w) { return w->quantum; }
int weights_qexp(const weights *w) { return w->qexp; }
int weights_has_table(const weights *w) { return w->tv != NULL; }

double weights_in(const weights *w, int k, int c, int vertical) {
  if (w->tv) {
    if (w->kind == COST_SPAN) return w->tv[(size_t)mod(k, w->m) * ((size_t)w->n + 1) + (size_t)c];
    if (vertical) return w->tv[(size_t)mod(k - 1, w->m) * ((size_t)w->n + 1) + (size_t)c];
    return w->th[(size_t)mod(k, w->m) * ((size_t)w->n + 1) + (size_t)c];
  }
  return vertical ? weights_v(w, k - c - 1, c) : weights_h(w, k - c, c - 1);
}
