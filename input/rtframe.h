/* rtframe.h -- the planes of an RT structure set's contours: least-squares
 * normals, the frames that turn an ROI's planes into z (input/rtstruct.h). */
#ifndef RTFRAME_H
#define RTFRAME_H

#include "input/rtstruct.h"

/* a . p for the point p[0..2]. */
double rtframe_dot(const double a[3], const double *p);

/* A contour whose points lie within this distance (mm) of a plane lies in
 * it, whatever the coordinates' precision; one whose points spread more
 * than RTFRAME_BENT off it never does. */
#define RTFRAME_FLAT 1e-3
#define RTFRAME_BENT 0.1

/* The plane of the ROI's contours (doc/dicom.md, "Planes" and "Oblique
 * stacks"): axial, sagittal or coronal where every contour is flat in that
 * axis, else an oblique frame; sets roi->plane, roi->frame, roi->flat and
 * each contour's height h.  Flat is judged against the coordinates' own
 * precision: the place value q of the last digit the file writes (the
 * least over the ROI's values, decimal.h) rounds each coordinate by up to
 * q/2, so points along a unit normal n may spread (|nx| + |ny| + |nz|) q
 * (and a quarter more) and lie in one plane: 0.01 mm rounding at any tilt
 * passes, a contour bent further is refused.  0, with a warning to show in *warn (malloc'd, or
 * NULL); or -1 with the contour at fault in *bad (its index) and why in
 * why[0..whylen-1] ("contour item K: ..."). */
int rtframe_fit(rtstruct_roi *roi, char **warn, int *bad, char *why, size_t whylen);

#endif
