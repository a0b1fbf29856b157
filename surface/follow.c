/* follow.c -- the pair a 1-1 band is tiled on (follow.h).
 *
 *   lo:  0 . 1 . . 2 3        a tile on the pair's edge 1-2 of lo, apex q,
 *        |  fan   |           becomes the fan of lo's edges between them
 *   hi:       q               (all in one plane), apex q */
#include "surface/follow.h"

#include <math.h>
#include <stdlib.h>

#include "util/xmem.h"

static void corners(const vec2 *p, int n, follow_side *s) {
  s->full = n;
  s->at = xmallocarray((size_t)n, sizeof *s->at);
  s->n = geom_corners(p, n, s->at);
  s->pt = xmallocarray((size_t)s->n, sizeof *s->pt);
  for (int k = 0; k < s->n; k++) s->pt[k] = p[s->at[k]];
}

void follow_pair(const vec2 *lo, int nlo, const vec2 *hi, int nhi, follow_side *a, follow_side *b) {
  corners(lo, nlo, a);
  corners(hi, nhi, b);
  vec2 c0 = geom_centroid(a->pt, a->n), c1 = geom_centroid(b->pt, b->n);
  double s = sqrt(geom_area2(a->pt, a->n) / geom_area2(b->pt, b->n));
  if (!(s > 0 && isfinite(s))) s = 1;   /* areas of one sign, never 0: a guard only */
  for (int k = 0; k < b->n; k++)
    b->pt[k] = (vec2){c0.x + s * (b->pt[k].x - c1.x), c0.y + s * (b->pt[k].y - c1.y)};
}

void follow_tiles(const tiling *t, const follow_side *a, const follow_side *b, int (*tile)[3],
                  unsigned char *on) {
  int steps = a->n + b->n, k = 0;
  int (*rt)[3] = xmallocarray((size_t)steps, sizeof *rt);
  unsigned char *ron = xmalloc((size_t)steps);
  tiling_tiles(t, rt, ron);
  for (int i = 0; i < steps; i++) {
    const follow_side *e = ron[i] ? b : a, *x = ron[i] ? a : b;
    int from = e->at[rt[i][0]], to = e->at[rt[i][1]], apex = x->at[rt[i][2]];
    for (int p = from; p != to; p = p + 1 == e->full ? 0 : p + 1, k++) {
      tile[k][0] = p, tile[k][1] = p + 1 == e->full ? 0 : p + 1, tile[k][2] = apex;
      on[k] = ron[i];
    }
  }
  XASSERT(k == a->full + b->full);
  free(rt);
  free(ron);
}

void follow_free(follow_side *s) {
  free(s->pt);
  free(s->at);
  s->pt = NULL, s->at = NULL;
}
