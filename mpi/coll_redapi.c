/* coll_redapi.c -- the MPI reductions: MPI_Reduce, MPI_Allreduce, MPI_Reduce_scatter,
 * MPI_Reduce_scatter_block, MPI_Scan, MPI_Exscan (mpi.h).  As coll_api.c: check, pack, pick
 * (the run's setting, else MPICH's rule, cited), run (coll.h), unpack.  An algorithm the
 * setting names that cannot run a call (Rabenseifner's for a user operation or fewer elements
 * than ranks, a commutative-only one for a non-commutative operation) gives way to MPICH's
 * choice, as MPICH's own checks would refuse it. */
#include <stdlib.h>
#include <string.h>

#include "coll.h"
#include "coll_inter.h"
#include "dtype.h"
#include "op.h"
#include "p2p.h"

/* The reduction's description for the algorithms. */
static tsmpi_red red_of(MPI_Datatype dt, MPI_Op op) {
  tsmpi_red r = {dt, op, tsmpi_type_size(dt), tsmpi_op_commutative(op)};
  return r;
}

/* count, datatype, op, and sendbuf (MPI_IN_PLACE allowed when in_place_ok). */
static int red_ok(MPI_Comm comm, const char *fn, const void *sendbuf, int count, MPI_Datatype dt, MPI_Op op,
                  int in_place_ok) {
  int rc;
  if ((rc = tsmpi_coll_data_ok(comm, fn, "datatype", sendbuf, count, dt)) || (rc = tsmpi_coll_op_ok(comm, fn, op, dt)))
    return rc;
  if (sendbuf == MPI_IN_PLACE && !in_place_ok) return tsmpi_coll_in_place_bad(comm, fn, "sendbuf on this rank");
  return MPI_SUCCESS;
}

/* ==== reduce and allreduce ================================================ */

int PMPI_Reduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, int root,
               MPI_Comm comm) {
  static const char fn[] = "MPI_Reduce";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_reduce(sendbuf, recvbuf, count, datatype, op, root, comm);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = tsmpi_check_root(comm, fn, root))) return rc;
  int me = tsmpi_comm_rank(comm);
  if ((rc = red_ok(comm, fn, sendbuf, count, datatype, op, me == root))) return rc;
  if (me == root) {
    if ((rc = tsmpi_check_buf(comm, fn, recvbuf, count, datatype))) return rc;
    if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  }
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_REDUCE, root);
  tsmpi_red r = red_of(datatype, op);
  size_t n = r.tsize * (size_t)count;
  if (n == 0) return tsmpi_coll_end(MPI_SUCCESS);
  char *in = tsmpi_coll_pack(&g, sendbuf == MPI_IN_PLACE ? recvbuf : sendbuf, count, datatype);
  char *out = me == root ? tsmpi_cg_alloc(&g, n) : NULL;
  int pof2 = tsmpi_pof2(g.size), rsg_ok = tsmpi_op_is_predefined(op) && count >= pof2;
  tsmpi_alg a = tsmpi_coll_setting(COLL_REDUCE);
  /* MPICH reduce.c: Rabenseifner's above MPIR_CVAR_REDUCE_SHORT_MSG_SIZE
   * (2048) bytes for predefined operations and count >= pof2, else the
   * binomial tree. */
  if (a == ALG_AUTO || (a == ALG_REDUCE_SCATTER_GATHER && !rsg_ok))
    a = n > 2048 && rsg_ok ? ALG_REDUCE_SCATTER_GATHER : ALG_BINOMIAL;
  if (g.size == 1) {
    memcpy(out, in, n);
    rc = MPI_SUCCESS;
  } else if (a == ALG_LINEAR) {
    rc = tsmpi_reduce_linear(&g, &r, in, out, count, root);
  } else if (a == ALG_REDUCE_SCATTER_GATHER) {
    rc = tsmpi_reduce_scatter_gather(&g, &r, in, out, count, root);
  } else {
    rc = tsmpi_reduce_binomial(&g, &r, in, out, count, root);
  }
  if (!rc && me == root) tsmpi_coll_unpack(out, recvbuf, count, datatype);
  tsmpi_cg_free(in);
  tsmpi_cg_free(out);
  return tsmpi_coll_end(rc);
}

