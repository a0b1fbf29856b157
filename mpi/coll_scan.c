/* coll_scan.c -- scan, exscan and reduce-scatter algorithms (coll.h).
 *
 * Sources: MPICH (pmodels/mpich), src/mpi/coll/scan/scan_intra_recursive_doubling.c,
 * exscan/exscan_intra_recursive_doubling.c, reduce_scatter/reduce_scatter_intra_*.c
 * (reduce_scatter_block's are the same with equal counts); the linear ones pass a running
 * result along the ranks, or reduce to rank 0 and scatter, as Open MPI's coll/basic. */
#include <stdlib.h>
#include <string.h>

#include "coll.h"

/* ==== scan and exscan ===================================================== */

/* Rank r receives ranks 0..r-1's result from r - 1, combines it with its
 * operand on the left, and passes the result on: ((a0 op a1) op a2) ...
 * exclusive: r passes on (prefix op a_r) and keeps the prefix. */
static int chain(const tsmpi_cg *g, const tsmpi_red *r, const void *in, void *out, int count, int inclusive) {
  size_t n = (size_t)count * r->tsize;
  int rank = g->rank, rc = MPI_SUCCESS;
  char *acc = tsmpi_cg_alloc(g, n);
  memcpy(acc, in, n);
  if (rank > 0) {
    char *prefix = tsmpi_cg_alloc(g, n);
    if ((rc = tsmpi_cg_recv(g, prefix, n, rank - 1, NULL)) == 0) {
      if (!inclusive) memcpy(out, prefix, n);
      tsmpi_red_apply(r, prefix, acc, count);
    }
    tsmpi_cg_free(prefix);
  }
  if (!rc && inclusive) memcpy(out, acc, n);
  if (!rc && rank + 1 < g->size) rc = tsmpi_cg_send(g, acc, n, rank + 1);
  tsmpi_cg_free(acc);
  return rc;
}

int tsmpi_scan_linear(const tsmpi_cg *g, const tsmpi_red *r, const void *in, void *out, int count) {
  return chain(g, r, in, out, count, 1);
}

int tsmpi_exscan_linear(const tsmpi_cg *g, const tsmpi_red *r, const void *in, void *out, int count) {
  return chain(g, r, in, out, count, 0);
}

/* Recursive doubling: in step k rank r exchanges its partial result (ranks
 * of its aligned block of 2^k) with r ^ 2^k; a result from below is
 * combined on the left of the partial and of the prefix so far.  Cost
 * lg p (alpha + n beta + n gamma). */
static int doubling(const tsmpi_cg *g, const tsmpi_red *r, const void *in, void *out, int count, int inclusive) {
  size_t n = (size_t)count * r->tsize;
  int size = g->size, rank = g->rank, rc = MPI_SUCCESS, have = inclusive;
  char *partial = tsmpi_cg_alloc(g, n), *tmp = tsmpi_cg_alloc(g, n);
  memcpy(partial, in, n);
  if (inclusive) memcpy(out, in, n);
  for (int mask = 1; mask < size; mask <<= 1) {
    int dst = rank ^ mask;
    if (dst >= size) continue;
    if ((rc = tsmpi_cg_sendrecv(g, partial, n, dst, tmp, n, dst, NULL))) break;
    if (rank > dst) {
      /* from below: prefix = received op prefix (exscan: the first one is
       * the prefix), partial = received op partial */
      if (!have) {
        memcpy(out, tmp, n);
        have = 1;
      } else {
        tsmpi_red_apply(r, tmp, out, count);
      }
      tsmpi_red_apply(r, tmp, partial, count);
    } else if (r->commute) {
      tsmpi_red_apply(r, tmp, partial, count);
    } else {
      tsmpi_red_apply(r, partial, tmp, count);
      memcpy(partial, tmp, n);
    }
  }
  tsmpi_cg_free(partial);
  tsmpi_cg_free(tmp);
  return rc;
}

int tsmpi_scan_recursive_doubling(const tsmpi_cg *g, const tsmpi_red *r, const void *in, void *out, int count) {
  return doubling(g, r, in, out, count, 1);
}

