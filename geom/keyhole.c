/* keyhole.c -- the exact keyhole repair (keyhole.h; after SlicerRT's
 * FixKeyholes without its tolerance). */
#include "geom/keyhole.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/crossing.h"
#include "geom/exact.h"
#include "util/xmem.h"

/* A polygon whose points each remember an input point (src). */
typedef struct {
  int n;
  vec2 *pt;
  int *src;
} poly;

/* ---------------------------------------------------- step 1: insertion -- */

typedef struct {
  int edge;      /* the edge that gets the point */
  vec2 q;
  int src;
  int dir;       /* exact_lex of the edge's ends: the order along it */
} insertion;


static int by_edge_then_along(const void *a, const void *b) {
  const insertion *p = a, *q = b;
  if (p->edge != q->edge) return p->edge - q->edge;
  return -p->dir * exact_lex(p->q, q->q);   /* from the edge's start (dir: exact_lex(start, end)) */
}

/* q, collinear with a and b, lies strictly between them. */
static int strictly_inside(vec2 a, vec2 b, vec2 q) {
  int s = exact_lex(a, b);
  return exact_lex(a, q) == s && exact_lex(q, b) == s;
}

static void push_ins(insertion **v, int *nv, int *cap, insertion x) {
  if (*nv == *cap) {
    *cap = *cap ? 2 * *cap : 16;
    *v = xreallocarray(*v, (size_t)*cap, sizeof **v);
  }
  (*v)[(*nv)++] = x;
}

/* Collinear ab and cd, in the same direction, share more than a point. */
static int same_way_overlap(vec2 a, vec2 b, vec2 c, vec2 d) {
  if (exact_lex(a, b) > 0) {
    vec2 t = a;
    a = b, b = t, t = c, c = d, d = t;
  }
  vec2 lo = exact_lex(a, c) >= 0 ? a : c, hi = exact_lex(b, d) <= 0 ? b : d;
  return exact_lex(lo, hi) < 0;
}

/* One round: every point that an opposite, collinear, overlapping edge has
 * strictly inside another.  Returns the number inserted (0: stable), or -1
 * when two collinear edges overlap in the same direction: a stretch walked
 * twice one way, which no split can make a keyhole (its two walks end in one
 * loop, two loops kept, a loop and a channel, or two channels, and steps 3-4
 * refuse each), and which could make the rounds insert O(N^2) points (N
 * nested edges walked to and fro on one line).  Without such a pair, each
 * end of an edge lies strictly inside at most one edge of the other
 * direction on its line, so a round inserts at most 2N points. */
static int insert_round(poly *P) {
  int n = P->n;
  geom_span *sx = xmallocarray((size_t)n, sizeof *sx);
  for (int i = 0; i < n; i++) {
    vec2 a = P->pt[i], b = P->pt[(i + 1) % n];
    sx[i] = (geom_span){fmin(a.x, b.x), fmax(a.x, b.x), i};
  }
  geom_span_sort(sx, n);
  insertion *ins = NULL;
  int nins = 0, cap = 0;
  for (int u = 0; u < n; u++) {
    int i = sx[u].i;
    vec2 a = P->pt[i], b = P->pt[(i + 1) % n];
    double ylo = fmin(a.y, b.y), yhi = fmax(a.y, b.y);
    for (int w = u + 1; w < n && sx[w].lo <= sx[u].hi; w++) {
      int j = sx[w].i;
      vec2 c = P->pt[j], d = P->pt[(j + 1) % n];
      if (fmax(c.y, d.y) < ylo || fmin(c.y, d.y) > yhi) continue;
      if (exact_orient(a, b, c) != 0 || exact_orient(a, b, d) != 0) continue;
      int si = exact_lex(a, b), sj = exact_lex(c, d);
      if (si == sj) {   /* the same direction: not a channel */
        if (!same_way_overlap(a, b, c, d)) continue;
        free(sx), free(ins);
        return -1;
      }
      const vec2 *e1[2] = {&c, &d}, *e2[2] = {&a, &b};
      int s1[2] = {P->src[j], P->src[(j + 1) % n]}, s2[2] = {P->src[i], P->src[(i + 1) % n]};
      for (int k = 0; k < 2; k++) {
        if (strictly_inside(a, b, *e1[k])) push_ins(&ins, &nins, &cap, (insertion){i, *e1[k], s1[k], si});
        if (strictly_inside(c, d, *e2[k])) push_ins(&ins, &nins, &cap, (insertion){j, *e2[k], s2[k], sj});
      }
      if (nins > 2 * n) {   /* only with a pair the same way, still to come (above) */
        free(sx), free(ins);
        return -1;
      }
    }
  }
  free(sx);
  if (nins == 0) return 0;
  qsort(ins, (size_t)nins, sizeof *ins, by_edge_then_along);
  vec2 *pt = xmallocarray((size_t)(n + nins), sizeof *pt);
  int *src = xmallocarray((size_t)(n + nins), sizeof *src);
  int m = 0, added = 0;
  for (int i = 0, k = 0; i < n; i++) {
    pt[m] = P->pt[i], src[m++] = P->src[i];
    for (; k < nins && ins[k].edge == i; k++)
      if (exact_lex(pt[m - 1], ins[k].q) != 0) pt[m] = ins[k].q, src[m++] = ins[k].src, added++;
  }
  free(ins);
  free(P->pt), free(P->src);
  P->pt = pt, P->src = src, P->n = m;
  return added;
}

