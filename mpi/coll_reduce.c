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

#include "mpi/coll.h"
#include "mpi/coll_sched.h"

/* acc = acc op right: the result lands in the right operand's buffer
 * (op.h), so it goes through scratch and back. */
static void acc_after(coll_sched *s, void *acc, const void *right, void *scratch, int count) {
  size_t n = (size_t)count * coll_sched_red(s)->tsize;
  coll_sched_copy(s, scratch, right, n);
  coll_sched_reduce(s, acc, scratch, count);
  coll_sched_copy(s, acc, scratch, n);
}

/* ==== reduce ============================================================== */

/* Every rank sends to the root, which folds the operands in rank order:
 * ((a0 op a1) op a2) ... */
void coll_reduce_linear(coll_sched *s, const void *sbuf, void *rbuf, int count, int root) {
  const coll_cg *g = coll_sched_group(s);
  size_t n = (size_t)count * coll_sched_red(s)->tsize;
  if (g->rank != root) {
    coll_sched_send(s, sbuf, n, root);
    return;
  }
  char *acc = coll_sched_mem(s, n), *in = coll_sched_mem(s, n);
  const void *mine = sbuf ? sbuf : rbuf;
  for (int i = 0; i < g->size; i++) {
    const void *a = mine;
    if (i != root) {
      coll_sched_recv(s, in, n, i);
      a = in;
    }
    if (i == 0) {
      coll_sched_copy(s, acc, a, n);
    } else if (a == in) {
      coll_sched_reduce(s, acc, in, count);
      coll_sched_copy(s, acc, in, n);
    } else {
      acc_after(s, acc, a, in, count);
    }
  }
  coll_sched_copy(s, rbuf, acc, n);
}

/* Binomial tree on ranks relative to the root (to rank 0, then a message
 * to the root, for non-commutative operations): a rank receives from
 * relrank | 2^k for rising k, combining, until its bit k is set, when it
 * sends its partial result to its parent.  MPICH combines a child's result
 * on the left of the parent's when op commutes, on the right otherwise. */
void coll_reduce_binomial(coll_sched *s, const void *sbuf, void *rbuf, int count, int root) {
  const coll_cg *g = coll_sched_group(s);
  const coll_red *r = coll_sched_red(s);
  int size = g->size, rank = g->rank;
  int lroot = r->commute ? root : 0, rel = (rank - lroot + size) % size;
  size_t n = (size_t)count * r->tsize;
  char *acc = coll_sched_mem(s, n), *tmp = coll_sched_mem(s, n);
  coll_sched_copy(s, acc, sbuf ? sbuf : rbuf, n);
  for (int mask = 1; mask < size; mask <<= 1) {
    if (!(mask & rel)) {
      int src = rel | mask;
      if (src < size) {
        coll_sched_recv(s, tmp, n, (src + lroot) % size);
        if (r->commute) {
          coll_sched_reduce(s, tmp, acc, count);   /* acc = child op acc */
        } else {
          coll_sched_reduce(s, acc, tmp, count);   /* acc = acc op child */
          coll_sched_copy(s, acc, tmp, n);
        }
      }
    } else {
      coll_sched_send(s, acc, n, ((rel & ~mask) + lroot) % size);
      break;
    }
  }
  if (!r->commute && root != 0) {
    if (rank == 0) coll_sched_send(s, acc, n, root);
    else if (rank == root) coll_sched_recv(s, acc, n, 0);
  }
  if (rank == root) coll_sched_copy(s, rbuf, acc, n);
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
 * 1, 2, 4, ... (newrank ^ mask).  work holds the operand and gets this
 * rank's reduced block. */
static void rsag_scatter(coll_sched *s, char *work, char *tmp, int newrank, int pof2, int rem, int odd_kept,
                         const int *cnts, const int *disps, int *send_idx, int *last_idx) {
  size_t ts = coll_sched_red(s)->tsize;
  int mask = 1, recv_idx = 0;
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
    coll_sched_sendrecv(s, work + (size_t)disps[*send_idx] * ts, (size_t)send_cnt * ts, dst,
                        tmp + (size_t)disps[recv_idx] * ts, (size_t)recv_cnt * ts, dst);
    /* received op ours: these algorithms run for predefined (commutative)
     * operations only */
    coll_sched_reduce(s, tmp + (size_t)disps[recv_idx] * ts, work + (size_t)disps[recv_idx] * ts, recv_cnt);
    *send_idx = recv_idx;
    mask <<= 1;
    if (mask < pof2) *last_idx = recv_idx + pof2 / mask;
  }
}

