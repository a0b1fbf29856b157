/* test_solids.c -- the analytic-solid slicer (tests/solids.c) against closed
 * forms; and, run as `test_solids --tile TILE` (tests/cli_solids.sh does),
 * ./tile end to end on the sliced solids, judged by the independent mesh
 * checker (tests/meshcheck.c).
 *
 * Without arguments: section counts along z, section areas against pi r^2,
 * the lens formula and 4 pi R sqrt(r^2 - z^2); volumes against the closed
 * forms of whole solids, and partial volumes against a quadrature of the
 * section areas; every polygon point on the solid's surface; polygon areas
 * against the closed-form inscribed areas, deficits O(1/N^2); the stacks
 * well posed (no crossing contours, no near touch); sliced volumes converging
 * to the closed forms; the .contours writer and reader; the scrambler.
 *
 * With --tile: for every solid, even and uneven slices, ./tile --caps must
 * give a closed, outward 2-manifold with the solid's components and Euler
 * characteristics, through every input segment, within 2% of the solid's
 * volume between the first and last slices, and with the report's identity
 * mesh volume = sum of the bands' volumes (flat caps add none), band by band
 * against the mesh's own slabs.  And a second encoding of each stack (and of
 * tinypatient_0) must give byte-identical output.
 *
 * Tools: `test_solids --gen SOLID K N even|uneven OUT.contours` writes a
 * solid's stack; `test_solids --check MESH STACK [SOLID]` checks a mesh. */
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/check.h"
#include "util/csvtab.h"
#include "tests/meshcheck.h"
#include "tests/solids.h"
#include "tests/tilejudge.h"
#include "util/xmem.h"

#define PI 3.14159265358979323846

/* Stacks with several contours a slice, end to end: the multi-contour solids (two spheres,
 * tori, cavities, an island), crossing correspondences, tinypatient_0, apex
 * caps and the second encodings.  On since ./tile takes several contours per
 * slice; 0 leaves only what a one-contour-per-slice ./tile could do
 * (TILESIM_SOLIDS_ALL=1 in the environment then turns them on again). */
static const int several_per_slice = 1;

/* The stacks the end-to-end tests tile: K planes, about N points a contour. */
enum { K_SINGLE = 30, K_MULTI = 72, N_POINTS = 64 };

/* ------------------------------------------------------------ unit tests -- */

static int runs_of(int s, const double *z, int K, int *runs, int max) {
  int n = 0;
  for (int k = 0; k < K; k++) {
    int c = solid_section_count(s, z[k]);
    if (n == 0 || runs[n - 1] != c) {
      if (n == max) return -1;
      runs[n++] = c;
    }
  }
  return n;
}

/* Along the planes of the end-to-end stacks the sections go as the solid says. */
static void test_counts(void) {
  static const struct { const char *name; int n, runs[6]; } want[] = {
      {"sphere", 1, {1}}, {"cone", 1, {1}}, {"cylinder", 1, {1}},
      {"spheres_overlapping", 3, {2, 1, 2}}, {"spheres_separate", 3, {1, 2, 1}},
      {"torus_across", 3, {1, 2, 1}}, {"torus_along", 1, {2}},
      {"hollow_sphere", 3, {1, 2, 1}}, {"island", 5, {1, 2, 3, 2, 1}},
  };
  CHECK(solid_count() == (int)(sizeof want / sizeof want[0]), "%d solids", solid_count());
  for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
    int s = solid_find(want[i].name);
    CHECK(s >= 0, "no solid %s", want[i].name);
    if (s < 0) continue;
    for (int uneven = 0; uneven < 2; uneven++) {
      int K = solid_get(s)->multi ? K_MULTI : K_SINGLE, runs[16];
      double *z = xmallocarray((size_t)K, sizeof *z);
      solid_planes(s, K, uneven, z);
      int n = runs_of(s, z, K, runs, 16);
      int ok = n == want[i].n;
      for (int j = 0; ok && j < n; j++) ok = runs[j] == want[i].runs[j];
      CHECK(ok, "%s: %d runs of section counts along z, expected %d", want[i].name, n, want[i].n);
      int multi = 0;
      for (int j = 0; j < n; j++) multi |= runs[j] > 1;
      CHECK(multi == solid_get(s)->multi, "%s: multi flag", want[i].name);
      for (int k = 1; k < K; k++) CHECK(z[k] > z[k - 1], "%s: planes not increasing at %d", want[i].name, k);
      free(z);
    }
  }
}

