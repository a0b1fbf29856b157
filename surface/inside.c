/* inside.c -- exact point-in-polygon through a row index of the segments.
 *
 *   rows:  y = ylo + r h .. ylo + (r+1) h,  h = (yhi - ylo) / R
 *   row(y) = floor((y - ylo) / h), clamped: monotone in y, so a segment
 *   whose y range holds y is listed in row(y) whatever the rounding. */
#include "surface/inside.h"

#include <stdlib.h>

#include "geom/crossing.h"
#include "geom/exact.h"
#include "util/xmem.h"

struct inside_index {
  const vec2 *p;
  int n, rows;
  double ylo, inv;   /* row(y) = (y - ylo) * inv */
  vec2 lo, hi;       /* bounding box */
  int *start;        /* row r: seg[start[r] .. start[r+1]-1] */
  int *seg;
};

static int row(const inside_index *ix, double y) {
  double r = (y - ix->ylo) * ix->inv;
  if (!(r > 0)) return 0;   /* also NaN-safe */
  if (r >= ix->rows) return ix->rows - 1;
  return (int)r;
}

static double lo2(double a, double b) { return a < b ? a : b; }
static double hi2(double a, double b) { return a < b ? b : a; }

inside_index *inside_new(const vec2 *p, int n) {
  XASSERT(n >= 3);
  inside_index *ix = xcalloc(1, sizeof *ix);
  ix->p = p;
  ix->n = n;
  ix->lo = ix->hi = p[0];
  for (int i = 1; i < n; i++) {
    ix->lo.x = lo2(ix->lo.x, p[i].x), ix->lo.y = lo2(ix->lo.y, p[i].y);
    ix->hi.x = hi2(ix->hi.x, p[i].x), ix->hi.y = hi2(ix->hi.y, p[i].y);
  }
  ix->ylo = ix->lo.y;
  ix->rows = ix->hi.y > ix->lo.y ? (n + 1) / 2 : 1;
  ix->inv = ix->hi.y > ix->lo.y ? ix->rows / (ix->hi.y - ix->lo.y) : 0;
  ix->start = xcalloc((size_t)ix->rows + 1, sizeof *ix->start);
  for (int pass = 0; pass < 2; pass++) {
    for (int s = 0; s < n; s++) {
      vec2 a = p[s], b = p[(s + 1) % n];
      int r0 = row(ix, lo2(a.y, b.y)), r1 = row(ix, hi2(a.y, b.y));
      for (int r = r0; r <= r1; r++) {
        if (pass == 0) ix->start[r + 1]++;
        else ix->seg[ix->start[r]++] = s;
      }
    }
    if (pass == 0) {
      for (int r = 0; r < ix->rows; r++) ix->start[r + 1] += ix->start[r];
      ix->seg = xmallocarray((size_t)ix->start[ix->rows] + 1, sizeof *ix->seg);
    } else {
      for (int r = ix->rows; r > 0; r--) ix->start[r] = ix->start[r - 1];
      ix->start[0] = 0;
    }
  }
  return ix;
}

void inside_free(inside_index *ix) {
  if (!ix) return;
  free(ix->start);
  free(ix->seg);
  free(ix);
}

int inside_point(const inside_index *ix, vec2 q) {
  if (q.x < ix->lo.x || q.x > ix->hi.x || q.y < ix->lo.y || q.y > ix->hi.y) return INSIDE_OUT;
  int r = row(ix, q.y), odd = 0;
  for (int k = ix->start[r]; k < ix->start[r + 1]; k++) {
    int s = ix->seg[k];
    vec2 a = ix->p[s], b = ix->p[(s + 1) % ix->n];
    if (q.y < lo2(a.y, b.y) || q.y > hi2(a.y, b.y)) continue;
    int up = a.y > q.y, bup = b.y > q.y;
    if (up == bup && (q.x < lo2(a.x, b.x) || q.x > hi2(a.x, b.x))) continue;
    int o = exact_orient(a, b, q);
    if (o == 0) {
      if (q.x >= lo2(a.x, b.x) && q.x <= hi2(a.x, b.x)) return INSIDE_ON;
      continue;
    }
    /* The segment straddles the line y = q.y (half-open: the lower end
     * counts) and crosses it right of q when q is left of it, going up. */
    if (up != bup && (bup ? o > 0 : o < 0)) odd ^= 1;
  }
  return odd ? INSIDE_IN : INSIDE_OUT;
}

void inside_near(const inside_index *ix, vec2 a, vec2 b, void (*fn)(void *ud, int s), void *ud) {
  vec2 lo = {lo2(a.x, b.x), lo2(a.y, b.y)}, hi = {hi2(a.x, b.x), hi2(a.y, b.y)};
  if (hi.x < ix->lo.x || lo.x > ix->hi.x || hi.y < ix->lo.y || lo.y > ix->hi.y) return;
  int r0 = row(ix, lo.y), r1 = row(ix, hi.y);
  for (int r = r0; r <= r1; r++)
    for (int k = ix->start[r]; k < ix->start[r + 1]; k++) {
      int s = ix->seg[k];
      vec2 c = ix->p[s], d = ix->p[(s + 1) % ix->n];
      int first = row(ix, lo2(c.y, d.y));
      if ((first > r0 ? first : r0) != r) continue;   /* reported in an earlier row */
      if (hi2(c.x, d.x) < lo.x || lo2(c.x, d.x) > hi.x || hi2(c.y, d.y) < lo.y || lo2(c.y, d.y) > hi.y)
        continue;
      fn(ud, s);
    }
}

void inside_box(const inside_index *ix, vec2 *lo, vec2 *hi) {
  *lo = ix->lo;
  *hi = ix->hi;
}

const vec2 *inside_points(const inside_index *ix, int *n) {
  *n = ix->n;
  return ix->p;
}

typedef struct {
  const inside_index *ix;
  vec2 a, b, ok1, ok2;
  int bad;
} meets_q;

static int same(vec2 a, vec2 b) { return a.x == b.x && a.y == b.y; }

static void meets_cb(void *ud, int s) {
  meets_q *m = ud;
  if (m->bad) return;
  vec2 at;
  crossing_kind k = crossing_segments(m->a, m->b, m->ix->p[s], m->ix->p[(s + 1) % m->ix->n], &at);
  if (k == CROSSING_NONE || (k == CROSSING_TOUCH && (same(at, m->ok1) || same(at, m->ok2)))) return;
  m->bad = 1;
}

int inside_segment_meets(const inside_index *ix, vec2 a, vec2 b, vec2 ok1, vec2 ok2) {
  meets_q m = {ix, a, b, ok1, ok2, 0};
  inside_near(ix, a, b, meets_cb, &m);
  return m.bad;
}
