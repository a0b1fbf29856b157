/* polyunion.c -- the exact union of overlapping simple polygons (polyunion.h).
 *
 *   1. contacts: every pair of segments of two polygons whose boxes overlap
 *      (a sweep in x), classified exactly (crossing_segments); a crossing
 *      is a new point, a touch or an overlap puts the input vertex that lies
 *      inside the other segment on it; polygons in contact are grouped
 *      (union-find);
 *   2. per group of two or more, the arrangement: its points (input vertices
 *      and crossings) sorted lexicographically, exactly, equal ones one
 *      node; each segment cut at the nodes on it into edges; edges that
 *      several polygons share merged, with how many run each way;
 *   3. the faces: around each node the edges in counter-clockwise order
 *      (exact), the next edge of a face the one clockwise from the edge's
 *      reverse at its head; the unbounded face at the least node;
 *   4. winding numbers from the unbounded face (0) across each edge (the
 *      polygons running along it one way less those running the other);
 *   5. the boundary: the edges with a covered face (>= 1) on the left and an
 *      uncovered one (0) on the right; linked head to tail into loops, each
 *      node on one loop once (else the union pinches there);
 *   6. the new vertices rounded to doubles, the loops checked (crossing.h).
 * The geometry of steps 2-3 is exact: coordinates are integers at the
 * group's least significant bit (bigz.h), a crossing the rational point
 * (Ax d + dx t, Ay d + dy t) / d of d = (B - A) x (D - C), t = (C - A) x (D - C);
 * every comparison first compares the correctly rounded doubles (rounding to
 * nearest is monotone, so different rounded values decide) and goes to big
 * integers only when they are equal. */
#include "geom/polyunion.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geom/bigz.h"
#include "geom/exact.h"
#include "util/xmem.h"

typedef struct {
  vec2 a, b;   /* directed so that every polygon runs counter-clockwise */
  int poly;
} seg;

/* A point: an input vertex (s1 < 0) or the crossing of segments s1 < s2. */
typedef struct {
  vec2 r;      /* its coordinates, rounded (exact for a vertex) */
  int s1, s2;
  int node;
} upt;

typedef struct {
  int seg, pt;   /* a point (index into pts) on a segment */
} onseg;

typedef struct {
  const seg *s;
  upt *pts;
  int npts, cappts;
  int e;         /* the integer scale: every coordinate is an integer times 2^e */
} ctx;

/* ---------------------------------------------------------------- exact */

/* The crossing of segments s1, s2 as (nx / d, ny / d) 2^e, d > 0. */
static void crossing_exact(const ctx *c, int s1, int s2, bigz *nx, bigz *ny, bigz *d) {
  static _Thread_local bigz ax, ay, bx, by, cx, cy, dx, dy, t1, t2, tt;
  const seg *p = &c->s[s1], *q = &c->s[s2];
  bigz_from_double(&ax, p->a.x, c->e), bigz_from_double(&ay, p->a.y, c->e);
  bigz_from_double(&bx, p->b.x, c->e), bigz_from_double(&by, p->b.y, c->e);
  bigz_from_double(&cx, q->a.x, c->e), bigz_from_double(&cy, q->a.y, c->e);
  bigz_from_double(&dx, q->b.x, c->e), bigz_from_double(&dy, q->b.y, c->e);
  bigz_sub(&bx, &bx, &ax), bigz_sub(&by, &by, &ay);   /* B - A */
  bigz_sub(&dx, &dx, &cx), bigz_sub(&dy, &dy, &cy);   /* D - C */
  bigz_sub(&cx, &cx, &ax), bigz_sub(&cy, &cy, &ay);   /* C - A */
  bigz_mul(&t1, &bx, &dy), bigz_mul(&t2, &by, &dx), bigz_sub(d, &t1, &t2);
  bigz_mul(&t1, &cx, &dy), bigz_mul(&t2, &cy, &dx), bigz_sub(&tt, &t1, &t2);   /* t */
  bigz_mul(&t1, &ax, d), bigz_mul(&t2, &bx, &tt), bigz_add(nx, &t1, &t2);
  bigz_mul(&t1, &ay, d), bigz_mul(&t2, &by, &tt), bigz_add(ny, &t1, &t2);
  if (bigz_sign(d) < 0) bigz_neg(d), bigz_neg(nx), bigz_neg(ny);
  XASSERT(bigz_sign(d) > 0);
}

/* Coordinate k of point p, exactly, as num / den 2^e. */
static void coord_exact(const ctx *c, const upt *p, int k, bigz *num, bigz *den) {
  if (p->s1 < 0) {
    bigz_from_double(num, k ? p->r.y : p->r.x, c->e);
    bigz_set_int(den, 1);
    return;
  }
  static _Thread_local bigz other;
  if (k) crossing_exact(c, p->s1, p->s2, &other, num, den);
  else crossing_exact(c, p->s1, p->s2, num, &other, den);
}

static int cmp_coord(const ctx *c, const upt *p, const upt *q, int k) {
  double a = k ? p->r.y : p->r.x, b = k ? q->r.y : q->r.x;
  if (a != b) return a < b ? -1 : 1;   /* rounding is monotone: this decides */
  if (p->s1 < 0 && q->s1 < 0) return 0;
  static _Thread_local bigz n1, d1, n2, d2, l, r;
  coord_exact(c, p, k, &n1, &d1);
  coord_exact(c, q, k, &n2, &d2);
  bigz_mul(&l, &n1, &d2), bigz_mul(&r, &n2, &d1);
  return bigz_cmp(&l, &r);
}

