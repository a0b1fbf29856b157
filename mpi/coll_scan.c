/* coll_scan.c -- scan, exscan and reduce-scatter algorithms (coll.h).
 *
 * Sources: MPICH (pmodels/mpich), src/mpi/coll/scan/scan_intra_recursive_doubling.c,
 * exscan/exscan_intra_recursive_doubling.c, reduce_scatter/reduce_scatter_intra_*.c
 * (reduce_scatter_block's are the same with equal counts); the linear ones pass a running
 * result along the ranks, or reduce to rank 0 and scatter, as Open MPI's coll/basic. */
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/coll_sched.h"

/* ==== scan and exscan ===================================================== */

/* Rank r receives ranks 0..r-1's result from r - 1, combines it with its
 * operand on the left, and passes the result on: ((a0 op a1) op a2) ...
 * exclusive: r passes on (prefix op a_r) and keeps the prefix. */
static void chain(coll_sched *s, const void *in, void *out, int count, int inclusive) {
  const coll_cg *g = coll_sched_group(s);
  size_t n = (size_t)count * coll_sched_red(s)->tsize;
  int rank = g->rank;
  char *acc = coll_sched_mem(s, n);
  coll_sched_copy(s, acc, in, n);
  if (rank > 0) {
    char *prefix = coll_sched_mem(s, n);
    coll_sched_recv(s, prefix, n, rank - 1);
    if (!inclusive) coll_sched_copy(s, out, prefix, n);
    coll_sched_reduce(s, prefix, acc, count);
  }
  if (inclusive) coll_sched_copy(s, out, acc, n);
  if (rank + 1 < g->size) coll_sched_send(s, acc, n, rank + 1);
}

void coll_scan_linear(coll_sched *s, const void *in, void *out, int count) { chain(s, in, out, count, 1); }
void coll_exscan_linear(coll_sched *s, const void *in, void *out, int count) { chain(s, in, out, count, 0); }

/* Recursive doubling: in step k rank r exchanges its partial result (ranks
 * of its aligned block of 2^k) with r ^ 2^k; a result from below is
 * combined on the left of the partial and of the prefix so far.  Cost
 * lg p (alpha + n beta + n gamma). */
static void doubling(coll_sched *s, const void *in, void *out, int count, int inclusive) {
  const coll_cg *g = coll_sched_group(s);
  const coll_red *r = coll_sched_red(s);
  size_t n = (size_t)count * r->tsize;
  int size = g->size, rank = g->rank, have = inclusive;
  char *partial = coll_sched_mem(s, n), *tmp = coll_sched_mem(s, n);
  coll_sched_copy(s, partial, in, n);
  if (inclusive) coll_sched_copy(s, out, in, n);
  for (int mask = 1; mask < size; mask <<= 1) {
    int dst = rank ^ mask;
    if (dst >= size) continue;
    coll_sched_sendrecv(s, partial, n, dst, tmp, n, dst);
    if (rank > dst) {
      /* from below: prefix = received op prefix (exscan: the first one is
       * the prefix), partial = received op partial */
      if (!have) {
        coll_sched_copy(s, out, tmp, n);
        have = 1;
      } else {
        coll_sched_reduce(s, tmp, out, count);
      }
      coll_sched_reduce(s, tmp, partial, count);
    } else if (r->commute) {
      coll_sched_reduce(s, tmp, partial, count);
    } else {
      coll_sched_reduce(s, partial, tmp, count);
      coll_sched_copy(s, partial, tmp, n);
    }
  }
}

void coll_scan_recursive_doubling(coll_sched *s, const void *in, void *out, int count) {
  doubling(s, in, out, count, 1);
}

void coll_exscan_recursive_doubling(coll_sched *s, const void *in, void *out, int count) {
  doubling(s, in, out, count, 0);
}

/* ==== reduce-scatter ====================================================== */

/* The displacements of the blocks in elements, and their total. */
static int displacements(const coll_cg *g, const int *counts, int *disps) {
  int total = 0;
  for (int i = 0; i < g->size; i++) {
    disps[i] = total;
    total += counts[i];
  }
  return total;
}