int PMPI_Allreduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  static const char fn[] = "MPI_Allreduce";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_allreduce(sendbuf, recvbuf, count, datatype, op, comm);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = red_ok(comm, fn, sendbuf, count, datatype, op, 1)) ||
      (rc = tsmpi_check_buf(comm, fn, recvbuf, count, datatype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_ALLREDUCE, -1);
  tsmpi_red r = red_of(datatype, op);
  size_t n = r.tsize * (size_t)count;
  if (n == 0) return tsmpi_coll_end(MPI_SUCCESS);
  char *buf = tsmpi_coll_pack(&g, sendbuf == MPI_IN_PLACE ? recvbuf : sendbuf, count, datatype);
  int pof2 = tsmpi_pof2(g.size), rsag_ok = tsmpi_op_is_predefined(op) && count >= pof2;
  tsmpi_alg a = tsmpi_coll_setting(COLL_ALLREDUCE);
  /* MPICH allreduce.c: recursive doubling up to
   * MPIR_CVAR_ALLREDUCE_SHORT_MSG_SIZE (2048) bytes, for user operations
   * and for count < pof2; else Rabenseifner's. */
  if (a == ALG_AUTO || (a == ALG_REDUCE_SCATTER_ALLGATHER && !rsag_ok))
    a = n <= 2048 || !rsag_ok ? ALG_RECURSIVE_DOUBLING : ALG_REDUCE_SCATTER_ALLGATHER;
  if (g.size == 1) rc = MPI_SUCCESS;
  else if (a == ALG_LINEAR) rc = tsmpi_allreduce_linear(&g, &r, buf, count);
  else if (a == ALG_REDUCE_SCATTER_ALLGATHER) rc = tsmpi_allreduce_reduce_scatter_allgather(&g, &r, buf, count);
  else rc = tsmpi_allreduce_recursive_doubling(&g, &r, buf, count);
  if (!rc) tsmpi_coll_unpack(buf, recvbuf, count, datatype);
  tsmpi_cg_free(buf);
  return tsmpi_coll_end(rc);
}

/* ==== reduce-scatter ====================================================== */

/* The reduce-scatter of counts[] elements: MPICH reduce_scatter.c and
 * reduce_scatter_block.c: for commutative operations, recursive halving
 * below MPIR_CVAR_REDUCE_SCATTER_COMMUTATIVE_LONG_MSG_SIZE (524288) bytes in
 * all, else pairwise; for the others, Traff's butterfly on a power of two
 * ranks and equal blocks, else recursive doubling. */
static int redscat(const tsmpi_cg *g, tsmpi_coll c, const tsmpi_red *r, char *buf, char *out, const int *counts) {
  int size = g->size, regular = 1;
  size_t total = 0;
  for (int i = 0; i < size; i++) {
    total += (size_t)counts[i];
    if (counts[i] != counts[0]) regular = 0;
  }
  size_t n = total * r->tsize;
  tsmpi_alg a = tsmpi_coll_setting(c), mpich;
  if (r->commute) mpich = n < 524288 ? ALG_RECURSIVE_HALVING : ALG_PAIRWISE;
  else mpich = tsmpi_is_pof2(size) && regular ? ALG_NONCOMMUTATIVE : ALG_RECURSIVE_DOUBLING;
  if (a == ALG_AUTO || ((a == ALG_RECURSIVE_HALVING || a == ALG_PAIRWISE) && !r->commute) ||
      (a == ALG_NONCOMMUTATIVE && !(tsmpi_is_pof2(size) && regular)))
    a = mpich;
  if (size == 1) {
    memcpy(out, buf, n);
    return MPI_SUCCESS;
  }
  switch (a) {
  case ALG_LINEAR: return tsmpi_reduce_scatter_linear(g, r, buf, out, counts);
  case ALG_RECURSIVE_HALVING: return tsmpi_reduce_scatter_recursive_halving(g, r, buf, out, counts);
  case ALG_PAIRWISE: return tsmpi_reduce_scatter_pairwise(g, r, buf, out, counts);
  case ALG_NONCOMMUTATIVE: return tsmpi_reduce_scatter_noncommutative(g, r, buf, out, counts);
  default: return tsmpi_reduce_scatter_recursive_doubling(g, r, buf, out, counts);
  }
}

/* The common end of both: check, pack the whole operand, run, unpack this
 * rank's block (at the start of recvbuf, in place or not). */
