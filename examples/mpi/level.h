/* level.h -- level(comm): every rank of comm leaves at the same simulated
 * time on --net ideal (P >= 3), which the one-sided examples want before
 * they time an epoch.  After a round in which each rank sends 0 bytes to
 * every other, each leaves at the latest entry plus M, unless it alone
 * entered last; after a second round, at the same time.  A header of the
 * examples, included by halo_fence.c and lock_counter.c. */
#ifndef EXAMPLES_LEVEL_H
#define EXAMPLES_LEVEL_H

#include <mpi.h>
#include <stdlib.h>

static void level(MPI_Comm comm) {
  int p, r;
  MPI_Comm_size(comm, &p);
  MPI_Comm_rank(comm, &r);
  MPI_Request *q = malloc(2 * (size_t)p * sizeof *q);
  for (int round = 0; round < 2; round++) {
    int n = 0;
    for (int j = 0; j < p; j++) {
      if (j == r) continue;
      MPI_Irecv(NULL, 0, MPI_BYTE, j, 99, comm, &q[n++]);
      MPI_Isend(NULL, 0, MPI_BYTE, j, 99, comm, &q[n++]);
    }
    MPI_Waitall(n, q, MPI_STATUSES_IGNORE);
  }
  free(q);
}

#endif
