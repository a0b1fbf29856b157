/* coll_sched.c -- schedules: building, running in line, stepping as messages arrive (coll_sched.h). */
#include "mpi/coll_sched.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/dtype.h"
#include "mpi/op.h"
#include "mpi/core.h"

enum { OP_SEND, OP_RECV, OP_ISEND, OP_IRECV, OP_WAITALL, OP_REDUCE, OP_COPY, OP_UNPACK, OP_CALL };

typedef struct {
  unsigned char kind;      /* OP_* */
  int peer;                /* send, recv: the peer; reduce, unpack: the count */
  MPI_Datatype dt;         /* unpack: the type */
  size_t n;                /* bytes (send, recv, copy) */
  union {
    void *p;               /* recv, copy, reduce (right), unpack: where it writes */
    void (*fn)(void *);    /* call */
  } a;
  const void *b;           /* send, copy, reduce (left), unpack: what it reads; call: ud */
} op;

/* A block of the schedule's memory. */
typedef struct block {
  struct block *next;
  max_align_t data[];
} block;

struct coll_sched {
  coll_sched *next, *prev;   /* the rank's live schedules */
  coll_cg g;
  coll_red red;
  op *ops;
  int nops, cap;
  int at;                     /* the next step */
  int posted;                 /* step `at` (a receive) is posted: its request is cur */
  MPI_Request cur;
  MPI_Request *reqs;          /* isends and irecvs since the last waitall */
  int nreqs, capreqs;
  int err;
  block *mem;
  MPI_Datatype *held;         /* types the unpack steps hold */
  int nheld, capheld;
  void *frame;                /* coll_sched_frame */
  int red_held;               /* red's type and operation are held */
  int now;                    /* blocking: each step runs as it is added */
};

/* ==== the rank's live schedules =========================================== */

/* Released at the rank's end (a stopped run, or MPI_Finalize with some
 * still live): every schedule's memory; its requests go with the rank's. */
typedef struct {
  coll_sched *head;
} live;

static void live_release(void *ud) {
  live *l = ud;
  while (l->head) {
    coll_sched *s = l->head;
    l->head = s->next;
    s->nreqs = 0;
    s->posted = 0;   /* the rank's requests are freed with it */
    s->next = s->prev = NULL;
    coll_sched_free(s);
  }
  free(l);
}

static void oom(size_t n) {
  fprintf(stderr, "tilesim: a collective's schedule: out of memory (%zu bytes)\n", n);
  abort();
}

/* Array p of *cap items of size bytes, full, with room for more: first
 * items, or twice as many. */
static void *grow(void *p, int *cap, int first, size_t size) {
  int n = *cap ? 2 * *cap : first;
  void *q = realloc(p, (size_t)n * size);
  if (!q) oom((size_t)n * size);
  *cap = n;
  return q;
}

static void *xalloc(size_t n) {
  void *p = malloc(n ? n : 1);
  if (!p) oom(n);
  return p;
}

static live *rank_live(void) {
  live *l = st_part(ST_PART_SCHED);
  if (!l) {
    l = xalloc(sizeof *l);
    l->head = NULL;
    st_part_set(ST_PART_SCHED, l, live_release);
  }
  return l;
}

/* ==== building ============================================================ */

coll_sched *coll_sched_new(const coll_cg *g, const coll_red *r, int blocking) {
  coll_sched *s = xalloc(sizeof *s);
  memset(s, 0, sizeof *s);
  s->g = *g;
  s->now = blocking;
  if (r) coll_sched_set_red(s, r);
  s->cur = MPI_REQUEST_NULL;
  live *l = rank_live();
  s->next = l->head;
  if (l->head) l->head->prev = s;
  l->head = s;
  return s;
}

const coll_cg *coll_sched_group(const coll_sched *s) { return &s->g; }
const coll_red *coll_sched_red(const coll_sched *s) { return &s->red; }
/* The reduction's type and operation are held as long as the schedule: the
 * program may free them before a nonblocking collective completes. */
static void red_release(coll_sched *s) {
  if (!s->red_held) return;
  dtype_release(s->red.dt);
  op_release(s->red.op);
  s->red_held = 0;
}

void coll_sched_set_red(coll_sched *s, const coll_red *r) {
  red_release(s);
  s->red = *r;
  if (s->now) return;   /* used before the call returns */
  dtype_hold(r->dt);
  op_hold(r->op);
  s->red_held = 1;
}
void *coll_sched_frame(const coll_sched *s) { return s->frame; }
void coll_sched_set_frame(coll_sched *s, void *frame) { s->frame = frame; }

