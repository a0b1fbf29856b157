/* coll_reduce.c -- reduce and allreduce algorithms (coll.h).
 *
 * Sources: MPICH (pmodels/mpich), src/mpi/coll/reduce/reduce_intra_binomial.c,
 * reduce_intra_reduce_scatter_gather.c, allreduce/allreduce_intra_recursive_doubling.c,
 * allreduce_intra_reduce_scatter_allgather.c (Rabenseifner's algorithms,
 * www.hlrs.de/mpi/myreduce.html; Thakur, Rabenseifner, Gropp, "Optimization of collective
 * communication operations in MPICH", IJHPCA 19(1), 2005); the linear ones as Open MPI's
 * coll/basic.  Operands are combined as MPICH combines them: `left op right` below names the
 * order. */
#include <stdlib.h>
#include <string.h>

#include "coll.h"

/* acc = left op acc, or acc = acc op right: the result lands in the right
 * operand's buffer (op.h), so these copy it back when it is not acc. */
static void acc_after(const tsmpi_red *r, void *acc, const void *right, void *scratch, int count) {
  memcpy(scratch, right, (size_t)count * r->tsize);
  tsmpi_red_apply(r, acc, scratch, count);
  memcpy(acc, scratch, (size_t)count * r->tsize);
}

/* ==== reduce ============================================================== */

/* Every rank sends to the root, which folds the operands in rank order:
 * ((a0 op a1) op a2) ... */
int tsmpi_reduce_linear(const tsmpi_cg *g, const tsmpi_red *r, const void *sbuf, void *rbuf, int count, int root) {
  size_t n = (size_t)count * r->tsize;
  int rc = MPI_SUCCESS;
  if (g->rank != root) return tsmpi_cg_send(g, sbuf, n, root);
  char *acc = tsmpi_cg_alloc(g, n), *in = tsmpi_cg_alloc(g, n);
  const void *mine = sbuf ? sbuf : rbuf;
  for (int i = 0; i < g->size && !rc; i++) {
    const void *a = mine;
    if (i != root) {
      if ((rc = tsmpi_cg_recv(g, in, n, i, NULL))) break;
      a = in;
    }
    if (i == 0)
      memcpy(acc, a, n);
    else if (a == in)
      tsmpi_red_apply(r, acc, in, count), memcpy(acc, in, n);
    else
      acc_after(r, acc, a, in, count);
  }
  if (!rc) memcpy(rbuf, acc, n);
  tsmpi_cg_free(acc);
  tsmpi_cg_free(in);
  return rc;
}

/* Binomial tree on ranks relative to the root (to rank 0, then a message
 * to the root, for non-commutative operations): a rank receives from
 * relrank | 2^k for rising k, combining, until its bit k is set, when it
 * sends its partial result to its parent.  MPICH combines a child's result
 * on the left of the parent's when op commutes, on the right otherwise. */
int tsmpi_reduce_binomial(const tsmpi_cg *g, const tsmpi_red *r, const void *sbuf, void *rbuf, int count, int root) {
  int size = g->size, rank = g->rank, rc = MPI_SUCCESS;
  int lroot = r->commute ? root : 0, rel = (rank - lroot + size) % size;
  size_t n = (size_t)count * r->tsize;
  char *acc = tsmpi_cg_alloc(g, n), *tmp = tsmpi_cg_alloc(g, n);
  memcpy(acc, sbuf ? sbuf : rbuf, n);
  for (int mask = 1; mask < size; mask <<= 1) {
    if (!(mask & rel)) {
      int src = rel | mask;
      if (src < size) {
        if ((rc = tsmpi_cg_recv(g, tmp, n, (src + lroot) % size, NULL))) goto out;
        if (r->commute) {
          tsmpi_red_apply(r, tmp, acc, count);   /* acc = child op acc */
        } else {
          tsmpi_red_apply(r, acc, tmp, count);   /* acc = acc op child */
          memcpy(acc, tmp, n);
        }
      }
    } else {
      rc = tsmpi_cg_send(g, acc, n, ((rel & ~mask) + lroot) % size);
      goto out;
    }
  }
out:
  if (!rc && !r->commute && root != 0) {
    if (rank == 0) rc = tsmpi_cg_send(g, acc, n, root);
    else if (rank == root) rc = tsmpi_cg_recv(g, acc, n, 0, NULL);
  }
  if (!rc && rank == root) memcpy(rbuf, acc, n);
  tsmpi_cg_free(acc);
  tsmpi_cg_free(tmp);
  return rc;
}