static int cmp_lex(const ctx *c, const upt *p, const upt *q) {
  int k = cmp_coord(c, p, q, 0);
  return k ? k : cmp_coord(c, p, q, 1);
}

/* The sign of (b1 - a1) x (b2 - a2), exactly: through exact_orient when the
 * differences are doubles, else in big integers. */
/* hi - lo is the double d exactly (Knuth's TwoDiff: its error term is 0). */
static int exact_diff(double hi, double lo, double d) {
  if (!isfinite(d)) return 0;
  double bv = hi - d, av = d + bv;
  return (bv - lo) + (hi - av) == 0 && (bv - lo) == 0 && (hi - av) == 0;
}

static int cross_sign(const ctx *c, const seg *p, const seg *q) {
  double d[4] = {p->b.x - p->a.x, p->b.y - p->a.y, q->b.x - q->a.x, q->b.y - q->a.y};
  const double hi[4] = {p->b.x, p->b.y, q->b.x, q->b.y}, lo[4] = {p->a.x, p->a.y, q->a.x, q->a.y};
  int exact = 1;
  for (int i = 0; i < 4; i++) exact &= exact_diff(hi[i], lo[i], d[i]);
  if (exact) return exact_orient((vec2){0, 0}, (vec2){d[0], d[1]}, (vec2){d[2], d[3]});
  static _Thread_local bigz v[8], t1, t2;
  for (int i = 0; i < 4; i++) {
    bigz_from_double(&v[2 * i], hi[i], c->e), bigz_from_double(&v[2 * i + 1], lo[i], c->e);
    bigz_sub(&v[2 * i], &v[2 * i], &v[2 * i + 1]);
  }
  bigz_mul(&t1, &v[0], &v[6]), bigz_mul(&t2, &v[2], &v[4]);
  return bigz_cmp(&t1, &t2);
}

/* ---------------------------------------------------------------- helpers */

static int find_root(int *up, int x) {
  while (up[x] != x) x = up[x] = up[up[x]];
  return x;
}

static int add_pt(ctx *c, vec2 r, int s1, int s2) {
  if (c->npts == c->cappts) {
    c->cappts = c->cappts ? 2 * c->cappts : 64;
    c->pts = xreallocarray(c->pts, (size_t)c->cappts, sizeof *c->pts);
  }
  c->pts[c->npts] = (upt){r, s1, s2, -1};
  return c->npts++;
}

typedef struct {
  onseg *v;
  int n, cap;
} onlist;

static void push_on(onlist *l, int s, int p) {
  if (l->n == l->cap) {
    l->cap = l->cap ? 2 * l->cap : 64;
    l->v = xreallocarray(l->v, (size_t)l->cap, sizeof *l->v);
  }
  l->v[l->n++] = (onseg){s, p};
}

/* q lies strictly inside the segment ab (q collinear with it). */
static int strictly_inside(vec2 a, vec2 b, vec2 q) {
  int s = exact_lex(a, b);
  return exact_lex(a, q) == s && exact_lex(q, b) == s;
}


/* The exponent e of the least significant bit over all coordinates. */
static int least_exp(const crossing_poly *p, int np) {
  int e = INT32_MAX;
  for (int k = 0; k < np; k++)
    for (int j = 0; j < p[k].n; j++) {
      int a = bigz_lsb_exp(p[k].pt[j].x), b = bigz_lsb_exp(p[k].pt[j].y);
      if (a < e) e = a;
      if (b < e) e = b;
    }
  return e == INT32_MAX ? 0 : e;
}

/* ---------------------------------------------------------------- one group */

static _Thread_local const ctx *sort_ctx;   /* for qsort */

static int by_point(const void *a, const void *b) {
  const upt *p = &sort_ctx->pts[*(const int *)a], *q = &sort_ctx->pts[*(const int *)b];
  int k = cmp_lex(sort_ctx, p, q);
  if (k) return k;
  if ((p->s1 < 0) != (q->s1 < 0)) return p->s1 < 0 ? -1 : 1;   /* a vertex first */
  if (p->s1 != q->s1) return p->s1 < q->s1 ? -1 : 1;
  return p->s2 - q->s2;
}

typedef struct {
  int lo, hi;       /* nodes, lo < hi */
  int fwd, bwd;     /* polygons running lo -> hi, hi -> lo */
  int seg, sign;    /* a segment along it, +1 when it runs lo -> hi */
  int poly;         /* the least polygon along it */
} edge;

typedef struct {
  int u, v, seg, poly;
} piece;

static int by_piece(const void *a, const void *b) {
  const piece *p = a, *q = b;
  int pl = p->u < p->v ? p->u : p->v, ql = q->u < q->v ? q->u : q->v;
  int ph = p->u < p->v ? p->v : p->u, qh = q->u < q->v ? q->v : q->u;
  if (pl != ql) return pl - ql;
  if (ph != qh) return ph - qh;
  if (p->poly != q->poly) return p->poly - q->poly;
  return p->seg - q->seg;
}

/* Half-edge h: edge h / 2, from lo to hi when h is even. */
static int tail(const edge *E, int h) { return h & 1 ? E[h / 2].hi : E[h / 2].lo; }
static int head(const edge *E, int h) { return h & 1 ? E[h / 2].lo : E[h / 2].hi; }

typedef struct {
  const ctx *c;
  const edge *E;
} hctx;

static _Thread_local const hctx *sort_h;

