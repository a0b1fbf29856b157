/* coll_alltoall.c -- all-to-all algorithms (coll.h).
 *
 * Sources: MPICH (pmodels/mpich), src/mpi/coll/alltoall/alltoall_intra_brucks.c,
 * alltoall_intra_scattered.c, alltoall_intra_pairwise.c,
 * alltoall_intra_pairwise_sendrecv_replace.c, alltoallv/alltoallv_intra_scattered.c,
 * alltoallv_intra_pairwise_sendrecv_replace.c; the linear one as Open MPI's coll/basic
 * (every receive and send posted at once). */
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/coll_sched.h"

/* Post every receive, then every send, in rank order; wait for all. */
void coll_alltoallv_linear(coll_sched *s, const void *sbuf, const size_t *sc, const size_t *sd, void *rbuf,
                           const size_t *rc, const size_t *rd) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank;
  coll_sched_copy(s, (char *)rbuf + rd[rank], (const char *)sbuf + sd[rank], rc[rank]);
  for (int i = 0; i < size; i++)
    if (i != rank) coll_sched_irecv(s, (char *)rbuf + rd[i], rc[i], i);
  for (int i = 0; i < size; i++)
    if (i != rank) coll_sched_isend(s, (const char *)sbuf + sd[i], sc[i], i);
  coll_sched_waitall(s);
}

/* MPICH's "scattered": in blocks of 32 peers (MPIR_CVAR_ALLTOALL_THROTTLE),
 * post the receives from rank + i and the sends to rank - i, then wait;
 * the v form skips empty blocks.  Cost (p-1) alpha + n beta, overlapped. */
static void scattered(coll_sched *s, const void *sbuf, const size_t *sc, const size_t *sd, void *rbuf,
                      const size_t *rc, const size_t *rd, int skip_empty) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank, bblock = 32;
  for (int ii = 0; ii < size; ii += bblock) {
    int ss = size - ii < bblock ? size - ii : bblock;
    for (int i = 0; i < ss; i++) {
      int dst = (rank + i + ii) % size;
      if (!skip_empty || rc[dst]) coll_sched_irecv(s, (char *)rbuf + rd[dst], rc[dst], dst);
    }
    for (int i = 0; i < ss; i++) {
      int dst = (rank - i - ii + 2 * size) % size;
      if (!skip_empty || sc[dst]) coll_sched_isend(s, (const char *)sbuf + sd[dst], sc[dst], dst);
    }
    coll_sched_waitall(s);
  }
}

void coll_alltoallv_scattered(coll_sched *s, const void *sbuf, const size_t *sc, const size_t *sd, void *rbuf,
                              const size_t *rc, const size_t *rd) {
  scattered(s, sbuf, sc, sd, rbuf, rc, rd, 1);
}

/* Equal blocks of n bytes: counts and displacements for the v forms. */
static size_t *equal_blocks(coll_sched *s, size_t n) {
  int size = coll_sched_group(s)->size;
  size_t *cd = coll_sched_mem(s, 2 * (size_t)size * sizeof *cd);
  for (int i = 0; i < size; i++) {
    cd[i] = n;
    cd[size + i] = (size_t)i * n;
  }
  return cd;
}

/* MPI_Alltoall's scattered: the same without skipping empty blocks. */
void coll_alltoall_scattered(coll_sched *s, const void *sbuf, void *rbuf, size_t n) {
  size_t *cd = equal_blocks(s, n);
  int size = coll_sched_group(s)->size;
  scattered(s, sbuf, cd, cd + size, rbuf, cd, cd + size, 0);
}

/* In place: for every pair (i, j), i <= j in order, the two exchange their
 * blocks for each other with a send and receive into scratch (MPICH's
 * sendrecv_replace schedule; i == j exchanges with itself). */
void coll_alltoallv_pairwise_sendrecv_replace(coll_sched *s, void *rbuf, const size_t *rc, const size_t *rd) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank;
  size_t max = 0;
  for (int i = 0; i < size; i++)
    if (rc[i] > max) max = rc[i];
  char *tmp = coll_sched_mem(s, max);
  for (int i = 0; i < size; i++)
    for (int j = i; j < size; j++) {
      int peer = rank == i ? j : rank == j ? i : -1;
      if (peer < 0) continue;
      char *blk = (char *)rbuf + rd[peer];
      coll_sched_sendrecv(s, blk, rc[peer], peer, tmp, rc[peer], peer);
      coll_sched_copy(s, blk, tmp, rc[peer]);
    }
}

