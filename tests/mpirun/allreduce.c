/* allreduce.c -- MPI_Allreduce (sum) of COUNT 64-bit integers, ITERS times
 * (written for tilesim's benchmark, tests/bench_mpi.sh): rank r contributes
 * r + i + it at index i of iteration it, so every element of the result has
 * a closed form, p(p-1)/2 + p(i + it), which every rank checks.  Rank 0
 * prints a checksum (the sum of every result) and the time, or "wrong" and
 * exits 1 if any rank found an element off.  With COUNT 1 and ITERS 1 it
 * is a start-up: MPI_Init, one small collective, MPI_Finalize.
 *   allreduce [COUNT [ITERS]]     (default 1 1) */
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "mpibench.h"

int main(int argc, char **argv) {
  mpibench b;
  mpibench_init(&b, &argc, &argv);
  int r = b.r, p = b.p;
  long count = mpibench_arg(&b, 1, 1), iters = mpibench_arg(&b, 2, 1);
  mpibench_refuse(&b, count < 1 || iters < 1, "allreduce", "COUNT and ITERS >= 1");
  int64_t *in = malloc((size_t)count * sizeof *in), *out = malloc((size_t)count * sizeof *out);
  uint64_t sum = 0;
  int64_t bad = 0, pp = p;
  double t0 = MPI_Wtime();
  for (long it = 0; it < iters; it++) {
    for (long i = 0; i < count; i++) in[i] = r + i + it;
    MPI_Allreduce(in, out, (int)count, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
    for (long i = 0; i < count; i++) {
      bad += out[i] != pp * (pp - 1) / 2 + pp * (i + it);
      sum += (uint64_t)out[i];
    }
  }
  double t = MPI_Wtime() - t0;
  int64_t anybad = 0;
  MPI_Reduce(&bad, &anybad, 1, MPI_INT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
  int status = 0;
  if (r == 0) {
    if (anybad != 0) {
      printf("allreduce: wrong: %lld elements off their closed form\n", (long long)anybad);
      status = 1;
    } else {
      printf("allreduce: %d ranks, %ld integers, %ld iterations: checksum %llu, %.17g s\n", p, count, iters,
             (unsigned long long)sum, t);
    }
  }
  free(in);
  free(out);
  MPI_Finalize();
  return status;
}
