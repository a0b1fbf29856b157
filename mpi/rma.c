/* rma.c -- one-sided operations: issued, applied at the target when they
 * arrive, completed when their replies are back; passive-target locks and
 * their queues (win.h says how, doc/mpi-semantics.md what it costs).
 *
 * An operation is two transfers on the machine (mp_transfer): its request,
 * from the origin to the target (the origin's data: a put's or an
 * accumulate's bytes, both values of a compare-and-swap; nothing for a get
 * or a lock), and its reply, from the target back (a get's or a fetch's
 * data; nothing for the others: an acknowledgement).  The request leaves
 * when the operation is issued (after every earlier message and transfer
 * on the channel: two operations from one origin to one target arrive in
 * the order issued, as MPI's accumulate ordering asks), the origin applies
 * it at its arrival, and the reply leaves the target then.
 *
 *   origin  put -----.                flush: until the reply is back
 *                     \  request        ^
 *   target             '--> applied ----'  reply (0 bytes)
 *
 * The operations not yet applied wait in the window's list by (arrival,
 * order issued); each one-sided call on the window applies those that
 * have arrived by the time it needs (rma_progress), so on the simulator
 * every operation is applied in the global order of simulated time unless
 * its origin computed past its arrival in between. */
#include "mpi/win.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/dtype.h"
#include "mpi/engine.h"
#include "mpi/op.h"
#include "mpi/pt2pt.h"
#include "util/xmem.h"

struct rma_op {
  rma_op *next;
  double at;               /* when the request arrives at the target */
  uint64_t seq;            /* the order issued */
  int kind, target;
  char *taddr;             /* the target's elements */
  int tcount;
  MPI_Datatype tdt;        /* held */
  unsigned char *data;     /* the origin's data, packed (compare-and-swap: then the compare value) */
  size_t len;              /* the request's bytes */
  void *rbuf;              /* the result's elements */
  int rcount;
  MPI_Datatype rdt;        /* held, where there is a result */
  MPI_Op op;
  MPI_Datatype basic;      /* accumulates: the predefined type of every element, */
  int nbasic;              /* and how many */
  int lock;                /* OP_LOCK: MPI_LOCK_EXCLUSIVE or _SHARED */
  size_t reply;            /* the reply's bytes */
  rma_done *done;
};

struct rma_tgt {
  int target;              /* -1: an empty slot */
  int lock;                /* the lock this rank holds on it (MPI_LOCK_*), or 0 */
  int nocheck;             /* taken with MPI_MODE_NOCHECK: nothing was asked of the target */
  int inacc;               /* in the post/start epoch's group, */
  int posted;              /* and its post has come */
  int acci;                /* its place in that group */
  int npend;               /* operations to it not yet applied */
  double last;             /* the latest arrival among them */
  double lastget;          /* the latest arrival among those with data in their replies */
  double done;             /* the latest reply of those applied */
  double ldone;            /* the latest reply with data of those applied */
};

/* ==== time ================================================================ */

static void mpok(st_rank *R, int rc) {
  if (rc == MP_OK) return;
  if (rc == MP_ESTOPPED || rc == MP_EDEADLOCK) st_stopped(R);
  fprintf(stderr, "tilesim MPI: internal error: rank %d: one-sided: %s\n", R->wrank, mp_strerror(rc));
  abort();
}

void rma_until(st_rank *R, double t) {
  double now = mp_time(R->self);
  if (t > now) mpok(R, mp_sleep(R->self, t - now));
}

static double now_of(st_rank *R) { return mp_time(R->self); }
static double maxd(double a, double b) { return a > b ? a : b; }

/* ==== the targets a rank knows ============================================ */

static unsigned tg_hash(int t, int cap) { return ((unsigned)t * 2654435761u) & (unsigned)(cap - 1); }

/* The entry of target, or NULL if this rank never knew it. */
static rma_tgt *tgt_find(rma_window *w, int target) {
  if (!w->captg) return NULL;
  unsigned h = tg_hash(target, w->captg);
  while (w->tg[h].target >= 0) {
    if (w->tg[h].target == target) return &w->tg[h];
    h = (h + 1) & (unsigned)(w->captg - 1);
  }
  return NULL;
}

