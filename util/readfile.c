/* readfile.c -- a whole input file in memory (readfile.h). */
#include "util/readfile.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include "util/xmem.h"

char *readfile(const char *path, size_t *len, char *err, size_t errlen) {
  int stdin_ = strcmp(path, "-") == 0;
  FILE *f = stdin_ ? stdin : fopen(path, "rb");
  *len = 0;
  if (!f) {
    snprintf(err, errlen, "%s: cannot open (%s)", path, strerror(errno));
    return NULL;
  }
  size_t n = 0, cap = 1 << 16;
  char *buf = xmalloc(cap);
  for (;;) {
    size_t got = fread(buf + n, 1, cap - n, f);
    n += got;
    if (got == 0) break;
    if (n == cap) buf = xrealloc(buf, cap *= 2);
  }
  int bad = ferror(f), e = errno;
  if (!stdin_) fclose(f);
  if (bad) {
    snprintf(err, errlen, "%s: cannot read (%s)", path, strerror(e));
    free(buf);
    return NULL;
  }
  *len = n;
  return buf;
}

const char *readfile_name(const char *path) { return strcmp(path, "-") == 0 ? "<stdin>" : path; }
