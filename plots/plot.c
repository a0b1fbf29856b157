/* plot.c -- build/plot: the bench's CSV as SVG line charts, and a contour
 * stack with its surface (Fig. 17).  No dependencies beyond libc and libm.
 *
 *   plot lines CSV -x COL -y COL[,COL...] [--series COL[,COL...]] [--where COL=VALUE]...
 *        [--labels A,B,...] [--title T] [--xlabel T] [--ylabel T] [--yzero] -o OUT.svg
 *   plot surface STACK [--cost area|span] [--caps] [--title T] -o OUT.svg
 *
 * lines: one line per value of the --series column (in order of first
 * appearance; with several columns, per combination of their values) and
 * per y column, points sorted by x; rows must match every --where.  --labels
 * names the y columns, or with one y column and --series, the series.  surface: the stack is tiled (closed with --caps) and drawn. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atomicfile.h"
#include "contour.h"
#include "csvtab.h"
#include "mesh.h"
#include "svgchart.h"
#include "svgsurface.h"
#include "tiling.h"
#include "xmem.h"

static int usage(const char *why, const char *val) {
  if (why) fprintf(stderr, "plot: %s%s%s%s\n", why, val ? " (" : "", val ? val : "", val ? ")" : "");
  fputs("usage: plot lines CSV -x COL -y COL[,COL...] [--series COL[,COL...]] [--where COL=VALUE]...\n"
        "            [--labels A,B,...] [--title T] [--xlabel T] [--ylabel T] [--yzero] -o OUT.svg\n"
        "       plot surface STACK [--cost area|span] [--caps] [--title T] -o OUT.svg\n",
        stderr);
  return 2;
}

/* Write an SVG through draw(f, ud) to out, atomically; 0, or 1 after a message. */
static int write_svg(const char *out, void (*draw)(FILE *f, void *ud), void *ud) {
  char err[400];
  atomicfile af;
  if (atomicfile_open(&af, out, "w", err, sizeof err) != 0) {
    fprintf(stderr, "plot: %s\n", err);
    return 1;
  }
  draw(af.f, ud);
  if (atomicfile_close(&af, 1, err, sizeof err) != 0) {
    fprintf(stderr, "plot: %s\n", err);
    return 1;
  }
  return 0;
}

typedef struct {
  const svgchart_opts *o;
  const svgchart_series *s;
  int ns;
} chart;

static void draw_chart(FILE *f, void *ud) {
  const chart *c = ud;
  svgchart_write(f, c->o, c->s, c->ns);
}

typedef struct {
  const char *title;
  const contour_stack *s;
  const mesh *me;
} picture;

static void draw_surface(FILE *f, void *ud) {
  const picture *p = ud;
  svgsurface_write(f, p->title, p->s, p->me);
}

typedef struct { double x, y; } xy;
static int by_x(const void *a, const void *b) {
  const xy *p = a, *q = b;
  return (p->x > q->x) - (p->x < q->x);
}

