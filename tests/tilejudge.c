/* tilejudge.c -- ./tile's mesh and report judged by the independent mesh
 * checker (tilejudge.h). */
#include "tests/tilejudge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "util/csvtab.h"
#include "util/xmem.h"

static int is_int(const char *s) {
  if (*s == 0) return 0;
  for (; *s; s++)
    if (*s < '0' || *s > '9') return 0;
  return 1;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}
static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

/* The report (doc/tile.1, OUTPUT: a row per band, then with --caps a row
 * `cap` per cap, a row `mesh` and a row `component` per component) against
 * the mesh as the checker sees it: the bands' and caps' volumes sum to the
 * `mesh` row's volume, which is the mesh's own; the bands between two
 * planes, and the caps whose apex lies between them, sum to the mesh's slab
 * there (caps beyond the end planes: to the mesh beyond them); a flat cap
 * adds nothing; the `mesh` and `component` rows give the checker's
 * components, Euler characteristics and volumes. */
void tilejudge_report(const char *name, const char *csv, const mc_report *r, const mc_fidelity *f) {
  csvtab t;
  char err[512];
  if (csvtab_read(csv, &t, err, sizeof err) != 0) {
    CHECK(0, "%s: report: %s", name, err);
    return;
  }
  int cz0 = csvtab_col(&t, "z0"), cz1 = csvtab_col(&t, "z1"), cv = csvtab_col(&t, "volume");
  int cj = csvtab_col(&t, "junction"), ce = csvtab_col(&t, "euler");
  CHECK(cz0 >= 0 && cz1 >= 0 && cv >= 0, "%s: report lacks z0, z1 or volume", name);
  if (cz0 < 0 || cz1 < 0 || cv < 0) {
    csvtab_free(&t);
    return;
  }
  double bands = 0, caps = 0, meshvol = NAN, outside = 0;
  double *slab = xcalloc((size_t)f->nplanes + 1, sizeof *slab), *cvol = xcalloc((size_t)t.nrow + 1, sizeof *cvol);
  int *ceul = xcalloc((size_t)t.nrow + 1, sizeof *ceul);
  int nbands = 0, unplaced = 0, flatvol = 0, ncomp = 0, meshrows = 0, closed = 1, eul = 0;
  for (int i = 0; i < t.nrow; i++) {
    char **row = t.cell[i];
    double v = strtod(row[cv], NULL), z0 = strtod(row[cz0], NULL), z1 = strtod(row[cz1], NULL);
    double lo = fmin(z0, z1), hi = fmax(z0, z1);
    if (strcmp(row[0], "mesh") == 0) {
      meshvol = v, meshrows++;
      if (cj >= 0) closed = strcmp(row[cj], "closed") == 0;
      if (ce >= 0) eul = atoi(row[ce]);
      continue;
    }
    if (strcmp(row[0], "component") == 0) {
      cvol[ncomp] = v, ceul[ncomp] = ce >= 0 ? atoi(row[ce]) : 0, ncomp++;
      continue;
    }
    int cap = strcmp(row[0], "cap") == 0;
    if (!cap && !is_int(row[0])) continue;
    if (cap) {
      caps += v;
      if (z0 == z1) {   /* flat */
        flatvol += v != 0;
        continue;
      }
    } else {
      bands += v, nbands++;
    }
    int k = 0;   /* the slab that holds [lo, hi] */
    while (k + 1 < f->nplanes && !(f->planes[k] <= lo && hi <= f->planes[k + 1])) k++;
    if (k + 1 < f->nplanes && (cap || (f->planes[k] == lo && f->planes[k + 1] == hi))) slab[k] += v;
    else if (cap && (hi <= f->planes[0] || lo >= f->planes[f->nplanes - 1])) outside += v;
    else unplaced++;
  }
  double tol = 1e-9 * fabs(r->volume);
  CHECK(meshrows == 1, "%s: %d mesh rows", name, meshrows);
  CHECK(nbands >= f->nplanes - 1 && unplaced == 0 && flatvol == 0,
        "%s: %d band rows, %d not between consecutive planes, %d flat caps with a volume", name, nbands, unplaced, flatvol);
  CHECK(fabs(meshvol - r->volume) <= tol, "%s: the report's mesh volume %.17g, the mesh's %.17g", name, meshvol, r->volume);
  CHECK(fabs(bands + caps - meshvol) <= tol, "%s: bands %.17g + caps %.17g, the mesh row says %.17g", name, bands, caps,
        meshvol);
  int worst = -1;
  for (int k = 0; k + 1 < f->nplanes; k++)
    if (fabs(slab[k] - f->slab[k]) > tol && worst < 0) worst = k;
  CHECK(worst < 0, "%s: between z=%.17g and %.17g: report %.17g, mesh %.17g", name, worst < 0 ? 0 : f->planes[worst],
        worst < 0 ? 0 : f->planes[worst + 1], worst < 0 ? 0 : slab[worst], worst < 0 ? 0 : f->slab[worst]);
  CHECK(fabs(outside - f->outside) <= tol, "%s: caps beyond the end planes %.17g, the mesh there %.17g", name, outside,
        f->outside);
  if (cj >= 0 && ce >= 0) {   /* the mesh's own account of itself */
    int chi = 0, same = ncomp == r->ncomp;
    for (int c = 0; c < r->ncomp; c++) chi += r->chi[c];
    CHECK(closed == r->manifold && eul == chi, "%s: the mesh row says %s, Euler characteristic %d; the checker finds %s, %d",
          name, closed ? "closed" : "not closed", eul, r->manifold ? "closed" : "not closed", chi);
    if (same) {
      int *mc = xmallocarray((size_t)ncomp + 1, sizeof *mc);
      double *mv = xmallocarray((size_t)ncomp + 1, sizeof *mv);
      memcpy(mc, r->chi, (size_t)ncomp * sizeof *mc), memcpy(mv, r->cvol, (size_t)ncomp * sizeof *mv);
      qsort(mc, (size_t)ncomp, sizeof *mc, cmp_int), qsort(ceul, (size_t)ncomp, sizeof *ceul, cmp_int);
      qsort(mv, (size_t)ncomp, sizeof *mv, cmp_double), qsort(cvol, (size_t)ncomp, sizeof *cvol, cmp_double);
      for (int c = 0; c < ncomp; c++) same &= mc[c] == ceul[c] && fabs(mv[c] - cvol[c]) <= tol;
      free(mc), free(mv);
    }
    CHECK(same, "%s: %d component rows, the checker finds %d components (or their Euler characteristics or volumes differ)",
          name, ncomp, r->ncomp);
  }
  free(slab), free(cvol), free(ceul);
  csvtab_free(&t);
}