/* A linear reduce of the whole vector to rank 0, then a linear scatterv. */
void coll_reduce_scatter_linear(coll_sched *s, void *buf, void *out, const int *counts) {
  const coll_cg *g = coll_sched_group(s);
  size_t ts = coll_sched_red(s)->tsize;
  int size = g->size;
  size_t *bc = coll_sched_mem(s, 2 * (size_t)size * sizeof *bc), *bd = bc + size, total = 0;
  for (int i = 0; i < size; i++) {
    bc[i] = (size_t)counts[i] * ts;
    bd[i] = total;
    total += bc[i];
  }
  char *res = g->rank == 0 ? coll_sched_mem(s, total) : NULL;
  coll_reduce_linear(s, buf, res, (int)(total / (ts ? ts : 1)), 0);
  coll_scatterv_linear(s, res, bc, bd, out, bc[g->rank], 0);
}

/* Recursive halving (for commutative operations): beyond a power of two
 * the first even ranks fold into rank + 1 (even op odd); among the pof2
 * others, in step k (distance pof2 / 2^(k+1)) a rank sends the half of its
 * blocks its partner keeps and combines the half it keeps (received op
 * ours); the folded ranks get their block at the end.  Cost lg p alpha +
 * n (p-1)/p (beta + gamma). */
void coll_reduce_scatter_recursive_halving(coll_sched *s, void *buffer, void *out, const int *counts) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank, pof2 = coll_pof2(size), rem = size - pof2, newrank;
  size_t ts = coll_sched_red(s)->tsize;
  int *disps = coll_sched_mem(s, (size_t)(size + 2 * pof2) * sizeof *disps), *newcnts = disps + size,
      *newdisps = newcnts + pof2;
  int total = displacements(g, counts, disps);
  char *res = buffer, *tmp = coll_sched_mem(s, (size_t)total * ts);
  if (rank < 2 * rem) {
    if (rank % 2 == 0) {
      coll_sched_send(s, res, (size_t)total * ts, rank + 1);
      newrank = -1;
    } else {
      coll_sched_recv(s, tmp, (size_t)total * ts, rank - 1);
      coll_sched_reduce(s, tmp, res, total);
      newrank = rank / 2;
    }
  } else {
    newrank = rank - rem;
  }
  if (newrank != -1) {
    for (int i = 0; i < pof2; i++) {
      int old = i < rem ? i * 2 + 1 : i + rem;
      newcnts[i] = counts[old] + (old < 2 * rem ? counts[old - 1] : 0);
    }
    newdisps[0] = 0;
    for (int i = 1; i < pof2; i++) newdisps[i] = newdisps[i - 1] + newcnts[i - 1];
    int send_idx = 0, recv_idx = 0, last_idx = pof2;
    for (int mask = pof2 >> 1; mask > 0; mask >>= 1) {
      int newdst = newrank ^ mask, dst = newdst < rem ? newdst * 2 + 1 : newdst + rem, send_cnt = 0, recv_cnt = 0;
      if (newrank < newdst) {
        send_idx = recv_idx + mask;
        for (int i = send_idx; i < last_idx; i++) send_cnt += newcnts[i];
        for (int i = recv_idx; i < send_idx; i++) recv_cnt += newcnts[i];
      } else {
        recv_idx = send_idx + mask;
        for (int i = send_idx; i < recv_idx; i++) send_cnt += newcnts[i];
        for (int i = recv_idx; i < last_idx; i++) recv_cnt += newcnts[i];
      }
      char *sp = res + (size_t)newdisps[send_idx] * ts, *rp = tmp + (size_t)newdisps[recv_idx] * ts;
      if (send_cnt) coll_sched_send(s, sp, (size_t)send_cnt * ts, dst);
      if (recv_cnt) coll_sched_recv(s, rp, (size_t)recv_cnt * ts, dst);
      coll_sched_reduce(s, rp, res + (size_t)newdisps[recv_idx] * ts, recv_cnt);
      send_idx = recv_idx;
      last_idx = recv_idx + mask;
    }
    coll_sched_copy(s, out, res + (size_t)disps[rank] * ts, (size_t)counts[rank] * ts);
  }
  if (rank < 2 * rem) {
    if (rank % 2) {
      if (counts[rank - 1])
        coll_sched_send(s, res + (size_t)disps[rank - 1] * ts, (size_t)counts[rank - 1] * ts, rank - 1);
    } else if (counts[rank]) {
      coll_sched_recv(s, out, (size_t)counts[rank] * ts, rank + 1);
    }
  }
}

