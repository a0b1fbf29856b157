/* coll_redapi.c -- the MPI reductions MPI_Reduce, MPI_Allreduce, MPI_Reduce_scatter,
 * MPI_Reduce_scatter_block, MPI_Scan, MPI_Exscan and their nonblocking forms MPI_Ireduce,
 * MPI_Iallreduce, MPI_Ireduce_scatter, MPI_Ireduce_scatter_block, MPI_Iscan, MPI_Iexscan
 * (mpi.h).  As coll_api.c: one body per pair; check, start, pack, pick (the run's setting,
 * else MPICH's rule, cited), build, unpack at the end, finish.  An algorithm the setting names
 * that cannot run a call (Rabenseifner's for a user operation or fewer elements than ranks, a
 * commutative-only one for a non-commutative operation) gives way to MPICH's choice, as
 * MPICH's own checks would refuse it.  A nonblocking reduction combines in the order its
 * blocking form does (doc/mpi-support.md), so both give the same bits. */
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/coll_inter.h"
#include "mpi/dtype.h"
#include "mpi/op.h"
#include "mpi/core.h"
#include "mpi/coll_sched.h"

/* The reduction's description for the algorithms. */
static coll_red red_of(MPI_Datatype dt, MPI_Op op) {
  coll_red r = {dt, op, dtype_size(dt), op_commutative(op)};
  return r;
}

/* count, datatype, op, and sendbuf (MPI_IN_PLACE allowed when in_place_ok). */
static int red_ok(MPI_Comm comm, const char *fn, const void *sendbuf, int count, MPI_Datatype dt, MPI_Op op,
                  int in_place_ok) {
  int rc;
  if ((rc = coll_data_ok(comm, fn, "datatype", sendbuf, count, dt)) || (rc = coll_op_ok(comm, fn, op, dt)))
    return rc;
  if (sendbuf == MPI_IN_PLACE && !in_place_ok) return coll_in_place_bad(comm, fn, "sendbuf on this rank");
  return MPI_SUCCESS;
}

/* A nonblocking form's own first checks: the communicator and the request. */
static int nb_ok(MPI_Comm comm, const char *fn, MPI_Request *req) {
  int rc = comm_check(comm, fn);
  return rc ? rc : coll_req_ok(comm, fn, req);
}

/* ==== reduce and allreduce ================================================ */

static int reduce(const char *fn, const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op,
                  int root, MPI_Comm comm, MPI_Request *req) {
  int rc;
  if ((rc = err_comm_check_root(comm, fn, root))) return rc;
  int me = comm_rank(comm);
  if ((rc = red_ok(comm, fn, sendbuf, count, datatype, op, me == root))) return rc;
  if (me == root) {
    if ((rc = err_comm_check_buf(comm, fn, recvbuf, count, datatype))) return rc;
    if (recvbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
  }
  coll_sched *s = coll_start(fn, comm, COLL_REDUCE, root, req);
  coll_red r = red_of(datatype, op);
  coll_sched_set_red(s, &r);
  int size = coll_sched_group(s)->size;
  size_t n = r.tsize * (size_t)count;
  if (n == 0) return coll_finish(s);
  char *in = coll_pack(s, sendbuf == MPI_IN_PLACE ? recvbuf : sendbuf, count, datatype);
  char *out = me == root ? coll_place(s, recvbuf, count, datatype, 0) : NULL;
  int pof2 = coll_pof2(size), rsg_ok = op_is_predefined(op) && count >= pof2;
  coll_alg a = coll_setting(COLL_REDUCE);
  /* MPICH reduce.c: Rabenseifner's above MPIR_CVAR_REDUCE_SHORT_MSG_SIZE
   * (2048) bytes for predefined operations and count >= pof2, else the
   * binomial tree. */
  if (a == ALG_AUTO || (a == ALG_REDUCE_SCATTER_GATHER && !rsg_ok))
    a = n > 2048 && rsg_ok ? ALG_REDUCE_SCATTER_GATHER : ALG_BINOMIAL;
  if (size == 1)
    coll_sched_copy(s, out, in, n);
  else if (a == ALG_LINEAR)
    coll_reduce_linear(s, in, out, count, root);
  else if (a == ALG_REDUCE_SCATTER_GATHER)
    coll_reduce_scatter_gather(s, in, out, count, root);
  else
    coll_reduce_binomial(s, in, out, count, root);
  if (me == root) coll_sched_unpack(s, out, n, recvbuf, count, datatype);
  return coll_finish(s);
}

int PMPI_Reduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, int root,
               MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_reduce(sendbuf, recvbuf, count, datatype, op, root, comm);
  int rc = comm_check(comm, "MPI_Reduce");
  return rc ? rc : reduce("MPI_Reduce", sendbuf, recvbuf, count, datatype, op, root, comm, NULL);
}

