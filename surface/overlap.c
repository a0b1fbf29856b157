/* overlap.c -- the exact region overlap test.
 *
 * Let R be the common part of the open regions of P and Q.  If R is not
 * empty, then (the boundaries being simple closed polygons):
 *   1. a segment of P crosses a segment of Q at a point interior to both, or
 *   2. a vertex of one lies strictly inside the other, or
 *   3. one region lies inside the other: an interior point of it (the
 *      centroid of an ear) lies inside the other, or
 *   4. otherwise R's boundary runs along a piece of a segment of one polygon
 *      inside the other, between vertices of the other lying on it: that
 *      piece's midpoint lies strictly inside the other.
 * Each test is exact (geom/exact.h, geom/crossing.h) but for the rounding of
 * the points 3 and 4 construct, which lie well inside a region when they
 * count.  The cheap tests come first; 3 and 4 run only when the boundaries
 * touch or the regions are disjoint with overlapping boxes. */
#include "surface/overlap.h"

#include <stdlib.h>

#include "geom/crossing.h"
#include "geom/exact.h"
#include "util/xmem.h"

static int boxes_meet(const inside_index *a, const inside_index *b) {
  vec2 alo, ahi, blo, bhi;
  inside_box(a, &alo, &ahi);
  inside_box(b, &blo, &bhi);
  /* Open regions: boxes that only touch cannot hold a common interior point. */
  return alo.x < bhi.x && blo.x < ahi.x && alo.y < bhi.y && blo.y < ahi.y;
}

static int vertex_inside(const inside_index *a, const inside_index *b) {
  int n;
  const vec2 *p = inside_points(a, &n);
  for (int i = 0; i < n; i++)
    if (inside_point(b, p[i]) == INSIDE_IN) return 1;
  return 0;
}

typedef struct {
  const vec2 *q;   /* the other polygon's points */
  int nq;
  vec2 a, b;       /* the segment asked about */
  int hit;
} cross_q;

static void cross_cb(void *ud, int s) {
  cross_q *c = ud;
  if (c->hit) return;
  vec2 d = c->q[s], e = c->q[(s + 1) % c->nq];
  if (crossing_segments(c->a, c->b, d, e, NULL) == CROSSING_CROSS) c->hit = 1;
}

static int segments_cross(const inside_index *a, const inside_index *b) {
  int n;
  const vec2 *p = inside_points(a, &n);
  cross_q c = {NULL, 0, {0, 0}, {0, 0}, 0};
  c.q = inside_points(b, &c.nq);
  for (int i = 0; i < n && !c.hit; i++) {
    c.a = p[i], c.b = p[(i + 1) % n];
    inside_near(b, c.a, c.b, cross_cb, &c);
  }
  return c.hit;
}

/* Test 3: an interior point of a (the centroid of an ear: a convex vertex
 * whose triangle holds no other vertex) strictly inside b. */
static int ear_inside(const inside_index *a, const inside_index *b) {
  int n;
  const vec2 *p = inside_points(a, &n);
  int sign = geom_area2(p, n) > 0 ? 1 : -1;
  for (int i = 0; i < n; i++) {
    vec2 u = p[(i + n - 1) % n], v = p[i], w = p[(i + 1) % n];
    if (exact_orient(u, v, w) != sign) continue;
    int ear = 1;
    for (int j = 0; j < n && ear; j++) {
      if (j == i || j == (i + 1) % n || j == (i + n - 1) % n) continue;
      if (exact_orient(u, v, p[j]) != -sign && exact_orient(v, w, p[j]) != -sign &&
          exact_orient(w, u, p[j]) != -sign)
        ear = 0;
    }
    if (!ear) continue;
    vec2 c = {(u.x + v.x + w.x) / 3, (u.y + v.y + w.y) / 3};
    if (inside_point(a, c) != INSIDE_IN) continue;   /* a sliver: rounding left it */
    return inside_point(b, c) == INSIDE_IN;
  }
  return 0;
}

/* Test 4 for the segment uw of a against b. */
typedef struct {
  const vec2 *q;
  int nq;
  vec2 u, w;
  vec2 *on;        /* b's vertices strictly inside uw */
  int non, cap;
  int *near;       /* b's segments near uw */
  int nnear, capnear;
} piece_q;

static void piece_cb(void *ud, int s) {
  piece_q *c = ud;
  if (c->nnear == c->capnear) {
    c->capnear = c->capnear ? 2 * c->capnear : 16;
    c->near = xreallocarray(c->near, (size_t)c->capnear, sizeof *c->near);
  }
  c->near[c->nnear++] = s;
  vec2 v = c->q[s];
  if ((v.x == c->u.x && v.y == c->u.y) || (v.x == c->w.x && v.y == c->w.y)) return;
  if (exact_orient(c->u, c->w, v) != 0) return;
  double lx = c->u.x < c->w.x ? c->u.x : c->w.x, hx = c->u.x < c->w.x ? c->w.x : c->u.x;
  double ly = c->u.y < c->w.y ? c->u.y : c->w.y, hy = c->u.y < c->w.y ? c->w.y : c->u.y;
  if (v.x < lx || v.x > hx || v.y < ly || v.y > hy) return;
  if (c->non == c->cap) {
    c->cap = c->cap ? 2 * c->cap : 8;
    c->on = xreallocarray(c->on, (size_t)c->cap, sizeof *c->on);
  }
  c->on[c->non++] = v;
}