/* ------------------------------------------------------- step 2: split -- */

typedef struct {
  vec2 p;
  int i;
} indexed;

static int by_point(const void *a, const void *b) {
  const indexed *u = a, *v = b;
  int c = exact_lex(u->p, v->p);
  return c ? c : u->i - v->i;
}

/* Group points by exact coordinates: gid[i] in 0 .. ngroups-1. */
static int group_points(const vec2 *p, int n, int *gid) {
  indexed *o = xmallocarray((size_t)n, sizeof *o);
  int g = -1;
  for (int i = 0; i < n; i++) o[i] = (indexed){p[i], i};
  qsort(o, (size_t)n, sizeof *o, by_point);
  for (int k = 0; k < n; k++) {
    if (k == 0 || exact_lex(o[k].p, o[k - 1].p) != 0) g++;
    gid[o[k].i] = g;
  }
  free(o);
  return g + 1;
}

static int find_root(int *up, int x) {
  while (up[x] != x) x = up[x] = up[up[x]];
  return x;
}

/* No two channel pieces (the flat loops, two points each) share a point
 * but a common end: pairs whose boxes overlap, by a sweep in x. */
static int channels_apart(const poly *P, const int *loopidx, const int *lstart, const char *flat, int nl) {
  geom_span *sx = xmallocarray((size_t)nl + 1, sizeof *sx);
  int np = 0, ok = 1;
  for (int l = 0; l < nl; l++)
    if (flat[l]) {
      vec2 a = P->pt[loopidx[lstart[l]]], b = P->pt[loopidx[lstart[l] + 1]];
      sx[np++] = (geom_span){fmin(a.x, b.x), fmax(a.x, b.x), l};
    }
  geom_span_sort(sx, np);
  for (int u = 0; u < np && ok; u++) {
    vec2 a = P->pt[loopidx[lstart[sx[u].i]]], b = P->pt[loopidx[lstart[sx[u].i] + 1]];
    for (int w = u + 1; w < np && ok && sx[w].lo <= sx[u].hi; w++) {
      vec2 c = P->pt[loopidx[lstart[sx[w].i]]], d = P->pt[loopidx[lstart[sx[w].i] + 1]], at;
      crossing_kind k = crossing_segments(a, b, c, d, &at);
      if (k == CROSSING_NONE) continue;
      int end_a = exact_lex(at, a) == 0 || exact_lex(at, b) == 0, end_c = exact_lex(at, c) == 0 || exact_lex(at, d) == 0;
      if (k != CROSSING_TOUCH || !end_a || !end_c) ok = 0;
    }
  }
  free(sx);
  return ok;
}

