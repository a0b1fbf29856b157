/* atomicfile.h -- write a file beside its target and rename it into place
 * when complete, so that a failed run never leaves a partial file (as Redis
 * writes temp-%d.rdb, then rename()). */
#ifndef ATOMICFILE_H
#define ATOMICFILE_H

#include <stddef.h>
#include <stdio.h>

typedef struct {
  FILE *f;      /* write here */
  char *path;   /* the target */
  char *tmp;    /* the temporary file beside it */
} atomicfile;

/* Open a temporary file beside path (mode 0666 less the umask).  0, or -1
 * with "PATH: why" in err. */
int atomicfile_open(atomicfile *a, const char *path, const char *mode, char *err, size_t errlen);

/* ok: flush, close and rename into place (0, or -1 with "PATH: why" in err);
 * !ok: close and remove the temporary file (returns -1). */
int atomicfile_close(atomicfile *a, int ok, char *err, size_t errlen);

#endif
