/* strbuf.h -- a growing text buffer for messages: formatted and raw appends.
 *
 * A zeroed strbuf is empty (buf NULL until the first append); after any
 * append buf holds len bytes and a terminating NUL.  The caller owns buf and
 * frees it with free(). */
#ifndef STRBUF_H
#define STRBUF_H

#include <stdarg.h>
#include <stddef.h>
#include <string.h>

typedef struct {
  char *buf;
  size_t len, cap;
} strbuf;

void strbuf_vadd(strbuf *b, const char *fmt, va_list ap);
void strbuf_add(strbuf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Room for n more bytes and the NUL (grows b->buf; for strbuf_raw). */
void strbuf_grow(strbuf *b, size_t n);

/* n bytes of s as they are.  Inline: the DICOM reader appends each value of
 * a stack's text with it, three a point. */
static inline void strbuf_raw(strbuf *b, const char *s, size_t n) {
  if (b->len + n + 1 > b->cap) strbuf_grow(b, n);
  if (n) memcpy(b->buf + b->len, s, n);
  b->len += n;
  b->buf[b->len] = 0;
}

#endif
