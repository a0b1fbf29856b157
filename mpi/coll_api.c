/* coll_api.c -- the MPI collectives: MPI_Barrier, MPI_Bcast, MPI_Reduce, MPI_Allreduce,
 * MPI_Gather(v), MPI_Scatter(v), MPI_Allgather(v), MPI_Alltoall(v), MPI_Scan, MPI_Exscan,
 * MPI_Reduce_scatter, MPI_Reduce_scatter_block (mpi.h).
 *
 * Each checks its arguments (errors under the communicator's handler), packs
 * its data into contiguous bytes (dtype.h), picks the algorithm (the run's
 * --coll setting, else MPICH's choice: each rule below cites MPICH's
 * selection, src/mpi/coll/<name>/<name>.c, MPIR_<Name>_intra_auto, with its
 * MPIR_CVAR thresholds' defaults; SimGrid's src/smpi/colls/
 * smpi_mpich_selector.cpp copies them with a few differences, which tilesim
 * does not follow: doc/mpi-support.md), runs it (coll.h) and
 * unpacks the result.  While it may block, the rank's label names the call
 * for a deadlock report: "MPI_Bcast(root=0, MPI_COMM_WORLD)". */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "coll.h"
#include "coll_inter.h"
#include "dtype.h"
#include "mp.h"
#include "op.h"
#include "p2p.h"

/* ==== barrier and broadcast =============================================== */

int PMPI_Barrier(MPI_Comm comm) {
  static const char fn[] = "MPI_Barrier";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_barrier(comm);
  int rc = tsmpi_comm_check(comm, fn);
  if (rc) return rc;
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_BARRIER, -1);
  if (g.size == 1) return tsmpi_coll_end(MPI_SUCCESS);
  /* MPICH: MPIR_Barrier_intra_auto runs the dissemination barrier. */
  rc = tsmpi_coll_setting(COLL_BARRIER) == ALG_LINEAR ? tsmpi_barrier_linear(&g) : tsmpi_barrier_dissemination(&g);
  return tsmpi_coll_end(rc);
}

int PMPI_Bcast(void *buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm) {
  static const char fn[] = "MPI_Bcast";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_bcast(buffer, count, datatype, root, comm);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = tsmpi_check_root(comm, fn, root)) ||
      (rc = tsmpi_coll_data_ok(comm, fn, "datatype", buffer, count, datatype)))
    return rc;
  if (buffer == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "buffer");
  size_t n = tsmpi_type_size(datatype) * (size_t)count;
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_BCAST, root);
  if (n == 0 || g.size == 1) return tsmpi_coll_end(MPI_SUCCESS);
  char *p = g.rank == root ? tsmpi_coll_pack(&g, buffer, count, datatype) : tsmpi_cg_alloc(&g, n);
  tsmpi_alg a = tsmpi_coll_setting(COLL_BCAST);
  if (a == ALG_AUTO) {
    /* MPICH bcast.c: binomial below MPIR_CVAR_BCAST_SHORT_MSG_SIZE (12288)
     * bytes or MPIR_CVAR_BCAST_MIN_PROCS (8) ranks; else scatter and
     * recursive-doubling allgather below MPIR_CVAR_BCAST_LONG_MSG_SIZE
     * (524288) on a power of two ranks; else scatter and ring allgather. */
    if (n < 12288 || g.size < 8) a = ALG_BINOMIAL;
    else if (n < 524288 && tsmpi_is_pof2(g.size)) a = ALG_SCATTER_RECURSIVE_DOUBLING_ALLGATHER;
    else a = ALG_SCATTER_RING_ALLGATHER;
  }
  switch (a) {
  case ALG_LINEAR: rc = tsmpi_bcast_linear(&g, p, n, root); break;
  case ALG_SCATTER_RECURSIVE_DOUBLING_ALLGATHER: rc = tsmpi_bcast_scatter_rdb_allgather(&g, p, n, root); break;
  case ALG_SCATTER_RING_ALLGATHER: rc = tsmpi_bcast_scatter_ring_allgather(&g, p, n, root); break;
  default: rc = tsmpi_bcast_binomial(&g, p, n, root); break;
  }
  if (!rc && g.rank != root) tsmpi_coll_unpack(p, buffer, count, datatype);
  tsmpi_cg_free(p);
  return tsmpi_coll_end(rc);
}