int tsmpi_exscan_recursive_doubling(const tsmpi_cg *g, const tsmpi_red *r, const void *in, void *out, int count) {
  return doubling(g, r, in, out, count, 0);
}

/* ==== reduce-scatter ====================================================== */

/* The displacements of the blocks in elements, and their total. */
static int displacements(const tsmpi_cg *g, const int *counts, int *disps) {
  int total = 0;
  for (int i = 0; i < g->size; i++) {
    disps[i] = total;
    total += counts[i];
  }
  return total;
}

/* A linear reduce of the whole vector to rank 0, then a linear scatterv. */
int tsmpi_reduce_scatter_linear(const tsmpi_cg *g, const tsmpi_red *r, void *buf, void *out, const int *counts) {
  int size = g->size;
  size_t *bc = tsmpi_cg_alloc(g, 2 * (size_t)size * sizeof *bc), *bd = bc + size, total = 0;
  for (int i = 0; i < size; i++) {
    bc[i] = (size_t)counts[i] * r->tsize;
    bd[i] = total;
    total += bc[i];
  }
  char *res = g->rank == 0 ? tsmpi_cg_alloc(g, total) : NULL;
  int rc = tsmpi_reduce_linear(g, r, buf, res, (int)(total / (r->tsize ? r->tsize : 1)), 0);
  if (!rc) rc = tsmpi_scatterv_linear(g, res, bc, bd, out, bc[g->rank], 0);
  tsmpi_cg_free(res);
  tsmpi_cg_free(bc);
  return rc;
}

/* Recursive halving (for commutative operations): beyond a power of two
 * the first even ranks fold into rank + 1 (even op odd); among the pof2
 * others, in step k (distance pof2 / 2^(k+1)) a rank sends the half of its
 * blocks its partner keeps and combines the half it keeps (received op
 * ours); the folded ranks get their block at the end.  Cost lg p alpha +
 * n (p-1)/p (beta + gamma). */
int tsmpi_reduce_scatter_recursive_halving(const tsmpi_cg *g, const tsmpi_red *r, void *buffer, void *out,
                                           const int *counts) {
  int size = g->size, rank = g->rank, pof2 = tsmpi_pof2(size), rem = size - pof2, newrank, rc = MPI_SUCCESS;
  size_t ts = r->tsize;
  int *disps = tsmpi_cg_alloc(g, (size_t)(size + 2 * pof2) * sizeof *disps), *newcnts = disps + size,
      *newdisps = newcnts + pof2;
  int total = displacements(g, counts, disps);
  char *res = buffer, *tmp = tsmpi_cg_alloc(g, (size_t)total * ts);
  if (rank < 2 * rem) {
    if (rank % 2 == 0) {
      if ((rc = tsmpi_cg_send(g, res, (size_t)total * ts, rank + 1))) goto out;
      newrank = -1;
    } else {
      if ((rc = tsmpi_cg_recv(g, tmp, (size_t)total * ts, rank - 1, NULL))) goto out;
      tsmpi_red_apply(r, tmp, res, total);
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
      if (send_cnt && recv_cnt)
        rc = tsmpi_cg_sendrecv(g, sp, (size_t)send_cnt * ts, dst, rp, (size_t)recv_cnt * ts, dst, NULL);
      else if (recv_cnt)
        rc = tsmpi_cg_recv(g, rp, (size_t)recv_cnt * ts, dst, NULL);
      else if (send_cnt)
        rc = tsmpi_cg_send(g, sp, (size_t)send_cnt * ts, dst);
      if (rc) goto out;
      if (recv_cnt) tsmpi_red_apply(r, rp, res + (size_t)newdisps[recv_idx] * ts, recv_cnt);
      send_idx = recv_idx;
      last_idx = recv_idx + mask;
    }
    if (counts[rank]) memcpy(out, res + (size_t)disps[rank] * ts, (size_t)counts[rank] * ts);
  }
  if (rank < 2 * rem) {
    if (rank % 2) {
      if (counts[rank - 1])
        rc = tsmpi_cg_send(g, res + (size_t)disps[rank - 1] * ts, (size_t)counts[rank - 1] * ts, rank - 1);
    } else if (counts[rank]) {
      rc = tsmpi_cg_recv(g, out, (size_t)counts[rank] * ts, rank + 1, NULL);
    }
  }
out:
  tsmpi_cg_free(disps);
  tsmpi_cg_free(tmp);
  return rc;
}

