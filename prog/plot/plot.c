/* plot.c -- build/plot: the bench's CSV as SVG line charts, and a contour
 * stack with its surface (Fig. 17).  No dependencies beyond libc and libm.
 *
 *   plot lines CSV -x COL -y COL[,COL...] [--series COL[,COL...]] [--where COL=VALUE]...
 *        [--labels A,B,...] [--title T] [--xlabel T] [--ylabel T] [--yzero] -o OUT.svg
 *   plot surface STACK [--cost area|span] [--caps] [--title T] -o OUT.svg
 *   plot claims MAP.csv [--title T] -o OUT.svg   (claims.c)
 *
 * lines: one line per value of the --series column (in order of first
 * appearance; with several columns, per combination of their values) and
 * per y column, points sorted by x; rows must match every --where.  --labels
 * names the y columns, or with one y column and --series, the series.  surface: the stack is tiled (closed with --caps) and drawn. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "input/contour.h"
#include "util/csvtab.h"
#include "surface/mesh.h"
#include "prog/plot/claims.h"
#include "util/progname.h"
#include "input/stackfile.h"
#include "surface/pool.h"
#include "surface/stack.h"
#include "prog/plot/svgchart.h"
#include "prog/plot/svgsurface.h"
#include "algo/tiling.h"
#include "util/xmem.h"

static const char lines_usage[] =
    "usage: plot lines CSV -x COL -y COL[,COL...] [--series COL[,COL...]] [--where COL=VALUE]... "
    "[--labels A,B,...] [--title T] [--xlabel T] [--ylabel T] [--yzero] -o OUT.svg   "
    "(plot --help: every option)\n";
static const char surface_usage[] =
    "usage: plot surface STACK|FILE.dcm --roi NAME [--cost area|span] [--no-caps] [--band aligned|plain] [--join RULE] [--thickness T] "
    "[--skip-bad] [--union] [-v] "
    "[--title T] -o OUT.svg   "
    "(plot --help: every option)\n";
static const char any_usage[] =
    "usage: plot lines CSV ... -o OUT.svg | plot surface STACK ... -o OUT.svg | "
    "plot claims MAP.csv ... -o OUT.svg   "
    "(plot --help: every option)\n";

static void help(const char *name) {
  printf("usage: %s lines CSV -x COL -y COL[,COL...] [--series COL[,COL...]] [--where COL=VALUE]...\n"
        "            [--labels A,B,...] [--title T] [--xlabel T] [--ylabel T] [--yzero] -o OUT.svg\n"
        "       %s surface STACK|FILE.dcm [--roi NAME|NUMBER] [--cost area|span] [--no-caps]\n"
        "            [--band aligned|plain] [--join RULE] [--thickness T] [--skip-bad] [--union] [-v]\n"
        "            [--title T] -o OUT.svg\n"
        "       %s claims MAP.csv [--title T] -o OUT.svg\n"
        "\n"
        "%s -- tilesim's CSV as SVG line charts, a contour stack with its surface, and\n"
        "the claims map.\n"
        "\n"
        "lines: one line per value of the --series column and per y column (up to 8; a\n"
        "value's lines share a colour and marker, later y columns dashed), from the rows\n"
        "that match every --where (up to 16), points sorted by x.\n"
        "  -x COL             the x column\n"
        "  -y COL[,COL...]    the y columns, at most 8\n"
        "  --series COL[,COL...]  one line per value of COL (up to 4 columns: per\n"
        "                     combination of their values)\n"
        "  --where COL=VALUE  only the rows whose COL is VALUE\n"
        "  --labels A,B,...   the y columns' names in the legend (with one y column and\n"
        "                     --series, the series' names), up to 16\n"
        "  --title T, --xlabel T, --ylabel T   texts\n"
        "  --yzero            the y axis starts at 0\n"
        "  -o OUT.svg         the picture (written atomically)\n"
        "surface: the stack tiled (closed, as tile closes it), drawn beside its contours; a\n"
        "DICOM RT structure set's ROI with --roi, as tile FILE.dcm --roi tiles it.\n"
        "  --roi NAME|NUMBER  the ROI of a DICOM RT structure set to draw\n"
        "  --cost area|span   the tile weight (default area)\n"
        "  --no-caps          leave the ends open, as tile --no-caps does (--caps, the\n"
        "                     default, is accepted too)\n"
        "  --band aligned|plain  how a 1-1 band is tiled, as tile --band: on its\n"
        "                     contours aligned (default) or the paper's plain band\n"
        "  --join RULE        which contours of neighbouring slices are joined: overlap,\n"
        "                     touch, single (default), nearest or a distance, as tile\n"
        "                     --join does\n"
        "  --thickness T      a stack of one slice becomes a closed slab T thick\n"
        "  --skip-bad         drop the contours that cannot be tiled, as tile does\n"
        "  --union            merge overlapping contours of a slice, as tile does\n"
        "  -v, --verbose      every note on the input in full, as tile -v\n"
        "  --title T          the title\n"
        "  -o OUT.svg         the picture\n"
        "claims: a claims map (tilesim-bench --claims-map) as a grid: a panel per\n"
        "configuration less its m, the claims down, m/c across on a log scale, held,\n"
        "failed or n/a.\n"
        "  --title T          the title\n"
        "  -o OUT.svg         the picture\n"
        "\n"
        "Exit status: 0 done, 1 bad input (a file that cannot be read, a missing\n"
        "column), 2 bad usage.  The manual: tilesim-plot(1).\n",
         name, name, name, name);
}

/* Bad usage: "plot: why" (and the value, as util/args shows values), the
 * mode's usage line, exit status 2. */