/* The first of s[0..n-1] (sorted by lo) with lo >= x (strict: lo > x). */
static int first_from(const geom_span *s, int n, double x, int strict) {
  int a = 0, b = n;
  while (a < b) {
    int m = a + (b - a) / 2;
    if (s[m].lo < x || (strict && s[m].lo == x)) a = m + 1;
    else b = m;
  }
  return a;
}

/* No channel piece meets an edge of the loops kept but at one of its ends
 * that lies on a loop (crossing_segment's rule, allow as there).  Each pair
 * whose x ranges overlap is tested once, found from the side whose lo comes
 * first by a binary search in the other's list: O(N log N + such pairs),
 * where a crossing_segment per piece took O(pieces x N). */
static int channels_off_loops(const poly *P, const int *loopidx, const int *lstart, const char *flat, int nl,
                              const int *onloop, const int *gid, const crossing_poly *cp, int kept) {
  int ne = 0, nc = 0, ok = 1;
  for (int k = 0; k < kept; k++) ne += cp[k].n;
  geom_span *es = xmallocarray((size_t)ne + 1, sizeof *es), *cs = xmallocarray((size_t)nl + 1, sizeof *cs);
  vec2 *ea = xmallocarray((size_t)ne + 1, sizeof *ea), *eb = xmallocarray((size_t)ne + 1, sizeof *eb);
  ne = 0;
  for (int k = 0; k < kept; k++)
    for (int j = 0; j < cp[k].n; j++, ne++) {
      ea[ne] = cp[k].pt[j], eb[ne] = cp[k].pt[(j + 1) % cp[k].n];
      es[ne] = (geom_span){fmin(ea[ne].x, eb[ne].x), fmax(ea[ne].x, eb[ne].x), ne};
    }
  for (int l = 0; l < nl; l++)
    if (flat[l]) {
      vec2 a = P->pt[loopidx[lstart[l]]], b = P->pt[loopidx[lstart[l] + 1]];
      cs[nc++] = (geom_span){fmin(a.x, b.x), fmax(a.x, b.x), l};
    }
  geom_span_sort(es, ne);
  geom_span_sort(cs, nc);
  for (int side = 0; side < 2 && ok; side++) {
    /* side 0: each piece, the edges with lo in [its lo, its hi]; side 1:
     * each edge, the pieces with lo in (its lo, its hi]. */
    const geom_span *from = side ? es : cs, *to = side ? cs : es;
    int nfrom = side ? ne : nc, nto = side ? nc : ne;
    for (int u = 0; u < nfrom && ok; u++)
      for (int w = first_from(to, nto, from[u].lo, side); w < nto && ok && to[w].lo <= from[u].hi; w++) {
        int l = side ? to[w].i : from[u].i, e = side ? from[u].i : to[w].i;
        int ia = loopidx[lstart[l]], ib = loopidx[lstart[l] + 1];
        vec2 a = P->pt[ia], b = P->pt[ib], at;
        crossing_kind k = crossing_segments(a, b, ea[e], eb[e], &at);
        if (k == CROSSING_NONE) continue;
        if (k == CROSSING_TOUCH && ((onloop[gid[ia]] && exact_lex(at, a) == 0) || (onloop[gid[ib]] && exact_lex(at, b) == 0)))
          continue;
        ok = 0;
      }
  }
  free(es), free(cs), free(ea), free(eb);
  return ok;
}

