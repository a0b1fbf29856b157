/* shown.c -- bytes of an input as a message shows them (shown.h). */
#include "util/shown.h"

#include <stdio.h>
#include <string.h>

const char *shown_bytes(const char *s, size_t len, char *buf, size_t cap) {
  size_t j = 0;
  for (size_t i = 0; i < len && j + 5 < cap; i++) {
    unsigned char ch = (unsigned char)s[i];
    if (i == 40) {
      memcpy(buf + j, "...", 3);
      j += 3;
      break;
    }
    if (ch >= 32 && ch < 127) buf[j++] = (char)ch;
    else j += (size_t)snprintf(buf + j, cap - j, "\\x%02x", ch);
  }
  buf[j] = 0;
  return buf;
}
