/* match.c -- links by depth level, then connected groups (match.h).
 *
 * Level d (0, 1, 2, ...): every pair (a on slice k, b on slice k+1) of depth
 * d whose parents are already in one group (d > 0) is tested for overlap (the
 * open regions under MATCH_OVERLAP, else the closed ones); a link unites
 * their groups.  Then the links of the other rules at that level, each tried
 * on the groups as they stand (union-find, undone when the junction it makes
 * cannot be bridged).  Parents have depth d-1, so their groups are final
 * when level d starts. */
#include "surface/match.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "surface/bridge.h"
#include "surface/gap.h"
#include "surface/overlap.h"
#include "util/xmem.h"

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

typedef struct {
  const slices *sl;
  const match_opts *o;
  int k, f0, f1, f2, n;
  int *up;              /* local index i = contour f0 + i */
  int *save;            /* up before a tentative link */
  int *side[2];         /* scratch: a group's contours on slice k, k+1 */
  int nl, capl;
  match_link *links;
} mctx;

static match_link *new_link(mctx *m, int a, int b, int how) {
  if (m->nl == m->capl) {
    m->capl = m->capl ? 2 * m->capl : 8;
    m->links = xreallocarray(m->links, (size_t)m->capl, sizeof *m->links);
  }
  match_link *l = &m->links[m->nl++];
  memset(l, 0, sizeof *l);
  l->a = a, l->b = b, l->how = how, l->from = -1;
  return l;
}

static int root(mctx *m, int c) { return find(m->up, c - m->f0); }

/* Can bridges join the contours of c's group on each slice? */
static int bridgeable(mctx *m, int c) {
  const slices *sl = m->sl;
  int r = root(m, c), cnt[2] = {0, 0};
  for (int x = m->f0; x < m->f2; x++)
    if (root(m, x) == r) {
      int s = x >= m->f1;
      m->side[s][cnt[s]++] = x;
    }
  double dz = sl->z[m->k + 1] - sl->z[m->k];
  char err[600];
  for (int s = 0; s < 2; s++) {
    if (cnt[s] < 2) continue;
    composite cp;
    if (bridge_join(sl, m->side[s], cnt[s], s ? m->k : m->k + 1, s ? -dz / 2 : dz / 2, "", &cp, err,
                    sizeof err) != 0)
      return 0;
    bridge_free(&cp);
  }
  return 1;
}

/* Link a and b where the junction it makes can be bridged: 1, else 0 (and
 * the groups as they were). */
static int try_link(mctx *m, int a, int b) {
  memcpy(m->save, m->up, (size_t)m->n * sizeof *m->up);
  unite(m->up, a - m->f0, b - m->f0);
  if (bridgeable(m, a)) return 1;
  memcpy(m->up, m->save, (size_t)m->n * sizeof *m->up);
  return 0;
}

/* A candidate for contour s on the other slice: same depth (the caller's),
 * parents in one group. */
typedef struct {
  mctx *m;
  int s;
} cand_q;

static int parent_ok(void *ud, int c) {
  cand_q *q = ud;
  const slice_contour *S = &q->m->sl->c[q->s], *C = &q->m->sl->c[c];
  return S->depth == 0 || root(q->m, S->parent) == root(q->m, C->parent);
}

int match_nearest(const slices *sl, int c, int other, int (*ok)(void *ud, int cand), void *ud,
                  exactdist *gap) {
  const slice_contour *S = &sl->c[c];
  int best = -1;
  for (int x = sl->first[other]; x < sl->first[other + 1]; x++) {
    if (sl->c[x].depth != S->depth || (ok && !ok(ud, x))) continue;
    if (best >= 0 && gap_box_bound(S, &sl->c[x]) > gap->hi) continue;
    exactdist g;
    gap_between(S, &sl->c[x], &g);
    if (best < 0 || exactdist_cmp(&g, gap) < 0) *gap = g, best = x;
  }
  return best;
}

/* has[s][r]: group r has a contour on slice k (s = 0), k+1 (s = 1). */
static void partners(mctx *m, unsigned char *has[2]) {
  memset(has[0], 0, (size_t)m->n);
  memset(has[1], 0, (size_t)m->n);
  for (int x = m->f0; x < m->f2; x++) has[x >= m->f1][root(m, x)] = 1;
}

/* Has contour x no partner on the other slice? */
static int stray(mctx *m, unsigned char *has[2], int x) { return !has[x < m->f1][root(m, x)]; }

static int was_dropped(const mctx *m, int a, int b) {
  for (int i = 0; i < m->nl; i++)
    if (m->links[i].dropped && m->links[i].a == a && m->links[i].b == b) return 1;
  return 0;
}

/* Level d's links beyond the overlaps: touching pairs tp[0..ntp), then the
 * single shortcut, then the nearest. */