int PMPI_Ireduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, int root,
                MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Ireduce", comm, coll_inter_reduce(sendbuf, recvbuf, count, datatype, op, root, comm), request);
  int rc = nb_ok(comm, "MPI_Ireduce", request);
  return rc ? rc : reduce("MPI_Ireduce", sendbuf, recvbuf, count, datatype, op, root, comm, request);
}

static int allreduce(const char *fn, const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op,
                     MPI_Comm comm, MPI_Request *req) {
  int rc;
  if ((rc = red_ok(comm, fn, sendbuf, count, datatype, op, 1)) ||
      (rc = err_comm_check_buf(comm, fn, recvbuf, count, datatype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
  coll_sched *s = coll_start(fn, comm, COLL_ALLREDUCE, -1, req);
  coll_red r = red_of(datatype, op);
  coll_sched_set_red(s, &r);
  int size = coll_sched_group(s)->size;
  size_t n = r.tsize * (size_t)count;
  if (n == 0) return coll_finish(s);
  /* MPICH's way: sendbuf copied into recvbuf, reduced there (when contiguous) */
  char *buf = coll_place(s, recvbuf, count, datatype, sendbuf == MPI_IN_PLACE);
  if (sendbuf != MPI_IN_PLACE) dtype_pack(sendbuf, count, datatype, buf);
  int pof2 = coll_pof2(size), rsag_ok = op_is_predefined(op) && count >= pof2;
  coll_alg a = coll_setting(COLL_ALLREDUCE);
  /* MPICH allreduce.c: recursive doubling up to
   * MPIR_CVAR_ALLREDUCE_SHORT_MSG_SIZE (2048) bytes, for user operations
   * and for count < pof2; else Rabenseifner's. */
  if (a == ALG_AUTO || (a == ALG_REDUCE_SCATTER_ALLGATHER && !rsag_ok))
    a = n <= 2048 || !rsag_ok ? ALG_RECURSIVE_DOUBLING : ALG_REDUCE_SCATTER_ALLGATHER;
  if (size == 1)
    ;
  else if (a == ALG_LINEAR)
    coll_allreduce_linear(s, buf, count);
  else if (a == ALG_REDUCE_SCATTER_ALLGATHER)
    coll_allreduce_reduce_scatter_allgather(s, buf, count);
  else
    coll_allreduce_recursive_doubling(s, buf, count);
  coll_sched_unpack(s, buf, n, recvbuf, count, datatype);
  return coll_finish(s);
}

int PMPI_Allreduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_allreduce(sendbuf, recvbuf, count, datatype, op, comm);
  int rc = comm_check(comm, "MPI_Allreduce");
  return rc ? rc : allreduce("MPI_Allreduce", sendbuf, recvbuf, count, datatype, op, comm, NULL);
}

int PMPI_Iallreduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm,
                   MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Iallreduce", comm, coll_inter_allreduce(sendbuf, recvbuf, count, datatype, op, comm), request);
  int rc = nb_ok(comm, "MPI_Iallreduce", request);
  return rc ? rc : allreduce("MPI_Iallreduce", sendbuf, recvbuf, count, datatype, op, comm, request);
}

/* ==== reduce-scatter ====================================================== */

/* The reduce-scatter of counts[] elements: MPICH reduce_scatter.c and
 * reduce_scatter_block.c: for commutative operations, recursive halving
 * below MPIR_CVAR_REDUCE_SCATTER_COMMUTATIVE_LONG_MSG_SIZE (524288) bytes in
 * all, else pairwise; for the others, Traff's butterfly on a power of two
 * ranks and equal blocks, else recursive doubling. */
static void redscat_build(coll_sched *s, coll_id c, char *buf, char *out, const int *counts) {
  const coll_red *r = coll_sched_red(s);
  int size = coll_sched_group(s)->size, regular = 1;
  size_t total = 0;
  for (int i = 0; i < size; i++) {
    total += (size_t)counts[i];
    if (counts[i] != counts[0]) regular = 0;
  }
  size_t n = total * r->tsize;
  coll_alg a = coll_setting(c), mpich;
  if (r->commute) mpich = n < 524288 ? ALG_RECURSIVE_HALVING : ALG_PAIRWISE;
  else mpich = coll_is_pof2(size) && regular ? ALG_NONCOMMUTATIVE : ALG_RECURSIVE_DOUBLING;
  if (a == ALG_AUTO || ((a == ALG_RECURSIVE_HALVING || a == ALG_PAIRWISE) && !r->commute) ||
      (a == ALG_NONCOMMUTATIVE && !(coll_is_pof2(size) && regular)))
    a = mpich;
  if (size == 1) {
    coll_sched_copy(s, out, buf, n);
    return;
  }
  switch (a) {
  case ALG_LINEAR: coll_reduce_scatter_linear(s, buf, out, counts); break;
  case ALG_RECURSIVE_HALVING: coll_reduce_scatter_recursive_halving(s, buf, out, counts); break;
  case ALG_PAIRWISE: coll_reduce_scatter_pairwise(s, buf, out, counts); break;
  case ALG_NONCOMMUTATIVE: coll_reduce_scatter_noncommutative(s, buf, out, counts); break;
  default: coll_reduce_scatter_recursive_doubling(s, buf, out, counts); break;
  }
}

/* The common body of both: check, pack the whole operand, build, unpack
 * this rank's block (at the start of recvbuf, in place or not).  counts:
 * the blocks' counts (NULL: recvcount each). */
static int redscat(const char *fn, coll_id c, const void *sendbuf, void *recvbuf, const int *counts,
                   int recvcount, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm, MPI_Request *req) {
  int me = comm_rank(comm), size = comm_size(comm), rc;
  long long total = 0;
  for (int i = 0; i < size; i++) total += counts ? counts[i] : recvcount;
  if (total > 0x7fffffff) return err_comm_raise(comm, MPI_ERR_COUNT, fn, "%lld elements in all", total);
  int mine = counts ? counts[me] : recvcount;
  if ((rc = red_ok(comm, fn, sendbuf, (int)total, datatype, op, 1)) ||
      (rc = err_comm_check_buf(comm, fn, recvbuf, sendbuf == MPI_IN_PLACE ? (int)total : mine, datatype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
  coll_sched *s = coll_start(fn, comm, c, -1, req);
  coll_red r = red_of(datatype, op);
  coll_sched_set_red(s, &r);
  if (total == 0 || r.tsize == 0) return coll_finish(s);
  int *cnt = coll_sched_mem(s, (size_t)size * sizeof *cnt);
  for (int i = 0; i < size; i++) cnt[i] = counts ? counts[i] : recvcount;
  char *buf = coll_pack(s, sendbuf == MPI_IN_PLACE ? recvbuf : sendbuf, (int)total, datatype);
  char *out = coll_place(s, recvbuf, mine, datatype, 0);   /* buf is a copy even in place */
  redscat_build(s, c, buf, out, cnt);
  coll_sched_unpack(s, out, (size_t)mine * r.tsize, recvbuf, mine, datatype);
  return coll_finish(s);
}

int PMPI_Reduce_scatter(const void *sendbuf, void *recvbuf, const int recvcounts[], MPI_Datatype datatype, MPI_Op op,
                       MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_reduce_scatter(sendbuf, recvbuf, recvcounts, datatype, op, comm);
  static const char fn[] = "MPI_Reduce_scatter";
  int rc;
  if ((rc = comm_check(comm, fn)) ||
      (rc = coll_counts_ok(comm, fn, "recvcounts", recvcounts, NULL, comm_size(comm))))
    return rc;
  return redscat(fn, COLL_REDUCE_SCATTER, sendbuf, recvbuf, recvcounts, 0, datatype, op, comm, NULL);
}

int PMPI_Ireduce_scatter(const void *sendbuf, void *recvbuf, const int recvcounts[], MPI_Datatype datatype,
                        MPI_Op op, MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Ireduce_scatter", comm, coll_inter_reduce_scatter(sendbuf, recvbuf, recvcounts, datatype, op, comm), request);
  static const char fn[] = "MPI_Ireduce_scatter";
  int rc;
  if ((rc = nb_ok(comm, fn, request)) ||
      (rc = coll_counts_ok(comm, fn, "recvcounts", recvcounts, NULL, comm_size(comm))))
    return rc;
  return redscat(fn, COLL_REDUCE_SCATTER, sendbuf, recvbuf, recvcounts, 0, datatype, op, comm, request);
}

int PMPI_Reduce_scatter_block(const void *sendbuf, void *recvbuf, int recvcount, MPI_Datatype datatype, MPI_Op op,
                             MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_reduce_scatter_block(sendbuf, recvbuf, recvcount, datatype, op, comm);
  static const char fn[] = "MPI_Reduce_scatter_block";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = err_comm_check_count(comm, fn, recvcount))) return rc;
  return redscat(fn, COLL_REDUCE_SCATTER_BLOCK, sendbuf, recvbuf, NULL, recvcount, datatype, op, comm, NULL);
}

int PMPI_Ireduce_scatter_block(const void *sendbuf, void *recvbuf, int recvcount, MPI_Datatype datatype, MPI_Op op,
                              MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Ireduce_scatter_block", comm, coll_inter_reduce_scatter_block(sendbuf, recvbuf, recvcount, datatype, op, comm), request);
  static const char fn[] = "MPI_Ireduce_scatter_block";
  int rc;
  if ((rc = nb_ok(comm, fn, request)) || (rc = err_comm_check_count(comm, fn, recvcount))) return rc;
  return redscat(fn, COLL_REDUCE_SCATTER_BLOCK, sendbuf, recvbuf, NULL, recvcount, datatype, op, comm, request);
}

/* ==== scan and exscan ===================================================== */

static int scan(const char *fn, coll_id c, const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype,
                MPI_Op op, MPI_Comm comm, MPI_Request *req) {
  int rc;
  if ((rc = red_ok(comm, fn, sendbuf, count, datatype, op, 1)) ||
      (rc = err_comm_check_buf(comm, fn, recvbuf, count, datatype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
  coll_sched *s = coll_start(fn, comm, c, -1, req);
  const coll_cg *g = coll_sched_group(s);
  coll_red r = red_of(datatype, op);
  coll_sched_set_red(s, &r);
  size_t n = r.tsize * (size_t)count;
  if (n == 0) return coll_finish(s);
  int incl = c == COLL_SCAN;
  char *in = coll_pack(s, sendbuf == MPI_IN_PLACE ? recvbuf : sendbuf, count, datatype);
  /* The result in recvbuf itself where contiguous (in is a copy even in
   * place), but for MPI_Exscan's rank 0, whose recvbuf is left alone. */
  char *out = incl || g->rank != 0 ? coll_place(s, recvbuf, count, datatype, 0) : coll_sched_mem(s, n);
  /* MPICH scan.c and exscan.c: recursive doubling. */
  if (g->size == 1)
    coll_sched_copy(s, out, in, n);
  else if (coll_setting(c) == ALG_LINEAR)
    (incl ? coll_scan_linear : coll_exscan_linear)(s, in, out, count);
  else
    (incl ? coll_scan_recursive_doubling : coll_exscan_recursive_doubling)(s, in, out, count);
  /* MPI_Exscan leaves rank 0's recvbuf alone. */
  if (incl || g->rank != 0) coll_sched_unpack(s, out, n, recvbuf, count, datatype);
  return coll_finish(s);
}

int PMPI_Scan(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_none(comm, "MPI_Scan");
  int rc = comm_check(comm, "MPI_Scan");
  return rc ? rc : scan("MPI_Scan", COLL_SCAN, sendbuf, recvbuf, count, datatype, op, comm, NULL);
}

int PMPI_Iscan(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm,
              MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Iscan", comm, coll_inter_none(comm, "MPI_Iscan"), request);
  int rc = nb_ok(comm, "MPI_Iscan", request);
  return rc ? rc : scan("MPI_Iscan", COLL_SCAN, sendbuf, recvbuf, count, datatype, op, comm, request);
}

int PMPI_Exscan(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_none(comm, "MPI_Exscan");
  int rc = comm_check(comm, "MPI_Exscan");
  return rc ? rc : scan("MPI_Exscan", COLL_EXSCAN, sendbuf, recvbuf, count, datatype, op, comm, NULL);
}

int PMPI_Iexscan(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, MPI_Comm comm,
                MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Iexscan", comm, coll_inter_none(comm, "MPI_Iexscan"), request);
  int rc = nb_ok(comm, "MPI_Iexscan", request);
  return rc ? rc : scan("MPI_Iexscan", COLL_EXSCAN, sendbuf, recvbuf, count, datatype, op, comm, request);
}
