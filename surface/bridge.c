/* bridge.c -- joining the contours of one side of a junction (bridge.h).
 *
 * Each group of joined contours is one cyclic sequence of points; a bridge
 * splices the sequence of one group into the other at the bridged edges:
 *
 *   X: ... a0 a1 ...     Y: ... b0 b1 ...
 *   ->  ... a0 m1 b1 ... (all of Y) ... b0 m2 a1 ...
 */
#include "surface/bridge.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "geom/crossing.h"
#include "geom/exact.h"
#include "util/xmem.h"

typedef struct {
  int n;
  vec2 *pt;
  int *id;
  int *src;   /* the input contour (index into sl->c) of each point, or -1 */
  int *k;     /* its index in that contour */
} seq;

typedef struct { vec2 a, b; } segment;

typedef struct {
  const slices *sl;
  const int *cs;
  int count, slice, other;
  int sign;               /* +1: the contours run counter-clockwise, -1 clockwise */
  unsigned char **used;   /* used[x][i]: edge i of contour cs[x] carries a bridge */
  segment *bridges;       /* every bridge segment so far (2 per bridge) */
  vec2 (*quads)[4];       /* their corridors */
  int nb;
} ctx;

static double d2(vec2 a, vec2 b) {
  double x = a.x - b.x, y = a.y - b.y;
  return x * x + y * y;
}

static int same(vec2 a, vec2 b) { return a.x == b.x && a.y == b.y; }

/* Exact point in a small polygon: 1 inside or on, 0 outside. */
static int in_small(const vec2 *p, int n, vec2 q) {
  int odd = 0;
  for (int s = 0; s < n; s++) {
    vec2 a = p[s], b = p[(s + 1) % n];
    int o = exact_orient(a, b, q);
    if (o == 0 && q.x >= fmin(a.x, b.x) && q.x <= fmax(a.x, b.x) && q.y >= fmin(a.y, b.y) &&
        q.y <= fmax(a.y, b.y))
      return 1;
    int up = a.y > q.y, bup = b.y > q.y;
    if (up != bup && (bup ? o > 0 : o < 0)) odd ^= 1;
  }
  return odd;
}

/* Exact point strictly inside a small polygon: 1, else 0 (outside or on). */
static int in_strict(const vec2 *p, vec2 q) {
  for (int s = 0; s < 4; s++) {
    vec2 a = p[s], b = p[(s + 1) % 4];
    if (exact_orient(a, b, q) == 0 && q.x >= fmin(a.x, b.x) && q.x <= fmax(a.x, b.x) && q.y >= fmin(a.y, b.y) &&
        q.y <= fmax(a.y, b.y))
      return 0;
  }
  return in_small(p, 4, q);
}

static int meets(const slice_contour *c, segment s, vec2 ok1, vec2 ok2) {
  return inside_segment_meets(c->ix, s.a, s.b, ok1, ok2);
}

/* Is the bridge from edge i of contour cs[x] to edge j of contour cs[y]
 * legal?  (bridge.h) */
