/* words.c -- an enumeration's names (words.h). */
#include "util/words.h"

#include <stdio.h>
#include <string.h>

int words_find(const char *const *words, int n, const char *s) {
  for (int i = 0; i < n; i++)
    if (strcmp(s, words[i]) == 0) return i;
  return -1;
}

void words_join(const char *const *words, int n, char *buf, size_t len) {
  size_t k = 0;
  if (len) buf[0] = 0;
  for (int i = 0; i < n; i++)
    k += (size_t)snprintf(buf + k, k < len ? len - k : 0, "%s%s", i ? "|" : "", words[i]);
}
