/* naive.c -- brute force and one-DP-per-start references. */
#include "algo/naive.h"

#include <math.h>
#include <stdlib.h>

#include "util/xmem.h"

typedef struct {
  const weights *w;
  int m, n, s;
  double best;
} brute;

/* All monotone paths from (i, j) to (s+m, n), with `sum` so far. */
static void walk(brute *b, int i, int j, double sum) {
  if (i == b->s + b->m && j == b->n) {
    if (sum < b->best) b->best = sum;
    return;
  }
  if (i < b->s + b->m) walk(b, i + 1, j, sum + weights_v(b->w, i, j));
  if (j < b->n) walk(b, i, j + 1, sum + weights_h(b->w, i, j));
}

double naive_brute(const weights *w, int *start) {
  double best = HUGE_VAL;
  for (int s = 0; s < w->m; s++) {
    brute b = {w, w->m, w->n, s, HUGE_VAL};
    walk(&b, s, 0, 0);
    if (b.best < best) best = b.best, *start = s;
  }
  return best;
}

double naive_dp(const weights *w, int *start) {
  int m = w->m, n = w->n;
  double *V = xmallocarray((size_t)m * n, sizeof *V), *H = xmallocarray((size_t)m * n, sizeof *H);
  double *row = xmallocarray((size_t)n + 1, sizeof *row);
  for (int i = 0; i < m; i++)
    for (int j = 0; j < n; j++) {
      V[(size_t)i * n + j] = weights_v(w, i, j);
      H[(size_t)i * n + j] = weights_h(w, i, j);
    }
  double best = HUGE_VAL;
  for (int s = 0; s < m; s++) {
    /* Row i of the DP is torus row (s + i) mod m. */
    row[0] = 0;
    const double *h = H + (size_t)s * n;
    for (int j = 1; j <= n; j++) row[j] = row[j - 1] + h[j - 1];
    for (int i = 1; i <= m; i++) {
      const double *v = V + (size_t)((s + i - 1) % m) * n;
      h = H + (size_t)((s + i) % m) * n;
      row[0] += v[0];
      for (int j = 1; j <= n; j++) {
        double up = row[j] + v[j % n], left = row[j - 1] + h[j - 1];
        row[j] = up <= left ? up : left;
      }
    }
    if (row[n] < best) best = row[n], *start = s;
  }
  free(V);
  free(H);
  free(row);
  return best;
}
