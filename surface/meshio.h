/* meshio.h -- writing meshes as OBJ, PLY (ASCII, double) or binary STL.
 *
 * The file is written to a temporary file beside the target and renamed into
 * place only when complete: a failed run leaves no partial file. */
#ifndef MESHIO_H
#define MESHIO_H

#include <stddef.h>

#include "surface/mesh.h"

typedef enum { MESHIO_NONE = -1, MESHIO_OBJ, MESHIO_PLY, MESHIO_STL } meshio_format;

/* The format named by the path's extension (.obj, .ply, .stl, any case),
 * or MESHIO_NONE. */
meshio_format meshio_format_of(const char *file);

/* Write me to path in the format of its extension.  Returns 0, or -1 with a
 * message "PATH: what went wrong" in err. */
int meshio_write(const mesh *me, const char *file, char *err, size_t errlen);

#endif
