/* test_meshcheck.c -- the independent mesh checker (tests/meshcheck.c) on
 * hand-made meshes: a tetrahedron, a cube, a torus, two cubes, a cube in a
 * cube, and broken variants of them, each of which it must catch; its
 * readers on hand-written OBJ, PLY and STL; the input-fidelity check. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tests/check.h"
#include "tests/meshcheck.h"
#include "util/xmem.h"

#define PI 3.14159265358979323846

/* A growing mesh for building test cases. */
typedef struct { int nv, nt; double v[3 * 400]; int t[3 * 800]; } build;

static int addv(build *b, double x, double y, double z) {
  b->v[3 * b->nv] = x, b->v[3 * b->nv + 1] = y, b->v[3 * b->nv + 2] = z;
  return b->nv++;
}
static void addt(build *b, int x, int y, int z) {
  b->t[3 * b->nt] = x, b->t[3 * b->nt + 1] = y, b->t[3 * b->nt + 2] = z;
  b->nt++;
}

/* The unit tetrahedron, outward; returns its first vertex. */
static int tetra(build *b, double ox, double oy, double oz) {
  int o = addv(b, ox, oy, oz);
  addv(b, ox + 1, oy, oz), addv(b, ox, oy + 1, oz), addv(b, ox, oy, oz + 1);
  addt(b, o, o + 2, o + 1), addt(b, o, o + 1, o + 3), addt(b, o, o + 3, o + 2), addt(b, o + 1, o + 2, o + 3);
  return o;
}