/* A step at distance mask of the gather by recursive doubling that follows
 * rsag_scatter (MPICH's): the blocks from send_idx this rank sends
 * (*send_cnt elements) and those from *recv_idx it receives (*recv_cnt),
 * up: its partner's rank is above its own; *last_idx moves on. */
static void gather_step(const int *cnts, int pof2, int mask, int up, int send_idx, int *last_idx, int *recv_idx,
                        int *send_cnt, int *recv_cnt) {
  if (up) {
    if (mask != pof2 / 2) *last_idx += pof2 / (mask * 2);
    *recv_idx = send_idx + pof2 / (mask * 2);
    *send_cnt = sum(cnts, send_idx, *recv_idx);
    *recv_cnt = sum(cnts, *recv_idx, *last_idx);
  } else {
    *recv_idx = send_idx - pof2 / (mask * 2);
    *send_cnt = sum(cnts, send_idx, *last_idx);
    *recv_cnt = sum(cnts, *recv_idx, send_idx);
  }
}

/* Rabenseifner's reduce: beyond a power of two, the first odd ranks fold
 * their operands into their left neighbours; a reduce-scatter by recursive
 * halving among the pof2 remaining ranks; then a binomial gather of the
 * blocks to the root (through new rank 0 when the root was folded away).
 * For predefined operations and count >= pof2.  Cost 2 lg p alpha +
 * 2 n (p-1)/p beta + n (p-1)/p gamma. */
