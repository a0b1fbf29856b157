/* errlog.c -- quoting a run's first errors. */
#include "util/errlog.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

void errlog_add(errlog *e, const char *text, int always) {
  if (e->shown >= ERRLOG_SHOWN && !always) return;
  size_t old = e->text ? strlen(e->text) : 0, add = strlen(text);
  e->text = xrealloc(e->text, old + add + 8);
  if (old) {
    memcpy(e->text + old, "; then ", 7);
    old += 7;
  }
  memcpy(e->text + old, text, add + 1);
  e->shown++;
}

int errlog_report(const errlog *e, long long count, char *err, size_t errlen) {
  if (!count) return 0;
  const char *t = e->text ? e->text : "an error";
  if (count > e->shown) snprintf(err, errlen, "%s (%lld errors in all)", t, count);
  else snprintf(err, errlen, "%s", t);
  return -1;
}

void errlog_free(errlog *e) {
  free(e->text);
  e->text = NULL;
  e->shown = 0;
}
