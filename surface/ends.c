/* ends.c -- regions without a band on one side, and their caps. */
#include "surface/ends.h"

#include <stdlib.h>
#include <string.h>

#include "surface/apex.h"
#include "surface/flatcap.h"
#include "util/xmem.h"

enum { NONE, OUTER, HOLE };

/* The roles of slice k's contours on one side (up or down): OUTER of a
 * region, HOLE of its parent's region, or NONE (a band on that side). */
static void roles(const slices *sl, int k, const unsigned char *band, unsigned char *role) {
  int f = sl->first[k], e = sl->first[k + 1], maxd = 0;
  for (int c = f; c < e; c++) {
    role[c] = NONE;
    if (sl->c[c].depth > maxd) maxd = sl->c[c].depth;
  }
  for (int d = 0; d <= maxd; d++)   /* parents before children: by depth */
    for (int c = f; c < e; c++) {
      const slice_contour *C = &sl->c[c];
      int p = C->parent;
      if (C->depth != d) continue;
      if (band[c]) {   /* then so has its parent (match.h) */
        XASSERT(p < 0 || band[p]);
        continue;
      }
      role[c] = p < 0 || band[p] || role[p] == HOLE ? OUTER : HOLE;
    }
}

int ends_plan(const slices *sl, const unsigned char *band_up, const unsigned char *band_down,
              end_region **out) {
  int cap = 16, n = 0;
  end_region *r = xmallocarray((size_t)cap, sizeof *r);
  unsigned char *role[2] = {xcalloc((size_t)sl->ncontours + 1, 1), xcalloc((size_t)sl->ncontours + 1, 1)};
  for (int k = 0; k < sl->nslices; k++) {
    int f = sl->first[k], e = sl->first[k + 1];
    roles(sl, k, band_down, role[0]);
    roles(sl, k, band_up, role[1]);
    for (int up = 0; up < 2; up++)
      for (int c = f; c < e; c++) {
        if (role[up][c] != OUTER) continue;
        if (n == cap) r = xreallocarray(r, (size_t)(cap *= 2), sizeof *r);
        end_region *g = &r[n++];
        g->slice = k, g->up = up, g->outer = c, g->nholes = 0;
        /* Alone on its slice: the same region on both sides (a hole whose
         * other side is part of its parent's cap is not). */
        g->isolated = role[0][c] == OUTER && role[1][c] == OUTER;
        g->holes = NULL;
        for (int h = f; h < e; h++)
          if (role[up][h] == HOLE && sl->c[h].parent == c) {
            g->holes = xreallocarray(g->holes, (size_t)g->nholes + 1, sizeof *g->holes);
            g->holes[g->nholes++] = h;
          }
      }
  }
  free(role[0]);
  free(role[1]);
  *out = r;
  return n;
}

void ends_free(end_region *r, int n) {
  for (int i = 0; i < n; i++) free(r[i].holes);
  free(r);
}

/* Half the gap to the next slice on the cap's side (or on the other side at
 * the end of the stack). */
static double half_gap(const slices *sl, int k, int up) {
  int ns = sl->nslices;
  int j = up ? (k + 1 < ns ? k + 1 : k - 1) : (k > 0 ? k - 1 : k + 1);
  double d = sl->z[j] - sl->z[k];
  return (d < 0 ? -d : d) / 2;
}

static void add(end_cap *c, int a, int b, int d) {
  c->tri[c->ntri][0] = a, c->tri[c->ntri][1] = b, c->tri[c->ntri][2] = d;
  c->ntri++;
}

/* The slab of an isolated region (ends.h): its contours copied h above and
 * below. */