void coll_reduce_scatter_gather(coll_sched *s, const void *sbuf, void *rbuf, int count, int root) {
  const coll_cg *g = coll_sched_group(s);
  size_t ts = coll_sched_red(s)->tsize;
  int size = g->size, rank = g->rank, pof2 = coll_pof2(size), rem = size - pof2, newrank;
  size_t n = (size_t)count * ts;
  char *work = coll_sched_mem(s, n), *tmp = coll_sched_mem(s, n);
  int *cnts = coll_sched_mem(s, 2 * (size_t)pof2 * sizeof *cnts), *disps = cnts + pof2;
  int send_idx = 0, last_idx = 0, newroot;
  coll_sched_copy(s, work, sbuf ? sbuf : rbuf, n);
  if (rank < 2 * rem) {
    if (rank % 2) {
      coll_sched_send(s, work, n, rank - 1);
      newrank = -1;
    } else {
      coll_sched_recv(s, tmp, n, rank + 1);
      coll_sched_reduce(s, tmp, work, count);
      newrank = rank / 2;
    }
  } else {
    newrank = rank - rem;
  }
  blocks(count, pof2, cnts, disps);
  if (newrank != -1) rsag_scatter(s, work, tmp, newrank, pof2, rem, 0, cnts, disps, &send_idx, &last_idx);
  /* The gather to the root. */
  if (root < 2 * rem) {
    if (root % 2) {
      if (rank == root) {
        coll_sched_recv(s, work, (size_t)cnts[0] * ts, 0);
        newrank = 0;
        send_idx = 0;
        last_idx = 2;
      } else if (newrank == 0) {
        coll_sched_send(s, work, (size_t)cnts[0] * ts, root);
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
      gather_step(cnts, pof2, mask, newrank < newdst, send_idx, &last_idx, &recv_idx, &send_cnt, &recv_cnt);
      if (newdst_tree_root == newroot_tree_root) {
        coll_sched_send(s, work + (size_t)disps[send_idx] * ts, (size_t)send_cnt * ts, dst);
        break;
      }
      coll_sched_recv(s, work + (size_t)disps[recv_idx] * ts, (size_t)recv_cnt * ts, dst);
      if (newrank > newdst) send_idx = recv_idx;
    }
  }
  if (rank == root) coll_sched_copy(s, rbuf, work, n);
}

/* ==== allreduce =========================================================== */

/* A linear reduce to rank 0, then a linear broadcast. */
void coll_allreduce_linear(coll_sched *s, void *buf, int count) {
  const coll_cg *g = coll_sched_group(s);
  coll_reduce_linear(s, g->rank ? buf : NULL, buf, count, 0);
  coll_bcast_linear(s, buf, (size_t)count * coll_sched_red(s)->tsize, 0);
}

/* Fold the first 2 rem ranks pairwise into the odd ones (even sends to
 * rank + 1, which combines even op odd); the new rank, -1 for the even
 * ones. */
static int fold_into_odd(coll_sched *s, char *buf, char *tmp, int count, int rem) {
  int rank = coll_sched_group(s)->rank;
  size_t n = (size_t)count * coll_sched_red(s)->tsize;
  if (rank >= 2 * rem) return rank - rem;
  if (rank % 2 == 0) {
    coll_sched_send(s, buf, n, rank + 1);
    return -1;
  }
  coll_sched_recv(s, tmp, n, rank - 1);
  coll_sched_reduce(s, tmp, buf, count);
  return rank / 2;
}

/* ... and at the end the odd ones send the result back. */
static void unfold(coll_sched *s, char *buf, size_t n, int rem) {
  int rank = coll_sched_group(s)->rank;
  if (rank >= 2 * rem) return;
  if (rank % 2)
    coll_sched_send(s, buf, n, rank - 1);
  else
    coll_sched_recv(s, buf, n, rank + 1);
}

/* Recursive doubling: beyond a power of two the first ranks fold pairwise;
 * among the pof2 others, in step k every rank exchanges its whole partial
 * result with new rank ^ 2^k and combines (received op ours when op
 * commutes or the partner is lower, else ours op received); the folded
 * ranks get the result back.  Cost lg p (alpha + n beta + n gamma). */
void coll_allreduce_recursive_doubling(coll_sched *s, void *buffer, int count) {
  const coll_cg *g = coll_sched_group(s);
  const coll_red *r = coll_sched_red(s);
  int size = g->size, rank = g->rank, pof2 = coll_pof2(size), rem = size - pof2;
  size_t n = (size_t)count * r->tsize;
  char *buf = buffer, *tmp = coll_sched_mem(s, n);
  int newrank = fold_into_odd(s, buf, tmp, count, rem);
  if (newrank != -1) {
    for (int mask = 1; mask < pof2; mask <<= 1) {
      int newdst = newrank ^ mask, dst = newdst < rem ? newdst * 2 + 1 : newdst + rem;
      coll_sched_sendrecv(s, buf, n, dst, tmp, n, dst);
      if (r->commute || dst < rank) {
        coll_sched_reduce(s, tmp, buf, count);
      } else {
        coll_sched_reduce(s, buf, tmp, count);
        coll_sched_copy(s, buf, tmp, n);
      }
    }
  }
  unfold(s, buf, n, rem);
}

/* Rabenseifner's allreduce: the fold, a reduce-scatter by recursive
 * halving (partners at distance 1, 2, 4, ...), an allgather by recursive
 * doubling back, the unfold.  For predefined operations and count >= pof2.
 * Cost 2 lg p alpha + 2 n (p-1)/p beta + n (p-1)/p gamma. */
void coll_allreduce_reduce_scatter_allgather(coll_sched *s, void *buffer, int count) {
  const coll_cg *g = coll_sched_group(s);
  size_t ts = coll_sched_red(s)->tsize;
  int size = g->size, pof2 = coll_pof2(size), rem = size - pof2;
  size_t n = (size_t)count * ts;
  char *buf = buffer, *tmp = coll_sched_mem(s, n);
  int *cnts = coll_sched_mem(s, 2 * (size_t)pof2 * sizeof *cnts), *disps = cnts + pof2, send_idx, last_idx;
  int newrank = fold_into_odd(s, buf, tmp, count, rem);
  if (newrank != -1) {
    blocks(count, pof2, cnts, disps);
    rsag_scatter(s, buf, tmp, newrank, pof2, rem, 1, cnts, disps, &send_idx, &last_idx);
    for (int mask = pof2 >> 1; mask > 0; mask >>= 1) {
      int newdst = newrank ^ mask, dst = newdst < rem ? newdst * 2 + 1 : newdst + rem, recv_idx, send_cnt, recv_cnt;
      gather_step(cnts, pof2, mask, newrank < newdst, send_idx, &last_idx, &recv_idx, &send_cnt, &recv_cnt);
      coll_sched_sendrecv(s, buf + (size_t)disps[send_idx] * ts, (size_t)send_cnt * ts, dst,
                          buf + (size_t)disps[recv_idx] * ts, (size_t)recv_cnt * ts, dst);
      if (newrank > newdst) send_idx = recv_idx;
    }
  }
  unfold(s, buf, n, rem);
}
