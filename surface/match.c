/* match.c -- links by depth level, then connected groups.
 *
 * Level d (0, 1, 2, ...): every pair (a on slice k, b on slice k+1) of depth
 * d whose parents are already in one group (d > 0) and whose boxes meet is
 * tested for overlap; a link unites their groups.  Parents have depth d-1,
 * so their groups are final when level d starts. */
#include "match.h"

#include <stdlib.h>
#include <string.h>

#include "overlap.h"
#include "xmem.h"

static int find(int *up, int x) {
  while (up[x] != x) x = up[x] = up[up[x]];
  return x;
}

static void unite(int *up, int a, int b) {
  a = find(up, a), b = find(up, b);
  if (a < b) up[b] = a;
  else if (b < a) up[a] = b;
}

static int boxes_meet(const inside_index *a, const inside_index *b) {
  vec2 alo, ahi, blo, bhi;
  inside_box(a, &alo, &ahi);
  inside_box(b, &blo, &bhi);
  return alo.x < bhi.x && blo.x < ahi.x && alo.y < bhi.y && blo.y < ahi.y;
}

void match_slices(const slices *sl, int k, junctions *out) {
  int f0 = sl->first[k], f1 = sl->first[k + 1], f2 = sl->first[k + 2];
  int n = f2 - f0, maxd = 0;
  int *up = xmallocarray((size_t)n, sizeof *up);   /* local index i = contour f0 + i */
  for (int i = 0; i < n; i++) {
    up[i] = i;
    if (sl->c[f0 + i].depth > maxd) maxd = sl->c[f0 + i].depth;
  }
  for (int d = 0; d <= maxd; d++)
    for (int a = f0; a < f1; a++) {
      const slice_contour *ca = &sl->c[a];
      if (ca->depth != d) continue;
      for (int b = f1; b < f2; b++) {
        const slice_contour *cb = &sl->c[b];
        if (cb->depth != d || find(up, a - f0) == find(up, b - f0)) continue;
        if (d > 0 && find(up, ca->parent - f0) != find(up, cb->parent - f0)) continue;
        if (!boxes_meet(ca->ix, cb->ix) || !overlap_regions(ca->ix, cb->ix)) continue;
        unite(up, a - f0, b - f0);
      }
    }
  /* Groups in order of their least member (the root, by unite's rule). */
  int *slot = xmallocarray((size_t)n, sizeof *slot);
  out->n = 0;
  for (int i = 0; i < n; i++) slot[i] = find(up, i) == i ? out->n++ : -1;
  out->j = xcalloc((size_t)out->n + 1, sizeof *out->j);
  for (int i = 0; i < n; i++) {
    junction *j = &out->j[slot[find(up, i)]];
    if (i < f1 - f0) j->nlo++;
    else j->nhi++;
    j->depth = sl->c[f0 + i].depth;
  }
  for (int g = 0; g < out->n; g++) {
    out->j[g].lo = xmallocarray((size_t)out->j[g].nlo + 1, sizeof(int));
    out->j[g].hi = xmallocarray((size_t)out->j[g].nhi + 1, sizeof(int));
    out->j[g].nlo = out->j[g].nhi = 0;
  }
  for (int i = 0; i < n; i++) {
    junction *j = &out->j[slot[find(up, i)]];
    if (i < f1 - f0) j->lo[j->nlo++] = f0 + i;
    else j->hi[j->nhi++] = f0 + i;
  }
  free(slot);
  free(up);
}

void match_free(junctions *js) {
  for (int g = 0; g < js->n; g++) free(js->j[g].lo), free(js->j[g].hi);
  free(js->j);
  js->j = NULL;
  js->n = 0;
}
