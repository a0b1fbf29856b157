/* par.c -- what master and slave share: counters and message packing. */
#include "algo/par.h"

#include <stdlib.h>
#include <string.h>

#include "util/words.h"
#include "util/xmem.h"

const char *par_kind_name(par_kind k) {
  static const char *name[PAR_KINDS] = {"boundary", "backtrack", "bounds", "control"};
  return k < PAR_KINDS ? name[k] : "?";
}

static const char *const schedule_names[] = {"static", "dynamic"};

const char *par_schedule_name(par_schedule s) { return schedule_names[s == PAR_DYNAMIC]; }

int par_schedule_parse(const char *s, par_schedule *out) {
  int i = words_find(schedule_names, 2, s);
  return i < 0 ? -1 : (*out = (par_schedule)i, 0);
}

void par_counts_add(par_counts *into, const par_counts *c) {
  for (int k = 0; k < PAR_KINDS; k++) into->msgs[k] += c->msgs[k], into->bytes[k] += c->bytes[k];
  into->nodes += c->nodes;
  into->units += c->units;
  into->book += c->book;
  into->paths += c->paths;
  into->idle += c->idle;
}

void par_buf_reset(par_buf *m) { m->len = 0; }

void par_buf_free(par_buf *m) {
  free(m->b);
  m->b = NULL;
  m->len = m->cap = 0;
}

static void room(par_buf *m, size_t more) {
  if (m->len + more <= m->cap) return;
  size_t cap = m->cap ? m->cap : 256;
  while (cap < m->len + more) cap *= 2;
  m->b = xrealloc(m->b, cap);
  m->cap = cap;
}

void par_put_i32(par_buf *m, int32_t v) {
  room(m, 4);
  memcpy(m->b + m->len, &v, 4);
  m->len += 4;
}

void par_put_f64(par_buf *m, double v) {
  room(m, 8);
  memcpy(m->b + m->len, &v, 8);
  m->len += 8;
}

void par_put_i32s(par_buf *m, const int *v, int n) {
  room(m, 4 * (size_t)n);
  for (int i = 0; i < n; i++) {
    int32_t x = v[i];
    memcpy(m->b + m->len, &x, 4);
    m->len += 4;
  }
}

void par_put_f64s(par_buf *m, const double *v, int n) {
  room(m, 8 * (size_t)n);
  memcpy(m->b + m->len, v, 8 * (size_t)n);
  m->len += 8 * (size_t)n;
}

/* Read n bytes of r into v. */
static void take(par_rd *r, void *v, size_t n) {
  if ((size_t)(r->end - r->p) < n) xpanic("par: message too short");
  memcpy(v, r->p, n);
  r->p += n;
}

int32_t par_get_i32(par_rd *r) {
  int32_t v;
  take(r, &v, 4);
  return v;
}

double par_get_f64(par_rd *r) {
  double v;
  take(r, &v, 8);
  return v;
}

void par_get_i32s(par_rd *r, int *v, int n) {
  for (int i = 0; i < n; i++) v[i] = par_get_i32(r);
}

void par_get_f64s(par_rd *r, double *v, int n) {
  if (r->end - r->p < 8 * (ptrdiff_t)n) xpanic("par: message too short");
  memcpy(v, r->p, 8 * (size_t)n);
  r->p += 8 * (size_t)n;
}

int par_send(mp *self, par_counts *c, int kind, int dst, int tag, const par_buf *m) {
  if (kind >= 0) {
    c->msgs[kind]++;
    c->bytes[kind] += m->len;
  }
  return mp_send(self, dst, tag, m->b, m->len);
}

int par_recv(mp *self, int src, int tag, par_buf *buf, size_t maxlen, mp_status *st) {
  room(buf, maxlen > buf->len ? maxlen - buf->len : 0);
  int rc = mp_recv(self, src, tag, buf->b, buf->cap, st);
  buf->len = rc == MP_OK ? st->len : 0;
  return rc;
}

int par_compute(mp *self, par_counts *c, uint64_t units) {
  c->units += units;
  return mp_compute(self, (double)units);
}
