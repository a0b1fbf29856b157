/* crossing.c -- exact segment contacts, and a Shamos-Hoey sweep for the first
 * offending pair among closed polygons.
 *
 * The sweep (M. I. Shamos and D. Hoey, Geometric intersection problems,
 * FOCS 1976) moves a line across the plane in lexicographic order of points
 * (x, then y: a line x + eps y = const, tilted by an infinitesimal eps, so a
 * vertical segment is swept from its lower end to its upper end).  The
 * status is the list of segments the line meets, bottom to top; as long as
 * nothing offends behind the line it is a total order, kept in a treap.
 *
 * At each event point q (one or more segment ends):
 *   1. tally: the segments with an end at q, and those of the status whose
 *      interior holds q (a contiguous run where q falls).  Two that offend,
 *      or any three (three segments through one point always hold an
 *      offending pair: two neighbours meet only at their shared vertex, and
 *      no three segments of a polygon share one vertex), end the search;
 *   2. the segments ending at q leave the status, those starting at q enter
 *      it where q falls (two starting at q: by the turn between them);
 *   3. each pair that became adjacent is tested: (below, above) when nothing
 *      entered, else (below, lowest new) and (highest new, above).
 * Why that suffices: let q* be the first point (lexicographically) where an
 * offending pair meets.  If q* is an event point, step 1 sees the pair (it
 * holds both, or a third through q*).  Otherwise the two cross properly at
 * q*; every segment the status holds between them just before q* runs
 * through q* too (it cannot end in between, and cannot cross them before
 * q*), so two of the segments through q* are adjacent there, and they became
 * adjacent at some event before q*, where step 3 tested them.  Until q* the
 * status is ordered, so every search in it is sound.  Each event costs
 * O(log N) expected, so O(N log N) in all. */
#include "geom/crossing.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geom/exact.h"
#include "util/xmem.h"

const char *crossing_verb(crossing_kind k) {
  switch (k) {
  case CROSSING_CROSS: return "crosses";
  case CROSSING_TOUCH: return "touches";
  case CROSSING_OVERLAP: return "overlaps";
  default: return "meets nothing";
  }
}

/* --- two segments --------------------------------------------------------- */

static vec2 lexmin(vec2 a, vec2 b) { return exact_lex(a, b) <= 0 ? a : b; }
static vec2 lexmax(vec2 a, vec2 b) { return exact_lex(a, b) <= 0 ? b : a; }

static double maxabs(double m, double v) { return fabs(v) > m ? fabs(v) : m; }

/* The crossing point of ab and cd (for messages only): computed on copies
 * scaled by a power of two, so nothing overflows; then clamped to ab. */
static vec2 meet(vec2 a, vec2 b, vec2 c, vec2 d) {
  double m = 0;
  vec2 v[4] = {a, b, c, d};
  for (int i = 0; i < 4; i++) m = maxabs(maxabs(m, v[i].x), v[i].y);
  int e;
  frexp(m, &e);
  for (int i = 0; i < 4; i++) v[i].x = ldexp(v[i].x, -e), v[i].y = ldexp(v[i].y, -e);
  double ex = v[1].x - v[0].x, ey = v[1].y - v[0].y, fx = v[3].x - v[2].x, fy = v[3].y - v[2].y;
  double den = ex * fy - ey * fx, t = 0.5;
  if (den != 0) t = ((v[2].x - v[0].x) * fy - (v[2].y - v[0].y) * fx) / den;
  if (!(t >= 0)) t = 0;
  if (t > 1) t = 1;
  return (vec2){ldexp(v[0].x + t * ex, e), ldexp(v[0].y + t * ey, e)};
}

crossing_kind crossing_segments(vec2 a, vec2 b, vec2 c, vec2 d, vec2 *at) {
  int o1 = exact_orient(a, b, c), o2 = exact_orient(a, b, d);
  if (o1 * o2 > 0) return CROSSING_NONE;
  int o3 = exact_orient(c, d, a), o4 = exact_orient(c, d, b);
  if (o3 * o4 > 0) return CROSSING_NONE;
  if (!o1 && !o2) {   /* c and d on the line ab: all four collinear */
    vec2 lo1 = lexmin(a, b), hi1 = lexmax(a, b), lo2 = lexmin(c, d), hi2 = lexmax(c, d);
    if (exact_lex(lo1, hi2) > 0 || exact_lex(lo2, hi1) > 0) return CROSSING_NONE;
    vec2 lo = lexmax(lo1, lo2), hi = lexmin(hi1, hi2);
    if (at) *at = lo;
    return exact_lex(lo, hi) == 0 ? CROSSING_TOUCH : CROSSING_OVERLAP;
  }
  /* Not all collinear, and each segment meets the other's line: the lines
   * meet in one point.  An endpoint on the other line is that point. */
  if (!o1 || !o2 || !o3 || !o4) {
    if (at) *at = !o1 ? c : !o2 ? d : !o3 ? a : b;
    return CROSSING_TOUCH;
  }
  if (at) *at = meet(a, b, c, d);
  return CROSSING_CROSS;
}

