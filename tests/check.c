/* check.c -- the counters behind CHECK and the summary line. */
#include "tests/check.h"

int check_passed, check_failed;

int check_done(const char *name) {
  printf("%s: %d passed, %d failed\n", name, check_passed, check_failed);
  fflush(stdout);
  return check_failed ? 1 : 0;
}
