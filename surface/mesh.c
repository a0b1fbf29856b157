/* mesh.c -- triangles from tilings and caps; area and volume. */
#include "surface/mesh.h"

#include <math.h>
#include <stdlib.h>

#include "surface/cap.h"
#include "util/xmem.h"

void mesh_init(mesh *me, const contour_stack *s) {
  me->nv = 0;
  me->base = xmallocarray((size_t)s->n, sizeof *me->base);
  for (int i = 0; i < s->n; i++) me->base[i] = me->nv, me->nv += s->c[i].n;
  me->v = xmallocarray((size_t)me->nv, sizeof *me->v);
  for (int i = 0; i < s->n; i++)
    for (int j = 0; j < s->c[i].n; j++)
      me->v[me->base[i] + j] = (vec3){s->c[i].pt[j].x, s->c[i].pt[j].y, s->c[i].z};
  me->nt = 0;
  me->cap = 0;
  me->t = NULL;
}

void mesh_free(mesh *me) {
  free(me->v);
  free(me->t);
  free(me->base);
  me->v = NULL, me->t = NULL, me->base = NULL;
}

void mesh_add_tri(mesh *me, int a, int b, int c) {
  if (me->nt == me->cap) {
    me->cap = me->cap ? 2 * me->cap : 1024;
    me->t = xreallocarray(me->t, (size_t)me->cap, sizeof *me->t);
  }
  me->t[me->nt][0] = a, me->t[me->nt][1] = b, me->t[me->nt][2] = c;
  me->nt++;
}

static vec3 sub(vec3 a, vec3 b) { return (vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static vec3 crs(vec3 a, vec3 b) {
  return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static double dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* --- scale ------------------------------------------------------------------
 * Areas and volumes are computed on coordinates multiplied by a power of two
 * 2^-e that brings the largest into [1/2, 1), summed at that scale, and
 * scaled back once.  Such scaling is exact and commutes with every rounding,
 * so ordinary meshes get the same bits as without it; contours 1e300 wide
 * get inf (their area is beyond a double) where products overflowed into
 * inf - inf = NaN, and subnormal ones no longer lose every bit. */
static double vmax(vec3 v, double m) { return fmax(m, fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)))); }
static vec3 scl(vec3 v, int e) { return (vec3){geom_ldexp(v.x, -e), geom_ldexp(v.y, -e), geom_ldexp(v.z, -e)}; }

/* Triangle t's area at scale 2^-e. */
static double tri_area_at(const mesh *me, int t, int e) {
  vec3 a = scl(me->v[me->t[t][0]], e), b = scl(me->v[me->t[t][1]], e), c = scl(me->v[me->t[t][2]], e);
  vec3 x = crs(sub(b, a), sub(c, a));
  return 0.5 * sqrt(dot(x, x));
}

double mesh_tri_area(const mesh *me, int t) {
  double m = 0;
  for (int k = 0; k < 3; k++) m = vmax(me->v[me->t[t][k]], m);
  int e = geom_scale_exp(m);
  return ldexp(tri_area_at(me, t, e), 2 * e);
}

/* The triangle's share of the volume about o, all at scale 2^-e (o scaled). */
static double tri_volume_at(const mesh *me, int t, vec3 o, int e) {
  vec3 a = sub(scl(me->v[me->t[t][0]], e), o), b = sub(scl(me->v[me->t[t][1]], e), o);
  vec3 c = sub(scl(me->v[me->t[t][2]], e), o);
  return dot(a, crs(b, c)) / 6;
}