static int redscat_call(const char *fn, tsmpi_coll c, const void *sendbuf, void *recvbuf, const int *counts,
                        MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  int me = tsmpi_comm_rank(comm), size = tsmpi_comm_size(comm), rc;
  long long total = 0;
  for (int i = 0; i < size; i++) total += counts[i];
  if (total > 0x7fffffff) return tsmpi_raise(comm, MPI_ERR_COUNT, fn, "%lld elements in all", total);
  if ((rc = red_ok(comm, fn, sendbuf, (int)total, datatype, op, 1)) ||
      (rc = tsmpi_check_buf(comm, fn, recvbuf, sendbuf == MPI_IN_PLACE ? (int)total : counts[me], datatype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, c, -1);
  tsmpi_red r = red_of(datatype, op);
  if (total == 0 || r.tsize == 0) return tsmpi_coll_end(MPI_SUCCESS);
  char *buf = tsmpi_coll_pack(&g, sendbuf == MPI_IN_PLACE ? recvbuf : sendbuf, (int)total, datatype);
  char *out = tsmpi_cg_alloc(&g, (size_t)counts[me] * r.tsize);
  rc = redscat(&g, c, &r, buf, out, counts);
  if (!rc) tsmpi_coll_unpack(out, recvbuf, counts[me], datatype);
  tsmpi_cg_free(buf);
  tsmpi_cg_free(out);
  return tsmpi_coll_end(rc);
}

int PMPI_Reduce_scatter(const void *sendbuf, void *recvbuf, const int recvcounts[], MPI_Datatype datatype, MPI_Op op,
                       MPI_Comm comm) {
  static const char fn[] = "MPI_Reduce_scatter";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_reduce_scatter(sendbuf, recvbuf, recvcounts, datatype, op, comm);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) ||
      (rc = tsmpi_coll_counts_ok(comm, fn, "recvcounts", recvcounts, NULL, tsmpi_comm_size(comm))))
    return rc;
  return redscat_call(fn, COLL_REDUCE_SCATTER, sendbuf, recvbuf, recvcounts, datatype, op, comm);
}

int PMPI_Reduce_scatter_block(const void *sendbuf, void *recvbuf, int recvcount, MPI_Datatype datatype, MPI_Op op,
                             MPI_Comm comm) {
  static const char fn[] = "MPI_Reduce_scatter_block";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_reduce_scatter_block(sendbuf, recvbuf, recvcount, datatype, op, comm);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = tsmpi_check_count(comm, fn, recvcount))) return rc;
  int size = tsmpi_comm_size(comm);
  tsmpi_cg g = {comm, 0, size, 0, fn};
  int *counts = tsmpi_cg_alloc(&g, (size_t)size * sizeof *counts);
  for (int i = 0; i < size; i++) counts[i] = recvcount;
  rc = redscat_call(fn, COLL_REDUCE_SCATTER_BLOCK, sendbuf, recvbuf, counts, datatype, op, comm);
  tsmpi_cg_free(counts);
  return rc;
}

/* ==== scan and exscan ===================================================== */

static int scan_call(const char *fn, tsmpi_coll c, const void *sendbuf, void *recvbuf, int count,
                     MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_none(comm, fn);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = red_ok(comm, fn, sendbuf, count, datatype, op, 1)) ||
      (rc = tsmpi_check_buf(comm, fn, recvbuf, count, datatype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, c, -1);
  tsmpi_red r = red_of(datatype, op);
  size_t n = r.tsize * (size_t)count;
  if (n == 0) return tsmpi_coll_end(MPI_SUCCESS);
  char *in = tsmpi_coll_pack(&g, sendbuf == MPI_IN_PLACE ? recvbuf : sendbuf, count, datatype);
  char *out = tsmpi_cg_alloc(&g, n);
  int incl = c == COLL_SCAN;
  /* MPICH scan.c and exscan.c: recursive doubling. */
  if (g.size == 1) {
    memcpy(out, in, n);
    rc = MPI_SUCCESS;
  } else if (tsmpi_coll_setting(c) == ALG_LINEAR) {
    rc = incl ? tsmpi_scan_linear(&g, &r, in, out, count) : tsmpi_exscan_linear(&g, &r, in, out, count);
  } else {
    rc = incl ? tsmpi_scan_recursive_doubling(&g, &r, in, out, count)
              : tsmpi_exscan_recursive_doubling(&g, &r, in, out, count);
  }
  /* MPI_Exscan leaves rank 0's recvbuf alone. */
  if (!rc && (incl || g.rank != 0)) tsmpi_coll_unpack(out, recvbuf, count, datatype);
  tsmpi_cg_free(in);
  tsmpi_cg_free(out);
  return tsmpi_coll_end(rc);
}

int PMPI_Scan(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  return scan_call("MPI_Scan", COLL_SCAN, sendbuf, recvbuf, count, datatype, op, comm);
}

int PMPI_Exscan(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  return scan_call("MPI_Exscan", COLL_EXSCAN, sendbuf, recvbuf, count, datatype, op, comm);
}