/* --- segments of polygons ------------------------------------------------- */

typedef struct {
  const crossing_poly *p;
  int np, N;
  int *off;    /* off[k]: global number of polygon k's segment 0; off[np] = N */
  int *poly;   /* poly[g]: the polygon of segment g */
} segset;

static void segset_init(segset *S, const crossing_poly *p, int np) {
  S->p = p, S->np = np;
  S->off = xmallocarray((size_t)np + 1, sizeof *S->off);
  long long N = 0;
  for (int k = 0; k < np; k++) {
    XASSERT(p[k].n >= 3);
    S->off[k] = (int)N;
    N += p[k].n;
    XASSERT(N < (1LL << 30));
    for (int s = 0; s < p[k].n; s++) {
      vec2 a = p[k].pt[s], b = p[k].pt[s + 1 == p[k].n ? 0 : s + 1];
      XASSERT(isfinite(a.x) && isfinite(a.y));
      XASSERT(exact_lex(a, b) != 0);
    }
  }
  S->N = (int)N;
  S->off[np] = (int)N;
  S->poly = xmallocarray((size_t)N + 1, sizeof *S->poly);
  for (int k = 0; k < np; k++)
    for (int g = S->off[k]; g < S->off[k + 1]; g++) S->poly[g] = k;
}

static void segset_free(segset *S) {
  free(S->off);
  free(S->poly);
}

/* Segment g's ends in polygon order. */
static void ends(const segset *S, int g, vec2 *a, vec2 *b) {
  const crossing_poly *P = &S->p[S->poly[g]];
  int s = g - S->off[S->poly[g]];
  *a = P->pt[s];
  *b = P->pt[s + 1 == P->n ? 0 : s + 1];
}

/* Does the pair g, h offend?  Neighbours offend only by running back over
 * each other (collinear, on the same side of their shared vertex). */
static crossing_kind pair(const segset *S, int g, int h, vec2 *at) {
  if (g > h) {
    int t = g;
    g = h, h = t;
  }
  vec2 a, b, c, d;
  ends(S, g, &a, &b);
  ends(S, h, &c, &d);
  int k = S->poly[g];
  if (S->poly[h] == k) {
    int s = g - S->off[k], t = h - S->off[k], n = S->p[k].n;
    vec2 v, x, y;   /* the shared vertex, the other two ends */
    int adj = 1;
    if (t == s + 1) v = b, x = a, y = d;
    else if (s == 0 && t == n - 1) v = a, x = b, y = c;
    else adj = 0;
    if (adj) {
      if (exact_orient(x, v, y) == 0 && exact_lex(x, v) == exact_lex(y, v)) {
        if (at) *at = v;
        return CROSSING_OVERLAP;
      }
      return CROSSING_NONE;
    }
  }
  return crossing_segments(a, b, c, d, at);
}

static int report(const segset *S, int g, int h, crossing_kind k, vec2 at, crossing_hit *hit) {
  if (g > h) {
    int t = g;
    g = h, h = t;
  }
  hit->kind = k;
  hit->poly[0] = S->poly[g], hit->seg[0] = g - S->off[S->poly[g]];
  hit->poly[1] = S->poly[h], hit->seg[1] = h - S->off[S->poly[h]];
  hit->at = at;
  return 1;
}

int crossing_find_brute(const crossing_poly *p, int np, crossing_hit *hit) {
  segset S;
  segset_init(&S, p, np);
  int found = 0;
  for (int g = 0; g < S.N && !found; g++)
    for (int h = g + 1; h < S.N; h++) {
      vec2 at;
      crossing_kind k = pair(&S, g, h, &at);
      if (k) {
        found = report(&S, g, h, k, at, hit);
        break;
      }
    }
  segset_free(&S);
  return found;
}