static double rel(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

/* Section areas against formulas written out here. */
static void test_areas(void) {
  int sp = solid_find("sphere"), ov = solid_find("spheres_overlapping"), ta = solid_find("torus_along");
  int tx = solid_find("torus_across"), ho = solid_find("hollow_sphere");
  for (double z = -0.95; z < 0.96; z += 0.05) {
    double rho2 = 1 - z * z;
    CHECK(rel(solid_section_area(sp, z), PI * rho2) < 1e-14, "sphere area at %g", z);
    double rho = sqrt(rho2), d = 0.6, lens = rho > d ? 2 * rho2 * acos(d / rho) - 2 * d * sqrt(rho2 - d * d) : 0;
    if (fabs(rho - d) > 1e-6)   /* (not where the spheres' sections touch: acos near 1) */
      CHECK(rel(solid_section_area(ov, z), 2 * PI * rho2 - lens) < 1e-13, "overlapping spheres area at %g: %.17g against %.17g",
          z, solid_section_area(ov, z), 2 * PI * rho2 - lens);
    double hz = z - 0.05, cav = fabs(hz) < 0.5 ? PI * (0.25 - hz * hz) : 0;
    CHECK(rel(solid_section_area(ho, z), PI * rho2 - cav) < 1e-13, "hollow sphere area at %g", z);
  }
  for (double z = -0.44; z < 0.45; z += 0.04)
    CHECK(rel(solid_section_area(ta, z), 4 * PI * 1 * sqrt(0.45 * 0.45 - z * z)) < 1e-13, "torus_along area at %g", z);
  /* torus_across: the area (a quadrature across y) against the derivative of
   * the volume (a different quadrature, around the tube). */
  for (double z = -1.4; z < 1.41; z += 0.1) {
    double h = 1e-4, dv = (solid_volume(tx, -2, z + h) - solid_volume(tx, -2, z - h)) / (2 * h);
    CHECK(rel(solid_section_area(tx, z), dv) < 1e-6, "torus_across at %g: area %.12g, dV/dz %.12g", z,
          solid_section_area(tx, z), dv);
  }
}

/* Composite Simpson over the exact section areas, n intervals. */
static double simpson_areas(int s, double a, double b, int n) {
  double h = (b - a) / n, sum = solid_section_area(s, a) + solid_section_area(s, b);
  for (int i = 1; i < n; i++) sum += (i % 2 ? 4 : 2) * solid_section_area(s, a + i * h);
  return sum * h / 3;
}

static void test_volumes(void) {
  static const struct { const char *name; double v; } whole[] = {
      {"sphere", 4 * PI / 3},
      {"spheres_separate", 4 * PI / 3 * (1 + 0.729)},
      {"hollow_sphere", 4 * PI / 3 * (1 - 0.125)},
      {"island", 4 * PI / 3 * (1.728 - 0.614125 + 0.091125)},
      {"torus_along", 2 * PI * PI * 1 * 0.2025},
      {"torus_across", 2 * PI * PI * 1 * 0.2025},
      /* two unit spheres 1.2 apart, less their lens pi (4R + D)(2R - D)^2 / 12 */
      {"spheres_overlapping", 8 * PI / 3 - PI * 5.2 * 0.64 / 12},
      {"cone", 2 * PI / 3},
  };
  for (size_t i = 0; i < sizeof whole / sizeof whole[0]; i++) {
    int s = solid_find(whole[i].name);
    double v = solid_volume(s, -3, 3);
    CHECK(rel(v, whole[i].v) < 1e-10, "%s: whole volume %.15g, closed form %.15g", whole[i].name, v, whole[i].v);
  }
  int cy = solid_find("cylinder");
  CHECK(rel(solid_volume(cy, 0, 1.5), PI * 0.64 * 1.5) < 1e-15, "cylinder volume");
  /* Between the first and last planes: against Simpson over the areas. */
  for (int s = 0; s < solid_count(); s++) {
    const solid_info *in = solid_get(s);
    double v = solid_volume(s, in->za, in->zb), q = simpson_areas(s, in->za, in->zb, 2000);
    CHECK(rel(v, q) < 1e-5, "%s: volume %.12g, Simpson over the section areas %.12g", in->name, v, q);
    double mid = (in->za + in->zb) / 2;   /* additive */
    CHECK(rel(solid_volume(s, in->za, mid) + solid_volume(s, mid, in->zb), v) < 1e-11, "%s: volume not additive", in->name);
  }
}

/* The polygons: on the surface, inscribed, their areas as closed forms say. */
static void test_polygons(void) {
  for (int s = 0; s < solid_count(); s++) {
    const solid_info *in = solid_get(s);
    for (int uneven = 0; uneven < 2; uneven++) {
      int K = in->multi ? K_MULTI : K_SINGLE;
      double *z = xmallocarray((size_t)K, sizeof *z);
      solid_planes(s, K, uneven, z);
      sl_stack st;
      solid_slice(s, z, K, N_POINTS, 1, &st);
      double far = 0, area_err = 0;
      int arcs = 0, bad_sign = 0, bad_bound = 0;
      for (int k = 0; k < st.nslice; k++) {
        double sum = 0;
        for (int i = st.first[k]; i < st.first[k] + st.count[k]; i++) {
          const sl_contour *c = &st.c[i];
          for (int j = 0; j < c->n; j++) far = fmax(far, solid_surface_distance(s, c->x[j], c->y[j], c->z));
          double a = sl_shoelace(c), def = c->region - a;
          sum += c->region;
          if (!isnan(c->exact)) arcs++, area_err = fmax(area_err, fabs(a - c->exact) / fabs(c->region));
          /* inscribed: the polygon has less area than its curve, the same sign */
          if (!(def * c->region > 0) || !((c->depth % 2 == 0) == (a > 0))) bad_sign++;
          /* an inscribed polygon of n points loses (2 pi / n)^2 / 6 of a circle; up to
             4 times that for two near-full arcs of a union (twice the turning), more on
             the torus curves' tight ends */
          if (fabs(def) > 6 * (2 * PI / c->n) * (2 * PI / c->n) / 6 * fabs(c->region)) bad_bound++;
        }
        CHECK(rel(sum, solid_section_area(s, z[k])) < 1e-12 || fabs(sum) < 1e-12, "%s: slice %d's curves' areas", in->name, k);
      }
      CHECK(far < 1e-12, "%s: a polygon point %.3g off the surface", in->name, far);
      CHECK(area_err < 1e-12, "%s: shoelace against the closed-form polygon area: %.3g", in->name, area_err);
      CHECK(bad_sign == 0 && bad_bound == 0, "%s: %d polygons not inside their curves, %d losing too much", in->name,
            bad_sign, bad_bound);
      CHECK((s == solid_find("torus_across")) == (arcs == 0), "%s: %d arc polygons", in->name, arcs);
      /* Well posed for a tiler: no crossing or touching, nothing nearly touching. */
      CHECK(sl_stack_crossings(&st) == 0, "%s: contours cross", in->name);
      double margin = sl_stack_margin(&st);
      CHECK(margin > 0.03, "%s (%s): contours come within %g of each other", in->name, uneven ? "uneven" : "even", margin);
      sl_stack_free(&st);
      free(z);
    }
  }
  /* Torus curves (no closed form): the deficit shrinks as 1/N^2. */
  int tx = solid_find("torus_across");
  double zs[3] = {-1.0, 0.2, 0.7};   /* one curve, two curves, one curve with a waist */
  for (int i = 0; i < 3; i++) {
    double d[2];
    for (int h = 0; h < 2; h++) {
      sl_stack st;
      solid_slice(tx, &zs[i], 1, 64 << h, 0, &st);
      double poly = 0;
      for (int j = 0; j < st.n; j++) poly += sl_shoelace(&st.c[j]);
      d[h] = solid_section_area(tx, zs[i]) - poly;
      sl_stack_free(&st);
    }
    CHECK(d[0] > 0 && d[1] > 0 && d[0] / d[1] > 3.5 && d[0] / d[1] < 4.5, "torus_across at z=%g: deficits %g, %g", zs[i],
          d[0], d[1]);
  }
}

/* Sliced volumes (trapezoids over the polygons' areas) converge to the closed
 * forms: halving the spacing and doubling the points cuts the error by 3+. */
static void test_convergence(void) {
  const char *names[] = {"sphere", "torus_along", "torus_across", "hollow_sphere", "spheres_overlapping"};
  for (int i = 0; i < 5; i++) {
    int s = solid_find(names[i]);
    const solid_info *in = solid_get(s);
    double v = solid_volume(s, in->za, in->zb), e[3];
    for (int h = 0; h < 3; h++) {
      int K = (20 << h) + 1, N = 32 << h;
      double *z = xmallocarray((size_t)K, sizeof *z);
      solid_planes(s, K, 0, z);
      sl_stack st;
      solid_slice(s, z, K, N, 0, &st);
      double *A = xcalloc((size_t)K, sizeof *A), tv = 0;
      for (int k = 0; k < K; k++)
        for (int j = st.first[k]; j < st.first[k] + st.count[k]; j++) A[k] += sl_shoelace(&st.c[j]);
      for (int k = 0; k + 1 < K; k++) tv += (z[k + 1] - z[k]) * (A[k] + A[k + 1]) / 2;
      e[h] = fabs(tv - v) / v;
      sl_stack_free(&st);
      free(A), free(z);
    }
    CHECK(e[1] < e[0] / 3 && e[2] < e[1] / 3 && e[2] < 2e-3, "%s: sliced volume errors %.3g, %.3g, %.3g", names[i], e[0],
          e[1], e[2]);
  }
}

static void test_io(const char *dir) {
  char path[512], err[512];
  int s = solid_find("island");
  double z[9];
  solid_planes(s, 9, 1, z);
  sl_stack a, b, c;
  solid_slice(s, z, 9, 20, 1, &a);
  snprintf(path, sizeof path, "%s/io.contours", dir);
  CHECK(sl_stack_write(&a, path) == 0, "write %s", path);
  CHECK(sl_stack_read(path, &b, err, sizeof err) == 0, "read back: %s", err);
  int same = a.n == b.n && a.nslice == b.nslice;
  for (int i = 0; same && i < a.n; i++) {
    same = a.c[i].n == b.c[i].n && a.c[i].z == b.c[i].z;
    for (int j = 0; same && j < a.c[i].n; j++) same = a.c[i].x[j] == b.c[i].x[j] && a.c[i].y[j] == b.c[i].y[j];
  }
  for (int k = 0; same && k < a.nslice; k++) same = a.count[k] == b.count[k] && a.z[k] == b.z[k];
  CHECK(same, "the stack read back differs from the one written");

  /* The scrambler: per slice the same contours, each reversed and turned. */
  sl_stack_scramble(&b, 7, &c);
  int ok = c.nslice == b.nslice && c.n == b.n, moved = 0;
  for (int k = 0; ok && k < b.nslice; k++) {
    ok = c.count[k] == b.count[k] && c.z[k] == b.z[k];
    for (int i = 0; ok && i < c.count[k]; i++) {
      const sl_contour *q = &c.c[c.first[k] + i];
      int found = 0;
      for (int j = 0; j < b.count[k] && !found; j++) {
        const sl_contour *p = &b.c[b.first[k] + j];
        if (p->n != q->n) continue;
        for (int r = 0; r < p->n && !found; r++) {   /* q[t] = p[(r - t) mod n] */
          int eq = 1;
          for (int t = 0; t < p->n && eq; t++) {
            int src = ((r - t) % p->n + p->n) % p->n;
            eq = q->x[t] == p->x[src] && q->y[t] == p->y[src];
          }
          if (eq) found = 1, moved += r != 0 || j != i;
        }
      }
      ok = found;
    }
  }
  CHECK(ok && moved > a.n / 2, "scrambled stack is not the same contours reversed and turned (%d moved)", moved);
  sl_stack_free(&c);
  /* A repeated closing point is dropped first (tinypatient_0's first contour has one). */
  sl_stack t;
  CHECK(sl_stack_read("tests/data/slicerrt/tinypatient_0.contours", &t, err, sizeof err) == 0, "%s", err);
  CHECK(t.nslice == 9 && t.n == 18 && t.c[0].n == 27, "tinypatient_0: %d slices, %d contours", t.nslice, t.n);
  sl_stack_scramble(&t, 1, &c);
  CHECK(c.n == 18 && c.nslice == 9 && (c.c[0].n == 26 || c.c[1].n == 26), "tinypatient_0 scrambled: closing point kept");
  sl_stack_clean(&t);
  CHECK(t.c[0].n == 26 && t.c[1].n == 5, "tinypatient_0 cleaned: %d and %d points", t.c[0].n, t.c[1].n);
  sl_stack_free(&c), sl_stack_free(&t);
  unlink(path);
  sl_stack_free(&a), sl_stack_free(&b);
}

/* ------------------------------------------------------------ end to end -- */

static char tmpdir[64];

/* Run argv with stdout and stderr to files; the exit status, or 128 + signal. */
static int run(char *const argv[], const char *out, const char *errf) {
  fflush(stdout), fflush(stderr);
  pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    int fo = open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644), fe = open(errf, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fo < 0 || fe < 0) _exit(126);
    dup2(fo, 1), dup2(fe, 2);
    close(fo), close(fe);
    execv(argv[0], argv);
    _exit(127);
  }
  int st;
  if (waitpid(pid, &st, 0) < 0) return -1;
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

