/* rtframe.h -- the planes of an RT structure set's contours: least-squares
 * normals, the frames that turn an ROI's planes into z (input/rtstruct.h). */
#ifndef RTFRAME_H
#define RTFRAME_H

#include "rtstruct.h"

/* a . p for the point p[0..2]. */
double rtframe_dot(const double a[3], const double *p);

/* A contour within this distance (mm) of a plane counts as lying in it. */
#define RTFRAME_FLAT 1e-3

/* The plane of the ROI's contours (doc/dicom.md, "Planes" and "Oblique
 * stacks"): axial, sagittal or coronal where every contour is flat in that
 * axis, else an oblique frame; sets roi->plane, roi->frame and each
 * contour's height h.  0, with a warning to show in *warn (malloc'd, or
 * NULL); or -1 with the contour at fault in *bad (its index) and why in
 * why[0..whylen-1] ("contour item K: ..."). */
int rtframe_fit(rtstruct_roi *roi, char **warn, int *bad, char *why, size_t whylen);

#endif
