/* closed.c -- one operation, timed by every rank from a common start at 0:
 * a ping-pong, or one collective (tests/cli_mpirun.sh compares each rank's
 * time with the closed form of the algorithm on --net ideal).
 *   closed OP BYTES: OP pingpong, barrier, bcast, allgather or allreduce;
 *   BYTES the message (per rank for allgather; a multiple of 8 for
 *   allreduce, on doubles).  Each rank prints "closed R: T" and checks the
 *   operation's result. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv) {
  int r, p, bad = 0;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  const char *op = argc > 1 ? argv[1] : "pingpong";
  int n = argc > 2 ? atoi(argv[2]) : 8;
  char *a = calloc((size_t)n * (size_t)p + 8, 1), *b = calloc((size_t)n * (size_t)p + 8, 1);
  double t0 = MPI_Wtime();
  if (strcmp(op, "pingpong") == 0) {
    if (r == 0) {
      MPI_Send(a, n, MPI_BYTE, 1, 0, MPI_COMM_WORLD);
      MPI_Recv(a, n, MPI_BYTE, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    } else if (r == 1) {
      MPI_Recv(a, n, MPI_BYTE, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Send(a, n, MPI_BYTE, 0, 0, MPI_COMM_WORLD);
    }
  } else if (strcmp(op, "barrier") == 0) {
    MPI_Barrier(MPI_COMM_WORLD);
  } else if (strcmp(op, "bcast") == 0) {
    if (r == 0) memset(a, 7, (size_t)n);
    MPI_Bcast(a, n, MPI_BYTE, 0, MPI_COMM_WORLD);
    for (int i = 0; i < n; i++) bad += a[i] != 7;
  } else if (strcmp(op, "allgather") == 0) {
    memset(a, r + 1, (size_t)n);
    MPI_Allgather(a, n, MPI_BYTE, b, n, MPI_BYTE, MPI_COMM_WORLD);
    for (int i = 0; i < n * p; i++) bad += b[i] != i / n + 1;
  } else if (strcmp(op, "allreduce") == 0) {
    int k = n / 8;
    double *x = (double *)a, *y = (double *)b;
    for (int i = 0; i < k; i++) x[i] = r + i;
    MPI_Allreduce(x, y, k, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    for (int i = 0; i < k; i++) bad += y[i] != (double)p * (p - 1) / 2 + (double)p * i;
  }
  double t = MPI_Wtime() - t0;
  printf("closed %d: %.17g%s\n", r, t, bad ? " WRONG" : "");
  free(a);
  free(b);
  MPI_Finalize();
  return bad != 0;
}