/* ==== gather and scatter ================================================== */

int PMPI_Gather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
               MPI_Datatype recvtype, int root, MPI_Comm comm) {
  static const char fn[] = "MPI_Gather";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_gather(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = tsmpi_check_root(comm, fn, root))) return rc;
  int me = tsmpi_comm_rank(comm), size = tsmpi_comm_size(comm), in_place = sendbuf == MPI_IN_PLACE;
  if (in_place && me != root) return tsmpi_coll_in_place_bad(comm, fn, "sendbuf on a rank other than the root");
  if (!in_place && (rc = tsmpi_coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  if (me == root) {
    if ((rc = tsmpi_coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype))) return rc;
    if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  }
  size_t n = me == root ? tsmpi_type_size(recvtype) * (size_t)recvcount : tsmpi_type_size(sendtype) * (size_t)sendcount;
  if (me == root && !in_place && tsmpi_type_size(sendtype) * (size_t)sendcount != n)
    return tsmpi_raise(comm, MPI_ERR_TRUNCATE, fn, "the root sends %zu bytes to itself and receives %zu",
                       tsmpi_type_size(sendtype) * (size_t)sendcount, n);
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_GATHER, root);
  char *mine = in_place ? tsmpi_coll_pack(&g, tsmpi_coll_at(recvbuf, (MPI_Aint)root * recvcount, recvtype), recvcount, recvtype)
                        : tsmpi_coll_pack(&g, sendbuf, sendcount, sendtype);
  char *all = me == root ? tsmpi_cg_alloc(&g, n * (size_t)size) : NULL;
  /* MPICH gather.c: the binomial tree always. */
  rc = tsmpi_coll_setting(COLL_GATHER) == ALG_LINEAR ? tsmpi_gather_linear(&g, mine, all, n, root)
                                          : tsmpi_gather_binomial(&g, mine, all, n, root);
  if (!rc && me == root)
    for (int r = 0; r < size; r++) tsmpi_coll_unpack(all + (size_t)r * n, tsmpi_coll_at(recvbuf, (MPI_Aint)r * recvcount, recvtype), recvcount, recvtype);
  tsmpi_cg_free(mine);
  tsmpi_cg_free(all);
  return tsmpi_coll_end(rc);
}

int PMPI_Gatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, const int recvcounts[],
                const int displs[], MPI_Datatype recvtype, int root, MPI_Comm comm) {
  static const char fn[] = "MPI_Gatherv";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_gatherv(sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, root, comm);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = tsmpi_check_root(comm, fn, root))) return rc;
  int me = tsmpi_comm_rank(comm), size = tsmpi_comm_size(comm), in_place = sendbuf == MPI_IN_PLACE;
  if (in_place && me != root) return tsmpi_coll_in_place_bad(comm, fn, "sendbuf on a rank other than the root");
  if (!in_place && (rc = tsmpi_coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  size_t *bc = NULL, *bd = NULL, total = 0;
  if (me == root) {
    if ((rc = tsmpi_coll_counts_ok(comm, fn, "recvcounts", recvcounts, displs, size)) || (rc = tsmpi_coll_type_ok(comm, fn, "recvtype", recvtype)))
      return rc;
    if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  }
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_GATHERV, root);
  if (me == root) {
    size_t rs = tsmpi_type_size(recvtype);
    bc = tsmpi_cg_alloc(&g, 2 * (size_t)size * sizeof *bc);
    bd = bc + size;
    for (int i = 0; i < size; i++) {
      bc[i] = (size_t)recvcounts[i] * rs;
      bd[i] = total;
      total += bc[i];
    }
    size_t own = bc[root];
    if (!in_place && tsmpi_type_size(sendtype) * (size_t)sendcount != own) {
      tsmpi_cg_free(bc);
      return tsmpi_coll_end(tsmpi_raise(comm, MPI_ERR_TRUNCATE, fn, "the root sends %zu bytes to itself and receives %zu",
                                        tsmpi_type_size(sendtype) * (size_t)sendcount, own));
    }
  }
  char *mine = in_place ? tsmpi_coll_pack(&g, tsmpi_coll_at(recvbuf, displs[root], recvtype), recvcounts[root], recvtype)
                        : tsmpi_coll_pack(&g, sendbuf, sendcount, sendtype);
  size_t sn = in_place ? bc[root] : tsmpi_type_size(sendtype) * (size_t)sendcount;
  char *all = me == root ? tsmpi_cg_alloc(&g, total) : NULL;
  /* MPICH gatherv.c: the linear algorithm always. */
  rc = tsmpi_gatherv_linear(&g, mine, sn, all, bc, bd, root);
  if (!rc && me == root)
    for (int r = 0; r < size; r++) tsmpi_coll_unpack(all + bd[r], tsmpi_coll_at(recvbuf, displs[r], recvtype), recvcounts[r], recvtype);
  tsmpi_cg_free(mine);
  tsmpi_cg_free(all);
  tsmpi_cg_free(bc);
  return tsmpi_coll_end(rc);
}