int crossing_segment(const crossing_poly *p, int np, vec2 a, vec2 b, int allow,
                     crossing_hit *hit) {
  XASSERT(exact_lex(a, b) != 0);
  for (int k = 0; k < np; k++)
    for (int s = 0; s < p[k].n; s++) {
      vec2 c = p[k].pt[s], d = p[k].pt[s + 1 == p[k].n ? 0 : s + 1], at;
      crossing_kind kind = crossing_segments(a, b, c, d, &at);
      if (kind == CROSSING_NONE) continue;
      /* A touch has exactly one common point: allowed if it is an allowed end. */
      if (kind == CROSSING_TOUCH && (((allow & CROSSING_ALLOW_A) && exact_lex(at, a) == 0) ||
                                     ((allow & CROSSING_ALLOW_B) && exact_lex(at, b) == 0)))
        continue;
      hit->kind = kind;
      hit->poly[0] = k, hit->seg[0] = s;
      hit->poly[1] = hit->seg[1] = -1;
      hit->at = at;
      return 1;
    }
  return 0;
}

/* --- the sweep ------------------------------------------------------------ */

/* The sweep's data: each segment's ends in sweep order (lo before hi
 * lexicographically), and the events e = 2g + end (end 0: lo, 1: hi) with
 * their points, sorted. */
typedef struct {
  vec2 p;
  uint32_t e;
} event;

typedef struct {
  const segset *S;
  vec2 *lo, *hi;
} sweep;

static int event_cmp(const void *x, const void *y) {
  const event *a = x, *b = y;
  int c = exact_lex(a->p, b->p);
  if (c) return c;
  return a->e < b->e ? -1 : a->e > b->e;
}

/* The status: a treap over segment numbers (-1: none), ordered bottom to top,
 * with parent links; priorities a fixed hash of the segment number, so the
 * run is deterministic. */
typedef struct {
  int *l, *r, *up;
  uint32_t *pri;
  int root;
} treap;

static uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

static void treap_init(treap *T, int N) {
  T->l = xmallocarray((size_t)N, sizeof(int));
  T->r = xmallocarray((size_t)N, sizeof(int));
  T->up = xmallocarray((size_t)N, sizeof(int));
  T->pri = xmallocarray((size_t)N, sizeof(uint32_t));
  for (int g = 0; g < N; g++) T->pri[g] = hash32((uint32_t)g + 0x9e3779b9u);
  T->root = -1;
}

static void treap_free(treap *T) {
  free(T->l), free(T->r), free(T->up), free(T->pri);
}

/* Replace child `old` of p (or the root) by x. */
static void relink(treap *T, int p, int old, int x) {
  if (p < 0) T->root = x;
  else if (T->l[p] == old) T->l[p] = x;
  else T->r[p] = x;
  if (x >= 0) T->up[x] = p;
}

/* Rotate x above its parent. */
static void rotate_up(treap *T, int x) {
  int p = T->up[x], g = T->up[p];
  if (T->l[p] == x) {
    T->l[p] = T->r[x];
    if (T->r[x] >= 0) T->up[T->r[x]] = p;
    T->r[x] = p;
  } else {
    T->r[p] = T->l[x];
    if (T->l[x] >= 0) T->up[T->l[x]] = p;
    T->l[x] = p;
  }
  T->up[p] = x;
  relink(T, g, p, x);
}

static int leftmost(const treap *T, int x) {
  while (T->l[x] >= 0) x = T->l[x];
  return x;
}

static int succ(const treap *T, int x) {
  if (T->r[x] >= 0) return leftmost(T, T->r[x]);
  while (T->up[x] >= 0 && T->r[T->up[x]] == x) x = T->up[x];
  return T->up[x];
}

/* Insert x just above `after` (-1: at the bottom). */
static void treap_insert_after(treap *T, int after, int x) {
  T->l[x] = T->r[x] = -1;
  if (T->root < 0) {
    T->root = x, T->up[x] = -1;
    return;
  }
  if (after < 0) {
    int m = leftmost(T, T->root);
    T->l[m] = x, T->up[x] = m;
  } else if (T->r[after] < 0) {
    T->r[after] = x, T->up[x] = after;
  } else {
    int m = leftmost(T, T->r[after]);
    T->l[m] = x, T->up[x] = m;
  }
  while (T->up[x] >= 0 && T->pri[x] > T->pri[T->up[x]]) rotate_up(T, x);
}

static void treap_remove(treap *T, int x) {
  while (T->l[x] >= 0 && T->r[x] >= 0)
    rotate_up(T, T->pri[T->l[x]] > T->pri[T->r[x]] ? T->l[x] : T->r[x]);
  relink(T, T->up[x], x, T->l[x] >= 0 ? T->l[x] : T->r[x]);
}

