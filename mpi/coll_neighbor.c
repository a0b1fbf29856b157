/* coll_neighbor.c -- the neighbourhood collectives (MPI 3.1 section 7.6): MPI_Neighbor_allgather(v),
 * MPI_Neighbor_alltoall(v,w) and their nonblocking forms MPI_Ineighbor_* (mpi.h), on a
 * communicator with a process topology (topo.h says who a rank's neighbours are, in order).
 *
 * One algorithm, MPICH's (src/mpi/coll/ineighbor_NAME/ineighbor_NAME_allcomm_sched_linear.c, which
 * its blocking forms run too): a receive posted from every source in order, a send to every
 * destination in order, then the wait for all.  A neighbour that is MPI_PROC_NULL (the edge of
 * a non-periodic Cartesian dimension) sends and receives nothing: its block of the receive
 * buffer is left as it was.  A rank that is a neighbour twice (a periodic dimension of one or
 * two ranks, a graph's repeated edge) gets its messages matched in order.  As coll_api.c: one
 * body per blocking and nonblocking pair; the data packed, a schedule, unpacked at the end. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/coll_sched.h"
#include "mpi/dtype.h"
#include "mpi/core.h"
#include "mpi/topo.h"

/* The exchange: the packed block sb[l] (sn[l] bytes) to destination l, block
 * k of the sources' into rb[k] (rn[k] bytes). */
static void exchange(coll_sched *s, const ptopo *t, char *const *sb, const size_t *sn, char *const *rb,
                     const size_t *rn) {
  for (int k = 0; k < t->indeg; k++)
    if (t->sources[k] != MPI_PROC_NULL) coll_sched_irecv(s, rb[k], rn[k], t->sources[k]);
  for (int l = 0; l < t->outdeg; l++)
    if (t->dests[l] != MPI_PROC_NULL) coll_sched_isend(s, sb[l], sn[l], t->dests[l]);
  coll_sched_waitall(s);
}

/* One side of an exchange: per neighbour, count elements of a type at a
 * place of buf (unit 0: displacements in the type's extents; else bytes). */
typedef struct {
  const void *buf;
  const int *counts;       /* NULL: count for every neighbour */
  int count;
  const int *displs;       /* NULL: neighbour i at i * count extents */
  const MPI_Aint *bdispls; /* alltoallw's, in bytes */
  const MPI_Datatype *types;   /* NULL: type for every neighbour */
  MPI_Datatype type;
  int same;                /* every neighbour the same block (allgather's send side) */
  int arrays;              /* 1: counts and displacements per neighbour; 2: and types */
} side;

static int count_of(const side *d, int i) { return d->counts ? d->counts[i] : d->count; }
static MPI_Datatype type_of(const side *d, int i) { return d->types ? d->types[i] : d->type; }
static void *at(const side *d, int i) {
  if (d->same) return (void *)d->buf;
  if (d->bdispls) return (char *)d->buf + d->bdispls[i];
  MPI_Aint off = d->displs ? d->displs[i] : (MPI_Aint)i * d->count;
  return coll_at(d->buf, off, type_of(d, i));
}

/* n neighbours' blocks of a side: counts >= 0, types committed, arrays there. */
static int side_ok(MPI_Comm comm, const char *fn, const char *what, const side *d, int n) {
  int rc;
  if (d->buf == MPI_IN_PLACE) return coll_in_place_bad(comm, fn, what);
  if (d->arrays) {
    if (n > 0 && (!d->counts || (!d->displs && !d->bdispls)))
      return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL counts or displacements of %s", what);
    for (int i = 0; i < n; i++)
      if (d->counts[i] < 0) return err_comm_raise(comm, MPI_ERR_COUNT, fn, "%s's count [%d] = %d < 0", what, i, d->counts[i]);
  } else if ((rc = err_comm_check_count(comm, fn, d->count))) {
    return rc;
  }
  if (d->arrays == 2 && n > 0 && !d->types) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL types of %s", what);
  for (int i = 0; i < (d->types ? n : 1); i++) {
    char w[48];
    snprintf(w, sizeof w, d->types ? "%s's type [%d]" : "%s's type", what, i);
    if ((rc = coll_type_ok(comm, fn, w, d->types ? d->types[i] : d->type))) return rc;
  }
  return MPI_SUCCESS;
}

