/* test_mesh.c -- meshes from tilings: closed, consistently oriented, outward;
 * volumes against an independent formula; caps; the file writers. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "surface/cap.h"
#include "tests/check.h"
#include "input/gen.h"
#include "surface/mesh.h"
#include "surface/meshio.h"
#include "util/rng.h"
#include "algo/tiling.h"
#include "util/xmem.h"

/* Edges as (a, b) directed; sort and compare. */
typedef struct { int a, b; } edge;
static int cmp_edge(const void *x, const void *y) {
  const edge *p = x, *q = y;
  if (p->a != q->a) return p->a - q->a;
  return p->b - q->b;
}

/* Closed and consistently oriented: every directed edge exactly once and its
 * reverse exactly once.  Returns the number of undirected edges, or -1. */
static int closed_edges(const mesh *me) {
  int ne = 3 * me->nt;
  edge *e = xmallocarray((size_t)ne, sizeof *e);
  for (int t = 0; t < me->nt; t++)
    for (int k = 0; k < 3; k++) e[3 * t + k] = (edge){me->t[t][k], me->t[t][(k + 1) % 3]};
  qsort(e, (size_t)ne, sizeof *e, cmp_edge);
  int ok = 1;
  for (int i = 0; i < ne && ok; i++) {
    if (i + 1 < ne && e[i].a == e[i + 1].a && e[i].b == e[i + 1].b) ok = 0;   /* twice */
    edge r = {e[i].b, e[i].a};
    if (!bsearch(&r, e, (size_t)ne, sizeof *e, cmp_edge)) ok = 0;             /* unmatched */
  }
  free(e);
  return ok ? ne / 2 : -1;
}

/* The slab's volume by a formula that shares nothing with mesh.c: the section
 * at height fraction l is the polygon of the points (1-l) P_i + l Q_j of the
 * path's spans; its area is quadratic in l, so Simpson's rule is exact. */
static double simpson_volume(const contour *P, const contour *Q, const tiling *t) {
  int L = t->m + t->n;
  vec2 *sec = xmallocarray((size_t)L, sizeof *sec);
  double A[3];
  for (int s = 0; s < 3; s++) {
    double l = s / 2.0;
    int r = t->start, c = 0;
    for (int k = 0; k < L; k++) {
      int i = t->transposed ? c % t->n : r % t->m, j = t->transposed ? r % t->m : c % t->n;
      sec[k] = (vec2){(1 - l) * P->pt[i].x + l * Q->pt[j].x, (1 - l) * P->pt[i].y + l * Q->pt[j].y};
      if (t->col[k + 1] == t->col[k]) r++;
      else c++;
    }
    A[s] = 0.5 * geom_area2(sec, L);
  }
  free(sec);
  return fabs(Q->z - P->z) * (A[0] + 4 * A[1] + A[2]) / 6;
}

static void random_stack(rng *g, contour_stack *s, int shape) {
  s->n = s->nslices = rng_int(g, 2, 6);
  s->c = xcalloc((size_t)s->n, sizeof *s->c);
  double z = rng_uniform(g) * 10, dz = rng_int(g, 0, 1) ? 1 + rng_uniform(g) : -(1 + rng_uniform(g));
  for (int i = 0; i < s->n; i++) {
    contour *c = &s->c[i];
    c->n = rng_int(g, 3, 40);
    c->pt = xmallocarray((size_t)c->n, sizeof *c->pt);
    if (shape == 0) gen_star(g, c->pt, c->n, rng_uniform(g), rng_uniform(g), 5 + 3 * rng_uniform(g), 0.45);
    else gen_regular(c->pt, c->n, 0, 0, 4, rng_uniform(g));
    c->z = z;
    c->slice = dz > 0 ? i : s->n - 1 - i;
    z += dz;
  }
}