static _Atomic long long mem_given;   /* coll_sched_mem's bytes, every rank's */
long long coll_sched_mem_given(void) { return atomic_load_explicit(&mem_given, memory_order_relaxed); }

void *coll_sched_mem(coll_sched *s, size_t n) {
  if (n > (size_t)-1 - sizeof(block)) oom(n);
  atomic_fetch_add_explicit(&mem_given, (long long)n, memory_order_relaxed);
  block *b = xalloc(sizeof *b + n);
  b->next = s->mem;
  s->mem = b;
  return b->data;
}

/* A step: run now (a blocking schedule; nothing after an error) or kept. */
static void run_now(coll_sched *s, const op *o);
static void emit(coll_sched *s, const op *o) {
  if (s->now) {
    if (!s->err) run_now(s, o);
    return;
  }
  if (s->nops == s->cap) s->ops = grow(s->ops, &s->cap, 16, sizeof *s->ops);
  s->ops[s->nops++] = *o;
}

static void xfer(coll_sched *s, int kind, const void *buf, size_t n, int peer) {
  op o = {.kind = (unsigned char)kind, .peer = peer, .n = n};
  if (kind == OP_SEND || kind == OP_ISEND)
    o.b = buf;
  else
    o.a.p = (void *)buf;
  emit(s, &o);
}

void coll_sched_send(coll_sched *s, const void *buf, size_t n, int dst) { xfer(s, OP_SEND, buf, n, dst); }
void coll_sched_recv(coll_sched *s, void *buf, size_t n, int src) { xfer(s, OP_RECV, buf, n, src); }
void coll_sched_sendrecv(coll_sched *s, const void *sbuf, size_t sn, int dst, void *rbuf, size_t rn, int src) {
  if (!s->now) {
    xfer(s, OP_SEND, sbuf, sn, dst);
    xfer(s, OP_RECV, rbuf, rn, src);
  } else if (!s->err) {
    s->err = coll_cg_sendrecv(&s->g, sbuf, sn, dst, rbuf, rn, src, NULL);
  }
}
void coll_sched_isend(coll_sched *s, const void *buf, size_t n, int dst) { xfer(s, OP_ISEND, buf, n, dst); }
void coll_sched_irecv(coll_sched *s, void *buf, size_t n, int src) { xfer(s, OP_IRECV, buf, n, src); }

void coll_sched_waitall(coll_sched *s) {
  op o = {.kind = OP_WAITALL};
  emit(s, &o);
}

void coll_sched_reduce(coll_sched *s, const void *left, void *right, int count) {
  if (count <= 0) return;
  op o = {.kind = OP_REDUCE, .peer = count, .a.p = right, .b = left};
  emit(s, &o);
}

void coll_sched_copy(coll_sched *s, void *dst, const void *src, size_t n) {
  if (n == 0 || dst == src) return;
  op o = {.kind = OP_COPY, .n = n, .a.p = dst, .b = src};
  emit(s, &o);
}

void coll_sched_unpack(coll_sched *s, const void *p, size_t n, void *buf, int count, MPI_Datatype dt) {
  if (n == 0 || p == dtype_contig(buf, count, dt)) return;   /* nothing, or in place already */
  op o = {.kind = OP_UNPACK, .peer = count, .dt = dt, .n = n, .a.p = buf, .b = p};
  emit(s, &o);
  if (s->now || (s->nheld && s->held[s->nheld - 1] == dt)) return;   /* used now, or held already */
  if (s->nheld == s->capheld) s->held = grow(s->held, &s->capheld, 4, sizeof *s->held);
  dtype_hold(dt);
  s->held[s->nheld++] = dt;
}

void coll_sched_call(coll_sched *s, void (*fn)(void *ud), void *ud) {
  op o = {.kind = OP_CALL, .a.fn = fn, .b = ud};
  emit(s, &o);
}

/* ==== running ============================================================= */

/* A local step. */
static void local(coll_sched *s, const op *o) {
  switch (o->kind) {
  case OP_REDUCE: coll_red_apply(&s->red, o->b, o->a.p, o->peer); break;
  case OP_COPY: memmove(o->a.p, o->b, o->n); break;
  case OP_UNPACK: dtype_unpack(o->b, o->n, o->a.p, o->peer, o->dt); break;
  case OP_CALL: o->a.fn((void *)o->b); break;
  default: break;
  }
}

