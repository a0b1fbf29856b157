/* follow.c -- the pair a 1-1 band is tiled on (follow.h).
 *
 *   lo:  0 . 1 . . 2 3        a tile on the pair's edge 1-2 of lo, apex q,
 *        |  fan   |           becomes the fan of lo's edges between them
 *   hi:       q               (all in one plane), apex q */
#include "surface/follow.h"

#include <math.h>
#include <stdlib.h>

#include "geom/geom.h"
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

/* --- the shadow's weight (follow_shadow) -------------------------------- */

typedef struct {
  const follow_side *a, *b;
  const vec2 *lo, *hi;
  int e;            /* the scale: coordinates and heights times 2^-e */
  vec2 o;           /* the origin, lo[0] scaled */
  double h;         /* z1 - z0 scaled */
  double top;       /* the upper region's share: h A_hi / 3, scaled */
  cost_kind kind;
  double z0, z1;
} judge;

static vec2 at(const judge *j, vec2 p) {
  return (vec2){geom_ldexp(p.x, -j->e) - j->o.x, geom_ldexp(p.y, -j->e) - j->o.y};
}

/* det(p - o, q - o, r - o) for points of the two planes, z 0 or h. */
static double det(vec2 p, double pz, vec2 q, double qz, vec2 r, double rz) {
  return p.x * (q.y * rz - qz * r.y) + p.y * (qz * r.x - q.x * rz) + pz * (q.x * r.y - q.y * r.x);
}

/* The signed volume the band of the pair's solution t closes with its two
 * slices' regions, on the contours where they lie (a tile on an edge between
 * corners stands for its fan, of the same volume), oriented as the stack
 * orients its triangles: at the judge's scale. */
static double band_volume(const judge *j, const tiling *t) {
  int steps = j->a->n + j->b->n;
  int (*tile)[3] = xmallocarray((size_t)steps, sizeof *tile);
  unsigned char *on = xmalloc((size_t)steps);
  tiling_tiles(t, tile, on);
  double v = 0;
  for (int k = 0; k < steps; k++) {
    if (!on[k]) {   /* edge on lo, apex on hi */
      vec2 p = at(j, j->lo[j->a->at[tile[k][0]]]), q = at(j, j->lo[j->a->at[tile[k][1]]]);
      vec2 r = at(j, j->hi[j->b->at[tile[k][2]]]);
      v += det(p, 0, q, 0, r, j->h);
    } else {        /* edge on hi, backwards, apex on lo */
      vec2 p = at(j, j->hi[j->b->at[tile[k][1]]]), q = at(j, j->hi[j->b->at[tile[k][0]]]);
      vec2 r = at(j, j->lo[j->a->at[tile[k][2]]]);
      v += det(p, j->h, q, j->h, r, 0);
    }
  }
  free(tile);
  free(on);
  return v / 6 + j->top;
}

/* The band at weight wgt: its solution into *t, its volume returned. */
static double volume_at(const judge *j, double wgt, tiling *t) {
  tiling_solve_shadow(j->a->pt, j->a->n, j->z0, j->b->pt, j->b->n, j->z1, j->kind, wgt, -1, t);
  return band_volume(j, t);
}

double follow_shadow(const follow_side *a, const follow_side *b, const vec2 *lo, const vec2 *hi, double z0,
                     double z1, cost_kind kind, tiling *t) {
  judge j = {a, b, lo, hi, 0, {0, 0}, 0, 0, kind, z0, z1};
  double mx = fmax(fabs(z0), fabs(z1));
  for (int k = 0; k < a->full; k++) mx = fmax(mx, fmax(fabs(lo[k].x), fabs(lo[k].y)));
  for (int k = 0; k < b->full; k++) mx = fmax(mx, fmax(fabs(hi[k].x), fabs(hi[k].y)));
  j.e = geom_scale_exp(mx);
  j.o = (vec2){geom_ldexp(lo[0].x, -j.e), geom_ldexp(lo[0].y, -j.e)};
  j.h = geom_ldexp(z1, -j.e) - geom_ldexp(z0, -j.e);
  double a0 = 0.5 * geom_area2_at(lo, a->full, j.e), a1 = 0.5 * geom_area2_at(hi, b->full, j.e);
  j.top = j.h * a1 / 3;
  double v = volume_at(&j, 0, t);
  if (kind != COST_AREA || !(a0 * a1 > 0) || !(j.h > 0) || !isfinite(v)) return 0;
  /* The frustum's volume over the two areas (signed: holes negative). */
  double target = j.h * (a0 + a1 + copysign(sqrt(a0 * a1), a0)) / 3, tol = FOLLOW_TOLERANCE * fabs(target);
  double best = 0, gap = fabs(v - target);
  if (gap <= tol) return 0;
  /* The volume does not fall as the weight rises, and moves most near 0:
   * weights 1/64, 1/8 and FOLLOW_SHADOW_MAX towards the target until one
   * passes it, then false position with the Illinois rule between the last
   * two (a few solves where the volume moves smoothly with the weight, as
   * between contours of many points; a bisection's pace at worst), keeping
   * the nearest band. */
  static const double probe[] = {0x1p-6, 0x1p-3, FOLLOW_SHADOW_MAX};
  double dir = v < target ? 1 : -1, lo_w = 0, hi_w = 0, f_lo = v - target, f_hi = 0;
  int side = 0, bracketed = 0;
  for (int it = 0; it < FOLLOW_STEPS; it++) {
    double wgt;
    if (!bracketed) {
      if (it == 3) break;   /* even the heaviest weight falls short */
      wgt = dir * probe[it];
    } else {
      wgt = lo_w + (hi_w - lo_w) * (f_lo / (f_lo - f_hi));
      if (!(wgt > fmin(lo_w, hi_w) && wgt < fmax(lo_w, hi_w))) wgt = 0.5 * (lo_w + hi_w);
    }
    tiling u;
    double vw = volume_at(&j, wgt, &u);
    if (fabs(vw - target) < gap) {
      gap = fabs(vw - target), best = wgt;
      tiling_free(t);
      *t = u;
    } else {
      tiling_free(&u);
    }
    if (gap <= tol / 2) break;
    if ((vw - target) * dir < 0) {   /* short of it */
      lo_w = wgt, f_lo = vw - target;
      if (side < 0) f_hi /= 2;
      side = bracketed ? -1 : 0;
    } else {                         /* past it */
      hi_w = wgt, f_hi = vw - target;
      if (side > 0) f_lo /= 2;
      side = bracketed ? 1 : 0;
      bracketed = 1;
    }
    if (bracketed && fabs(hi_w - lo_w) <= 0x1p-14) break;
  }
  return best;
}
