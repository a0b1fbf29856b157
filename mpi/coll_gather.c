/* coll_gather.c -- gather, scatter and allgather algorithms, and their v forms (coll.h).
 *
 * Sources: MPICH (pmodels/mpich), src/mpi/coll/gather/gather_intra_binomial.c,
 * scatter/scatter_intra_binomial.c, gatherv/gatherv_allcomm_linear.c,
 * scatterv/scatterv_allcomm_linear.c, allgatherv/allgatherv_intra_recursive_doubling.c,
 * allgatherv_intra_brucks.c, allgatherv_intra_ring.c (allgather's three are the same message
 * for message with equal counts, but for the ring's pipelining, which is allgatherv's alone);
 * the linear ones as Open MPI's coll/basic component. */
#include <stdlib.h>
#include <string.h>

#include "coll.h"

/* ==== gather and scatter ================================================== */

/* The root receives every rank's block in rank order. */
int tsmpi_gather_linear(const tsmpi_cg *g, const void *sbuf, void *rbuf, size_t n, int root) {
  int rc = MPI_SUCCESS;
  if (g->rank != root) return tsmpi_cg_send(g, sbuf, n, root);
  for (int i = 0; i < g->size && !rc; i++) {
    char *dst = (char *)rbuf + (size_t)i * n;
    if (i == root) {
      if (sbuf && n) memcpy(dst, sbuf, n);
    } else {
      rc = tsmpi_cg_recv(g, dst, n, i, NULL);
    }
  }
  return rc;
}

/* Binomial tree on ranks relative to the root: a rank gathers its subtree's
 * blocks (relative ranks rel .. rel + 2^k - 1), then sends them to its
 * parent in one message.  Cost lg p alpha + n (p-1)/p beta. */
int tsmpi_gather_binomial(const tsmpi_cg *g, const void *sbuf, void *rbuf, size_t n, int root) {
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size, rc = MPI_SUCCESS;
  /* tmp holds the subtree's blocks in relative order, ours first. */
  int sub = 1;
  while (sub < size && !(rel & sub)) sub <<= 1;
  if (rel + sub > size) sub = size - rel;
  char *tmp = tsmpi_cg_alloc(g, (size_t)sub * n);
  if (n) memcpy(tmp, sbuf ? sbuf : (const char *)rbuf + (size_t)rank * n, n);
  size_t have = n;
  for (int mask = 1; mask < size; mask <<= 1) {
    if (!(rel & mask)) {
      int src = rel | mask;
      if (src < size) {
        size_t want = (size_t)(src + mask < size ? mask : size - src) * n;
        if ((rc = tsmpi_cg_recv(g, tmp + have, want, (src + root) % size, NULL))) break;
        have += want;
      }
    } else {
      rc = tsmpi_cg_send(g, tmp, have, ((rel ^ mask) + root) % size);
      break;
    }
  }
  if (!rc && rank == root && n)   /* relative order to rank order */
    for (int r = 0; r < size; r++) memcpy((char *)rbuf + (size_t)((r + root) % size) * n, tmp + (size_t)r * n, n);
  tsmpi_cg_free(tmp);
  return rc;
}

/* The root sends every rank its block in rank order. */
int tsmpi_scatter_linear(const tsmpi_cg *g, const void *sbuf, void *rbuf, size_t n, int root) {
  int rc = MPI_SUCCESS;
  if (g->rank != root) return tsmpi_cg_recv(g, rbuf, n, root, NULL);
  for (int i = 0; i < g->size && !rc; i++) {
    const char *src = (const char *)sbuf + (size_t)i * n;
    if (i == root) {
      if (rbuf && n) memcpy(rbuf, src, n);
    } else {
      rc = tsmpi_cg_send(g, src, n, i);
    }
  }
  return rc;
}

/* Binomial tree on relative ranks: a rank receives its subtree's blocks
 * from its parent, keeps its own and passes on each child's subtree,
 * farthest child first.  Cost lg p alpha + n (p-1)/p beta. */
int tsmpi_scatter_binomial(const tsmpi_cg *g, const void *sbuf, void *rbuf, size_t n, int root) {
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size, mask = 1, rc = MPI_SUCCESS;
  char *tmp;
  size_t cur = 0;
  if (rank == root) {   /* rank order to relative order */
    tmp = tsmpi_cg_alloc(g, (size_t)size * n);
    for (int r = 0; r < size && n; r++) memcpy(tmp + (size_t)r * n, (const char *)sbuf + (size_t)((r + root) % size) * n, n);
    cur = (size_t)size * n;
  } else {
    int sub = 1;
    while (sub < size && !(rel & sub)) sub <<= 1;
    tmp = tsmpi_cg_alloc(g, (size_t)(rel + sub > size ? size - rel : sub) * n);
  }
  while (mask < size) {
    if (rel & mask) {
      cur = (size_t)(rel + mask > size ? size - rel : mask) * n;
      if ((rc = tsmpi_cg_recv(g, tmp, cur, (rank - mask + size) % size, NULL))) goto out;
      break;
    }
    mask <<= 1;
  }
  for (mask >>= 1; mask > 0; mask >>= 1) {
    if (rel + mask < size) {
      size_t part = cur - n * (size_t)mask;
      if ((rc = tsmpi_cg_send(g, tmp + n * (size_t)mask, part, (rank + mask) % size))) goto out;
      cur -= part;
    }
  }
  if (rbuf && n) memcpy(rbuf, tmp, n);
out:
  tsmpi_cg_free(tmp);
  return rc;
}