/* The blocks the Rabenseifner algorithms cut count elements into among
 * pof2 ranks: count / pof2 each, one more for the first count % pof2. */
static void blocks(int count, int pof2, int *cnts, int *disps) {
  for (int i = 0; i < pof2; i++) cnts[i] = count / pof2 + (i < count % pof2);
  disps[0] = 0;
  for (int i = 1; i < pof2; i++) disps[i] = disps[i - 1] + cnts[i - 1];
}

static int sum(const int *cnts, int a, int b) {
  int s = 0;
  for (int i = a; i < b; i++) s += cnts[i];
  return s;
}

/* The reduce-scatter both Rabenseifner algorithms start with, among the
 * pof2 new ranks: recursive halving of the data with partners at distance
 * 1, 2, 4, ... (newrank ^ mask); ranks() maps a new rank to its rank.
 * work holds the operand and gets this rank's reduced block. */
static int rsag_scatter(const tsmpi_cg *g, const tsmpi_red *r, char *work, char *tmp, int newrank, int pof2,
                        int rem, int odd_kept, const int *cnts, const int *disps, int *send_idx, int *last_idx) {
  int mask = 1, recv_idx = 0, rc;
  *send_idx = 0;
  *last_idx = pof2;
  while (mask < pof2) {
    int newdst = newrank ^ mask, dst = newdst < rem ? newdst * 2 + odd_kept : newdst + rem, send_cnt, recv_cnt;
    if (newrank < newdst) {
      *send_idx = recv_idx + pof2 / (mask * 2);
      send_cnt = sum(cnts, *send_idx, *last_idx);
      recv_cnt = sum(cnts, recv_idx, *send_idx);
    } else {
      recv_idx = *send_idx + pof2 / (mask * 2);
      send_cnt = sum(cnts, *send_idx, recv_idx);
      recv_cnt = sum(cnts, recv_idx, *last_idx);
    }
    if ((rc = tsmpi_cg_sendrecv(g, work + (size_t)disps[*send_idx] * r->tsize, (size_t)send_cnt * r->tsize, dst,
                                tmp + (size_t)disps[recv_idx] * r->tsize, (size_t)recv_cnt * r->tsize, dst, NULL)))
      return rc;
    /* received op ours: these algorithms run for predefined (commutative)
     * operations only */
    tsmpi_red_apply(r, tmp + (size_t)disps[recv_idx] * r->tsize, work + (size_t)disps[recv_idx] * r->tsize, recv_cnt);
    *send_idx = recv_idx;
    mask <<= 1;
    if (mask < pof2) *last_idx = recv_idx + pof2 / mask;
  }
  return MPI_SUCCESS;
}

/* Rabenseifner's reduce: beyond a power of two, the first odd ranks fold
 * their operands into their left neighbours; a reduce-scatter by recursive
 * halving among the pof2 remaining ranks; then a binomial gather of the
 * blocks to the root (through new rank 0 when the root was folded away).
 * For predefined operations and count >= pof2.  Cost 2 lg p alpha +
 * 2 n (p-1)/p beta + n (p-1)/p gamma. */