/* The half-edge's direction's half-plane: 0 for angles in [0, pi), 1 for [pi, 2 pi). */
static int half(const hctx *H, int h) {
  const edge *e = &H->E[h / 2];
  const seg *s = &H->c->s[e->seg];
  int sg = (h & 1 ? -1 : 1) * e->sign;
  int dy = s->b.y > s->a.y ? 1 : s->b.y < s->a.y ? -1 : 0, dx = s->b.x > s->a.x ? 1 : s->b.x < s->a.x ? -1 : 0;
  dy *= sg, dx *= sg;
  return !(dy > 0 || (dy == 0 && dx > 0));
}

static int by_angle(const void *a, const void *b) {
  int h1 = *(const int *)a, h2 = *(const int *)b;
  int p = half(sort_h, h1), q = half(sort_h, h2);
  if (p != q) return p - q;
  const edge *e1 = &sort_h->E[h1 / 2], *e2 = &sort_h->E[h2 / 2];
  int sg = (h1 & 1 ? -1 : 1) * e1->sign * (h2 & 1 ? -1 : 1) * e2->sign;
  int cr = sg * cross_sign(sort_h->c, &sort_h->c->s[e1->seg], &sort_h->c->s[e2->seg]);
  return -cr;   /* counter-clockwise: d1 before d2 when d1 x d2 > 0 */
}

typedef struct {
  vec2 *pt;
  int npt, cappt;
  int *first, nloops, caploops;
  int *hole, *src;
} loops;

static void push_loop_pt(loops *L, vec2 p) {
  if (L->npt == L->cappt) {
    L->cappt = L->cappt ? 2 * L->cappt : 64;
    L->pt = xreallocarray(L->pt, (size_t)L->cappt, sizeof *L->pt);
  }
  L->pt[L->npt++] = p;
}

static void close_loop(loops *L, int hole, int src) {
  if (L->nloops + 2 > L->caploops) {
    L->caploops = L->caploops ? 2 * L->caploops : 8;
    L->first = xreallocarray(L->first, (size_t)L->caploops + 1, sizeof *L->first);
    L->hole = xreallocarray(L->hole, (size_t)L->caploops, sizeof *L->hole);
    L->src = xreallocarray(L->src, (size_t)L->caploops, sizeof *L->src);
  }
  L->hole[L->nloops] = hole, L->src[L->nloops] = src;
  L->first[++L->nloops] = L->npt;
}

static const double PI = 3.14159265358979323846;

/* What one group asks for and gives back (beyond its loops). */
typedef struct {
  int flags;            /* POLYUNION_NEST, POLYUNION_SPLIT */
  const int *local;     /* polygon -> its index in the group (gn of them) */
  int gn;
  const int (*contact)[2];   /* the group's pairs of polygons in contact */
  int ncontact;
  int nested;           /* out: every pair in contact nested (one inside the other) */
  int pinches;          /* out: points where the region touched itself, split */
  vec2 pinch_at;        /* out: the first */
} gjob;

/* The union of one group: its points pts[gp[0..ngp-1]], the points on its
 * segments on[0..non-1] (segment, point), its segments' polygons.  Appends
 * its loops to L.  POLYUNION_OK, or a failure with *at. */
