/* svgchart.c -- a small line-chart renderer: "nice" ticks (1, 2, 5 times a
 * power of ten), a colour and a marker per group of series, dash patterns,
 * a legend box; the picture sized to its texts. */
#include "prog/plot/svgchart.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "util/xmem.h"

/* The default picture and its margins; the plot keeps at least PW x PH. */
enum { W0 = 760, H0 = 480, ML0 = 78, MR0 = 190, MT0 = 48, MB = 62, PW = 492, PH = 370, LEG = 22 };

static const char *colour[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                               "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"};
enum { NCOLOUR = sizeof colour / sizeof *colour, NMARKER = 7 };
static const char *dash[] = {"", "6 4", "2 3", "9 3 2 3", "1 5"};
enum { NDASH = sizeof dash / sizeof *dash };

/* The wider of two fonts, character by character (32 to 126), regular and
 * bold: Helvetica (Adobe's AFM files, which Arial and Liberation Sans
 * match) and DejaVu Sans (its hmtx table; what Linux viewers fall back on
 * without them).  Advance widths in 1/1000 em. */
static const short widest[2][95] = {
    {318, 401, 460, 838, 636, 950, 780, 275, 390, 390, 500, 838, 318, 361, 318, 337, 636, 636, 636, 636,
     636, 636, 636, 636, 636, 636, 337, 337, 838, 838, 838, 556, 1015, 684, 686, 722, 770, 667, 611, 778,
     752, 295, 500, 667, 557, 863, 748, 787, 667, 787, 722, 667, 611, 732, 684, 989, 685, 667, 685, 390,
     337, 390, 838, 556, 500, 613, 635, 550, 635, 615, 352, 635, 634, 278, 278, 579, 278, 974, 634, 612,
     635, 635, 411, 521, 392, 634, 592, 818, 592, 592, 525, 636, 337, 636, 838},
    {348, 456, 521, 838, 696, 1002, 872, 306, 457, 457, 523, 838, 380, 415, 380, 365, 696, 696, 696, 696,
     696, 696, 696, 696, 696, 696, 400, 400, 838, 838, 838, 611, 1000, 774, 762, 734, 830, 683, 683, 821,
     837, 372, 556, 775, 637, 995, 837, 850, 733, 850, 770, 720, 682, 812, 774, 1103, 771, 724, 725, 457,
     365, 457, 838, 556, 500, 675, 716, 593, 716, 678, 435, 716, 712, 343, 343, 665, 343, 1042, 712, 687,
     716, 716, 493, 595, 478, 712, 652, 924, 645, 652, 582, 712, 365, 712, 838}};

double svg_text_width(const char *s, double px, int bold) {
  double em = 0;
  for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
    if (*p >= 32 && *p <= 126) em += widest[bold != 0][*p - 32] / 1000.0;
    else if ((*p & 0xC0) != 0x80) em += 1;   /* a character beyond ASCII (its first byte) */
  }
  return em * px * 1.03;
}

void svg_text(FILE *f, const char *s) {
  for (; *s; s++) {
    if (*s == '<') fputs("&lt;", f);
    else if (*s == '>') fputs("&gt;", f);
    else if (*s == '&') fputs("&amp;", f);
    else fputc(*s, f);
  }
}

int svg_name(const char *opt, const char *val, char *err, size_t errlen) {
  if (args_name(opt, val, "a file name", 0, err, errlen) != 0) return -1;
  size_t n = strlen(val);
  static const char ext[] = ".svg";
  int svg = n >= 4;
  for (size_t k = 0; svg && k < 4; k++) svg = tolower((unsigned char)val[n - 4 + k]) == ext[k];
  if (svg) return 0;
  char shown[200];
  const char *dot = strrchr(val, '.');
  args_show(val, shown, sizeof shown);
  if (dot && !strchr(dot, '/') && dot[1])
    snprintf(err, errlen, "%s takes a file name ending in .svg: the plotter writes SVG only, not %s (%s); "
             "a converter such as rsvg-convert makes other formats from it", opt, dot + 1, shown);
  else
    snprintf(err, errlen, "%s takes a file name ending in .svg: the plotter writes SVG only (%s)", opt, shown);
  return -1;
}

