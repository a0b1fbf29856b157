/* coll_api.c -- the MPI collectives MPI_Barrier, MPI_Bcast, MPI_Gather(v), MPI_Scatter(v) and
 * their nonblocking forms MPI_Ibarrier, MPI_Ibcast, MPI_Igather(v), MPI_Iscatter(v) (mpi.h).
 *
 * Each blocking and nonblocking pair shares one body: it checks the arguments (errors under
 * the communicator's handler), starts the call (coll.h: coll_start), packs its data
 * into contiguous bytes (dtype.h), picks the algorithm (the run's --coll setting, else
 * MPICH's choice: each rule below cites MPICH's selection, src/mpi/coll/<name>/<name>.c,
 * MPIR_<Name>_intra_auto, with its MPIR_CVAR thresholds' defaults; SimGrid's
 * src/smpi/colls/smpi_mpich_selector.cpp copies them with a few differences, which tilesim
 * does not follow: doc/mpi-support.md), builds its schedule, with the unpacking of the result
 * at its end, and finishes: the blocking call runs it, the nonblocking one starts it (nbc.h).
 * The nonblocking forms pick the algorithms the blocking ones do, so that they give the same
 * results, bit for bit. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/coll_inter.h"
#include "mpi/dtype.h"
#include "mp/mp.h"
#include "mpi/op.h"
#include "mpi/core.h"
#include "mpi/coll_sched.h"

/* ==== barrier and broadcast =============================================== */

static int barrier(const char *fn, MPI_Comm comm, MPI_Request *req) {
  coll_sched *s = coll_start(fn, comm, COLL_BARRIER, -1, req);
  /* MPICH: MPIR_Barrier_intra_auto runs the dissemination barrier. */
  if (coll_sched_group(s)->size > 1) {
    if (coll_setting(COLL_BARRIER) == ALG_LINEAR)
      coll_barrier_linear(s);
    else
      coll_barrier_dissemination(s);
  }
  return coll_finish(s);
}

int PMPI_Barrier(MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_barrier(comm);
  int rc = comm_check(comm, "MPI_Barrier");
  return rc ? rc : barrier("MPI_Barrier", comm, NULL);
}

int PMPI_Ibarrier(MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Ibarrier", comm, coll_inter_barrier(comm), request);
  static const char fn[] = "MPI_Ibarrier";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  return barrier(fn, comm, request);
}

static int bcast(const char *fn, void *buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm,
                 MPI_Request *req) {
  int rc;
  if ((rc = err_comm_check_root(comm, fn, root)) ||
      (rc = coll_data_ok(comm, fn, "datatype", buffer, count, datatype)))
    return rc;
  if (buffer == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "buffer");
  size_t n = dtype_size(datatype) * (size_t)count;
  coll_sched *s = coll_start(fn, comm, COLL_BCAST, root, req);
  const coll_cg *g = coll_sched_group(s);
  if (n == 0 || g->size == 1) return coll_finish(s);
  char *p = coll_place(s, buffer, count, datatype, g->rank == root);   /* in place when contiguous */
  coll_alg a = coll_setting(COLL_BCAST);
  if (a == ALG_AUTO) {
    /* MPICH bcast.c: binomial below MPIR_CVAR_BCAST_SHORT_MSG_SIZE (12288)
     * bytes or MPIR_CVAR_BCAST_MIN_PROCS (8) ranks; else scatter and
     * recursive-doubling allgather below MPIR_CVAR_BCAST_LONG_MSG_SIZE
     * (524288) on a power of two ranks; else scatter and ring allgather. */
    if (n < 12288 || g->size < 8) a = ALG_BINOMIAL;
    else if (n < 524288 && coll_is_pof2(g->size)) a = ALG_SCATTER_RECURSIVE_DOUBLING_ALLGATHER;
    else a = ALG_SCATTER_RING_ALLGATHER;
  }
  switch (a) {
  case ALG_LINEAR: coll_bcast_linear(s, p, n, root); break;
  case ALG_SCATTER_RECURSIVE_DOUBLING_ALLGATHER: coll_bcast_scatter_rdb_allgather(s, p, n, root); break;
  case ALG_SCATTER_RING_ALLGATHER: coll_bcast_scatter_ring_allgather(s, p, n, root); break;
  default: coll_bcast_binomial(s, p, n, root); break;
  }
  if (g->rank != root) coll_sched_unpack(s, p, n, buffer, count, datatype);
  return coll_finish(s);
}

