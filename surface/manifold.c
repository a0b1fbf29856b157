/* manifold.c -- components by union-find over triangles' vertices; the rest
 * vertex by vertex, with no global sort of the edges.
 *
 * Around a vertex v every triangle (v, b, c) gives a link edge b -> c: the
 * mesh's edges v -> b (out of v) and c -> v (into v).  The mesh is closed at
 * v when the out-neighbours b and the in-neighbours c are the same multiset
 * (every edge out of v comes back); each edge once when they have no
 * repeats; one fan when the link edges b -> c form a single cycle.  The
 * undirected edges at v are its distinct neighbours: E = (sum over v) / 2. */
#include "surface/manifold.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

static int find(int *up, int x) {
  while (up[x] != x) x = up[x] = up[up[x]];
  return x;
}

static int cmp_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return x < y ? -1 : x > y;
}

/* Sort a few ints (insertion sort; qsort when many). */
static void sort_ints(int *x, int n) {
  if (n > 24) {
    qsort(x, (size_t)n, sizeof *x, cmp_int);
    return;
  }
  for (int i = 1; i < n; i++)
    for (int j = i; j > 0 && x[j - 1] > x[j]; j--) {
      int t = x[j];
      x[j] = x[j - 1], x[j - 1] = t;
    }
}

int manifold_components(const mesh *me, manifold_component **out) {
  int nv = me->nv, nt = me->nt;
  int *up = xmallocarray((size_t)nv + 1, sizeof *up);
  unsigned char *used = xcalloc((size_t)nv + 1, 1);
  for (int v = 0; v < nv; v++) up[v] = v;
  for (int t = 0; t < nt; t++)
    for (int k = 0; k < 3; k++) {
      int a = find(up, me->t[t][k]), b = find(up, me->t[t][(k + 1) % 3]);
      if (a < b) up[b] = a;
      else if (b < a) up[a] = b;
      used[me->t[t][k]] = 1;
    }
  int *comp = xmallocarray((size_t)nv + 1, sizeof *comp), nc = 0;
  for (int v = 0; v < nv; v++) comp[v] = used[v] && find(up, v) == v ? nc++ : -1;
  for (int v = 0; v < nv; v++)
    if (used[v]) comp[v] = comp[find(up, v)];
  manifold_component *c = xcalloc((size_t)nc + 1, sizeof *c);
  for (int i = 0; i < nc; i++) c[i].closed = c[i].manifold = 1, c[i].first = -1;
  double *big = xcalloc((size_t)nc + 1, sizeof *big);   /* each component's largest |coordinate| */
  for (int v = 0; v < nv; v++) {
    if (!used[v]) continue;
    manifold_component *x = &c[comp[v]];
    big[comp[v]] = fmax(big[comp[v]], fmax(fabs(me->v[v].x), fmax(fabs(me->v[v].y), fabs(me->v[v].z))));
    if (x->first < 0) x->first = v, x->zmin = x->zmax = me->v[v].z;
    x->nv++;
    if (me->v[v].z < x->zmin) x->zmin = me->v[v].z;
    if (me->v[v].z > x->zmax) x->zmax = me->v[v].z;
  }
  /* Area and volume about the component's first vertex (so that far-off
   * coordinates do not cancel); the volume summed at the scale 2^-e that
   * brings the component's largest coordinate into [1/2, 1), then scaled
   * back (the same bits as unscaled; no inf - inf = NaN at 1e300). */
  int *sc = xmallocarray((size_t)nc + 1, sizeof *sc);
  for (int i = 0; i < nc; i++) sc[i] = geom_scale_exp(big[i]);
  for (int t = 0; t < nt; t++) {
    int ci = comp[me->t[t][0]], e = sc[ci];
    manifold_component *x = &c[ci];
    vec3 o = me->v[x->first], a = me->v[me->t[t][0]], b = me->v[me->t[t][1]], d = me->v[me->t[t][2]];
    a.x = geom_ldexp(a.x, -e) - geom_ldexp(o.x, -e), a.y = geom_ldexp(a.y, -e) - geom_ldexp(o.y, -e), a.z = geom_ldexp(a.z, -e) - geom_ldexp(o.z, -e);
    b.x = geom_ldexp(b.x, -e) - geom_ldexp(o.x, -e), b.y = geom_ldexp(b.y, -e) - geom_ldexp(o.y, -e), b.z = geom_ldexp(b.z, -e) - geom_ldexp(o.z, -e);
    d.x = geom_ldexp(d.x, -e) - geom_ldexp(o.x, -e), d.y = geom_ldexp(d.y, -e) - geom_ldexp(o.y, -e), d.z = geom_ldexp(d.z, -e) - geom_ldexp(o.z, -e);
    x->nt++;
    x->area += mesh_tri_area(me, t);
    x->volume += (a.x * (b.y * d.z - b.z * d.y) + a.y * (b.z * d.x - b.x * d.z) + a.z * (b.x * d.y - b.y * d.x)) / 6;
  }
  for (int i = 0; i < nc; i++) c[i].volume = ldexp(c[i].volume, 3 * sc[i]);
  free(sc);
  free(big);
  /* The link of every vertex. */
  int *deg = xcalloc((size_t)nv + 1, sizeof *deg);
  for (int t = 0; t < nt; t++)
    for (int k = 0; k < 3; k++) deg[me->t[t][k] + 1]++;
  for (int v = 0; v < nv; v++) deg[v + 1] += deg[v];
  int *at = xmallocarray((size_t)nv + 1, sizeof *at), (*link)[2] = xmallocarray(3 * (size_t)nt + 1, sizeof *link);
  memcpy(at, deg, (size_t)nv * sizeof *at);
  for (int t = 0; t < nt; t++)
    for (int k = 0; k < 3; k++) {
      int v = me->t[t][k];
      link[at[v]][0] = me->t[t][(k + 1) % 3];
      link[at[v]][1] = me->t[t][(k + 2) % 3];
      at[v]++;
    }
  int cap = 64, *outs = xmallocarray((size_t)cap, sizeof *outs), *ins = xmallocarray((size_t)cap, sizeof *ins);
  long long *twice_e = xcalloc((size_t)nc + 1, sizeof *twice_e);
  for (int v = 0; v < nv; v++) {
    int lo = deg[v], n = deg[v + 1] - lo;
    if (n == 0) continue;
    manifold_component *x = &c[comp[v]];
    if (n > cap) {
      cap = 2 * n;
      outs = xreallocarray(outs, (size_t)cap, sizeof *outs);
      ins = xreallocarray(ins, (size_t)cap, sizeof *ins);
    }
    for (int k = 0; k < n; k++) outs[k] = link[lo + k][0], ins[k] = link[lo + k][1];
    sort_ints(outs, n);
    sort_ints(ins, n);
    int same = 1, repeats = 0, distinct = 0;
    for (int k = 0; k < n; k++) {
      if (outs[k] != ins[k] || outs[k] == v) same = 0;
      if (k > 0 && (outs[k] == outs[k - 1] || ins[k] == ins[k - 1])) repeats = 1;
    }
    /* distinct neighbours: the union of the two sorted lists */
    for (int i = 0, j = 0; i < n || j < n;) {
      int y = j >= n || (i < n && outs[i] <= ins[j]) ? outs[i] : ins[j];
      distinct++;
      while (i < n && outs[i] == y) i++;
      while (j < n && ins[j] == y) j++;
    }
    twice_e[comp[v]] += distinct;
    if (!same) x->closed = 0;
    if (repeats) x->manifold = 0;
    if (!same || repeats) continue;
    /* One fan: follow b -> c from the first link edge (each b once). */
    int start = link[lo][0], cur = start, steps = 0;
    do {
      int next = -1;
      for (int k = lo; k < lo + n; k++)
        if (link[k][0] == cur) {
          next = link[k][1];
          break;
        }
      if (next < 0) break;
      cur = next;
      steps++;
    } while (cur != start && steps <= n);
    if (cur != start || steps != n) x->manifold = 0;
  }
  for (int i = 0; i < nc; i++) c[i].ne = (int)(twice_e[i] / 2);
  free(twice_e), free(outs), free(ins);
  for (int i = 0; i < nc; i++) {
    c[i].manifold &= c[i].closed;
    c[i].euler = c[i].nv - c[i].ne + c[i].nt;
    c[i].genus = c[i].manifold ? (2 - c[i].euler) / 2 : -1;
  }
  free(at), free(link), free(deg), free(comp), free(used), free(up);
  *out = c;
  return nc;
}