static void check_stacks(rng *g) {
  for (int trial = 0; trial < 300; trial++) {
    contour_stack s;
    random_stack(g, &s, trial % 5 == 4);
    cost_kind kind = trial % 3 == 2 ? COST_SPAN : COST_AREA;
    mesh me;
    mesh_init(&me, &s);
    double sum_vol = 0, sum_area = 0;
    int bad_simpson = 0, bad_cost = 0;
    for (int i = 0; i + 1 < s.n; i++) {
      tiling t;
      const contour *P = &s.c[i], *Q = &s.c[i + 1];
      tiling_solve(P->pt, P->n, P->z, Q->pt, Q->n, Q->z, kind, -1, &t);
      double area, vol;
      mesh_add_band(&me, &s, i, &t, &area, &vol);
      double sv = simpson_volume(P, Q, &t);
      if (fabs(vol - sv) > 1e-9 * fabs(sv)) bad_simpson++;
      if (kind == COST_AREA && fabs(area - t.cost) > 1e-9 * t.cost) bad_cost++;
      sum_vol += vol;
      sum_area += area;
      tiling_free(&t);
    }
    CHECK(bad_simpson == 0, "trial %d: %d slab volumes disagree with Simpson's formula", trial, bad_simpson);
    CHECK(bad_cost == 0, "trial %d: %d bands' triangle areas do not sum to their cost", trial, bad_cost);
    double cap_area = mesh_add_caps(&me, &s);
    int ne = closed_edges(&me);
    CHECK(ne > 0, "trial %d: the capped mesh is not closed and consistently oriented", trial);
    CHECK(ne < 0 || me.nv - ne + me.nt == 2, "trial %d: Euler characteristic %d, not 2", trial, me.nv - ne + me.nt);
    double vol = mesh_volume(&me);
    CHECK(vol > 0, "trial %d: volume %g is not positive (triangles face inward?)", trial, vol);
    CHECK(fabs(vol - sum_vol) <= 1e-9 * fabs(sum_vol), "trial %d: mesh volume %.17g, slabs sum to %.17g", trial, vol, sum_vol);
    double a = mesh_area(&me);
    CHECK(fabs(a - (sum_area + cap_area)) <= 1e-9 * a, "trial %d: mesh area %.17g, parts %.17g", trial, a, sum_area + cap_area);
    double caps_true = 0.5 * (geom_area2(s.c[0].pt, s.c[0].n) + geom_area2(s.c[s.n - 1].pt, s.c[s.n - 1].n));
    CHECK(fabs(cap_area - caps_true) <= 1e-9 * caps_true, "trial %d: caps' area %.17g, polygons %.17g", trial, cap_area, caps_true);
    mesh_free(&me);
    contour_stack_free(&s);
  }
}

/* A prism of identical regular polygons: volume = area x height, exactly. */
static void check_prism(void) {
  contour_stack s = {3, xcalloc(3, sizeof(contour)), 3};
  for (int i = 0; i < 3; i++) {
    s.c[i].n = 12;
    s.c[i].pt = xmallocarray(12, sizeof(vec2));
    gen_regular(s.c[i].pt, 12, 1, 2, 3, 0.1);
    s.c[i].z = 2.0 * i;
    s.c[i].slice = i;
  }
  mesh me;
  mesh_init(&me, &s);
  for (int i = 0; i < 2; i++) {
    tiling t;
    tiling_solve(s.c[i].pt, 12, s.c[i].z, s.c[i + 1].pt, 12, s.c[i + 1].z, COST_AREA, -1, &t);
    double a, v;
    mesh_add_band(&me, &s, i, &t, &a, &v);
    tiling_free(&t);
  }
  mesh_add_caps(&me, &s);
  double want = 0.5 * geom_area2(s.c[0].pt, 12) * 4.0;
  CHECK(fabs(mesh_volume(&me) - want) < 1e-12 * want, "prism volume %.17g, want %.17g", mesh_volume(&me), want);
  CHECK(closed_edges(&me) > 0, "prism not closed");
  mesh_free(&me);
  contour_stack_free(&s);
}