/* The body of them all. */
static int neighbor(const char *fn, coll_id c, side snd, side rcv, MPI_Comm comm, MPI_Request *req) {
  int rc = comm_check(comm, fn);
  if (rc || (req && (rc = coll_req_ok(comm, fn, req)))) return rc;
  ptopo *t = ptopo_of(comm, fn, 0, &rc);
  if (!t) return rc;
  if ((rc = side_ok(comm, fn, "sendbuf", &snd, t->outdeg)) || (rc = side_ok(comm, fn, "recvbuf", &rcv, t->indeg)))
    return rc;
  coll_sched *s = coll_start(fn, comm, c, -1, req);
  int nb = t->indeg + t->outdeg;
  char **blk = coll_sched_mem(s, ((size_t)nb + 1) * sizeof *blk);
  size_t *len = coll_sched_mem(s, ((size_t)nb + 1) * sizeof *len);
  char **sb = blk, **rb = blk + t->outdeg;
  size_t *sn = len, *rn = len + t->outdeg;
  for (int l = 0; l < t->outdeg; l++) {
    if (snd.same && l > 0) {   /* allgather: one block for every destination */
      sb[l] = sb[0];
      sn[l] = sn[0];
      continue;
    }
    sb[l] = coll_pack(s, at(&snd, l), count_of(&snd, l), type_of(&snd, l));
    sn[l] = (size_t)count_of(&snd, l) * dtype_size(type_of(&snd, l));
  }
  for (int k = 0; k < t->indeg; k++) {
    rn[k] = (size_t)count_of(&rcv, k) * dtype_size(type_of(&rcv, k));
    rb[k] = coll_sched_mem(s, rn[k]);
  }
  exchange(s, t, sb, sn, rb, rn);
  for (int k = 0; k < t->indeg; k++)
    if (t->sources[k] != MPI_PROC_NULL)
      coll_sched_unpack(s, rb[k], rn[k], at(&rcv, k), count_of(&rcv, k), type_of(&rcv, k));
  return coll_finish(s);
}

/* ==== the calls =========================================================== */

static int allgather(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                     int recvcount, MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *req) {
  side snd = {sendbuf, NULL, sendcount, NULL, NULL, NULL, sendtype, 1, 0};
  side rcv = {recvbuf, NULL, recvcount, NULL, NULL, NULL, recvtype, 0, 0};
  if (sendcount < 0) return err_comm_check_count(comm, fn, sendcount);
  return neighbor(fn, COLL_NEIGHBOR_ALLGATHER, snd, rcv, comm, req);
}

int PMPI_Neighbor_allgather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                           MPI_Datatype recvtype, MPI_Comm comm) {
  return allgather("MPI_Neighbor_allgather", sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, NULL);
}

int PMPI_Ineighbor_allgather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                            int recvcount, MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request) {
  static const char fn[] = "MPI_Ineighbor_allgather";
  int rc = comm_check(comm, fn);
  if (rc || (rc = coll_req_ok(comm, fn, request))) return rc;
  return allgather(fn, sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, request);
}

static int allgatherv(const char *fn, const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                      const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm,
                      MPI_Request *req) {
  side snd = {sendbuf, NULL, sendcount, NULL, NULL, NULL, sendtype, 1, 0};
  side rcv = {recvbuf, recvcounts, 0, displs, NULL, NULL, recvtype, 0, 1};
  if (sendcount < 0) return err_comm_check_count(comm, fn, sendcount);
  return neighbor(fn, COLL_NEIGHBOR_ALLGATHERV, snd, rcv, comm, req);
}

int PMPI_Neighbor_allgatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                            const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm) {
  return allgatherv("MPI_Neighbor_allgatherv", sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype,
                    comm, NULL);
}

int PMPI_Ineighbor_allgatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                             const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm,
                             MPI_Request *request) {
  static const char fn[] = "MPI_Ineighbor_allgatherv";
  int rc = comm_check(comm, fn);
  if (rc || (rc = coll_req_ok(comm, fn, request))) return rc;
  return allgatherv(fn, sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm, request);
}

