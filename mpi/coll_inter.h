/* coll_inter.h -- the collectives on an intercommunicator (MPI 3.1 section
 * 5.2.2), which each MPI collective hands its call to when its
 * communicator is one (core.h: comm_inter), before any check of its
 * own.  Same arguments as the MPI functions.
 *
 * ROOTS.  In the rooted ones (bcast, gather(v), scatter(v), reduce) the
 * root's group passes MPI_ROOT at the root and MPI_PROC_NULL elsewhere (who
 * then do nothing), the other group the root's rank in the remote group.
 * The all- ones move data from each group to the other: a rank's receive
 * buffer gets the remote group's data, its counts and displacements are
 * the remote ranks'; reduce_scatter's result over one group's operands is
 * scattered over the other (the sum of the counts the same in both).
 * MPI_IN_PLACE is not allowed (MPI_ERR_BUFFER); Scan and Exscan are
 * intracommunicators' only (MPI_ERR_COMM).
 *
 * ALGORITHMS, as MPICH's intercommunicator ones (src/mpi/coll/<name>/
 * <name>_inter_*): a group's data meets at its rank 0 by the local
 * collective (on a hidden intracommunicator of the group: intercomm.c),
 * crosses between the groups' ranks 0 or to the root, and spreads by the
 * local collective; gatherv, scatterv and the all-to-alls go rank to rank.
 * Reductions combine a group's operands in the local reduce's order. */
#ifndef TSMPI_COLL_INTER_H
#define TSMPI_COLL_INTER_H

#include "mpi/mpi.h"

int coll_inter_barrier(MPI_Comm comm);
int coll_inter_bcast(void *buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm);
int coll_inter_gather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                      MPI_Datatype recvtype, int root, MPI_Comm comm);
int coll_inter_gatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                       const int recvcounts[], const int displs[], MPI_Datatype recvtype, int root, MPI_Comm comm);
int coll_inter_scatter(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                       MPI_Datatype recvtype, int root, MPI_Comm comm);
int coll_inter_scatterv(const void *sendbuf, const int sendcounts[], const int displs[], MPI_Datatype sendtype,
                        void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm);
int coll_inter_allgather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                         MPI_Datatype recvtype, MPI_Comm comm);
int coll_inter_allgatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                          const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm);
int coll_inter_alltoall(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                        MPI_Datatype recvtype, MPI_Comm comm);
int coll_inter_alltoallv(const void *sendbuf, const int sendcounts[], const int sdispls[], MPI_Datatype sendtype,
                         void *recvbuf, const int recvcounts[], const int rdispls[], MPI_Datatype recvtype,
                         MPI_Comm comm);
int coll_inter_alltoallw(const void *sendbuf, const int sendcounts[], const int sdispls[],
                         const MPI_Datatype sendtypes[], void *recvbuf, const int recvcounts[], const int rdispls[],
                         const MPI_Datatype recvtypes[], MPI_Comm comm);
int coll_inter_reduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, int root,
                      MPI_Comm comm);
int coll_inter_allreduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op,
                         MPI_Comm comm);
int coll_inter_reduce_scatter(const void *sendbuf, void *recvbuf, const int recvcounts[], MPI_Datatype datatype,
                              MPI_Op op, MPI_Comm comm);
int coll_inter_reduce_scatter_block(const void *sendbuf, void *recvbuf, int recvcount, MPI_Datatype datatype,
                                    MPI_Op op, MPI_Comm comm);

/* MPI_ERR_COMM raised for fn (Scan, Exscan). */
int coll_inter_none(MPI_Comm comm, const char *fn);

#endif
