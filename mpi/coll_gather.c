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

#include "mpi/coll.h"
#include "mpi/coll_sched.h"

/* ==== gather and scatter ================================================== */

/* The root receives every rank's block in rank order. */
void coll_gather_linear(coll_sched *s, const void *sbuf, void *rbuf, size_t n, int root) {
  const coll_cg *g = coll_sched_group(s);
  if (g->rank != root) {
    coll_sched_send(s, sbuf, n, root);
    return;
  }
  for (int i = 0; i < g->size; i++) {
    char *dst = (char *)rbuf + (size_t)i * n;
    if (i != root)
      coll_sched_recv(s, dst, n, i);
    else if (sbuf)
      coll_sched_copy(s, dst, sbuf, n);
  }
}

/* Blocks in relative order (from the root's on) at from, into rank order at
 * to, or back (unrotate): two copies. */
static void rotate(coll_sched *s, char *to, const char *from, size_t n, int root, int unrotate) {
  int size = coll_sched_group(s)->size;
  size_t head = (size_t)(size - root) * n, tail = (size_t)root * n;
  if (unrotate) {   /* rank order at from, relative order at to */
    coll_sched_copy(s, to, from + tail, head);
    coll_sched_copy(s, to + head, from, tail);
  } else {
    coll_sched_copy(s, to + tail, from, head);
    coll_sched_copy(s, to, from + head, tail);
  }
}

/* Binomial tree on ranks relative to the root: a rank gathers its subtree's
 * blocks (relative ranks rel .. rel + 2^k - 1), then sends them to its
 * parent in one message.  Cost lg p alpha + n (p-1)/p beta. */
void coll_gather_binomial(coll_sched *s, const void *sbuf, void *rbuf, size_t n, int root) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size;
  /* tmp holds the subtree's blocks in relative order, ours first. */
  int sub = 1;
  while (sub < size && !(rel & sub)) sub <<= 1;
  if (rel + sub > size) sub = size - rel;
  char *tmp = coll_sched_mem(s, (size_t)sub * n);
  coll_sched_copy(s, tmp, sbuf ? sbuf : (const char *)rbuf + (size_t)rank * n, n);
  size_t have = n;
  for (int mask = 1; mask < size; mask <<= 1) {
    if (!(rel & mask)) {
      int src = rel | mask;
      if (src < size) {
        size_t want = (size_t)(src + mask < size ? mask : size - src) * n;
        coll_sched_recv(s, tmp + have, want, (src + root) % size);
        have += want;
      }
    } else {
      coll_sched_send(s, tmp, have, ((rel ^ mask) + root) % size);
      break;
    }
  }
  if (rank == root) rotate(s, rbuf, tmp, n, root, 0);   /* relative order to rank order */
}

/* The root sends every rank its block in rank order. */
void coll_scatter_linear(coll_sched *s, const void *sbuf, void *rbuf, size_t n, int root) {
  const coll_cg *g = coll_sched_group(s);
  if (g->rank != root) {
    coll_sched_recv(s, rbuf, n, root);
    return;
  }
  for (int i = 0; i < g->size; i++) {
    const char *src = (const char *)sbuf + (size_t)i * n;
    if (i != root)
      coll_sched_send(s, src, n, i);
    else if (rbuf)
      coll_sched_copy(s, rbuf, src, n);
  }
}

/* Binomial tree on relative ranks: a rank receives its subtree's blocks
 * from its parent, keeps its own and passes on each child's subtree,
 * farthest child first.  Cost lg p alpha + n (p-1)/p beta. */
void coll_scatter_binomial(coll_sched *s, const void *sbuf, void *rbuf, size_t n, int root) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size, mask = 1;
  char *tmp;
  size_t cur = 0;
  if (rank == root) {   /* rank order to relative order */
    tmp = coll_sched_mem(s, (size_t)size * n);
    rotate(s, tmp, sbuf, n, root, 1);
    cur = (size_t)size * n;
  } else {
    int sub = 1;
    while (sub < size && !(rel & sub)) sub <<= 1;
    tmp = coll_sched_mem(s, (size_t)(rel + sub > size ? size - rel : sub) * n);
  }
  while (mask < size) {
    if (rel & mask) {
      cur = (size_t)(rel + mask > size ? size - rel : mask) * n;
      coll_sched_recv(s, tmp, cur, (rank - mask + size) % size);
      break;
    }
    mask <<= 1;
  }
  for (mask >>= 1; mask > 0; mask >>= 1) {
    if (rel + mask < size) {
      size_t part = cur - n * (size_t)mask;
      coll_sched_send(s, tmp + n * (size_t)mask, part, (rank + mask) % size);
      cur -= part;
    }
  }
  if (rbuf) coll_sched_copy(s, rbuf, tmp, n);
}

