/* claims.c -- build/plot claims: bench --claims-map's CSV as a grid.
 *
 *   plot claims MAP.csv [--title T] -o OUT.svg
 *
 * A panel per configuration less its message cost (net, pair, c and the
 * other machine columns), the seven claims down, m/c across on a log scale;
 * each cell is one configuration's verdict on one claim: held, failed, or
 * n/a (the sweep cannot show it).  A cell spans its m/c halfway (in log
 * scale) to its neighbours.  The tc2000 profile's m/c is a dashed line and
 * the cells at it are outlined; a legend below. */
#include "prog/plot/claims.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "util/csvtab.h"
#include "util/progname.h"
#include "sim/sim.h"
#include "prog/plot/svgchart.h"
#include "util/xmem.h"

enum { W = 940, LW = 300, RM = 30, TOP = 64, RH = 22, PHEAD = 30, PFOOT = 40, LEG = 58 };

static const char *const claim_label[8] = {"",
                                           "1  2 processors slightly slower than 1",
                                           "2  large drop from 2 to 3",
                                           "3  half: little change 3-4 and 5-6",
                                           "4  speedup flattens, degrades from ~12",
                                           "5  size better than half, no plateaus",
                                           "6  d = 80 gives the best time",
                                           "7  larger contours, larger speedups"};
static const char *const fill[3] = {"#d9d9d9", "#d62728", "#2ca02c"};   /* n/a, failed, held */

/* The columns that tell panels apart (all but m and m/c; L is m under loggp). */
static const char *const keycol[] = {"net", "input", "pair", "seed", "c", "o", "g", "G", "per_byte", "master_c"};
enum { NKEY = sizeof keycol / sizeof *keycol };

typedef struct {
  int row0;          /* its first row, for the key */
  int n, *rows;      /* its rows, sorted by m/c */
} panel;

static const csvtab *sort_tab;
static int sort_col;
static int by_x(const void *a, const void *b) {
  double x = atof(sort_tab->cell[*(const int *)a][sort_col]), y = atof(sort_tab->cell[*(const int *)b][sort_col]);
  return (x > y) - (x < y);
}

static int verdict(const char *s) { return strcmp(s, "1") == 0 ? 2 : strcmp(s, "0") == 0 ? 1 : 0; }

typedef struct {
  const csvtab *t;
  panel *p;
  int np, kc[NKEY], xc, cc[8];
  const char *title;
  double lo, hi;   /* the axis, log10 */
  double tc, tc_m, tc_c;   /* the tc2000's m/c, m and c */
} grid;

static double gx(const grid *g, double lx) { return LW + (lx - g->lo) / (g->hi - g->lo) * (W - LW - RM); }

/* The cell's left and right edges in log10 m/c. */
static void cell_span(const grid *g, const panel *p, int i, double *l, double *r) {
  double x = log10(atof(g->t->cell[p->rows[i]][g->xc]));
  double xl = i > 0 ? log10(atof(g->t->cell[p->rows[i - 1]][g->xc])) : NAN;
  double xr = i + 1 < p->n ? log10(atof(g->t->cell[p->rows[i + 1]][g->xc])) : NAN;
  double half = 0.15;   /* a lone column: 0.3 of a decade */
  if (!isnan(xl) && !isnan(xr)) half = fmin(x - xl, xr - x) / 2;
  else if (!isnan(xl)) half = (x - xl) / 2;
  else if (!isnan(xr)) half = (xr - x) / 2;
  *l = isnan(xl) ? x - half : (xl + x) / 2;
  *r = isnan(xr) ? x + half : (x + xr) / 2;
}

static void panel_title(FILE *f, const grid *g, const panel *p) {
  const csvtab *t = g->t;
  char *const *row = t->cell[p->row0];
  const char *in = row[g->kc[1]];
  fputs(row[g->kc[0]], f);
  if (strcmp(in, "generated") == 0) {
    fputs(", generated pair, seed ", f);
    svg_text(f, row[g->kc[3]]);
  } else {
    const char *base = strrchr(in, '/');
    fputs(", ", f);
    svg_text(f, base ? base + 1 : in);
    fputs(" pair ", f);
    svg_text(f, row[g->kc[2]]);
  }
  /* the other columns that differ between panels */
  for (int k = 4; k < NKEY; k++)
    for (int q = 0; q < g->np; q++)
      if (strcmp(t->cell[g->p[q].row0][g->kc[k]], row[g->kc[k]]) != 0) {
        fprintf(f, ", %s = ", keycol[k]);
        svg_text(f, row[g->kc[k]]);
        break;
      }
}