int tsmpi_reduce_scatter_gather(const tsmpi_cg *g, const tsmpi_red *r, const void *sbuf, void *rbuf, int count,
                                int root) {
  int size = g->size, rank = g->rank, rc = MPI_SUCCESS, pof2 = tsmpi_pof2(size), rem = size - pof2, newrank;
  size_t n = (size_t)count * r->tsize;
  char *work = tsmpi_cg_alloc(g, n), *tmp = tsmpi_cg_alloc(g, n);
  int *cnts = tsmpi_cg_alloc(g, 2 * (size_t)pof2 * sizeof *cnts), *disps = cnts + pof2;
  int send_idx = 0, last_idx = 0, newroot;
  memcpy(work, sbuf ? sbuf : rbuf, n);
  if (rank < 2 * rem) {
    if (rank % 2) {
      if ((rc = tsmpi_cg_send(g, work, n, rank - 1))) goto out;
      newrank = -1;
    } else {
      if ((rc = tsmpi_cg_recv(g, tmp, n, rank + 1, NULL))) goto out;
      tsmpi_red_apply(r, tmp, work, count);
      newrank = rank / 2;
    }
  } else {
    newrank = rank - rem;
  }
  blocks(count, pof2, cnts, disps);
  if (newrank != -1 && (rc = rsag_scatter(g, r, work, tmp, newrank, pof2, rem, 0, cnts, disps, &send_idx, &last_idx)))
    goto out;
  /* The gather to the root. */
  if (root < 2 * rem) {
    if (root % 2) {
      if (rank == root) {
        if ((rc = tsmpi_cg_recv(g, work, (size_t)cnts[0] * r->tsize, 0, NULL))) goto out;
        newrank = 0;
        send_idx = 0;
        last_idx = 2;
      } else if (newrank == 0) {
        if ((rc = tsmpi_cg_send(g, work, (size_t)cnts[0] * r->tsize, root))) goto out;
        newrank = -1;
      }
      newroot = 0;
    } else {
      newroot = root / 2;
    }
  } else {
    newroot = root - rem;
  }
  if (newrank != -1) {
    int j = 0, mask = 1;
    while (mask < pof2) {
      mask <<= 1;
      j++;
    }
    mask >>= 1;
    j--;
    for (; mask > 0; mask >>= 1, j--) {
      int newdst = newrank ^ mask, dst = newdst < rem ? newdst * 2 : newdst + rem, recv_idx, send_cnt, recv_cnt;
      if (newdst == 0 && root < 2 * rem && root % 2) dst = root;
      int newdst_tree_root = newdst >> j << j, newroot_tree_root = newroot >> j << j;
      if (newrank < newdst) {
        if (mask != pof2 / 2) last_idx = last_idx + pof2 / (mask * 2);
        recv_idx = send_idx + pof2 / (mask * 2);
        send_cnt = sum(cnts, send_idx, recv_idx);
        recv_cnt = sum(cnts, recv_idx, last_idx);
      } else {
        recv_idx = send_idx - pof2 / (mask * 2);
        send_cnt = sum(cnts, send_idx, last_idx);
        recv_cnt = sum(cnts, recv_idx, send_idx);
      }
      if (newdst_tree_root == newroot_tree_root) {
        rc = tsmpi_cg_send(g, work + (size_t)disps[send_idx] * r->tsize, (size_t)send_cnt * r->tsize, dst);
        break;
      }
      if ((rc = tsmpi_cg_recv(g, work + (size_t)disps[recv_idx] * r->tsize, (size_t)recv_cnt * r->tsize, dst, NULL)))
        break;
      if (newrank > newdst) send_idx = recv_idx;
    }
  }
  if (!rc && rank == root) memcpy(rbuf, work, n);
out:
  tsmpi_cg_free(work);
  tsmpi_cg_free(tmp);
  tsmpi_cg_free(cnts);
  return rc;
}

/* ==== allreduce =========================================================== */

/* A linear reduce to rank 0, then a linear broadcast. */
int tsmpi_allreduce_linear(const tsmpi_cg *g, const tsmpi_red *r, void *buf, int count) {
  int rc = tsmpi_reduce_linear(g, r, g->rank ? buf : NULL, buf, count, 0);
  return rc ? rc : tsmpi_bcast_linear(g, buf, (size_t)count * r->tsize, 0);
}

/* Fold the first 2 rem ranks pairwise into the odd ones (even sends to
 * rank + 1, which combines even op odd); *newrank is -1 for the even ones. */
static int fold_into_odd(const tsmpi_cg *g, const tsmpi_red *r, char *buf, char *tmp, int count, int rem,
                         int *newrank) {
  int rank = g->rank, rc;
  size_t n = (size_t)count * r->tsize;
  if (rank >= 2 * rem) {
    *newrank = rank - rem;
    return MPI_SUCCESS;
  }
  if (rank % 2 == 0) {
    *newrank = -1;
    return tsmpi_cg_send(g, buf, n, rank + 1);
  }
  if ((rc = tsmpi_cg_recv(g, tmp, n, rank - 1, NULL))) return rc;
  tsmpi_red_apply(r, tmp, buf, count);
  *newrank = rank / 2;
  return MPI_SUCCESS;
}

