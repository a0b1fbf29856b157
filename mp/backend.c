/* backend.c -- what the backends of mp.h share: the way into a rank, a
 * run's errors and warnings, the deadlock report's words (backend.h). */
#include "mp/backend.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

/* ==== entering a rank ===================================================== */

void mp_enter(mp *self, mp_main main, void *ud) {
  jmp_buf out;
  self->exit_to = &out;
  mp_set_self(self);
  if (setjmp(out) == 0) main(self, ud);
  self->exit_to = NULL;
  self->describe = NULL;
  self->call_depth = 0;   /* a rank that left inside a call */
  self->call_name = NULL;
  mp_set_progress(self, NULL, NULL);
}

const char *mp_label_text(const mp *self, char *buf, size_t len) {
  if (!self->describe || len == 0) return NULL;
  buf[0] = 0;
  self->describe(self->describe_ud, buf, len);
  return buf;
}

/* ==== errors and warnings ================================================= */

/* fmt's text, in memory of its own. */
static char *vformat(const char *fmt, va_list ap) {
  va_list aq;
  va_copy(aq, ap);
  int n = vsnprintf(NULL, 0, fmt, aq);
  va_end(aq);
  XASSERT(n >= 0);
  char *buf = xmalloc((size_t)n + 1);
  vsnprintf(buf, (size_t)n + 1, fmt, ap);
  return buf;
}

void mp_fail_text(mp_log *lg, const char *text, int always) {
  lg->st->errors++;
  errlog_add(&lg->errs, text, always);
}

void mp_fail(mp_log *lg, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  char *text = vformat(fmt, ap);
  va_end(ap);
  mp_fail_text(lg, text, 0);
  free(text);
}

void mp_warn(mp_log *lg, const char *fmt, ...) {
  lg->st->warnings++;
  if (!lg->warn) return;
  va_list ap;
  va_start(ap, fmt);
  char *text = vformat(fmt, ap);
  va_end(ap);
  fprintf(lg->warn, "%s: warning: %s\n", lg->name, text);
  free(text);
}

int mp_log_report(const mp_log *lg, char *err, size_t errlen) {
  return errlog_report(&lg->errs, lg->st->errors, err, errlen);
}

void mp_log_free(mp_log *lg) { errlog_free(&lg->errs); }

/* ==== the deadlock report ================================================= */

const char *mp_peer_name(int v, char *buf, size_t len) {
  if (v < 0) return "any";
  snprintf(buf, len, "%d", v);
  return buf;
}

/* Room for n more bytes of text. */
static void room(mp_deadlock *d, size_t n) {
  if (d->cap - d->len > n) return;
  while (d->cap - d->len <= n) d->cap *= 2;
  d->text = xrealloc(d->text, d->cap);
}

void mp_deadlock_begin(mp_deadlock *d, const char *head, ...) {
  d->cap = 64 + MP_DEADLOCK_SHOWN * 64;
  d->text = xmalloc(d->cap);
  d->len = 0;
  d->blocked = 0;
  va_list ap;
  va_start(ap, head);
  char *text = vformat(head, ap);
  va_end(ap);
  room(d, strlen(text));
  d->len += (size_t)snprintf(d->text, d->cap, "%s", text);
  free(text);
}

void mp_deadlock_rank(mp_deadlock *d, const mp *rank, int wait_src, int wait_tag) {
  if (d->blocked++ >= MP_DEADLOCK_SHOWN) return;
  char what[160], a[16], b[16];
  const char *label = mp_label_text(rank, what, sizeof what);
  room(d, 200);
  if (label)
    d->len += (size_t)snprintf(d->text + d->len, d->cap - d->len, "%s rank %d waits in %s",
                               d->blocked > 1 ? ";" : "", rank->rank, label);
  else
    d->len += (size_t)snprintf(d->text + d->len, d->cap - d->len, "%s rank %d waits in recv(src=%s, tag=%s)",
                               d->blocked > 1 ? ";" : "", rank->rank, mp_peer_name(wait_src, a, sizeof a),
                               mp_peer_name(wait_tag, b, sizeof b));
}

char *mp_deadlock_end(mp_deadlock *d) {
  if (d->blocked > MP_DEADLOCK_SHOWN) {
    room(d, 48);
    snprintf(d->text + d->len, d->cap - d->len, "; and %d more ranks", d->blocked - MP_DEADLOCK_SHOWN);
  }
  return d->text;
}
