/* svgchart.c -- a small line-chart renderer: "nice" ticks (1, 2, 5 times a
 * power of ten), one colour per series, markers, a legend box. */
#include "svgchart.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "args.h"

enum { W = 760, H = 480, ML = 78, MR = 190, MT = 48, MB = 62 };

static const char *colour[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                               "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"};

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
  double pw = W - ML - MR, ph = H - MT - MB;
#define PX(v) (ML + ((v) - x0) / (x1 - x0) * pw)
#define PY(v) (MT + ph - ((v) - y0) / (y1 - y0) * ph)
  fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
             "font-family=\"Helvetica, Arial, sans-serif\" font-size=\"13\">\n", W, H, W, H);
  fprintf(f, "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n", W, H);
  fprintf(f, "<text x=\"%d\" y=\"28\" font-size=\"16\" font-weight=\"bold\">", ML);
  svg_text(f, o->title ? o->title : "");
  fputs("</text>\n", f);
  /* Grid and ticks. */
  char b[32];
  for (double v = ceil(x0 / xs) * xs; v <= x1 + xs * 1e-9; v += xs) {
    fprintf(f, "<line x1=\"%.2f\" y1=\"%d\" x2=\"%.2f\" y2=\"%d\" stroke=\"#e6e6e6\"/>\n", PX(v), MT, PX(v), H - MB);
    fmt(b, sizeof b, v, xs);
    fprintf(f, "<text x=\"%.2f\" y=\"%d\" text-anchor=\"middle\">%s</text>\n", PX(v), H - MB + 18, b);
  }
  for (double v = y0; v <= y1 + ys * 1e-9; v += ys) {
    fprintf(f, "<line x1=\"%d\" y1=\"%.2f\" x2=\"%d\" y2=\"%.2f\" stroke=\"#e6e6e6\"/>\n", ML, PY(v), W - MR, PY(v));
    fmt(b, sizeof b, v, ys);
    fprintf(f, "<text x=\"%d\" y=\"%.2f\" text-anchor=\"end\">%s</text>\n", ML - 8, PY(v) + 4, b);
  }
  fprintf(f, "<rect x=\"%d\" y=\"%d\" width=\"%.0f\" height=\"%.0f\" fill=\"none\" stroke=\"black\"/>\n", ML, MT, pw, ph);
  fprintf(f, "<text x=\"%.2f\" y=\"%d\" text-anchor=\"middle\">", ML + pw / 2, H - 18);
  svg_text(f, o->xlabel ? o->xlabel : "");
  fputs("</text>\n", f);
  fprintf(f, "<text transform=\"translate(20 %.2f) rotate(-90)\" text-anchor=\"middle\">", MT + ph / 2);
  svg_text(f, o->ylabel ? o->ylabel : "");
  fputs("</text>\n", f);
  /* The series, then the legend. */
  for (int i = 0; i < ns; i++) {
    const char *col = colour[i % 10];
    fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\"%s points=\"", col,
            s[i].dashed ? " stroke-dasharray=\"6 4\"" : "");
    for (int k = 0; k < s[i].n; k++)
      if (isfinite(s[i].y[k])) fprintf(f, "%s%.2f,%.2f", k ? " " : "", PX(s[i].x[k]), PY(s[i].y[k]));
    fputs("\"/>\n", f);
    for (int k = 0; k < s[i].n; k++)
      if (isfinite(s[i].y[k]))
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3\" fill=\"%s\"/>\n", PX(s[i].x[k]), PY(s[i].y[k]), col);
    double ly = MT + 12 + 22 * i;
    fprintf(f, "<line x1=\"%d\" y1=\"%.2f\" x2=\"%d\" y2=\"%.2f\" stroke=\"%s\" stroke-width=\"2\"%s/>\n",
            W - MR + 14, ly, W - MR + 40, ly, col, s[i].dashed ? " stroke-dasharray=\"6 4\"" : "");
    fprintf(f, "<text x=\"%d\" y=\"%.2f\">", W - MR + 46, ly + 4);
    svg_text(f, s[i].label);
    fputs("</text>\n", f);
  }
  fputs("</svg>\n", f);
#undef PX
#undef PY
}