/* Pairwise (for commutative operations and long vectors): in step i rank
 * r sends rank r + i its block and receives its own block of rank r - i,
 * combining received op ours: a_{r-p+1} op (... op (a_{r-1} op a_r)).
 * Cost (p-1) alpha + n (p-1)/p (beta + gamma). */
void coll_reduce_scatter_pairwise(coll_sched *s, void *buffer, void *out, const int *counts) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank;
  size_t ts = coll_sched_red(s)->tsize;
  int *disps = coll_sched_mem(s, (size_t)size * sizeof *disps);
  displacements(g, counts, disps);
  char *buf = buffer, *tmp = coll_sched_mem(s, (size_t)counts[rank] * ts);
  coll_sched_copy(s, out, buf + (size_t)disps[rank] * ts, (size_t)counts[rank] * ts);
  for (int i = 1; i < size; i++) {
    int src = (rank - i + size) % size, dst = (rank + i) % size;
    coll_sched_sendrecv(s, buf + (size_t)disps[dst] * ts, (size_t)counts[dst] * ts, dst, tmp,
                        (size_t)counts[rank] * ts, src);
    coll_sched_reduce(s, tmp, out, counts[rank]);
  }
}

/* Recursive doubling's exchanges, local: all but the blocks of one subtree
 * (two runs, before and after it) out of res into a message, or back. */
typedef struct {
  char *res, *msg;
  size_t b0, b1, d1;   /* bytes of the first run, of the second, where the second starts */
  int out;
} rd_runs;

static void rd_move(void *ud) {
  const rd_runs *m = ud;
  if (m->out) {
    memcpy(m->msg, m->res, m->b0);
    memcpy(m->msg + m->b0, m->res + m->d1, m->b1);
  } else {
    memcpy(m->res, m->msg, m->b0);
    memcpy(m->res + m->d1, m->msg + m->b0, m->b1);
  }
}

static void runs(coll_sched *s, char *res, char *msg, size_t b0, size_t b1, size_t d1, int out) {
  rd_runs *m = coll_sched_mem(s, sizeof *m);
  *m = (rd_runs){res, msg, b0, b1, d1, out};
  coll_sched_call(s, rd_move, m);
}

/* Recursive doubling (non-commutative operations, any p and counts): in
 * step k rank r exchanges with r ^ 2^k everything but the blocks of its
 * own and its partner's subtrees, combining in rank order; beyond a power
 * of two, ranks without a partner get their subtree's result from one that
 * had (MPICH).  Cost lg p alpha + n (lg p - (p-1)/p)(beta + gamma). */
void coll_reduce_scatter_recursive_doubling(coll_sched *s, void *buffer, void *out, const int *counts) {
  const coll_cg *g = coll_sched_group(s);
  const coll_red *r = coll_sched_red(s);
  int size = g->size, rank = g->rank;
  size_t ts = r->tsize;
  int *disps = coll_sched_mem(s, (size_t)size * sizeof *disps);
  int total = displacements(g, counts, disps);
  char *res = buffer, *tmp = coll_sched_mem(s, (size_t)total * ts), *sp = coll_sched_mem(s, (size_t)total * ts),
       *rp = coll_sched_mem(s, (size_t)total * ts);
  for (int mask = 1, i = 0; mask < size; mask <<= 1, i++) {
    int dst = rank ^ mask, dst_root = dst >> i << i, my_root = rank >> i << i, received = 0;
    /* What is sent: all but my subtree's blocks; received: all but the
     * partner subtree's (two runs each: before and after the subtree). */
    int sb0 = 0, sb1 = 0, sd1, rb0 = 0, rb1 = 0, rd1;
    for (int j = 0; j < my_root; j++) sb0 += counts[j];
    for (int j = my_root + mask; j < size; j++) sb1 += counts[j];
    sd1 = sb0;
    for (int j = my_root; j < my_root + mask && j < size; j++) sd1 += counts[j];
    for (int j = 0; j < dst_root && j < size; j++) rb0 += counts[j];
    for (int j = dst_root + mask; j < size; j++) rb1 += counts[j];
    rd1 = rb0;
    for (int j = dst_root; j < dst_root + mask && j < size; j++) rd1 += counts[j];
    size_t slen = (size_t)(sb0 + sb1) * ts, rlen = (size_t)(rb0 + rb1) * ts;
    size_t rb0b = (size_t)rb0 * ts, rb1b = (size_t)rb1 * ts, rd1b = (size_t)rd1 * ts;
    if (dst < size) {
      runs(s, res, sp, (size_t)sb0 * ts, (size_t)sb1 * ts, (size_t)sd1 * ts, 1);
      coll_sched_sendrecv(s, sp, slen, dst, rp, rlen, dst);
      runs(s, tmp, rp, rb0b, rb1b, rd1b, 0);
      received = 1;
    }
    if (dst_root + mask > size) {
      int done = size - my_root - mask, k = 0;
      for (int j = mask; j; j >>= 1) k++;
      k--;
      for (int tmask = mask >> 1; tmask; tmask >>= 1, k--) {
        int d = rank ^ tmask, tree_root = rank >> k << k;
        if (d > rank && rank < tree_root + done && d >= tree_root + done) {
          /* send the current result (tmp, the received type's runs) */
          runs(s, tmp, rp, rb0b, rb1b, rd1b, 1);
          coll_sched_send(s, rp, rlen, d);
        } else if (d < rank && d < tree_root + done && rank >= tree_root + done) {
          coll_sched_recv(s, rp, rlen, d);
          runs(s, tmp, rp, rb0b, rb1b, rd1b, 0);
          received = 1;
        }
      }
    }
    if (!received) continue;
    if (r->commute || dst_root < my_root) {
      coll_sched_reduce(s, tmp, res, rb0);
      coll_sched_reduce(s, tmp + rd1b, res + rd1b, rb1);
    } else {
      coll_sched_reduce(s, res, tmp, rb0);
      coll_sched_reduce(s, res + rd1b, tmp + rd1b, rb1);
      coll_sched_copy(s, res, tmp, rb0b);
      coll_sched_copy(s, res + rd1b, tmp + rd1b, rb1b);
    }
  }
  coll_sched_copy(s, out, res + (size_t)disps[rank] * ts, (size_t)counts[rank] * ts);
}

