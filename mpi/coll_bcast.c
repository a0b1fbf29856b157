/* coll_bcast.c -- barrier and broadcast algorithms (coll.h).
 *
 * Sources: MPICH (pmodels/mpich), src/mpi/coll/barrier/barrier_intra_dissemination.c,
 * src/mpi/coll/bcast/bcast_intra_binomial.c, bcast_utils.c (MPII_Scatter_for_bcast),
 * bcast_intra_scatter_recursive_doubling_allgather.c, bcast_intra_scatter_ring_allgather.c;
 * the linear ones as Open MPI's coll/basic component (ompi/mca/coll/basic). */
#include <string.h>

#include "coll.h"

/* ==== barrier ============================================================= */

/* Everyone tells rank 0, which then answers everyone, in rank order. */
int tsmpi_barrier_linear(const tsmpi_cg *g) {
  int rc = MPI_SUCCESS;
  if (g->rank != 0) {
    if ((rc = tsmpi_cg_send(g, NULL, 0, 0))) return rc;
    return tsmpi_cg_recv(g, NULL, 0, 0, NULL);
  }
  for (int i = 1; i < g->size && !rc; i++) rc = tsmpi_cg_recv(g, NULL, 0, i, NULL);
  for (int i = 1; i < g->size && !rc; i++) rc = tsmpi_cg_send(g, NULL, 0, i);
  return rc;
}

/* Dissemination (Hensgen, Finkel, Manber 1988): ceil(lg p) rounds; in round
 * k each rank signals rank + 2^k and waits for rank - 2^k. */
int tsmpi_barrier_dissemination(const tsmpi_cg *g) {
  int rc = MPI_SUCCESS;
  for (int mask = 1; mask < g->size && !rc; mask <<= 1) {
    int dst = (g->rank + mask) % g->size, src = (g->rank - mask + g->size) % g->size;
    rc = tsmpi_cg_sendrecv(g, NULL, 0, dst, NULL, 0, src, NULL);
  }
  return rc;
}

/* ==== broadcast =========================================================== */

/* The root sends to every other rank in rank order. */
int tsmpi_bcast_linear(const tsmpi_cg *g, void *buf, size_t n, int root) {
  int rc = MPI_SUCCESS;
  if (g->rank != root) return tsmpi_cg_recv(g, buf, n, root, NULL);
  for (int i = 0; i < g->size && !rc; i++)
    if (i != root) rc = tsmpi_cg_send(g, buf, n, i);
  return rc;
}

/* Binomial tree on ranks relative to the root: receive from the parent
 * (relative rank minus its lowest set bit), then send to the children,
 * farthest first.  Cost lg p (alpha + n beta). */
int tsmpi_bcast_binomial(const tsmpi_cg *g, void *buf, size_t n, int root) {
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size, mask = 1, rc = MPI_SUCCESS;
  while (mask < size) {
    if (rel & mask) {
      if ((rc = tsmpi_cg_recv(g, buf, n, (rank - mask + size) % size, NULL))) return rc;
      break;
    }
    mask <<= 1;
  }
  for (mask >>= 1; mask > 0 && !rc; mask >>= 1)
    if (rel + mask < size) rc = tsmpi_cg_send(g, buf, n, (rank + mask) % size);
  return rc;
}

/* The scatter both long-message broadcasts start with (MPICH's
 * MPII_Scatter_for_bcast): a binomial scatter of the n bytes in blocks of
 * ss = ceil(n / p), relative rank r getting bytes [r ss, (r + 1) ss); each
 * rank ends with its subtree's bytes from r ss on, *have of them. */