static int legal(const ctx *c, int x, int i, int y, int j, int strict) {
  const slices *sl = c->sl;
  const slice_contour *X = &sl->c[c->cs[x]], *Y = &sl->c[c->cs[y]];
  if (c->used[x][i] || c->used[y][j]) return 0;
  vec2 a0 = X->pt[i], a1 = X->pt[(i + 1) % X->n], b0 = Y->pt[j], b1 = Y->pt[(j + 1) % Y->n];
  vec2 quad[4] = {a0, b1, b0, a1};
  double qa = geom_area2(quad, 4);   /* the corridor runs the contours' way: it faces out */
  if (qa == 0 || (qa > 0 ? 1 : -1) != c->sign) return 0;
  segment s1 = {a0, b1}, s2 = {b0, a1};
  if (crossing_segments(s1.a, s1.b, s2.a, s2.b, NULL) != CROSSING_NONE) return 0;
  vec2 none = {NAN, NAN};
  /* This slice: only the bridge's own ends may touch, on their own contours. */
  for (int z = sl->first[c->slice]; z < sl->first[c->slice + 1]; z++) {
    const slice_contour *Z = &sl->c[z];
    if (meets(Z, s1, Z == X ? a0 : none, Z == Y ? b1 : none)) return 0;
    if (meets(Z, s2, Z == Y ? b0 : none, Z == X ? a1 : none)) return 0;
    if (Z != X && Z != Y && in_small(quad, 4, Z->pt[0])) return 0;
  }
  /* The partner slice: no contact but at the bridge's ends (when strict). */
  for (int z = sl->first[c->other]; strict && z < sl->first[c->other + 1]; z++) {
    const slice_contour *Z = &sl->c[z];
    if (meets(Z, s1, a0, b1) || meets(Z, s2, b0, a1)) return 0;
  }
  /* Earlier bridges: at most a shared end. */
  for (int b = 0; b < 2 * c->nb; b++) {
    segment e = c->bridges[b];
    const segment *mine[2] = {&s1, &s2};
    for (int m = 0; m < 2; m++) {
      vec2 at;
      crossing_kind k = crossing_segments(mine[m]->a, mine[m]->b, e.a, e.b, &at);
      if (k == CROSSING_NONE) continue;
      int shared = (same(at, mine[m]->a) || same(at, mine[m]->b)) && (same(at, e.a) || same(at, e.b));
      if (k != CROSSING_TOUCH || !shared) return 0;
    }
  }
  /* An earlier corridor may not hold either contour: a point of it strictly
   * inside (a contour's own corner of that corridor, on its boundary, does
   * not count: a contour may carry several bridges). */
  for (int b = 0; b < c->nb; b++)
    if (in_strict(c->quads[b], X->pt[0]) || in_strict(c->quads[b], Y->pt[0])) return 0;
  return 1;
}

static double cost(const slice_contour *X, int i, const slice_contour *Y, int j) {
  return d2(X->pt[i], Y->pt[(j + 1) % Y->n]) + d2(X->pt[(i + 1) % X->n], Y->pt[j]);
}

/* For each edge i of X, the best edge j of Y; sorted by cost.  Returns the count. */
static int best_per_edge(const slice_contour *X, const slice_contour *Y, geom_pick *out) {
  for (int i = 0; i < X->n; i++) {
    geom_pick b = {HUGE_VAL, i, 0};
    for (int j = 0; j < Y->n; j++) {
      double v = cost(X, i, Y, j);
      if (v < b.w) b.w = v, b.b = j;
    }
    out[i] = b;
  }
  geom_pick_sort(out, (size_t)X->n);
  return X->n;
}

/* The shortest legal bridge between cs[x] and cs[y]: 1 and *i, *j, or 0. */
static int find_bridge(const ctx *c, int x, int y, int strict, int *bi, int *bj) {
  const slice_contour *X = &c->sl->c[c->cs[x]], *Y = &c->sl->c[c->cs[y]];
  geom_pick *cd = xmallocarray((size_t)X->n, sizeof *cd);
  int n = best_per_edge(X, Y, cd), found = 0;
  for (int k = 0; k < n && !found; k++)
    if (legal(c, x, cd[k].a, y, cd[k].b, strict)) *bi = cd[k].a, *bj = cd[k].b, found = 1;
  free(cd);
  if (found) return 1;
  /* Every edge's nearest partner is illegal: try all pairs, shortest first
   * (for a strict bridge, a preference, only the 4096 shortest: two large
   * contours with none would otherwise cost m n tests before the relaxed
   * pass). */
  size_t all = (size_t)X->n * (size_t)Y->n;
  cd = xmallocarray(all, sizeof *cd);
  size_t m = 0;
  for (int i = 0; i < X->n; i++)
    for (int j = 0; j < Y->n; j++) cd[m++] = (geom_pick){cost(X, i, Y, j), i, j};
  geom_pick_sort(cd, m);
  if (strict && m > 4096) m = 4096;
  for (size_t k = 0; k < m && !found; k++)
    if (legal(c, x, cd[k].a, y, cd[k].b, strict)) *bi = cd[k].a, *bj = cd[k].b, found = 1;
  free(cd);
  return found;
}