int keyhole_repair(const vec2 *p, int n, keyhole_split *out) {
  memset(out, 0, sizeof *out);
  poly P = {n, xmallocarray((size_t)n, sizeof(vec2)), xmallocarray((size_t)n, sizeof(int))};
  memcpy(P.pt, p, (size_t)n * sizeof *p);
  /* src: the first input point with those coordinates. */
  int *g0 = xmallocarray((size_t)n, sizeof *g0);
  int ng0 = group_points(p, n, g0), *firstof = xmallocarray((size_t)ng0, sizeof *firstof);
  for (int g = 0; g < ng0; g++) firstof[g] = n;
  for (int i = 0; i < n; i++)
    if (i < firstof[g0[i]]) firstof[g0[i]] = i;
  for (int i = 0; i < n; i++) P.src[i] = firstof[g0[i]];
  free(g0), free(firstof);

  /* Step 1: each round adds points already there, so it ends (at most one
   * of each point per edge). */
  int added;
  while ((added = insert_round(&P)) > 0) {}
  if (added < 0) {
    free(P.pt), free(P.src);
    return 0;
  }

  /* Step 2: the stack walk.  loopidx holds the loops' points (indices into
   * P), loop k at loopidx[lstart[k] .. lstart[k+1]-1], from its point of return. */
  int N = P.n, *gid = xmallocarray((size_t)N, sizeof *gid);
  int ng = group_points(P.pt, N, gid);
  int *onstack = xmallocarray((size_t)ng, sizeof *onstack), *stk = xmallocarray((size_t)N, sizeof *stk);
  int *loopidx = xmallocarray(2 * (size_t)N + 1, sizeof *loopidx), *lstart = xmallocarray((size_t)N + 2, sizeof *lstart);
  int top = 0, nl = 0, used = 0;
  for (int g = 0; g < ng; g++) onstack[g] = -1;
  lstart[0] = 0;
  for (int i = 0; i < N; i++) {
    int g = gid[i];
    if (onstack[g] >= 0) {
      int pos = onstack[g];
      for (int k = pos; k < top; k++) loopidx[used++] = stk[k];
      lstart[++nl] = used;
      for (int k = pos + 1; k < top; k++) onstack[gid[stk[k]]] = -1;
      top = pos + 1;
    } else {
      onstack[g] = top;
      stk[top++] = i;
    }
  }
  for (int k = 0; k < top; k++) loopidx[used++] = stk[k];
  lstart[++nl] = used;
  free(onstack), free(stk);

  /* Step 3: channels (all points collinear) and the loops kept. */
  char *flat = xcalloc((size_t)nl + 1, 1);
  int kept = 0, ok = 1;
  for (int l = 0; l < nl; l++) {
    const int *v = loopidx + lstart[l];
    int m = lstart[l + 1] - lstart[l];
    flat[l] = 1;
    for (int k = 2; k < m && flat[l]; k++)
      if (exact_orient(P.pt[v[0]], P.pt[v[1]], P.pt[v[k]]) != 0) flat[l] = 0;
    if (m < 2 || (flat[l] && m != 2)) ok = 0;   /* step 1 leaves no collinear loop of 3 points */
    kept += !flat[l];
  }
  if (kept < 1 || kept == nl) ok = 0;   /* nothing of zero width to drop */
  int *onloop = xcalloc((size_t)ng + 1, sizeof *onloop);   /* a point of a loop kept */
  for (int l = 0; l < nl; l++)
    if (!flat[l])
      for (int j = lstart[l]; j < lstart[l + 1]; j++) onloop[gid[loopidx[j]]] = 1;
  int *up = xmallocarray((size_t)nl + 1, sizeof *up), *piece_at = xmallocarray((size_t)ng + 1, sizeof *piece_at);
  double *plen = xcalloc((size_t)nl + 1, sizeof *plen);
  for (int l = 0; l < nl; l++) up[l] = l;
  for (int g = 0; g < ng; g++) piece_at[g] = -1;
  for (int l = 0; l < nl && ok; l++) {
    if (!flat[l]) continue;
    const int *v = loopidx + lstart[l];
    int m = lstart[l + 1] - lstart[l];
    /* Its length: the collinear loop's extent (walked out and back). */
    int lo = 0, hi = 0;
    for (int k = 1; k < m; k++) {
      if (exact_lex(P.pt[v[k]], P.pt[v[lo]]) < 0) lo = k;
      if (exact_lex(P.pt[v[k]], P.pt[v[hi]]) > 0) hi = k;
    }
    plen[l] = hypot(P.pt[v[hi]].x - P.pt[v[lo]].x, P.pt[v[hi]].y - P.pt[v[lo]].y);
    /* One piece of zero width: pieces that meet off the loops (pieces that
     * meet at a loop's point are two).  up[] joins pieces (by loop index)
     * through the first piece seen at each point off the loops. */
    for (int k = 0; k < 2; k++) {
      int g = gid[v[k]];
      if (onloop[g]) continue;
      if (piece_at[g] < 0) piece_at[g] = l;
      else up[find_root(up, l)] = find_root(up, piece_at[g]);
    }
  }
  /* Each connected piece is a channel when it meets the loops at two or
   * more points, a spur when it hangs off one (walked out and back from
   * there): both enclose no area and are dropped alike.  touch[r]: the
   * first loop point piece r meets (-1 none), -2 when it meets two. */
  int *touch = xmallocarray((size_t)nl + 1, sizeof *touch), first_channel = -1, first_spur = -1;
  for (int l = 0; l < nl; l++) touch[l] = -1;
  for (int l = 0; l < nl && ok; l++) {
    if (!flat[l]) continue;
    const int *v = loopidx + lstart[l];
    int r = find_root(up, l);
    for (int k = 0; k < 2; k++) {
      int g = gid[v[k]];
      if (!onloop[g] || touch[r] == -2) continue;
      if (touch[r] == -1) touch[r] = g;
      else if (touch[r] != g) touch[r] = -2;
    }
  }

  /* Step 4: the loops kept, simple, apart. */
  if (ok) {
    out->first = xmallocarray((size_t)kept + 1, sizeof *out->first);
    out->pt = xmallocarray((size_t)used, sizeof *out->pt);
    out->src = xmallocarray((size_t)used, sizeof *out->src);
    crossing_poly *cp = xmallocarray((size_t)kept, sizeof *cp);
    int m = 0, k = 0;
    for (int l = 0; l < nl; l++) {
      if (flat[l]) continue;
      out->first[k] = m;
      for (int j = lstart[l]; j < lstart[l + 1]; j++) out->pt[m] = P.pt[loopidx[j]], out->src[m++] = P.src[loopidx[j]];
      cp[k] = (crossing_poly){out->pt + out->first[k], m - out->first[k]};
      k++;
    }
    out->first[kept] = m;
    out->nloops = kept;
    crossing_hit h;
    if (crossing_find(cp, kept, &h)) ok = 0;
    /* The channels may meet the loops only where they leave them, and each
     * other only at a common end. */
    if (ok && !channels_off_loops(&P, loopidx, lstart, flat, nl, onloop, gid, cp, kept)) ok = 0;
    free(cp);
    if (ok && !channels_apart(&P, loopidx, lstart, flat, nl)) ok = 0;
  }
  if (ok) {
    for (int l = 0; l < nl; l++) {
      if (!flat[l]) continue;
      int r = find_root(up, l), channel = touch[r] == -2;
      const int *v = loopidx + lstart[l];
      int meets = onloop[gid[v[0]]] || onloop[gid[v[1]]];
      if (channel) {
        out->channels += r == l;
        out->length += plen[l];
        if (first_channel < 0 && meets) first_channel = l;
      } else {
        out->spurs += r == l;
        out->spur_length += plen[l];
        if (first_spur < 0 && meets) first_spur = l;
      }
    }
    for (int w = 0; w < 2; w++) {
      int f = w ? first_spur : first_channel;
      if (f < 0) continue;
      int a = loopidx[lstart[f]], b = loopidx[lstart[f] + 1];
      *(w ? &out->spur_at : &out->at) = P.pt[onloop[gid[a]] ? a : b];
    }
  } else {
    keyhole_free(out);
  }
  free(flat), free(up), free(piece_at), free(plen), free(touch), free(onloop), free(gid), free(loopidx), free(lstart);
  free(P.pt), free(P.src);
  return ok;
}

void keyhole_free(keyhole_split *k) {
  free(k->first);
  free(k->pt);
  free(k->src);
  memset(k, 0, sizeof *k);
}
