/* check.h -- a tiny test harness: CHECK(cond, fmt, ...) and a summary line.
 *
 * A failure prints "file:line: what was expected, what came"; check_done()
 * prints "NAME: N passed, N failed" and returns the exit status. */
#ifndef CHECK_H
#define CHECK_H

#include <stdio.h>

extern int check_passed, check_failed;

#define CHECK(cond, ...)                                                       \
  do {                                                                         \
    if (cond) {                                                                \
      check_passed++;                                                          \
    } else {                                                                   \
      check_failed++;                                                          \
      fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);                          \
      fprintf(stderr, __VA_ARGS__);                                            \
      fputc('\n', stderr);                                                     \
    }                                                                          \
  } while (0)

/* Prints the summary line and returns 0 if nothing failed, 1 otherwise. */
int check_done(const char *name);

/* Removes a test's temporary directory and all below it (rm -rf): 0, or -1. */
int check_rmtree(const char *dir);

#endif