/* A cube of side s at (ox, oy, oz): vertex x + 2y + 4z; flip != 0 faces inward. */
static void cube(build *b, double ox, double oy, double oz, double s, int flip) {
  int o = b->nv;
  for (int i = 0; i < 8; i++) addv(b, ox + s * (i & 1), oy + s * (i >> 1 & 1), oz + s * (i >> 2 & 1));
  static const int f[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                               {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  for (int i = 0; i < 12; i++)
    if (flip) addt(b, o + f[i][0], o + f[i][2], o + f[i][1]);
    else addt(b, o + f[i][0], o + f[i][1], o + f[i][2]);
}

/* A torus (R, r) around z, nu x nv quads, outward: d/du x d/dv points out. */
static void torus(build *b, int nu, int nv, double R, double r) {
  int o = b->nv;
  for (int i = 0; i < nu; i++)
    for (int j = 0; j < nv; j++) {
      double u = 2 * PI * i / nu, w = 2 * PI * j / nv;
      addv(b, (R + r * cos(w)) * cos(u), (R + r * cos(w)) * sin(u), r * sin(w));
    }
  for (int i = 0; i < nu; i++)
    for (int j = 0; j < nv; j++) {
      int a = o + i * nv + j, bb = o + (i + 1) % nu * nv + j;
      int c = o + (i + 1) % nu * nv + (j + 1) % nv, d = o + i * nv + (j + 1) % nv;
      addt(b, a, bb, c), addt(b, a, c, d);
    }
}

static void check_build(const build *b, mc_report *r) {
  mc_mesh m;
  mc_make(&m, b->v, b->nv, b->t, b->nt);
  mc_check(&m, r);
  mc_free(&m);
}

static void test_good(void) {
  mc_report r;
  build *b = xcalloc(1, sizeof *b);

  tetra(b, 0, 0, 0);
  check_build(b, &r);
  CHECK(r.manifold && r.outward, "tetrahedron: %s", r.first);
  CHECK(r.ncomp == 1 && r.chi[0] == 2 && r.edges == 6, "tetrahedron: %d components, chi %d, %d edges", r.ncomp, r.chi[0], r.edges);
  CHECK(fabs(r.volume - 1.0 / 6) < 1e-15, "tetrahedron volume %.17g", r.volume);
  CHECK(fabs(r.area - (1.5 + sqrt(3) / 2)) < 1e-14, "tetrahedron area %.17g", r.area);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);
  cube(b, 0.5, -2, 3, 1, 0);
  check_build(b, &r);
  CHECK(r.manifold && r.outward && r.ncomp == 1 && r.chi[0] == 2, "cube: %s, chi %d", r.first, r.chi[0]);
  CHECK(fabs(r.volume - 1) < 1e-14 && fabs(r.area - 6) < 1e-14, "cube volume %.17g area %.17g", r.volume, r.area);
  CHECK(r.edges == 18, "cube edges %d", r.edges);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);
  torus(b, 12, 8, 2, 0.7);
  check_build(b, &r);
  CHECK(r.manifold && r.outward, "torus: %s", r.first);
  CHECK(r.ncomp == 1 && r.chi[0] == 0, "torus: %d components, chi %d (genus 1 gives 0)", r.ncomp, r.chi[0]);
  /* An inscribed polyhedron: a little less than 2 pi^2 R r^2, more than half of it. */
  double vt = 2 * PI * PI * 2 * 0.49;
  CHECK(r.volume < vt && r.volume > 0.8 * vt, "torus volume %g against %g", r.volume, vt);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* two disjoint cubes */
  cube(b, 0, 0, 0, 1, 0), cube(b, 3, 0, 0, 2, 0);
  check_build(b, &r);
  CHECK(r.manifold && r.outward && r.ncomp == 2, "two cubes: %s, %d components", r.first, r.ncomp);
  CHECK(r.ncomp == 2 && r.chi[0] == 2 && r.chi[1] == 2 && fabs(r.cvol[0] - 1) < 1e-14 && fabs(r.cvol[1] - 8) < 1e-13,
        "two cubes: chi %d %d, volumes %g %g", r.chi[0], r.chi[1], r.cvol[0], r.cvol[1]);
  CHECK(fabs(r.volume - 9) < 1e-13, "two cubes volume %g", r.volume);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* a cube with a cubic cavity, its faces into the cavity */
  cube(b, 0, 0, 0, 3, 0), cube(b, 1, 1, 1, 1, 1);
  check_build(b, &r);
  CHECK(r.manifold && r.outward && r.ncomp == 2, "cube with a cavity: %s", r.first);
  CHECK(r.ncomp == 2 && r.wind[0] == 0 && r.wind[1] == 1 && r.cvol[1] < 0, "cavity: winding %d %d, volume %g",
        r.wind[0], r.wind[1], r.cvol[1]);
  CHECK(fabs(r.volume - 26) < 1e-12, "cube with a cavity: volume %g", r.volume);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* and an island in the cavity: three shells */
  cube(b, 0, 0, 0, 5, 0), cube(b, 1, 1, 1, 3, 1), cube(b, 2, 2, 2, 1, 0);
  check_build(b, &r);
  CHECK(r.manifold && r.outward && r.ncomp == 3, "island in a cavity: %s", r.first);
  CHECK(r.ncomp == 3 && r.wind[2] == 0 && fabs(r.volume - (125 - 27 + 1)) < 1e-11, "island: winding %d, volume %g",
        r.ncomp == 3 ? r.wind[2] : -9, r.volume);
  mc_report_free(&r);
  free(b);
}