/* Pairwise (for commutative operations and long vectors): in step i rank
 * r sends rank r + i its block and receives its own block of rank r - i,
 * combining received op ours: a_{r-p+1} op (... op (a_{r-1} op a_r)).
 * Cost (p-1) alpha + n (p-1)/p (beta + gamma). */
int tsmpi_reduce_scatter_pairwise(const tsmpi_cg *g, const tsmpi_red *r, void *buffer, void *out,
                                  const int *counts) {
  int size = g->size, rank = g->rank, rc = MPI_SUCCESS;
  size_t ts = r->tsize;
  int *disps = tsmpi_cg_alloc(g, (size_t)size * sizeof *disps);
  displacements(g, counts, disps);
  char *buf = buffer, *tmp = tsmpi_cg_alloc(g, (size_t)counts[rank] * ts);
  memcpy(out, buf + (size_t)disps[rank] * ts, (size_t)counts[rank] * ts);
  for (int i = 1; i < size && !rc; i++) {
    int src = (rank - i + size) % size, dst = (rank + i) % size;
    rc = tsmpi_cg_sendrecv(g, buf + (size_t)disps[dst] * ts, (size_t)counts[dst] * ts, dst, tmp,
                           (size_t)counts[rank] * ts, src, NULL);
    if (!rc) tsmpi_red_apply(r, tmp, out, counts[rank]);
  }
  tsmpi_cg_free(disps);
  tsmpi_cg_free(tmp);
  return rc;
}

/* Recursive doubling (non-commutative operations, any p and counts): in
 * step k rank r exchanges with r ^ 2^k everything but the blocks of its
 * own and its partner's subtrees, combining in rank order; beyond a power
 * of two, ranks without a partner get their subtree's result from one that
 * had (MPICH).  Cost lg p alpha + n (lg p - (p-1)/p)(beta + gamma). */
int tsmpi_reduce_scatter_recursive_doubling(const tsmpi_cg *g, const tsmpi_red *r, void *buffer, void *out,
                                            const int *counts) {
  int size = g->size, rank = g->rank, rc = MPI_SUCCESS;
  size_t ts = r->tsize;
  int *disps = tsmpi_cg_alloc(g, (size_t)size * sizeof *disps);
  int total = displacements(g, counts, disps);
  char *res = buffer, *tmp = tsmpi_cg_alloc(g, (size_t)total * ts), *sp = tsmpi_cg_alloc(g, (size_t)total * ts),
       *rp = tsmpi_cg_alloc(g, (size_t)total * ts);
  for (int mask = 1, i = 0; mask < size && !rc; mask <<= 1, i++) {
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
    if (dst < size) {
      memcpy(sp, res, (size_t)sb0 * ts);
      memcpy(sp + (size_t)sb0 * ts, res + (size_t)sd1 * ts, (size_t)sb1 * ts);
      if ((rc = tsmpi_cg_sendrecv(g, sp, slen, dst, rp, rlen, dst, NULL))) break;
      memcpy(tmp, rp, (size_t)rb0 * ts);
      memcpy(tmp + (size_t)rd1 * ts, rp + (size_t)rb0 * ts, (size_t)rb1 * ts);
      received = 1;
    }
    if (dst_root + mask > size) {
      int done = size - my_root - mask, k = 0;
      for (int j = mask; j; j >>= 1) k++;
      k--;
      for (int tmask = mask >> 1; tmask && !rc; tmask >>= 1, k--) {
        int d = rank ^ tmask, tree_root = rank >> k << k;
        if (d > rank && rank < tree_root + done && d >= tree_root + done) {
          /* send the current result (tmp, the received type's runs) */
          memcpy(rp, tmp, (size_t)rb0 * ts);
          memcpy(rp + (size_t)rb0 * ts, tmp + (size_t)rd1 * ts, (size_t)rb1 * ts);
          rc = tsmpi_cg_send(g, rp, rlen, d);
        } else if (d < rank && d < tree_root + done && rank >= tree_root + done) {
          if ((rc = tsmpi_cg_recv(g, rp, rlen, d, NULL))) break;
          memcpy(tmp, rp, (size_t)rb0 * ts);
          memcpy(tmp + (size_t)rd1 * ts, rp + (size_t)rb0 * ts, (size_t)rb1 * ts);
          received = 1;
        }
      }
    }
    if (rc || !received) continue;
    if (r->commute || dst_root < my_root) {
      tsmpi_red_apply(r, tmp, res, rb0);
      tsmpi_red_apply(r, tmp + (size_t)rd1 * ts, res + (size_t)rd1 * ts, rb1);
    } else {
      tsmpi_red_apply(r, res, tmp, rb0);
      tsmpi_red_apply(r, res + (size_t)rd1 * ts, tmp + (size_t)rd1 * ts, rb1);
      memcpy(res, tmp, (size_t)rb0 * ts);
      memcpy(res + (size_t)rd1 * ts, tmp + (size_t)rd1 * ts, (size_t)rb1 * ts);
    }
  }
  if (!rc && counts[rank]) memcpy(out, res + (size_t)disps[rank] * ts, (size_t)counts[rank] * ts);
  tsmpi_cg_free(disps);
  tsmpi_cg_free(tmp);
  tsmpi_cg_free(sp);
  tsmpi_cg_free(rp);
  return rc;
}

