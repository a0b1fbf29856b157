/* svgchart.h -- line charts as SVG: axes, ticks, labels, a legend. */
#ifndef SVGCHART_H
#define SVGCHART_H

#include <stddef.h>
#include <stdio.h>

typedef struct {
  const char *label;   /* in the legend */
  int n;
  const double *x, *y;
  int dashed;          /* 0 solid; k > 0: the k-th dash pattern (a group's k-th y column) */
  int group;           /* series of one group share a colour and a marker shape
                          (a size's simulated and model times) */
} svgchart_series;

typedef struct {
  const char *title, *xlabel, *ylabel;
  int yzero;           /* 1: the y axis starts at 0 */
  int xint;            /* 1: x ticks on whole numbers */
} svgchart_opts;

/* Write the chart to f: 760 x 480 pixels, or more where the legend, the
 * title or the tick labels need it (a title too wide is wrapped at its
 * blanks), so that no text leaves the picture; deterministic text.  Every
 * series has its group's colour and marker (open, so that a marker under
 * another shows) and its dash pattern; a series that lies on an earlier one
 * gets a dash pattern of its own, so that both show. */
void svgchart_write(FILE *f, const svgchart_opts *o, const svgchart_series *s, int ns);

/* The width in pixels of text s at font size px (bold != 0: bold), in the
 * wider of Helvetica (and the fonts that match it: Arial, Liberation Sans)
 * and DejaVu Sans, the fonts a viewer draws the charts in, and 3% more; a
 * character beyond ASCII counts one em. */
double svg_text_width(const char *s, double px, int bold);

/* The SVG text escapes of s, into f. */
void svg_text(FILE *f, const char *s);

/* opt's value names an SVG picture to write: a file name as args_name takes
 * it, ending in .svg (any case), since SVG is all the plotter writes.  0, or
 * -1 with "-o takes a file name ending in .svg: plot writes SVG only
 * (x.png)" in err. */
int svg_name(const char *opt, const char *val, char *err, size_t errlen);

#endif
