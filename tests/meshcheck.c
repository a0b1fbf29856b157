/* meshcheck.c -- reading meshes and checking them (see meshcheck.h), the way
 * Triangle's checkmesh checks its own: every edge matched, every triangle
 * oriented, every vertex's fan closed. */
#include "tests/meshcheck.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

#define PI 3.14159265358979323846

/* --------------------------------------------------------------- readers -- */

typedef struct { int n, cap; double *v; } dvec;
typedef struct { int n, cap; int *v; } ivec;
static void dpush(dvec *a, double x) {
  if (a->n == a->cap) a->v = xreallocarray(a->v, (size_t)(a->cap = a->cap ? 2 * a->cap : 256), sizeof *a->v);
  a->v[a->n++] = x;
}
static void ipush(ivec *a, int x) {
  if (a->n == a->cap) a->v = xreallocarray(a->v, (size_t)(a->cap = a->cap ? 2 * a->cap : 256), sizeof *a->v);
  a->v[a->n++] = x;
}

static int fail(char *err, size_t errlen, const char *path, int line, const char *why) {
  if (line > 0) snprintf(err, errlen, "%s:%d: %s", path, line, why);
  else snprintf(err, errlen, "%s: %s", path, why);
  return -1;
}

static int read_obj(FILE *f, const char *path, mc_mesh *m, char *err, size_t errlen) {
  dvec v = {0};
  ivec t = {0};
  char line[4096];
  int lineno = 0, rc = 0;
  while (rc == 0 && fgets(line, sizeof line, f)) {
    lineno++;
    char *p = line;
    if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) {
      char *e;
      for (int k = 0; k < 3; k++) {
        double x = strtod(p + (k ? 0 : 1), &e);
        if (e == p + (k ? 0 : 1)) { rc = fail(err, errlen, path, lineno, "bad vertex"); break; }
        dpush(&v, x);
        p = e;
      }
    } else if (p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) {
      int idx[4], k = 0;
      p++;
      for (;;) {
        while (*p == ' ' || *p == '\t') p++;
        if (*p == 0 || *p == '\n' || *p == '\r') break;
        char *e;
        long a = strtol(p, &e, 10);
        if (e == p || k == 4) { rc = fail(err, errlen, path, lineno, "bad face"); break; }
        while (*e && *e != ' ' && *e != '\t' && *e != '\n' && *e != '\r') e++;   /* a/b/c */
        int nvert = v.n / 3;
        long i = a > 0 ? a - 1 : nvert + a;
        if (a == 0 || i < 0 || i >= nvert) { rc = fail(err, errlen, path, lineno, "face index out of range"); break; }
        idx[k++] = (int)i;
        p = e;
      }
      if (rc == 0 && k != 3) rc = fail(err, errlen, path, lineno, "face is not a triangle");
      for (int j = 0; rc == 0 && j < 3; j++) ipush(&t, idx[j]);
    }
  }
  m->nv = v.n / 3, m->v = v.v, m->nt = t.n / 3, m->t = t.v;
  return rc;
}

