/* coll_xapi.c -- the MPI collectives where every rank sends to every rank: MPI_Allgather(v),
 * MPI_Alltoall(v,w) and their nonblocking forms MPI_Iallgather(v), MPI_Ialltoall(v,w) (mpi.h).
 * As coll_api.c: one body per pair; check, start, pack, pick (the run's setting, else MPICH's
 * rule, cited), build, unpack at the end, finish. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/coll_inter.h"
#include "mpi/dtype.h"
#include "mpi/core.h"
#include "mpi/coll_sched.h"

/* ==== allgather =========================================================== */

/* The allgather algorithm for tot bytes on the group: MPICH allgather.c
 * and allgatherv.c: recursive doubling below MPIR_CVAR_ALLGATHER_LONG_MSG_SIZE
 * (524288) bytes on a power of two ranks, else Bruck below
 * MPIR_CVAR_ALLGATHER_SHORT_MSG_SIZE (81920), else the ring. */
static coll_alg allgather_alg(coll_id c, int size, size_t tot) {
  coll_alg a = coll_setting(c);
  if (a != ALG_AUTO) return a;
  if (tot < 524288 && coll_is_pof2(size)) return ALG_RECURSIVE_DOUBLING;
  return tot < 81920 ? ALG_BRUCKS : ALG_RING;
}

/* Every rank's block (at bd[r], bc[r] bytes of the packed buf) to every
 * rank; unit and extent: the receive type's, for the pipelined ring. */
static void allgather_build(coll_sched *s, coll_alg a, char *buf, const size_t *bc, const size_t *bd, int v,
                            size_t unit, size_t extent) {
  switch (a) {
  case ALG_LINEAR: coll_allgatherv_linear(s, buf, bc, bd); break;
  case ALG_RECURSIVE_DOUBLING: coll_allgatherv_recursive_doubling(s, buf, bc, bd); break;
  case ALG_BRUCKS: coll_allgatherv_brucks(s, buf, bc, bd); break;
  default:
    if (v)
      coll_allgatherv_ring_pipelined(s, buf, bc, bd, unit, extent);
    else
      coll_allgatherv_ring(s, buf, bc, bd);
  }
}

static int allgather(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                     int recvcount, MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *req) {
  int rc, in_place = sendbuf == MPI_IN_PLACE;
  if ((rc = coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype))) return rc;
  if (recvbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
  if (!in_place && (rc = coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  size_t n = dtype_size(recvtype) * (size_t)recvcount;
  if (!in_place && dtype_size(sendtype) * (size_t)sendcount != n)
    return err_comm_raise(comm, MPI_ERR_TRUNCATE, fn, "this rank sends %zu bytes and receives %zu from each rank",
                          dtype_size(sendtype) * (size_t)sendcount, n);
  coll_sched *s = coll_start(fn, comm, COLL_ALLGATHER, -1, req);
  const coll_cg *g = coll_sched_group(s);
  /* MPICH: nothing to do when nothing is sent or received. */
  if ((!in_place && sendcount == 0) || recvcount == 0) return coll_finish(s);
  int size = g->size;
  size_t *bc = coll_sched_mem(s, 2 * (size_t)size * sizeof *bc), *bd = bc + size;
  for (int i = 0; i < size; i++) {
    bc[i] = n;
    bd[i] = (size_t)i * n;
  }
  /* recvbuf itself when contiguous: in place, this rank's block is there already */
  char *all = coll_place(s, recvbuf, recvcount * size, recvtype, 0);
  if (!in_place)
    dtype_pack(sendbuf, sendcount, sendtype, all + bd[g->rank]);
  else if (all != dtype_contig(recvbuf, recvcount * size, recvtype))
    dtype_pack(coll_at(recvbuf, (MPI_Aint)g->rank * recvcount, recvtype), recvcount, recvtype,
               all + bd[g->rank]);
  if (size > 1) allgather_build(s, allgather_alg(COLL_ALLGATHER, size, n * (size_t)size), all, bc, bd, 0, 0, 0);
  coll_sched_unpack(s, all, n * (size_t)size, recvbuf, recvcount * size, recvtype);
  return coll_finish(s);
}

int PMPI_Allgather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                  MPI_Datatype recvtype, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_allgather(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm);
  int rc = comm_check(comm, "MPI_Allgather");
  return rc ? rc : allgather("MPI_Allgather", sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, NULL);
}

int PMPI_Iallgather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                   MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Iallgather", comm, coll_inter_allgather(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm), request);
  static const char fn[] = "MPI_Iallgather";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  return allgather(fn, sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, request);
}