/* The entry of target, made if new (a new one may move the others). */
static rma_tgt *tgt(rma_window *w, int target) {
  rma_tgt *e = tgt_find(w, target);
  if (e) return e;
  if (2 * (w->ntg + 1) > w->captg) {
    int cap = w->captg ? 2 * w->captg : 8;
    rma_tgt *old = w->tg, *t = xmallocarray((size_t)cap, sizeof *t);
    for (int i = 0; i < cap; i++) t[i].target = -1;
    for (int i = 0; i < w->captg; i++) {
      if (old[i].target < 0) continue;
      unsigned h = tg_hash(old[i].target, cap);
      while (t[h].target >= 0) h = (h + 1) & (unsigned)(cap - 1);
      t[h] = old[i];
    }
    free(old);
    w->tg = t;
    w->captg = cap;
  }
  unsigned h = tg_hash(target, w->captg);
  while (w->tg[h].target >= 0) h = (h + 1) & (unsigned)(w->captg - 1);
  w->tg[h] = (rma_tgt){.target = target, .last = -INFINITY, .lastget = -INFINITY, .done = -INFINITY,
                       .ldone = -INFINITY};
  w->ntg++;
  return &w->tg[h];
}

int rma_locked(rma_window *w, int target) {
  rma_tgt *t = tgt_find(w, target);
  return t ? t->lock : 0;
}

/* ==== the list of operations ============================================== */

static void insert(rma_window *w, rma_op *op) {
  rma_op **at = &w->ops;
  if (w->ops_tail && (w->ops_tail->at < op->at || (w->ops_tail->at == op->at && w->ops_tail->seq < op->seq))) {
    at = &w->ops_tail->next;
  } else {
    while (*at && ((*at)->at < op->at || ((*at)->at == op->at && (*at)->seq < op->seq))) at = &(*at)->next;
  }
  op->next = *at;
  *at = op;
  if (!op->next) w->ops_tail = op;
}

static int with_data(const rma_op *op) { return op->kind == OP_GET || op->kind == OP_GACC || op->kind == OP_CAS; }

/* op's request leaves now for its target. */
static void send(st_rank *R, rma_window *w, rma_op *op) {
  op->at = mp_transfer(R->self, R->wrank, w->sh->part[op->target].wrank, op->len, now_of(R));
  rma_tgt *t = tgt(w, op->target);
  t->last = maxd(t->last, op->at);
  if (with_data(op)) t->lastget = maxd(t->lastget, op->at);
  insert(w, op);
}

static void free_op(rma_op *op) {
  if (op->tdt) dtype_release(op->tdt);
  if (op->rdt) dtype_release(op->rdt);
  free(op->data);
  free(op);
}

/* ==== issuing ============================================================= */

void rma_issue(st_rank *R, rma_window *w, const rma_args *a, rma_done *done) {
  rma_op *op = xcalloc(1, sizeof *op);
  op->kind = a->kind;
  op->target = a->target;
  op->seq = w->seq++;
  op->taddr = a->taddr;
  op->tcount = a->tcount;
  op->op = a->op;
  op->lock = a->lock;
  op->done = done;
  if (done) done->applied = 0;
  size_t tbytes = 0;
  if (a->kind <= OP_CAS) {
    op->tdt = a->tdt;
    dtype_hold(a->tdt);
    tbytes = (size_t)a->tcount * dtype_size(a->tdt);
  }
  int carries = a->kind == OP_PUT || a->kind == OP_ACC || a->kind == OP_CAS ||
                (a->kind == OP_GACC && a->op != MPI_NO_OP);
  if (carries) {
    size_t olen = (size_t)a->ocount * dtype_size(a->odt);
    op->len = a->kind == OP_CAS ? 2 * olen : olen;
    if (op->len) {
      op->data = xmalloc(op->len);
      dtype_pack(a->obuf, a->ocount, a->odt, op->data);
      if (a->kind == OP_CAS) dtype_pack(a->compare, a->ocount, a->odt, op->data + olen);
    }
  }
  if (with_data(op)) {
    op->rbuf = a->rbuf;
    op->rcount = a->rcount;
    op->rdt = a->rdt;
    dtype_hold(a->rdt);
    op->reply = tbytes;
  }
  if (a->kind == OP_ACC || a->kind == OP_GACC) {
    MPI_Count per = 0;
    int idx = dtype_elem(a->tdt, &per);
    op->basic = (MPI_Datatype)(3 << 24 | idx);
    op->nbasic = (int)(per * a->tcount);
  }
  rma_tgt *t = tgt(w, a->target);
  t->npend++;
  if (t->inacc && !t->posted && !rma_access_posted(R, w, a->target)) {   /* it waits for the post */
    rma_op **at = &w->deferred;
    while (*at) at = &(*at)->next;
    op->next = NULL;
    *at = op;
    return;
  }
  send(R, w, op);
  rma_progress(R, w, now_of(R));
}

