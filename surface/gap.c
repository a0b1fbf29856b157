/* gap.c -- the least distance between two contours (gap.h).
 *
 * Every vertex of one against the segments of the other near it: the row
 * index of the other (inside_near) lists the segments whose boxes meet the
 * square of half-side r about the vertex, r the least distance found so far;
 * vertices whose distance to the other's box exceeds r are skipped.  The
 * first vertex tried is the one nearest the other's box, so r is small
 * early. */
#include "surface/gap.h"

#include <math.h>

typedef struct {
  const vec2 *q;
  int nq;
  vec2 p;
  exactdist *best;
  int any;
} near_q;

static void near_cb(void *ud, int s) {
  near_q *c = ud;
  exactdist d;
  exactdist_segment(c->p, c->q[s], c->q[(s + 1) % c->nq], &d);
  if (c->any && (d.lo > c->best->hi || exactdist_cmp(&d, c->best) >= 0)) return;
  *c->best = d;
  c->any = 1;
}

/* The squared distance from p to the box [lo, hi], rounded down. */
static double box_d2(vec2 p, vec2 lo, vec2 hi) {
  double x = p.x < lo.x ? lo.x - p.x : p.x > hi.x ? p.x - hi.x : 0;
  double y = p.y < lo.y ? lo.y - p.y : p.y > hi.y ? p.y - hi.y : 0;
  return (x * x + y * y) * (1 - 0x1p-48);
}

/* Vertex p of one contour against the segments of the other (index ix). */
static void vertex(near_q *c, const inside_index *ix, vec2 p) {
  c->p = p;
  if (!c->any || !(c->best->hi < INFINITY)) {
    for (int s = 0; s < c->nq; s++) near_cb(c, s);
    return;
  }
  double r = sqrt(c->best->hi) * (1 + 0x1p-40) + (fabs(p.x) + fabs(p.y)) * 0x1p-50;
  inside_near(ix, (vec2){p.x - r, p.y - r}, (vec2){p.x + r, p.y + r}, near_cb, c);
}

static void one_way(const slice_contour *A, const slice_contour *B, near_q *c) {
  vec2 lo, hi;
  inside_box(B->ix, &lo, &hi);
  c->q = B->pt, c->nq = B->n;
  if (!c->any) {   /* start where the other is nearest */
    int k = 0;
    double bk = box_d2(A->pt[0], lo, hi);
    for (int i = 1; i < A->n; i++) {
      double v = box_d2(A->pt[i], lo, hi);
      if (v < bk) bk = v, k = i;
    }
    vertex(c, B->ix, A->pt[k]);
  }
  for (int i = 0; i < A->n; i++)
    if (!(box_d2(A->pt[i], lo, hi) > c->best->hi)) vertex(c, B->ix, A->pt[i]);
}

void gap_between(const slice_contour *A, const slice_contour *B, exactdist *out) {
  near_q c = {NULL, 0, {0, 0}, out, 0};
  one_way(A, B, &c);
  one_way(B, A, &c);
}

double gap_box_bound(const slice_contour *A, const slice_contour *B) {
  vec2 alo, ahi, blo, bhi;
  inside_box(A->ix, &alo, &ahi);
  inside_box(B->ix, &blo, &bhi);
  double x = alo.x > bhi.x ? alo.x - bhi.x : blo.x > ahi.x ? blo.x - ahi.x : 0;
  double y = alo.y > bhi.y ? alo.y - bhi.y : blo.y > ahi.y ? blo.y - ahi.y : 0;
  return (x * x + y * y) * (1 - 0x1p-48);
}