static int allgatherv(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                      const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm,
                      MPI_Request *req) {
  int rc, in_place = sendbuf == MPI_IN_PLACE;
  int me = comm_rank(comm), size = comm_size(comm);
  if ((rc = coll_counts_ok(comm, fn, "recvcounts", recvcounts, displs, size)) ||
      (rc = coll_type_ok(comm, fn, "recvtype", recvtype)))
    return rc;
  if (recvbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
  if (!in_place && (rc = coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  size_t rs = dtype_size(recvtype);
  if (!in_place && dtype_size(sendtype) * (size_t)sendcount != (size_t)recvcounts[me] * rs)
    return err_comm_raise(comm, MPI_ERR_TRUNCATE, fn, "this rank sends %zu bytes and receives %zu from itself",
                          dtype_size(sendtype) * (size_t)sendcount, (size_t)recvcounts[me] * rs);
  coll_sched *s = coll_start(fn, comm, COLL_ALLGATHERV, -1, req);
  size_t *bc = coll_sched_mem(s, 2 * (size_t)size * sizeof *bc), *bd = bc + size, total = 0;
  for (int i = 0; i < size; i++) {
    bc[i] = (size_t)recvcounts[i] * rs;
    bd[i] = total;
    total += bc[i];
  }
  /* MPICH: nothing to do when the total is 0. */
  if (total == 0) return coll_finish(s);
  /* recvbuf itself when its blocks are contiguous and lie in rank order,
   * back to back (the algorithms send runs of blocks): in place, this rank's
   * block is there already. */
  size_t *off = coll_sched_mem(s, (size_t)size * sizeof *off);
  char *all = coll_vdirect(recvbuf, recvcounts, displs, NULL, recvtype, size, bc, off);
  for (int i = 0; all && i < size; i++)
    if (bc[i] && off[i] != bd[i]) all = NULL;
  if (!all) all = coll_sched_mem(s, total);
  if (bc[me] && !in_place)
    dtype_pack(sendbuf, sendcount, sendtype, all + bd[me]);
  else if (bc[me] && all + bd[me] != dtype_contig(coll_at(recvbuf, displs[me], recvtype), recvcounts[me], recvtype))
    dtype_pack(coll_at(recvbuf, displs[me], recvtype), recvcounts[me], recvtype, all + bd[me]);
  if (size > 1)
    allgather_build(s, allgather_alg(COLL_ALLGATHERV, size, total), all, bc, bd, 1, rs,
                    (size_t)dtype_extent(recvtype));
  for (int r = 0; r < size; r++)
    coll_sched_unpack(s, all + bd[r], bc[r], coll_at(recvbuf, displs[r], recvtype), recvcounts[r], recvtype);
  return coll_finish(s);
}

int PMPI_Allgatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, const int recvcounts[],
                   const int displs[], MPI_Datatype recvtype, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_allgatherv(sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm);
  int rc = comm_check(comm, "MPI_Allgatherv");
  return rc ? rc
            : allgatherv("MPI_Allgatherv", sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm,
                         NULL);
}

int PMPI_Iallgatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                    const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm,
                    MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Iallgatherv", comm, coll_inter_allgatherv(sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm), request);
  static const char fn[] = "MPI_Iallgatherv";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  return allgatherv(fn, sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm, request);
}

/* ==== all-to-all ========================================================== */

static int alltoall(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                    int recvcount, MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *req) {
  int rc, in_place = sendbuf == MPI_IN_PLACE;
  if ((rc = coll_data_ok(comm, fn, "recvtype", recvbuf, recvcount, recvtype))) return rc;
  if (recvbuf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
  if (!in_place && (rc = coll_data_ok(comm, fn, "sendtype", sendbuf, sendcount, sendtype))) return rc;
  size_t n = dtype_size(recvtype) * (size_t)recvcount;
  size_t sn = in_place ? n : dtype_size(sendtype) * (size_t)sendcount;
  if (sn != n)
    return err_comm_raise(comm, MPI_ERR_TRUNCATE, fn, "this rank sends %zu bytes to each rank and receives %zu", sn, n);
  coll_sched *s = coll_start(fn, comm, COLL_ALLTOALL, -1, req);
  int size = coll_sched_group(s)->size;
  /* MPICH alltoall.c: nothing to do for recvcount 0; in place, the pairwise
   * sendrecv_replace schedule; else Bruck for blocks of at most
   * MPIR_CVAR_ALLTOALL_SHORT_MSG_SIZE (256) bytes on
   * MPIR_CVAR_ALLTOALL_MIN_PROCS (8) ranks or more, "scattered" for blocks
   * of at most MPIR_CVAR_ALLTOALL_MEDIUM_MSG_SIZE (32768), else pairwise. */
  if (recvcount == 0) return coll_finish(s);
  coll_alg a = coll_setting(COLL_ALLTOALL);
  if (a == ALG_AUTO) {
    if (in_place) a = ALG_PAIRWISE_SENDRECV_REPLACE;
    else if (n <= 256 && size >= 8) a = ALG_BRUCKS;
    else if (n <= 32768) a = ALG_SCATTERED;
    else a = ALG_PAIRWISE;
  }
  /* Contiguous buffers, not in place: the algorithms read sendbuf and write
   * recvbuf where they lie (no packed copies). */
  char *rdirect = a != ALG_PAIRWISE_SENDRECV_REPLACE && !in_place
                      ? (char *)dtype_contig(recvbuf, recvcount * size, recvtype) : NULL;
  const char *sdirect = rdirect ? dtype_contig(sendbuf, sendcount * size, sendtype) : NULL;
  char *out = sdirect ? rdirect : coll_pack(s, recvbuf, recvcount * size, recvtype), *in = out;
  if (sdirect) {
    in = (char *)sdirect;
  } else if (a != ALG_PAIRWISE_SENDRECV_REPLACE) {
    if (!in_place) in = coll_pack(s, sendbuf, sendcount * size, sendtype);
    else out = coll_sched_mem(s, n * (size_t)size);
  } else if (!in_place) {
    dtype_pack(sendbuf, sendcount * size, sendtype, out);
  }
  size_t *cd = coll_sched_mem(s, 2 * (size_t)size * sizeof *cd);
  for (int i = 0; i < size; i++) {
    cd[i] = n;
    cd[size + i] = (size_t)i * n;
  }
  switch (a) {
  case ALG_LINEAR: coll_alltoallv_linear(s, in, cd, cd + size, out, cd, cd + size); break;
  case ALG_BRUCKS: coll_alltoall_brucks(s, in, out, n); break;
  case ALG_SCATTERED: coll_alltoall_scattered(s, in, out, n); break;
  case ALG_PAIRWISE: coll_alltoall_pairwise(s, in, out, n); break;
  default: coll_alltoallv_pairwise_sendrecv_replace(s, out, cd, cd + size); break;
  }
  if (!sdirect) coll_sched_unpack(s, out, n * (size_t)size, recvbuf, recvcount * size, recvtype);
  return coll_finish(s);
}

int PMPI_Alltoall(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                 MPI_Datatype recvtype, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_alltoall(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm);
  int rc = comm_check(comm, "MPI_Alltoall");
  return rc ? rc : alltoall("MPI_Alltoall", sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, NULL);
}

int PMPI_Ialltoall(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                  MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Ialltoall", comm, coll_inter_alltoall(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm), request);
  static const char fn[] = "MPI_Ialltoall";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  return alltoall(fn, sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, request);
}

/* The blocks of an alltoallv or alltoallw, described once: block i of the
 * send (receive) side is counts[i] elements of types[i] at displs[i] units
 * (unit 0: the type's extent, alltoallv; 1: bytes, alltoallw). */
typedef struct {
  const int *counts, *displs;
  const MPI_Datatype *types;   /* one per rank (alltoallw), or NULL: type for all */
  MPI_Datatype type;
  const void *buf;
} side;

static MPI_Datatype type_at(const side *d, int i) { return d->types ? d->types[i] : d->type; }

static void *block_at(const side *d, int i) {
  if (d->types) return (char *)d->buf + d->displs[i];
  return coll_at(d->buf, d->displs[i], d->type);
}

/* Checks of one side's arrays and types. */
static int side_ok(MPI_Comm comm, const char *fn, const char *what, const char *twhat, const side *d, int size) {
  int rc;
  if ((rc = coll_counts_ok(comm, fn, what, d->counts, d->displs, size))) return rc;
  if (!d->types) return coll_type_ok(comm, fn, twhat, d->type);
  for (int i = 0; i < size; i++) {
    char w[48];
    snprintf(w, sizeof w, "%s[%d]", twhat, i);
    if ((rc = coll_type_ok(comm, fn, w, d->types[i]))) return rc;
  }
  return MPI_SUCCESS;
}

/* The body of MPI_Alltoallv and MPI_Alltoallw (and their nonblocking forms). */
static int alltoallvw(const char *fn, coll_id c, side snd, side rcv, MPI_Comm comm, MPI_Request *req) {
  int rc, in_place = snd.buf == MPI_IN_PLACE;
  int size = comm_size(comm), me = comm_rank(comm);
  const char *tw = c == COLL_ALLTOALLW ? "recvtypes" : "recvtype";
  if ((rc = side_ok(comm, fn, "recvcounts", tw, &rcv, size))) return rc;
  if (rcv.buf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, "recvbuf");
  if (in_place)
    snd = rcv;   /* MPI 3.1 section 5.8: the receive side's counts, displacements and types */
  else if ((rc = side_ok(comm, fn, "sendcounts", c == COLL_ALLTOALLW ? "sendtypes" : "sendtype", &snd, size)))
    return rc;
  size_t s0 = (size_t)snd.counts[me] * dtype_size(type_at(&snd, me));
  size_t r0 = (size_t)rcv.counts[me] * dtype_size(type_at(&rcv, me));
  if (s0 != r0)
    return err_comm_raise(comm, MPI_ERR_TRUNCATE, fn, "this rank sends %zu bytes to itself and receives %zu", s0, r0);
  coll_sched *s = coll_start(fn, comm, c, -1, req);
  size_t *v = coll_sched_mem(s, 4 * (size_t)size * sizeof *v), *sc = v, *sd = v + size, *rcn = v + 2 * size,
         *rd = v + 3 * size, stot = 0, rtot = 0;
  for (int i = 0; i < size; i++) {
    sc[i] = (size_t)snd.counts[i] * dtype_size(type_at(&snd, i));
    sd[i] = stot;
    stot += sc[i];
    rcn[i] = (size_t)rcv.counts[i] * dtype_size(type_at(&rcv, i));
    rd[i] = rtot;
    rtot += rcn[i];
  }
  /* MPICH alltoallv.c and alltoallw.c: in place, the pairwise
   * sendrecv_replace schedule; else "scattered". */
  coll_alg a = coll_setting(c);
  if (a == ALG_AUTO) a = in_place ? ALG_PAIRWISE_SENDRECV_REPLACE : ALG_SCATTERED;
  /* Not in place, a side whose blocks are contiguous is read or written
   * where it lies (as MPI_Alltoall's: no packed copy); else packed. */
  char *out = NULL, *in = NULL;
  if (!in_place && a != ALG_PAIRWISE_SENDRECV_REPLACE) {
    out = coll_vdirect(rcv.buf, rcv.counts, rcv.displs, rcv.types, rcv.type, size, rcn, rd);
    in = coll_vdirect(snd.buf, snd.counts, snd.displs, snd.types, snd.type, size, sc, sd);
  }
  if (!out) out = coll_sched_mem(s, rtot);
  if (!in) {
    in = coll_sched_mem(s, stot);
    for (int i = 0; i < size; i++)
      if (sc[i]) dtype_pack(block_at(&snd, i), snd.counts[i], type_at(&snd, i), in + sd[i]);
  }
  if (a == ALG_PAIRWISE_SENDRECV_REPLACE && stot == rtot && !memcmp(sc, rcn, (size_t)size * sizeof *sc)) {
    /* Each block goes out from and comes back into one place (in place,
     * the counts of both directions are the receive counts, as MPI says;
     * forced, when they are the same). */
    coll_sched_copy(s, out, in, rtot);
    coll_alltoallv_pairwise_sendrecv_replace(s, out, rcn, rd);
  } else if (a == ALG_LINEAR) {
    coll_alltoallv_linear(s, in, sc, sd, out, rcn, rd);
  } else {
    coll_alltoallv_scattered(s, in, sc, sd, out, rcn, rd);
  }
  for (int i = 0; i < size; i++)
    coll_sched_unpack(s, out + rd[i], rcn[i], block_at(&rcv, i), rcv.counts[i], type_at(&rcv, i));
  return coll_finish(s);
}

int PMPI_Alltoallv(const void *sendbuf, const int sendcounts[], const int sdispls[], MPI_Datatype sendtype,
                  void *recvbuf, const int recvcounts[], const int rdispls[], MPI_Datatype recvtype, MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_alltoallv(sendbuf, sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls, recvtype, comm);
  static const char fn[] = "MPI_Alltoallv";
  int rc = comm_check(comm, fn);
  side snd = {sendcounts, sdispls, NULL, sendtype, sendbuf}, rcv = {recvcounts, rdispls, NULL, recvtype, recvbuf};
  return rc ? rc : alltoallvw(fn, COLL_ALLTOALLV, snd, rcv, comm, NULL);
}

int PMPI_Ialltoallv(const void *sendbuf, const int sendcounts[], const int sdispls[], MPI_Datatype sendtype,
                   void *recvbuf, const int recvcounts[], const int rdispls[], MPI_Datatype recvtype, MPI_Comm comm,
                   MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Ialltoallv", comm, coll_inter_alltoallv(sendbuf, sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls, recvtype, comm), request);
  static const char fn[] = "MPI_Ialltoallv";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  side snd = {sendcounts, sdispls, NULL, sendtype, sendbuf}, rcv = {recvcounts, rdispls, NULL, recvtype, recvbuf};
  return alltoallvw(fn, COLL_ALLTOALLV, snd, rcv, comm, request);
}

int PMPI_Alltoallw(const void *sendbuf, const int sendcounts[], const int sdispls[], const MPI_Datatype sendtypes[],
                  void *recvbuf, const int recvcounts[], const int rdispls[], const MPI_Datatype recvtypes[],
                  MPI_Comm comm) {
  if (comm_inter(comm)) return coll_inter_alltoallw(sendbuf, sendcounts, sdispls, sendtypes, recvbuf, recvcounts, rdispls, recvtypes, comm);
  static const char fn[] = "MPI_Alltoallw";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  if ((sendbuf != MPI_IN_PLACE && !sendtypes) || !recvtypes)
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "a NULL array of types");
  side snd = {sendcounts, sdispls, sendtypes, MPI_DATATYPE_NULL, sendbuf};
  side rcv = {recvcounts, rdispls, recvtypes, MPI_DATATYPE_NULL, recvbuf};
  return alltoallvw(fn, COLL_ALLTOALLW, snd, rcv, comm, NULL);
}

int PMPI_Ialltoallw(const void *sendbuf, const int sendcounts[], const int sdispls[],
                   const MPI_Datatype sendtypes[], void *recvbuf, const int recvcounts[], const int rdispls[],
                   const MPI_Datatype recvtypes[], MPI_Comm comm, MPI_Request *request) {
  if (comm_inter(comm)) return coll_ran("MPI_Ialltoallw", comm, coll_inter_alltoallw(sendbuf, sendcounts, sdispls, sendtypes, recvbuf, recvcounts, rdispls, recvtypes, comm), request);
  static const char fn[] = "MPI_Ialltoallw";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = coll_req_ok(comm, fn, request))) return rc;
  if ((sendbuf != MPI_IN_PLACE && !sendtypes) || !recvtypes)
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "a NULL array of types");
  side snd = {sendcounts, sdispls, sendtypes, MPI_DATATYPE_NULL, sendbuf};
  side rcv = {recvcounts, rdispls, recvtypes, MPI_DATATYPE_NULL, recvbuf};
  return alltoallvw(fn, COLL_ALLTOALLW, snd, rcv, comm, request);
}