void rma_posted(st_rank *R, rma_window *w, int target) {
  rma_op **at = &w->deferred;
  while (*at) {
    rma_op *op = *at;
    if (op->target != target) {
      at = &op->next;
      continue;
    }
    *at = op->next;
    op->next = NULL;
    send(R, w, op);
  }
}

/* ==== applying ============================================================ */

static int compatible(const rma_part *p, int excl) { return excl ? !p->excl && !p->shared : !p->excl; }

static void take(rma_part *p, int excl) {
  if (excl)
    p->excl = 1;
  else
    p->shared++;
}

/* inout = in op inout on op's packed elements (MPI_REPLACE: in). */
static void combine(const rma_op *op, const unsigned char *in, unsigned char *inout, size_t n) {
  if (op->op == MPI_REPLACE)
    memcpy(inout, in, n);
  else if (op->op != MPI_NO_OP)
    op_reduce_packed(op->op, op->basic, in, inout, op->nbasic);
}

/* Apply op at its target (its arrival is now): the data moved, the lock
 * taken or released, and its reply sent back. */
static void apply(st_rank *R, rma_window *w, rma_op *op) {
  rma_shared *sh = w->sh;
  rma_part *p = &sh->part[op->target];
  size_t tb = op->tdt ? (size_t)op->tcount * dtype_size(op->tdt) : 0;
  unsigned char *tmp = with_data(op) || op->kind == OP_ACC ? xmalloc(tb ? tb : 1) : NULL;
  int granted = 1, *lets = NULL, ng = 0;
  pthread_mutex_lock(&sh->mu);
  switch (op->kind) {
  case OP_PUT:
    if (tb) dtype_unpack(op->data, tb, op->taddr, op->tcount, op->tdt);
    break;
  case OP_GET:
    if (tb) dtype_pack(op->taddr, op->tcount, op->tdt, tmp);
    break;
  case OP_ACC:
    if (!tb || op->op == MPI_NO_OP) break;
    if (op->op == MPI_REPLACE) {
      dtype_unpack(op->data, tb, op->taddr, op->tcount, op->tdt);
      break;
    }
    dtype_pack(op->taddr, op->tcount, op->tdt, tmp);
    combine(op, op->data, tmp, tb);
    dtype_unpack(tmp, tb, op->taddr, op->tcount, op->tdt);
    break;
  case OP_GACC:
    if (!tb) break;
    dtype_pack(op->taddr, op->tcount, op->tdt, tmp);
    if (op->op != MPI_NO_OP) {
      unsigned char *upd = xmalloc(tb);
      memcpy(upd, tmp, tb);
      combine(op, op->data, upd, tb);
      dtype_unpack(upd, tb, op->taddr, op->tcount, op->tdt);
      free(upd);
    }
    break;
  case OP_CAS:
    if (!tb) break;
    dtype_pack(op->taddr, op->tcount, op->tdt, tmp);
    if (memcmp(tmp, op->data + tb, tb) == 0) dtype_unpack(op->data, tb, op->taddr, op->tcount, op->tdt);
    break;
  case OP_LOCK:
    if (p->nq == 0 && compatible(p, op->lock == MPI_LOCK_EXCLUSIVE)) {
      take(p, op->lock == MPI_LOCK_EXCLUSIVE);
    } else {
      if (p->nq == p->capq) p->q = xreallocarray(p->q, (size_t)(p->capq = p->capq ? 2 * p->capq : 4), sizeof *p->q);
      p->q[p->nq++] = (rma_lockwait){w->rank, op->lock == MPI_LOCK_EXCLUSIVE};
      granted = 0;
    }
    break;
  case OP_UNLOCK:
    if (p->excl)
      p->excl = 0;
    else if (p->shared > 0)
      p->shared--;
    /* The waiting origins it lets in, first come first served. */
    while (ng < p->nq && compatible(p, p->q[ng].excl)) take(p, p->q[ng++].excl);
    if (ng) {
      lets = xmallocarray((size_t)ng, sizeof *lets);
      for (int i = 0; i < ng; i++) lets[i] = p->q[i].rank;
      memmove(p->q, p->q + ng, (size_t)(p->nq -= ng) * sizeof *p->q);
    }
    break;
  }
  pthread_mutex_unlock(&sh->mu);
  if (tmp && tb && with_data(op)) dtype_unpack(tmp, tb, op->rbuf, op->rcount, op->rdt);
  free(tmp);
  /* The grants leave the target now, for each origin let in. */
  double now = op->at;
  for (int i = 0; i < ng; i++) {
    int to = sh->part[lets[i]].wrank;
    double arr = mp_transfer(R->self, p->wrank, to, 0, now);
    mpok(R, mp_notify(R->self, to, st_env_encode(K_DATA, 2 * w->c->pair, WTAG_GRANT), arr));
  }
  free(lets);
  rma_tgt *t = tgt(w, op->target);
  t->npend--;
  double reply = -1;
  if (granted) {
    reply = mp_transfer(R->self, p->wrank, R->wrank, op->reply, now);
    t->done = maxd(t->done, reply);
    if (with_data(op)) t->ldone = maxd(t->ldone, reply);
    w->done_all = maxd(w->done_all, reply);
  }
  if (op->done) {
    op->done->applied = 1;
    op->done->at = reply;   /* -1: a lock queued, its grant to come */
  }
  free_op(op);
}

