/* bcast.c -- MPI_Bcast of SIZE bytes from rank 0, ITERS times (written for
 * tilesim's benchmark, tests/bench_mpi.sh).  Iteration it's bytes hold it
 * and their offset at every 4096th byte and at the end; every rank checks
 * those marks and one byte between them, and adds the marks into a
 * checksum; rank 0 prints the sum over the ranks (an MPI_Reduce) and the
 * time, or "wrong" and exits 1 if a byte was not what the root sent.
 *   bcast [SIZE [ITERS]]     (default 16777216 3) */
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "mpibench.h"
#include <string.h>

static uint64_t mark(long it, long at) { return ((uint64_t)it << 40) + 2 * (uint64_t)at + 1; }

int main(int argc, char **argv) {
  mpibench b;
  mpibench_init(&b, &argc, &argv);
  int r = b.r;
  long size = mpibench_arg(&b, 1, 16777216), iters = mpibench_arg(&b, 2, 3);
  mpibench_refuse(&b, size < 32 || size > 1073741824 || iters < 1, "bcast", "SIZE from 32 to 2^30, ITERS >= 1");
  char *buf = malloc((size_t)size);
  memset(buf, r == 0 ? 'b' : 0, (size_t)size);
  uint64_t sum = 0, bad = 0;
  double t0 = MPI_Wtime();
  for (long it = 0; it < iters; it++) {
    if (r == 0) {
      for (long at = 0; at + 8 <= size; at += 4096) {
        uint64_t m = mark(it, at);
        memcpy(buf + at, &m, 8);
      }
      uint64_t m = mark(it, size - 8);
      memcpy(buf + size - 8, &m, 8);
    }
    MPI_Bcast(buf, (int)size, MPI_BYTE, 0, MPI_COMM_WORLD);
    for (long at = 0; at + 8 <= size; at += 4096) {
      uint64_t m;
      memcpy(&m, buf + at, 8);
      bad += m != mark(it, at);
      sum += m;
    }
    uint64_t m;
    memcpy(&m, buf + size - 8, 8);
    bad += m != mark(it, size - 8) || buf[12] != 'b';   /* between the first two marks */
    sum += m;
  }
  double t = MPI_Wtime() - t0;
  int status = mpibench_report(&b, "bcast", sum, bad, "marks were not what the root sent", size, iters, t);
  free(buf);
  MPI_Finalize();
  return status;
}
