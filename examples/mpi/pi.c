/* pi.c -- an MPI program to start from: pi as the integral of 4 / (1 + x^2)
 * over [0, 1] by the midpoint rule, the intervals dealt round the ranks,
 * the parts summed on rank 0 by MPI_Reduce.  Plain MPI: it builds with any
 * mpicc, and with tilesim-mpicc for the simulated machine:
 *
 *   ./tilesim-mpicc examples/mpi/pi.c -o pi
 *   ./tilesim-mpirun -np 16 --topology torus:4x4 ./pi [INTERVALS]
 *
 * Rank 0 prints the sum, its distance from pi, and the time the run took
 * (simulated seconds under tilesim-mpirun; the same every run). */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int rank, size;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  long n = 1000000;
  if (argc > 1) {
    char *end;
    n = strtol(argv[1], &end, 10);
    if (*end || n < 1) {
      if (rank == 0) fprintf(stderr, "pi: INTERVALS is a whole number from 1 up (%s)\n", argv[1]);
      MPI_Abort(MPI_COMM_WORLD, 2);
    }
  }
  double t0 = MPI_Wtime(), h = 1.0 / (double)n, part = 0;
  for (long i = rank; i < n; i += size) {   /* interval i: [i h, (i + 1) h] */
    double x = h * ((double)i + 0.5);
    part += 4.0 / (1.0 + x * x);
  }
  part *= h;
  double sum = 0;
  MPI_Reduce(&part, &sum, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  double t = MPI_Wtime() - t0;
  const double pi = 3.14159265358979323846;
  if (rank == 0)
    printf("pi is %.15f, %.1e from the true value: %ld intervals on %d ranks, %g s\n", sum, fabs(sum - pi), n,
           size, t);
  MPI_Finalize();
  return 0;
}
