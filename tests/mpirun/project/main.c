/* main.c -- a 1-D heat equation, split among the ranks: the project's
 * program.  heat [STEPS] */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

#include "stats.h"

enum { N = 64 };

int main(int argc, char **argv) {
  int rank, size, steps = argc > 1 ? atoi(argv[1]) : 50;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  double u[N + 2] = {0}, nu[N + 2];
  for (int i = 1; i <= N; i++) u[i] = (rank * N + i) % 17 == 0 ? 100.0 : 0.0;
  int left = rank > 0 ? rank - 1 : MPI_PROC_NULL, right = rank < size - 1 ? rank + 1 : MPI_PROC_NULL;
  for (int s = 0; s < steps; s++) {
    MPI_Sendrecv(&u[1], 1, MPI_DOUBLE, left, 0, &u[N + 1], 1, MPI_DOUBLE, right, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Sendrecv(&u[N], 1, MPI_DOUBLE, right, 1, &u[0], 1, MPI_DOUBLE, left, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    for (int i = 1; i <= N; i++) nu[i] = u[i] + 0.25 * (u[i - 1] - 2 * u[i] + u[i + 1]);
    for (int i = 1; i <= N; i++) u[i] = nu[i];
  }
  stats st = stats_of(&u[1], N, MPI_COMM_WORLD);
  if (rank == 0)
    printf("%d ranks, %d steps: min %.6f max %.6f mean %.6f norm %.6f\n", size, steps, st.min, st.max, st.mean, st.norm);
  MPI_Finalize();
  return 0;
}
