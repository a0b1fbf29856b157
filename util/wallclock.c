/* wallclock.c -- CLOCK_MONOTONIC in seconds. */
#include "util/wallclock.h"

#include <time.h>

double wallclock(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}