int PMPI_Scatter(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                MPI_Datatype recvtype, int root, MPI_Comm comm) {
  static const char fn[] = "MPI_Scatter";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_scatter(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = tsmpi_check_root(comm, fn, root))) return rc;
  int me = tsmpi_comm_rank(comm), size = tsmpi_comm_size(comm), in_place = recvbuf == MPI_IN_PLACE;
  if (in_place && me != root) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf on a rank other than the root");
  if (!in_place && (rc = tsmpi_coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype))) return rc;
  if (me == root) {
    if ((rc = tsmpi_coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
    if (sendbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "sendbuf");
  }
  size_t n = me == root ? tsmpi_type_size(sendtype) * (size_t)sendcount : tsmpi_type_size(recvtype) * (size_t)recvcount;
  if (me == root && !in_place && tsmpi_type_size(recvtype) * (size_t)recvcount < n)
    return tsmpi_raise(comm, MPI_ERR_TRUNCATE, fn, "the root sends %zu bytes to itself and receives at most %zu", n,
                       tsmpi_type_size(recvtype) * (size_t)recvcount);
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_SCATTER, root);
  char *all = me == root ? tsmpi_coll_pack(&g, sendbuf, sendcount * size, sendtype) : NULL;
  char *mine = in_place ? NULL : tsmpi_cg_alloc(&g, n);
  /* MPICH scatter.c: the binomial tree always. */
  rc = tsmpi_coll_setting(COLL_SCATTER) == ALG_LINEAR ? tsmpi_scatter_linear(&g, all, mine, n, root)
                                           : tsmpi_scatter_binomial(&g, all, mine, n, root);
  if (!rc && !in_place && n) tsmpi_type_unpack(mine, n, recvbuf, recvcount, recvtype);
  tsmpi_cg_free(mine);
  tsmpi_cg_free(all);
  return tsmpi_coll_end(rc);
}

