/* flatcap.c -- holes woven into their boundary by cuts, then ear clipping.
 *
 *   boundary ... w  ->  ... w h h+1 ... h-1 h w ...   (h on the hole)
 */
#include "surface/flatcap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "surface/cap.h"
#include "geom/crossing.h"
#include "util/xmem.h"

int flatcap_region(const slices *sl, int outer, const int *holes, int nholes, int (**tri)[3]) {
  const slice_contour *O = &sl->c[outer];
  int total = O->n;
  for (int h = 0; h < nholes; h++) total += sl->c[holes[h]].n + 2;
  vec2 *pt = xmallocarray((size_t)total, sizeof *pt);
  int *id = xmallocarray((size_t)total, sizeof *id);
  int n = O->n;
  for (int i = 0; i < n; i++) pt[i] = O->pt[i], id[i] = O->base + i;
  vec2 (*cuts)[2] = xmallocarray((size_t)nholes + 1, sizeof *cuts);
  vec2 none = {NAN, NAN};
  for (int h = 0; h < nholes; h++) {
    const slice_contour *H = &sl->c[holes[h]];
    /* Woven points that appear once (cut ends appear twice). */
    int *once = xcalloc((size_t)n, sizeof *once);
    for (int p = 0; p < n; p++) {
      once[p] = 1;
      for (int q = 0; q < n; q++)
        if (q != p && id[q] == id[p]) once[p] = 0;
    }
    size_t m = 0;
    /* (squared distance, hole point, woven position) of every pair. */
    geom_pick *cd = xmallocarray((size_t)H->n * (size_t)n, sizeof *cd);
    for (int i = 0; i < H->n; i++)
      for (int p = 0; p < n; p++)
        if (once[p]) {
          double dx = H->pt[i].x - pt[p].x, dy = H->pt[i].y - pt[p].y;
          cd[m++] = (geom_pick){dx * dx + dy * dy, i, p};
        }
    geom_pick_sort(cd, m);
    int found = -1;
    for (size_t k = 0; k < m && found < 0; k++) {
      vec2 a = H->pt[cd[k].a], b = pt[cd[k].b];
      int bad = inside_segment_meets(O->ix, a, b, none, b);
      for (int g = 0; g < nholes && !bad; g++)
        bad = inside_segment_meets(sl->c[holes[g]].ix, a, b, g == h ? a : none, b);
      for (int g = 0; g < h && !bad; g++)
        bad = crossing_segments(a, b, cuts[g][0], cuts[g][1], NULL) != CROSSING_NONE;
      if (!bad) found = (int)k;
    }
    /* Every hole has a legal cut (the region is connected: a nearest pair of
     * a hole and the rest is always visible); none means a broken invariant. */
    XASSERT(found >= 0);
    int hi = cd[found].a, w = cd[found].b;
    cuts[h][0] = H->pt[hi], cuts[h][1] = pt[w];
    free(cd);
    free(once);
    /* Splice: ... w, hole from hi around to hi, w ... */
    int add = H->n + 2;
    memmove(pt + w + 1 + add, pt + w + 1, (size_t)(n - w - 1) * sizeof *pt);
    memmove(id + w + 1 + add, id + w + 1, (size_t)(n - w - 1) * sizeof *id);
    for (int t = 0; t <= H->n; t++) {
      int i = (hi + t) % H->n;
      pt[w + 1 + t] = H->pt[i], id[w + 1 + t] = H->base + i;
    }
    pt[w + add] = pt[w], id[w + add] = id[w];
    n += add;
  }
  free(cuts);
  XASSERT(n == total);
  /* Ear clipping wants counter-clockwise: reverse a clockwise region (odd
   * depth) and its triangles back. */
  int cw = O->area2 < 0;
  if (cw)
    for (int i = 0, j = n - 1; i < j; i++, j--) {
      vec2 t = pt[i];
      pt[i] = pt[j], pt[j] = t;
      int u = id[i];
      id[i] = id[j], id[j] = u;
    }
  int (*loc)[3] = xmallocarray((size_t)n, sizeof *loc);
  int nt = cap_triangulate(pt, n, loc);
  for (int k = 0; k < nt; k++) {
    int a = id[loc[k][0]], b = id[loc[k][1]], c = id[loc[k][2]];
    loc[k][0] = a;
    loc[k][1] = cw ? c : b;
    loc[k][2] = cw ? b : c;
  }
  free(pt);
  free(id);
  *tri = loc;
  return nt;
}