static int lines(int argc, char **argv) {
  const char *in = argc > 2 ? argv[2] : NULL, *xc = NULL, *yc = NULL, *sc = NULL, *out = NULL;
  const char *where[16], *labels = NULL;
  int nwhere = 0;
  svgchart_opts o = {NULL, NULL, NULL, 0, 0};
  if (!in) return usage("no CSV", NULL);
  for (int i = 3; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (strcmp(a, "--yzero") == 0) { o.yzero = 1; continue; }
    if (!v) return usage("an option needs a value", a);
    if (strcmp(a, "-x") == 0) xc = v;
    else if (strcmp(a, "-y") == 0) yc = v;
    else if (strcmp(a, "--series") == 0) sc = v;
    else if (strcmp(a, "--where") == 0 && nwhere < 16 && strchr(v, '=')) where[nwhere++] = v;
    else if (strcmp(a, "--labels") == 0) labels = v;
    else if (strcmp(a, "--title") == 0) o.title = v;
    else if (strcmp(a, "--xlabel") == 0) o.xlabel = v;
    else if (strcmp(a, "--ylabel") == 0) o.ylabel = v;
    else if (strcmp(a, "-o") == 0) out = v;
    else return usage("unknown option", a);
    i++;
  }
  if (!xc || !yc || !out) return usage("lines needs -x, -y and -o", NULL);
  char err[400];
  csvtab t;
  if (csvtab_read(in, &t, err, sizeof err) != 0) {
    fprintf(stderr, "plot: %s\n", err);
    return 1;
  }
  int xi = csvtab_col(&t, xc), wi[16], si[4], nsc = 0, sbad = 0;
  char sbuf[256];
  if (sc) {
    snprintf(sbuf, sizeof sbuf, "%s", sc);
    for (char *p = strtok(sbuf, ","); p; p = strtok(NULL, ","))
      if (nsc < 4) si[nsc] = csvtab_col(&t, p), sbad |= si[nsc++] < 0;
      else sbad = 1;
  }
  char ybuf[256], *ycols[8];
  int ny = 0, yi[8];
  snprintf(ybuf, sizeof ybuf, "%s", yc);
  for (char *p = strtok(ybuf, ","); p && ny < 8; p = strtok(NULL, ",")) ycols[ny] = p, yi[ny++] = csvtab_col(&t, p);
  int bad = xi < 0 || sbad || (sc && nsc == 0);
  for (int k = 0; k < ny; k++) bad |= yi[k] < 0;
  char wname[16][64];
  const char *wval[16];
  for (int k = 0; k < nwhere; k++) {
    const char *eq = strchr(where[k], '=');
    snprintf(wname[k], sizeof wname[k], "%.*s", (int)(eq - where[k]), where[k]);
    wval[k] = eq + 1;
    wi[k] = csvtab_col(&t, wname[k]);
    bad |= wi[k] < 0;
  }
  if (bad) {
    fprintf(stderr, "plot: %s: a column named in -x, -y, --series or --where is not in its header\n", in);
    csvtab_free(&t);
    return 1;
  }
  char lbuf[512], *lab[16];
  int nl = 0;
  if (labels) {
    snprintf(lbuf, sizeof lbuf, "%s", labels);
    for (char *p = strtok(lbuf, ","); p && nl < 16; p = strtok(NULL, ",")) lab[nl++] = p;
  }
  /* The series: distinct values of the series columns (joined by spaces), in
   * order of appearance. */
  char (*key)[128] = xcalloc((size_t)t.nrow + 1, sizeof *key);
  for (int r = 0; r < t.nrow; r++) {
    size_t len = 0;
    for (int k = 0; k < nsc && len < sizeof key[r]; k++)
      len += (size_t)snprintf(key[r] + len, sizeof key[r] - len, "%s%s", k ? " " : "", t.cell[r][si[k]]);
  }
  const char **sv = xmallocarray((size_t)t.nrow + 1, sizeof *sv);
  int nsv = 0;
  for (int r = 0; r < t.nrow; r++) {
    int keep = 1;
    for (int k = 0; k < nwhere; k++) keep &= strcmp(t.cell[r][wi[k]], wval[k]) == 0;
    if (!keep) continue;
    int seen = 0;
    for (int k = 0; k < nsv; k++) seen |= strcmp(sv[k], key[r]) == 0;
    if (!seen) sv[nsv++] = key[r];
  }
  int ns = nsv * ny;
  svgchart_series *s = xcalloc((size_t)ns + 1, sizeof *s);
  char (*names)[128] = xcalloc((size_t)ns + 1, sizeof *names);
  for (int a = 0; a < nsv; a++)
    for (int k = 0; k < ny; k++) {
      xy *p = xmallocarray((size_t)t.nrow + 1, sizeof *p);
      int n = 0;
      for (int r = 0; r < t.nrow; r++) {
        int keep = strcmp(key[r], sv[a]) == 0;
        for (int q = 0; q < nwhere; q++) keep &= strcmp(t.cell[r][wi[q]], wval[q]) == 0;
        if (keep) p[n++] = (xy){strtod(t.cell[r][xi], NULL), strtod(t.cell[r][yi[k]], NULL)};
      }
      qsort(p, (size_t)n, sizeof *p, by_x);
      double *x = xmallocarray((size_t)n + 1, sizeof *x), *y = xmallocarray((size_t)n + 1, sizeof *y);
      for (int q = 0; q < n; q++) x[q] = p[q].x, y[q] = p[q].y;
      free(p);
      int i = a * ny + k;
      const char *yname = k < nl ? lab[k] : ycols[k];
      if (sc && ny > 1) snprintf(names[i], sizeof names[i], "%s=%s, %s", sc, sv[a], yname);
      else if (sc && a < nl) snprintf(names[i], sizeof names[i], "%s", lab[a]);
      else if (sc && nsc > 1) snprintf(names[i], sizeof names[i], "%s", sv[a]);
      else if (sc) snprintf(names[i], sizeof names[i], "%s=%s", sc, sv[a]);
      else snprintf(names[i], sizeof names[i], "%s", yname);
      s[i] = (svgchart_series){names[i], n, x, y, k > 0};
    }
  o.xint = 1;
  chart c = {&o, s, ns};
  int rc = write_svg(out, draw_chart, &c);
  for (int i = 0; i < ns; i++) free((void *)s[i].x), free((void *)s[i].y);
  free(s), free(names), free(sv), free(key);
  csvtab_free(&t);
  return rc;
}