static char *slurp(const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 1 << 16, len = 0;
  char *b = xmalloc(cap);
  size_t r;
  while ((r = fread(b + len, 1, cap - len, f)) > 0)
    if ((len += r) == cap) b = xrealloc(b, cap *= 2);
  fclose(f);
  *n = len;
  return b;
}

static int same_file(const char *p, const char *q) {
  size_t n, m;
  char *a = slurp(p, &n), *b = slurp(q, &m);
  int same = a && b && n == m && memcmp(a, b, n) == 0;
  free(a), free(b);
  return same;
}

static void firstline(const char *path, char *buf, size_t n) {
  FILE *f = fopen(path, "r");
  buf[0] = 0;
  if (f) {
    if (!fgets(buf, (int)n, f)) buf[0] = 0;
    fclose(f);
  }
  buf[strcspn(buf, "\n")] = 0;
}

static void path_of(char *buf, size_t n, const char *base, const char *ext) {
  snprintf(buf, n, "%s/%s%s", tmpdir, base, ext);
}

/* Judge a mesh and report of solid s's stack st (planes z[0..K)): the
 * checks above, and the volume.  Returns the mesh's volume and area. */
static void judge(const char *name, int s, const sl_stack *st, const double *z, int K, const char *obj,
                  const char *csv, double *vol, double *area) {
  mc_report r;
  mc_fidelity f;
  tilejudge_mesh(name, obj, st, s, 1, &r, &f);
  /* The volume: the solid's between the first and last planes, against the
   * mesh's there (apex caps beyond the end planes left out).  The mesh
   * differs by the polygons' deficit (about (2 pi / N)^2 / 6 = 0.16% at
   * N = 64), the linear bands between curved slices (~0.1%), and where the
   * topology changes (branches, caps of parts that begin between two
   * planes: a fraction of a band each, a band being 1-2% at 72 slices). */
  double v = solid_volume(s, z[0], z[K - 1]), mv = r.volume - f.outside, e = (mv - v) / v;
  CHECK(fabs(e) < 0.02, "%s: mesh volume %.9g between the end planes, the solid's %.9g (%+.2f%%)", name, mv, v, 100 * e);
  printf("cli_solids: %-32s %2d slices %3d contours: volume %+.3f%% of the solid's, %d components\n", name, K, st->n,
         100 * e, r.ncomp);
  tilejudge_report(name, csv, &r, &f);
  *vol = r.volume, *area = r.area;
  mc_report_free(&r), mc_fidelity_free(&f);
}