static int usage(const char *line, const char *why, const char *val) { return args_usage("plot", line, why, val); }

/* A comma-separated list of names, none empty, at most max: 0 and the
 * count in *n, or -1 and a message. */
static int names(const char *opt, const char *val, int max, int *n, char *err, size_t errlen) {
  char shown[200];
  *n = 0;
  const char *p = val;
  for (;;) {
    size_t len = strcspn(p, ",");
    if (len == 0 || *n == max) break;
    (*n)++;
    if (!p[len]) return 0;
    p += len + 1;
  }
  args_show(val, shown, sizeof shown);
  snprintf(err, errlen, "%s takes 1 to %d names, comma-separated, none empty (%s)", opt, max, shown);
  return -1;
}

/* Can out be written?  Asked before any work: 0, or 1 after a message. */
static int cannot_write(const char *out) {
  char err[400];
  if (atomicfile_check(out, err, sizeof err) == 0) return 0;
  progname_eprintf("plot: %s\n", err);
  return 1;
}

/* Write an SVG through draw(f, ud) to out, atomically; 0, or 1 after a message. */
static int write_svg(const char *out, void (*draw)(FILE *f, void *ud), void *ud) {
  char err[400];
  atomicfile af;
  if (atomicfile_open(&af, out, "w", err, sizeof err) != 0) {
    progname_eprintf("plot: %s\n", err);
    return 1;
  }
  draw(af.f, ud);
  if (atomicfile_close(&af, 1, err, sizeof err) != 0) {
    progname_eprintf("plot: %s\n", err);
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
  int nwhere = 0, nn;
  svgchart_opts o = {NULL, NULL, NULL, 0, 0};
  char err[400];
  if (!in || (in[0] == '-' && in[1])) return usage(lines_usage, "lines needs a CSV file first", in);
  if (!in[0]) return usage(lines_usage, "lines needs a CSV file first", in);
  for (int i = 3; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int bad = 0;
    if (strcmp(a, "--yzero") == 0) { o.yzero = 1; continue; }
    static const char *const opts[] = {"-x", "-y", "--series", "--where", "--labels", "--title",
                                       "--xlabel", "--ylabel", "-o"};
    int known = 0;
    for (size_t k = 0; k < sizeof opts / sizeof *opts; k++) known |= strcmp(a, opts[k]) == 0;
    if (!known) return usage(lines_usage, a[0] == '-' ? "unknown option" : "unexpected argument", a);
    if (!v) return usage(lines_usage, "an option needs a value", a);
    if (strcmp(a, "-x") == 0) bad = args_name(a, v, "a column name", 0, err, sizeof err), xc = v;
    else if (strcmp(a, "-y") == 0) bad = names(a, v, 8, &nn, err, sizeof err), yc = v;
    else if (strcmp(a, "--series") == 0) bad = names(a, v, 4, &nn, err, sizeof err), sc = v;
    else if (strcmp(a, "--where") == 0) {
      const char *eq = strchr(v, '=');
      if (!eq || eq == v) {
        char shown[200];
        args_show(v, shown, sizeof shown);
        snprintf(err, sizeof err, "--where takes COL=VALUE, a column name and a value (%s)", shown);
        bad = 1;
      } else if (nwhere == 16) {
        snprintf(err, sizeof err, "--where is given at most 16 times");
        bad = 1;
      } else {
        where[nwhere++] = v;
      }
    } else if (strcmp(a, "--labels") == 0) bad = names(a, v, 16, &nn, err, sizeof err), labels = v;
    else if (strcmp(a, "--title") == 0) o.title = v;
    else if (strcmp(a, "--xlabel") == 0) o.xlabel = v;
    else if (strcmp(a, "--ylabel") == 0) o.ylabel = v;
    else bad = svg_name(a, v, err, sizeof err), out = v;
    if (bad) return usage(lines_usage, err, NULL);
    i++;
  }
  if (!xc || !yc || !out) return usage(lines_usage, "lines needs -x, -y and -o", NULL);
  if (cannot_write(out)) return 1;
  csvtab t;
  if (csvtab_read(in, &t, err, sizeof err) != 0) {
    progname_eprintf("plot: %s\n", err);
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
  /* Every column named that the header lacks, by its option:
   * "no column 'nosuch' (-y), 'x' (--where)". */
  char missing[1024] = "";
  size_t ml = 0;
#define MISSING(name, opt) \
  ml += (size_t)snprintf(missing + ml, ml < sizeof missing ? sizeof missing - ml : 0, "%s'%.60s' (%s)", \
                         ml ? ", " : "", name, opt)
  if (xi < 0) MISSING(xc, "-x");
  for (int k = 0; k < ny; k++)
    if (yi[k] < 0) MISSING(ycols[k], "-y");
  if (sc) {
    char sb2[256];
    snprintf(sb2, sizeof sb2, "%s", sc);
    for (char *p = strtok(sb2, ","); p; p = strtok(NULL, ","))
      if (csvtab_col(&t, p) < 0) MISSING(p, "--series");
  }
  char wname[16][64];
  const char *wval[16];
  for (int k = 0; k < nwhere; k++) {
    const char *eq = strchr(where[k], '=');
    snprintf(wname[k], sizeof wname[k], "%.*s", (int)(eq - where[k]), where[k]);
    wval[k] = eq + 1;
    wi[k] = csvtab_col(&t, wname[k]);
    if (wi[k] < 0) MISSING(wname[k], "--where");
  }
#undef MISSING
  if (ml > 0 || sbad || (sc && nsc == 0)) {
    progname_eprintf("plot: %s: its header has no column %s\n", in, ml ? missing : "named in --series");
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
      s[i] = (svgchart_series){names[i], n, x, y, k, a};   /* a size's columns: one colour, dashes */
    }
  o.xint = 1;
  chart c = {&o, s, ns};
  int rc = write_svg(out, draw_chart, &c);
  for (int i = 0; i < ns; i++) free((void *)s[i].x), free((void *)s[i].y);
  free(s), free(names), free(sv), free(key);
  csvtab_free(&t);
  return rc;
}


/* Each line of a refusal as "plot: LINE" (one names every bad contour). */
static void say_lines(const char *text) {
  for (const char *p = text; *p;) {
    const char *e = strchr(p, '\n');
    size_t n = e ? (size_t)(e - p) : strlen(p);
    progname_eprintf("plot: %.*s\n", (int)n, p);
    p += n + (e != NULL);
  }
}

static int surface(int argc, char **argv) {
  const char *in = argc > 2 ? argv[2] : NULL, *out = NULL, *title = NULL, *roikey = NULL;
  cost_kind kind = COST_AREA;
  int caps = 1, flags = CONTOUR_DROP_DEGENERATE;   /* and CONTOUR_SKIP_BAD, CONTOUR_UNION, CONTOUR_VERBOSE */
  stack_band band = STACK_BAND_ALIGNED;
  match_rule join = MATCH_SINGLE;
  double join_dist = INFINITY, thickness = 0;
  static char err[1 << 16];   /* a refusal may name every bad contour */
  if (!in || !in[0] || (in[0] == '-' && in[1])) return usage(surface_usage, "surface needs a contour stack first", in);
  for (int i = 3; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int bad = 0;
    if (strcmp(a, "--caps") == 0) { caps = 1; continue; }
    if (strcmp(a, "--no-caps") == 0) { caps = 0; continue; }
    if (strcmp(a, "--skip-bad") == 0) { flags |= CONTOUR_SKIP_BAD; continue; }
    if (strcmp(a, "--union") == 0) { flags |= CONTOUR_UNION; continue; }
    if (strcmp(a, "-v") == 0 || strcmp(a, "--verbose") == 0) { flags |= CONTOUR_VERBOSE; continue; }
    if (strcmp(a, "-o") != 0 && strcmp(a, "--title") != 0 && strcmp(a, "--cost") != 0 && strcmp(a, "--roi") != 0 &&
        strcmp(a, "--join") != 0 && strcmp(a, "--thickness") != 0 && strcmp(a, "--band") != 0)
      return usage(surface_usage, a[0] == '-' ? "unknown option" : "unexpected argument", a);
    if (!v) return usage(surface_usage, "an option needs a value", a);
    if (strcmp(a, "-o") == 0) bad = svg_name(a, v, err, sizeof err), out = v;
    else if (strcmp(a, "--title") == 0) title = v;
    else if (strcmp(a, "--join") == 0) bad = stack_parse_join(a, v, &join, &join_dist, err, sizeof err) != 0;
    else if (strcmp(a, "--thickness") == 0) bad = stack_parse_thickness(a, v, &thickness, err, sizeof err) != 0;
    else if (strcmp(a, "--band") == 0) {
      int b = args_word(a, v, "aligned|plain", err, sizeof err);
      bad = b < 0;
      band = b == 1 ? STACK_BAND_PLAIN : STACK_BAND_ALIGNED;
    }
    else if (strcmp(a, "--roi") == 0) {
      if (!v[0]) bad = 1, snprintf(err, sizeof err, "--roi takes an ROI's name or number ('')");
      roikey = v;
    } else if (cost_parse(v, &kind) != 0) bad = args_word(a, v, "area|span", err, sizeof err) < 0;
    if (bad) return usage(surface_usage, err, NULL);
    i++;
  }
  if (!out) return usage(surface_usage, "surface needs -o", NULL);
  if (cannot_write(out)) return 1;
  int dicom = stackfile_is_dicom(in);
  if (dicom && !roikey) {
    progname_eprintf("plot: %s: a DICOM RT structure set: name the ROI to draw with --roi (tile %s --list "
            "lists them)\n", in, in);
    return 1;
  }
  if (!dicom && roikey) return usage(surface_usage, "--roi is for a DICOM RT structure set", in);
  /* An ROI's notes are said (and its contours without area dropped); a
   * file's repairs are made silently. */
  stackfile *sf;
  if (stackfile_open(in, roikey, flags | CONTOUR_ONE_SLICE | (dicom ? CONTOUR_DROP_DEGENERATE : 0),
                     dicom ? stderr : NULL, progname_as("plot"), &sf, err, sizeof err) != 0) {
    say_lines(err);
    return 1;
  }
  contour_stack *s = stackfile_stack(sf);
  if (!title) title = dicom ? stackfile_title(sf) : "Fig. 17: contours and surface";
  /* The surface ./tile makes: any number of contours a slice, holes,
   * branching (surface/stack.h), on the machine's cores.  Its notes are
   * held until it is made, then said (an ROI's with its places named as
   * the reader names them). */
  char *held = NULL;
  size_t heldlen = 0;
  FILE *notes = open_memstream(&held, &heldlen);
  stack_options so = {kind, caps, 0, pool_cores(), NULL, notes ? notes : stderr, progname_as("plot"), NULL, NULL,
                      join, join_dist, thickness, band};
  stack_surface *ss;
  int bad = stack_tile(s, stackfile_name(sf), &so, &ss, err, sizeof err) != 0;
  if (notes) fclose(notes);
  const char *said[2] = {held, bad ? err : NULL};
  for (int k = 0; k < 2; k++) {
    if (!said[k] || !said[k][0]) continue;
    char *m = stackfile_say(sf, said[k]);
    if (k) say_lines(m);
    else fputs(m, stderr);
    free(m);
  }
  free(held);
  if (bad) {
    stackfile_close(sf);
    return 1;
  }
  mesh me;
  stack_take_mesh(ss, &me);
  stack_free(ss);
  picture p = {title, s, &me};
  int rc = write_svg(out, draw_surface, &p);
  mesh_free(&me);
  stackfile_close(sf);
  return rc;
}

int main(int argc, char **argv) {
  /* Its messages and --help name it as it was run: plot in the source tree
   * (build/plot), tilesim-plot installed (util/progname.h). */
  progname_init("plot", argc > 0 ? argv[0] : NULL);
  if (argc >= 2 && strcmp(argv[1], "lines") == 0) return lines(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "surface") == 0) return surface(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "claims") == 0) return plot_claims(argc, argv);
  if (argc >= 2 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
    help(progname());
    return 0;
  }
  return usage(any_usage, argc >= 2 ? "unknown mode, use lines, surface or claims"
                                 : "no mode, use lines, surface or claims",
               argc >= 2 ? argv[1] : NULL);
}
