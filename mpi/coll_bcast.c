/* coll_bcast.c -- barrier and broadcast algorithms (coll.h).
 *
 * Sources: MPICH (pmodels/mpich), src/mpi/coll/barrier/barrier_intra_dissemination.c,
 * src/mpi/coll/bcast/bcast_intra_binomial.c, bcast_utils.c (MPII_Scatter_for_bcast),
 * bcast_intra_scatter_recursive_doubling_allgather.c, bcast_intra_scatter_ring_allgather.c;
 * the linear ones as Open MPI's coll/basic component (ompi/mca/coll/basic). */
#include <string.h>

#include "mpi/coll.h"
#include "mpi/coll_sched.h"

/* ==== barrier ============================================================= */

/* Everyone tells rank 0, which then answers everyone, in rank order. */
void coll_barrier_linear(coll_sched *s) {
  const coll_cg *g = coll_sched_group(s);
  if (g->rank != 0) {
    coll_sched_send(s, NULL, 0, 0);
    coll_sched_recv(s, NULL, 0, 0);
    return;
  }
  for (int i = 1; i < g->size; i++) coll_sched_recv(s, NULL, 0, i);
  for (int i = 1; i < g->size; i++) coll_sched_send(s, NULL, 0, i);
}

/* Dissemination (Hensgen, Finkel, Manber 1988): ceil(lg p) rounds; in round
 * k each rank signals rank + 2^k and waits for rank - 2^k. */
void coll_barrier_dissemination(coll_sched *s) {
  const coll_cg *g = coll_sched_group(s);
  for (int mask = 1; mask < g->size; mask <<= 1) {
    int dst = (g->rank + mask) % g->size, src = (g->rank - mask + g->size) % g->size;
    coll_sched_sendrecv(s, NULL, 0, dst, NULL, 0, src);
  }
}

/* ==== broadcast =========================================================== */

/* The root sends to every other rank in rank order. */
void coll_bcast_linear(coll_sched *s, void *buf, size_t n, int root) {
  const coll_cg *g = coll_sched_group(s);
  if (g->rank != root) {
    coll_sched_recv(s, buf, n, root);
    return;
  }
  for (int i = 0; i < g->size; i++)
    if (i != root) coll_sched_send(s, buf, n, i);
}

/* Binomial tree on ranks relative to the root: receive from the parent
 * (relative rank minus its lowest set bit), then send to the children,
 * farthest first.  Cost lg p (alpha + n beta). */
void coll_bcast_binomial(coll_sched *s, void *buf, size_t n, int root) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size, mask = 1;
  while (mask < size) {
    if (rel & mask) {
      coll_sched_recv(s, buf, n, (rank - mask + size) % size);
      break;
    }
    mask <<= 1;
  }
  for (mask >>= 1; mask > 0; mask >>= 1)
    if (rel + mask < size) coll_sched_send(s, buf, n, (rank + mask) % size);
}

/* Bytes [a, b) of n, clamped: their count. */
static size_t clamp_span(size_t a, size_t b, size_t n) {
  if (a >= n) return 0;
  return (b < n ? b : n) - a;
}

/* The scatter both long-message broadcasts start with (MPICH's
 * MPII_Scatter_for_bcast): a binomial scatter of the n bytes in blocks of
 * ss = ceil(n / p), relative rank r getting bytes [r ss, (r + 1) ss).  A
 * rank receives its subtree's bytes, [r ss, (r + 2^k) ss) of n with 2^k
 * its relative rank's lowest bit, and passes on each child's; it ends with
 * its own block. */
static void scatter_for_bcast(coll_sched *s, char *buf, size_t n, int root, size_t ss) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size, mask = 1;
  size_t cur = rank == root ? n : 0;
  while (mask < size) {
    if (rel & mask) {
      size_t off = (size_t)rel * ss;
      cur = clamp_span(off, (size_t)(rel + mask) * ss, n);
      if (cur) coll_sched_recv(s, buf + off, n - off, (rank - mask + size) % size);
      break;
    }
    mask <<= 1;
  }
  for (mask >>= 1; mask > 0; mask >>= 1) {
    if (rel + mask < size) {
      size_t sub = ss * (size_t)mask;
      if (cur > sub) {
        coll_sched_send(s, buf + (size_t)(rel + mask) * ss, cur - sub, (rank + mask) % size);
        cur = sub;
      }
    }
  }
}