static void draw(FILE *f, const grid *g) {
  int ph = PHEAD + 7 * RH + PFOOT, H = TOP + g->np * ph + LEG;
  fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
             "font-family=\"Helvetica, Arial, sans-serif\" font-size=\"13\">\n", W, H, W, H);
  fprintf(f, "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n", W, H);
  fputs("<text x=\"16\" y=\"28\" font-size=\"16\" font-weight=\"bold\">", f);
  svg_text(f, g->title);
  fputs("</text>\n", f);
  fputs("<text x=\"16\" y=\"48\">each cell: one configuration's sweeps (P = 1..16, half and size, at each size; "
        "d = 20..100 at the largest) judged on one claim</text>\n", f);
  for (int q = 0; q < g->np; q++) {
    const panel *p = &g->p[q];
    int y0 = TOP + q * ph, gy = y0 + PHEAD;
    fprintf(f, "<text x=\"16\" y=\"%d\" font-weight=\"bold\">", y0 + 20);
    panel_title(f, g, p);
    fputs("</text>\n", f);
    for (int c = 1; c <= 7; c++) {
      fprintf(f, "<text x=\"16\" y=\"%d\">", gy + (c - 1) * RH + 15);
      svg_text(f, claim_label[c]);
      fputs("</text>\n", f);
    }
    for (int i = 0; i < p->n; i++) {
      double l, r, x = atof(g->t->cell[p->rows[i]][g->xc]);
      cell_span(g, p, i, &l, &r);
      int at_tc = fabs(x - g->tc) <= 1e-9 * g->tc;
      for (int c = 1; c <= 7; c++)
        fprintf(f, "<rect x=\"%.2f\" y=\"%d\" width=\"%.2f\" height=\"%d\" fill=\"%s\" stroke=\"white\"/>\n",
                gx(g, l), gy + (c - 1) * RH, gx(g, r) - gx(g, l), RH, fill[verdict(g->t->cell[p->rows[i]][g->cc[c]])]);
      if (at_tc)
        fprintf(f, "<rect x=\"%.2f\" y=\"%d\" width=\"%.2f\" height=\"%d\" fill=\"none\" stroke=\"black\" "
                   "stroke-width=\"2.5\"/>\n", gx(g, l), gy, gx(g, r) - gx(g, l), 7 * RH);
      fprintf(f, "<line x1=\"%.2f\" y1=\"%d\" x2=\"%.2f\" y2=\"%d\" stroke=\"black\"/>\n", gx(g, log10(x)),
              gy + 7 * RH, gx(g, log10(x)), gy + 7 * RH + 4);
    }
    /* the axis: 1, 2, 5 times the powers of ten */
    int ay = gy + 7 * RH;
    fprintf(f, "<line x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\" stroke=\"black\"/>\n", LW, ay, W - RM, ay);
    for (int e = (int)floor(g->lo) - 1; e <= (int)ceil(g->hi); e++)
      for (int m = 1; m <= 5; m += m == 1 ? 1 : 3) {
        double lx = e + log10(m);
        if (lx < g->lo - 1e-9 || lx > g->hi + 1e-9) continue;
        fprintf(f, "<text x=\"%.2f\" y=\"%d\" text-anchor=\"middle\" fill=\"#555\">%g</text>\n", gx(g, lx), ay + 17,
                m * pow(10, e));
      }
    fprintf(f, "<text x=\"%d\" y=\"%d\" text-anchor=\"end\" fill=\"#555\">m/c (a message's cost over a node's)</text>\n",
            W - RM, ay + 34);
    double lt = log10(g->tc);
    if (lt >= g->lo && lt <= g->hi) {
      fprintf(f, "<line x1=\"%.2f\" y1=\"%d\" x2=\"%.2f\" y2=\"%d\" stroke=\"black\" stroke-dasharray=\"5 3\"/>\n",
              gx(g, lt), gy - 6, gx(g, lt), ay + 4);
      fprintf(f, "<text x=\"%.2f\" y=\"%d\" text-anchor=\"middle\" font-size=\"11\">tc2000</text>\n", gx(g, lt), gy - 8);
    }
  }
  /* the legend */
  int ly = TOP + g->np * ph + 16;
  static const char *const what[3] = {"n/a: the sweep cannot show it", "fails", "holds"};
  static const int at[3] = {190, 110, 16};
  for (int i = 0; i < 3; i++) {
    fprintf(f, "<rect x=\"%d\" y=\"%d\" width=\"18\" height=\"14\" fill=\"%s\"/>\n", at[i], ly, fill[i]);
    fprintf(f, "<text x=\"%d\" y=\"%d\">%s</text>\n", at[i] + 24, ly + 12, what[i]);
  }
  fprintf(f, "<line x1=\"440\" y1=\"%d\" x2=\"440\" y2=\"%d\" stroke=\"black\" stroke-dasharray=\"5 3\"/>\n", ly - 2,
          ly + 16);
  fprintf(f, "<rect x=\"448\" y=\"%d\" width=\"18\" height=\"14\" fill=\"none\" stroke=\"black\" "
             "stroke-width=\"2.5\"/>\n", ly);
  fprintf(f, "<text x=\"474\" y=\"%d\">the tc2000 profile: m/c = %g (m = %g us, c = %g us)</text>\n", ly + 12,
          g->tc_m / g->tc_c, g->tc_m * 1e6, g->tc_c * 1e6);
  fputs("</svg>\n", f);
}