/* Bruck's steps, local: the blocks whose index has bit pof2 set, packed
 * out of r into pack, or back. */
typedef struct {
  char *r, *pack;
  size_t n;
  int size, pof2, out;
} bruck_step;

static void bruck_move(void *ud) {
  const bruck_step *b = ud;
  size_t len = 0;
  for (int i = 1; i < b->size; i++)
    if (i & b->pof2) {
      if (b->out)
        memcpy(b->pack + len, b->r + (size_t)i * b->n, b->n);
      else
        memcpy(b->r + (size_t)i * b->n, b->pack + len, b->n);
      len += b->n;
    }
}

/* ... and the end: rotate up by rank + 1, then reverse. */
typedef struct {
  char *r, *tmp;
  size_t n;
  int size, rank;
} bruck_end;

static void bruck_finish(void *ud) {
  const bruck_end *b = ud;
  for (int i = 0; i < b->size; i++)
    memcpy(b->tmp + (size_t)i * b->n, b->r + (size_t)((b->rank + 1 + i) % b->size) * b->n, b->n);
  for (int i = 0; i < b->size; i++)
    memcpy(b->r + (size_t)i * b->n, b->tmp + (size_t)(b->size - 1 - i) * b->n, b->n);
}

/* Bruck et al. 1997: rotate the blocks up by rank; in step k send to
 * rank + 2^k (and receive from rank - 2^k) every block whose index has bit
 * k set; rotate back and reverse.  ceil(lg p) steps of n p / 2 bytes:
 * for short blocks. */
void coll_alltoall_brucks(coll_sched *s, const void *sbuf, void *rbuf, size_t n) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank;
  char *r = rbuf, *tmp = coll_sched_mem(s, (size_t)size * n), *pack = coll_sched_mem(s, (size_t)size * n);
  /* Phase 1: block i of rbuf is sbuf's block rank + i. */
  size_t head = (size_t)(size - rank) * n;
  coll_sched_copy(s, r, (const char *)sbuf + (size_t)rank * n, head);
  coll_sched_copy(s, r + head, sbuf, (size_t)rank * n);
  /* Phase 2. */
  for (int pof2 = 1; pof2 < size; pof2 *= 2) {
    int dst = (rank + pof2) % size, src = (rank - pof2 + size) % size;
    size_t len = 0;
    for (int b = 1; b < size; b++)
      if (b & pof2) len += n;
    bruck_step *out = coll_sched_mem(s, 2 * sizeof *out), *in = out + 1;
    *out = (bruck_step){r, pack, n, size, pof2, 1};
    *in = (bruck_step){r, tmp, n, size, pof2, 0};
    coll_sched_call(s, bruck_move, out);
    coll_sched_sendrecv(s, pack, len, dst, tmp, len, src);
    coll_sched_call(s, bruck_move, in);
  }
  /* Phase 3. */
  bruck_end *e = coll_sched_mem(s, sizeof *e);
  *e = (bruck_end){r, tmp, n, size, rank};
  coll_sched_call(s, bruck_finish, e);
}

/* p - 1 exchanges: with rank ^ i when p is a power of two, else sending to
 * rank + i and receiving from rank - i.  Cost (p-1) alpha + n beta: for
 * long blocks. */
void coll_alltoall_pairwise(coll_sched *s, const void *sbuf, void *rbuf, size_t n) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank, pof2 = coll_is_pof2(size);
  const char *sp = sbuf;
  char *r = rbuf;
  coll_sched_copy(s, r + (size_t)rank * n, sp + (size_t)rank * n, n);
  for (int i = 1; i < size; i++) {
    int src = pof2 ? rank ^ i : (rank - i + size) % size, dst = pof2 ? rank ^ i : (rank + i) % size;
    coll_sched_sendrecv(s, sp + (size_t)dst * n, n, dst, r + (size_t)src * n, n, src);
  }
}