/* Scatter, then a recursive-doubling allgather of the blocks (Thakur,
 * Rabenseifner, Gropp 2005); ranks beyond a power of two get the blocks
 * they miss from their subtree, as MPICH does.  What each step brings is
 * the partner subtree's blocks (MPICH's schedule computes it so:
 * ibcast_intra_sched_scatter_recursive_doubling_allgather.c).  Cost
 * 2 lg p alpha + 2 n (p-1)/p beta (p a power of two). */
void coll_bcast_scatter_rdb_allgather(coll_sched *s, void *buffer, size_t n, int root) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size;
  char *buf = buffer;
  size_t ss = (n + (size_t)size - 1) / (size_t)size, got = 0;
  scatter_for_bcast(s, buf, n, root, ss);
  size_t cur = clamp_span((size_t)rel * ss, (size_t)(rel + 1) * ss, n);
  for (int mask = 1, i = 0; mask < size; mask <<= 1, i++) {
    int rdst = rel ^ mask, dst = (rdst + root) % size;
    int dst_root = rdst >> i << i, my_root = rel >> i << i;
    size_t soff = (size_t)my_root * ss, roff = (size_t)dst_root * ss;
    if (rdst < size) {
      size_t room = roff < n ? n - roff : 0;
      got = clamp_span(roff, roff + (size_t)mask * ss, n);
      coll_sched_sendrecv(s, buf + (soff < n ? soff : n), cur, dst, buf + (roff < n ? roff : n), room, dst);
      cur += got;
    }
    /* Ranks of this subtree whose partner was beyond p get the missing
     * blocks from those of the subtree that have them. */
    if (dst_root + mask > size) {
      int done = size - my_root - mask, k = 0, j;
      for (j = mask; j; j >>= 1) k++;
      k--;
      size_t off = (size_t)(my_root + mask) * ss;
      for (int tmask = mask >> 1; tmask; tmask >>= 1, k--) {
        int rd = rel ^ tmask, d = (rd + root) % size, tree_root = rel >> k << k;
        if (rd > rel && rel < tree_root + done && rd >= tree_root + done) {
          coll_sched_send(s, buf + (off < n ? off : n), got, d);
        } else if (rd < rel && rd < tree_root + done && rel >= tree_root + done) {
          got = clamp_span(off, off + (size_t)mask * ss, n);
          coll_sched_recv(s, buf + (off < n ? off : n), off < n ? n - off : 0, d);
          cur += got;
        }
      }
    }
  }
}

/* Scatter, then a ring allgather of the blocks: p - 1 steps, each rank
 * passing on to rank + 1 the block it got from rank - 1.  Cost
 * (lg p + p - 1) alpha + 2 n (p-1)/p beta. */
void coll_bcast_scatter_ring_allgather(coll_sched *s, void *buffer, size_t n, int root) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank;
  char *buf = buffer;
  size_t ss = (n + (size_t)size - 1) / (size_t)size;
  scatter_for_bcast(s, buf, n, root, ss);
  int left = (size + rank - 1) % size, right = (rank + 1) % size, j = rank, jnext = left;
  for (int i = 1; i < size; i++) {
    int lb = (jnext - root + size) % size, rb = (j - root + size) % size;
    size_t loff = (size_t)lb * ss, roff = (size_t)rb * ss;
    size_t lcnt = clamp_span(loff, loff + ss, n), rcnt = clamp_span(roff, roff + ss, n);
    coll_sched_sendrecv(s, buf + (roff < n ? roff : n), rcnt, right, buf + (loff < n ? loff : n), lcnt, left);
    j = jnext;
    jnext = (size + jnext - 1) % size;
  }
}