static void solid_stack(int s, int uneven, double **z, int *K, sl_stack *st) {
  *K = solid_get(s)->multi ? K_MULTI : K_SINGLE;
  *z = xmallocarray((size_t)*K, sizeof **z);
  solid_planes(s, *K, uneven, *z);
  solid_slice(s, *z, *K, N_POINTS, 1, st);
}

/* Tile one solid's stack and check everything; its volume and area, or NAN.
 * apex != 0: with --cap-style apex. */
static void e2e_solid(const char *tile, int s, int uneven, int apex, double *vol, double *area) {
  const solid_info *in = solid_get(s);
  char name[96], base[96], stack[512], obj[512], csv[512], errf[512];
  snprintf(name, sizeof name, "%s %s%s", in->name, uneven ? "uneven" : "even", apex ? " apex" : "");
  snprintf(base, sizeof base, "%s_%d", in->name, uneven);
  path_of(obj, sizeof obj, base, ".obj"), path_of(csv, sizeof csv, base, ".csv");
  path_of(errf, sizeof errf, base, ".err"), path_of(stack, sizeof stack, base, ".contours");
  double *z;
  int K;
  sl_stack st;
  solid_stack(s, uneven, &z, &K, &st);
  CHECK(sl_stack_write(&st, stack) == 0, "%s: cannot write %s", name, stack);
  char *argv[] = {(char *)tile, stack, "--caps", "-q", "-o", obj, NULL, NULL, NULL};
  if (apex) argv[6] = "--cap-style", argv[7] = "apex";
  int rc = run(argv, csv, errf);
  char line[512];
  firstline(errf, line, sizeof line);
  CHECK(rc == 0, "%s: ./tile exit status %d: %s", name, rc, line);
  *vol = *area = NAN;
  if (rc == 0) judge(name, s, &st, z, K, obj, csv, vol, area);
  unlink(obj), unlink(csv), unlink(errf), unlink(stack);
  sl_stack_free(&st);
  free(z);
}

