/* progname.c -- the sources' name of a program written as the name it was
 * run by. */
#include "util/progname.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

static const char *src_name = "";   /* "bench" */
static const char *run_name = "";   /* "tilesim-bench" */
static int at_start = 1;            /* the last write to stderr ended a line */

void progname_init(const char *name, const char *argv0) {
  const char *base = argv0 && *argv0 ? argv0 : name;
  const char *slash = strrchr(base, '/');
  src_name = name;
  run_name = slash && slash[1] ? slash + 1 : base;
}

const char *progname(void) { return run_name; }

const char *progname_as(const char *prog) {
  return *src_name && prog && strcmp(prog, src_name) == 0 ? run_name : prog;
}

/* Is text + i the sources' name as a word? */
static int word_at(const char *text, size_t i, size_t n) {
  if (n == 0 || strncmp(text + i, src_name, n) != 0) return 0;
  char after = text[i + n];
  if (after && !strchr(" :,;)\n", after)) return 0;
  if (i == 0) return 1;
  char before = text[i - 1];
  if (!strchr(" (\n", before)) return 0;
  return !(i >= 5 && strncmp(text + i - 5, "make ", 5) == 0);
}

void progname_fputs(const char *text, FILE *f) {
  size_t n = strlen(src_name);
  if (n == 0 || strcmp(src_name, run_name) == 0) {
    fputs(text, f);
    return;
  }
  for (size_t i = 0; text[i];) {
    if (word_at(text, i, n)) {
      fputs(run_name, f);
      i += n;
    } else {
      fputc(text[i++], f);
    }
  }
}

void progname_eprintf(const char *fmt, ...) {
  char small[1024], *buf = small;
  va_list ap;
  va_start(ap, fmt);
  int len = vsnprintf(small, sizeof small, fmt, ap);
  va_end(ap);
  if (len < 0) return;
  if ((size_t)len >= sizeof small) {
    buf = xmalloc((size_t)len + 1);
    va_start(ap, fmt);
    vsnprintf(buf, (size_t)len + 1, fmt, ap);
    va_end(ap);
  }
  size_t n = strlen(src_name);
  int same = n == 0 || strcmp(src_name, run_name) == 0;
  flockfile(stderr);
  for (int i = 0; i < len;) {
    if (at_start && !same && strncmp(buf + i, src_name, n) == 0 && buf[i + (int)n] == ':') {
      fputs(run_name, stderr);
      i += (int)n;
      at_start = 0;
      continue;
    }
    at_start = buf[i] == '\n';
    putc_unlocked(buf[i++], stderr);
  }
  funlockfile(stderr);
  if (buf != small) free(buf);
}