static void test_broken(void) {
  mc_report r;
  build *b = xcalloc(1, sizeof *b);

  cube(b, 0, 0, 0, 1, 0);   /* a missing triangle */
  b->nt--;
  check_build(b, &r);
  CHECK(!r.manifold && r.boundary == 3 && r.overused == 0, "missing triangle: manifold %d, boundary %d, overused %d",
        r.manifold, r.boundary, r.overused);
  CHECK(r.first[0] != 0, "missing triangle: no message");
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* a flipped triangle */
  cube(b, 0, 0, 0, 1, 0);
  int w = b->t[3 * 5 + 1];
  b->t[3 * 5 + 1] = b->t[3 * 5 + 2], b->t[3 * 5 + 2] = w;
  check_build(b, &r);
  CHECK(!r.manifold && r.overused == 3 && r.boundary == 3, "flipped triangle: overused %d, boundary %d", r.overused, r.boundary);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* two tetrahedra sharing a vertex: a pinch */
  tetra(b, 0, 0, 0);
  int o = addv(b, -1, 0, 0);
  addv(b, 0, -1, 0), addv(b, 0, 0, -1);
  /* the point reflection of the first: every face turned round */
  addt(b, 0, o, o + 1), addt(b, 0, o + 2, o), addt(b, 0, o + 1, o + 2), addt(b, o, o + 2, o + 1);
  check_build(b, &r);
  CHECK(!r.manifold && r.pinched == 1 && r.boundary == 0 && r.overused == 0,
        "pinched vertex: manifold %d, pinched %d, boundary %d, overused %d", r.manifold, r.pinched, r.boundary, r.overused);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* two tetrahedra sharing an edge: 4 triangles on it */
  tetra(b, 0, 0, 0);   /* the edge 0-1 along x */
  o = addv(b, 0, -1, 0);
  addv(b, 0, 0, -1);
  /* the first turned half round the x axis: y, z -> -y, -z */
  addt(b, 0, o, 1), addt(b, 0, 1, o + 1), addt(b, 0, o + 1, o), addt(b, 1, o, o + 1);
  check_build(b, &r);
  CHECK(!r.manifold && r.overused == 2, "edge of 4 triangles: manifold %d, overused %d", r.manifold, r.overused);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* a triangle twice, once each way round */
  tetra(b, 0, 0, 0);
  addt(b, 0, 2, 1), addt(b, 0, 1, 2);
  check_build(b, &r);
  CHECK(!r.manifold && r.duplicate == 2, "duplicate triangles: %d", r.duplicate);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* a zero-area triangle closing a split edge */
  tetra(b, 0, 0, 0);
  int mid = addv(b, 0.5, 0, 0);
  b->nt = 0;
  addt(b, 0, 2, 1), addt(b, 0, 3, 2), addt(b, 1, 2, 3);
  addt(b, 0, mid, 3), addt(b, mid, 1, 3), addt(b, 1, mid, 0);
  check_build(b, &r);
  CHECK(!r.manifold && r.degenerate == 1 && r.boundary == 0 && r.overused == 0, "zero-area triangle: degenerate %d",
        r.degenerate);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* a repeated vertex in a triangle */
  tetra(b, 0, 0, 0);
  addt(b, 1, 1, 2);
  check_build(b, &r);
  CHECK(!r.manifold && r.degenerate == 1, "repeated vertex: degenerate %d", r.degenerate);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* inside out */
  cube(b, 0, 0, 0, 1, 1);
  check_build(b, &r);
  CHECK(r.manifold && !r.outward && r.volume < 0, "inward cube: outward %d, volume %g", r.outward, r.volume);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* a cavity facing the wrong way */
  cube(b, 0, 0, 0, 3, 0), cube(b, 1, 1, 1, 1, 0);
  check_build(b, &r);
  CHECK(r.manifold && !r.outward, "cavity facing out: outward %d", r.outward);
  mc_report_free(&r);

  memset(b, 0, sizeof *b);   /* a vertex in no triangle; two vertices at one point */
  tetra(b, 0, 0, 0);
  addv(b, 5, 5, 5);
  check_build(b, &r);
  CHECK(!r.manifold && r.unused == 1, "unused vertex: %d", r.unused);
  mc_report_free(&r);
  memset(b, 0, sizeof *b);
  tetra(b, 0, 0, 0), tetra(b, 0, 0, 0);
  check_build(b, &r);
  CHECK(!r.manifold && r.samepoint == 4, "vertices at one point: %d", r.samepoint);
  mc_report_free(&r);
  free(b);
}

static int write_file(const char *path, const void *data, size_t n) {
  FILE *f = fopen(path, "wb");
  if (!f) return -1;
  size_t w = fwrite(data, 1, n, f);
  return fclose(f) == 0 && w == n ? 0 : -1;
}

static void put32(unsigned char *p, uint32_t x) {
  p[0] = (unsigned char)x, p[1] = (unsigned char)(x >> 8), p[2] = (unsigned char)(x >> 16), p[3] = (unsigned char)(x >> 24);
}