void coll_gatherv_linear(coll_sched *s, const void *sbuf, size_t sn, void *rbuf, const size_t *counts,
                         const size_t *displs, int root) {
  const coll_cg *g = coll_sched_group(s);
  if (g->rank != root) {
    if (sn) coll_sched_send(s, sbuf, sn, root);
    return;
  }
  for (int i = 0; i < g->size; i++) {
    if (!counts[i]) continue;
    if (i != root)
      coll_sched_irecv(s, (char *)rbuf + displs[i], counts[i], i);
    else if (sbuf)
      coll_sched_copy(s, (char *)rbuf + displs[i], sbuf, counts[i]);
  }
  coll_sched_waitall(s);
}

void coll_scatterv_linear(coll_sched *s, const void *sbuf, const size_t *counts, const size_t *displs,
                          void *rbuf, size_t rn, int root) {
  const coll_cg *g = coll_sched_group(s);
  if (g->rank != root) {
    if (rn) coll_sched_recv(s, rbuf, rn, root);
    return;
  }
  for (int i = 0; i < g->size; i++) {
    if (!counts[i]) continue;
    if (i != root)
      coll_sched_isend(s, (const char *)sbuf + displs[i], counts[i], i);
    else if (rbuf)
      coll_sched_copy(s, rbuf, (const char *)sbuf + displs[i], counts[i]);
  }
  coll_sched_waitall(s);
}

/* ==== allgather =========================================================== */

/* A gather to rank 0, then a broadcast, both linear (Open MPI's basic). */
void coll_allgatherv_linear(coll_sched *s, void *buf, const size_t *counts, const size_t *displs) {
  const coll_cg *g = coll_sched_group(s);
  size_t total = 0;
  for (int i = 0; i < g->size; i++) total += counts[i];
  coll_gatherv_linear(s, g->rank ? (char *)buf + displs[g->rank] : NULL, counts[g->rank], buf, counts, displs, 0);
  coll_bcast_linear(s, buf, total, 0);
}

/* Bytes of ranks [a, b) (b may exceed p: wraps around) in the packed
 * buffer, whose blocks lie in rank order from displs[0] = 0. */
static size_t span(const coll_cg *g, const size_t *counts, int a, int b) {
  size_t s = 0;
  for (int i = a; i < b; i++) s += counts[i % g->size];
  return s;
}

/* Recursive doubling: in step k, rank r exchanges all it has with r ^ 2^k;
 * beyond a power of two, the ranks that had no partner get the missing
 * blocks from their subtree (MPICH).  What a step brings is the partner
 * subtree's blocks.  Cost lg p alpha + n (p-1)/p beta. */
void coll_allgatherv_recursive_doubling(coll_sched *s, void *buffer, const size_t *counts, const size_t *displs) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank;
  char *buf = buffer;
  (void)displs;   /* the packed blocks lie in rank order */
  size_t total = span(g, counts, 0, size), cur = counts[rank], got = 0;
  for (int mask = 1, i = 0; mask < size; mask <<= 1, i++) {
    int dst = rank ^ mask, dst_root = dst >> i << i, my_root = rank >> i << i;
    if (dst < size) {
      size_t soff = span(g, counts, 0, my_root), roff = span(g, counts, 0, dst_root);
      got = span(g, counts, dst_root, dst_root + mask < size ? dst_root + mask : size);
      coll_sched_sendrecv(s, buf + soff, cur, dst, buf + roff, total - roff, dst);
      cur += got;
    }
    if (dst_root + mask > size) {
      int done = size - my_root - mask, k = 0, j;
      for (j = mask; j; j >>= 1) k++;
      k--;
      int from = my_root + mask < size ? my_root + mask : size;
      size_t off = span(g, counts, 0, from);
      for (int tmask = mask >> 1; tmask; tmask >>= 1, k--) {
        int d = rank ^ tmask, tree_root = rank >> k << k;
        if (d > rank && rank < tree_root + done && d >= tree_root + done) {
          coll_sched_send(s, buf + off, got, d);
        } else if (d < rank && d < tree_root + done && rank >= tree_root + done) {
          got = span(g, counts, from, my_root + 2 * mask < size ? my_root + 2 * mask : size);
          coll_sched_recv(s, buf + off, total - off, d);
          cur += got;
        }
      }
    }
  }
}

