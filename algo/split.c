/* split.c -- the diagonal split and the processor allocation. */
#include "algo/split.h"

#include <string.h>

#include "util/words.h"

int split_active(int len, int p, int d) {
  int q = len / (d > 0 ? d : 1);
  if (q > p) q = p;
  return q < 1 ? 1 : q;
}

void split_positions(int len, int q, int *N) {
  N[0] = 0;
  for (int i = 1; i <= q; i++) N[i] = (len - N[i - 1]) / (q - i + 1) + N[i - 1];
}

int split_owner(int a, int b, int q, int c) {
  /* Positions 0 .. (q-r)x-1 go x at a time to slaves 0 .. q-r-1, the rest
   * x+1 at a time to the last r (split_n). */
  int len = b - a + 1, pos = c - a, x = len / q, r = len % q, first = (q - r) * x;
  return pos < first ? pos / x : q - r + (pos - first) / (x + 1);
}

int split_slaves(split_alloc how, int p, int64_t w_above, int64_t w_below, int paths_above,
                 int paths_below) {
  if (how == ALLOC_HALF) return (p + 1) / 2;
  if (paths_below <= 0) return 0;
  if (paths_above <= 0) return p;
  int64_t tot = w_above + w_below;
  int below = tot > 0 ? (int)((2 * (int64_t)p * w_below + tot) / (2 * tot)) : (p + 1) / 2;
  if (below < 1) below = 1;
  if (below > p - 1) below = p - 1;
  return below;
}

int64_t split_region(int m, int n, const gpath *U, const gpath *L) {
  int lo = U->start, hi = L->start;
  if (hi - lo < 2) return 0;
  /* Nodes on or below U and on or above L, diagonal by diagonal, over the
   * diagonals the inner paths use (lo+1 .. hi-1+m+n). */
  int64_t size = 0;
  int pa = -1, pb = -1;
  for (int k = lo + 1; k <= hi - 1 + m + n; k++) {
    int t = k - lo, uc = t <= m + n ? U->col[t] : n;
    int tl = k - hi, lc = tl >= 0 ? L->col[tl] : 0;
    int a = lc, b = uc;
    if (k - (hi - 1) - m > a) a = k - (hi - 1) - m;   /* row <= hi-1+m */
    if (k - (lo + 1) < b) b = k - (lo + 1);           /* row >= lo+1 */
    if (a > b) continue;
    if (!(a == b && pa == pb && pa >= 0)) size += b - a + 1;
    pa = a, pb = b;
  }
  return size;
}

int split_usable(int m, int n, int s, const gpath *U, const gpath *L, int d) {
  int most = 1, pa = 0, pb = 0;
  for (int t = 1; t <= m + n; t++) {
    int a, b;
    band_range(m, n, s, U, L, s + t, &a, &b);
    if (!(a == b && pa == pb) && (b - a + 1) / d > most) most = (b - a + 1) / d;
    pa = a, pb = b;
  }
  return most;
}

const char *const split_alloc_names[SPLIT_ALLOCS] = {"half", "size", "fit"};

const char *split_alloc_name(split_alloc a) {
  return (unsigned)a < SPLIT_ALLOCS ? split_alloc_names[a] : "half";
}

int split_alloc_parse(const char *s, split_alloc *a) {
  int i = words_find(split_alloc_names, SPLIT_ALLOCS, s);
  return i < 0 ? -1 : (*a = (split_alloc)i, 0);
}