static int surface(int argc, char **argv) {
  const char *in = argc > 2 ? argv[2] : NULL, *out = NULL, *title = "Fig. 17: contours and surface";
  cost_kind kind = COST_AREA;
  int caps = 0;
  if (!in) return usage("no contour stack", NULL);
  for (int i = 3; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (strcmp(a, "--caps") == 0) { caps = 1; continue; }
    if (!v) return usage("an option needs a value", a);
    if (strcmp(a, "-o") == 0) out = v;
    else if (strcmp(a, "--title") == 0) title = v;
    else if (strcmp(a, "--cost") == 0 && cost_parse(v, &kind) == 0) {}
    else return usage("unknown option or bad value", a);
    i++;
  }
  if (!out) return usage("surface needs -o", NULL);
  char err[400];
  contour_stack s;
  if (contour_read(in, &s, NULL, "plot", err, sizeof err) != 0) {
    fprintf(stderr, "plot: %s\n", err);
    return 1;
  }
  if (contour_stack_pairs(&s, in, err, sizeof err) != 0) {
    fprintf(stderr, "plot: %s\n", err);
    contour_stack_free(&s);
    return 1;
  }
  mesh me;
  mesh_init(&me, &s);
  for (int i = 0; i + 1 < s.n; i++) {
    tiling t;
    double a, v;
    tiling_solve(s.c[i].pt, s.c[i].n, s.c[i].z, s.c[i + 1].pt, s.c[i + 1].n, s.c[i + 1].z, kind, -1, &t);
    mesh_add_band(&me, &s, i, &t, &a, &v);
    tiling_free(&t);
  }
  if (caps) mesh_add_caps(&me, &s);
  picture p = {title, &s, &me};
  int rc = write_svg(out, draw_surface, &p);
  mesh_free(&me);
  contour_stack_free(&s);
  return rc;
}

int main(int argc, char **argv) {
  if (argc >= 2 && strcmp(argv[1], "lines") == 0) return lines(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "surface") == 0) return surface(argc, argv);
  if (argc >= 2 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
    usage(NULL, NULL);
    return 0;
  }
  return usage(argc >= 2 ? "unknown mode" : "no mode", argc >= 2 ? argv[1] : NULL);
}
