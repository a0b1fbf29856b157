/* tiling.c -- divide and conquer over non-crossing paths (section 3.2). */
#include "algo/tiling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

typedef struct {
  const weights *w;
  band_ws *ws;
  tiling_best *best;
  band_count *count;
  int levels;
  int **pool;      /* the columns of the path at each recursion level */
  double **cpool;  /* and their prefix sums (one allocation each, so that a
                      read past one path's end is caught, not another's) */
} solver;

/* The path arrays of recursion level `level`. */
static gpath pathbuf(solver *s, int level) {
  XASSERT(level < s->levels);
  return (gpath){0, s->pool[level], s->cpool[level]};
}

static void consider(solver *s, int start, double quanta, const int *col) {
  tiling_best *b = s->best;
  if (quanta < b->quanta || (quanta == b->quanta && start < b->start)) {
    b->quanta = quanta;
    b->start = start;
    memcpy(b->col, col, (size_t)(s->w->m + s->w->n + 1) * sizeof *col);
  }
}

/* findallpaths(lo, hi): every mu(i), lo < i < hi, between U = mu(lo) and
 * L = mu(hi). */
static void findall(solver *s, const gpath *U, const gpath *L, int level) {
  int lo = U->start, hi = L->start;
  if (hi - lo < 2) return;
  int mid = tiling_mid(lo, hi);
  gpath P = pathbuf(s, level);
  double q = band_solve(s->w, s->ws, mid, U, L, &P, s->count);
  consider(s, mid, q, P.col);
  findall(s, U, &P, level + 1);
  findall(s, &P, L, level + 1);
}

static int levels(int m) {
  int k = 2;
  for (int x = m; x > 1; x >>= 1) k++;
  return k;
}

static void solver_init(solver *s, const weights *w, band_ws *ws, tiling_best *best,
                        band_count *count) {
  size_t len = (size_t)(w->m + w->n + 1);
  int lv = levels(w->m);
  *s = (solver){w, ws, best, count, lv, xmallocarray((size_t)lv, sizeof(int *)),
                xmallocarray((size_t)lv, sizeof(double *))};
  for (int i = 0; i < lv; i++) {
    s->pool[i] = xmallocarray(len, sizeof(int));
    s->cpool[i] = xmallocarray(len, sizeof(double));
  }
}

static void solver_done(solver *s) {
  for (int i = 0; i < s->levels; i++) free(s->pool[i]), free(s->cpool[i]);
  free(s->pool);
  free(s->cpool);
}

void tiling_range(const weights *w, band_ws *ws, const gpath *U, const gpath *L,
                  tiling_best *best, band_count *count) {
  solver s;
  solver_init(&s, w, ws, best, count);
  findall(&s, U, L, 0);
  solver_done(&s);
}

void tiling_solve_w(const weights *w, tiling *out) {
  int m = w->m, n = w->n;
  memset(out, 0, sizeof *out);
  out->m = m;
  out->n = n;
  out->quantum = weights_quantum(w);
  out->qexp = weights_qexp(w);
  out->shadow = w->shadow;
  out->col = xmallocarray((size_t)(m + n + 1), sizeof *out->col);
  tiling_best best = {HUGE_VAL, 0, out->col};
  band_ws *ws = band_ws_new(m, n);
  solver s;
  solver_init(&s, w, ws, &best, &out->count);
  /* shortestpath(G): mu(0) on the whole graph, mu(m) its copy m rows down. */
  gpath mu0 = pathbuf(&s, 0);
  double q = band_solve(w, ws, 0, NULL, NULL, &mu0, &out->count);
  consider(&s, 0, q, mu0.col);
  gpath mum = {m, mu0.col, mu0.cum};
  findall(&s, &mu0, &mum, 1);
  solver_done(&s);
  band_ws_free(ws);
  out->quanta = best.quanta;
  out->start = best.start;
  out->cost = ldexp(out->quanta, out->qexp);
}

void tiling_solve(const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq,
                  cost_kind kind, int table, tiling *out) {
  tiling_solve_shadow(P, np, zp, Q, nq, zq, kind, 0, table, out);
}

void tiling_solve_shadow(const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq,
                         cost_kind kind, double shadow, int table, tiling *out) {
  int tr = nq < np;
  weights *w = tr ? weights_new_shadow(Q, nq, zq, P, np, zp, kind, shadow, table)
                  : weights_new_shadow(P, np, zp, Q, nq, zq, kind, shadow, table);
  tiling_solve_w(w, out);
  out->transposed = tr;
  weights_free(w);
}

void tiling_free(tiling *t) {
  free(t->col);
  t->col = NULL;
}