/* The solids whose surface is made of parts with one contour per slice each
 * (two separate spheres; a sphere and its cavity; and the ball in it): tile
 * every part alone with ./tile as it is, turn the cavities' surfaces inside
 * out, and put the meshes and reports together.  That surface must pass
 * every check, which tests the checks' multi-component paths today; and,
 * once ./tile takes the whole stack, whose junctions here are all
 * one to one or ends, its mesh must have this one's volume and area. */
static int decomposable(int s) {
  return s == solid_find("spheres_separate") || s == solid_find("hollow_sphere") || s == solid_find("island");
}

static void e2e_decomposed(const char *tile, int s, int uneven, double *vol, double *area) {
  const solid_info *in = solid_get(s);
  int sep = s == solid_find("spheres_separate");
  char name[96], stack[512], obj[512], csv[512], errf[512], mobj[512], mcsv[512];
  snprintf(name, sizeof name, "%s %s by parts", in->name, uneven ? "uneven" : "even");
  path_of(stack, sizeof stack, "part", ".contours"), path_of(obj, sizeof obj, "part", ".obj");
  path_of(csv, sizeof csv, "part", ".csv"), path_of(errf, sizeof errf, "part", ".err");
  path_of(mobj, sizeof mobj, "merged", ".obj"), path_of(mcsv, sizeof mcsv, "merged", ".csv");
  double *z;
  int K;
  sl_stack st;
  solid_stack(s, uneven, &z, &K, &st);
  int nparts = 0, base = 0, ok = 1;
  double meshvol = 0;
  FILE *fo = fopen(mobj, "w"), *fc = fopen(mcsv, "w");
  CHECK(fo && fc, "cannot write %s, %s", mobj, mcsv);
  if (!fo || !fc) {
    ok = 0;
    goto done;
  }
  fprintf(fc, "pair,z0,z1,volume\n");
  /* The parts: by depth (outer, cavity, island), or left and right. */
  for (int i = 0; i < st.n; i++) {
    int p = sep ? st.c[i].x[0] > 0 : st.c[i].depth;
    if (p >= nparts) nparts = p + 1;
  }
  for (int p = 0; p < nparts && ok; p++) {
    sl_stack sub = st;   /* the contours of part p, one per slice */
    sub.c = xmallocarray((size_t)st.n, sizeof *sub.c);
    sub.n = 0;
    int flip = 0;
    for (int i = 0; i < st.n; i++)
      if ((sep ? st.c[i].x[0] > 0 : st.c[i].depth) == p) sub.c[sub.n++] = st.c[i], flip = st.c[i].depth % 2;
    ok = sl_stack_write(&sub, stack) == 0;
    free(sub.c);
    char *argv[] = {(char *)tile, stack, "--caps", "-q", "-o", obj, NULL};
    int rc = ok ? run(argv, csv, errf) : -1;
    CHECK(rc == 0, "%s: ./tile exit status %d on part %d", name, rc, p);
    mc_mesh m;
    csvtab t;
    char err[512];
    if (rc != 0 || mc_read(obj, &m, err, sizeof err) != 0) { ok = 0; break; }
    for (int v = 0; v < m.nv; v++) fprintf(fo, "v %.17g %.17g %.17g\n", m.v[3 * v], m.v[3 * v + 1], m.v[3 * v + 2]);
    for (int i = 0; i < m.nt; i++)   /* a cavity's surface faces into it */
      fprintf(fo, "f %d %d %d\n", base + m.t[3 * i] + 1, base + m.t[3 * i + (flip ? 2 : 1)] + 1,
              base + m.t[3 * i + (flip ? 1 : 2)] + 1);
    base += m.nv;
    mc_free(&m);
    if (csvtab_read(csv, &t, err, sizeof err) != 0) { ok = 0; break; }
    int cz0 = csvtab_col(&t, "z0"), cz1 = csvtab_col(&t, "z1"), cv = csvtab_col(&t, "volume");
    for (int i = 0; ok && i < t.nrow; i++) {
      double v = (flip ? -1 : 1) * strtod(t.cell[i][cv], NULL);
      if (strcmp(t.cell[i][0], "mesh") == 0) meshvol += v;
      else fprintf(fc, "%s,%s,%s,%.17g\n", t.cell[i][0], t.cell[i][cz0], t.cell[i][cz1], v);
    }
    csvtab_free(&t);
  }
  fprintf(fc, "mesh,,,%.17g\n", meshvol);
done:
  if (fo) fclose(fo);
  if (fc) fclose(fc);
  *vol = *area = NAN;
  CHECK(ok, "%s: a part could not be tiled or read", name);
  if (ok) judge(name, s, &st, z, K, mobj, mcsv, vol, area);
  unlink(stack), unlink(obj), unlink(csv), unlink(errf), unlink(mobj), unlink(mcsv);
  sl_stack_free(&st);
  free(z);
}