void mesh_add_band(mesh *me, const contour_stack *s, int i, const tiling *t, double *area,
                   double *volume) {
  const contour *P = &s->c[i], *Q = &s->c[i + 1];
  int steps = t->m + t->n, first = me->nt;
  int (*tile)[3] = xmallocarray((size_t)steps, sizeof *tile);
  unsigned char *on = xmalloc((size_t)steps);
  tiling_tiles(t, tile, on);
  for (int k = 0; k < steps; k++) {
    /* The edge x_a x_b lies on one contour, the apex y on the other.  Seen
     * from outside, a counter-clockwise contour's edge with the apex above
     * it runs x_a, x_b, y; with the apex below, the other way. */
    const contour *X = on[k] ? Q : P, *Y = on[k] ? P : Q;
    int bx = me->base[on[k] ? i + 1 : i], by = me->base[on[k] ? i : i + 1];
    int xa = bx + tile[k][0], xb = bx + tile[k][1], y = by + tile[k][2];
    if (Y->z > X->z) mesh_add_tri(me, xa, xb, y);
    else mesh_add_tri(me, xb, xa, y);
  }
  free(tile);
  free(on);

  /* Area, and the volume of the slab: the band plus the two contour planes
   * (a plane at height z, normal +-z, adds +-z A / 3), about a point o on the
   * lower plane so the sum does not cancel. */
  const contour *lo = P->z < Q->z ? P : Q, *hi = P->z < Q->z ? Q : P;
  double m = fmax(fabs(lo->z), fabs(hi->z));
  for (int k = 0; k < lo->n; k++) m = fmax(m, fmax(fabs(lo->pt[k].x), fabs(lo->pt[k].y)));
  for (int k = 0; k < hi->n; k++) m = fmax(m, fmax(fabs(hi->pt[k].x), fabs(hi->pt[k].y)));
  int e = geom_scale_exp(m);
  vec3 o = scl((vec3){lo->pt[0].x, lo->pt[0].y, lo->z}, e);
  double ar = 0, vol = 0;
  for (int k = first; k < me->nt; k++) ar += tri_area_at(me, k, e), vol += tri_volume_at(me, k, o, e);
  vol += (geom_ldexp(hi->z, -e) - geom_ldexp(lo->z, -e)) * 0.5 * geom_area2_at(hi->pt, hi->n, e) / 3;
  *area = ldexp(ar, 2 * e);
  *volume = ldexp(vol, 3 * e);
}

double mesh_add_caps(mesh *me, const contour_stack *s) {
  double ar = 0;
  for (int e = 0; e < 2; e++) {
    int i = e ? s->n - 1 : 0, other = e ? s->n - 2 : 1;
    const contour *c = &s->c[i];
    int (*tri)[3] = xmallocarray((size_t)c->n, sizeof *tri);
    int nt = cap_triangulate(c->pt, c->n, tri);
    /* Counter-clockwise triangles face +z: right for the top, reversed for the bottom. */
    int top = c->z > s->c[other].z, b = me->base[i];
    for (int k = 0; k < nt; k++) {
      if (top) mesh_add_tri(me, b + tri[k][0], b + tri[k][1], b + tri[k][2]);
      else mesh_add_tri(me, b + tri[k][0], b + tri[k][2], b + tri[k][1]);
      ar += mesh_tri_area(me, me->nt - 1);
    }
    free(tri);
  }
  return ar;
}

double mesh_area(const mesh *me) {
  double a = 0;
  for (int k = 0; k < me->nt; k++) a += mesh_tri_area(me, k);
  return a;
}

double mesh_volume(const mesh *me) {
  double m = 0;
  for (int k = 0; k < me->nv; k++) m = vmax(me->v[k], m);
  int e = geom_scale_exp(m);
  vec3 o = {0, 0, 0};
  if (me->nv) {
    for (int k = 0; k < me->nv; k++) {
      vec3 v = scl(me->v[k], e);
      o.x += v.x, o.y += v.y, o.z += v.z;
    }
    o.x /= me->nv, o.y /= me->nv, o.z /= me->nv;
  }
  double v = 0;
  for (int k = 0; k < me->nt; k++) v += tri_volume_at(me, k, o, e);
  return ldexp(v, 3 * e);
}
