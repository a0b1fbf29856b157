/* unpinch.c -- the cheapest path with two runs of each kind of step.
 *
 * State of a partial path from (s, 0): its first and last step (V or H) and
 * how many runs of V and of H steps it has made (0..3, 3 meaning 3 or more).
 * A V step after a V step keeps the runs; after an H step it starts a run.
 * At (s+m, n) the cycle closes: when the first and the last steps are of one
 * kind their runs are one, so that kind has one run fewer.  A path counts
 * when it then has at least two runs of each kind. */
#include "surface/unpinch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

enum { V = 0, H = 1, NS = 64 };

static int st(int f, int l, int a, int b) { return f * 32 + l * 16 + a * 4 + b; }

int unpinch_repeats(const tiling *t) {
  int steps = t->m + t->n, runs[2] = {0, 0}, first = -1, last = -1;
  for (int k = 1; k <= steps; k++) {
    int d = t->col[k] == t->col[k - 1] ? V : H;
    if (first < 0) first = d;
    if (d != last) runs[d]++;
    last = d;
  }
  if (first == last && first >= 0) runs[first]--;
  return runs[V] <= 1 || runs[H] <= 1;
}

/* The program for start row s: best[st] at (m, n) in *fin; with par, the
 * predecessor state and step of every (node, state) for backtracking. */
static void program(const weights *w, int s, double *cost, unsigned char *par, double *fin,
                    uint64_t *nodes) {
  int m = w->m, n = w->n;
  size_t at = (size_t)(n + 1) * NS;
  for (size_t k = 0; k < (size_t)(m + 1) * at; k++) cost[k] = HUGE_VAL;
  for (int r = 0; r <= m; r++)
    for (int c = 0; c <= n; c++) {
      double *here = cost + (size_t)r * at + (size_t)c * NS;
      if (r == 0 && c == 0) {   /* the first step */
        if (m > 0) {
          double v = weights_v(w, s, 0), *d = cost + at + st(V, V, 1, 0);
          *d = v;
          if (par) par[at + st(V, V, 1, 0)] = 0xff;
        }
        if (n > 0) {
          double v = weights_h(w, s, 0), *d = cost + NS + st(H, H, 0, 1);
          *d = v;
          if (par) par[NS + st(H, H, 0, 1)] = 0xff;
        }
        continue;
      }
      (*nodes)++;
      for (int x = 0; x < NS; x++) {
        double q = here[x];
        if (q == HUGE_VAL) continue;
        int f = x >> 5, l = (x >> 4) & 1, a = (x >> 2) & 3, b = x & 3;
        if (r < m) {   /* a vertical step */
          int na = l == V ? a : (a < 3 ? a + 1 : 3), y = st(f, V, na, b);
          double v = q + weights_v(w, s + r, c);
          size_t to = (size_t)(r + 1) * at + (size_t)c * NS + (size_t)y;
          if (v < cost[to]) {
            cost[to] = v;
            if (par) par[to] = (unsigned char)x;
          }
        }
        if (c < n) {   /* a horizontal step */
          int nb = l == H ? b : (b < 3 ? b + 1 : 3), y = st(f, H, a, nb);
          double v = q + weights_h(w, s + r, c);
          size_t to = (size_t)r * at + (size_t)(c + 1) * NS + (size_t)y;
          if (v < cost[to]) {
            cost[to] = v;
            if (par) par[to] = (unsigned char)(x | 0x40);   /* 0x40: came by H */
          }
        }
      }
    }
  /* Closing the cycle. */
  *fin = HUGE_VAL;
  const double *end = cost + (size_t)m * at + (size_t)n * NS;
  for (int x = 0; x < NS; x++) {
    int f = x >> 5, l = (x >> 4) & 1, a = (x >> 2) & 3, b = x & 3;
    if (f == l) {
      if (f == V) a--;
      else b--;
    }
    if (a >= 2 && b >= 2 && end[x] < *fin) *fin = end[x];
  }
}

int unpinch_solve(const vec2 *P, int np, double zp, const vec2 *Q, int nq, double zq, cost_kind kind,
                  double shadow, tiling *out) {
  int tr = nq < np;
  int m = tr ? nq : np, n = tr ? np : nq;
  if (m < 2 || n < 2 || (double)m * m * n > 4194304.0) return -1;
  weights *w = tr ? weights_new_shadow(Q, nq, zq, P, np, zp, kind, shadow, 0)
                  : weights_new_shadow(P, np, zp, Q, nq, zq, kind, shadow, 0);
  size_t cells = (size_t)(m + 1) * (size_t)(n + 1) * NS;
  double *cost = xmallocarray(cells, sizeof *cost);
  uint64_t nodes = 0;
  double best = HUGE_VAL;
  int bs = -1;
  for (int s = 0; s < m; s++) {
    double fin;
    program(w, s, cost, NULL, &fin, &nodes);
    if (fin < best) best = fin, bs = s;
  }
  if (bs < 0) {
    free(cost);
    weights_free(w);
    return -1;
  }
  /* Again for the best start, keeping the way back. */
  unsigned char *par = xmalloc(cells);
  double fin;
  program(w, bs, cost, par, &fin, &nodes);
  size_t at = (size_t)(n + 1) * NS;
  const double *end = cost + (size_t)m * at + (size_t)n * NS;
  int x = -1;
  for (int y = 0; y < NS && x < 0; y++) {
    int f = y >> 5, l = (y >> 4) & 1, a = (y >> 2) & 3, b = y & 3;
    if (f == l) {
      if (f == V) a--;
      else b--;
    }
    if (a >= 2 && b >= 2 && end[y] == fin) x = y;
  }
  XASSERT(x >= 0);
  memset(out, 0, sizeof *out);
  out->m = m, out->n = n, out->transposed = tr, out->start = bs, out->shadow = w->shadow;
  out->quantum = weights_quantum(w);
  out->qexp = weights_qexp(w);
  out->quanta = fin;
  out->cost = ldexp(fin, out->qexp);
  out->col = xmallocarray((size_t)(m + n + 1), sizeof *out->col);
  out->count.nodes = nodes;
  out->count.paths = (uint64_t)m + 1;
  /* Backtrack: col[t] is the column after t steps. */
  int r = m, c = n;
  for (int t = m + n; t > 0; t--) {
    out->col[t] = c;
    unsigned char p = par[(size_t)r * at + (size_t)c * NS + (size_t)x];
    if (p == 0xff) {   /* the first step, from (0, 0) */
      if (r == 1 && c == 0) r = 0;
      else c = 0;
      XASSERT(t == 1);
      break;
    }
    if (p & 0x40) c--;
    else r--;
    x = p & 0x3f;
  }
  out->col[0] = 0;
  free(par);
  free(cost);
  weights_free(w);
  return 0;
}