static int along(const piece_q *c, vec2 a, vec2 b) {
  for (int k = 0; k < c->nnear; k++) {
    int s = c->near[k];
    vec2 d = c->q[s], e = c->q[(s + 1) % c->nq];
    if (exact_orient(d, e, a) || exact_orient(d, e, b)) continue;
    double lx = d.x < e.x ? d.x : e.x, hx = d.x < e.x ? e.x : d.x;
    double ly = d.y < e.y ? d.y : e.y, hy = d.y < e.y ? e.y : d.y;
    if (a.x >= lx && a.x <= hx && a.y >= ly && a.y <= hy && b.x >= lx && b.x <= hx && b.y >= ly &&
        b.y <= hy)
      return 1;
  }
  return 0;
}

static int pieces_inside(const inside_index *a, const inside_index *b) {
  int n, found = 0;
  const vec2 *p = inside_points(a, &n);
  piece_q c = {NULL, 0, {0, 0}, {0, 0}, NULL, 0, 0, NULL, 0, 0};
  c.q = inside_points(b, &c.nq);
  for (int i = 0; i < n && !found; i++) {
    c.u = p[i], c.w = p[(i + 1) % n];
    c.non = c.nnear = 0;
    inside_near(b, c.u, c.w, piece_cb, &c);
    /* The split points in order along uw. */
    vec2 d = {c.w.x - c.u.x, c.w.y - c.u.y};
    for (int x = 1; x < c.non; x++)   /* insertion sort: few points on one segment */
      for (int y = x; y > 0; y--) {
        vec2 s = c.on[y - 1], t = c.on[y];
        double ds = (s.x - c.u.x) * d.x + (s.y - c.u.y) * d.y, dt = (t.x - c.u.x) * d.x + (t.y - c.u.y) * d.y;
        if (ds <= dt) break;
        c.on[y - 1] = t, c.on[y] = s;
      }
    vec2 prev = c.u;
    for (int k = 0; k <= c.non && !found; k++) {
      vec2 next = k < c.non ? c.on[k] : c.w;
      if (!along(&c, prev, next)) {
        vec2 m = {(prev.x + next.x) / 2, (prev.y + next.y) / 2};
        if (inside_point(b, m) == INSIDE_IN) found = 1;
      }
      prev = next;
    }
  }
  free(c.on);
  free(c.near);
  return found;
}

int overlap_regions(const inside_index *ip, const inside_index *iq) {
  if (!boxes_meet(ip, iq)) return 0;
  int n;
  /* The first vertices first: a cheap answer for most overlapping pairs. */
  if (inside_point(iq, inside_points(ip, &n)[0]) == INSIDE_IN) return 1;
  if (inside_point(ip, inside_points(iq, &n)[0]) == INSIDE_IN) return 1;
  if (segments_cross(ip, iq)) return 1;
  if (vertex_inside(ip, iq) || vertex_inside(iq, ip)) return 1;
  if (ear_inside(ip, iq) || ear_inside(iq, ip)) return 1;
  return pieces_inside(ip, iq) || pieces_inside(iq, ip);
}

/* The first contact of the boundaries found (CROSSING_NONE: they do not meet). */
typedef struct {
  const vec2 *q;
  int nq;
  vec2 a, b;
  crossing_kind kind;
} contact_q;

static void contact_cb(void *ud, int s) {
  contact_q *c = ud;
  if (c->kind == CROSSING_NONE) c->kind = crossing_segments(c->a, c->b, c->q[s], c->q[(s + 1) % c->nq], NULL);
}

int overlap_closed(const inside_index *ip, const inside_index *iq) {
  vec2 alo, ahi, blo, bhi;
  inside_box(ip, &alo, &ahi);
  inside_box(iq, &blo, &bhi);
  if (alo.x > bhi.x || blo.x > ahi.x || alo.y > bhi.y || blo.y > ahi.y) return OVERLAP_APART;
  int n, nq;
  const vec2 *p = inside_points(ip, &n), *q = inside_points(iq, &nq);
  int r0 = inside_point(iq, p[0]), r1 = inside_point(ip, q[0]);
  if (r0 == INSIDE_IN || r1 == INSIDE_IN) return OVERLAP_INTERIOR;
  int touch = r0 == INSIDE_ON || r1 == INSIDE_ON;
  if (!touch) {
    /* Boundaries apart, and neither first point inside the other: apart
     * (nested contours would have put one inside). */
    contact_q c = {q, nq, {0, 0}, {0, 0}, CROSSING_NONE};
    for (int i = 0; i < n && c.kind == CROSSING_NONE; i++) {
      c.a = p[i], c.b = p[(i + 1) % n];
      inside_near(iq, c.a, c.b, contact_cb, &c);
    }
    if (c.kind == CROSSING_CROSS) return OVERLAP_INTERIOR;
    if (c.kind == CROSSING_NONE) return OVERLAP_APART;
  }
  return overlap_regions(ip, iq) ? OVERLAP_INTERIOR : OVERLAP_TOUCH;
}