int PMPI_Scatterv(const void *sendbuf, const int sendcounts[], const int displs[], MPI_Datatype sendtype,
                 void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm) {
  static const char fn[] = "MPI_Scatterv";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_scatterv(sendbuf, sendcounts, displs, sendtype, recvbuf, recvcount, recvtype, root, comm);
  int rc;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = tsmpi_check_root(comm, fn, root))) return rc;
  int me = tsmpi_comm_rank(comm), size = tsmpi_comm_size(comm), in_place = recvbuf == MPI_IN_PLACE;
  if (in_place && me != root) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf on a rank other than the root");
  if (!in_place && (rc = tsmpi_coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype))) return rc;
  if (me == root) {
    if ((rc = tsmpi_coll_counts_ok(comm, fn, "sendcounts", sendcounts, displs, size)) || (rc = tsmpi_coll_type_ok(comm, fn, "sendtype", sendtype)))
      return rc;
    if (sendbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "sendbuf");
  }
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_SCATTERV, root);
  size_t *bc = NULL, *bd = NULL, total = 0, rn = in_place ? 0 : tsmpi_type_size(recvtype) * (size_t)recvcount;
  char *all = NULL;
  if (me == root) {
    size_t ss = tsmpi_type_size(sendtype);
    bc = tsmpi_cg_alloc(&g, 2 * (size_t)size * sizeof *bc);
    bd = bc + size;
    for (int i = 0; i < size; i++) {
      bc[i] = (size_t)sendcounts[i] * ss;
      bd[i] = total;
      total += bc[i];
    }
    all = tsmpi_cg_alloc(&g, total);
    for (int i = 0; i < size; i++)
      if (bc[i]) tsmpi_type_pack(tsmpi_coll_at(sendbuf, displs[i], sendtype), sendcounts[i], sendtype, all + bd[i]);
    size_t own = bc[root];
    if (!in_place && own > rn) {
      tsmpi_cg_free(bc);
      tsmpi_cg_free(all);
      return tsmpi_coll_end(tsmpi_raise(comm, MPI_ERR_TRUNCATE, fn,
                                        "the root sends %zu bytes to itself and receives at most %zu", own, rn));
    }
    if (!in_place) rn = bc[root];
  }
  char *mine = in_place ? NULL : tsmpi_cg_alloc(&g, rn);
  /* MPICH scatterv.c: the linear algorithm always. */
  rc = tsmpi_scatterv_linear(&g, all, bc, bd, mine, rn, root);
  if (!rc && !in_place && rn) tsmpi_type_unpack(mine, rn, recvbuf, recvcount, recvtype);
  tsmpi_cg_free(mine);
  tsmpi_cg_free(all);
  tsmpi_cg_free(bc);
  return tsmpi_coll_end(rc);
}

/* ==== allgather =========================================================== */

/* The allgather algorithm for tot bytes on the group: MPICH allgather.c
 * and allgatherv.c: recursive doubling below MPIR_CVAR_ALLGATHER_LONG_MSG_SIZE
 * (524288) bytes on a power of two ranks, else Bruck below
 * MPIR_CVAR_ALLGATHER_SHORT_MSG_SIZE (81920), else the ring. */
static tsmpi_alg allgather_alg(tsmpi_coll c, const tsmpi_cg *g, size_t tot) {
  tsmpi_alg a = tsmpi_coll_setting(c);
  if (a != ALG_AUTO) return a;
  if (tot < 524288 && tsmpi_is_pof2(g->size)) return ALG_RECURSIVE_DOUBLING;
  return tot < 81920 ? ALG_BRUCKS : ALG_RING;
}

/* Every rank's block (at bd[r], bc[r] bytes of the packed buf) to every
 * rank; unit and extent: the receive type's, for the pipelined ring. */
static int allgather_run(const tsmpi_cg *g, tsmpi_alg a, char *buf, const size_t *bc, const size_t *bd, int v,
                         size_t unit, size_t extent) {
  switch (a) {
  case ALG_LINEAR: return tsmpi_allgatherv_linear(g, buf, bc, bd);
  case ALG_RECURSIVE_DOUBLING: return tsmpi_allgatherv_recursive_doubling(g, buf, bc, bd);
  case ALG_BRUCKS: return tsmpi_allgatherv_brucks(g, buf, bc, bd);
  default:
    return v ? tsmpi_allgatherv_ring_pipelined(g, buf, bc, bd, unit, extent) : tsmpi_allgatherv_ring(g, buf, bc, bd);
  }
}

