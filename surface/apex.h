/* apex.h -- a rounder cap: a fan from the contour to one point half a slice
 * out, over a point from which the region is star-shaped (IMOD closes ends
 * by a fan to the centre at +-0.5 section, imeshContourCap; DICOMautomaton at
 * 0.49 spacing).  The fan is a valid cap only when every edge sees the
 * point from the region's side, i.e. the point lies in the polygon's kernel
 * (Preparata and Shamos 1985, 7.1.4: the kernel is the intersection of the
 * edges' inner half-planes).  Where there is no such point the cap is flat. */
#ifndef APEX_H
#define APEX_H

#include "geom/geom.h"

/* A point strictly inside the kernel of the simple polygon p[0..n-1]
 * (either orientation): the area centroid if it is one, else the centroid
 * of the kernel (half-plane clipping).  Returns 1 and *at, or 0 when the
 * polygon is not star-shaped from any point found.  Exact in the answer: a
 * point is returned only when exact orientation tests confirm it. */
int apex_point(const vec2 *p, int n, vec2 *at);

/* 1 if every edge of p has q strictly on its inner side (exact). */
int apex_sees_all(const vec2 *p, int n, vec2 q);

#endif
