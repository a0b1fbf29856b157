/* state.c -- one rank's MPI state: finding it, tables of communicators,
 * groups' ranks and requests, its release, the other parts' slots. */
#include "mpi/state.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/attr.h"
#include "mpi/engine.h"
#include "mpi/init.h"
#include "mpi/errh.h"
#include "mpi/info.h"
#include "mpi/topo.h"
#include "util/xmem.h"

/* ==== finding the rank's state ============================================ */

st_rank *st_get(void) {
  mp *self = mp_self();
  if (!self) return NULL;
  void *u = mp_user(self);
  return u == INIT_MARK_FINALIZED || u == INIT_MARK_STOPPED ? NULL : u;
}

_Noreturn void st_need_fail(const char *fn) {
  mp *self = mp_self();
  if (!self) {
    fprintf(stderr, "tilesim MPI: %s called outside a rank: MPI programs run under tilesim-mpirun\n", fn);
    exit(1);
  }
  void *u = mp_user(self);
  char why[200];
  snprintf(why, sizeof why, "rank %d: %s called %s", mp_rank(self), fn,
           u ? "after MPI_Finalize" : "before MPI_Init");
  mp_abort(self, 1, why);
}

_Noreturn void st_stopped(st_rank *R) {
  mp *self = R->self;
  st_release(R);
  mp_set_user(self, INIT_MARK_STOPPED);
  mp_exit(self);
}

/* ==== the other parts' slots ============================================== */

void *st_part(int part) {
  st_rank *R = st_get();
  return R && part >= 0 && part < ST_PARTS ? R->part[part] : NULL;
}

void st_part_set(int part, void *p, void (*release)(void *p)) {
  st_rank *R = st_need("st_part_set");
  if (part < 0 || part >= ST_PARTS) {
    fprintf(stderr, "tilesim MPI: internal error: st_part_set(%d)\n", part);
    abort();
  }
  R->part[part] = p;
  R->release[part] = release;
}

/* ==== groups' ranks ======================================================= */

static int cmp_pair(const void *a, const void *b) {
  const int *x = a, *y = b;
  return (x[0] > y[0]) - (x[0] < y[0]);
}

st_ranks *st_ranks_new(int n, const int *world) {
  st_ranks *g = xcalloc(1, sizeof *g);
  g->refs = 1;
  g->n = n;
  int ident = 1;
  for (int i = 0; world && i < n; i++) ident &= world[i] == i;
  if (ident) return g;
  g->world = xmallocarray((size_t)n, sizeof *g->world);
  memcpy(g->world, world, (size_t)n * sizeof *world);
  int *pairs = xmallocarray((size_t)n, 2 * sizeof *pairs);
  for (int i = 0; i < n; i++) {
    pairs[2 * i] = world[i];
    pairs[2 * i + 1] = i;
  }
  qsort(pairs, (size_t)n, 2 * sizeof *pairs, cmp_pair);
  g->sw = xmallocarray((size_t)n, sizeof *g->sw);
  g->sr = xmallocarray((size_t)n, sizeof *g->sr);
  for (int i = 0; i < n; i++) {
    g->sw[i] = pairs[2 * i];
    g->sr[i] = pairs[2 * i + 1];
  }
  free(pairs);
  return g;
}

void st_ranks_drop(st_ranks *g) {
  if (!g || --g->refs > 0) return;
  free(g->world);
  free(g->sw);
  free(g->sr);
  free(g);
}