void rma_progress(st_rank *R, rma_window *w, double t) {
  while (w->ops && w->ops->at <= t) {
    rma_op *op = w->ops;
    w->ops = op->next;
    if (!w->ops) w->ops_tail = NULL;
    rma_until(R, op->at);
    apply(R, w, op);
  }
}

void rma_wait_done(st_rank *R, rma_window *w, rma_done *d) {
  while (!d->applied) {
    if (!w->ops) {   /* deferred for a post: it is waited for */
      for (int i = 0; i < w->nacc; i++)
        while (!rma_access_posted(R, w, w->acc[i])) eng_step(R);
      continue;
    }
    rma_progress(R, w, w->ops->at);
  }
  rma_until(R, d->at);
}

/* ==== completing ========================================================== */

void rma_complete(st_rank *R, rma_window *w, int target, int local) {
  if (target >= 0) {
    rma_tgt *t = tgt_find(w, target);
    if (!t) return;
    if (t->npend) rma_progress(R, w, local ? t->lastget : t->last);
    rma_until(R, local ? t->ldone : t->done);
    return;
  }
  double until = -INFINITY, last = -INFINITY;
  for (int i = 0; i < w->captg; i++) {
    rma_tgt *t = &w->tg[i];
    if (t->target < 0) continue;
    if (t->npend) last = maxd(last, local ? t->lastget : t->last);
    until = maxd(until, local ? t->ldone : t->done);
  }
  if (last > -INFINITY) rma_progress(R, w, last);
  for (int i = 0; i < w->captg; i++)
    if (w->tg[i].target >= 0) until = maxd(until, local ? w->tg[i].ldone : w->tg[i].done);
  rma_until(R, until);
}

/* ==== locks =============================================================== */

/* Wait for n grants of queued lock requests (the caller's label set). */
static void grants(st_rank *R, rma_window *w, int n) {
  for (int i = 0; i < n; i++) {
    st_req q;
    st_req_stack(&q);
    pt2pt_recv_fill(&q, w->c, 0, NULL, 0, MPI_BYTE, MPI_ANY_SOURCE, WTAG_GRANT, w->comm, "MPI_Win_lock");
    pt2pt_recv_block(R, &q);
  }
}

void rma_lock(st_rank *R, rma_window *w, int target, int lock, int nocheck) {
  if (nocheck) {
    rma_tgt *t = tgt(w, target);
    t->lock = lock;
    t->nocheck = 1;
    return;
  }
  rma_done d;
  rma_args a = {.kind = OP_LOCK, .target = target, .lock = lock};
  rma_issue(R, w, &a, &d);
  rma_complete(R, w, target, 0);
  if (d.at < 0) grants(R, w, 1);
  rma_tgt *t = tgt(w, target);
  t->lock = lock;
  t->nocheck = 0;
}

void rma_unlock(st_rank *R, rma_window *w, int target) {
  if (!tgt(w, target)->nocheck) {
    rma_args a = {.kind = OP_UNLOCK, .target = target};
    rma_issue(R, w, &a, NULL);
  }
  rma_complete(R, w, target, 0);
  rma_tgt *t = tgt(w, target);
  t->lock = t->nocheck = 0;
}