/* A real stack: a closed, outward surface of ncomp components of Euler
 * characteristic 2, through every input segment (after the repairs ./tile
 * makes), and the report's identity. */
static void e2e_real(const char *tile, const char *path, int ncomp) {
  const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
  char obj[512], csv[512], errf[512], err[512];
  path_of(obj, sizeof obj, "real", ".obj"), path_of(csv, sizeof csv, "real", ".csv");
  path_of(errf, sizeof errf, "real", ".err");
  sl_stack st;
  if (sl_stack_read(path, &st, err, sizeof err) != 0) {
    CHECK(0, "%s", err);
    return;
  }
  sl_stack_clean(&st);
  char *argv[] = {(char *)tile, (char *)path, "--caps", "-q", "-o", obj, NULL};
  int rc = run(argv, csv, errf);
  char line[512];
  firstline(errf, line, sizeof line);
  CHECK(rc == 0, "%s: ./tile exit status %d: %s", name, rc, line);
  if (rc == 0) {
    mc_report r;
    mc_fidelity f;
    tilejudge_mesh(name, obj, &st, -1, 1, &r, &f);
    int chi2 = r.ncomp == ncomp;
    for (int c = 0; c < r.ncomp; c++) chi2 &= r.chi[c] == 2;
    CHECK(chi2, "%s: %d components (expected %d, each of Euler characteristic 2)", name, r.ncomp, ncomp);
    tilejudge_report(name, csv, &r, &f);
    mc_report_free(&r), mc_fidelity_free(&f);
  }
  unlink(obj), unlink(csv), unlink(errf);
  sl_stack_free(&st);
}

/* Crossing correspondences (2-2 junctions): two discs of radius 0.5 at
 * +-0.6 (cos t, sin t), t turning 90 degrees from slice to slice, so that
 * each disc overlaps both discs of the next slice (0.85 apart) but not the
 * other disc of its own (1.2 apart).  By the rule every band is one
 * 2-2 junction, a sphere with four holes (Euler characteristic -2); with the
 * four end caps the surface is one component of characteristic
 * 4 - 2 (L - 1) = 6 - 2L for L slices: genus L - 2.  (No solid has these
 * sections and this topology; the slices are too far apart to say how the
 * discs connect, and the rule decides.) */
static void e2e_twist(const char *tile) {
  enum { L = 6, N = 48 };
  sl_stack st;
  memset(&st, 0, sizeof st);
  st.nslice = L, st.n = 2 * L;
  st.z = xmallocarray(L, sizeof *st.z), st.first = xmallocarray(L, sizeof *st.first);
  st.count = xmallocarray(L, sizeof *st.count), st.c = xcalloc(2 * L, sizeof *st.c);
  for (int k = 0; k < L; k++) {
    st.z[k] = 0.5 * k, st.first[k] = 2 * k, st.count[k] = 2;
    for (int i = 0; i < 2; i++) {
      sl_contour *c = &st.c[2 * k + i];
      double t = PI / 2 * k + PI * i, cx = 0.6 * cos(t), cy = 0.6 * sin(t);
      c->n = N, c->z = st.z[k], c->exact = c->region = NAN;
      c->x = xmallocarray(N, sizeof *c->x), c->y = xmallocarray(N, sizeof *c->y);
      for (int j = 0; j < N; j++) c->x[j] = cx + 0.5 * cos(2 * PI * j / N + 0.1 * k), c->y[j] = cy + 0.5 * sin(2 * PI * j / N + 0.1 * k);
    }
  }
  char stack[512], obj[512], csv[512], errf[512];
  path_of(stack, sizeof stack, "twist", ".contours"), path_of(obj, sizeof obj, "twist", ".obj");
  path_of(csv, sizeof csv, "twist", ".csv"), path_of(errf, sizeof errf, "twist", ".err");
  CHECK(sl_stack_write(&st, stack) == 0, "cannot write %s", stack);
  char *argv[] = {(char *)tile, stack, "--caps", "-q", "-o", obj, NULL};
  int rc = run(argv, csv, errf);
  char line[512];
  firstline(errf, line, sizeof line);
  CHECK(rc == 0, "twist: ./tile exit status %d: %s", rc, line);
  if (rc == 0) {
    mc_report r;
    mc_fidelity f;
    tilejudge_mesh("twist", obj, &st, -1, 1, &r, &f);
    CHECK(r.ncomp == 1 && r.chi[0] == 6 - 2 * L, "twist: %d components, chi %d; expected 1, chi %d (genus %d)", r.ncomp,
          r.ncomp ? r.chi[0] : 0, 6 - 2 * L, L - 2);
    tilejudge_report("twist", csv, &r, &f);
    mc_report_free(&r), mc_fidelity_free(&f);
  }
  unlink(stack), unlink(obj), unlink(csv), unlink(errf);
  sl_stack_free(&st);
}