int tsmpi_gatherv_linear(const tsmpi_cg *g, const void *sbuf, size_t sn, void *rbuf, const size_t *counts,
                         const size_t *displs, int root) {
  if (g->rank != root) return sn ? tsmpi_cg_send(g, sbuf, sn, root) : MPI_SUCCESS;
  int size = g->size, nreq = 0, rc;
  MPI_Request *req = tsmpi_cg_alloc(g, (size_t)size * sizeof *req);
  for (int i = 0; i < size; i++) {
    if (!counts[i]) continue;
    if (i == root) {
      if (sbuf) memcpy((char *)rbuf + displs[i], sbuf, counts[i]);
    } else if ((rc = tsmpi_cg_irecv(g, (char *)rbuf + displs[i], counts[i], i, &req[nreq++]))) {
      nreq--;
      break;
    }
  }
  rc = tsmpi_cg_waitall(g, nreq, req);
  tsmpi_cg_free(req);
  return rc;
}

int tsmpi_scatterv_linear(const tsmpi_cg *g, const void *sbuf, const size_t *counts, const size_t *displs,
                          void *rbuf, size_t rn, int root) {
  if (g->rank != root) return rn ? tsmpi_cg_recv(g, rbuf, rn, root, NULL) : MPI_SUCCESS;
  int size = g->size, nreq = 0, rc;
  MPI_Request *req = tsmpi_cg_alloc(g, (size_t)size * sizeof *req);
  for (int i = 0; i < size; i++) {
    if (!counts[i]) continue;
    if (i == root) {
      if (rbuf) memcpy(rbuf, (const char *)sbuf + displs[i], counts[i]);
    } else if ((rc = tsmpi_cg_isend(g, (const char *)sbuf + displs[i], counts[i], i, &req[nreq++]))) {
      nreq--;
      break;
    }
  }
  rc = tsmpi_cg_waitall(g, nreq, req);
  tsmpi_cg_free(req);
  return rc;
}

/* ==== allgather =========================================================== */

/* A gather to rank 0, then a broadcast, both linear (Open MPI's basic). */
int tsmpi_allgatherv_linear(const tsmpi_cg *g, void *buf, const size_t *counts, const size_t *displs) {
  size_t total = 0;
  for (int i = 0; i < g->size; i++) total += counts[i];
  int rc = tsmpi_gatherv_linear(g, g->rank ? (char *)buf + displs[g->rank] : NULL, counts[g->rank], buf, counts,
                                displs, 0);
  return rc ? rc : tsmpi_bcast_linear(g, buf, total, 0);
}

/* Bytes of ranks [a, b) (b may exceed p: wraps around) in the packed
 * buffer, whose blocks lie in rank order from displs[0] = 0. */
static size_t span(const tsmpi_cg *g, const size_t *counts, int a, int b) {
  size_t s = 0;
  for (int i = a; i < b; i++) s += counts[i % g->size];
  return s;
}

/* Recursive doubling: in step k, rank r exchanges all it has with r ^ 2^k;
 * beyond a power of two, the ranks that had no partner get the missing
 * blocks from their subtree (MPICH).  Cost lg p alpha + n (p-1)/p beta. */
int tsmpi_allgatherv_recursive_doubling(const tsmpi_cg *g, void *buffer, const size_t *counts,
                                        const size_t *displs) {
  int size = g->size, rank = g->rank, rc;
  char *buf = buffer;
  (void)displs;   /* the packed blocks lie in rank order */
  size_t total = span(g, counts, 0, size), cur = counts[rank], got = 0;
  for (int mask = 1, i = 0; mask < size; mask <<= 1, i++) {
    int dst = rank ^ mask, dst_root = dst >> i << i, my_root = rank >> i << i;
    if (dst < size) {
      size_t soff = span(g, counts, 0, my_root), roff = span(g, counts, 0, dst_root);
      got = 0;
      if ((rc = tsmpi_cg_sendrecv(g, buf + soff, cur, dst, buf + roff, total - roff, dst, &got))) return rc;
      cur += got;
    }
    if (dst_root + mask > size) {
      int done = size - my_root - mask, k = 0, j;
      for (j = mask; j; j >>= 1) k++;
      k--;
      size_t off = span(g, counts, 0, my_root + mask < size ? my_root + mask : size);
      for (int tmask = mask >> 1; tmask; tmask >>= 1, k--) {
        int d = rank ^ tmask, tree_root = rank >> k << k;
        if (d > rank && rank < tree_root + done && d >= tree_root + done) {
          if ((rc = tsmpi_cg_send(g, buf + off, got, d))) return rc;
        } else if (d < rank && d < tree_root + done && rank >= tree_root + done) {
          got = 0;
          if ((rc = tsmpi_cg_recv(g, buf + off, total - off, d, &got))) return rc;
          cur += got;
        }
      }
    }
  }
  return MPI_SUCCESS;
}