void rma_lock_all(st_rank *R, rma_window *w) {
  rma_done *d = xmallocarray((size_t)w->size, sizeof *d);
  for (int r = 0; r < w->size; r++) {
    rma_args a = {.kind = OP_LOCK, .target = r, .lock = MPI_LOCK_SHARED};
    rma_issue(R, w, &a, &d[r]);
  }
  rma_complete(R, w, -1, 0);
  int queued = 0;
  for (int r = 0; r < w->size; r++) queued += d[r].at < 0;
  free(d);
  grants(R, w, queued);
}

void rma_unlock_all(st_rank *R, rma_window *w) {
  for (int r = 0; r < w->size; r++) {
    rma_args a = {.kind = OP_UNLOCK, .target = r};
    rma_issue(R, w, &a, NULL);
  }
  rma_complete(R, w, -1, 0);
}

/* ==== post/start/complete ================================================= */

/* The post of start group member i has come (its receive done): its
 * request freed, the operations deferred for it sent. */
static int post_came(st_rank *R, rma_window *w, int i) {
  st_req *q = st_req_get(R, w->postrq[i]);
  if (q && q->state == RS_ACTIVE) return 0;
  if (q) st_req_free(R, q);
  w->postrq[i] = MPI_REQUEST_NULL;
  rma_tgt *t = tgt(w, w->acc[i]);
  t->posted = 1;
  rma_posted(R, w, w->acc[i]);
  return 1;
}

void rma_access_begin(st_rank *R, rma_window *w) {
  w->postrq = xmallocarray((size_t)w->nacc + 1, sizeof *w->postrq);
  for (int i = 0; i < w->nacc; i++) {
    rma_tgt *t = tgt(w, w->acc[i]);
    t->inacc = 1;
    t->posted = 0;
    t->acci = i;
    st_req *q = st_req_new(R);
    pt2pt_recv_fill(q, w->c, 0, NULL, 0, MPI_BYTE, w->acc[i], WTAG_POST, w->comm, "MPI_Win_start");
    pt2pt_recv_start(R, q);
    w->postrq[i] = st_req_handle(q);
  }
}

int rma_access_has(rma_window *w, int target) {
  rma_tgt *t = tgt_find(w, target);
  return t && t->inacc;
}

int rma_access_posted(st_rank *R, rma_window *w, int target) {
  rma_tgt *t = tgt_find(w, target);
  if (!t || !t->inacc) return 0;
  if (t->posted) return 1;
  eng_poll(R);
  return post_came(R, w, t->acci);
}

void rma_access_end(st_rank *R, rma_window *w) {
  /* Every post, the deferred operations leaving as each comes. */
  for (;;) {
    int left = 0;
    for (int i = 0; i < w->nacc; i++)
      if (w->postrq[i] != MPI_REQUEST_NULL && !post_came(R, w, i)) left++;
    if (!left) break;
    eng_step(R);
  }
  /* The dones: each leaves now, after the operations on its channel, and
   * is sent once they have been applied. */
  double *d = xmallocarray((size_t)w->nacc + 1, sizeof *d), last = -INFINITY, until = -INFINITY;
  for (int i = 0; i < w->nacc; i++) {
    int t = w->acc[i];
    d[i] = mp_transfer(R->self, R->wrank, w->sh->part[t].wrank, 0, now_of(R));
    rma_tgt *e = tgt(w, t);
    if (e->npend) last = maxd(last, e->last);
  }
  if (last > -INFINITY) rma_progress(R, w, last);
  for (int i = 0; i < w->nacc; i++) {
    mpok(R, mp_notify(R->self, w->sh->part[w->acc[i]].wrank, st_env_encode(K_DATA, 2 * w->c->pair, WTAG_DONE), d[i]));
    rma_tgt *e = tgt(w, w->acc[i]);
    e->inacc = e->posted = 0;
    until = maxd(until, e->ldone);
  }
  free(d);
  /* Local completion: the gets' data are in. */
  rma_until(R, until);
  free(w->postrq);
  w->postrq = NULL;
}

/* ==== the end ============================================================= */

void rma_release(rma_window *w) {
  for (rma_op *op = w->ops, *n; op; op = n) {
    n = op->next;
    free_op(op);
  }
  for (rma_op *op = w->deferred, *n; op; op = n) {
    n = op->next;
    free_op(op);
  }
  w->ops = w->ops_tail = w->deferred = NULL;
  free(w->tg);
  w->tg = NULL;
  w->ntg = w->captg = 0;
}