/* The other mesh formats: PLY the same mesh exactly, STL the same surface. */
static void e2e_formats(const char *tile) {
  int s = solid_find("sphere");
  double z[12];
  solid_planes(s, 12, 1, z);
  sl_stack st;
  solid_slice(s, z, 12, 40, 1, &st);
  char stack[512], out[512], csv[512], errf[512];
  path_of(stack, sizeof stack, "formats", ".contours"), path_of(csv, sizeof csv, "formats", ".csv");
  path_of(errf, sizeof errf, "formats", ".err");
  CHECK(sl_stack_write(&st, stack) == 0, "cannot write %s", stack);
  double vol[3];
  const char *ext[3] = {".obj", ".ply", ".stl"};
  for (int i = 0; i < 3; i++) {
    path_of(out, sizeof out, "formats", ext[i]);
    char *argv[] = {(char *)tile, stack, "--caps", "-q", "-o", out, NULL};
    int rc = run(argv, csv, errf);
    CHECK(rc == 0, "sphere %s: ./tile exit status %d", ext[i], rc);
    mc_report r;
    mc_fidelity f;
    char name[64];
    snprintf(name, sizeof name, "sphere as %s", ext[i] + 1);
    tilejudge_mesh(name, out, &st, s, i < 2, &r, &f);   /* STL is float32: topology only */
    vol[i] = r.volume;
    mc_report_free(&r), mc_fidelity_free(&f);
    unlink(out);
  }
  CHECK(vol[0] == vol[1] && rel(vol[2], vol[0]) < 1e-5, "volumes OBJ %.17g PLY %.17g STL %.17g", vol[0], vol[1], vol[2]);
  unlink(stack), unlink(csv), unlink(errf);
  sl_stack_free(&st);
}

/* A second encoding of one stack must give the same report and mesh, byte
 * for byte: contours of a slice shuffled, start points turned, windings
 * reversed. */
static void e2e_encoding(const char *tile, const char *name, const char *orig, const sl_stack *st) {
  char enc[512], o1[512], o2[512], c1[512], c2[512], e1[512], e2[512];
  path_of(enc, sizeof enc, "enc", ".contours");
  path_of(o1, sizeof o1, "enc1", ".obj"), path_of(o2, sizeof o2, "enc2", ".obj");
  path_of(c1, sizeof c1, "enc1", ".csv"), path_of(c2, sizeof c2, "enc2", ".csv");
  path_of(e1, sizeof e1, "enc1", ".err"), path_of(e2, sizeof e2, "enc2", ".err");
  for (unsigned long long seed = 1; seed <= 2; seed++) {
    sl_stack sc;
    sl_stack_scramble(st, seed, &sc);
    CHECK(sl_stack_write(&sc, enc) == 0, "cannot write %s", enc);
    CHECK(!same_file(orig, enc), "%s: the second encoding is the same file", name);
    char *a1[] = {(char *)tile, (char *)orig, "--caps", "-q", "-o", o1, NULL};
    char *a2[] = {(char *)tile, enc, "--caps", "-q", "-o", o2, NULL};
    int r1 = run(a1, c1, e1), r2 = run(a2, c2, e2);
    char l1[512], l2[512];
    firstline(e1, l1, sizeof l1), firstline(e2, l2, sizeof l2);
    CHECK(r1 == 0 && r2 == 0, "%s: ./tile exit status %d (%s), on the second encoding %d (%s)", name, r1, l1, r2, l2);
    if (r1 == 0 && r2 == 0) {
      CHECK(same_file(c1, c2), "%s: the second encoding (seed %llu) changes the report", name, seed);
      CHECK(same_file(o1, o2), "%s: the second encoding (seed %llu) changes the mesh", name, seed);
    }
    sl_stack_free(&sc);
  }
  unlink(enc), unlink(o1), unlink(o2), unlink(c1), unlink(c2), unlink(e1), unlink(e2);
}

static int e2e(const char *tile) {
  const char *env = getenv("TILESIM_SOLIDS_ALL");
  int all = several_per_slice || (env && strcmp(env, "1") == 0);
  if (access(tile, X_OK) != 0) {
    CHECK(0, "no program %s", tile);
    return check_done("cli_solids");
  }
  for (int s = 0; s < solid_count(); s++)
    for (int uneven = 0; uneven < 2; uneven++) {
      double v = NAN, a = NAN, vd, ad;
      if (!solid_get(s)->multi || all) e2e_solid(tile, s, uneven, 0, &v, &a);
      if (!decomposable(s)) continue;
      e2e_decomposed(tile, s, uneven, &vd, &ad);
      if (all)
        CHECK(rel(v, vd) < 1e-8 && rel(a, ad) < 1e-8, "%s: volume %.17g and area %.17g, but tiled part by part %.17g and %.17g",
              solid_get(s)->name, v, a, vd, ad);
    }
  e2e_formats(tile);
  const char *real[] = {"tinypatient_1", "prostate_1", "prostate_2", "prostate_3", "prostate_4", "prostate_5"};
  for (int i = 0; i < 6; i++) {
    char path[256];
    snprintf(path, sizeof path, "tests/data/slicerrt/%s.contours", real[i]);
    e2e_real(tile, path, 1);
  }
  if (all) {   /* tinypatient_0: two structures, each a stack of one contour a slice */
    const char *tp = "tests/data/slicerrt/tinypatient_0.contours";
    e2e_real(tile, tp, 2);
    e2e_twist(tile);
    /* Apex caps: ends as cones half a slice out (flat where a point does not
     * see the whole region, as on the torus's annuli); their volumes in the
     * report's identity, in the slabs that hold them. */
    const char *apex[] = {"sphere", "cone", "spheres_separate", "hollow_sphere", "island", "torus_along", "torus_across"};
    for (int i = 0; i < 7; i++) {
      double v, a;
      e2e_solid(tile, solid_find(apex[i]), 1, 1, &v, &a);
    }
    /* second encodings: tinypatient_0 and every solid's stack */
    sl_stack st;
    char err[512];
    CHECK(sl_stack_read(tp, &st, err, sizeof err) == 0, "%s", err);
    e2e_encoding(tile, "tinypatient_0", tp, &st);
    sl_stack_free(&st);
    for (int s = 0; s < solid_count(); s++) {
      const solid_info *in = solid_get(s);
      double *z;
      int K;
      solid_stack(s, 1, &z, &K, &st);
      char orig[512];
      path_of(orig, sizeof orig, "orig", ".contours");
      CHECK(sl_stack_write(&st, orig) == 0, "cannot write %s", orig);
      e2e_encoding(tile, in->name, orig, &st);
      unlink(orig);
      sl_stack_free(&st);
      free(z);
    }
  } else {
    printf("cli_solids: the multi-contour solids, apex caps and second encodings were not run "
           "(several_per_slice is 0 in tests/test_solids.c)\n");
  }
  return check_done("cli_solids");
}

