/* solids.h -- analytic solids sliced exactly, as references for ./tile.
 *
 * A solid (a sphere, two spheres, a torus, a hollow sphere, ...) is cut by
 * planes z = z_k; each section is a set of closed curves (circular arcs, or
 * the curves of a torus cut across its axis).  solid_slice() samples every
 * curve at points that lie on it, so every polygon is inscribed in the true
 * section, and returns them as a contour stack, outer contours
 * counter-clockwise and holes clockwise seen from +z.  Beside the stack come
 * the facts a mesh of it must match, derived in closed form (or by
 * quadrature of closed-form integrands), never from the polygons: the
 * surface's components, their Euler characteristics and orientations, the
 * exact section areas, the exact area of each polygon where its curve is made
 * of circular arcs, and the solid's volume between two planes. */
#ifndef SOLIDS_H
#define SOLIDS_H

#include <stdio.h>

enum { SOLID_MAXCOMP = 4 };

typedef struct {
  const char *name;     /* "sphere", "torus_across", ... */
  const char *what;     /* one line for messages */
  int multi;            /* some slice has several contours (needs the stack tiler) */
  double za, zb;        /* the first and last plane solid_planes() uses */
  int ncomp;            /* connected components of the boundary surface */
  int chi[SOLID_MAXCOMP];    /* Euler characteristic of each, 2 - 2 genus */
  int sign[SOLID_MAXCOMP];   /* +1 an outer shell, -1 a cavity's surface */
} solid_info;

typedef struct {
  int n;                /* points */
  double z;
  double *x, *y;        /* n each, in order; the closing point is not repeated */
  int depth;            /* 0 an outer boundary, 1 a hole, 2 an island in a hole */
  double region;        /* signed area of the true section curve it samples */
  double exact;         /* signed area of this polygon in closed form (arc
                           curves), or NAN where there is none (torus curves) */
} sl_contour;

typedef struct {
  int nslice;
  double *z;            /* nslice planes, increasing */
  int *first, *count;   /* slice k holds c[first[k] .. first[k] + count[k]) */
  int n;                /* contours */
  sl_contour *c;
} sl_stack;

int solid_count(void);
const solid_info *solid_get(int s);
int solid_find(const char *name);    /* index, or -1 */

/* K planes from za to zb: evenly spaced, or (uneven != 0) with spacings
 * varying smoothly by a factor of about 2 along the stack. */
void solid_planes(int s, int K, int uneven, double *z);

/* The section at z: the number of curves and their exact signed area (outer
 * curves count positive, holes negative). */
int solid_section_count(int s, double z);
double solid_section_area(int s, double z);

/* The solid's volume between the planes a <= b: closed forms, or adaptive
 * quadrature of closed-form integrands to ~1e-11 relative. */
double solid_volume(int s, double a, double b);

/* How far (x, y, z) is from the nearest of the surfaces the solid is made
 * of (its spheres, tori, cone or cylinder): 0 for a point on its boundary. */
double solid_surface_distance(int s, double x, double y, double z);

/* Slice at the K planes z[], about N points per curve (N >= 8).  vary != 0
 * changes N a little from curve to curve and turns the start point of full
 * circles from slice to slice, so that no two bands are alike. */
void solid_slice(int s, const double *z, int K, int N, int vary, sl_stack *out);
void sl_stack_free(sl_stack *st);

/* Write st as a .contours file (%.17g, exact).  0, or -1 with errno. */
int sl_stack_write(const sl_stack *st, const char *path);

/* Read a .contours file (comments, blank lines, CRLF; contours with the same
 * z, consecutive in the file, form one slice; depth, region and exact are
 * left 0 / NAN).  0, or -1 with a message in err. */
int sl_stack_read(const char *path, sl_stack *st, char *err, size_t errlen);

/* Drop what ./tile repairs: consecutive repeated points, and a repeated
 * closing point.  In place. */
void sl_stack_clean(sl_stack *st);

/* A second encoding of the same stack: on every slice the contours shuffled,
 * each one's start point turned and its winding reversed; a repeated closing
 * point is dropped first.  From seed; z and the points themselves unchanged. */
void sl_stack_scramble(const sl_stack *in, unsigned long long seed, sl_stack *out);

/* Polygon area by the shoelace formula (signed, counter-clockwise > 0). */
double sl_shoelace(const sl_contour *c);

/* Geometry of the stack for the tests: the smallest distance between
 * vertices of two different contours of a slice, or of one contour at least
 * n/8 steps apart along it (a neck); and whether any two segments of a slice
 * cross or touch (other than neighbours in one contour). */
double sl_stack_margin(const sl_stack *st);
int sl_stack_crossings(const sl_stack *st);

#endif