static int usage(const char *why, const char *val) {
  return args_usage("plot", "usage: plot claims MAP.csv [--title T] -o OUT.svg   (plot --help: every option)\n", why, val);
}

int plot_claims(int argc, char **argv) {
  const char *in = argc > 2 ? argv[2] : NULL, *out = NULL, *title = "Where the paper's claims hold";
  char msg[400];
  if (!in || !in[0] || in[0] == '-') return usage("no claims map (tilesim-bench --claims-map -o MAP.csv)", NULL);
  for (int i = 3; i < argc; i += 2) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (strcmp(a, "-o") != 0 && strcmp(a, "--title") != 0)
      return usage(a[0] == '-' ? "unknown option" : "unexpected argument", a);
    if (!v) return usage("an option needs a value", a);
    if (strcmp(a, "-o") == 0) {
      if (svg_name(a, v, msg, sizeof msg) != 0) return usage(msg, NULL);
      out = v;
    } else {
      title = v;
    }
  }
  if (!out) return usage("claims needs -o", NULL);
  char err[400];
  csvtab t;
  if (csvtab_read(in, &t, err, sizeof err) != 0) {
    progname_eprintf("plot: %s\n", err);
    return 1;
  }
  grid g;
  memset(&g, 0, sizeof g);
  g.t = &t, g.title = title;
  int bad = (g.xc = csvtab_col(&t, "m_over_c")) < 0;
  for (int k = 0; k < NKEY; k++) bad |= (g.kc[k] = csvtab_col(&t, keycol[k])) < 0;
  for (int c = 1; c <= 7; c++) {
    char name[24];
    snprintf(name, sizeof name, "claim%d", c);
    bad |= (g.cc[c] = csvtab_col(&t, name)) < 0;
  }
  if (bad) {
    progname_eprintf("plot: %s: not a claims map (tilesim-bench --claims-map): no m_over_c, claim1..claim7 or "
                    "configuration columns\n", in);
    csvtab_free(&t);
    return 1;
  }
  /* Panels, in order of first appearance; rows with an m/c to place. */
  g.p = xcalloc((size_t)t.nrow + 1, sizeof *g.p);
  g.lo = INFINITY, g.hi = -INFINITY;
  for (int r = 0; r < t.nrow; r++) {
    double x = atof(t.cell[r][g.xc]);
    if (!(x > 0) || !isfinite(x)) continue;
    int q = 0;
    for (; q < g.np; q++) {
      int same = 1;
      for (int k = 0; k < NKEY && same; k++) same = strcmp(t.cell[g.p[q].row0][g.kc[k]], t.cell[r][g.kc[k]]) == 0;
      if (same) break;
    }
    if (q == g.np) g.p[g.np++] = (panel){r, 0, xmallocarray((size_t)t.nrow, sizeof(int))};
    g.p[q].rows[g.p[q].n++] = r;
  }
  if (g.np == 0) {
    progname_eprintf("plot: %s: no configuration with an m/c above 0\n", in);
    free(g.p);
    csvtab_free(&t);
    return 1;
  }
  sort_tab = &t, sort_col = g.xc;
  for (int q = 0; q < g.np; q++) {
    qsort(g.p[q].rows, (size_t)g.p[q].n, sizeof(int), by_x);
    for (int i = 0; i < g.p[q].n; i++) {
      double l, r;
      cell_span(&g, &g.p[q], i, &l, &r);
      g.lo = fmin(g.lo, l), g.hi = fmax(g.hi, r);
    }
  }
  sim_config tc;
  sim_config_init(&tc);
  g.tc = tc.m / tc.c, g.tc_m = tc.m, g.tc_c = tc.c;
  int rc = 0;
  atomicfile af;
  if (atomicfile_open(&af, out, "w", err, sizeof err) != 0) {
    progname_eprintf("plot: %s\n", err);
    rc = 1;
  } else {
    draw(af.f, &g);
    if (atomicfile_close(&af, 1, err, sizeof err) != 0) {
      progname_eprintf("plot: %s\n", err);
      rc = 1;
    }
  }
  for (int q = 0; q < g.np; q++) free(g.p[q].rows);
  free(g.p);
  csvtab_free(&t);
  return rc;
}
