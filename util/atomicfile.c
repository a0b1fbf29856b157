/* atomicfile.c -- a temporary file, then rename(). */
#include "atomicfile.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "xmem.h"

int atomicfile_open(atomicfile *a, const char *path, const char *mode, char *err, size_t errlen) {
  size_t len = strlen(path) + 16;
  a->f = NULL;
  a->path = xstrdup(path);
  a->tmp = xmalloc(len);
  snprintf(a->tmp, len, "%s.tmpXXXXXX", path);
  int fd = mkstemp(a->tmp);
  if (fd >= 0) {
    mode_t um = umask(0);   /* mkstemp makes 0600; give the file the usual mode */
    umask(um);
    fchmod(fd, 0666 & ~um);
    a->f = fdopen(fd, mode);
  }
  if (!a->f) {
    snprintf(err, errlen, "%s: cannot create a temporary file beside it (%s)", path, strerror(errno));
    if (fd >= 0) close(fd), unlink(a->tmp);
    free(a->path), free(a->tmp);
    a->path = a->tmp = NULL;
    return -1;
  }
  return 0;
}

int atomicfile_close(atomicfile *a, int ok, char *err, size_t errlen) {
  int bad = !ok || fflush(a->f) != 0 || ferror(a->f);
  int e = errno;
  if (fclose(a->f) != 0 && !bad) bad = 1, e = errno;
  if (!bad && rename(a->tmp, a->path) != 0) bad = 1, e = errno;
  if (bad) {
    if (ok) snprintf(err, errlen, "%s: cannot write (%s)", a->path, strerror(e));
    unlink(a->tmp);
  }
  free(a->path);
  free(a->tmp);
  a->f = NULL;
  a->path = a->tmp = NULL;
  return bad ? -1 : 0;
}
