/* errlog.h -- the errors of a run, as a backend reports them: the first few
 * quoted in full, "; then "-separated, the rest only counted (by the
 * caller, in its statistics). */
#ifndef ERRLOG_H
#define ERRLOG_H

#include <stddef.h>

enum { ERRLOG_SHOWN = 3 };   /* errors quoted; the rest are counted */

typedef struct {
  char *text;   /* the errors quoted so far, or NULL */
  int shown;    /* how many */
} errlog;

/* Quote text if fewer than ERRLOG_SHOWN are quoted, or always. */
void errlog_add(errlog *e, const char *text, int always);

/* Into err: the quoted errors, and "(N errors in all)" when count > shown.
 * 0 if count is 0, else -1. */
int errlog_report(const errlog *e, long long count, char *err, size_t errlen);

void errlog_free(errlog *e);

#endif
