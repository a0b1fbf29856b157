/* mp.c -- the message-passing calls, their arguments checked once here for
 * every backend, then dispatched to the backend behind the handle; the
 * calling rank (mp_self) and the way out of a rank (mp_exit). */
#include "mp/mp.h"

#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mp/backend.h"

int mp_rank(const mp *self) { return self->rank; }
int mp_size(const mp *self) { return self->size; }

/* mp_set_hooks's, or NULL (the common case: one test and a branch). */
static const mp_hooks *hooks;

void mp_set_hooks(const mp_hooks *h) { hooks = h; }

/* A call between the hooks: `ret` of the backend's `call`. */
#define HOOKED(type, self, call)                                               \
  do {                                                                         \
    if (!hooks) return call;                                                   \
    hooks->enter(self);                                                        \
    type r_ = call;                                                            \
    hooks->leave(self);                                                        \
    return r_;                                                                 \
  } while (0)

/* ==== the arguments ======================================================= */

/* A path of the calls taken only when something is wrong or hooked, kept
 * out of their common case's code (no registers saved there). */
#if defined(__GNUC__)
#define SIDE __attribute__((noinline))
#else
#define SIDE
#endif

/* A bad argument: the backend rejects the call (backend.h), why says it. */
static MP_PRINTF(3, 4) int bad(mp *self, int code, const char *fmt, ...) {
  char why[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  return self->ops->reject(self, code, why);
}

static SIDE int bad_send(mp *self, const char *call, int dst, int tag, size_t len) {
  int me = self->rank, max = self->ops->tag_max;
  if (dst < 0 || dst >= self->size)
    return bad(self, MP_ERANK, "rank %d: %s to rank %d, which does not exist (%d ranks)", me, call, dst,
               self->size);
  if (tag < 0 || tag > max) {
    if (max == INT_MAX) return bad(self, MP_EARG, "rank %d: %s to rank %d with tag %d: tags are >= 0", me, call, dst, tag);
    return bad(self, MP_EARG, "rank %d: %s to rank %d with tag %d: tags are 0..%d", me, call, dst, tag, max);
  }
  return bad(self, MP_EARG, "rank %d: %s of %zu bytes from a NULL buffer", me, call, len);
}

/* A send's destination, tag and buffer: MP_OK, or the call rejected. */
static inline int send_ok(const mp *self, int dst, int tag, const void *buf, size_t len) {
  return dst >= 0 && dst < self->size && tag >= 0 && tag <= self->ops->tag_max && (buf || !len);
}
static inline int send_args(mp *self, const char *call, int dst, int tag, const void *buf, size_t len) {
  if (send_ok(self, dst, tag, buf, len)) return MP_OK;
  return bad_send(self, call, dst, tag, len);
}

static SIDE int bad_match(mp *self, const char *call, int src, int tag) {
  int me = self->rank, max = self->ops->tag_max;
  if (src < MP_ANY || src >= self->size)
    return bad(self, MP_ERANK, "rank %d: %s from rank %d, which does not exist (%d ranks)", me, call, src,
               self->size);
  if (max == INT_MAX) return bad(self, MP_EARG, "rank %d: %s with tag %d: tags are >= 0 or MP_ANY", me, call, tag);
  return bad(self, MP_EARG, "rank %d: %s with tag %d: tags are 0..%d or MP_ANY", me, call, tag, max);
}

/* A receive's or probe's source and tag: MP_OK, or the call rejected. */
static inline int match_ok(const mp *self, int src, int tag) {
  return src >= MP_ANY && src < self->size && tag >= MP_ANY && tag <= self->ops->tag_max;
}
static inline int match_args(mp *self, const char *call, int src, int tag) {
  if (match_ok(self, src, tag)) return MP_OK;
  return bad_match(self, call, src, tag);
}

static inline int finite_nonneg(double v) { return v >= 0 && !isinf(v); }

/* ==== the calls =========================================================== */

static inline int send_(mp *self, int dst, int tag, const void *buf, size_t len) {
  int rc = send_args(self, "mp_send", dst, tag, buf, len);
  return rc != MP_OK ? rc : self->ops->send(self, dst, tag, buf, len);
}

static SIDE int send_hooked(mp *self, int dst, int tag, const void *buf, size_t len) {
  HOOKED(int, self, send_(self, dst, tag, buf, len));
}

int mp_send(mp *self, int dst, int tag, const void *buf, size_t len) {
  /* The common case (no hooks, the arguments fine) straight to the backend. */
  if (!hooks && send_ok(self, dst, tag, buf, len)) return self->ops->send(self, dst, tag, buf, len);
  return send_hooked(self, dst, tag, buf, len);
}

static inline int recv_(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st) {
  int rc = match_args(self, "mp_recv", src, tag);
  if (rc != MP_OK) return rc;
  if (cap && !buf) return bad(self, MP_EARG, "rank %d: mp_recv into a NULL buffer of %zu bytes", self->rank, cap);
  return self->ops->recv(self, src, tag, buf, cap, st);
}

int mp_recv(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st) {
  HOOKED(int, self, recv_(self, src, tag, buf, cap, st));
}

static int probe_(mp *self, int src, int tag, mp_status *st) {
  int rc = match_args(self, "mp_probe", src, tag);
  return rc != MP_OK ? rc : self->ops->probe(self, src, tag, st);
}

int mp_probe(mp *self, int src, int tag, mp_status *st) { HOOKED(int, self, probe_(self, src, tag, st)); }

static int compute_(mp *self, double units) {
  if (!finite_nonneg(units))
    return bad(self, MP_EARG, "rank %d: mp_compute(%g): units must be finite and >= 0", self->rank, units);
  return self->ops->compute(self, units);
}

int mp_compute(mp *self, double units) { HOOKED(int, self, compute_(self, units)); }

double mp_time(const mp *self) { HOOKED(double, (mp *)self, self->ops->time(self)); }

static int wait_(mp *self, int src, int tag, mp_status *st) {
  int rc = match_args(self, "mp_wait", src, tag);
  return rc != MP_OK ? rc : self->ops->wait(self, src, tag, st);
}

int mp_wait(mp *self, int src, int tag, mp_status *st) { HOOKED(int, self, wait_(self, src, tag, st)); }

int mp_charge(mp *self, double seconds) {
  if (!finite_nonneg(seconds))
    return bad(self, MP_EARG, "rank %d: mp_busy(%g): seconds must be finite and >= 0", self->rank, seconds);
  return self->ops->busy(self, seconds);
}

int mp_busy(mp *self, double seconds) { HOOKED(int, self, mp_charge(self, seconds)); }

static int sleep_(mp *self, double seconds) {
  if (self->ops->sleep_bounded && !(seconds >= 0 && seconds <= 1e9))
    return bad(self, MP_EARG, "rank %d: mp_sleep(%g): seconds must be from 0 to 1e9", self->rank, seconds);
  if (!finite_nonneg(seconds))
    return bad(self, MP_EARG, "rank %d: mp_sleep(%g): seconds must be finite and >= 0", self->rank, seconds);
  return self->ops->sleep_for(self, seconds);
}

int mp_sleep(mp *self, double seconds) { HOOKED(int, self, sleep_(self, seconds)); }

static int yield_(mp *self) { return self->ops->yield ? self->ops->yield(self) : MP_OK; }

int mp_yield(mp *self) { HOOKED(int, self, yield_(self)); }

/* ==== messages without copies ============================================= */

/* A held message where the backend copies: its bytes, taken by mp_recv. */
struct mp_msg {
  size_t len;
  unsigned char data[];
};

static int send_ref_(mp *self, int dst, int tag, const void *buf, size_t len, mp_ref **ref) {
  int rc = send_args(self, "mp_send", dst, tag, buf, len);
  if (rc != MP_OK) return rc;
  if (!self->ops->send_ref) return self->ops->send(self, dst, tag, buf, len);
  return self->ops->send_ref(self, dst, tag, buf, len, ref);
}

int mp_send_ref(mp *self, int dst, int tag, const void *buf, size_t len, mp_ref **ref) {
  *ref = NULL;
  HOOKED(int, self, send_ref_(self, dst, tag, buf, len, ref));
}

void mp_settle(mp *self, mp_ref *ref) {
  if (ref) self->ops->settle(self, ref);
}

int mp_withdraw(mp *self, mp_ref *ref) { return ref ? self->ops->withdraw(self, ref) : 0; }

/* The message mp_recv(src, tag) would take, into memory of its own. */
static int recv_copy(mp *self, int src, int tag, mp_msg **msg, mp_status *st) {
  mp_status s;
  int rc = self->ops->wait(self, src, tag, &s);
  if (rc != MP_OK) return rc;
  mp_msg *m = malloc(sizeof *m + s.len);
  if (!m) {
    fprintf(stderr, "mp_recv_msg: out of memory for a message of %zu bytes\n", s.len);
    abort();
  }
  m->len = s.len;
  rc = self->ops->recv(self, s.source, s.tag, m->data, s.len, st);
  if (rc != MP_OK) {
    free(m);
    return rc;
  }
  *msg = m;
  return MP_OK;
}

static int recv_msg_(mp *self, int src, int tag, mp_msg **msg, mp_status *st) {
  int rc = match_args(self, "mp_recv_msg", src, tag);
  if (rc != MP_OK) return rc;
  if (!self->ops->recv_msg) return recv_copy(self, src, tag, msg, st);
  return self->ops->recv_msg(self, src, tag, msg, st);
}

static SIDE int recv_msg_hooked(mp *self, int src, int tag, mp_msg **msg, mp_status *st) {
  HOOKED(int, self, recv_msg_(self, src, tag, msg, st));
}

int mp_recv_msg(mp *self, int src, int tag, mp_msg **msg, mp_status *st) {
  *msg = NULL;
  if (!hooks && self->ops->recv_msg && match_ok(self, src, tag))   /* the common case, as mp_send's */
    return self->ops->recv_msg(self, src, tag, msg, st);
  return recv_msg_hooked(self, src, tag, msg, st);
}

/* The message mp_recv_msg takes, read at once where it fits. */
static int recv_into_(mp *self, int src, int tag, int mask, int want, void *buf, size_t cap, mp_msg **msg,
                      mp_status *st) {
  int rc = match_args(self, "mp_recv_msg", src, tag);
  if (rc != MP_OK) return rc;
  if (self->ops->recv_msg_into) return self->ops->recv_msg_into(self, src, tag, mask, want, buf, cap, msg, st);
  mp_status got;
  rc = self->ops->recv_msg ? self->ops->recv_msg(self, src, tag, msg, &got) : recv_copy(self, src, tag, msg, &got);
  if (rc != MP_OK) return rc;
  if (st) *st = got;
  if (((got.tag ^ want) & mask) == 0 && got.len <= cap) {
    rc = mp_msg_read(self, *msg, buf, cap);
    *msg = NULL;
  }
  return rc;
}

static SIDE int recv_into_hooked(mp *self, int src, int tag, int mask, int want, void *buf, size_t cap, mp_msg **msg,
                                 mp_status *st) {
  HOOKED(int, self, recv_into_(self, src, tag, mask, want, buf, cap, msg, st));
}

int mp_recv_msg_into(mp *self, int src, int tag, int mask, int want, void *buf, size_t cap, mp_msg **msg,
                     mp_status *st) {
  *msg = NULL;
  if (!hooks && self->ops->recv_msg_into && match_ok(self, src, tag))   /* the common case */
    return self->ops->recv_msg_into(self, src, tag, mask, want, buf, cap, msg, st);
  return recv_into_hooked(self, src, tag, mask, want, buf, cap, msg, st);
}

int mp_msg_read(mp *self, mp_msg *msg, void *buf, size_t cap) {
  if (self->ops->msg_read) return self->ops->msg_read(self, msg, buf, cap);
  size_t n = msg->len < cap ? msg->len : cap;
  if (n) memcpy(buf, msg->data, n);
  int rc = msg->len > cap && buf ? MP_ETRUNC : MP_OK;
  free(msg);
  return rc;
}

int mp_msg_gone(mp *self, const mp_msg *msg) {
  return self->ops->msg_gone ? self->ops->msg_gone(self, msg) : 0;
}

mp_promise *mp_promise_make(mp *self, int src, int tag, int mask, void *buf, size_t cap) {
  return self->ops->promise ? self->ops->promise(self, src, tag, mask, buf, cap) : NULL;
}

int mp_promise_drop(mp *self, mp_promise *p, int keep) {
  return p ? self->ops->promise_drop(self, p, keep) : 0;
}

/* ==== one-sided transfers ================================================= */

static double transfer_(mp *self, int src, int dst, size_t len, double at) {
  int n = self->size;
  if (src < 0 || src >= n || dst < 0 || dst >= n || !finite_nonneg(at)) {
    bad(self, MP_EARG, "rank %d: mp_transfer(src=%d, dst=%d, at=%g): ranks are 0..%d, times finite and >= 0",
        self->rank, src, dst, at, n - 1);
    return at;
  }
  return self->ops->transfer(self, src, dst, len, at);
}

double mp_transfer(mp *self, int src, int dst, size_t len, double at) {
  if (!self->ops->transfer) return at;
  HOOKED(double, self, transfer_(self, src, dst, len, at));
}

static int notify_(mp *self, int dst, int tag, double at) {
  int rc = send_args(self, "mp_notify", dst, tag, NULL, 0);
  if (rc != MP_OK) return rc;
  if (!finite_nonneg(at))
    return bad(self, MP_EARG, "rank %d: mp_notify(dst=%d, at=%g): the time must be finite and >= 0", self->rank,
               dst, at);
  return self->ops->notify(self, dst, tag, at);
}

int mp_notify(mp *self, int dst, int tag, double at) {
  if (!self->ops->notify) return mp_send(self, dst, tag, NULL, 0);
  HOOKED(int, self, notify_(self, dst, tag, at));
}

const char *mp_strerror(int code) {
  switch (code) {
  case MP_OK: return "ok";
  case MP_EDEADLOCK: return "deadlock";
  case MP_ERANK: return "no such rank";
  case MP_ETRUNC: return "message longer than the buffer";
  case MP_EARG: return "bad argument";
  case MP_ESTOPPED: return "run stopped";
  case MP_EGONE: return "message withdrawn by its sender";
  default: return "unknown error";
  }
}

/* ==== the calling rank ==================================================== */

/* Each thread runs one rank at a time: a rank's thread (threads), the
 * process (MPI), or the simulator's thread, whose coroutines take turns. */
static _Thread_local mp *self_now;

/* What mp.h's inline mp_self_user and mp_self_watched read: self_now's
 * user pointer and self_now if watched, set again whenever self_now, its
 * user pointer or its progress function changes (a backend sets traced
 * for a whole run, before its ranks start). */
_Thread_local void *mp_user_now;
_Thread_local mp *mp_watched_now;

static void now_again(void) {
  mp *s = self_now;
  mp_user_now = s ? s->user : NULL;
  mp_watched_now = s && (s->traced || s->progress) ? s : NULL;
}

mp *mp_self(void) { return self_now; }
void mp_set_self(mp *self) {
  self_now = self;
  now_again();
}

void *mp_user(const mp *self) { return self->user; }
void mp_set_user(mp *self, void *p) {
  self->user = p;
  if (self == self_now) now_again();
}

void mp_label(mp *self, mp_describe describe, void *ud) {
  self->describe = describe;
  self->describe_ud = ud;
}

void mp_set_progress(mp *self, mp_progress fn, void *ud) {
  self->progress = fn;
  self->progress_ud = ud;
  if (self == self_now) now_again();
}

int mp_progressing(const mp *self) { return self->progress != NULL; }

int mp_traced(const mp *self) { return self->traced; }

void mp_stack(const mp *self, void **lo, size_t *size, void **guard) {
  *lo = self->stack_lo;
  *size = self->stack_size;
  *guard = self->stack_guard;
}

void mp_call_begin(mp *self, const char *name) {
  if (self->call_depth++ == 0 && self->traced) {
    self->call_name = name;
    self->ops->call(self, name, 1);
  }
}

void mp_call_end(mp *self) {
  if (self->call_depth > 0 && --self->call_depth == 0 && self->traced && self->call_name) {
    self->ops->call(self, self->call_name, 0);
    self->call_name = NULL;
  }
}

/* ==== leaving a rank ====================================================== */

MP_NORETURN void mp_exit(mp *self) {
  if (hooks) hooks->enter(self);   /* what it computed last is charged */
  if (!self->exit_to) {   /* a bug of the backend: main was not run by mp_enter */
    fprintf(stderr, "mp_exit: rank %d is not inside mp_enter\n", self->rank);
    abort();
  }
  longjmp(*(jmp_buf *)self->exit_to, 1);
}

MP_NORETURN void mp_abort(mp *self, int code, const char *why) {
  if (hooks) hooks->enter(self);
  self->ops->stop(self, code, why);
  mp_exit(self);
}
