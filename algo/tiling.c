/* tiling.c -- divide and conquer over non-crossing paths (section 3.2). */
#include "tiling.h"

#include <stdlib.h>
#include <string.h>

#include "xmem.h"

typedef struct {
  const weights *w;
  band_ws *ws;
  tiling *out;
  int *pool;     /* column arrays for the recursion stack */
  double *cpool; /* and their prefix sums */
} solver;

/* The path arrays of recursion level `level`. */
static gpath pathbuf(solver *s, int level) {
  size_t len = (size_t)(s->w->m + s->w->n + 1);
  return (gpath){0, s->pool + (size_t)level * len, s->cpool + (size_t)level * len};
}

static void consider(solver *s, int start, double quanta, const int *col) {
  tiling *o = s->out;
  if (quanta < o->quanta || (quanta == o->quanta && start < o->start)) {
    o->quanta = quanta;
    o->start = start;
    memcpy(o->col, col, (size_t)(s->w->m + s->w->n + 1) * sizeof *col);
  }
}

/* findallpaths(lo, hi): every mu(i), lo < i < hi, between U = mu(lo) and
 * L = mu(hi). */
static void findall(solver *s, const gpath *U, const gpath *L, int level) {
  int lo = U->start, hi = L->start;
  if (hi - lo < 2) return;
  int mid = tiling_mid(lo, hi);
  gpath P = pathbuf(s, level);
  double q = band_solve(s->w, s->ws, mid, U, L, &P, &s->out->count);
  consider(s, mid, q, P.col);
  findall(s, U, &P, level + 1);
  findall(s, &P, L, level + 1);
}

void tiling_solve_w(const weights *w, tiling *out) {
  int m = w->m, n = w->n;
  memset(out, 0, sizeof *out);
  out->m = m;
  out->n = n;
  out->quantum = weights_quantum(w);
  out->col = xmallocarray((size_t)(m + n + 1), sizeof *out->col);
  solver s = {w, band_ws_new(m, n), out, NULL, NULL};
  int levels = 2;
  for (int x = m; x > 1; x >>= 1) levels++;
  s.pool = xmallocarray((size_t)levels * (size_t)(m + n + 1), sizeof *s.pool);
  s.cpool = xmallocarray((size_t)levels * (size_t)(m + n + 1), sizeof *s.cpool);

  gpath mu0 = pathbuf(&s, 0);
  out->quanta = band_solve(w, s.ws, 0, NULL, NULL, &mu0, &out->count);
  out->start = 0;
  memcpy(out->col, mu0.col, (size_t)(m + n + 1) * sizeof *mu0.col);
  gpath mum = {m, mu0.col, mu0.cum};   /* mu(m): the same path, m rows down */
  findall(&s, &mu0, &mum, 1);
  out->cost = out->quanta * out->quantum;
  free(s.pool);
  free(s.cpool);
  band_ws_free(s.ws);
}

void tiling_solve(const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq,
                  cost_kind kind, int table, tiling *out) {
  int tr = nq < np;
  weights *w = tr ? weights_new(Q, nq, zq, P, np, zp, kind, table)
                  : weights_new(P, np, zp, Q, nq, zq, kind, table);
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