/* Check the mesh in path against the stack and the solid s (s < 0: topology
 * and fidelity only); exact != 0: its coordinates must be the input's. */
void tilejudge_mesh(const char *name, const char *path, const sl_stack *st, int s, int exact, mc_report *r,
                    mc_fidelity *f) {
  mc_mesh m;
  char err[512];
  memset(r, 0, sizeof *r), memset(f, 0, sizeof *f);
  if (mc_read(path, &m, err, sizeof err) != 0) {
    CHECK(0, "%s: %s", name, err);
    return;
  }
  mc_check(&m, r);
  CHECK(r->manifold, "%s: not a closed 2-manifold: %d boundary, %d overused, %d pinched, %d degenerate, %d duplicate, "
                     "%d unused, %d at one point; first: %s",
        name, r->boundary, r->overused, r->pinched, r->degenerate, r->duplicate, r->unused, r->samepoint, r->first);
  CHECK(r->outward, "%s: not outward: %s", name, r->first);
  if (s >= 0) {   /* components: the solid's, matched by Euler characteristic and orientation */
    const solid_info *in = solid_get(s);
    int used[SOLID_MAXCOMP] = {0}, matched = 0;
    for (int c = 0; c < r->ncomp; c++)
      for (int j = 0; j < in->ncomp; j++)
        if (!used[j] && r->chi[c] == in->chi[j] && (r->cvol[c] > 0) == (in->sign[j] > 0)) {
          used[j] = 1, matched++;
          break;
        }
    CHECK(r->ncomp == in->ncomp && matched == in->ncomp, "%s: %d components (chi %d, ...), the solid has %d (chi %d, ...)",
          name, r->ncomp, r->ncomp ? r->chi[0] : 0, in->ncomp, in->chi[0]);
  }
  mc_poly *pc = xmallocarray((size_t)st->n + 1, sizeof *pc);
  for (int i = 0; i < st->n; i++) pc[i] = (mc_poly){st->c[i].n, st->c[i].z, st->c[i].x, st->c[i].y};
  mc_check_input(&m, pc, st->n, f);
  if (exact) {
    CHECK(f->absent == 0 && f->missing == 0, "%s: of %d input points %d are no mesh vertex; of %d segments %d are no mesh edge",
          name, f->points, f->absent, f->segments, f->missing);
    CHECK(f->strays == 0 && f->crossing == 0, "%s: %d other vertices on input planes, %d triangles across a plane", name,
          f->strays, f->crossing);
  }
  free(pc);
  mc_free(&m);
}