/* A tick step for the range: 1, 2 or 5 times a power of ten, about 6 ticks. */
static double nice_step(double span, int whole) {
  if (!(span > 0)) return 1;
  double raw = span / 6, p = pow(10, floor(log10(raw))), st = p;
  if (raw / p > 5) st = 10 * p;
  else if (raw / p > 2) st = 5 * p;
  else if (raw / p > 1) st = 2 * p;
  if (whole && st < 1) st = 1;
  return st;
}

static void fmt(char *b, size_t n, double v, double step) {
  int dec = step >= 1 ? 0 : (int)ceil(-log10(step) - 1e-9);
  if (dec > 6) dec = 6;
  snprintf(b, n, "%.*f", dec, fabs(v) < step * 1e-9 ? 0.0 : v);
}

/* The title's lines: text cut at blanks so that each line is at most w wide
 * at 16 px bold (a word wider than w stands alone); the count, at most max,
 * the starts and lengths in at[] and len[]. */
static int wrap(const char *text, double w, int max, const char **at, int *len) {
  int n = 0;
  const char *p = text;
  char buf[1024];
  while (*p && n < max) {
    while (*p == ' ') p++;
    if (!*p) break;
    const char *end = p, *best = NULL;
    for (;;) {   /* extend word by word while the line fits */
      const char *q = end;
      while (*q == ' ') q++;
      while (*q && *q != ' ') q++;
      int l = (int)(q - p) < (int)sizeof buf - 1 ? (int)(q - p) : (int)sizeof buf - 1;
      memcpy(buf, p, (size_t)l);
      buf[l] = 0;
      if (best && svg_text_width(buf, 16, 1) > w) break;
      best = end = q;
      if (!*q) break;
    }
    if (n == max - 1) end = p + strlen(p);   /* the last line takes the rest */
    at[n] = p, len[n] = (int)(end - p), n++;
    p = end;
  }
  return n;
}

/* Does series b lie on series a (the same x, every y within tol)? */
static int lies_on(const svgchart_series *a, const svgchart_series *b, double tol) {
  if (a->n != b->n || a->n == 0) return 0;
  for (int k = 0; k < a->n; k++)
    if (a->x[k] != b->x[k] || !(fabs(a->y[k] - b->y[k]) <= tol)) return 0;
  return 1;
}

/* Marker m (0 circle, 1 square, 2 triangle, 3 diamond, 4 triangle down,
 * 5 cross, 6 plus) at (x, y), open: white inside, outlined in col. */
static void marker(FILE *f, int m, double x, double y, const char *col) {
  const double r = 3.5;
  const char *style = "fill=\"white\" stroke-width=\"1.5\"";
  switch (m % NMARKER) {
  case 0: fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.1f\" %s stroke=\"%s\"/>\n", x, y, r, style, col); break;
  case 1:
    fprintf(f, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.1f\" height=\"%.1f\" %s stroke=\"%s\"/>\n", x - r, y - r, 2 * r,
            2 * r, style, col);
    break;
  case 2:
    fprintf(f, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" %s stroke=\"%s\"/>\n", x, y - r - 1, x + r + 0.5,
            y + r, x - r - 0.5, y + r, style, col);
    break;
  case 3:
    fprintf(f, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f %.2f,%.2f\" %s stroke=\"%s\"/>\n", x, y - r - 1,
            x + r + 1, y, x, y + r + 1, x - r - 1, y, style, col);
    break;
  case 4:
    fprintf(f, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" %s stroke=\"%s\"/>\n", x, y + r + 1, x + r + 0.5,
            y - r, x - r - 0.5, y - r, style, col);
    break;
  case 5:
    fprintf(f, "<path d=\"M%.2f %.2fL%.2f %.2fM%.2f %.2fL%.2f %.2f\" stroke=\"%s\" stroke-width=\"1.8\"/>\n", x - r,
            y - r, x + r, y + r, x - r, y + r, x + r, y - r, col);
    break;
  default:
    fprintf(f, "<path d=\"M%.2f %.2fL%.2f %.2fM%.2f %.2fL%.2f %.2f\" stroke=\"%s\" stroke-width=\"1.8\"/>\n", x - r - 1,
            y, x + r + 1, y, x, y - r - 1, x, y + r + 1, col);
  }
}