/* Ear clipping on random simple polygons, convex and not. */
static void check_caps(rng *g) {
  int bad = 0;
  for (int trial = 0; trial < 500; trial++) {
    int n = rng_int(g, 3, 120);
    vec2 *p = xmallocarray((size_t)n, sizeof *p);
    gen_star(g, p, n, 0, 0, 10, trial % 2 ? 0.8 : 0.05);   /* star-shaped: simple */
    int (*tri)[3] = xmallocarray((size_t)n, sizeof *tri);
    int nt = cap_triangulate(p, n, tri);
    double sum = 0;
    int neg = 0;
    int *use = xcalloc((size_t)n, sizeof *use);
    for (int k = 0; k < nt; k++) {
      vec2 t3[3] = {p[tri[k][0]], p[tri[k][1]], p[tri[k][2]]};
      double a2 = geom_area2(t3, 3);
      if (a2 < 0) neg++;
      sum += a2;
      for (int e = 0; e < 3; e++) {   /* polygon edge i -> i+1 */
        int u = tri[k][e], v = tri[k][(e + 1) % 3];
        if (v == (u + 1) % n) use[u]++;
      }
    }
    int once = 1;
    for (int i = 0; i < n; i++) once &= use[i] == 1;
    double area = geom_area2(p, n);
    if (nt != n - 2 || neg || !once || fabs(sum - area) > 1e-9 * area) bad++;
    free(p), free(tri), free(use);
  }
  CHECK(bad == 0, "%d of 500 polygons badly triangulated", bad);
}

/* A square with a triangular hole of side e joined by a keyhole bridge (the
 * composite a flat cap clips): for e from 1 down to 1e-12 of the square, every
 * triangle counter-clockwise and their areas summing to the region's, so no
 * two overlap.  Every ear that touches a hole of 1e-8 is a sliver by the
 * relative test; the clipper must still find real ears. */
static void check_cap_tiny_hole(void) {
  int bad = 0;
  for (double e = 1; e >= 1e-12; e /= 10) {
    vec2 A = {0, 0}, H = {4, 4};
    vec2 p[9] = {A, {10, 0}, {10, 10}, {0, 10}, A, H, {4, 4 + e}, {4 + e, 4}, H};
    int tri[7][3];
    int nt = cap_triangulate(p, 9, tri);
    double sum = 0;
    int neg = 0;
    for (int k = 0; k < nt; k++) {
      vec2 t3[3] = {p[tri[k][0]], p[tri[k][1]], p[tri[k][2]]};
      double a2 = geom_area2(t3, 3);
      neg += a2 < 0;
      sum += a2;
    }
    double area = 200 - e * e;   /* twice the region's area */
    if (nt != 7 || neg || fabs(sum - area) > 1e-12 * area) {
      bad++;
      fprintf(stderr, "hole of side %g: %d triangles, %d clockwise, twice the area %.17g, want %.17g\n",
              e, nt, neg, sum, area);
    }
  }
  CHECK(bad == 0, "%d of 13 keyholed squares badly triangulated", bad);
}

static unsigned char *slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char *b = xmalloc((size_t)n + 1);
  *len = fread(b, 1, (size_t)n, f);
  b[*len] = 0;
  fclose(f);
  return b;
}

static float getf(const unsigned char *b) {
  uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
  float x;
  memcpy(&x, &u, 4);
  return x;
}