static void extra_links(mctx *m, int d, const int (*tp)[2], int ntp, unsigned char *has[2]) {
  const slices *sl = m->sl;
  const match_opts *o = m->o;
  for (int i = 0; i < ntp; i++) {
    int a = tp[i][0], b = tp[i][1];
    if (root(m, a) == root(m, b)) continue;
    match_link *l = new_link(m, a, b, MATCH_LINK_TOUCH);
    l->dropped = !try_link(m, a, b);
  }
  if (d == 0 && (o->rule == MATCH_SINGLE || o->rule == MATCH_NEAREST)) {
    int a = -1, b = -1, na = 0, nb = 0;
    for (int x = m->f0; x < m->f2; x++)
      if (sl->c[x].depth == 0) {
        if (x < m->f1) a = x, na++;
        else b = x, nb++;
      }
    if (na == 1 && nb == 1 && root(m, a) != root(m, b)) {
      match_link *l = new_link(m, a, b, MATCH_LINK_SINGLE);
      unite(m->up, a - m->f0, b - m->f0);   /* 1-1: no bridge */
      if (o->gaps) gap_between(&sl->c[a], &sl->c[b], &l->gap), l->has_gap = 1;
    }
  }
  if (o->rule != MATCH_NEAREST) return;
  /* The strays as the links above left them, each with its nearest. */
  partners(m, has);
  int np = 0;
  struct prop { int s, c; exactdist g; } *pr = xmallocarray((size_t)m->n + 1, sizeof *pr);
  for (int x = m->f0; x < m->f2; x++) {
    if (sl->c[x].depth != d || !stray(m, has, x)) continue;
    cand_q q = {m, x};
    exactdist g;
    int c = match_nearest(sl, x, x < m->f1 ? m->k + 1 : m->k, parent_ok, &q, &g);
    if (c < 0 || (isfinite(o->dist) && exactdist_cmp_len(&g, o->dist) > 0)) continue;
    pr[np].s = x, pr[np].c = c, pr[np++].g = g;
  }
  for (int i = 0; i < np; i++) {
    int a = pr[i].s < pr[i].c ? pr[i].s : pr[i].c, b = pr[i].s ^ pr[i].c ^ a;
    if (root(m, a) == root(m, b) || was_dropped(m, a, b)) continue;
    match_link *l = new_link(m, a, b, MATCH_LINK_NEAREST);
    l->from = pr[i].s, l->gap = pr[i].g, l->has_gap = 1;
    l->dropped = !try_link(m, a, b);
  }
  free(pr);
}

void match_slices(const slices *sl, int k, const match_opts *o, junctions *out) {
  memset(out, 0, sizeof *out);
  int f0 = sl->first[k], f1 = sl->first[k + 1], f2 = sl->first[k + 2];
  int n = f2 - f0, maxd = 0;
  mctx m = {sl, o, k, f0, f1, f2, n, NULL, NULL, {NULL, NULL}, 0, 0, NULL};
  int *up = m.up = xmallocarray((size_t)n, sizeof *up);
  m.save = xmallocarray((size_t)n, sizeof *m.save);
  m.side[0] = xmallocarray((size_t)n, sizeof(int));
  m.side[1] = xmallocarray((size_t)n, sizeof(int));
  unsigned char *has[2] = {xmalloc((size_t)n), xmalloc((size_t)n)};
  for (int i = 0; i < n; i++) {
    up[i] = i;
    if (sl->c[f0 + i].depth > maxd) maxd = sl->c[f0 + i].depth;
  }
  int ntp = 0, captp = 0;
  int (*tp)[2] = NULL;   /* touching pairs of the level */
  for (int d = 0; d <= maxd; d++) {
    ntp = 0;
    for (int a = f0; a < f1; a++) {
      const slice_contour *ca = &sl->c[a];
      if (ca->depth != d) continue;
      for (int b = f1; b < f2; b++) {
        const slice_contour *cb = &sl->c[b];
        if (cb->depth != d || find(up, a - f0) == find(up, b - f0)) continue;
        if (d > 0 && find(up, ca->parent - f0) != find(up, cb->parent - f0)) continue;
        if (o->rule == MATCH_OVERLAP) {
          if (!boxes_meet(ca->ix, cb->ix) || !overlap_regions(ca->ix, cb->ix)) continue;
        } else {
          int r = overlap_closed(ca->ix, cb->ix);
          if (r == OVERLAP_TOUCH) {
            if (ntp == captp) tp = xreallocarray(tp, (size_t)(captp = captp ? 2 * captp : 8), sizeof *tp);
            tp[ntp][0] = a, tp[ntp++][1] = b;
          }
          if (r != OVERLAP_INTERIOR) continue;
        }
        if (o->careful) {
          if (!try_link(&m, a, b)) new_link(&m, a, b, MATCH_LINK_OVERLAP)->dropped = 1;
          continue;
        }
        unite(up, a - f0, b - f0);
      }
    }
    extra_links(&m, d, (const int (*)[2])tp, ntp, has);
  }
  free(tp);
  /* The ends left: no partner, though the other slice has candidates. */
  partners(&m, has);
  for (int x = f0; x < f2; x++) {
    if (!stray(&m, has, x)) continue;
    int other = x < f1 ? k + 1 : k, any = 0;
    cand_q q = {&m, x};
    for (int c = sl->first[other]; c < sl->first[other + 1] && !any; c++)
      any = sl->c[c].depth == sl->c[x].depth && parent_ok(&q, c);
    if (!any) continue;
    out->ends = xreallocarray(out->ends, (size_t)out->nends + 1, sizeof *out->ends);
    match_end *e = &out->ends[out->nends++];
    memset(e, 0, sizeof *e);
    e->c = x;
    e->nearest = o->gaps ? match_nearest(sl, x, other, parent_ok, &q, &e->gap) : -1;
  }
  out->links = m.links, out->nlinks = m.nl;
  free(has[0]), free(has[1]);
  free(m.save), free(m.side[0]), free(m.side[1]);
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
  for (int i = 0; i < out->nlinks; i++) {
    const match_link *l = &out->links[i];
    junction *j = &out->j[slot[find(up, l->a - f0)]];
    if (!l->dropped && l->how != MATCH_LINK_TOUCH && j->nlo == 1 && j->nhi == 1) j->apart = 1;
  }
  free(slot);
  free(up);
}

void match_free(junctions *js) {
  for (int g = 0; g < js->n; g++) free(js->j[g].lo), free(js->j[g].hi);
  free(js->j);
  free(js->links);
  free(js->ends);
  memset(js, 0, sizeof *js);
}
