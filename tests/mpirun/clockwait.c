/* clockwait.c -- a rank that waits a second of its clock by reading the
 * clock again and again (written for tests/cli_mpirun.sh): HOW 0 with
 * gettimeofday, 1 clock, 2 time, 3 clock_gettime, 4 MPI_Wtime; WHEN
 * "before" MPI_Init, "after" MPI_Finalize, or between them (the default).
 * Rank 0 prints how many reads the second took.  Under tilesim-mpirun the
 * clocks are the rank's simulated one: with --wtime-cost S each read costs
 * S (so 1/S reads), without it the clock cannot move and the run is
 * stopped.
 *   clockwait HOW [WHEN] */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <time.h>

/* The clock, in seconds, as call `how` reads it. */
static double read_clock(int how) {
  struct timeval tv;
  struct timespec ts;
  switch (how) {
  case 0: gettimeofday(&tv, NULL); return (double)tv.tv_sec + (double)tv.tv_usec * 1e-6;
  case 1: return (double)clock() / CLOCKS_PER_SEC;
  case 2: return (double)time(NULL);
  case 3: clock_gettime(CLOCK_MONOTONIC, &ts); return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
  default: return MPI_Wtime();
  }
}

/* Reads of the clock until it has moved a second. */
static long wait_second(int how) {
  double t0 = read_clock(how);
  long reads = 0;
  do reads++;
  while (read_clock(how) - t0 < 1);
  return reads;
}

int main(int argc, char **argv) {
  int how = argc > 1 ? atoi(argv[1]) : 0, r;
  const char *when = argc > 2 ? argv[2] : "";
  long reads = 0;
  if (strcmp(when, "before") == 0) reads = wait_second(how);
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  if (!*when) reads = wait_second(how);
  MPI_Finalize();
  if (strcmp(when, "after") == 0) reads = wait_second(how);
  if (r == 0) printf("waited a second in %ld reads\n", reads);
  return 0;
}