int st_ranks_find(const st_ranks *g, int w) {
  if (!g->world) return w >= 0 && w < g->n ? w : -1;
  int lo = 0, hi = g->n - 1;
  while (lo <= hi) {
    int mid = lo + (hi - lo) / 2;
    if (g->sw[mid] == w) return g->sr[mid];
    if (g->sw[mid] < w)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

/* ==== communicators ======================================================= */

st_comm *st_comm_get(st_rank *R, MPI_Comm comm) {
  if (comm == MPI_COMM_WORLD) return &R->world;
  if (comm == MPI_COMM_SELF) return &R->selfc;
  unsigned slot = (unsigned)comm - (unsigned)(HK_COMM << H_KIND_SHIFT | H_CREATED);
  if (slot < (unsigned)R->ncomms && R->comms[slot]) return R->comms[slot];
  return NULL;
}

st_comm *st_comm_must(st_rank *R, MPI_Comm comm, const char *fn) {
  st_comm *c = st_comm_get(R, comm);
  if (c) return c;
  fprintf(stderr, "tilesim MPI: internal error: rank %d: %s on an unchecked communicator 0x%x\n", R->wrank,
          fn, (unsigned)comm);
  abort();
}

int st_comm_rank_of(const st_comm *c, int w) { return st_ranks_find(c->g, w); }

const char *st_pair_name(int pair, char *buf) {
  if (pair == 0) return "MPI_COMM_WORLD";
  if (pair == 1) return "MPI_COMM_SELF";
  snprintf(buf, 32, "communicator %d", pair);
  return buf;
}

/* ==== requests ============================================================ */

st_req *st_req_new(st_rank *R) {
  st_req *q = R->freereq;
  if (q) {
    R->freereq = q->next;
  } else {
    if (R->nreqs >= H_SLOT_MASK) {
      fprintf(stderr, "tilesim MPI: rank %d has %d requests at once: too many\n", R->wrank, R->nreqs);
      abort();
    }
    int slot = R->nreqs++;
    if ((slot & (slot - 1)) == 0 || slot == 0)   /* a power of two: grow */
      R->reqs = xreallocarray(R->reqs, slot ? 2 * (size_t)slot : 1, sizeof *R->reqs);
    q = xmalloc(sizeof *q);
    q->slot = slot;
    R->reqs[slot] = q;
  }
  int slot = q->slot;
  memset(q, 0, sizeof *q);
  q->slot = slot;
  q->used = 1;
  return q;
}

st_req *st_req_get(st_rank *R, MPI_Request h) {
  unsigned slot = (unsigned)h - (unsigned)(HK_REQ << H_KIND_SHIFT | H_CREATED);
  if (slot >= (unsigned)R->nreqs) return NULL;
  st_req *q = R->reqs[slot];
  return q->used ? q : NULL;
}

int st_req_free(st_rank *R, st_req *q) {
  eng_settle(R, q);
  if (q->slot < 0) return MPI_SUCCESS;
  int err = MPI_SUCCESS;
  if (q->kind == RQ_KIND) {
    R->nkinds--;
    if (q->ops->free) err = q->ops->free(q->ext);
  }
  if (q->held) dtype_release(q->dt);
  q->held = 0;
  q->used = 0;
  q->kind = RQ_SEND;   /* no kind's callbacks once freed */
  q->next = R->freereq;
  R->freereq = q;
  return err;
}

/* ==== matched probes' messages ============================================ */

MPI_Message st_msg_handle(st_rank *R, st_msg *m) {
  int slot = 0;
  while (slot < R->nmsgs && R->msgs[slot]) slot++;
  if (slot == R->nmsgs) {
    if (R->nmsgs >= H_SLOT_MASK) {
      fprintf(stderr, "tilesim MPI: rank %d holds %d matched messages at once: too many\n", R->wrank, R->nmsgs);
      abort();
    }
    int n = R->nmsgs ? 2 * R->nmsgs : 4;
    R->msgs = xreallocarray(R->msgs, (size_t)n, sizeof *R->msgs);
    for (int i = R->nmsgs; i < n; i++) R->msgs[i] = NULL;
    R->nmsgs = n;
  }
  R->msgs[slot] = m;
  return (MPI_Message)(HK_MSG << H_KIND_SHIFT | H_CREATED | slot);
}

st_msg *st_msg_take(st_rank *R, MPI_Message h) {
  unsigned slot = (unsigned)h - (unsigned)(HK_MSG << H_KIND_SHIFT | H_CREATED);
  if (slot >= (unsigned)R->nmsgs || !R->msgs[slot]) return NULL;
  st_msg *m = R->msgs[slot];
  R->msgs[slot] = NULL;
  return m;
}

/* ==== the end ============================================================= */

void st_release(st_rank *R) {
  mp_set_progress(R->self, NULL, NULL);   /* no nonblocking collective goes on past the rank's MPI */
  eng_settle_all(R);                      /* before the parts free what sends refer to */
  for (int i = ST_PARTS - 1; i >= 0; i--)
    if (R->release[i]) R->release[i](R->part[i]);
  eng_release(R);
  for (int i = 0; i < R->nreqs; i++) {
    st_req *q = R->reqs[i];
    if (q->used && q->kind == RQ_KIND && q->ops->drop) q->ops->drop(q->ext);
  }
  for (int i = 0; i < R->nmsgs; i++)
    if (R->msgs[i]) eng_msg_free(R, R->msgs[i]);
  free(R->msgs);
  for (int i = 0; i < R->nreqs; i++) free(R->reqs[i]);
  free(R->reqs);
  for (int i = 0; i < R->ncomms; i++) {
    if (!R->comms[i]) continue;
    st_ranks_drop(R->comms[i]->g);
    if (R->comms[i]->inter) st_ranks_drop(R->comms[i]->lg);
    ptopo_unref(R->comms[i]->topo);
    free(R->comms[i]);
  }
  free(R->comms);
  for (int i = 0; i < R->ngroups; i++) st_ranks_drop(R->groups[i]);
  free(R->groups);
  st_ranks_drop(R->world.g);
  st_ranks_drop(R->selfc.g);
  st_ranks_drop(R->empty);
  attr_release_all(R);
  errh_release_all(R);
  info_release_all(R);
  free(R);
}