/* Bruck, Ho, Kipnis, Upfal, Weathersby 1997: ceil(lg p) steps; in step k
 * rank r sends all it has (the blocks of r .. r + 2^k - 1) to r - 2^k and
 * receives as much from r + 2^k; then the blocks are rotated into place.
 * Cost ceil(lg p) alpha + n (p-1)/p beta. */
void coll_allgatherv_brucks(coll_sched *s, void *buffer, const size_t *counts, const size_t *displs) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank;
  char *buf = buffer;
  size_t total = span(g, counts, 0, size), cur = counts[rank];
  char *tmp = coll_sched_mem(s, total);
  coll_sched_copy(s, tmp, buf + displs[rank], cur);
  int pof2 = 1;
  for (; pof2 <= size / 2; pof2 *= 2) {
    int src = (rank + pof2) % size, dst = (rank - pof2 + size) % size;
    size_t in = span(g, counts, src, src + pof2);
    coll_sched_sendrecv(s, tmp, cur, dst, tmp + cur, in, src);
    cur += in;
  }
  int rem = size - pof2;
  if (rem) {
    int src = (rank + pof2) % size, dst = (rank - pof2 + size) % size;
    size_t out = span(g, counts, rank, rank + rem), in = span(g, counts, src, src + rem);
    coll_sched_sendrecv(s, tmp, out, dst, tmp + cur, in, src);
  }
  /* tmp holds the blocks of ranks rank, rank + 1, ... in turn: rank's
   * onwards go to displs[rank], the rest to the start. */
  size_t head = span(g, counts, rank, size);
  coll_sched_copy(s, buf + displs[rank], tmp, head);
  coll_sched_copy(s, buf, tmp + head, total - head);
}

/* The ring: p - 1 steps, each rank passing to rank + 1 the block it got
 * from rank - 1 in the step before; pipelined in chunks of `chunk` bytes
 * when chunk > 0 (MPICH's allgatherv cuts blocks longer than 32 KiB,
 * MPIR_CVAR_ALLGATHERV_PIPELINE_MSG_SIZE).  Cost (p-1) alpha +
 * n (p-1)/p beta, unpipelined. */
static void ring(coll_sched *s, char *buf, const size_t *counts, const size_t *displs, size_t chunk) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank;
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
    char *sp = buf + displs[sidx] + soff, *rp = buf + displs[ridx] + roff;
    if (!tosend) sendnow = 0;
    if (!torecv) recvnow = 0;
    if (sendnow) coll_sched_send(s, sp, sendnow, right);
    if (recvnow) coll_sched_recv(s, rp, recvnow, left);
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
}

void coll_allgatherv_ring(coll_sched *s, void *buf, const size_t *counts, const size_t *displs) {
  ring(s, buf, counts, displs, 0);
}

/* MPICH's allgatherv ring, pipelined in chunks of 32 KiB of the receive
 * type's extent (a whole number of elements, at least one). */
void coll_allgatherv_ring_pipelined(coll_sched *s, void *buf, const size_t *counts, const size_t *displs,
                                    size_t unit, size_t extent) {
  size_t chunk = 0, max = 0;
  for (int i = 0; i < coll_sched_group(s)->size; i++)
    if (counts[i] > max) max = counts[i];
  if (unit && extent && max / unit * extent > 32768) {
    chunk = 32768 / extent;
    if (!chunk) chunk = 1;
    chunk *= unit;
  }
  ring(s, buf, counts, displs, chunk);
}