int PMPI_Bcast(void *buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_bcast(buffer, count, datatype, root, comm);
  int rc = comm_check(comm, "MPI_Bcast");
  return rc ? rc : bcast("MPI_Bcast", buffer, count, datatype, root, comm, NULL);
}

int PMPI_Ibcast(void *buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Ibcast", comm, coll_inter_bcast(buffer, count, datatype, root, comm), request);
  static const char fn[] = "MPI_Ibcast";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  return bcast(fn, buffer, count, datatype, root, comm, request);
}

/* ==== gather and scatter ================================================== */

static int gather(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                  int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm, MPI_Request *req) {
  int rc;
  if ((rc = err_comm_check_root(comm, fn, root))) return rc;
  int me = comm_rank(comm), size = comm_size(comm), in_place = sendbuf == MPI_IN_PLACE;
  if (in_place && me != root) return coll_in_place_bad(comm, fn, "sendbuf on a rank other than the root");
  if (!in_place && (rc = coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  if (me == root) {
    if ((rc = coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype))) return rc;
    if (recvbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
  }
  size_t n = me == root ? dtype_size(recvtype) * (size_t)recvcount : dtype_size(sendtype) * (size_t)sendcount;
  if (me == root && !in_place && dtype_size(sendtype) * (size_t)sendcount != n)
    return err_comm_raise(comm, MPI_ERR_TRUNCATE, fn, "the root sends %zu bytes to itself and receives %zu",
                          dtype_size(sendtype) * (size_t)sendcount, n);
  coll_sched *s = coll_start(fn, comm, COLL_GATHER, root, req);
  const char *mine = in_place
                         ? coll_pack(s, coll_at(recvbuf, (MPI_Aint)root * recvcount, recvtype), recvcount, recvtype)
                         : coll_view(s, sendbuf, sendcount, sendtype);
  char *all = me == root ? coll_place(s, recvbuf, recvcount * size, recvtype, 0) : NULL;
  /* MPICH gather.c: the binomial tree always. */
  if (coll_setting(COLL_GATHER) == ALG_LINEAR)
    coll_gather_linear(s, mine, all, n, root);
  else
    coll_gather_binomial(s, mine, all, n, root);
  if (me == root)
    for (int r = 0; r < size; r++)
      coll_sched_unpack(s, all + (size_t)r * n, n, coll_at(recvbuf, (MPI_Aint)r * recvcount, recvtype),
                        recvcount, recvtype);
  return coll_finish(s);
}

int PMPI_Gather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
               MPI_Datatype recvtype, int root, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_gather(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm);
  int rc = comm_check(comm, "MPI_Gather");
  return rc ? rc : gather("MPI_Gather", sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm, NULL);
}

int PMPI_Igather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                MPI_Datatype recvtype, int root, MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Igather", comm, coll_inter_gather(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm), request);
  static const char fn[] = "MPI_Igather";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  return gather(fn, sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm, request);
}

/* The byte counts and offsets of a v collective's blocks (packed in rank
 * order), in the schedule's memory: counts[i] elements of unit bytes. */
static size_t *byte_blocks(coll_sched *s, const int *counts, size_t unit, size_t *total) {
  int size = coll_sched_group(s)->size;
  size_t *bc = coll_sched_mem(s, 2 * (size_t)size * sizeof *bc), t = 0;
  for (int i = 0; i < size; i++) {
    bc[i] = (size_t)counts[i] * unit;
    bc[size + i] = t;
    t += bc[i];
  }
  if (total) *total = t;
  return bc;
}