int PMPI_Allgather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                  MPI_Datatype recvtype, MPI_Comm comm) {
  static const char fn[] = "MPI_Allgather";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_allgather(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm);
  int rc, in_place = sendbuf == MPI_IN_PLACE;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = tsmpi_coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  if (!in_place && (rc = tsmpi_coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  size_t n = tsmpi_type_size(recvtype) * (size_t)recvcount;
  if (!in_place && tsmpi_type_size(sendtype) * (size_t)sendcount != n)
    return tsmpi_raise(comm, MPI_ERR_TRUNCATE, fn, "this rank sends %zu bytes and receives %zu from each rank",
                       tsmpi_type_size(sendtype) * (size_t)sendcount, n);
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_ALLGATHER, -1);
  /* MPICH: nothing to do when nothing is sent or received. */
  if ((!in_place && sendcount == 0) || recvcount == 0) return tsmpi_coll_end(MPI_SUCCESS);
  int size = g.size;
  size_t *bc = tsmpi_cg_alloc(&g, 2 * (size_t)size * sizeof *bc), *bd = bc + size;
  for (int i = 0; i < size; i++) {
    bc[i] = n;
    bd[i] = (size_t)i * n;
  }
  char *all = tsmpi_cg_alloc(&g, n * (size_t)size);
  if (in_place)
    tsmpi_type_pack(tsmpi_coll_at(recvbuf, (MPI_Aint)g.rank * recvcount, recvtype), recvcount, recvtype, all + bd[g.rank]);
  else
    tsmpi_type_pack(sendbuf, sendcount, sendtype, all + bd[g.rank]);
  rc = size == 1 ? MPI_SUCCESS : allgather_run(&g, allgather_alg(COLL_ALLGATHER, &g, n * (size_t)size), all, bc, bd, 0, 0, 0);
  if (!rc)
    for (int r = 0; r < size; r++) tsmpi_coll_unpack(all + bd[r], tsmpi_coll_at(recvbuf, (MPI_Aint)r * recvcount, recvtype), recvcount, recvtype);
  tsmpi_cg_free(all);
  tsmpi_cg_free(bc);
  return tsmpi_coll_end(rc);
}

int PMPI_Allgatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, const int recvcounts[],
                   const int displs[], MPI_Datatype recvtype, MPI_Comm comm) {
  static const char fn[] = "MPI_Allgatherv";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_allgatherv(sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm);
  int rc, in_place = sendbuf == MPI_IN_PLACE;
  if ((rc = tsmpi_comm_check(comm, fn))) return rc;
  int me = tsmpi_comm_rank(comm), size = tsmpi_comm_size(comm);
  if ((rc = tsmpi_coll_counts_ok(comm, fn, "recvcounts", recvcounts, displs, size)) ||
      (rc = tsmpi_coll_type_ok(comm, fn, "recvtype", recvtype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  if (!in_place && (rc = tsmpi_coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  size_t rs = tsmpi_type_size(recvtype);
  if (!in_place && tsmpi_type_size(sendtype) * (size_t)sendcount != (size_t)recvcounts[me] * rs)
    return tsmpi_raise(comm, MPI_ERR_TRUNCATE, fn, "this rank sends %zu bytes and receives %zu from itself",
                       tsmpi_type_size(sendtype) * (size_t)sendcount, (size_t)recvcounts[me] * rs);
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_ALLGATHERV, -1);
  size_t *bc = tsmpi_cg_alloc(&g, 2 * (size_t)size * sizeof *bc), *bd = bc + size, total = 0;
  for (int i = 0; i < size; i++) {
    bc[i] = (size_t)recvcounts[i] * rs;
    bd[i] = total;
    total += bc[i];
  }
  /* MPICH: nothing to do when the total is 0. */
  if (total == 0) {
    tsmpi_cg_free(bc);
    return tsmpi_coll_end(MPI_SUCCESS);
  }
  char *all = tsmpi_cg_alloc(&g, total);
  if (bc[me])
    tsmpi_type_pack(in_place ? tsmpi_coll_at(recvbuf, displs[me], recvtype) : sendbuf,
                    in_place ? recvcounts[me] : sendcount, in_place ? recvtype : sendtype, all + bd[me]);
  rc = size == 1 ? MPI_SUCCESS
                 : allgather_run(&g, allgather_alg(COLL_ALLGATHERV, &g, total), all, bc, bd, 1, rs,
                                 (size_t)tsmpi_type_extent(recvtype));
  if (!rc)
    for (int r = 0; r < size; r++) tsmpi_coll_unpack(all + bd[r], tsmpi_coll_at(recvbuf, displs[r], recvtype), recvcounts[r], recvtype);
  tsmpi_cg_free(all);
  tsmpi_cg_free(bc);
  return tsmpi_coll_end(rc);
}

/* ==== all-to-all ========================================================== */

int PMPI_Alltoall(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                 MPI_Datatype recvtype, MPI_Comm comm) {
  static const char fn[] = "MPI_Alltoall";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_alltoall(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm);
  int rc, in_place = sendbuf == MPI_IN_PLACE;
  if ((rc = tsmpi_comm_check(comm, fn)) || (rc = tsmpi_coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  if (!in_place && (rc = tsmpi_coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  size_t n = tsmpi_type_size(recvtype) * (size_t)recvcount;
  size_t sn = in_place ? n : tsmpi_type_size(sendtype) * (size_t)sendcount;
  if (sn != n)
    return tsmpi_raise(comm, MPI_ERR_TRUNCATE, fn, "this rank sends %zu bytes to each rank and receives %zu", sn, n);
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_ALLTOALL, -1);
  int size = g.size;
  /* MPICH alltoall.c: nothing to do for recvcount 0; in place, the pairwise
   * sendrecv_replace schedule; else Bruck for blocks of at most
   * MPIR_CVAR_ALLTOALL_SHORT_MSG_SIZE (256) bytes on
   * MPIR_CVAR_ALLTOALL_MIN_PROCS (8) ranks or more, "scattered" for blocks
   * of at most MPIR_CVAR_ALLTOALL_MEDIUM_MSG_SIZE (32768), else pairwise. */
  if (recvcount == 0) return tsmpi_coll_end(MPI_SUCCESS);
  tsmpi_alg a = tsmpi_coll_setting(COLL_ALLTOALL);
  if (a == ALG_AUTO) {
    if (in_place) a = ALG_PAIRWISE_SENDRECV_REPLACE;
    else if (n <= 256 && size >= 8) a = ALG_BRUCKS;
    else if (n <= 32768) a = ALG_SCATTERED;
    else a = ALG_PAIRWISE;
  }
  /* Contiguous buffers, not in place: the algorithms read sendbuf and write
   * recvbuf where they lie (no packed copies). */
  char *rdirect = a != ALG_PAIRWISE_SENDRECV_REPLACE && !in_place
                      ? (char *)tsmpi_type_contig(recvbuf, recvcount * size, recvtype) : NULL;
  const char *sdirect = rdirect ? tsmpi_type_contig(sendbuf, sendcount * size, sendtype) : NULL;
  char *out = sdirect ? rdirect : tsmpi_coll_pack(&g, recvbuf, recvcount * size, recvtype), *in = NULL;
  if (sdirect) {
    in = (char *)sdirect;
  } else if (a != ALG_PAIRWISE_SENDRECV_REPLACE) {
    in = in_place ? out : tsmpi_coll_pack(&g, sendbuf, sendcount * size, sendtype);
    if (in_place) out = tsmpi_cg_alloc(&g, n * (size_t)size);
  } else if (!in_place) {
    tsmpi_type_pack(sendbuf, sendcount * size, sendtype, out);
  }
  size_t *cd = tsmpi_cg_alloc(&g, 2 * (size_t)size * sizeof *cd);
  for (int i = 0; i < size; i++) {
    cd[i] = n;
    cd[size + i] = (size_t)i * n;
  }
  switch (a) {
  case ALG_LINEAR: rc = tsmpi_alltoallv_linear(&g, in, cd, cd + size, out, cd, cd + size); break;
  case ALG_BRUCKS: rc = tsmpi_alltoall_brucks(&g, in, out, n); break;
  case ALG_SCATTERED: rc = tsmpi_alltoall_scattered(&g, in, out, n); break;
  case ALG_PAIRWISE: rc = tsmpi_alltoall_pairwise(&g, in, out, n); break;
  default: rc = tsmpi_alltoallv_pairwise_sendrecv_replace(&g, out, cd, cd + size, cd, cd + size); break;
  }
  if (!rc && !sdirect) tsmpi_coll_unpack(out, recvbuf, recvcount * size, recvtype);
  tsmpi_cg_free(cd);
  if (!sdirect) {
    tsmpi_cg_free(in);
    tsmpi_cg_free(out);
  }
  return tsmpi_coll_end(rc);
}

int PMPI_Alltoallv(const void *sendbuf, const int sendcounts[], const int sdispls[], MPI_Datatype sendtype,
                  void *recvbuf, const int recvcounts[], const int rdispls[], MPI_Datatype recvtype, MPI_Comm comm) {
  static const char fn[] = "MPI_Alltoallv";
  if (tsmpi_comm_inter(comm)) return tsmpi_inter_alltoallv(sendbuf, sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls, recvtype, comm);
  int rc, in_place = sendbuf == MPI_IN_PLACE;
  if ((rc = tsmpi_comm_check(comm, fn))) return rc;
  int size = tsmpi_comm_size(comm);
  if ((rc = tsmpi_coll_counts_ok(comm, fn, "recvcounts", recvcounts, rdispls, size)) ||
      (rc = tsmpi_coll_type_ok(comm, fn, "recvtype", recvtype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return tsmpi_coll_in_place_bad(comm, fn, "recvbuf");
  if (!in_place && ((rc = tsmpi_coll_counts_ok(comm, fn, "sendcounts", sendcounts, sdispls, size)) ||
                    (rc = tsmpi_coll_type_ok(comm, fn, "sendtype", sendtype))))
    return rc;
  tsmpi_cg g;
  tsmpi_label l;
  tsmpi_coll_begin(&g, &l, fn, comm, COLL_ALLTOALLV, -1);
  size_t *v = tsmpi_cg_alloc(&g, 4 * (size_t)size * sizeof *v), *sc = v, *sd = v + size, *rcn = v + 2 * size,
         *rd = v + 3 * size, stot = 0, rtot = 0, rs = tsmpi_type_size(recvtype);
  size_t ss = in_place ? rs : tsmpi_type_size(sendtype);
  for (int i = 0; i < size; i++) {
    sc[i] = (size_t)(in_place ? recvcounts : sendcounts)[i] * ss;
    sd[i] = stot;
    stot += sc[i];
    rcn[i] = (size_t)recvcounts[i] * rs;
    rd[i] = rtot;
    rtot += rcn[i];
  }
  if (sc[g.rank] != rcn[g.rank]) {
    size_t s0 = sc[g.rank], r0 = rcn[g.rank];
    tsmpi_cg_free(v);
    return tsmpi_coll_end(tsmpi_raise(comm, MPI_ERR_TRUNCATE, fn, "this rank sends %zu bytes to itself and receives %zu",
                                      s0, r0));
  }
  /* MPICH alltoallv.c: in place, the pairwise sendrecv_replace schedule;
   * else "scattered". */
  tsmpi_alg a = tsmpi_coll_setting(COLL_ALLTOALLV);
  if (a == ALG_AUTO) a = in_place ? ALG_PAIRWISE_SENDRECV_REPLACE : ALG_SCATTERED;
  char *out = tsmpi_cg_alloc(&g, rtot), *in = tsmpi_cg_alloc(&g, stot);
  MPI_Datatype st = in_place ? recvtype : sendtype;
  const void *sb = in_place ? recvbuf : sendbuf;
  const int *scnt = in_place ? recvcounts : sendcounts, *sdsp = in_place ? rdispls : sdispls;
  for (int i = 0; i < size; i++)
    if (sc[i]) tsmpi_type_pack(tsmpi_coll_at(sb, sdsp[i], st), scnt[i], st, in + sd[i]);
  if (a == ALG_PAIRWISE_SENDRECV_REPLACE) {
    /* In place: each block goes out from and comes back into one place
     * (the counts of both directions are the receive counts, as MPI says). */
    if (stot == rtot && !memcmp(sc, rcn, (size_t)size * sizeof *sc)) {
      memcpy(out, in, rtot);
      rc = tsmpi_alltoallv_pairwise_sendrecv_replace(&g, out, rcn, rd, rcn, rd);
    } else {
      rc = tsmpi_alltoallv_scattered(&g, in, sc, sd, out, rcn, rd);
    }
  } else if (a == ALG_LINEAR) {
    rc = tsmpi_alltoallv_linear(&g, in, sc, sd, out, rcn, rd);
  } else {
    rc = tsmpi_alltoallv_scattered(&g, in, sc, sd, out, rcn, rd);
  }
  if (!rc)
    for (int i = 0; i < size; i++) tsmpi_coll_unpack(out + rd[i], tsmpi_coll_at(recvbuf, rdispls[i], recvtype), recvcounts[i], recvtype);
  tsmpi_cg_free(in);
  tsmpi_cg_free(out);
  tsmpi_cg_free(v);
  return tsmpi_coll_end(rc);
}
