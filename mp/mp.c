/* mp.c -- the message-passing calls, dispatched to the backend behind the handle. */
#include "mp.h"

int mp_rank(const mp *self) { return self->rank; }
int mp_size(const mp *self) { return self->size; }

int mp_send(mp *self, int dst, int tag, const void *buf, size_t len) {
  return self->ops->send(self, dst, tag, buf, len);
}

int mp_recv(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st) {
  return self->ops->recv(self, src, tag, buf, cap, st);
}

int mp_probe(mp *self, int src, int tag, mp_status *st) {
  return self->ops->probe(self, src, tag, st);
}

int mp_compute(mp *self, double units) { return self->ops->compute(self, units); }

double mp_time(const mp *self) { return self->ops->time(self); }

const char *mp_strerror(int code) {
  switch (code) {
  case MP_OK: return "ok";
  case MP_EDEADLOCK: return "deadlock";
  case MP_ERANK: return "no such rank";
  case MP_ETRUNC: return "message longer than the buffer";
  case MP_EARG: return "bad argument";
  case MP_ESTOPPED: return "run stopped";
  default: return "unknown error";
  }
}
