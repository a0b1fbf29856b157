/* bigcopy.h -- copying a message's payload.
 *
 * bigcopy(dst, src, n) is memcpy (the regions must not overlap), but a
 * payload of BIGCOPY_MIN bytes or more is written with stores that bypass
 * the caches (x86-64: SSE2 non-temporal stores; elsewhere memcpy).  A big
 * payload is usually one of many in flight (a window of sends, an
 * alltoall), so its destination is not in cache anyway: an ordinary store
 * first reads each line of it from memory, and the stream stores do not,
 * so the copy moves two bytes through memory for each byte instead of
 * three.  The same bytes land either way. */
#ifndef BIGCOPY_H
#define BIGCOPY_H

#include <stddef.h>
#include <string.h>

#define BIGCOPY_MIN ((size_t)256 << 10)

void bigcopy_stream(void *dst, const void *src, size_t n);

static inline void bigcopy(void *dst, const void *src, size_t n) {
  if (n >= BIGCOPY_MIN) bigcopy_stream(dst, src, n);
  else if (n) memcpy(dst, src, n);
}

#endif
