/* tile.c -- ./tile: contours in, the optimal tiling out (CSV report and a mesh).
 *
 *   tile STACK [-o OUT.obj|OUT.ply|OUT.stl] [--cost area|span] [--caps] [-q]
 *
 * Every contour is tiled with the next one in file order by the exact
 * solver (algo/tiling.h).  CSV on stdout, one row per pair; with --caps the
 * first and last contours are closed and a last row gives the mesh's area and
 * enclosed volume. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "contour.h"
#include "mesh.h"
#include "meshio.h"
#include "tiling.h"
#include "xmem.h"

static const char usage_line[] =
    "usage: tile STACK [-o OUT.obj|OUT.ply|OUT.stl] [--cost area|span] [--caps] [-q]\n";

static void usage(FILE *f) {
  fputs(usage_line, f);
  if (f == stdout)
    fputs("\n"
          "Tile each contour of STACK with the next one by the minimum-cost acceptable\n"
          "path over all start rows (Fuchs, Kedem, Uselton 1977; exact, O(mn log m)).\n"
          "\n"
          "  -o FILE         write the mesh: .obj, .ply (ASCII) or .stl (binary)\n"
          "  --cost area     tile weight: the triangle's area (default)\n"
          "  --cost span     tile weight: the length of the span the tile adds\n"
          "  --caps          close the first and last contours (watertight mesh)\n"
          "  -q, --quiet     no notes about repaired input on stderr\n"
          "  -h, --help      this text\n"
          "\n"
          "CSV on stdout: pair,z0,z1,m,n,cost,area,volume,nodes; with --caps a last row\n"
          "'mesh' with the whole mesh's area and enclosed volume.\n",
          f);
}

static int bad_usage(const char *fmt, const char *arg) {
  fprintf(stderr, "tile: ");
  fprintf(stderr, fmt, arg);
  fputc('\n', stderr);
  fputs(usage_line, stderr);
  return 2;
}

int main(int argc, char **argv) {
  const char *in = NULL, *out = NULL;
  cost_kind kind = COST_AREA;
  int caps = 0, quiet = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
      usage(stdout);
      return 0;
    } else if (strcmp(a, "-o") == 0 || strcmp(a, "--cost") == 0) {
      if (i + 1 >= argc) return bad_usage("option %s needs a value", a);
      const char *v = argv[++i];
      if (a[1] == 'o') {
        if (meshio_format_of(v) == MESHIO_NONE)
          return bad_usage("unknown mesh format, use .obj, .ply or .stl (%s)", v);
        out = v;
      } else if (cost_parse(v, &kind) != 0) {
        return bad_usage("unknown cost, use area or span (%s)", v);
      }
    } else if (strcmp(a, "--caps") == 0) {
      caps = 1;
    } else if (strcmp(a, "-q") == 0 || strcmp(a, "--quiet") == 0) {
      quiet = 1;
    } else if (a[0] == '-' && a[1] != 0) {
      return bad_usage("unknown option (%s)", a);
    } else if (in) {
      return bad_usage("one contour stack at a time (%s)", a);
    } else {
      in = a;
    }
  }
  if (!in) return bad_usage("%s", "no contour stack given");

  char err[512];
  contour_stack s;
  if (contour_read(in, &s, quiet ? NULL : stderr, "tile", err, sizeof err) != 0) {
    fprintf(stderr, "tile: %s\n", err);
    return 1;
  }

  mesh me;
  mesh_init(&me, &s);
  int progress = isatty(2) && s.n > 2;
  double total_cost = 0;
  unsigned long long total_nodes = 0;
  printf("pair,z0,z1,m,n,cost,area,volume,nodes\n");
  for (int i = 0; i + 1 < s.n; i++) {
    const contour *P = &s.c[i], *Q = &s.c[i + 1];
    tiling t;
    tiling_solve(P->pt, P->n, P->z, Q->pt, Q->n, Q->z, kind, -1, &t);
    double area, volume;
    mesh_add_band(&me, &s, i, &t, &area, &volume);
    printf("%d,%.17g,%.17g,%d,%d,%.17g,%.17g,%.17g,%llu\n", i, P->z, Q->z, P->n, Q->n, t.cost,
           area, volume, (unsigned long long)t.count.nodes);
    total_cost += t.cost;
    total_nodes += t.count.nodes;
    tiling_free(&t);
    if (progress) fprintf(stderr, "\rtile: pair %d of %d", i + 1, s.n - 1);
  }
  if (progress) fputs("\r\033[K", stderr);
  if (caps) {
    mesh_add_caps(&me, &s);
    printf("mesh,%.17g,%.17g,,,%.17g,%.17g,%.17g,%llu\n", s.c[0].z, s.c[s.n - 1].z, total_cost,
           mesh_area(&me), mesh_volume(&me), total_nodes);
  }
  int rc = 0;
  if (fflush(stdout) != 0) {
    fprintf(stderr, "tile: cannot write the report (%s)\n", strerror(errno));
    rc = 1;
  }
  if (rc == 0 && out && meshio_write(&me, out, err, sizeof err) != 0) {
    fprintf(stderr, "tile: %s\n", err);
    rc = 1;
  }
  mesh_free(&me);
  contour_stack_free(&s);
  return rc;
}