int PMPI_Neighbor_alltoall(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                          MPI_Datatype recvtype, MPI_Comm comm) {
  side snd = {sendbuf, NULL, sendcount, NULL, NULL, NULL, sendtype, 0, 0};
  side rcv = {recvbuf, NULL, recvcount, NULL, NULL, NULL, recvtype, 0, 0};
  return neighbor("MPI_Neighbor_alltoall", COLL_NEIGHBOR_ALLTOALL, snd, rcv, comm, NULL);
}

int PMPI_Ineighbor_alltoall(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                           MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request) {
  static const char fn[] = "MPI_Ineighbor_alltoall";
  side snd = {sendbuf, NULL, sendcount, NULL, NULL, NULL, sendtype, 0, 0};
  side rcv = {recvbuf, NULL, recvcount, NULL, NULL, NULL, recvtype, 0, 0};
  int rc = comm_check(comm, fn);
  if (rc || (rc = coll_req_ok(comm, fn, request))) return rc;
  return neighbor(fn, COLL_NEIGHBOR_ALLTOALL, snd, rcv, comm, request);
}

int PMPI_Neighbor_alltoallv(const void *sendbuf, const int sendcounts[], const int sdispls[], MPI_Datatype sendtype,
                           void *recvbuf, const int recvcounts[], const int rdispls[], MPI_Datatype recvtype,
                           MPI_Comm comm) {
  side snd = {sendbuf, sendcounts, 0, sdispls, NULL, NULL, sendtype, 0, 1};
  side rcv = {recvbuf, recvcounts, 0, rdispls, NULL, NULL, recvtype, 0, 1};
  return neighbor("MPI_Neighbor_alltoallv", COLL_NEIGHBOR_ALLTOALLV, snd, rcv, comm, NULL);
}

int PMPI_Ineighbor_alltoallv(const void *sendbuf, const int sendcounts[], const int sdispls[], MPI_Datatype sendtype,
                            void *recvbuf, const int recvcounts[], const int rdispls[], MPI_Datatype recvtype,
                            MPI_Comm comm, MPI_Request *request) {
  static const char fn[] = "MPI_Ineighbor_alltoallv";
  side snd = {sendbuf, sendcounts, 0, sdispls, NULL, NULL, sendtype, 0, 1};
  side rcv = {recvbuf, recvcounts, 0, rdispls, NULL, NULL, recvtype, 0, 1};
  int rc = comm_check(comm, fn);
  if (rc || (rc = coll_req_ok(comm, fn, request))) return rc;
  return neighbor(fn, COLL_NEIGHBOR_ALLTOALLV, snd, rcv, comm, request);
}

int PMPI_Neighbor_alltoallw(const void *sendbuf, const int sendcounts[], const MPI_Aint sdispls[],
                           const MPI_Datatype sendtypes[], void *recvbuf, const int recvcounts[],
                           const MPI_Aint rdispls[], const MPI_Datatype recvtypes[], MPI_Comm comm) {
  side snd = {sendbuf, sendcounts, 0, NULL, sdispls, sendtypes, MPI_DATATYPE_NULL, 0, 2};
  side rcv = {recvbuf, recvcounts, 0, NULL, rdispls, recvtypes, MPI_DATATYPE_NULL, 0, 2};
  return neighbor("MPI_Neighbor_alltoallw", COLL_NEIGHBOR_ALLTOALLW, snd, rcv, comm, NULL);
}

int PMPI_Ineighbor_alltoallw(const void *sendbuf, const int sendcounts[], const MPI_Aint sdispls[],
                            const MPI_Datatype sendtypes[], void *recvbuf, const int recvcounts[],
                            const MPI_Aint rdispls[], const MPI_Datatype recvtypes[], MPI_Comm comm,
                            MPI_Request *request) {
  static const char fn[] = "MPI_Ineighbor_alltoallw";
  side snd = {sendbuf, sendcounts, 0, NULL, sdispls, sendtypes, MPI_DATATYPE_NULL, 0, 2};
  side rcv = {recvbuf, recvcounts, 0, NULL, rdispls, recvtypes, MPI_DATATYPE_NULL, 0, 2};
  int rc = comm_check(comm, fn);
  if (rc || (rc = coll_req_ok(comm, fn, request))) return rc;
  return neighbor(fn, COLL_NEIGHBOR_ALLTOALLW, snd, rcv, comm, request);
}
