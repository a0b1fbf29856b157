/* band.c -- the dynamic program over one band, diagonal by diagonal
 * (section 4), with two diagonals of costs and one bit per node (section 7.3). */
#include "algo/band.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "algo/kernel.h"
#include "util/xmem.h"

typedef struct { int t0, t1; } run;   /* diagonals s+t0 .. s+t1 joined from U */

struct band_ws {
  int m, n;
  double *prev, *cur;   /* costs by column, index -1 .. n+1 */
  uint64_t *bits;       /* edge bits, each diagonal from a word boundary */
  int64_t *woff;        /* word offset of diagonal s+t */
  int *a;               /* first column of diagonal s+t */
  run *runs;            /* the runs joined from U, in order */
};

band_ws *band_ws_new(int m, int n) {
  band_ws *ws = xcalloc(1, sizeof *ws);
  ws->m = m;
  ws->n = n;
  ws->prev = (double *)xmallocarray((size_t)n + 3, sizeof(double)) + 1;
  ws->cur = (double *)xmallocarray((size_t)n + 3, sizeof(double)) + 1;
  /* A band never holds more than the (m+1) x (n+1) nodes a path can reach. */
  int64_t words = ((int64_t)(m + 1) * (n + 1)) / 64 + m + n + 2;
  ws->bits = xmallocarray((size_t)words, sizeof(uint64_t));
  ws->woff = xmallocarray((size_t)(m + n + 2), sizeof(int64_t));
  ws->a = xmallocarray((size_t)(m + n + 2), sizeof(int));
  ws->runs = xmallocarray((size_t)(m + n + 2) / 2 + 1, sizeof(run));
  return ws;
}

void band_ws_free(band_ws *ws) {
  if (!ws) return;
  free(ws->prev - 1);
  free(ws->cur - 1);
  free(ws->bits);
  free(ws->woff);
  free(ws->a);
  free(ws->runs);
  free(ws);
}

int band_shared_until(int m, int n, int s, const gpath *U, const gpath *L, int t) {
  if (!U || !L) return t - 1;
  int du = s - U->start, dl = s - L->start;   /* U's index = t + du, L's = t + dl */
  int end = m + n - du;   /* U exists on diagonals s+t for t <= end, L for t >= -dl */
  if (t > end || t - 1 + dl < 0) return t - 1;
  const int *uc = U->col + du, *lc = L->col + dl;
  if (uc[t - 1] != lc[t - 1]) return t - 1;
  int u = t;
  while (u + 16 <= end + 1 && memcmp(uc + u, lc + u, 16 * sizeof *uc) == 0) u += 16;
  while (u <= end && uc[u] == lc[u]) u++;
  return u - 1;
}

double band_solve(const weights *w, band_ws *ws, int s, const gpath *U, const gpath *L,
                  gpath *P, band_count *count) {
  int m = w->m, n = w->n, T = m + n, nruns = 0;
  double *prev = ws->prev, *cur = ws->cur;
  XASSERT(m == ws->m && n == ws->n);
  prev[-1] = prev[1] = HUGE_VAL;
  prev[0] = 0;
  ws->a[0] = 0;
  int pa = 0, pb = 0;
  int64_t wo = 0;
  for (int t = 1; t <= T; t++) {
    int k = s + t, a, b;
    band_range(m, n, s, U, L, k, &a, &b);
    XASSERT(a <= b && (a == pa || a == pa + 1) && (b == pb || b == pb + 1));
    if (a == b && pa == pb) {
      int t1 = band_shared_until(m, n, s, U, L, t);
      if (t1 > t) {
        /* U and L run together over diagonals s+t-1 .. s+t1: join the run. */
        int du = s - U->start;
        double v = prev[pa] + (U->cum[t1 + du] - U->cum[t - 1 + du]);
        ws->runs[nruns++] = (run){t, t1};
        count->forced += (uint64_t)(t1 - t + 1);
        pa = pb = U->col[t1 + du];
        prev[pa - 1] = prev[pa + 1] = HUGE_VAL;
        prev[pa] = v;
        ws->a[t1] = pa;
        t = t1;
        continue;
      }
      /* A single cut edge between two one-node diagonals. */
      int vert = band_cut_vertical(pa, a);
      cur[a] = prev[pa] + weights_in(w, k, a, vert);
      cur[a - 1] = cur[a + 1] = HUGE_VAL;
      ws->bits[wo] = (uint64_t)vert;
      count->forced++;
    } else {
      prev[pa - 1] = HUGE_VAL;   /* outside the last diagonal: not in the band */
      prev[pb + 1] = HUGE_VAL;
      kernel_diag(w, k, a, b, prev, cur, ws->bits + wo);
      count->nodes += (uint64_t)(b - a + 1);
    }
    ws->a[t] = a;
    ws->woff[t] = wo;
    wo += kernel_words(b - a + 1);
    double *x = prev;
    prev = cur;
    cur = x;
    pa = a, pb = b;
  }
  XASSERT(pa == n && pb == n);
  double cost = prev[n];
  count->paths++;

  /* Backtrack from (s+m, n) (Fig. 14); runs are copied from U. */
  int *col = P->col, c = n, r = nruns - 1;
  for (int t = T; t >= 1; t--) {
    if (r >= 0 && ws->runs[r].t1 == t) {
      int t0 = ws->runs[r--].t0, du = s - U->start;
      XASSERT(c == U->col[t + du]);
      memcpy(col + t0, U->col + t0 + du, (size_t)(t - t0 + 1) * sizeof *col);
      t = t0;
      c = U->col[t0 - 1 + du];
      continue;
    }
    col[t] = c;
    int i = c - ws->a[t];
    uint64_t bit = (ws->bits[ws->woff[t] + (i >> 6)] >> (i & 63)) & 1;
    if (!bit) c--;
  }
  XASSERT(c == 0);
  col[0] = 0;
  P->start = s;

  /* Prefix sums along the path: from U on the runs, from the weights elsewhere. */
  double *cum = P->cum;
  cum[0] = 0;
  r = 0;
  for (int t = 1; t <= T; t++) {
    if (r < nruns && ws->runs[r].t0 == t) {
      int t1 = ws->runs[r++].t1, du = s - U->start;
      double base = cum[t - 1] - U->cum[t - 1 + du];
      for (int u = t; u <= t1; u++) cum[u] = base + U->cum[u + du];
      t = t1;
      continue;
    }
    cum[t] = cum[t - 1] + weights_in(w, s + t, col[t], col[t] == col[t - 1]);
  }
  XASSERT(cum[T] == cost);
  return cost;
}

int64_t band_size(int m, int n, int s, const gpath *U, const gpath *L) {
  int64_t size = 0;
  int pa = 0, pb = 0;
  for (int t = 1; t <= m + n; t++) {
    int a, b;
    band_range(m, n, s, U, L, s + t, &a, &b);
    if (!(a == b && pa == pb)) size += b - a + 1;
    pa = a, pb = b;
  }
  return size;
}