static void req_add(coll_sched *s, MPI_Request r) {
  if (s->nreqs == s->capreqs) s->reqs = grow(s->reqs, &s->capreqs, 8, sizeof *s->reqs);
  s->reqs[s->nreqs++] = r;
}

/* A blocking schedule's step, at once: the algorithm's own call in line. */
static void run_now(coll_sched *s, const op *o) {
  const coll_cg *g = &s->g;
  MPI_Request r;
  int rc = MPI_SUCCESS;
  switch (o->kind) {
  case OP_SEND: rc = coll_cg_send(g, o->b, o->n, o->peer); break;
  case OP_RECV: rc = coll_cg_recv(g, o->a.p, o->n, o->peer, NULL); break;
  case OP_ISEND:
    if ((rc = coll_cg_isend(g, o->b, o->n, o->peer, &r)) == 0) req_add(s, r);
    break;
  case OP_IRECV:
    if ((rc = coll_cg_irecv(g, o->a.p, o->n, o->peer, &r)) == 0) req_add(s, r);
    break;
  case OP_WAITALL:
    rc = coll_cg_waitall(g, s->nreqs, s->reqs);
    s->nreqs = 0;
    break;
  default: local(s, o); break;
  }
  s->err = rc;
}

int coll_sched_run(coll_sched *s) {
  int rc = s->err;
  if (rc && s->nreqs) coll_cg_waitall(&s->g, s->nreqs, s->reqs);   /* as the algorithms did: theirs finish */
  s->nreqs = 0;
  coll_sched_free(s);
  return rc;
}

/* A request of ours (from src, or -1) that may be done: 1 (and freed) if it
 * is; an error is raised and kept. */
static int req_done(coll_sched *s, MPI_Request *r, int src) {
  MPI_Status st;
  if (!coll_p2p_done(r, &st)) return 0;
  int err = st.MPI_ERROR;
  if (err && !s->err) s->err = coll_cg_failed(&s->g, err, src);
  return 1;
}

int coll_sched_step(coll_sched *s) {
  const coll_cg *g = &s->g;
  while (s->at < s->nops && !s->err) {
    const op *o = &s->ops[s->at];
    MPI_Request r;
    int rc = MPI_SUCCESS;
    switch (o->kind) {
    case OP_SEND: rc = coll_cg_send(g, o->b, o->n, o->peer); break;
    case OP_RECV:
      if (!s->posted) {
        if ((rc = coll_cg_irecv(g, o->a.p, o->n, o->peer, &s->cur))) break;
        coll_p2p_watch(s->cur);
        s->posted = 1;
      }
      if (!req_done(s, &s->cur, o->peer)) return 0;
      s->posted = 0;
      break;
    case OP_ISEND:
      if ((rc = coll_cg_isend(g, o->b, o->n, o->peer, &r)) == 0) req_add(s, r);
      break;
    case OP_IRECV:
      if ((rc = coll_cg_irecv(g, o->a.p, o->n, o->peer, &r)) == 0) {
        coll_p2p_watch(r);
        req_add(s, r);
      }
      break;
    case OP_WAITALL:
      while (s->nreqs > 0) {
        if (!req_done(s, &s->reqs[s->nreqs - 1], -1)) return 0;
        s->nreqs--;
      }
      break;
    default: local(s, o); break;
    }
    if (rc && !s->err) s->err = rc;
    s->at++;
  }
  return 1;
}

int coll_sched_error(const coll_sched *s) { return s->err; }

void coll_sched_free(coll_sched *s) {
  if (!s) return;
  if (s->posted) coll_p2p_drop(&s->cur);
  for (int i = 0; i < s->nreqs; i++) coll_p2p_drop(&s->reqs[i]);
  live *l = st_part(ST_PART_SCHED);
  if (s->prev)
    s->prev->next = s->next;
  else if (l && l->head == s)
    l->head = s->next;
  if (s->next) s->next->prev = s->prev;
  for (block *b = s->mem, *n; b; b = n) {
    n = b->next;
    free(b);
  }
  for (int i = 0; i < s->nheld; i++) dtype_release(s->held[i]);
  red_release(s);
  free(s->held);
  free(s->ops);
  free(s->reqs);
  free(s);
}