/* Bruck, Ho, Kipnis, Upfal, Weathersby 1997: ceil(lg p) steps; in step k
 * rank r sends all it has (the blocks of r .. r + 2^k - 1) to r - 2^k and
 * receives as much from r + 2^k; then the blocks are rotated into place.
 * Cost ceil(lg p) alpha + n (p-1)/p beta. */
int tsmpi_allgatherv_brucks(const tsmpi_cg *g, void *buffer, const size_t *counts, const size_t *displs) {
  int size = g->size, rank = g->rank, rc = MPI_SUCCESS;
  char *buf = buffer;
  size_t total = span(g, counts, 0, size), cur = counts[rank];
  char *tmp = tsmpi_cg_alloc(g, total);
  memcpy(tmp, buf + displs[rank], cur);
  int pof2 = 1;
  for (; pof2 <= size / 2; pof2 *= 2) {
    int src = (rank + pof2) % size, dst = (rank - pof2 + size) % size;
    size_t in = span(g, counts, src, src + pof2);
    if ((rc = tsmpi_cg_sendrecv(g, tmp, cur, dst, tmp + cur, in, src, NULL))) goto out;
    cur += in;
  }
  int rem = size - pof2;
  if (rem) {
    int src = (rank + pof2) % size, dst = (rank - pof2 + size) % size;
    size_t out = span(g, counts, rank, rank + rem), in = span(g, counts, src, src + rem);
    if ((rc = tsmpi_cg_sendrecv(g, tmp, out, dst, tmp + cur, in, src, NULL))) goto out;
  }
  /* tmp holds the blocks of ranks rank, rank + 1, ... in turn. */
  size_t off = 0;
  for (int i = 0; i < size; i++) {
    int r = (rank + i) % size;
    memcpy(buf + displs[r], tmp + off, counts[r]);
    off += counts[r];
  }
out:
  tsmpi_cg_free(tmp);
  return rc;
}

/* The ring: p - 1 steps, each rank passing to rank + 1 the block it got
 * from rank - 1 in the step before; pipelined in chunks of `chunk` bytes
 * when chunk > 0 (MPICH's allgatherv cuts blocks longer than 32 KiB,
 * MPIR_CVAR_ALLGATHERV_PIPELINE_MSG_SIZE).  Cost (p-1) alpha +
 * n (p-1)/p beta, unpipelined. */
static int ring(const tsmpi_cg *g, char *buf, const size_t *counts, const size_t *displs, size_t chunk) {
  int size = g->size, rank = g->rank, rc;
  int left = (size + rank - 1) % size, right = (rank + 1) % size;
  size_t total = span(g, counts, 0, size), torecv = total - counts[rank], tosend = total - counts[right];
  size_t soff = 0, roff = 0;
  int sidx = rank, ridx = left;
  if (!chunk) {
    for (int i = 0; i < size; i++)
      if (counts[i] > chunk) chunk = counts[i];
  }
  while (tosend || torecv) {
    size_t sendnow = counts[sidx] - soff > chunk ? chunk : counts[sidx] - soff;
    size_t recvnow = counts[ridx] - roff > chunk ? chunk : counts[ridx] - roff;
    char *s = buf + displs[sidx] + soff, *r = buf + displs[ridx] + roff;
    if (!tosend) sendnow = 0;
    if (!torecv) recvnow = 0;
    if (sendnow && recvnow) {
      if ((rc = tsmpi_cg_sendrecv(g, s, sendnow, right, r, recvnow, left, NULL))) return rc;
    } else if (recvnow) {
      if ((rc = tsmpi_cg_recv(g, r, recvnow, left, NULL))) return rc;
    } else if (sendnow) {
      if ((rc = tsmpi_cg_send(g, s, sendnow, right))) return rc;
    }
    tosend -= sendnow;
    torecv -= recvnow;
    soff += sendnow;
    roff += recvnow;
    if (soff == counts[sidx]) {
      soff = 0;
      sidx = (sidx + size - 1) % size;
    }
    if (roff == counts[ridx]) {
      roff = 0;
      ridx = (ridx + size - 1) % size;
    }
  }
  return MPI_SUCCESS;
}

int tsmpi_allgatherv_ring(const tsmpi_cg *g, void *buf, const size_t *counts, const size_t *displs) {
  return ring(g, buf, counts, displs, 0);
}

/* MPICH's allgatherv ring, pipelined in chunks of 32 KiB of the receive
 * type's extent (a whole number of elements, at least one). */
int tsmpi_allgatherv_ring_pipelined(const tsmpi_cg *g, void *buf, const size_t *counts, const size_t *displs,
                                    size_t unit, size_t extent) {
  size_t chunk = 0, max = 0;
  for (int i = 0; i < g->size; i++)
    if (counts[i] > max) max = counts[i];
  if (unit && extent && max / unit * extent > 32768) {
    chunk = 32768 / extent;
    if (!chunk) chunk = 1;
    chunk *= unit;
  }
  return ring(g, buf, counts, displs, chunk);
}
