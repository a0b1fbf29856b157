/* svgchart.h -- line charts as SVG: axes, ticks, labels, a legend. */
#ifndef SVGCHART_H
#define SVGCHART_H

#include <stddef.h>
#include <stdio.h>

typedef struct {
  const char *label;   /* in the legend */
  int n;
  const double *x, *y;
  int dashed;
} svgchart_series;

typedef struct {
  const char *title, *xlabel, *ylabel;
  int yzero;           /* 1: the y axis starts at 0 */
  int xint;            /* 1: x ticks on whole numbers */
} svgchart_opts;

/* Write the chart to f: 760 x 480 pixels, deterministic text. */
void svgchart_write(FILE *f, const svgchart_opts *o, const svgchart_series *s, int ns);

/* The SVG text escapes of s, into f. */
void svg_text(FILE *f, const char *s);

/* opt's value names an SVG picture to write: a file name as args_name takes
 * it, ending in .svg (any case), since SVG is all the plotter writes.  0, or
 * -1 with "-o takes a file name ending in .svg: plot writes SVG only
 * (x.png)" in err. */
int svg_name(const char *opt, const char *val, char *err, size_t errlen);

#endif
