/* slices.h -- the stack in canonical form, with each slice's nesting forest.
 *
 * Canonical: nothing depends on the file's order of contours, their start
 * points or their winding (doc/surface.md).  Slices run in increasing z; the contours of a slice are
 * sorted by their least point (x, then y: distinct, since contours on one
 * slice may not touch); each starts at that point; each runs by its depth in
 * the slice's containment forest -- depth 0 an outer boundary, 1 a hole, 2 an
 * island in a hole, ... -- counter-clockwise (seen from +z) at even depth and
 * clockwise at odd depth, so that the material is always on the left.  The
 * file's winding is not trusted (holes by nesting, not by winding: winding is
 * wrong in real files, e.g. pydicom's rtstruct.dcm).
 *
 * Refused: contours of one slice that cross or touch (geom/crossing.h). */
#ifndef SLICES_H
#define SLICES_H

#include <stddef.h>

#include "input/contour.h"
#include "surface/inside.h"

typedef struct {
  int n;             /* points */
  vec2 *pt;          /* canonical: from the least point, oriented by depth */
  int line;          /* its "C" line in the file */
  int slice;         /* 0 .. nslices-1, increasing z */
  int pos;           /* its place among the slice's contours (0, 1, ...) */
  int depth;         /* 0 outer boundary, 1 hole, 2 island in a hole, ... */
  int parent;        /* the contour directly around it (index into c), or -1 */
  int base;          /* mesh vertex of pt[0]; pt[k] is vertex base + k */
  double area2;      /* twice the signed area: > 0 at even depth, < 0 at odd */
  int filecw;        /* 1 if the file gave it clockwise */
  inside_index *ix;  /* point location against it */
  int src;           /* its contour in the stack given (index into contour_stack.c) */
  int from, rev;     /* pt[k] is that contour's point (from + k) mod n, or (from - k)
                        mod n when rev (a hole, turned clockwise) */
} slice_contour;

typedef struct {
  int ncontours;
  slice_contour *c;  /* slice by slice; within a slice in canonical order */
  int nslices;
  double *z;         /* each slice's z */
  int *first;        /* slice k holds c[first[k] .. first[k+1]-1] */
  int nverts;        /* the contours' points in all: mesh vertices 0 .. nverts-1 */
  int reoriented;    /* contours whose file winding disagreed with their depth */
  int scale;         /* the points and z are the file's times 2^-scale (slices_build_at);
                        messages give ldexp(v, scale), the file's own values */
} slices;

/* Build from the stack s (read from the file `name`, for messages), slices
 * on `threads` threads.  Returns 0, or -1 with "NAME:LINE: contour crosses
 * the contour at line K on slice z=Z (at X Y)" in err (the lowest slice with
 * a crossing; LINE the later contour in the file). */
int slices_build(const contour_stack *s, const char *name, int threads, slices *out, char *err,
                 size_t errlen);

/* The same on the stack multiplied by 2^-scale (x, y and z, exactly unless a
 * value falls below 2^-1022; messages in the file's units).  With scale =
 * slices_scale_exp(s) the largest coordinate lies in [1/2, 1): every product
 * the surface forms is then safe, and a stack scaled by 2^k (exactly) gives
 * bit-identical slices (surface/stack.h). */
int slices_build_at(const contour_stack *s, const char *name, int scale, int threads, slices *out,
                    char *err, size_t errlen);

/* The e for which the stack's largest |x|, |y| or |z| times 2^-e lies in
 * [1/2, 1) (geom_scale_exp; 0 for an all-zero stack). */
int slices_scale_exp(const contour_stack *s);

void slices_free(slices *sl);

#endif