void tiling_tiles(const tiling *t, int (*tile)[3], unsigned char *on) {
  int m = t->m, n = t->n;
  int r = t->start, c = 0;
  for (int i = 1; i <= m + n; i++) {
    int *x = tile[i - 1];
    unsigned char rows = (unsigned char)t->transposed;   /* which contour the rows are */
    if (t->col[i] == t->col[i - 1]) {   /* vertical: R_r R_{r+1} C_c */
      x[0] = r % m, x[1] = (r + 1) % m, x[2] = c % n;
      on[i - 1] = rows;
      r++;
    } else {                            /* horizontal: C_c C_{c+1} R_r */
      x[0] = c % n, x[1] = (c + 1) % n, x[2] = r % m;
      on[i - 1] = (unsigned char)!rows;
      c++;
    }
  }
}

double tiling_path_cost(const tiling *t, const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq,
                        cost_kind kind) {
  /* The scale: the largest coordinate and the height into [1/2, 1). */
  double mx = 0, h = zq - zp;
  for (int i = 0; i < np; i++) mx = fmax(mx, fmax(fabs(P[i].x), fabs(P[i].y)));
  for (int i = 0; i < nq; i++) mx = fmax(mx, fmax(fabs(Q[i].x), fabs(Q[i].y)));
  int e = 0, eh = 0;
  if (mx > 0) frexp(mx, &e);
  if (isfinite(h) && h != 0) frexp(h, &eh);
  else if (!isfinite(h)) frexp(0.5 * zq - 0.5 * zp, &eh), eh++;
  if (eh > e || mx == 0) e = eh;
  double hs = isfinite(h) ? ldexp(h, -e) : ldexp(0.5 * zq - 0.5 * zp, 1 - e);
  int steps = t->m + t->n;
  int (*tile)[3] = xmallocarray((size_t)steps + 1, sizeof *tile);
  unsigned char *on = xmallocarray((size_t)steps + 1, 1);
  tiling_tiles(t, tile, on);
  double sum = 0;
  for (int k = 0; k < steps; k++) {
    const vec2 *E = on[k] ? Q : P, *X = on[k] ? P : Q;   /* the edge's contour, the apex's */
    vec2 a = E[tile[k][0]], b = E[tile[k][1]], c = X[tile[k][2]];
    double ax = ldexp(a.x, -e), ay = ldexp(a.y, -e), bx = ldexp(b.x, -e), by = ldexp(b.y, -e);
    double cx = ldexp(c.x, -e), cy = ldexp(c.y, -e);
    if (kind == COST_AREA) {   /* |(b - a) x (c - a)| / 2, c one height away */
      double ux = bx - ax, uy = by - ay, vx = cx - ax, vy = cy - ay;
      double x = uy * hs, y = -ux * hs, z = ux * vy - uy * vx;
      sum += 0.5 * hypot(hypot(x, y), z);   /* (squares of a tiny height would underflow) */
      if (t->shadow != 0) sum += t->shadow * 0.5 * z;   /* its shadow, as weights_tri */
    } else {                   /* the span from the edge's end to the apex */
      sum += hypot(hypot(cx - bx, cy - by), hs);
    }
  }
  free(tile);
  free(on);
  return ldexp(sum, kind == COST_AREA ? 2 * e : e);
}

typedef struct {
  int64_t key;   /* the span: (r mod m) n + (c mod n) */
  int step;      /* where the path is at it */
} span_use;

static int by_key_step(const void *a, const void *b) {
  const span_use *x = a, *y = b;
  if (x->key != y->key) return x->key < y->key ? -1 : 1;
  return (x->step > y->step) - (x->step < y->step);
}

static int by_step(const void *a, const void *b) {
  const span_use *x = a, *y = b;
  return (x->step > y->step) - (x->step < y->step);
}

int tiling_repeated_spans(const tiling *t, int (*span)[2], int max) {
  /* The nodes of the cycle, steps 0 .. m+n-1 (the last node is the first
   * again), sorted by span: a span at two steps is used twice. */
  int m = t->m, n = t->n, steps = m + n, found = 0;
  span_use *u = xmallocarray((size_t)steps, sizeof *u);
  for (int k = 0, r = t->start, c = 0; k < steps; k++) {
    u[k] = (span_use){(int64_t)(r % m) * n + c % n, k};
    if (t->col[k + 1] == t->col[k]) r++;
    else c++;
  }
  qsort(u, (size_t)steps, sizeof *u, by_key_step);
  for (int k = 0; k < steps;) {   /* each repeated span once, at its first use */
    int j = k;
    while (j < steps && u[j].key == u[k].key) j++;
    if (j - k > 1) u[found++] = u[k];
    k = j;
  }
  qsort(u, (size_t)found, sizeof *u, by_step);
  for (int k = 0; k < found && k < max; k++) {
    int row = (int)(u[k].key / n), col = (int)(u[k].key % n);
    span[k][0] = t->transposed ? col : row;   /* the rows are P unless transposed */
    span[k][1] = t->transposed ? row : col;
  }
  free(u);
  return found;
}