static int read_ply(FILE *f, const char *path, mc_mesh *m, char *err, size_t errlen) {
  char line[4096];
  int lineno = 0, nv = -1, nf = -1, nprop = 0, ix = -1, iy = -1, iz = -1, in_vertex = 0;
  while (fgets(line, sizeof line, f)) {
    lineno++;
    char w1[64], w2[64], w3[64];
    int k = sscanf(line, "%63s %63s %63s", w1, w2, w3);
    if (lineno == 1 && (k < 1 || strcmp(w1, "ply") != 0)) return fail(err, errlen, path, 1, "not a PLY file");
    if (k >= 1 && strcmp(w1, "end_header") == 0) break;
    if (k >= 2 && strcmp(w1, "format") == 0 && strcmp(w2, "ascii") != 0)
      return fail(err, errlen, path, lineno, "only ASCII PLY is read");
    if (k == 3 && strcmp(w1, "element") == 0) {
      in_vertex = strcmp(w2, "vertex") == 0;
      if (in_vertex) nv = atoi(w3);
      else if (strcmp(w2, "face") == 0) nf = atoi(w3);
      else return fail(err, errlen, path, lineno, "unknown element");
    } else if (k == 3 && strcmp(w1, "property") == 0 && in_vertex) {
      if (strcmp(w3, "x") == 0) ix = nprop;
      if (strcmp(w3, "y") == 0) iy = nprop;
      if (strcmp(w3, "z") == 0) iz = nprop;
      nprop++;
    }
  }
  if (nv < 0 || nf < 0 || ix < 0 || iy < 0 || iz < 0 || nprop > 16)
    return fail(err, errlen, path, lineno, "header lacks vertex x, y, z or faces");
  m->nv = nv, m->nt = nf;
  m->v = xmallocarray((size_t)nv * 3 + 1, sizeof *m->v);
  m->t = xmallocarray((size_t)nf * 3 + 1, sizeof *m->t);
  for (int i = 0; i < nv; i++) {
    double p[16];
    for (int j = 0; j < nprop; j++)
      if (fscanf(f, "%lf", &p[j]) != 1) return fail(err, errlen, path, 0, "short vertex list");
    m->v[3 * i] = p[ix], m->v[3 * i + 1] = p[iy], m->v[3 * i + 2] = p[iz];
  }
  for (int i = 0; i < nf; i++) {
    int c;
    if (fscanf(f, "%d", &c) != 1 || c != 3) return fail(err, errlen, path, 0, "face is not a triangle");
    for (int j = 0; j < 3; j++) {
      int a;
      if (fscanf(f, "%d", &a) != 1 || a < 0 || a >= nv) return fail(err, errlen, path, 0, "bad face index");
      m->t[3 * i + j] = a;
    }
  }
  return 0;
}

/* STL: the vertices of every triangle, then welded. */
typedef struct { float p[3]; int i; } fpt;
static int cmp_fpt(const void *a, const void *b) {
  const fpt *x = a, *y = b;
  for (int k = 0; k < 3; k++)
    if (x->p[k] != y->p[k]) return x->p[k] < y->p[k] ? -1 : 1;
  return x->i - y->i;
}

static int read_stl(FILE *f, const char *path, mc_mesh *m, char *err, size_t errlen) {
  if (fseek(f, 0, SEEK_END) != 0) return fail(err, errlen, path, 0, "cannot seek");
  long size = ftell(f);
  rewind(f);
  unsigned char head[84];
  fpt *pt = NULL;
  int n = 0;
  if (size >= 84 && fread(head, 1, 84, f) == 84) {
    uint32_t nt = (uint32_t)head[80] | (uint32_t)head[81] << 8 | (uint32_t)head[82] << 16 | (uint32_t)head[83] << 24;
    if ((long)nt * 50 + 84 == size) {   /* binary */
      n = (int)nt;
      pt = xmallocarray((size_t)n * 3 + 1, sizeof *pt);
      for (int i = 0; i < n; i++) {
        unsigned char b[50];
        if (fread(b, 1, 50, f) != 50) { free(pt); return fail(err, errlen, path, 0, "short file"); }
        for (int k = 0; k < 3; k++)
          for (int c = 0; c < 3; c++) {
            const unsigned char *q = b + 12 + 12 * k + 4 * c;
            uint32_t u = (uint32_t)q[0] | (uint32_t)q[1] << 8 | (uint32_t)q[2] << 16 | (uint32_t)q[3] << 24;
            memcpy(&pt[3 * i + k].p[c], &u, 4);
            pt[3 * i + k].i = 3 * i + k;
          }
      }
    }
  }
  if (!pt) {   /* ASCII: "vertex x y z" lines, three a facet */
    rewind(f);
    char line[4096];
    int cap = 0, k = 0;
    while (fgets(line, sizeof line, f)) {
      float x, y, z;
      if (sscanf(line, " vertex %f %f %f", &x, &y, &z) != 3) continue;
      if (k == cap) pt = xreallocarray(pt, (size_t)(cap = cap ? 2 * cap : 256), sizeof *pt);
      pt[k] = (fpt){{x, y, z}, k};
      k++;
    }
    if (k == 0 || k % 3) { free(pt); return fail(err, errlen, path, 0, "neither binary nor ASCII STL"); }
    n = k / 3;
  }
  qsort(pt, (size_t)n * 3, sizeof *pt, cmp_fpt);
  m->nt = n, m->nv = 0;
  m->t = xmallocarray((size_t)n * 3 + 1, sizeof *m->t);
  m->v = xmallocarray((size_t)n * 9 + 1, sizeof *m->v);
  for (int j = 0; j < 3 * n; j++) {
    if (j == 0 || memcmp(pt[j].p, pt[j - 1].p, sizeof pt[j].p) != 0) {
      for (int c = 0; c < 3; c++) m->v[3 * m->nv + c] = pt[j].p[c];
      m->nv++;
    }
    m->t[pt[j].i] = m->nv - 1;
  }
  free(pt);
  return 0;
}

