/* ring.c -- a token around a ring of ranks, LAPS times (default 62500: on 16
 * ranks 10^6 messages), the MPI program tests/bench_mpi.sh runs under
 * tilesim-mpirun and under SimGrid's smpirun.  Rank 0 prints the token's
 * count and the time (simulated under both).  ring [LAPS [BYTES]] */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

#include "mpibench.h"
#include <string.h>

int main(int argc, char **argv) {
  mpibench b;
  mpibench_init(&b, &argc, &argv);
  int r = b.r, p = b.p;
  long laps = mpibench_arg(&b, 1, 62500);
  int bytes = (int)mpibench_arg(&b, 2, 8);
  char *buf = calloc((size_t)bytes + 8, 1);
  long long token = 0;
  double t0 = MPI_Wtime();
  for (long k = 0; k < laps; k++) {
    if (r == 0) {
      token++;
      memcpy(buf, &token, sizeof token);
      MPI_Send(buf, bytes, MPI_BYTE, 1 % p, 0, MPI_COMM_WORLD);
      MPI_Recv(buf, bytes, MPI_BYTE, p - 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      memcpy(&token, buf, sizeof token);
    } else {
      MPI_Recv(buf, bytes, MPI_BYTE, r - 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      memcpy(&token, buf, sizeof token);
      token++;
      memcpy(buf, &token, sizeof token);
      MPI_Send(buf, bytes, MPI_BYTE, (r + 1) % p, 0, MPI_COMM_WORLD);
    }
  }
  double t = MPI_Wtime() - t0;
  if (r == 0) printf("ring: %d ranks, %ld laps: token %lld, %.17g s\n", p, laps, token, t);
  free(buf);
  MPI_Finalize();
  return 0;
}
