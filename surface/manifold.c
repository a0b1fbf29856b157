/* manifold.c -- components by union-find over triangles' vertices; the edge
 * census by sorting 64-bit keys (a << 32 | b); vertex fans by following
 * each vertex's link. */
#include "manifold.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "xmem.h"

static int find(int *up, int x) {
  while (up[x] != x) x = up[x] = up[up[x]];
  return x;
}

static int cmp_u64(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return x < y ? -1 : x > y;
}

/* How many times key appears in the sorted k[0..n-1]. */
static size_t count(const uint64_t *k, size_t n, uint64_t key) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    size_t m = lo + (hi - lo) / 2;
    if (k[m] < key) lo = m + 1;
    else hi = m;
  }
  size_t c = 0;
  while (lo + c < n && k[lo + c] == key) c++;
  return c;
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
  for (int v = 0; v < nv; v++) {
    if (!used[v]) continue;
    manifold_component *x = &c[comp[v]];
    if (x->first < 0) x->first = v, x->zmin = x->zmax = me->v[v].z;
    x->nv++;
    if (me->v[v].z < x->zmin) x->zmin = me->v[v].z;
    if (me->v[v].z > x->zmax) x->zmax = me->v[v].z;
  }
  /* Area and volume about the component's first vertex (so that far-off
   * coordinates do not cancel). */
  for (int t = 0; t < nt; t++) {
    manifold_component *x = &c[comp[me->t[t][0]]];
    vec3 o = me->v[x->first], a = me->v[me->t[t][0]], b = me->v[me->t[t][1]], d = me->v[me->t[t][2]];
    a.x -= o.x, a.y -= o.y, a.z -= o.z;
    b.x -= o.x, b.y -= o.y, b.z -= o.z;
    d.x -= o.x, d.y -= o.y, d.z -= o.z;
    x->nt++;
    x->area += mesh_tri_area(me, t);
    x->volume += (a.x * (b.y * d.z - b.z * d.y) + a.y * (b.z * d.x - b.x * d.z) + a.z * (b.x * d.y - b.y * d.x)) / 6;
  }
  /* Directed edges: each as often as its reverse (no border), and once
   * (else the edge has more than two triangles: pinched). */
  size_t ne = 3 * (size_t)nt;
  uint64_t *key = xmallocarray(ne + 1, sizeof *key);
  for (int t = 0; t < nt; t++)
    for (int k = 0; k < 3; k++)
      key[3 * (size_t)t + k] = (uint64_t)(uint32_t)me->t[t][k] << 32 | (uint32_t)me->t[t][(k + 1) % 3];
  qsort(key, ne, sizeof *key, cmp_u64);
  for (size_t i = 0; i < ne; i++) {
    if (i > 0 && key[i] == key[i - 1]) continue;
    uint32_t a = (uint32_t)(key[i] >> 32), b = (uint32_t)key[i];
    manifold_component *x = &c[comp[a]];
    size_t here = count(key + i, ne - i, key[i]), back = count(key, ne, (uint64_t)b << 32 | a);
    if (here != back || a == b) x->closed = 0;
    if (here > 1) x->manifold = 0;
    if (back == 0 || a < b) x->ne++;
  }
  /* Fans: around a closed vertex v, the triangles (v, b, c) give the link
   * edges b -> c; one cycle through all of them means one fan. */
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
  for (int v = 0; v < nv; v++) {
    int lo = deg[v], n = deg[v + 1] - lo;
    if (n == 0) continue;
    manifold_component *x = &c[comp[v]];
    if (!x->closed || !x->manifold) {
      x->manifold = 0;
      continue;
    }
    /* Follow b -> c from the first link edge; count the steps back. */
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
  for (int i = 0; i < nc; i++) {
    c[i].manifold &= c[i].closed;
    c[i].euler = c[i].nv - c[i].ne + c[i].nt;
    c[i].genus = c[i].manifold ? (2 - c[i].euler) / 2 : -1;
  }
  free(at), free(link), free(deg), free(key), free(comp), free(used), free(up);
  *out = c;
  return nc;
}
