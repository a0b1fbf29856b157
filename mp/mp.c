/* mp.c -- the message-passing calls, dispatched to the backend behind the
 * handle; the calling rank (mp_self) and the way out of a rank (mp_exit). */
#include "mp/mp.h"
#include "mp/backend.h"

#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

int mp_send(mp *self, int dst, int tag, const void *buf, size_t len) {
  HOOKED(int, self, self->ops->send(self, dst, tag, buf, len));
}

int mp_recv(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st) {
  HOOKED(int, self, self->ops->recv(self, src, tag, buf, cap, st));
}

int mp_probe(mp *self, int src, int tag, mp_status *st) { HOOKED(int, self, self->ops->probe(self, src, tag, st)); }

int mp_compute(mp *self, double units) { HOOKED(int, self, self->ops->compute(self, units)); }

double mp_time(const mp *self) { HOOKED(double, (mp *)self, self->ops->time(self)); }

int mp_wait(mp *self, int src, int tag, mp_status *st) { HOOKED(int, self, self->ops->wait(self, src, tag, st)); }

int mp_busy(mp *self, double seconds) { HOOKED(int, self, self->ops->busy(self, seconds)); }

int mp_sleep(mp *self, double seconds) { HOOKED(int, self, self->ops->sleep_for(self, seconds)); }

int mp_charge(mp *self, double seconds) { return self->ops->busy(self, seconds); }

/* ==== messages without copies ============================================= */

/* A held message where the backend copies: its bytes, taken by mp_recv. */
struct mp_msg {
  size_t len;
  unsigned char data[];
};

int mp_send_ref(mp *self, int dst, int tag, const void *buf, size_t len, mp_ref **ref) {
  *ref = NULL;
  if (!self->ops->send_ref) HOOKED(int, self, self->ops->send(self, dst, tag, buf, len));
  HOOKED(int, self, self->ops->send_ref(self, dst, tag, buf, len, ref));
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

int mp_recv_msg(mp *self, int src, int tag, mp_msg **msg, mp_status *st) {
  *msg = NULL;
  if (!self->ops->recv_msg) HOOKED(int, self, recv_copy(self, src, tag, msg, st));
  HOOKED(int, self, self->ops->recv_msg(self, src, tag, msg, st));
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

double mp_transfer(mp *self, int src, int dst, size_t len, double at) {
  if (!self->ops->transfer) return at;
  HOOKED(double, self, self->ops->transfer(self, src, dst, len, at));
}

int mp_notify(mp *self, int dst, int tag, double at) {
  if (!self->ops->notify) return mp_send(self, dst, tag, NULL, 0);
  HOOKED(int, self, self->ops->notify(self, dst, tag, at));
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

mp *mp_self(void) { return self_now; }
void mp_set_self(mp *self) { self_now = self; }

void *mp_user(const mp *self) { return self->user; }
void mp_set_user(mp *self, void *p) { self->user = p; }

void mp_label(mp *self, mp_describe describe, void *ud) {
  self->describe = describe;
  self->describe_ud = ud;
}

const char *mp_label_text(const mp *self, char *buf, size_t len) {
  if (!self->describe || len == 0) return NULL;
  buf[0] = 0;
  self->describe(self->describe_ud, buf, len);
  return buf;
}

void mp_set_progress(mp *self, mp_progress fn, void *ud) {
  self->progress = fn;
  self->progress_ud = ud;
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

/* ==== entering and leaving a rank ========================================= */

void mp_enter(mp *self, mp_main main, void *ud) {
  jmp_buf out;
  self->exit_to = &out;
  mp_set_self(self);
  if (setjmp(out) == 0) main(self, ud);
  self->exit_to = NULL;
  self->describe = NULL;
  self->call_depth = 0;   /* a rank that left inside a call */
  self->call_name = NULL;
  self->progress = NULL;
}

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
