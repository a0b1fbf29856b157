/* geom.h -- plane geometry of contours: points, polygon area, orientation. */
#ifndef GEOM_H
#define GEOM_H

typedef struct { double x, y; } vec2;

/* Twice the signed area of the closed polygon p[0..n-1] (shoelace, about
 * its first point): positive when counter-clockwise seen from +z. */
double geom_area2(const vec2 *p, int n);

/* 1 if every point of p[0..n-1] lies on one line (to within 1e-12 of the
 * polygon's extent), else 0. */
int geom_collinear(const vec2 *p, int n);

/* Reverse p[0..n-1] in place, keeping p[0] first. */
void geom_reverse(vec2 *p, int n);

#endif