static void dash_attr(FILE *f, int d) {
  if (d % NDASH) fprintf(f, " stroke-dasharray=\"%s\"", dash[d % NDASH]);
}

void svgchart_write(FILE *f, const svgchart_opts *o, const svgchart_series *s, int ns) {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (int i = 0; i < ns; i++)
    for (int k = 0; k < s[i].n; k++) {
      if (!isfinite(s[i].x[k]) || !isfinite(s[i].y[k])) continue;
      x0 = fmin(x0, s[i].x[k]), x1 = fmax(x1, s[i].x[k]);
      y0 = fmin(y0, s[i].y[k]), y1 = fmax(y1, s[i].y[k]);
    }
  if (!isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (o->yzero && y0 > 0) y0 = 0;
  if (x1 == x0) x1 = x0 + 1;
  if (y1 == y0) y1 = y0 + 1;
  double xs = nice_step(x1 - x0, o->xint), ys = nice_step(y1 - y0, 0);
  if (!o->xint) x0 = floor(x0 / xs) * xs, x1 = ceil(x1 / xs) * xs;
  y0 = floor(y0 / ys) * ys, y1 = ceil(y1 / ys) * ys;

  /* The picture sized to its texts: the y tick labels and the y label on
   * the left, the legend on the right, the title (wrapped) above, the
   * legend's rows and the y label's length down. */
  char b[32];
  double wtick = 0;
  for (double v = y0; v <= y1 + ys * 1e-9; v += ys) fmt(b, sizeof b, v, ys), wtick = fmax(wtick, svg_text_width(b, 13, 0));
  double ml = fmax(ML0, 34 + 8 + wtick), wleg = 0;
  for (int i = 0; i < ns; i++) wleg = fmax(wleg, svg_text_width(s[i].label ? s[i].label : "", 13, 0));
  double mr = fmax(MR0, 46 + wleg + 12);
  double pw = fmax(PW, svg_text_width(o->xlabel ? o->xlabel : "", 13, 0) + 8);
  double W = ceil(fmax(W0, ml + pw + mr));
  pw = W - ml - mr;
  const char *at[8];
  int len[8], nt = wrap(o->title ? o->title : "", W - ml - 12, 8, at, len);
  for (int k = 0; k < nt; k++) {   /* a word wider than the picture widens it */
    char line[1024];
    snprintf(line, sizeof line, "%.*s", len[k], at[k]);
    double need = ml + svg_text_width(line, 16, 1) + 12;
    if (need > W) W = ceil(need), pw = W - ml - mr;
  }
  double mt = MT0 + 20 * (nt > 1 ? nt - 1 : 0);
  double ph = fmax(PH, fmax(LEG * ns + 12, svg_text_width(o->ylabel ? o->ylabel : "", 13, 0) + 8));
  double H = ceil(mt + ph + MB);
#define PX(v) (ml + ((v) - x0) / (x1 - x0) * pw)
#define PY(v) (mt + ph - ((v) - y0) / (y1 - y0) * ph)
  fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
             "font-family=\"Helvetica, Arial, sans-serif\" font-size=\"13\">\n", W, H, W, H);
  fprintf(f, "<rect width=\"%.0f\" height=\"%.0f\" fill=\"white\"/>\n", W, H);
  for (int k = 0; k < nt; k++) {
    char line[1024];
    snprintf(line, sizeof line, "%.*s", len[k], at[k]);
    fprintf(f, "<text x=\"%.0f\" y=\"%d\" font-size=\"16\" font-weight=\"bold\">", ml, 28 + 20 * k);
    svg_text(f, line);
    fputs("</text>\n", f);
  }
  /* Grid and ticks. */
  for (double v = ceil(x0 / xs) * xs; v <= x1 + xs * 1e-9; v += xs) {
    fprintf(f, "<line x1=\"%.2f\" y1=\"%.0f\" x2=\"%.2f\" y2=\"%.0f\" stroke=\"#e6e6e6\"/>\n", PX(v), mt, PX(v), mt + ph);
    fmt(b, sizeof b, v, xs);
    fprintf(f, "<text x=\"%.2f\" y=\"%.0f\" text-anchor=\"middle\">%s</text>\n", PX(v), mt + ph + 18, b);
  }
  for (double v = y0; v <= y1 + ys * 1e-9; v += ys) {
    fprintf(f, "<line x1=\"%.0f\" y1=\"%.2f\" x2=\"%.0f\" y2=\"%.2f\" stroke=\"#e6e6e6\"/>\n", ml, PY(v), ml + pw, PY(v));
    fmt(b, sizeof b, v, ys);
    fprintf(f, "<text x=\"%.0f\" y=\"%.2f\" text-anchor=\"end\">%s</text>\n", ml - 8, PY(v) + 4, b);
  }
  fprintf(f, "<rect x=\"%.0f\" y=\"%.0f\" width=\"%.0f\" height=\"%.0f\" fill=\"none\" stroke=\"black\"/>\n", ml, mt,
          pw, ph);
  fprintf(f, "<text x=\"%.2f\" y=\"%.0f\" text-anchor=\"middle\">", ml + pw / 2, H - 18);
  svg_text(f, o->xlabel ? o->xlabel : "");
  fputs("</text>\n", f);
  fprintf(f, "<text transform=\"translate(20 %.2f) rotate(-90)\" text-anchor=\"middle\">", mt + ph / 2);
  svg_text(f, o->ylabel ? o->ylabel : "");
  fputs("</text>\n", f);
  /* The series, then the legend.  A series that lies on an earlier one of
   * the same dash pattern takes the next pattern no such one has. */
  int *used = xcalloc((size_t)ns + 1, sizeof *used);
  for (int i = 0; i < ns; i++) {
    int d = s[i].dashed, tries = 0, clash = 1;
    while (clash && tries++ < NDASH) {
      clash = 0;
      for (int j = 0; j < i && !clash; j++)
        clash = used[j] % NDASH == d % NDASH && lies_on(&s[j], &s[i], (y1 - y0) * 0.005);
      if (clash) d++;
    }
    used[i] = d;
    const char *col = colour[s[i].group % NCOLOUR];
    fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\"", col);
    dash_attr(f, d);
    fputs(" points=\"", f);
    for (int k = 0; k < s[i].n; k++)
      if (isfinite(s[i].y[k])) fprintf(f, "%s%.2f,%.2f", k ? " " : "", PX(s[i].x[k]), PY(s[i].y[k]));
    fputs("\"/>\n", f);
    for (int k = 0; k < s[i].n; k++)
      if (isfinite(s[i].y[k])) marker(f, s[i].group, PX(s[i].x[k]), PY(s[i].y[k]), col);
    double ly = mt + 12 + LEG * i, lx = W - mr;
    fprintf(f, "<line x1=\"%.0f\" y1=\"%.2f\" x2=\"%.0f\" y2=\"%.2f\" stroke=\"%s\" stroke-width=\"2\"", lx + 8, ly,
            lx + 40, ly, col);
    dash_attr(f, d);
    fputs("/>\n", f);
    marker(f, s[i].group, lx + 24, ly, col);
    fprintf(f, "<text x=\"%.0f\" y=\"%.2f\">", lx + 46, ly + 4);
    svg_text(f, s[i].label ? s[i].label : "");
    fputs("</text>\n", f);
  }
  free(used);
  fputs("</svg>\n", f);
#undef PX
#undef PY
}