/* The mirror permutation of lg-bit numbers: bits reversed. */
static int mirror(int x, int bits) {
  int y = 0;
  for (int b = 0; b < bits; b++)
    if (x & (1 << b)) y |= 1 << (bits - 1 - b);
  return y;
}

/* Traff's butterfly ("An improved algorithm for (non-commutative)
 * reduce-scatter", EuroPVM/MPI 2005), for p a power of two and equal
 * blocks: the blocks permuted by bit reversal, then lg p steps that halve
 * the data, combining in rank order. */
int tsmpi_reduce_scatter_noncommutative(const tsmpi_cg *g, const tsmpi_red *r, void *buffer, void *out,
                                        const int *counts) {
  int size = g->size, rank = g->rank, lg = 0, rc = MPI_SUCCESS;
  while ((1 << lg) < size) lg++;
  size_t ts = r->tsize, block = (size_t)counts[0], total = block * (size_t)size;
  char *b0 = tsmpi_cg_alloc(g, total * ts), *b1 = tsmpi_cg_alloc(g, total * ts), *in = buffer;
  for (int i = 0; i < size; i++) memcpy(b0 + (size_t)mirror(i, lg) * block * ts, in + (size_t)i * block * ts, block * ts);
  int buf0_inout = 1;
  size_t soff = 0, roff = 0, len = total;
  for (int k = 0; k < lg && !rc; k++) {
    char *incoming = buf0_inout ? b1 : b0, *outgoing = buf0_inout ? b0 : b1;
    int peer = rank ^ (1 << k);
    len /= 2;
    if (rank > peer) roff += len;
    else soff += len;
    if ((rc = tsmpi_cg_sendrecv(g, outgoing + soff * ts, len * ts, peer, incoming + roff * ts, len * ts, peer, NULL)))
      break;
    if (rank > peer) {
      tsmpi_red_apply(r, incoming + roff * ts, outgoing + roff * ts, (int)len);
    } else {
      tsmpi_red_apply(r, outgoing + roff * ts, incoming + roff * ts, (int)len);
      buf0_inout = !buf0_inout;
    }
    soff = roff;
  }
  if (!rc && block) memcpy(out, (buf0_inout ? b0 : b1) + roff * ts, block * ts);
  tsmpi_cg_free(b0);
  tsmpi_cg_free(b1);
  return rc;
}
