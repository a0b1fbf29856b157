/* xmem.h -- allocation that never returns NULL, and the one way to die. */
#ifndef XMEM_H
#define XMEM_H

#include <stddef.h>

/* Allocate, or print the size asked for and abort: out of memory is not an
 * error any caller can mend.  Free with free(). */
void *xmalloc(size_t size);
void *xcalloc(size_t count, size_t size);
void *xrealloc(void *p, size_t size);
char *xstrdup(const char *s);

/* Array helpers: count * size with an overflow check. */
void *xmallocarray(size_t count, size_t size);
void *xreallocarray(void *p, size_t count, size_t size);

/* A broken internal invariant: print "tilesim: internal error: ..." and abort. */
void xpanic(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((noreturn, format(printf, 1, 2)))
#endif
    ;

#define XASSERT(cond)                                                          \
  do {                                                                         \
    if (!(cond))                                                               \
      xpanic("%s:%d: assertion failed: %s", __FILE__, __LINE__, #cond);       \
  } while (0)

#endif