int mc_read(const char *path, mc_mesh *m, char *err, size_t errlen) {
  memset(m, 0, sizeof *m);
  const char *dot = strrchr(path, '.');
  if (!dot) return fail(err, errlen, path, 0, "no extension");
  FILE *f = fopen(path, "rb");
  if (!f) {
    snprintf(err, errlen, "%s: cannot open (%s)", path, strerror(errno));
    return -1;
  }
  int rc;
  if (strcmp(dot, ".obj") == 0) rc = read_obj(f, path, m, err, errlen);
  else if (strcmp(dot, ".ply") == 0) rc = read_ply(f, path, m, err, errlen);
  else if (strcmp(dot, ".stl") == 0) rc = read_stl(f, path, m, err, errlen);
  else rc = fail(err, errlen, path, 0, "unknown extension");
  fclose(f);
  if (rc != 0) mc_free(m);
  return rc;
}

void mc_make(mc_mesh *m, const double *v, int nv, const int *t, int nt) {
  m->nv = nv, m->nt = nt;
  m->v = xmallocarray((size_t)nv * 3 + 1, sizeof *m->v);
  m->t = xmallocarray((size_t)nt * 3 + 1, sizeof *m->t);
  memcpy(m->v, v, (size_t)nv * 3 * sizeof *v);
  memcpy(m->t, t, (size_t)nt * 3 * sizeof *t);
}

void mc_free(mc_mesh *m) {
  free(m->v), free(m->t);
  memset(m, 0, sizeof *m);
}

/* ---------------------------------------------------------------- checks -- */