static void seq_of(seq *q, const slice_contour *X, int src) {
  q->n = X->n;
  q->pt = xmallocarray((size_t)X->n, sizeof *q->pt);
  q->id = xmallocarray((size_t)X->n, sizeof *q->id);
  q->src = xmallocarray((size_t)X->n, sizeof *q->src);
  q->k = xmallocarray((size_t)X->n, sizeof *q->k);
  for (int i = 0; i < X->n; i++) q->pt[i] = X->pt[i], q->id[i] = X->base + i, q->src[i] = src, q->k[i] = i;
}

static void seq_free(seq *q) {
  free(q->pt), free(q->id), free(q->src), free(q->k);
  memset(q, 0, sizeof *q);
}

static int seq_find(const seq *q, int src, int k) {
  for (int p = 0; p < q->n; p++)
    if (q->src[p] == src && q->k[p] == k) return p;
  xpanic("bridge: point %d of contour %d not in its group", k, src);
}

/* Splice Y into X at the bridge (X's point px = a0, Y's point py = b0). */
static void splice(seq *X, seq *Y, int px, int py, int s1, int s2, vec2 m1, vec2 m2) {
  int n = X->n + Y->n + 2, w = 0;
  seq r = {n, xmallocarray((size_t)n, sizeof(vec2)), xmallocarray((size_t)n, sizeof(int)),
           xmallocarray((size_t)n, sizeof(int)), xmallocarray((size_t)n, sizeof(int))};
#define PUT(P, I, S, K) (r.pt[w] = (P), r.id[w] = (I), r.src[w] = (S), r.k[w] = (K), w++)
  for (int p = 0; p <= px; p++) PUT(X->pt[p], X->id[p], X->src[p], X->k[p]);
  PUT(m1, -1 - s1, -1, -1);
  for (int t = 1; t <= Y->n; t++) {   /* b1 ... around ... b0 */
    int p = (py + t) % Y->n;
    PUT(Y->pt[p], Y->id[p], Y->src[p], Y->k[p]);
  }
  PUT(m2, -1 - s2, -1, -1);
  for (int p = px + 1; p < X->n; p++) PUT(X->pt[p], X->id[p], X->src[p], X->k[p]);
#undef PUT
  XASSERT(w == n);
  seq_free(X);
  seq_free(Y);
  *X = r;
}

static int find_root(int *up, int x) {
  while (up[x] != x) x = up[x] = up[up[x]];
  return x;
}

