/* svgsurface.h -- a contour stack and its surface, drawn side by side as SVG
 * from one fixed viewpoint (the paper's Fig. 17). */
#ifndef SVGSURFACE_H
#define SVGSURFACE_H

#include <stdio.h>

#include "input/contour.h"
#include "surface/mesh.h"

/* Left: the contours as lines; right: the mesh's triangles, shaded (Lambert,
 * one light) and painted back to front.  Deterministic text. */
void svgsurface_write(FILE *f, const char *title, const contour_stack *s, const mesh *me);

#endif
