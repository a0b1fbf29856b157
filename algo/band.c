/* band.c -- the dynamic program over one band, diagonal by diagonal
 * (section 4), with two diagonals of costs and one bit per node (section 7.3). */
#include "band.h"

#include <math.h>
#include <stdlib.h>

#include "kernel.h"
#include "xmem.h"

struct band_ws {
  int m, n;
  double *prev, *cur;   /* costs by column, index -1 .. n+1 */
  uint64_t *bits;       /* edge bits, each diagonal from a word boundary */
  int64_t *woff;        /* word offset of diagonal s+t */
  int *a;               /* first column of diagonal s+t */
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
  return ws;
}

void band_ws_free(band_ws *ws) {
  if (!ws) return;
  free(ws->prev - 1);
  free(ws->cur - 1);
  free(ws->bits);
  free(ws->woff);
  free(ws->a);
  free(ws);
}

double band_solve(const weights *w, band_ws *ws, int s, const path *U, const path *L,
                  int *col, band_count *count) {
  int m = w->m, n = w->n, T = m + n;
  double *prev = ws->prev, *cur = ws->cur;
  XASSERT(m == ws->m && n == ws->n);
  for (int c = -1; c <= n + 1; c++) prev[c] = cur[c] = HUGE_VAL;
  prev[0] = 0;
  ws->a[0] = 0;
  ws->woff[0] = 0;
  ws->woff[1] = 0;
  int pa = 0, pb = 0;
  int64_t wo = 0;
  for (int t = 1; t <= T; t++) {
    int k = s + t, a, b;
    band_range(m, n, s, U, L, k, &a, &b);
    XASSERT(a <= b && (a == pa || a == pa + 1) && (b == pb || b == pb + 1));
    prev[pa - 1] = HUGE_VAL;   /* outside the last diagonal: not in the band */
    prev[pb + 1] = HUGE_VAL;
    if (a == b && pa == pb) {
      /* A cut edge: the only edge between two one-node diagonals. */
      int v = band_cut_vertical(pa, a);
      cur[a] = prev[pa] + (v ? weights_v(w, k - 1 - a, a) : weights_h(w, k - a, a - 1));
      ws->bits[wo] = (uint64_t)v;
      count->forced++;
    } else {
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
  /* Backtrack from (s+m, n) (Fig. 14). */
  int c = n;
  for (int t = T; t >= 1; t--) {
    col[t] = c;
    int i = c - ws->a[t];
    uint64_t bit = (ws->bits[ws->woff[t] + (i >> 6)] >> (i & 63)) & 1;
    if (!bit) c--;
  }
  XASSERT(c == 0);
  col[0] = 0;
  return cost;
}

int64_t band_size(int m, int n, int s, const path *U, const path *L) {
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