int bridge_join(const slices *sl, const int *cs, int count, int other, double lift,
                const char *name, composite *out, char *err, size_t errlen) {
  memset(out, 0, sizeof *out);
  const slice_contour *first = &sl->c[cs[0]];
  ctx c = {sl, cs, count, first->slice, other, first->area2 > 0 ? 1 : -1,
           xcalloc((size_t)count, sizeof(unsigned char *)), NULL, NULL, 0};
  seq *g = xcalloc((size_t)count, sizeof *g);
  int *up = xmallocarray((size_t)count, sizeof *up);
  for (int x = 0; x < count; x++) {
    c.used[x] = xcalloc((size_t)sl->c[cs[x]].n, 1);
    seq_of(&g[x], &sl->c[cs[x]], cs[x]);
    up[x] = x;
  }
  c.bridges = xmallocarray(2 * (size_t)count, sizeof *c.bridges);
  c.quads = xmallocarray((size_t)count, sizeof *c.quads);
  out->steiner = xmallocarray(2 * (size_t)count, sizeof *out->steiner);
  out->tri = xmallocarray(4 * (size_t)count, sizeof *out->tri);
  double z = sl->z[c.slice] + lift;

  /* Kruskal over the pairs, by the length of each pair's closest points. */
  int np = count * (count - 1) / 2, joins = 0, rc = 0;
  geom_pick *pr = xmallocarray((size_t)np + 1, sizeof *pr);
  np = 0;
  for (int x = 0; x < count; x++)
    for (int y = x + 1; y < count; y++) {
      const slice_contour *X = &sl->c[cs[x]], *Y = &sl->c[cs[y]];
      double best = HUGE_VAL;
      for (int i = 0; i < X->n; i++)
        for (int j = 0; j < Y->n; j++) best = fmin(best, d2(X->pt[i], Y->pt[j]));
      pr[np++] = (geom_pick){best, x, y};
    }
  geom_pick_sort(pr, (size_t)np);
  /* Strict bridges first: crossing no contour of either slice.  Real data
   * needs more: a blob just outside the body whose slice above bulges over
   * it (dicompyler BODY), two vessels merging into a kinked one (Lt Lung):
   * no bridge between them avoids the other slice's contour in projection.
   * Then a bridge may cross the partner slice's contours (it lies between
   * the planes, so it meets none of them in space); never its own slice's,
   * which would make the composite cross itself.  A note says where. */
  for (int strict = 1; strict >= 0 && joins < count - 1; strict--) {
    for (int k = 0; k < np && joins < count - 1; k++) {
      int x = pr[k].a, y = pr[k].b, i, j;
      int rx = find_root(up, x), ry = find_root(up, y);
      if (rx == ry || !find_bridge(&c, x, y, strict, &i, &j)) continue;
      if (!strict && out->relaxed++ == 0) {
        out->relaxed_line[0] = sl->c[cs[x]].line;
        out->relaxed_line[1] = sl->c[cs[y]].line;
      }
      const slice_contour *X = &sl->c[cs[x]], *Y = &sl->c[cs[y]];
      vec2 a0 = X->pt[i], a1 = X->pt[(i + 1) % X->n], b0 = Y->pt[j], b1 = Y->pt[(j + 1) % Y->n];
      vec2 m1 = {(a0.x + b1.x) / 2, (a0.y + b1.y) / 2}, m2 = {(a1.x + b0.x) / 2, (a1.y + b0.y) / 2};
      int s1 = out->nsteiner++, s2 = out->nsteiner++;
      out->steiner[s1] = (vec3){m1.x, m1.y, z};
      out->steiner[s2] = (vec3){m2.x, m2.y, z};
      int ia0 = X->base + i, ia1 = X->base + (i + 1) % X->n, ib0 = Y->base + j, ib1 = Y->base + (j + 1) % Y->n;
      int im1 = -1 - s1, im2 = -1 - s2;
      int t[4][3] = {{ia0, ia1, im2}, {ia0, im2, im1}, {im2, ib0, ib1}, {im2, ib1, im1}};
      for (int q = 0; q < 4; q++) {
        int *d = out->tri[out->ntri++];
        d[0] = t[q][0];
        d[1] = lift > 0 ? t[q][1] : t[q][2];
        d[2] = lift > 0 ? t[q][2] : t[q][1];
      }
      c.used[x][i] = c.used[y][j] = 1;
      c.bridges[2 * c.nb] = (segment){a0, b1};
      c.bridges[2 * c.nb + 1] = (segment){b0, a1};
      c.quads[c.nb][0] = a0, c.quads[c.nb][1] = b1, c.quads[c.nb][2] = b0, c.quads[c.nb][3] = a1;
      c.nb++;
      splice(&g[rx], &g[ry], seq_find(&g[rx], cs[x], i), seq_find(&g[ry], cs[y], j), s1, s2, m1, m2);
      up[ry] = rx;
      joins++;
    }
  }
  free(pr);
  if (joins < count - 1) {
    /* Name a contour left out and one of the group of the first. */
    int r0 = find_root(up, 0), lone = 1;
    while (find_root(up, lone) == r0) lone++;
    const slice_contour *L = &sl->c[cs[lone]];
    snprintf(err, errlen,
             "%s:%d: no bridge can join the contour to the contour at line %d without crossing "
             "or enclosing a contour of their slice (they meet one contour of the slice at "
             "z=%s; slice z=%s)",
             name, L->line, first->line, ARGS_G(ldexp(sl->z[other], sl->scale)), ARGS_G(ldexp(sl->z[c.slice], sl->scale)));
    rc = -1;
  } else {
    seq *r = &g[find_root(up, 0)];
    out->n = r->n;
    out->pt = r->pt, out->id = r->id;
    r->pt = NULL, r->id = NULL;
    out->nbridges = c.nb;
  }
  for (int x = 0; x < count; x++) {
    seq_free(&g[x]);
    free(c.used[x]);
  }
  free(g);
  free(up);
  free(c.used);
  free(c.bridges);
  free(c.quads);
  if (rc != 0) bridge_free(out);
  return rc;
}

void bridge_free(composite *c) {
  free(c->pt), free(c->id), free(c->steiner), free(c->tri);
  memset(c, 0, sizeof *c);
}
