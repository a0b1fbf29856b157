/* coll_alltoall.c -- all-to-all algorithms (coll.h).
 *
 * Sources: MPICH (pmodels/mpich), src/mpi/coll/alltoall/alltoall_intra_brucks.c,
 * alltoall_intra_scattered.c, alltoall_intra_pairwise.c,
 * alltoall_intra_pairwise_sendrecv_replace.c, alltoallv/alltoallv_intra_scattered.c,
 * alltoallv_intra_pairwise_sendrecv_replace.c; the linear one as Open MPI's coll/basic
 * (every receive and send posted at once). */
#include <stdlib.h>
#include <string.h>

#include "coll.h"

/* Post every receive, then every send, in rank order; wait for all. */
int tsmpi_alltoallv_linear(const tsmpi_cg *g, const void *sbuf, const size_t *sc, const size_t *sd, void *rbuf,
                           const size_t *rc, const size_t *rd) {
  int size = g->size, rank = g->rank, n = 0, err = MPI_SUCCESS;
  MPI_Request *req = tsmpi_cg_alloc(g, 2 * (size_t)size * sizeof *req);
  if (rc[rank]) memcpy((char *)rbuf + rd[rank], (const char *)sbuf + sd[rank], rc[rank]);
  for (int i = 0; i < size && !err; i++)
    if (i != rank && (err = tsmpi_cg_irecv(g, (char *)rbuf + rd[i], rc[i], i, &req[n])) == 0) n++;
  for (int i = 0; i < size && !err; i++)
    if (i != rank && (err = tsmpi_cg_isend(g, (const char *)sbuf + sd[i], sc[i], i, &req[n])) == 0) n++;
  int w = tsmpi_cg_waitall(g, n, req);
  tsmpi_cg_free(req);
  return err ? err : w;
}

/* MPICH's "scattered": in blocks of 32 peers (MPIR_CVAR_ALLTOALL_THROTTLE),
 * post the receives from rank + i and the sends to rank - i, then wait;
 * the v form skips empty blocks.  Cost (p-1) alpha + n beta, overlapped. */
static int scattered(const tsmpi_cg *g, const void *sbuf, const size_t *sc, const size_t *sd, void *rbuf,
                     const size_t *rc, const size_t *rd, int skip_empty) {
  int size = g->size, rank = g->rank, bblock = 32, err = MPI_SUCCESS;
  MPI_Request *req = tsmpi_cg_alloc(g, 2 * (size_t)bblock * sizeof *req);
  for (int ii = 0; ii < size && !err; ii += bblock) {
    int ss = size - ii < bblock ? size - ii : bblock, n = 0;
    for (int i = 0; i < ss && !err; i++) {
      int dst = (rank + i + ii) % size;
      if ((!skip_empty || rc[dst]) && (err = tsmpi_cg_irecv(g, (char *)rbuf + rd[dst], rc[dst], dst, &req[n])) == 0)
        n++;
    }
    for (int i = 0; i < ss && !err; i++) {
      int dst = (rank - i - ii + 2 * size) % size;
      if ((!skip_empty || sc[dst]) &&
          (err = tsmpi_cg_isend(g, (const char *)sbuf + sd[dst], sc[dst], dst, &req[n])) == 0)
        n++;
    }
    int w = tsmpi_cg_waitall(g, n, req);
    if (!err) err = w;
  }
  tsmpi_cg_free(req);
  return err;
}

int tsmpi_alltoallv_scattered(const tsmpi_cg *g, const void *sbuf, const size_t *sc, const size_t *sd, void *rbuf,
                              const size_t *rc, const size_t *rd) {
  return scattered(g, sbuf, sc, sd, rbuf, rc, rd, 1);
}

/* MPI_Alltoall's scattered: the same without skipping empty blocks. */
int tsmpi_alltoall_scattered(const tsmpi_cg *g, const void *sbuf, void *rbuf, size_t n) {
  int size = g->size;
  size_t *cd = tsmpi_cg_alloc(g, 2 * (size_t)size * sizeof *cd);
  for (int i = 0; i < size; i++) {
    cd[i] = n;
    cd[size + i] = (size_t)i * n;
  }
  int rc = scattered(g, sbuf, cd, cd + size, rbuf, cd, cd + size, 0);
  tsmpi_cg_free(cd);
  return rc;
}