static polyunion_status union_group(ctx *c, const int *gp, int ngp, const onseg *on, int non, loops *L,
                                    int *newpts, vec2 *at, gjob *gj) {
  polyunion_status st = POLYUNION_OK;
  /* 2. nodes */
  int *ord = xmallocarray((size_t)ngp, sizeof *ord);
  memcpy(ord, gp, (size_t)ngp * sizeof *ord);
  sort_ctx = c;
  qsort(ord, (size_t)ngp, sizeof *ord, by_point);
  int nn = 0;
  vec2 *nodept = xmallocarray((size_t)ngp, sizeof *nodept);
  char *isnew = xcalloc((size_t)ngp, 1);
  for (int i = 0; i < ngp; i++) {
    if (i == 0 || cmp_lex(c, &c->pts[ord[i]], &c->pts[ord[i - 1]]) != 0) {
      nodept[nn] = c->pts[ord[i]].r;
      isnew[nn] = c->pts[ord[i]].s1 >= 0;   /* a crossing equal to no vertex */
      nn++;
    }
    c->pts[ord[i]].node = nn - 1;
  }
  free(ord);
  /* Each segment's points by node (lexicographic = along the segment, one
   * way or the other), cut into pieces. */
  int npc = 0, cappc = non + 16;
  piece *pc = xmallocarray((size_t)cappc, sizeof *pc);
  int *nodes = NULL, capn = 0;
  for (int i = 0, j; i < non; i = j) {
    int s = on[i].seg;
    for (j = i; j < non && on[j].seg == s; j++) {}
    int m = j - i;
    if (m > capn) capn = 2 * m, nodes = xreallocarray(nodes, (size_t)capn, sizeof *nodes);
    for (int k = 0; k < m; k++) nodes[k] = c->pts[on[i + k].pt].node;
    /* sort ascending (insertion for the few, qsort else) */
    for (int k = 1; k < m; k++)
      for (int q = k; q > 0 && nodes[q - 1] > nodes[q]; q--) {
        int t = nodes[q];
        nodes[q] = nodes[q - 1], nodes[q - 1] = t;
      }
    int up = exact_lex(c->s[s].a, c->s[s].b) < 0;
    int k2 = 0;
    for (int k = 0; k < m; k++)
      if (k2 == 0 || nodes[k2 - 1] != nodes[k]) nodes[k2++] = nodes[k];
    for (int k = 0; k + 1 < k2; k++) {
      if (npc + 1 > cappc) cappc *= 2, pc = xreallocarray(pc, (size_t)cappc, sizeof *pc);
      int u = up ? nodes[k] : nodes[k2 - 1 - k], v = up ? nodes[k + 1] : nodes[k2 - 2 - k];
      pc[npc++] = (piece){u, v, s, c->s[s].poly};
    }
  }
  free(nodes);
  /* Edges: pieces between the same two nodes merged; each keeps its pieces
   * (pc[pfirst[e] .. pfirst[e + 1] - 1]) for the coverage below. */
  qsort(pc, (size_t)npc, sizeof *pc, by_piece);
  edge *E = xmallocarray((size_t)npc + 1, sizeof *E);
  int *pfirst = xmallocarray((size_t)npc + 2, sizeof *pfirst);
  int ne = 0;
  for (int i = 0; i < npc; i++) {
    int lo = pc[i].u < pc[i].v ? pc[i].u : pc[i].v, hi = pc[i].u ^ pc[i].v ^ lo;
    if (ne == 0 || E[ne - 1].lo != lo || E[ne - 1].hi != hi) {
      pfirst[ne] = i;
      E[ne++] = (edge){lo, hi, 0, 0, pc[i].seg, exact_lex(c->s[pc[i].seg].a, c->s[pc[i].seg].b) < 0 ? 1 : -1,
                       pc[i].poly};
      /* sign: +1 when the segment runs from lo to hi (lo is the lesser node) */
    }
    if (pc[i].u == lo) E[ne - 1].fwd++;
    else E[ne - 1].bwd++;
  }
  pfirst[ne] = npc;
  /* 3. around each node, counter-clockwise */
  int nh = 2 * ne;
  int *deg = xcalloc((size_t)nn + 1, sizeof *deg), *out = xmallocarray((size_t)nh + 1, sizeof *out);
  for (int h = 0; h < nh; h++) deg[tail(E, h) + 1]++;
  for (int v = 0; v < nn; v++) deg[v + 1] += deg[v];
  int *fill = xmallocarray((size_t)nn + 1, sizeof *fill), *pos = xmallocarray((size_t)nh + 1, sizeof *pos);
  memcpy(fill, deg, (size_t)(nn + 1) * sizeof *fill);
  for (int h = 0; h < nh; h++) out[fill[tail(E, h)]++] = h;
  hctx H = {c, E};
  sort_h = &H;
  for (int v = 0; v < nn; v++)
    if (deg[v + 1] - deg[v] > 2 || v == 0) qsort(out + deg[v], (size_t)(deg[v + 1] - deg[v]), sizeof *out, by_angle);
  for (int i = 0; i < nh; i++) pos[out[i]] = i;
  /* faces: next(h) = the half-edge clockwise from h's reverse at h's head */
  int *face = xmallocarray((size_t)nh + 1, sizeof *face), nf = 0, *fstart = xmallocarray((size_t)nh + 1, sizeof *fstart);
  for (int h = 0; h < nh; h++) face[h] = -1;
  for (int h0 = 0; h0 < nh; h0++) {
    if (face[h0] >= 0) continue;
    fstart[nf] = h0;
    for (int h = h0; face[h] < 0;) {
      face[h] = nf;
      int t = h ^ 1, v = tail(E, t), i = pos[t], d0 = deg[v], d = deg[v + 1] - d0;
      h = out[d0 + (i - d0 + d - 1) % d];
    }
    nf++;
  }
  /* the unbounded face: left of the counter-clockwise-most half-edge at
   * node 0 (the least point: every edge leaves it into x > 0, or up) */
  int unb;
  {
    int d0 = deg[0], d = deg[1] - d0, last = out[d0 + d - 1];
    for (int i = 0; i < d; i++)
      if (half(&H, out[d0 + i]) == 0) last = out[d0 + i];
    unb = face[last];
  }
  /* 4. the faces of the region, from the unbounded one (face[h] lies left
   * of h: the polygons, all counter-clockwise, cover their left) */
  unsigned char *mat = xcalloc((size_t)nf + 1, 1);
  int *queue = xmallocarray((size_t)nf + 1, sizeof *queue), qh = 0, qt = 0;
  if (!(gj->flags & POLYUNION_NEST)) {
    /* winding numbers: the union is where they are >= 1 */
    int *w = xmallocarray((size_t)nf + 1, sizeof *w);
    for (int f = 0; f < nf; f++) w[f] = INT32_MIN;
    w[unb] = 0, queue[qt++] = unb;
    while (qh < qt) {
      int f = queue[qh++], h0 = fstart[f], h = h0;
      do {
        const edge *e = &E[h / 2];
        int along = h & 1 ? e->bwd - e->fwd : e->fwd - e->bwd, g = face[h ^ 1];
        int want = w[f] - along;   /* w(left of h) - w(right of h) = along */
        if (w[g] == INT32_MIN) w[g] = want, queue[qt++] = g;
        else XASSERT(w[g] == want);
        int t = h ^ 1, v = tail(E, t), i = pos[t], d0 = deg[v], d = deg[v + 1] - d0;
        h = out[d0 + (i - d0 + d - 1) % d];
      } while (h != h0);
    }
    for (int f = 0; f < nf; f++) {
      XASSERT(w[f] >= 0);
      mat[f] = w[f] >= 1;
    }
    free(w);
  } else {
    /* the polygons covering each face (a bit set), then which polygon lies
     * inside which (i in j: every face i covers, j covers), each one's depth
     * (the longest chain of polygons around it; 0 for a piece of a union)
     * and the region: the faces whose deepest covering polygon lies at even
     * depth */
    int gn = gj->gn, W = (gn + 63) / 64;
    uint64_t *cov = xcalloc((size_t)nf * (size_t)W + 1, sizeof *cov);
    unsigned char *seen = xcalloc((size_t)nf + 1, 1);
    seen[unb] = 1, queue[qt++] = unb;
    while (qh < qt) {
      int f = queue[qh++], h0 = fstart[f], h = h0;
      do {
        int g = face[h ^ 1];
        if (!seen[g]) {
          seen[g] = 1, queue[qt++] = g;
          memcpy(cov + (size_t)g * W, cov + (size_t)f * W, (size_t)W * sizeof *cov);
          for (int k = pfirst[h / 2]; k < pfirst[h / 2 + 1]; k++) {
            int l = gj->local[pc[k].poly];
            uint64_t bit = UINT64_C(1) << (l % 64), *x = cov + (size_t)g * W + l / 64;
            if (pc[k].u == tail(E, h)) *x &= ~bit;   /* runs along h: covers f, not g */
            else *x |= bit;
          }
        }
        int t = h ^ 1, v = tail(E, t), i = pos[t], d0 = deg[v], d = deg[v + 1] - d0;
        h = out[d0 + (i - d0 + d - 1) % d];
      } while (h != h0);
    }
    uint64_t *notin = xcalloc((size_t)gn * (size_t)W + 1, sizeof *notin);
    for (int f = 0; f < nf; f++)
      for (int l = 0; l < gn; l++)
        if (cov[(size_t)f * W + l / 64] >> (l % 64) & 1)
          for (int k = 0; k < W; k++) notin[(size_t)l * W + k] |= ~cov[(size_t)f * W + k];
#define INSIDE(i, j) ((i) != (j) && !(notin[(size_t)(i) * W + (j) / 64] >> ((j) % 64) & 1))
    int *cnt = xcalloc((size_t)gn + 1, sizeof *cnt), *ord2 = xmallocarray((size_t)gn + 1, sizeof *ord2);
    int *depth = xcalloc((size_t)gn + 1, sizeof *depth);
    for (int i = 0; i < gn; i++)
      for (int j = 0; j < gn; j++) cnt[i] += INSIDE(i, j);
    for (int i = 0; i < gn; i++) ord2[i] = i;
    for (int i = 1; i < gn; i++)   /* by how many lie around: every container comes first */
      for (int k = i; k > 0 && cnt[ord2[k - 1]] > cnt[ord2[k]]; k--) {
        int t = ord2[k];
        ord2[k] = ord2[k - 1], ord2[k - 1] = t;
      }
    /* a polygon in contact with one neither inside it nor around it is a
     * piece of a union (depth 0), whatever lies around it */
    unsigned char *ispiece = xcalloc((size_t)gn + 1, 1);
    gj->nested = 1;
    for (int k = 0; k < gj->ncontact; k++) {
      int i = gj->local[gj->contact[k][0]], j = gj->local[gj->contact[k][1]];
      if (!INSIDE(i, j) && !INSIDE(j, i)) ispiece[i] = ispiece[j] = 1, gj->nested = 0;
    }
    for (int a2 = 0; a2 < gn; a2++) {
      int i = ord2[a2];
      for (int j = 0; j < gn && !ispiece[i]; j++)
        if (INSIDE(i, j) && depth[j] + 1 > depth[i]) depth[i] = depth[j] + 1;
    }
    free(ispiece);
    for (int f = 0; f < nf; f++) {
      int best = -1;
      for (int l = 0; l < gn; l++)
        if ((cov[(size_t)f * W + l / 64] >> (l % 64) & 1) && depth[l] > best) best = depth[l];
      mat[f] = best >= 0 && best % 2 == 0;
    }
#undef INSIDE
    free(cnt), free(ord2), free(depth), free(notin), free(cov), free(seen);
  }
  free(queue);
  /* 5. the boundary: the half-edges with the region on the left and not on
   * the right; each one's successor at its head.  Where the region touches
   * itself (a pinch: more than one boundary edge leaves a node) it cannot
   * be followed, unless POLYUNION_SPLIT: then the successor is the first
   * boundary edge clockwise from the reverse (keeping to one wedge of the
   * region), and a loop that comes back to a node is split there. */
  unsigned char *isb = xcalloc((size_t)nh + 1, 1);
  int *nextb = xmallocarray((size_t)nh + 1, sizeof *nextb), *bout = xmallocarray((size_t)nn + 1, sizeof *bout);
  for (int v = 0; v < nn; v++) bout[v] = -1;
  for (int h = 0; h < nh; h++) isb[h] = mat[face[h]] && !mat[face[h ^ 1]];
  for (int h = 0; h < nh && st == POLYUNION_OK; h++) {
    if (!isb[h]) continue;
    int v = tail(E, h);
    if (bout[v] >= 0 && !(gj->flags & POLYUNION_SPLIT)) {
      st = POLYUNION_PINCH;
      *at = nodept[v];
    }
    bout[v] = h;
  }
  for (int h = 0; h < nh && st == POLYUNION_OK; h++) {
    if (!isb[h]) continue;
    int v = head(E, h), i = pos[h ^ 1], d0 = deg[v], d = deg[v + 1] - d0;
    nextb[h] = -1;
    for (int k = 1; k <= d && nextb[h] < 0; k++) {
      int g = out[d0 + ((i - d0 - k) % d + d) % d];
      if (isb[g]) nextb[h] = g;
    }
    XASSERT(nextb[h] >= 0);
  }
  char *done = xcalloc((size_t)nh + 1, 1);
  int *stack = xmallocarray((size_t)nh + 1, sizeof *stack), *nodeat = xmallocarray((size_t)nn + 1, sizeof *nodeat);
  int *lnode = xmallocarray((size_t)nh + 1, sizeof *lnode), nln = 0;   /* each loop's nodes, in order */
  int *lfirst = xmallocarray((size_t)nh + 2, sizeof *lfirst), *lsrc = xmallocarray((size_t)nh + 1, sizeof *lsrc), nl = 0;
  for (int v = 0; v < nn; v++) nodeat[v] = -1;
  for (int h0 = 0; h0 < nh && st == POLYUNION_OK; h0++) {
    if (!isb[h0] || done[h0]) continue;
    int top = 0, h = h0;
    for (int closing = 0; !closing;) {
      int v = tail(E, h);
      closing = h == h0 && top > 0;
      if (nodeat[v] >= 0) {   /* back at v: the loop from there is closed */
        int a = nodeat[v];
        lfirst[nl] = nln, lsrc[nl] = E[stack[a] / 2].poly;
        for (int k = a; k < top; k++) {
          lnode[nln++] = tail(E, stack[k]);
          nodeat[tail(E, stack[k])] = -1;
          if (E[stack[k] / 2].poly < lsrc[nl]) lsrc[nl] = E[stack[k] / 2].poly;
        }
        nl++;
        top = a;
      }
      if (closing) break;
      nodeat[v] = top, stack[top++] = h, done[h] = 1;
      h = nextb[h];
    }
    XASSERT(top == 0);
  }
  lfirst[nl] = nln;
  /* Loops that share a node (split pinches): all but one are kept off it,
   * their corner there cut 2^-20 of the way along its two edges, inside
   * the sector between them that holds no other loop's edge; the loop kept
   * is the one whose such sector is widest (the one loop whose sector may
   * be 180 degrees or more, where a cut would not part them). */
  int *uses = xcalloc((size_t)nn + 1, sizeof *uses);
  for (int k = 0; k < nln; k++) uses[lnode[k]]++;
  int *cut = xcalloc((size_t)nln + 1, sizeof *cut);
  for (int v = 0; v < nn && st == POLYUNION_OK; v++) {
    if (uses[v] < 2) continue;
    if (gj->pinches++ == 0) gj->pinch_at = nodept[v];
    int keep = -1;
    double best = -1;
    for (int l = 0; l < nl; l++)
      for (int k = lfirst[l]; k < lfirst[l + 1]; k++) {
        if (lnode[k] != v) continue;
        int m = lfirst[l + 1] - lfirst[l], k0 = k - lfirst[l];
        vec2 q = nodept[v], pv = nodept[lnode[lfirst[l] + (k0 + m - 1) % m]], nx = nodept[lnode[lfirst[l] + (k0 + 1) % m]];
        double a0 = atan2(nx.y - q.y, nx.x - q.x), a1 = atan2(pv.y - q.y, pv.x - q.x);
        double inside = fmod(a1 - a0 + 4 * PI, 2 * PI);   /* its left (region) side, from next to prev */
        int other = 0;   /* another loop's edge inside that side? */
        for (int l2 = 0; l2 < nl; l2++)
          for (int k2 = lfirst[l2]; k2 < lfirst[l2 + 1] && l2 != l; k2++) {
            if (lnode[k2] != v) continue;
            int m2 = lfirst[l2 + 1] - lfirst[l2], j2 = k2 - lfirst[l2];
            vec2 e[2] = {nodept[lnode[lfirst[l2] + (j2 + 1) % m2]], nodept[lnode[lfirst[l2] + (j2 + m2 - 1) % m2]]};
            for (int x = 0; x < 2; x++) other |= fmod(atan2(e[x].y - q.y, e[x].x - q.x) - a0 + 4 * PI, 2 * PI) < inside;
          }
        double freeside = other ? 2 * PI - inside : inside;
        if (freeside > best) best = freeside, keep = k;
      }
    for (int k = 0; k < nln; k++)
      if (lnode[k] == v && k != keep) cut[k] = 1;
  }
  /* 6. the loops' points, rounded: consecutive equal points merged */
  int first_loop = L->nloops;
  for (int l = 0; l < nl && st == POLYUNION_OK; l++) {
    int start = L->npt, m = lfirst[l + 1] - lfirst[l];
    for (int k = 0; k < m; k++) {
      int kk = lfirst[l] + k, v = lnode[kk];
      if (!cut[kk]) {
        if (isnew[v]) (*newpts)++;
        push_loop_pt(L, nodept[v]);
        continue;
      }
      vec2 q = nodept[v], pv = nodept[lnode[lfirst[l] + (k + m - 1) % m]], nx = nodept[lnode[lfirst[l] + (k + 1) % m]];
      const double t = 0x1p-20;
      push_loop_pt(L, (vec2){q.x + t * (pv.x - q.x), q.y + t * (pv.y - q.y)});
      push_loop_pt(L, (vec2){q.x + t * (nx.x - q.x), q.y + t * (nx.y - q.y)});
    }
    int mm = 0;
    vec2 *q = L->pt + start;
    int n = L->npt - start;
    for (int i = 0; i < n; i++)
      if (mm == 0 || exact_lex(q[i], q[mm - 1]) != 0) q[mm++] = q[i];
    while (mm > 1 && exact_lex(q[mm - 1], q[0]) == 0) mm--;
    L->npt = start + mm;
    if (mm < 3 || geom_collinear(q, mm)) {
      st = POLYUNION_ROUNDING;
      *at = q[0];
      break;
    }
    close_loop(L, geom_orientation(q, mm) < 0, lsrc[l]);
  }
  if (st == POLYUNION_OK) {
    int nlp = L->nloops - first_loop;
    crossing_poly *cp = xmallocarray((size_t)nlp + 1, sizeof *cp);
    for (int k = 0; k < nlp; k++) {
      int f = L->first[first_loop + k];
      cp[k] = (crossing_poly){L->pt + f, L->first[first_loop + k + 1] - f};
    }
    crossing_hit hit;
    if (crossing_find(cp, nlp, &hit)) st = POLYUNION_ROUNDING, *at = hit.at;
    free(cp);
  }
  if (st != POLYUNION_OK) {   /* the group's loops are not returned */
    L->nloops = first_loop;
    L->npt = L->first[first_loop];
  }
  free(uses), free(cut), free(lnode), free(lfirst), free(lsrc), free(stack), free(nodeat), free(done);
  free(isb), free(nextb), free(bout), free(mat), free(face), free(fstart), free(deg), free(out), free(fill), free(pos);
  free(E), free(pfirst), free(pc), free(nodept), free(isnew);
  return st;
}

