/* strbuf.c -- a growing text buffer (strbuf.h). */
#include "util/strbuf.h"

#include <stdio.h>
#include <string.h>

#include "util/xmem.h"

void strbuf_grow(strbuf *b, size_t n) {
  if (b->len + n + 1 > b->cap) {
    b->cap = (b->len + n + 1) * 2;
    b->buf = xrealloc(b->buf, b->cap);
  }
}

void strbuf_vadd(strbuf *b, const char *fmt, va_list ap) {
  va_list aq;
  va_copy(aq, ap);
  int k = vsnprintf(NULL, 0, fmt, aq);
  va_end(aq);
  if (k < 0) return;
  strbuf_grow(b, (size_t)k);
  vsnprintf(b->buf + b->len, b->cap - b->len, fmt, ap);
  b->len += (size_t)k;
}

void strbuf_add(strbuf *b, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  strbuf_vadd(b, fmt, ap);
  va_end(ap);
}