/* In place: for every pair (i, j), i <= j in order, the two exchange their
 * blocks for each other with a send and receive into scratch (MPICH's
 * sendrecv_replace schedule; i == j exchanges with itself). */
int tsmpi_alltoallv_pairwise_sendrecv_replace(const tsmpi_cg *g, void *rbuf, const size_t *sc, const size_t *sd,
                                              const size_t *rc, const size_t *rd) {
  int size = g->size, rank = g->rank, err = MPI_SUCCESS;
  (void)sc, (void)sd;   /* in place: the receive blocks are sent */
  size_t max = 0;
  for (int i = 0; i < size; i++)
    if (rc[i] > max) max = rc[i];
  char *tmp = tsmpi_cg_alloc(g, max);
  for (int i = 0; i < size && !err; i++)
    for (int j = i; j < size && !err; j++) {
      int peer = rank == i ? j : rank == j ? i : -1;
      if (peer < 0) continue;
      char *blk = (char *)rbuf + rd[peer];
      if ((err = tsmpi_cg_sendrecv(g, blk, rc[peer], peer, tmp, rc[peer], peer, NULL)) == 0) memcpy(blk, tmp, rc[peer]);
    }
  tsmpi_cg_free(tmp);
  return err;
}

/* Bruck et al. 1997: rotate the blocks up by rank; in step k send to
 * rank + 2^k (and receive from rank - 2^k) every block whose index has bit
 * k set; rotate back and reverse.  ceil(lg p) steps of n p / 2 bytes:
 * for short blocks. */
int tsmpi_alltoall_brucks(const tsmpi_cg *g, const void *sbuf, void *rbuf, size_t n) {
  int size = g->size, rank = g->rank, err = MPI_SUCCESS;
  char *r = rbuf;
  const char *s = sbuf;
  char *tmp = tsmpi_cg_alloc(g, (size_t)size * n), *pack = tsmpi_cg_alloc(g, (size_t)size * n);
  /* Phase 1: block i of rbuf is sbuf's block rank + i. */
  for (int i = 0; i < size; i++) memcpy(r + (size_t)i * n, s + (size_t)((rank + i) % size) * n, n);
  /* Phase 2. */
  for (int pof2 = 1; pof2 < size && !err; pof2 *= 2) {
    int dst = (rank + pof2) % size, src = (rank - pof2 + size) % size;
    size_t len = 0;
    for (int b = 1; b < size; b++)
      if (b & pof2) {
        memcpy(pack + len, r + (size_t)b * n, n);
        len += n;
      }
    if ((err = tsmpi_cg_sendrecv(g, pack, len, dst, tmp, len, src, NULL))) break;
    len = 0;
    for (int b = 1; b < size; b++)
      if (b & pof2) {
        memcpy(r + (size_t)b * n, tmp + len, n);
        len += n;
      }
  }
  if (!err) {
    /* Phase 3: rotate up by rank + 1, then reverse. */
    for (int i = 0; i < size; i++) memcpy(tmp + (size_t)i * n, r + (size_t)((rank + 1 + i) % size) * n, n);
    for (int i = 0; i < size; i++) memcpy(r + (size_t)i * n, tmp + (size_t)(size - 1 - i) * n, n);
  }
  tsmpi_cg_free(tmp);
  tsmpi_cg_free(pack);
  return err;
}

/* p - 1 exchanges: with rank ^ i when p is a power of two, else sending to
 * rank + i and receiving from rank - i.  Cost (p-1) alpha + n beta: for
 * long blocks. */
int tsmpi_alltoall_pairwise(const tsmpi_cg *g, const void *sbuf, void *rbuf, size_t n) {
  int size = g->size, rank = g->rank, pof2 = tsmpi_is_pof2(size), err = MPI_SUCCESS;
  const char *s = sbuf;
  char *r = rbuf;
  memcpy(r + (size_t)rank * n, s + (size_t)rank * n, n);
  for (int i = 1; i < size && !err; i++) {
    int src = pof2 ? rank ^ i : (rank - i + size) % size, dst = pof2 ? rank ^ i : (rank + i) % size;
    err = tsmpi_cg_sendrecv(g, s + (size_t)dst * n, n, dst, r + (size_t)src * n, n, src, NULL);
  }
  return err;
}