/* ---------------------------------------------------------------- the whole */

static int by_seg(const void *a, const void *b) {
  const onseg *p = a, *q = b;
  if (p->seg != q->seg) return p->seg - q->seg;
  return p->pt - q->pt;
}

static int by_pair(const void *a, const void *b) {
  const int *p = a, *q = b;
  return p[0] != q[0] ? p[0] - q[0] : p[1] - q[1];
}

int polyunion(const crossing_poly *p, int np, polyunion_result *out) { return polyunion_flags(p, np, 0, out); }

int polyunion_flags(const crossing_poly *p, int np, int flags, polyunion_result *out) {
  memset(out, 0, sizeof *out);
  int N = 0;
  for (int k = 0; k < np; k++) N += p[k].n;
  seg *S = xmallocarray((size_t)N + 1, sizeof *S);
  int *off = xmallocarray((size_t)np + 1, sizeof *off);
  for (int k = 0, g = 0; k < np; k++) {
    off[k] = g;
    int n = p[k].n, ccw = geom_orientation(p[k].pt, n) > 0;
    for (int j = 0; j < n; j++, g++) {
      vec2 a = p[k].pt[j], b = p[k].pt[(j + 1) % n];
      S[g] = ccw ? (seg){a, b, k} : (seg){b, a, k};
    }
  }
  off[np] = N;
  ctx c = {S, NULL, 0, 0, least_exp(p, np)};
  /* Every vertex a point, with each of its two segments. */
  onlist on = {0};
  for (int k = 0; k < np; k++)
    for (int j = 0; j < p[k].n; j++) {
      /* vertex j ends segment j - 1 and starts segment j (either direction) */
      int g = off[k] + j, q = add_pt(&c, p[k].pt[j], -1, -1);
      int prev = off[k] + (j + p[k].n - 1) % p[k].n;
      push_on(&on, g, q), push_on(&on, prev, q);
    }
  /* 1. contacts (and the pairs of polygons in contact) */
  int (*con)[2] = NULL, ncon = 0, capcon = 0;
  int *up = xmallocarray((size_t)np + 1, sizeof *up);
  for (int k = 0; k < np; k++) up[k] = k;
  geom_span *sx = xmallocarray((size_t)N + 1, sizeof *sx);
  for (int g = 0; g < N; g++) sx[g] = (geom_span){fmin(S[g].a.x, S[g].b.x), fmax(S[g].a.x, S[g].b.x), g};
  geom_span_sort(sx, N);
  static _Thread_local bigz nx, ny, d;
  for (int u = 0; u < N; u++) {
    int i = sx[u].i;
    const seg *A = &S[i];
    double ylo = fmin(A->a.y, A->b.y), yhi = fmax(A->a.y, A->b.y);
    for (int t = u + 1; t < N && sx[t].lo <= sx[u].hi; t++) {
      int j = sx[t].i;
      const seg *B = &S[j];
      if (B->poly == A->poly || fmax(B->a.y, B->b.y) < ylo || fmin(B->a.y, B->b.y) > yhi) continue;
      vec2 at;
      crossing_kind k = crossing_segments(A->a, A->b, B->a, B->b, &at);
      if (k == CROSSING_NONE) continue;
      up[find_root(up, A->poly)] = find_root(up, B->poly);
      if (ncon == capcon) capcon = capcon ? 2 * capcon : 16, con = xreallocarray(con, (size_t)capcon, sizeof *con);
      con[ncon][0] = A->poly < B->poly ? A->poly : B->poly, con[ncon++][1] = A->poly < B->poly ? B->poly : A->poly;
      if (k == CROSSING_CROSS) {
        int s1 = i < j ? i : j, s2 = i < j ? j : i;
        crossing_exact(&c, s1, s2, &nx, &ny, &d);
        vec2 r = {bigz_ratio(&nx, &d, c.e), bigz_ratio(&ny, &d, c.e)};
        int q = add_pt(&c, r, s1, s2);
        push_on(&on, i, q), push_on(&on, j, q);
      } else {
        /* An end of one inside the other: a point of it there. */
        const vec2 ends[4] = {A->a, A->b, B->a, B->b};
        for (int e = 0; e < 4; e++) {
          const seg *o = e < 2 ? B : A;
          int os = e < 2 ? j : i;
          if (exact_orient(o->a, o->b, ends[e]) == 0 && strictly_inside(o->a, o->b, ends[e])) {
            int q = add_pt(&c, ends[e], -1, -1);
            push_on(&on, os, q);
          }
        }
      }
    }
  }
  free(sx);
  /* groups of two or more */
  out->group = xmallocarray((size_t)np + 1, sizeof *out->group);
  int *size = xcalloc((size_t)np + 1, sizeof *size), *gid = xmallocarray((size_t)np + 1, sizeof *gid);
  for (int k = 0; k < np; k++) size[find_root(up, k)]++;
  for (int k = 0; k < np; k++) gid[k] = -1;
  for (int k = 0; k < np; k++) {
    int r = find_root(up, k);
    if (size[r] < 2) {
      out->group[k] = -1;
      continue;
    }
    if (gid[r] < 0) gid[r] = out->ngroups++;
    out->group[k] = gid[r];
  }
  int G = out->ngroups;
  out->gmember = xcalloc((size_t)G + 2, sizeof *out->gmember);
  out->members = xmallocarray((size_t)np + 1, sizeof *out->members);
  for (int k = 0; k < np; k++)
    if (out->group[k] >= 0) out->gmember[out->group[k] + 1]++;
  for (int g = 0; g < G; g++) out->gmember[g + 1] += out->gmember[g];
  {
    int *f = xmallocarray((size_t)G + 1, sizeof *f);
    memcpy(f, out->gmember, (size_t)(G + 1) * sizeof *f);
    for (int k = 0; k < np; k++)
      if (out->group[k] >= 0) out->members[f[out->group[k]]++] = k;
    free(f);
  }
  out->gfirst = xcalloc((size_t)G + 2, sizeof *out->gfirst);
  out->newpts = xcalloc((size_t)G + 1, sizeof *out->newpts);
  out->gstatus = xcalloc((size_t)G + 1, sizeof *out->gstatus);
  out->gat = xcalloc((size_t)G + 1, sizeof *out->gat);
  out->nested = xcalloc((size_t)G + 1, sizeof *out->nested);
  out->pinches = xcalloc((size_t)G + 1, sizeof *out->pinches);
  out->pinch_at = xcalloc((size_t)G + 1, sizeof *out->pinch_at);
  /* each polygon's place in its group; the pairs in contact, once each, by group */
  int *local = xmallocarray((size_t)np + 1, sizeof *local);
  for (int g = 0; g < G; g++)
    for (int k = out->gmember[g]; k < out->gmember[g + 1]; k++) local[out->members[k]] = k - out->gmember[g];
  if (ncon) qsort(con, (size_t)ncon, sizeof *con, by_pair);
  int nc2 = 0;
  for (int k = 0; k < ncon; k++)
    if (nc2 == 0 || con[k][0] != con[nc2 - 1][0] || con[k][1] != con[nc2 - 1][1])
      con[nc2][0] = con[k][0], con[nc2++][1] = con[k][1];
  int (*gcon)[2] = xmallocarray((size_t)nc2 + 1, sizeof *gcon);
  /* points on segments, by segment */
  qsort(on.v, (size_t)on.n, sizeof *on.v, by_seg);
  loops L = {0};
  L.first = xmallocarray(9, sizeof *L.first);
  L.caploops = 8;
  L.hole = xmallocarray(8, sizeof *L.hole), L.src = xmallocarray(8, sizeof *L.src);
  L.first[0] = 0;
  int rc = 0;
  /* per group: its points and its segments' points */
  int *gp = xmallocarray((size_t)c.npts + 1, sizeof *gp);
  onseg *gon = xmallocarray((size_t)on.n + 1, sizeof *gon);
  char *inpt = xcalloc((size_t)c.npts + 1, 1);
  for (int g = 0; g < G; g++) {
    out->gfirst[g] = L.nloops;
    int ngp = 0, non = 0;
    for (int i = 0; i < on.n; i++) {
      int s = on.v[i].seg;
      if (out->group[S[s].poly] != g) continue;
      gon[non++] = on.v[i];
      if (!inpt[on.v[i].pt]) inpt[on.v[i].pt] = 1, gp[ngp++] = on.v[i].pt;
    }
    for (int i = 0; i < ngp; i++) inpt[gp[i]] = 0;
    int ngc = 0;
    for (int k = 0; k < nc2; k++)
      if (out->group[con[k][0]] == g) gcon[ngc][0] = con[k][0], gcon[ngc++][1] = con[k][1];
    gjob gj = {flags, local, out->gmember[g + 1] - out->gmember[g], (const int(*)[2])gcon, ngc, 0, 0, {0, 0}};
    polyunion_status st = union_group(&c, gp, ngp, gon, non, &L, &out->newpts[g], &out->gat[g], &gj);
    out->gstatus[g] = st;
    out->nested[g] = gj.nested, out->pinches[g] = gj.pinches, out->pinch_at[g] = gj.pinch_at;
    if (st != POLYUNION_OK && rc == 0) {
      out->status = st;
      out->bad_group = g;
      out->at = out->gat[g];
      rc = -1;
    }
  }
  out->gfirst[G] = L.nloops;
  out->nloops = L.nloops;
  out->first = L.first;
  out->pt = L.pt;
  out->hole = L.hole;
  out->src = L.src;
  free(gp), free(gon), free(inpt), free(size), free(gid), free(up), free(on.v), free(c.pts), free(S), free(off);
  free(local), free(con), free(gcon);
  return rc;
}

void polyunion_free(polyunion_result *u) {
  free(u->group), free(u->members), free(u->gmember), free(u->gfirst), free(u->first), free(u->pt), free(u->hole);
  free(u->src), free(u->newpts), free(u->gstatus), free(u->gat), free(u->nested), free(u->pinches), free(u->pinch_at);
  memset(u, 0, sizeof *u);
}