static int scatter_for_bcast(const tsmpi_cg *g, char *buf, size_t n, int root, size_t ss, size_t *have) {
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size, mask = 1, rc;
  size_t cur = rank == root ? n : 0;
  while (mask < size) {
    if (rel & mask) {
      size_t off = (size_t)rel * ss;
      cur = 0;
      if (off < n && (rc = tsmpi_cg_recv(g, buf + off, n - off, (rank - mask + size) % size, &cur))) return rc;
      break;
    }
    mask <<= 1;
  }
  for (mask >>= 1; mask > 0; mask >>= 1) {
    if (rel + mask < size) {
      size_t sub = ss * (size_t)mask;
      if (cur > sub) {
        if ((rc = tsmpi_cg_send(g, buf + (size_t)(rel + mask) * ss, cur - sub, (rank + mask) % size))) return rc;
        cur = sub;
      }
    }
  }
  *have = cur;
  return MPI_SUCCESS;
}

/* Scatter, then a recursive-doubling allgather of the blocks (Thakur,
 * Rabenseifner, Gropp 2005); ranks beyond a power of two get the blocks
 * they miss from their subtree, as MPICH does.  Cost 2 lg p alpha +
 * 2 n (p-1)/p beta (p a power of two). */
int tsmpi_bcast_scatter_rdb_allgather(const tsmpi_cg *g, void *buffer, size_t n, int root) {
  int size = g->size, rank = g->rank, rel = (rank - root + size) % size, rc;
  char *buf = buffer;
  size_t ss = (n + (size_t)size - 1) / (size_t)size, cur, got = 0;
  if ((rc = scatter_for_bcast(g, buf, n, root, ss, &cur))) return rc;
  for (int mask = 1, i = 0; mask < size; mask <<= 1, i++) {
    int rdst = rel ^ mask, dst = (rdst + root) % size;
    int dst_root = rdst >> i << i, my_root = rel >> i << i;
    size_t soff = (size_t)my_root * ss, roff = (size_t)dst_root * ss;
    if (rdst < size) {
      size_t room = roff < n ? n - roff : 0;
      got = 0;
      if ((rc = tsmpi_cg_sendrecv(g, buf + (soff < n ? soff : n), cur, dst, buf + (roff < n ? roff : n), room,
                                  dst, &got)))
        return rc;
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
          if ((rc = tsmpi_cg_send(g, buf + (off < n ? off : n), got, d))) return rc;
        } else if (rd < rel && rd < tree_root + done && rel >= tree_root + done) {
          got = 0;
          if ((rc = tsmpi_cg_recv(g, buf + (off < n ? off : n), off < n ? n - off : 0, d, &got))) return rc;
          cur += got;
        }
      }
    }
  }
  return MPI_SUCCESS;
}

/* Scatter, then a ring allgather of the blocks: p - 1 steps, each rank
 * passing on to rank + 1 the block it got from rank - 1.  Cost
 * (lg p + p - 1) alpha + 2 n (p-1)/p beta. */
int tsmpi_bcast_scatter_ring_allgather(const tsmpi_cg *g, void *buffer, size_t n, int root) {
  int size = g->size, rank = g->rank, rc;
  char *buf = buffer;
  size_t ss = (n + (size_t)size - 1) / (size_t)size, cur;
  if ((rc = scatter_for_bcast(g, buf, n, root, ss, &cur))) return rc;
  int left = (size + rank - 1) % size, right = (rank + 1) % size, j = rank, jnext = left;
  for (int i = 1; i < size; i++) {
    int lb = (jnext - root + size) % size, rb = (j - root + size) % size;
    size_t loff = (size_t)lb * ss, roff = (size_t)rb * ss;
    size_t lcnt = loff < n ? (n - loff < ss ? n - loff : ss) : 0, rcnt = roff < n ? (n - roff < ss ? n - roff : ss) : 0;
    if ((rc = tsmpi_cg_sendrecv(g, buf + (roff < n ? roff : n), rcnt, right, buf + (loff < n ? loff : n), lcnt, left,
                                NULL)))
      return rc;
    j = jnext;
    jnext = (size + jnext - 1) % size;
  }
  return MPI_SUCCESS;
}
