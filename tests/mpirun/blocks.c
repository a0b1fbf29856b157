/* blocks.c -- cpi's loop between two clock readings, for --compute blocks
 * (tests/cli_mpirun.sh): built with tilesim-mpicc --count-blocks -O2 the loop
 * is one basic block an iteration, so with --block-c 1 the time between the
 * readings grows by exactly one second an interval.  blocks N */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  long n = argc > 1 ? atol(argv[1]) : 1000;
  double h = 1.0 / (double)n, sum = 0;
  double t0 = MPI_Wtime();
  for (long i = 1; i <= n; i++) {
    double x = h * ((double)i - 0.5);
    sum += 4.0 / (1.0 + x * x);
  }
  double t1 = MPI_Wtime();
  printf("blocks: pi %.6f, %.17g s\n", h * sum, t1 - t0);
  MPI_Finalize();
  return 0;
}