static int gatherv(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                   const int recvcounts[], const int displs[], MPI_Datatype recvtype, int root, MPI_Comm comm,
                   MPI_Request *req) {
  int rc;
  if ((rc = err_comm_check_root(comm, fn, root))) return rc;
  int me = comm_rank(comm), size = comm_size(comm), in_place = sendbuf == MPI_IN_PLACE;
  if (in_place && me != root) return coll_in_place_bad(comm, fn, "sendbuf on a rank other than the root");
  if (!in_place && (rc = coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  if (me == root) {
    if ((rc = coll_counts_ok(comm, fn, "recvcounts", recvcounts, displs, size)) ||
        (rc = coll_type_ok(comm, fn, "recvtype", recvtype)))
      return rc;
    if (recvbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
    size_t own = (size_t)recvcounts[root] * dtype_size(recvtype);
    if (!in_place && dtype_size(sendtype) * (size_t)sendcount != own)
      return err_comm_raise(comm, MPI_ERR_TRUNCATE, fn, "the root sends %zu bytes to itself and receives %zu",
                            dtype_size(sendtype) * (size_t)sendcount, own);
  }
  coll_sched *s = coll_start(fn, comm, COLL_GATHERV, root, req);
  size_t *bc = NULL, *bd = NULL, total = 0;
  if (me == root) {
    bc = byte_blocks(s, recvcounts, dtype_size(recvtype), &total);
    bd = bc + size;
  }
  char *mine = in_place ? coll_pack(s, coll_at(recvbuf, displs[root], recvtype), recvcounts[root], recvtype)
                        : coll_pack(s, sendbuf, sendcount, sendtype);
  size_t sn = in_place ? bc[root] : dtype_size(sendtype) * (size_t)sendcount;
  char *all = NULL;
  if (me == root && !(all = coll_vdirect(recvbuf, recvcounts, displs, NULL, recvtype, size, bc, bd)))
    all = coll_sched_mem(s, total);   /* blocks with gaps: received packed, unpacked at the end */
  /* MPICH gatherv.c: the linear algorithm always. */
  coll_gatherv_linear(s, mine, sn, all, bc, bd, root);
  if (me == root)
    for (int r = 0; r < size; r++)
      coll_sched_unpack(s, all + bd[r], bc[r], coll_at(recvbuf, displs[r], recvtype), recvcounts[r], recvtype);
  return coll_finish(s);
}

int PMPI_Gatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, const int recvcounts[],
                const int displs[], MPI_Datatype recvtype, int root, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_gatherv(sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, root, comm);
  int rc = comm_check(comm, "MPI_Gatherv");
  return rc ? rc
            : gatherv("MPI_Gatherv", sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, root, comm,
                      NULL);
}

int PMPI_Igatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, const int recvcounts[],
                 const int displs[], MPI_Datatype recvtype, int root, MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Igatherv", comm, coll_inter_gatherv(sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, root, comm), request);
  static const char fn[] = "MPI_Igatherv";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  return gatherv(fn, sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, root, comm, request);
}

static int scatter(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                   int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm, MPI_Request *req) {
  int rc;
  if ((rc = err_comm_check_root(comm, fn, root))) return rc;
  int me = comm_rank(comm), size = comm_size(comm), in_place = recvbuf == MPI_IN_PLACE;
  if (in_place && me != root) return coll_in_place_bad(comm, fn, "recvbuf on a rank other than the root");
  if (!in_place && (rc = coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype))) return rc;
  if (me == root) {
    if ((rc = coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
    if (sendbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "sendbuf");
  }
  size_t n = me == root ? dtype_size(sendtype) * (size_t)sendcount : dtype_size(recvtype) * (size_t)recvcount;
  if (me == root && !in_place && dtype_size(recvtype) * (size_t)recvcount < n)
    return err_comm_raise(comm, MPI_ERR_TRUNCATE, fn, "the root sends %zu bytes to itself and receives at most %zu", n,
                          dtype_size(recvtype) * (size_t)recvcount);
  coll_sched *s = coll_start(fn, comm, COLL_SCATTER, root, req);
  const char *all = me == root ? coll_view(s, sendbuf, sendcount * size, sendtype) : NULL;
  char *mine = in_place ? NULL : coll_place(s, recvbuf, recvcount, recvtype, 0);
  /* MPICH scatter.c: the binomial tree always. */
  if (coll_setting(COLL_SCATTER) == ALG_LINEAR)
    coll_scatter_linear(s, all, mine, n, root);
  else
    coll_scatter_binomial(s, all, mine, n, root);
  if (!in_place) coll_sched_unpack(s, mine, n, recvbuf, recvcount, recvtype);
  return coll_finish(s);
}

int PMPI_Scatter(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                MPI_Datatype recvtype, int root, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_scatter(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm);
  int rc = comm_check(comm, "MPI_Scatter");
  return rc ? rc : scatter("MPI_Scatter", sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm, NULL);
}

int PMPI_Iscatter(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                 MPI_Datatype recvtype, int root, MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Iscatter", comm, coll_inter_scatter(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm), request);
  static const char fn[] = "MPI_Iscatter";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  return scatter(fn, sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm, request);
}

static int scatterv(const char *fn, const void *sendbuf, const int sendcounts[], const int displs[],
                    MPI_Datatype sendtype, void *recvbuf, int recvcount, MPI_Datatype recvtype, int root,
                    MPI_Comm comm, MPI_Request *req) {
  int rc;
  if ((rc = err_comm_check_root(comm, fn, root))) return rc;
  int me = comm_rank(comm), size = comm_size(comm), in_place = recvbuf == MPI_IN_PLACE;
  if (in_place && me != root) return coll_in_place_bad(comm, fn, "recvbuf on a rank other than the root");
  if (!in_place && (rc = coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype))) return rc;
  size_t rn = in_place ? 0 : dtype_size(recvtype) * (size_t)recvcount;
  if (me == root) {
    if ((rc = coll_counts_ok(comm, fn, "sendcounts", sendcounts, displs, size)) ||
        (rc = coll_type_ok(comm, fn, "sendtype", sendtype)))
      return rc;
    if (sendbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "sendbuf");
    size_t own = (size_t)sendcounts[root] * dtype_size(sendtype);
    if (!in_place && own > rn)
      return err_comm_raise(comm, MPI_ERR_TRUNCATE, fn, "the root sends %zu bytes to itself and receives at most %zu",
                            own, rn);
    if (!in_place) rn = own;
  }
  coll_sched *s = coll_start(fn, comm, COLL_SCATTERV, root, req);
  size_t *bc = NULL, *bd = NULL, total = 0;
  char *all = NULL;
  if (me == root) {
    MPI_Aint ss = dtype_size(sendtype);
    bc = byte_blocks(s, sendcounts, (size_t)ss, &total);
    bd = bc + size;
    if (!(all = coll_vdirect(sendbuf, sendcounts, displs, NULL, sendtype, size, bc, bd))) {   /* else packed */
      all = coll_sched_mem(s, total);
      for (int i = 0; i < size; i++)
        if (bc[i]) dtype_pack(coll_at(sendbuf, displs[i], sendtype), sendcounts[i], sendtype, all + bd[i]);
    }
  }
  char *mine = in_place ? NULL : coll_place(s, recvbuf, recvcount, recvtype, 0);
  /* MPICH scatterv.c: the linear algorithm always. */
  coll_scatterv_linear(s, all, bc, bd, mine, rn, root);
  if (!in_place) coll_sched_unpack(s, mine, rn, recvbuf, recvcount, recvtype);
  return coll_finish(s);
}

int PMPI_Scatterv(const void *sendbuf, const int sendcounts[], const int displs[], MPI_Datatype sendtype,
                 void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_scatterv(sendbuf, sendcounts, displs, sendtype, recvbuf, recvcount, recvtype, root, comm);
  int rc = comm_check(comm, "MPI_Scatterv");
  return rc ? rc
            : scatterv("MPI_Scatterv", sendbuf, sendcounts, displs, sendtype, recvbuf, recvcount, recvtype, root, comm,
                       NULL);
}

int PMPI_Iscatterv(const void *sendbuf, const int sendcounts[], const int displs[], MPI_Datatype sendtype,
                  void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm,
                  MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Iscatterv", comm, coll_inter_scatterv(sendbuf, sendcounts, displs, sendtype, recvbuf, recvcount, recvtype, root, comm), request);
  static const char fn[] = "MPI_Iscatterv";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  return scatterv(fn, sendbuf, sendcounts, displs, sendtype, recvbuf, recvcount, recvtype, root, comm, request);
}
