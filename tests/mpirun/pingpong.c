/* pingpong.c -- ranks 0 and 1 exchange BYTES bytes K times (default 100000
 * round trips of 8 bytes), the MPI program tests/bench_mpi.sh runs under
 * tilesim-mpirun and SimGrid's smpirun.  Rank 0 prints the time (simulated
 * under both).  pingpong [K [BYTES]] */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv) {
  int r;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  long k = argc > 1 ? atol(argv[1]) : 100000;
  int bytes = argc > 2 ? atoi(argv[2]) : 8;
  char *buf = calloc((size_t)bytes + 1, 1);
  double t0 = MPI_Wtime();
  for (long i = 0; i < k && r < 2; i++) {
    if (r == 0) {
      MPI_Send(buf, bytes, MPI_BYTE, 1, 0, MPI_COMM_WORLD);
      MPI_Recv(buf, bytes, MPI_BYTE, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    } else {
      MPI_Recv(buf, bytes, MPI_BYTE, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Send(buf, bytes, MPI_BYTE, 0, 0, MPI_COMM_WORLD);
    }
  }
  if (r == 0) printf("pingpong: %ld round trips of %d bytes, %.17g s\n", k, bytes, MPI_Wtime() - t0);
  free(buf);
  MPI_Finalize();
  return 0;
}