static void test_readers(const char *dir) {
  char path[512], err[512];
  mc_mesh m;
  mc_report r;
  /* OBJ: comments, normals, a/b/c and negative indices, 0.1 exactly as written. */
  const char *obj = "# a tetrahedron\nv 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nvn 0 0 1\nv 0 0 0.1\n"
                    "f 1 3 2\nf 1/1/1 2/2/2 4/4/4\nf 1//1 4//1 3//1\nf -3 -2 -1\n";
  snprintf(path, sizeof path, "%s/t.obj", dir);
  CHECK(write_file(path, obj, strlen(obj)) == 0, "write %s", path);
  CHECK(mc_read(path, &m, err, sizeof err) == 0, "read OBJ: %s", err);
  CHECK(m.nv == 4 && m.nt == 4 && m.v[3] == 0.1 && m.t[9] == 1 && m.t[11] == 3, "OBJ: %d vertices, %d triangles", m.nv, m.nt);
  mc_check(&m, &r);
  CHECK(r.manifold && r.outward && fabs(r.volume - 0.001 / 6) < 1e-17, "OBJ tetrahedron: %s %g", r.first, r.volume);
  mc_report_free(&r), mc_free(&m);

  const char *bad[] = {"v 0 0 0\nv 1 0 0\nf 1 2 3\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\n", "v 0 0 x\n"};
  const char *why[] = {":3: face index out of range", ":5: face is not a triangle", ":1: bad vertex"};
  for (int i = 0; i < 3; i++) {
    CHECK(write_file(path, bad[i], strlen(bad[i])) == 0, "write %s", path);
    err[0] = 0;
    CHECK(mc_read(path, &m, err, sizeof err) == -1 && strstr(err, why[i]), "bad OBJ %d: '%s', expected '%s'", i, err, why[i]);
  }

  /* PLY: an extra property, the face list. */
  const char *ply = "ply\nformat ascii 1.0\ncomment x\nelement vertex 4\nproperty double x\nproperty float q\n"
                    "property double y\nproperty double z\nelement face 4\nproperty list uchar int vertex_indices\n"
                    "end_header\n0 9 0 0\n1 9 0 0\n0 9 1 0\n0 9 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  snprintf(path, sizeof path, "%s/t.ply", dir);
  CHECK(write_file(path, ply, strlen(ply)) == 0, "write %s", path);
  CHECK(mc_read(path, &m, err, sizeof err) == 0, "read PLY: %s", err);
  mc_check(&m, &r);
  CHECK(m.nv == 4 && r.manifold && r.outward && fabs(r.volume - 1.0 / 6) < 1e-15, "PLY tetrahedron: %s", r.first);
  mc_report_free(&r), mc_free(&m);
  const char *bply = "ply\nformat binary_little_endian 1.0\nend_header\n";
  CHECK(write_file(path, bply, strlen(bply)) == 0, "write %s", path);
  CHECK(mc_read(path, &m, err, sizeof err) == -1 && strstr(err, "only ASCII PLY"), "binary PLY: %s", err);

  /* Binary STL of the cube: 36 corners welded back into 8 vertices. */
  build *b = xcalloc(1, sizeof *b);
  cube(b, 0, 0, 0, 1, 0);
  unsigned char *stl = xcalloc(84 + 50 * 12, 1);
  memcpy(stl, "test cube", 9);
  put32(stl + 80, 12);
  for (int i = 0; i < 12; i++)
    for (int k = 0; k < 3; k++)
      for (int c = 0; c < 3; c++) {
        float x = (float)b->v[3 * b->t[3 * i + k] + c];
        uint32_t u;
        memcpy(&u, &x, 4);
        put32(stl + 84 + 50 * i + 12 + 12 * k + 4 * c, u);
      }
  snprintf(path, sizeof path, "%s/t.stl", dir);
  CHECK(write_file(path, stl, 84 + 50 * 12) == 0, "write %s", path);
  CHECK(mc_read(path, &m, err, sizeof err) == 0, "read STL: %s", err);
  mc_check(&m, &r);
  CHECK(m.nv == 8 && m.nt == 12 && r.manifold && r.outward && fabs(r.volume - 1) < 1e-12, "STL cube: %d vertices, %s",
        m.nv, r.first);
  mc_report_free(&r), mc_free(&m);
  /* ASCII STL of the tetrahedron. */
  const char *astl = "solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
                     "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
                     "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
                     "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid t\n";
  CHECK(write_file(path, astl, strlen(astl)) == 0, "write %s", path);
  CHECK(mc_read(path, &m, err, sizeof err) == 0, "read ASCII STL: %s", err);
  mc_check(&m, &r);
  CHECK(m.nv == 4 && m.nt == 4 && r.manifold && r.outward, "ASCII STL tetrahedron: %d vertices, %s", m.nv, r.first);
  mc_report_free(&r), mc_free(&m);
  free(stl), free(b);
}

