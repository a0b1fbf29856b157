/* shown.h -- bytes of an input as a message shows them: printable ASCII as
 * it is, any other byte as \xNN, at most 40 bytes and then "...". */
#ifndef SHOWN_H
#define SHOWN_H

#include <stddef.h>

/* s[0..len-1] shown in buf (as much as cap - 1 bytes hold); returns buf. */
const char *shown_bytes(const char *s, size_t len, char *buf, size_t cap);

#endif
