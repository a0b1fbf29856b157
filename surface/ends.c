/* ends.c -- regions without a band on one side, and their caps. */
#include "ends.h"

#include <stdlib.h>
#include <string.h>

#include "apex.h"
#include "flatcap.h"
#include "xmem.h"

enum { NONE, OUTER, HOLE };

int ends_plan(const slices *sl, const unsigned char *band_up, const unsigned char *band_down,
              end_region **out) {
  int cap = 16, n = 0;
  end_region *r = xmallocarray((size_t)cap, sizeof *r);
  unsigned char *role = xcalloc((size_t)sl->ncontours + 1, 1);
  for (int k = 0; k < sl->nslices; k++)
    for (int up = 0; up < 2; up++) {
      int f = sl->first[k], e = sl->first[k + 1], maxd = 0;
      const unsigned char *band = up ? band_up : band_down;
      for (int c = f; c < e; c++) {
        role[c] = NONE;
        if (sl->c[c].depth > maxd) maxd = sl->c[c].depth;
      }
      /* Parents before children: by depth. */
      for (int d = 0; d <= maxd; d++)
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
      for (int c = f; c < e; c++) {
        if (role[c] != OUTER) continue;
        if (n == cap) r = xreallocarray(r, (size_t)(cap *= 2), sizeof *r);
        end_region *g = &r[n++];
        g->slice = k, g->up = up, g->outer = c, g->nholes = 0;
        g->isolated = !band_up[c] && !band_down[c];
        g->holes = NULL;
        for (int h = f; h < e; h++)
          if (role[h] == HOLE && sl->c[h].parent == c) {
            g->holes = xreallocarray(g->holes, (size_t)g->nholes + 1, sizeof *g->holes);
            g->holes[g->nholes++] = h;
          }
      }
    }
  free(role);
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

void ends_cap(const slices *sl, const end_region *r, int apex, end_cap *out) {
  memset(out, 0, sizeof *out);
  const slice_contour *O = &sl->c[r->outer];
  vec2 at;
  if ((apex || r->isolated) && r->nholes == 0 && apex_point(O->pt, O->n, &at)) {
    double h = half_gap(sl, r->slice, r->up);
    out->apex = 1;
    out->at = (vec3){at.x, at.y, sl->z[r->slice] + (r->up ? h : -h)};
    out->ntri = O->n;
    out->tri = xmallocarray((size_t)O->n, sizeof *out->tri);
    for (int i = 0; i < O->n; i++) {
      int a = O->base + i, b = O->base + (i + 1) % O->n;
      /* On top the contour's edges run their own way (the band below uses
       * them backwards); at the bottom the other way. */
      out->tri[i][0] = r->up ? a : b;
      out->tri[i][1] = r->up ? b : a;
      out->tri[i][2] = -1;
    }
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
  memset(c, 0, sizeof *c);
}