/* The mirror permutation of lg-bit numbers: bits reversed. */
static int mirror(int x, int bits) {
  int y = 0;
  for (int b = 0; b < bits; b++)
    if (x & (1 << b)) y |= 1 << (bits - 1 - b);
  return y;
}

/* Traff's first step, local: the blocks permuted by bit reversal. */
typedef struct {
  char *to;
  const char *from;
  size_t block;
  int size, lg;
} permute;

static void mirror_blocks(void *ud) {
  const permute *m = ud;
  for (int i = 0; i < m->size; i++)
    memcpy(m->to + (size_t)mirror(i, m->lg) * m->block, m->from + (size_t)i * m->block, m->block);
}

/* Traff's butterfly ("An improved algorithm for (non-commutative)
 * reduce-scatter", EuroPVM/MPI 2005), for p a power of two and equal
 * blocks: the blocks permuted by bit reversal, then lg p steps that halve
 * the data, combining in rank order. */
void coll_reduce_scatter_noncommutative(coll_sched *s, void *buffer, void *out, const int *counts) {
  const coll_cg *g = coll_sched_group(s);
  int size = g->size, rank = g->rank, lg = 0;
  while ((1 << lg) < size) lg++;
  size_t ts = coll_sched_red(s)->tsize, block = (size_t)counts[0], total = block * (size_t)size;
  char *b0 = coll_sched_mem(s, total * ts), *b1 = coll_sched_mem(s, total * ts);
  permute *m = coll_sched_mem(s, sizeof *m);
  *m = (permute){b0, buffer, block * ts, size, lg};
  coll_sched_call(s, mirror_blocks, m);
  int buf0_inout = 1;
  size_t soff = 0, roff = 0, len = total;
  for (int k = 0; k < lg; k++) {
    char *incoming = buf0_inout ? b1 : b0, *outgoing = buf0_inout ? b0 : b1;
    int peer = rank ^ (1 << k);
    len /= 2;
    if (rank > peer) roff += len;
    else soff += len;
    coll_sched_sendrecv(s, outgoing + soff * ts, len * ts, peer, incoming + roff * ts, len * ts, peer);
    if (rank > peer) {
      coll_sched_reduce(s, incoming + roff * ts, outgoing + roff * ts, (int)len);
    } else {
      coll_sched_reduce(s, outgoing + roff * ts, incoming + roff * ts, (int)len);
      buf0_inout = !buf0_inout;
    }
    soff = roff;
  }
  coll_sched_copy(s, out, (buf0_inout ? b0 : b1) + roff * ts, block * ts);
}