/* Where q lies against status segment g: +1 above it, -1 below, 0 on its line. */
static int side(const sweep *W, int g, vec2 q) { return exact_orient(W->lo[g], W->hi[g], q); }

/* A status segment by where q lies: mode 0, the lowest with side <= 0 (the
 * first through q or above it); 1, the highest with q above it; 2, the
 * lowest with q below it. */
static int search(const treap *T, const sweep *W, vec2 q, int mode) {
  int x = T->root, best = -1;
  while (x >= 0) {
    int sd = side(W, x, q);
    int hit = mode == 0 ? sd <= 0 : mode == 1 ? sd > 0 : sd < 0;
    if (hit) best = x;
    /* modes 0 and 2 look for the lowest such node, mode 1 the highest */
    if (mode == 1) x = hit ? T->r[x] : T->l[x];
    else x = hit ? T->l[x] : T->r[x];
  }
  return best;
}

/* Test g and h (both may be -1); report when they offend. */
static int check(const segset *S, int g, int h, crossing_hit *hit) {
  if (g < 0 || h < 0) return 0;
  vec2 at;
  crossing_kind k = pair(S, g, h, &at);
  return k ? report(S, g, h, k, at, hit) : 0;
}

int crossing_find(const crossing_poly *p, int np, crossing_hit *hit) {
  segset S;
  segset_init(&S, p, np);
  sweep W = {&S, xmallocarray((size_t)S.N + 1, sizeof(vec2)), xmallocarray((size_t)S.N + 1, sizeof(vec2))};
  size_t ne = 2 * (size_t)S.N;
  event *ev = xmallocarray(ne + 1, sizeof *ev);
  for (int g = 0; g < S.N; g++) {
    vec2 a, b;
    ends(&S, g, &a, &b);
    if (exact_lex(a, b) > 0) {
      vec2 t = a;
      a = b, b = t;
    }
    W.lo[g] = a, W.hi[g] = b;
    ev[2 * (size_t)g] = (event){a, 2 * (uint32_t)g};
    ev[2 * (size_t)g + 1] = (event){b, 2 * (uint32_t)g + 1};
  }
  qsort(ev, ne, sizeof *ev, event_cmp);   /* a total order: deterministic */
  treap T;
  treap_init(&T, S.N);
  int found = 0;
  for (size_t i = 0; i < ne && !found;) {
    vec2 q = ev[i].p;
    size_t j = i;
    while (j < ne && exact_lex(ev[j].p, q) == 0) j++;

    /* 1. The tally: up to three segments through q. */
    int touch[3], nt = 0;
    for (size_t e = i; e < j && nt < 3; e++) touch[nt++] = (int)(ev[e].e >> 1);
    for (int g = search(&T, &W, q, 0); g >= 0 && nt < 3 && side(&W, g, q) == 0; g = succ(&T, g))
      if (exact_lex(W.hi[g], q) != 0) touch[nt++] = g;   /* q inside g (ends at q: counted) */
    for (int x = 0; x < nt && !found; x++)
      for (int y = x + 1; y < nt && !found; y++) found = check(&S, touch[x], touch[y], hit);
    if (found) break;
    XASSERT(nt <= 2);   /* three through one point always hold an offending pair */

    /* 2. Out go the segments ending at q, in those starting at q. */
    int in[2], ni = 0;
    for (size_t e = i; e < j; e++) {
      if (ev[e].e & 1) treap_remove(&T, (int)(ev[e].e >> 1));
      else in[ni++] = (int)(ev[e].e >> 1);
    }
    int below = search(&T, &W, q, 1), above = search(&T, &W, q, 2);
    if (ni == 2 && exact_orient(q, W.hi[in[0]], W.hi[in[1]]) < 0) {
      int t = in[0];   /* bottom first: the second turns left of the first */
      in[0] = in[1], in[1] = t;
    }
    for (int k = 0, after = below; k < ni; k++) {
      treap_insert_after(&T, after, in[k]);
      after = in[k];
    }

    /* 3. The pairs that became adjacent. */
    if (ni == 0) found = check(&S, below, above, hit);
    else found = check(&S, below, in[0], hit) || check(&S, in[ni - 1], above, hit);
    i = j;
  }
  treap_free(&T);
  free(ev);
  free(W.lo);
  free(W.hi);
  segset_free(&S);
  return found;
}
