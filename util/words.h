/* words.h -- the names an enumeration's values go by: looked up, and
 * listed for a message ("half|size|fit"). */
#ifndef WORDS_H
#define WORDS_H

#include <stddef.h>

/* The index of s among words[0..n-1], or -1 if it is none of them. */
int words_find(const char *const *words, int n, const char *s);

/* words[0..n-1] joined by '|' into buf (cut short to len - 1 bytes). */
void words_join(const char *const *words, int n, char *buf, size_t len);

#endif