static int cmp_u64(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}
static uint64_t key(int a, int b) { return (uint64_t)(uint32_t)a << 32 | (uint32_t)b; }
static int has(const uint64_t *k, int n, uint64_t x) { return bsearch(&x, k, (size_t)n, sizeof *k, cmp_u64) != NULL; }
/* Occurrences of x in the sorted k[0..n). */
static int count_of(const uint64_t *k, int n, uint64_t x) {
  const uint64_t *p = bsearch(&x, k, (size_t)n, sizeof *k, cmp_u64);
  if (!p) return 0;
  const uint64_t *lo = p, *hi = p;
  while (lo > k && lo[-1] == x) lo--;
  while (hi + 1 < k + n && hi[1] == x) hi++;
  return (int)(hi - lo) + 1;
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void note(mc_report *r, const char *fmt, ...) {
  if (r->first[0]) return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(r->first, sizeof r->first, fmt, ap);
  va_end(ap);
}

typedef struct { int v[3], i; } tri3;
static int cmp_tri3(const void *a, const void *b) {
  const tri3 *x = a, *y = b;
  for (int k = 0; k < 3; k++)
    if (x->v[k] != y->v[k]) return x->v[k] < y->v[k] ? -1 : 1;
  return x->i - y->i;
}

static int find(int *parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

static void cross(const double *a, const double *b, const double *c, double *n) {
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
}

/* Solid angle of triangle abc seen from p (Van Oosterom and Strackee 1983):
 * positive when p is on the inner side of an outward-facing triangle. */
static double solid_angle(const double *p, const double *A, const double *B, const double *C) {
  double a[3], b[3], c[3];
  for (int k = 0; k < 3; k++) a[k] = A[k] - p[k], b[k] = B[k] - p[k], c[k] = C[k] - p[k];
  double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2], ac = a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
  double bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
  return 2 * atan2(det, la * lb * lc + ab * lc + ac * lb + bc * la);
}

/* Vertices sorted by coordinates, for exact look-ups. */
static const double *sort_v;
static int cmp_vidx(const void *a, const void *b) {
  const double *x = sort_v + 3 * *(const int *)a, *y = sort_v + 3 * *(const int *)b;
  for (int k = 0; k < 3; k++)
    if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
  return 0;
}
static int *sorted_vertices(const mc_mesh *m) {
  int *s = xmallocarray((size_t)m->nv + 1, sizeof *s);
  for (int i = 0; i < m->nv; i++) s[i] = i;
  sort_v = m->v;
  qsort(s, (size_t)m->nv, sizeof *s, cmp_vidx);
  return s;
}
/* The vertex at exactly p, or -1 (s from sorted_vertices). */
static int lookup(const mc_mesh *m, const int *s, const double *p) {
  int lo = 0, hi = m->nv - 1;
  while (lo <= hi) {
    int mid = (lo + hi) / 2, c = 0;
    const double *q = m->v + 3 * s[mid];
    for (int k = 0; k < 3 && !c; k++)
      if (q[k] != p[k]) c = q[k] < p[k] ? -1 : 1;
    if (c == 0) return s[mid];
    if (c < 0) lo = mid + 1;
    else hi = mid - 1;
  }
  return -1;
}

/* The power of two 2^-e that brings the largest |coordinate| of m into
 * [1/2, 1), and m's coordinates so scaled (exact, unless a coordinate is
 * over 2^1022 times smaller than the largest).  The checks and measures work
 * on that copy and give areas and volumes back by 2^2e and 2^3e, so that a
 * mesh scaled by 2^k is judged as at unit scale, its measures exactly 2^2k
 * and 2^3k as large (where a double holds them), and nothing under- or
 * overflows on meshes near 1e-300 or 1e300. */
static double *scaled_copy(const mc_mesh *m, int *e) {
  double big = 0;
  for (int i = 0; i < 3 * m->nv; i++) big = fmax(big, fabs(m->v[i]));
  *e = 0;
  if (big > 0) frexp(big, e);
  double *v = xmallocarray(3 * (size_t)m->nv + 1, sizeof *v);
  for (int i = 0; i < 3 * m->nv; i++) v[i] = ldexp(m->v[i], -*e);
  return v;
}

void mc_check(const mc_mesh *m, mc_report *r) {
  memset(r, 0, sizeof *r);
  int nt = m->nt, nv = m->nv, scale;
  const int *t = m->t;
  double *Vs = scaled_copy(m, &scale);
  const double *V = Vs;

  /* Directed edges: each once, and its reverse once. */
  uint64_t *de = xmallocarray((size_t)nt * 3 + 1, sizeof *de);
  for (int i = 0; i < nt; i++)
    for (int k = 0; k < 3; k++) de[3 * i + k] = key(t[3 * i + k], t[3 * i + (k + 1) % 3]);
  qsort(de, (size_t)nt * 3, sizeof *de, cmp_u64);
  for (int i = 0; i < 3 * nt; i++) {
    int a = (int)(de[i] >> 32), b = (int)(uint32_t)de[i];
    if (i + 1 < 3 * nt && de[i + 1] == de[i]) r->overused++, note(r, "edge %d->%d used by several triangles", a, b);
    if ((i == 0 || de[i - 1] != de[i]) && !has(de, 3 * nt, key(b, a)))
      r->boundary++, note(r, "edge %d->%d has no reverse", a, b);
  }
  /* Undirected edges, once each. */
  uint64_t *ue = xmallocarray((size_t)nt * 3 + 1, sizeof *ue);
  for (int i = 0; i < 3 * nt; i++) {
    int a = (int)(de[i] >> 32), b = (int)(uint32_t)de[i];
    ue[i] = a < b ? key(a, b) : key(b, a);
  }
  qsort(ue, (size_t)nt * 3, sizeof *ue, cmp_u64);
  int nue = 0;
  for (int i = 0; i < 3 * nt; i++)
    if (i == 0 || ue[i] != ue[i - 1]) ue[nue++] = ue[i];
  r->edges = nue;

  /* Degenerate and duplicate triangles; the area. */
  tri3 *tk = xmallocarray((size_t)nt + 1, sizeof *tk);
  for (int i = 0; i < nt; i++) {
    int a = t[3 * i], b = t[3 * i + 1], c = t[3 * i + 2];
    double n[3];
    cross(V + 3 * a, V + 3 * b, V + 3 * c, n);
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), e = 0;
    r->area += len / 2;
    for (int k = 0; k < 3; k++) {   /* the longest edge, squared */
      const double *p = V + 3 * t[3 * i + k], *q = V + 3 * t[3 * i + (k + 1) % 3];
      e = fmax(e, (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    }
    if (a == b || b == c || a == c || len <= 1e-12 * e)
      r->degenerate++, note(r, "triangle %d (%d %d %d) is degenerate", i, a, b, c);
    int s[3] = {a, b, c};   /* the vertex set, sorted */
    for (int x = 0; x < 2; x++)
      for (int y = x + 1; y < 3; y++)
        if (s[y] < s[x]) { int w = s[x]; s[x] = s[y]; s[y] = w; }
    tk[i] = (tri3){{s[0], s[1], s[2]}, i};
  }
  qsort(tk, (size_t)nt, sizeof *tk, cmp_tri3);
  for (int i = 1; i < nt; i++)
    if (memcmp(tk[i].v, tk[i - 1].v, sizeof tk[i].v) == 0)
      r->duplicate++, note(r, "triangles %d and %d have the same vertices", tk[i - 1].i, tk[i].i);
  free(tk);

  /* Vertices: unused, at the same point as another. */
  int *deg = xcalloc((size_t)nv + 1, sizeof *deg);
  for (int i = 0; i < 3 * nt; i++) deg[t[i]]++;
  for (int i = 0; i < nv; i++)
    if (!deg[i]) r->unused++, note(r, "vertex %d is in no triangle", i);
  int *sv = sorted_vertices(m);
  for (int i = 1; i < nv; i++) {
    sort_v = m->v;   /* the coordinates as given: exactly equal */
    if (cmp_vidx(&sv[i - 1], &sv[i]) == 0) r->samepoint++, note(r, "vertices %d and %d are at one point", sv[i - 1], sv[i]);
  }
  free(sv);

  /* Each vertex's fan: the edges b->c opposite it, one cycle through all. */
  int *start = xcalloc((size_t)nv + 2, sizeof *start);
  for (int v = 0; v < nv; v++) start[v + 1] = start[v] + deg[v];
  int *fill = xcalloc((size_t)nv + 1, sizeof *fill);
  uint64_t *link = xmallocarray((size_t)nt * 3 + 1, sizeof *link);
  for (int i = 0; i < nt; i++)
    for (int k = 0; k < 3; k++) {
      int v = t[3 * i + k];
      link[start[v] + fill[v]++] = key(t[3 * i + (k + 1) % 3], t[3 * i + (k + 2) % 3]);
    }
  for (int v = 0; v < nv; v++) {
    int d = deg[v];
    if (!d) continue;
    uint64_t *L = link + start[v];
    qsort(L, (size_t)d, sizeof *L, cmp_u64);
    int ok = d >= 3;
    for (int i = 1; i < d && ok; i++)
      if (L[i] >> 32 == L[i - 1] >> 32) ok = 0;   /* a vertex starts two link edges */
    if (ok) {   /* follow b -> c from the first edge: back after exactly d steps */
      uint32_t first = (uint32_t)(L[0] >> 32), cur = first;
      int steps = 0;
      do {
        int lo = 0, hi = d - 1, at = -1;
        while (lo <= hi) {
          int mid = (lo + hi) / 2;
          uint32_t b = (uint32_t)(L[mid] >> 32);
          if (b == cur) { at = mid; break; }
          if (b < cur) lo = mid + 1;
          else hi = mid - 1;
        }
        if (at < 0) { ok = 0; break; }
        cur = (uint32_t)L[at];
        steps++;
      } while (cur != first && steps <= d);
      if (steps != d) ok = 0;
    }
    if (!ok) r->pinched++, note(r, "vertex %d: its triangles are not one closed fan", v);
  }
  free(link), free(fill), free(start);

  r->manifold = !r->boundary && !r->overused && !r->pinched && !r->degenerate && !r->duplicate &&
                !r->unused && !r->samepoint;

  /* Components through shared vertices; per component V - E + F and volume. */
  int *parent = xmallocarray((size_t)nv + 1, sizeof *parent);
  for (int i = 0; i < nv; i++) parent[i] = i;
  for (int i = 0; i < nt; i++) {
    int a = find(parent, t[3 * i]);
    for (int k = 1; k < 3; k++) {
      int b = find(parent, t[3 * i + k]);
      if (a != b) parent[b] = a;
    }
  }
  int *comp = xmallocarray((size_t)nv + 1, sizeof *comp);
  for (int i = 0; i < nv; i++) comp[i] = -1;
  for (int i = 0; i < nv; i++)
    if (deg[i] && comp[find(parent, i)] < 0) comp[find(parent, i)] = r->ncomp++;
  int nc = r->ncomp;
  r->chi = xcalloc((size_t)nc + 1, sizeof *r->chi);
  r->cvol = xcalloc((size_t)nc + 1, sizeof *r->cvol);
  r->wind = xcalloc((size_t)nc + 1, sizeof *r->wind);
  int *vc = xmallocarray((size_t)nv + 1, sizeof *vc);   /* vertex -> component */
  for (int i = 0; i < nv; i++) vc[i] = deg[i] ? comp[find(parent, i)] : -1;
  for (int i = 0; i < nv; i++)
    if (vc[i] >= 0) r->chi[vc[i]]++;
  for (int i = 0; i < nue; i++) r->chi[vc[(int)(ue[i] >> 32)]]--;
  double c0[3] = {0, 0, 0};   /* a centre, against cancellation */
  if (nv) {
    for (int k = 0; k < 3; k++) {
      double lo = V[k], hi = V[k];
      for (int i = 1; i < nv; i++) lo = fmin(lo, V[3 * i + k]), hi = fmax(hi, V[3 * i + k]);
      c0[k] = (lo + hi) / 2;
    }
  }
  for (int i = 0; i < nt; i++) {
    int cc = vc[t[3 * i]];
    r->chi[cc]++;
    double p[3][3];
    for (int k = 0; k < 3; k++)
      for (int j = 0; j < 3; j++) p[k][j] = V[3 * t[3 * i + k] + j] - c0[j];
    double n[3] = {p[1][1] * p[2][2] - p[1][2] * p[2][1], p[1][2] * p[2][0] - p[1][0] * p[2][2],
                   p[1][0] * p[2][1] - p[1][1] * p[2][0]};
    r->cvol[cc] += (p[0][0] * n[0] + p[0][1] * n[1] + p[0][2] * n[2]) / 6;
  }
  for (int c = 0; c < nc; c++) r->volume += r->cvol[c];

  /* Winding of the other components around one vertex of each. */
  r->outward = 1;
  int *rep = xmallocarray((size_t)nc + 1, sizeof *rep);
  for (int c = 0; c < nc; c++) rep[c] = -1;
  for (int i = 0; i < nt; i++)
    if (rep[vc[t[3 * i]]] < 0) rep[vc[t[3 * i]]] = t[3 * i];
  for (int c = 0; c < nc; c++) {
    double w = 0;
    const double *p = V + 3 * rep[c];
    if (nc > 1)
      for (int i = 0; i < nt; i++)
        if (vc[t[3 * i]] != c) w += solid_angle(p, V + 3 * t[3 * i], V + 3 * t[3 * i + 1], V + 3 * t[3 * i + 2]);
    w /= 4 * PI;
    r->wind[c] = (int)lround(w);
    int ok = fabs(w - r->wind[c]) < 0.01 &&
             ((r->cvol[c] > 0 && r->wind[c] == 0) || (r->cvol[c] < 0 && r->wind[c] == 1));
    if (!ok) r->outward = 0, note(r, "component %d faces inward (winding of the others around it %d)", c, r->wind[c]);
  }
  free(rep), free(vc), free(comp), free(parent), free(deg), free(ue), free(de);
  r->area = ldexp(r->area, 2 * scale);
  r->volume = ldexp(r->volume, 3 * scale);
  for (int c = 0; c < nc; c++) r->cvol[c] = ldexp(r->cvol[c], 3 * scale);
  free(Vs);
}

void mc_report_free(mc_report *r) {
  free(r->chi), free(r->cvol), free(r->wind);
  memset(r, 0, sizeof *r);
}

/* --------------------------------------------------------- input fidelity -- */

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static int on_plane(const mc_fidelity *f, double z) {
  return bsearch(&z, f->planes, (size_t)f->nplanes, sizeof z, cmp_d) != NULL;
}

void mc_check_input(const mc_mesh *m, const mc_poly *c, int nc, mc_fidelity *f) {
  memset(f, 0, sizeof *f);
  /* The planes. */
  f->planes = xmallocarray((size_t)nc + 1, sizeof *f->planes);
  for (int i = 0; i < nc; i++) f->planes[i] = c[i].z;
  qsort(f->planes, (size_t)nc, sizeof *f->planes, cmp_d);
  for (int i = 0; i < nc; i++)
    if (f->nplanes == 0 || f->planes[i] != f->planes[f->nplanes - 1]) f->planes[f->nplanes++] = f->planes[i];
  f->slab = xcalloc((size_t)f->nplanes + 1, sizeof *f->slab);

  /* Segments and points, by exact coordinates. */
  int *sv = sorted_vertices(m);
  uint64_t *ue = xmallocarray((size_t)m->nt * 3 + 1, sizeof *ue);
  for (int i = 0; i < m->nt; i++)
    for (int k = 0; k < 3; k++) {
      int a = m->t[3 * i + k], b = m->t[3 * i + (k + 1) % 3];
      ue[3 * i + k] = a < b ? key(a, b) : key(b, a);
    }
  qsort(ue, (size_t)m->nt * 3, sizeof *ue, cmp_u64);
  char *input = xcalloc((size_t)m->nv + 1, 1);   /* vertex is an input point */
  for (int i = 0; i < nc; i++) {
    int n = c[i].n, *id = xmallocarray((size_t)n, sizeof *id);
    for (int j = 0; j < n; j++) {
      double p[3] = {c[i].x[j], c[i].y[j], c[i].z};
      id[j] = lookup(m, sv, p);
      f->points++;
      if (id[j] < 0) f->absent++;
      else input[id[j]] = 1;
    }
    /* A segment whose reverse is a segment of the same contour too is a
     * keyhole's channel, walked out and back: it need not be an edge. */
    uint64_t *dk = xmallocarray((size_t)n + 1, sizeof *dk);
    int nd = 0;
    for (int j = 0; j < n; j++)
      if (id[j] >= 0 && id[(j + 1) % n] >= 0) dk[nd++] = key(id[j], id[(j + 1) % n]);
    qsort(dk, (size_t)nd, sizeof *dk, cmp_u64);
    for (int j = 0; j < n; j++) {
      int a = id[j], b = id[(j + 1) % n];
      f->segments++;
      if (a >= 0 && b >= 0 && has(dk, nd, key(b, a))) f->channel++;
      else if (a < 0 || b < 0 || count_of(ue, 3 * m->nt, a < b ? key(a, b) : key(b, a)) == 0) f->missing++;
    }
    free(dk);
    free(id);
  }
  for (int v = 0; v < m->nv; v++)
    if (!input[v] && on_plane(f, m->v[3 * v + 2])) f->strays++;

  /* Slabs: the flux of (x - cx, y - cy, 0) / 2 through each triangle, on
   * the mesh scaled as in mc_check (then back by 2^3e). */
  int scale;
  double *vs = scaled_copy(m, &scale), cx = 0, cy = 0;
  for (int v = 0; v < m->nv; v++) cx += vs[3 * v] / m->nv, cy += vs[3 * v + 1] / m->nv;
  int K = f->nplanes;
  for (int i = 0; i < m->nt; i++) {
    const double *p[3] = {vs + 3 * m->t[3 * i], vs + 3 * m->t[3 * i + 1], vs + 3 * m->t[3 * i + 2]};
    const double *z[3] = {m->v + 3 * m->t[3 * i], m->v + 3 * m->t[3 * i + 1], m->v + 3 * m->t[3 * i + 2]};
    double zlo = fmin(z[0][2], fmin(z[1][2], z[2][2])), zhi = fmax(z[0][2], fmax(z[1][2], z[2][2]));
    if (zlo == zhi) continue;   /* horizontal: no flux */
    double n[3];
    cross(p[0], p[1], p[2], n);
    double mx = (p[0][0] + p[1][0] + p[2][0]) / 3 - cx, my = (p[0][1] + p[1][1] + p[2][1]) / 3 - cy;
    double flux = (n[0] * mx + n[1] * my) / 4;
    if (K == 0 || zhi <= f->planes[0] || zlo >= f->planes[K - 1]) {
      f->outside += flux;
      continue;
    }
    int lo = 0, hi = K - 1;   /* the last plane <= zlo */
    while (lo < hi) {
      int mid = (lo + hi + 1) / 2;
      if (f->planes[mid] <= zlo) lo = mid;
      else hi = mid - 1;
    }
    if (f->planes[lo] <= zlo && lo + 1 < K && zhi <= f->planes[lo + 1]) f->slab[lo] += flux;
    else f->crossing++;
  }
  for (int k = 0; k + 1 < K; k++) f->slab[k] = ldexp(f->slab[k], 3 * scale);
  f->outside = ldexp(f->outside, 3 * scale);
  free(vs), free(input), free(ue), free(sv);
}

void mc_fidelity_free(mc_fidelity *f) {
  free(f->planes), free(f->slab);
  memset(f, 0, sizeof *f);
}