static void check_writers(rng *g) {
  contour_stack s;
  random_stack(g, &s, 0);
  mesh me;
  mesh_init(&me, &s);
  for (int i = 0; i + 1 < s.n; i++) {
    tiling t;
    tiling_solve(s.c[i].pt, s.c[i].n, s.c[i].z, s.c[i + 1].pt, s.c[i + 1].n, s.c[i + 1].z, COST_AREA, -1, &t);
    double a, v;
    mesh_add_band(&me, &s, i, &t, &a, &v);
    tiling_free(&t);
  }
  mesh_add_caps(&me, &s);
  char dir[] = "/tmp/tilesim-meshXXXXXX", path[300], err[400];
  CHECK(mkdtemp(dir) != NULL, "mkdtemp");
  const char *ext[] = {"obj", "ply", "stl", "OBJ"};
  for (int f = 0; f < 4; f++) {
    snprintf(path, sizeof path, "%s/m.%s", dir, ext[f]);
    CHECK(meshio_write(&me, path, err, sizeof err) == 0, "write %s: %s", path, err);
    size_t len, len2;
    unsigned char *b = slurp(path, &len);
    CHECK(b != NULL, "%s not written", path);
    if (!b) continue;
    CHECK(meshio_write(&me, path, err, sizeof err) == 0, "rewrite");
    unsigned char *b2 = slurp(path, &len2);
    CHECK(b2 && len == len2 && memcmp(b, b2, len) == 0, "%s: two writes differ", path);
    free(b2);
    if (f == 2) {   /* binary STL: header, count, 50 bytes a triangle */
      CHECK(len == 84 + 50 * (size_t)me.nt, "STL size %zu for %d triangles", len, me.nt);
      CHECK(memcmp(b, "solid", 5) != 0, "binary STL must not begin with 'solid'");
      uint32_t n = (uint32_t)b[80] | (uint32_t)b[81] << 8 | (uint32_t)b[82] << 16 | (uint32_t)b[83] << 24;
      CHECK(n == (uint32_t)me.nt, "STL count %u", n);
      int bad = 0;
      for (int t = 0; t < me.nt; t++)
        for (int k = 0; k < 3; k++) {
          const unsigned char *q = b + 84 + 50 * t + 12 + 12 * k;
          vec3 v = me.v[me.t[t][k]];
          if (getf(q) != (float)v.x || getf(q + 4) != (float)v.y || getf(q + 8) != (float)v.z) bad++;
        }
      CHECK(bad == 0, "STL: %d vertices differ", bad);
    } else {   /* text: read back every vertex and face exactly */
      char *p = (char *)b;
      int nv = 0, nt = 0, bad = 0;
      if (f == 1) {
        char want[200];
        snprintf(want, sizeof want, "element vertex %d\n", me.nv);
        CHECK(strstr(p, want) != NULL, "PLY header lacks '%s'", want);
        CHECK(strncmp(p, "ply\nformat ascii 1.0\n", 21) == 0, "PLY magic");
        p = strstr(p, "end_header\n");
        p = p ? p + 11 : (char *)b + len;
      }
      while (*p) {
        char *e = strchr(p, '\n');
        if (!e) break;
        *e = 0;
        double x, y, z;
        int i, j, k, three;
        if (f != 1 && sscanf(p, "v %lf %lf %lf", &x, &y, &z) == 3) {
          vec3 v = me.v[nv++];
          bad += x != v.x || y != v.y || z != v.z;
        } else if (f != 1 && sscanf(p, "f %d %d %d", &i, &j, &k) == 3) {
          bad += i - 1 != me.t[nt][0] || j - 1 != me.t[nt][1] || k - 1 != me.t[nt][2];
          nt++;
        } else if (f == 1 && nv < me.nv && sscanf(p, "%lf %lf %lf", &x, &y, &z) == 3) {
          vec3 v = me.v[nv++];
          bad += x != v.x || y != v.y || z != v.z;
        } else if (f == 1 && sscanf(p, "%d %d %d %d", &three, &i, &j, &k) == 4) {
          bad += three != 3 || i != me.t[nt][0] || j != me.t[nt][1] || k != me.t[nt][2];
          nt++;
        }
        p = e + 1;
      }
      CHECK(nv == me.nv && nt == me.nt && bad == 0, "%s: read back %d/%d vertices, %d/%d faces, %d differ",
            ext[f], nv, me.nv, nt, me.nt, bad);
    }
    free(b);
    unlink(path);
  }
  /* A directory that is not there: an error, and no file. */
  snprintf(path, sizeof path, "%s/nowhere/m.obj", dir);
  CHECK(meshio_write(&me, path, err, sizeof err) != 0 && strstr(err, "nowhere/m.obj"), "write into a missing directory: %s", err);
  snprintf(path, sizeof path, "%s/m.xyz", dir);
  CHECK(meshio_write(&me, path, err, sizeof err) != 0 && strstr(err, "unknown mesh format"), "unknown format: %s", err);
  CHECK(meshio_format_of("a.b/c") == MESHIO_NONE && meshio_format_of("x.Stl") == MESHIO_STL, "format names");
  CHECK(rmdir(dir) == 0, "temporary files left in %s", dir);
  mesh_free(&me);
  contour_stack_free(&s);
}

int main(void) {
  rng g;
  rng_seed(&g, 77);
  check_stacks(&g);
  check_prism();
  check_caps(&g);
  check_cap_tiny_hole();
  check_writers(&g);
  return check_done("test_mesh");
}