/* Tools for whoever works on ./tile: write a solid's stack; check a mesh. */
static int tool_gen(char **argv) {
  int s = solid_find(argv[2]), K = atoi(argv[3]), N = atoi(argv[4]), uneven = strcmp(argv[5], "uneven") == 0;
  if (s < 0 || K < 2 || N < 8) {
    fprintf(stderr, "test_solids: unknown solid or bad K, N; solids:");
    for (int i = 0; i < solid_count(); i++) fprintf(stderr, " %s", solid_get(i)->name);
    fputc('\n', stderr);
    return 2;
  }
  double *z = xmallocarray((size_t)K, sizeof *z);
  solid_planes(s, K, uneven, z);
  sl_stack st;
  solid_slice(s, z, K, N, 1, &st);
  int rc = sl_stack_write(&st, argv[6]) == 0 ? 0 : 1;
  printf("%s: %s; %d slices, %d contours; volume between the first and last planes %.17g\n", argv[6],
         solid_get(s)->what, K, st.n, solid_volume(s, z[0], z[K - 1]));
  sl_stack_free(&st);
  free(z);
  return rc;
}

static int tool_check(const char *mesh, const char *stack, const char *solid) {
  sl_stack st;
  char err[512];
  if (sl_stack_read(stack, &st, err, sizeof err) != 0) {
    fprintf(stderr, "test_solids: %s\n", err);
    return 1;
  }
  sl_stack_clean(&st);
  int s = solid ? solid_find(solid) : -1;
  mc_report r;
  mc_fidelity f;
  tilejudge_mesh(mesh, mesh, &st, s, 1, &r, &f);
  printf("%s: %d boundary, %d overused, %d pinched, %d degenerate, %d duplicate, %d unused, %d at one point%s%s\n", mesh,
         r.boundary, r.overused, r.pinched, r.degenerate, r.duplicate, r.unused, r.samepoint, r.first[0] ? "; first: " : "",
         r.first);
  for (int c = 0; c < r.ncomp; c++)
    printf("component %d: chi %d, volume %.17g, winding of the others %d\n", c, r.chi[c], r.cvol[c], r.wind[c]);
  printf("volume %.17g, area %.17g, outward %d\n", r.volume, r.area, r.outward);
  printf("input: %d/%d points absent, %d/%d segments missing, %d strays, %d crossing, %d channel segments\n", f.absent,
         f.points, f.missing, f.segments, f.strays, f.crossing, f.channel);
  if (s >= 0 && st.nslice) {
    double v = solid_volume(s, st.z[0], st.z[st.nslice - 1]);
    printf("the solid's volume between the first and last planes %.17g (mesh %+.3f%%)\n", v, 100 * (r.volume - v) / v);
  }
  mc_report_free(&r), mc_fidelity_free(&f);
  sl_stack_free(&st);
  return check_done("test_solids --check");
}

int main(int argc, char **argv) {
  snprintf(tmpdir, sizeof tmpdir, "/tmp/tilesim-solids.XXXXXX");
  if (!mkdtemp(tmpdir)) {
    perror("mkdtemp");
    return 1;
  }
  int rc;
  if (argc == 3 && strcmp(argv[1], "--tile") == 0) {
    rc = e2e(argv[2]);
  } else if (argc == 7 && strcmp(argv[1], "--gen") == 0) {
    rc = tool_gen(argv);
  } else if ((argc == 4 || argc == 5) && strcmp(argv[1], "--check") == 0) {
    rc = tool_check(argv[2], argv[3], argc == 5 ? argv[4] : NULL);
  } else if (argc == 1) {
    test_counts();
    test_areas();
    test_volumes();
    test_polygons();
    test_convergence();
    test_io(tmpdir);
    rc = check_done("test_solids");
  } else {
    fprintf(stderr, "usage: test_solids                        the slicer's unit tests\n"
                    "       test_solids --tile TILE            ./tile end to end on the solids\n"
                    "       test_solids --gen SOLID K N even|uneven OUT.contours\n"
                    "       test_solids --check MESH STACK.contours [SOLID]\n");
    rc = 2;
  }
  rmdir(tmpdir);
  return rc;
}