static void test_fidelity(void) {
  build *b = xcalloc(1, sizeof *b);
  cube(b, 0, 0, 0, 1, 0);
  mc_mesh m;
  mc_make(&m, b->v, b->nv, b->t, b->nt);
  mc_fidelity f;

  /* The bottom and top squares: every segment an edge; the sides are one slab. */
  double sx[] = {0, 1, 1, 0}, sy[] = {0, 0, 1, 1};
  mc_poly sq[2] = {{4, 0, sx, sy}, {4, 1, sx, sy}};
  mc_check_input(&m, sq, 2, &f);
  CHECK(f.segments == 8 && f.missing == 0 && f.points == 8 && f.absent == 0 && f.strays == 0 && f.crossing == 0,
        "cube squares: %d/%d segments missing, %d absent, %d strays, %d crossing", f.missing, f.segments, f.absent, f.strays, f.crossing);
  CHECK(f.nplanes == 2 && fabs(f.slab[0] - 1) < 1e-15 && f.outside == 0, "cube slab %g, outside %g", f.slab[0], f.outside);
  mc_fidelity_free(&f);

  /* A triangle whose long side is no edge (the bottom's diagonal is 0-3);
   * and three of the top's four corners, closed along the top's diagonal. */
  double tx[] = {0, 1, 0}, ty[] = {0, 0, 1};
  mc_poly tri[2] = {{3, 0, tx, ty}, {3, 1, sx, sy}};
  mc_check_input(&m, tri, 2, &f);
  CHECK(f.segments == 6 && f.missing == 1 && f.absent == 0 && f.strays == 2,
        "triangle: %d missing (1: the side across; the top's closing side is its diagonal), %d strays (2: a corner "
        "on each plane)", f.missing, f.strays);
  mc_fidelity_free(&f);

  /* A point that is not a vertex, off by one unit in the last place. */
  double px[] = {0, 1, nextafter(1, 2), 0};
  mc_poly off = {4, 0, px, sy};
  mc_check_input(&m, &off, 1, &f);
  CHECK(f.absent == 1 && f.missing == 2, "point off by one ulp: %d absent, %d missing", f.absent, f.missing);
  mc_fidelity_free(&f);

  /* A plane through the middle: the side triangles cross it. */
  mc_poly mid[3] = {{4, 0, sx, sy}, {4, 0.5, sx, sy}, {4, 1, sx, sy}};
  mc_check_input(&m, mid, 3, &f);
  CHECK(f.crossing == 8 && f.absent == 4, "plane across: %d crossing, %d absent", f.crossing, f.absent);
  mc_fidelity_free(&f);
  mc_free(&m);

  /* A double pyramid over the square at z = 0: all of it beyond the one plane. */
  memset(b, 0, sizeof *b);
  for (int i = 0; i < 4; i++) addv(b, sx[i], sy[i], 0);
  int top = addv(b, 0.5, 0.5, 1), bot = addv(b, 0.5, 0.5, -2);
  for (int i = 0; i < 4; i++) addt(b, i, (i + 1) % 4, top), addt(b, (i + 1) % 4, i, bot);
  mc_make(&m, b->v, b->nv, b->t, b->nt);
  mc_report r;
  mc_check(&m, &r);
  mc_check_input(&m, sq, 1, &f);
  CHECK(r.manifold && fabs(r.volume - 1) < 1e-15 && fabs(f.outside - 1) < 1e-15 && f.missing == 0,
        "double pyramid: %s, volume %g, outside %g", r.first, r.volume, f.outside);
  mc_report_free(&r), mc_fidelity_free(&f), mc_free(&m);
  free(b);
}

int main(void) {
  char dir[] = "/tmp/tilesim-meshcheck.XXXXXX";
  if (!mkdtemp(dir)) {
    perror("mkdtemp");
    return 1;
  }
  test_good();
  test_broken();
  test_readers(dir);
  test_fidelity();
  const char *names[] = {"t.obj", "t.ply", "t.stl"};
  for (int i = 0; i < 3; i++) {
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, names[i]);
    unlink(p);
  }
  rmdir(dir);
  return check_done("test_meshcheck");
}