static void slab(const slices *sl, const end_region *r, double h, end_cap *out) {
  int cs[1 + 64], nc = 1 + r->nholes, pts = 0;
  int *list = nc <= 65 ? cs : xmallocarray((size_t)nc, sizeof *list);
  list[0] = r->outer;
  for (int k = 0; k < r->nholes; k++) list[k + 1] = r->holes[k];
  for (int k = 0; k < nc; k++) pts += sl->c[list[k]].n;
  double z = sl->z[r->slice];
  out->nnew = 2 * pts;
  out->at = xmallocarray((size_t)out->nnew, sizeof *out->at);
  int (*flat)[3];
  int nf = flatcap_region(sl, r->outer, r->holes, r->nholes, &flat);
  out->tri = xmallocarray(2 * (size_t)nf + 4 * (size_t)pts, sizeof *out->tri);
  /* New vertex of point j of the region (numbered contour after contour):
   * top copy -1-j, bottom copy -1-(pts+j). */
  int first = 0;
  for (int k = 0; k < nc; k++) {
    const slice_contour *C = &sl->c[list[k]];
    for (int i = 0; i < C->n; i++) {
      out->at[first + i] = (vec3){C->pt[i].x, C->pt[i].y, z + h};
      out->at[pts + first + i] = (vec3){C->pt[i].x, C->pt[i].y, z - h};
      int a = C->base + i, b = C->base + (i + 1) % C->n, j = first + i, jn = first + (i + 1) % C->n;
      int ta = -1 - j, tb = -1 - jn, ba = -1 - (pts + j), bb = -1 - (pts + jn);
      /* Strips, as bands: the lower contour's edges run their way, the
       * upper's backwards. */
      add(out, a, b, tb), add(out, tb, ta, a);     /* contour below its top copy */
      add(out, ba, bb, b), add(out, b, a, ba);     /* bottom copy below the contour */
    }
    first += C->n;
  }
  /* The copies' caps: the region's flat triangulation, on the top copy as
   * a top cap, on the bottom copy turned over. */
  for (int t = 0; t < nf; t++) {
    int v[3];
    for (int e = 0; e < 3; e++) {   /* mesh id -> its place j in the region */
      int id = flat[t][e], j = 0;
      for (int k = 0; k < nc; k++) {
        const slice_contour *C = &sl->c[list[k]];
        if (id >= C->base && id < C->base + C->n) {
          v[e] = j + id - C->base;
          break;
        }
        j += C->n;
      }
    }
    add(out, -1 - v[0], -1 - v[1], -1 - v[2]);
    add(out, -1 - (pts + v[0]), -1 - (pts + v[2]), -1 - (pts + v[1]));
  }
  free(flat);
  if (list != cs) free(list);
}

void ends_cap(const slices *sl, const end_region *r, int apex, double half, end_cap *out) {
  memset(out, 0, sizeof *out);
  const slice_contour *O = &sl->c[r->outer];
  vec2 at;
  if (sl->nslices == 1) {   /* a stack of one slice: a slab 2 half thick */
    if (r->up) slab(sl, r, half, out);
    return;
  }
  if ((apex || r->isolated) && r->nholes == 0 && apex_point(O->pt, O->n, &at)) {
    double h = half_gap(sl, r->slice, r->up);
    out->nnew = 1;
    out->at = xmalloc(sizeof *out->at);
    out->at[0] = (vec3){at.x, at.y, sl->z[r->slice] + (r->up ? h : -h)};
    out->tri = xmallocarray((size_t)O->n, sizeof *out->tri);
    for (int i = 0; i < O->n; i++) {
      int a = O->base + i, b = O->base + (i + 1) % O->n;
      /* On top the contour's edges run their own way (the band below uses
       * them backwards); at the bottom the other way. */
      if (r->up) add(out, a, b, -1);
      else add(out, b, a, -1);
    }
    return;
  }
  if (r->isolated) {   /* the slab, all of it with the top region */
    if (r->up) slab(sl, r, half_gap(sl, r->slice, 1) / 3, out);
    return;
  }
  out->ntri = flatcap_region(sl, r->outer, r->holes, r->nholes, &out->tri);
  if (!r->up)
    for (int k = 0; k < out->ntri; k++) {
      int t = out->tri[k][1];
      out->tri[k][1] = out->tri[k][2];
      out->tri[k][2] = t;
    }
}

void ends_cap_free(end_cap *c) {
  free(c->tri);
  free(c->at);
  memset(c, 0, sizeof *c);
}