/* ... and at the end the odd ones send the result back. */
static int unfold(const tsmpi_cg *g, char *buf, size_t n, int rem) {
  int rank = g->rank;
  if (rank >= 2 * rem) return MPI_SUCCESS;
  return rank % 2 ? tsmpi_cg_send(g, buf, n, rank - 1) : tsmpi_cg_recv(g, buf, n, rank + 1, NULL);
}

/* Recursive doubling: beyond a power of two the first ranks fold pairwise;
 * among the pof2 others, in step k every rank exchanges its whole partial
 * result with new rank ^ 2^k and combines (received op ours when op
 * commutes or the partner is lower, else ours op received); the folded
 * ranks get the result back.  Cost lg p (alpha + n beta + n gamma). */
int tsmpi_allreduce_recursive_doubling(const tsmpi_cg *g, const tsmpi_red *r, void *buffer, int count) {
  int size = g->size, rank = g->rank, pof2 = tsmpi_pof2(size), rem = size - pof2, newrank, rc;
  size_t n = (size_t)count * r->tsize;
  char *buf = buffer, *tmp = tsmpi_cg_alloc(g, n);
  if ((rc = fold_into_odd(g, r, buf, tmp, count, rem, &newrank))) goto out;
  if (newrank != -1) {
    for (int mask = 1; mask < pof2; mask <<= 1) {
      int newdst = newrank ^ mask, dst = newdst < rem ? newdst * 2 + 1 : newdst + rem;
      if ((rc = tsmpi_cg_sendrecv(g, buf, n, dst, tmp, n, dst, NULL))) goto out;
      if (r->commute || dst < rank) {
        tsmpi_red_apply(r, tmp, buf, count);
      } else {
        tsmpi_red_apply(r, buf, tmp, count);
        memcpy(buf, tmp, n);
      }
    }
  }
  rc = unfold(g, buf, n, rem);
out:
  tsmpi_cg_free(tmp);
  return rc;
}

/* Rabenseifner's allreduce: the fold, a reduce-scatter by recursive
 * halving (partners at distance 1, 2, 4, ...), an allgather by recursive
 * doubling back, the unfold.  For predefined operations and count >= pof2.
 * Cost 2 lg p alpha + 2 n (p-1)/p beta + n (p-1)/p gamma. */
int tsmpi_allreduce_reduce_scatter_allgather(const tsmpi_cg *g, const tsmpi_red *r, void *buffer, int count) {
  int size = g->size, pof2 = tsmpi_pof2(size), rem = size - pof2, newrank, rc;
  size_t n = (size_t)count * r->tsize;
  char *buf = buffer, *tmp = tsmpi_cg_alloc(g, n);
  int *cnts = tsmpi_cg_alloc(g, 2 * (size_t)pof2 * sizeof *cnts), *disps = cnts + pof2, send_idx, last_idx;
  if ((rc = fold_into_odd(g, r, buf, tmp, count, rem, &newrank))) goto out;
  if (newrank != -1) {
    blocks(count, pof2, cnts, disps);
    if ((rc = rsag_scatter(g, r, buf, tmp, newrank, pof2, rem, 1, cnts, disps, &send_idx, &last_idx))) goto out;
    for (int mask = pof2 >> 1; mask > 0; mask >>= 1) {
      int newdst = newrank ^ mask, dst = newdst < rem ? newdst * 2 + 1 : newdst + rem, recv_idx, send_cnt, recv_cnt;
      if (newrank < newdst) {
        if (mask != pof2 / 2) last_idx = last_idx + pof2 / (mask * 2);
        recv_idx = send_idx + pof2 / (mask * 2);
        send_cnt = sum(cnts, send_idx, recv_idx);
        recv_cnt = sum(cnts, recv_idx, last_idx);
      } else {
        recv_idx = send_idx - pof2 / (mask * 2);
        send_cnt = sum(cnts, send_idx, last_idx);
        recv_cnt = sum(cnts, recv_idx, send_idx);
      }
      if ((rc = tsmpi_cg_sendrecv(g, buf + (size_t)disps[send_idx] * r->tsize, (size_t)send_cnt * r->tsize, dst,
                                  buf + (size_t)disps[recv_idx] * r->tsize, (size_t)recv_cnt * r->tsize, dst, NULL)))
        goto out;
      if (newrank > newdst) send_idx = recv_idx;
    }
  }
  rc = unfold(g, buf, n, rem);
out:
  tsmpi_cg_free(tmp);
  tsmpi_cg_free(cnts);
  return rc;
}
