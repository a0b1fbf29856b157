/* alltoall.c -- MPI_Alltoall of SIZE bytes a pair, ITERS times (written for
 * tilesim's benchmark, tests/bench_mpi.sh; no code of the OSU suite).  The
 * block rank s sends rank d in iteration it holds s, d and it at both ends;
 * every rank checks every block it receives and adds its ends into a
 * checksum; rank 0 prints the sum over the ranks (an MPI_Reduce) and the
 * time, or "wrong" and exits 1 if a block was not what its sender wrote.
 *   alltoall [SIZE [ITERS]]     (default 262144 10) */
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "mpibench.h"
#include <string.h>

static uint64_t mark(int s, int d, long it, int end) {
  return ((uint64_t)s << 40) ^ ((uint64_t)d << 20) ^ (uint64_t)(it * 2 + end + 1);
}

int main(int argc, char **argv) {
  mpibench b;
  mpibench_init(&b, &argc, &argv);
  int r = b.r, p = b.p;
  long size = mpibench_arg(&b, 1, 262144), iters = mpibench_arg(&b, 2, 10);
  mpibench_refuse(&b, size < 16 || iters < 1, "alltoall", "SIZE >= 16 and ITERS >= 1");
  char *out = malloc((size_t)p * (size_t)size), *in = malloc((size_t)p * (size_t)size);
  memset(out, 'a' + r % 26, (size_t)p * (size_t)size);
  memset(in, 0, (size_t)p * (size_t)size);
  uint64_t sum = 0, bad = 0;
  double t0 = MPI_Wtime();
  for (long it = 0; it < iters; it++) {
    for (int d = 0; d < p; d++) {
      uint64_t a = mark(r, d, it, 0), b = mark(r, d, it, 1);
      memcpy(out + (size_t)d * size, &a, 8);
      memcpy(out + (size_t)d * size + size - 8, &b, 8);
    }
    MPI_Alltoall(out, (int)size, MPI_BYTE, in, (int)size, MPI_BYTE, MPI_COMM_WORLD);
    for (int s = 0; s < p; s++) {
      uint64_t a, b;
      memcpy(&a, in + (size_t)s * size, 8);
      memcpy(&b, in + (size_t)s * size + size - 8, 8);
      bad += a != mark(s, r, it, 0) || b != mark(s, r, it, 1) || in[(size_t)s * size + size / 2] != 'a' + s % 26;
      sum += a + b;
    }
  }
  double t = MPI_Wtime() - t0;
  int status = mpibench_report(&b, "alltoall", sum, bad, "blocks were not what their sender wrote", size, iters, t);
  free(out);
  free(in);
  MPI_Finalize();
  return status;
}
