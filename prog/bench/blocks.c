/* blocks.c -- what a basic block of an MPI program costs on this host
 * (bench --calibrate; tilesim-mpirun --compute blocks charges --block-c
 * seconds a block).  This file alone is compiled with
 * -fsanitize-coverage=trace-pc, as tilesim-mpicc --count-blocks compiles a
 * program: the loop below, cpi's (MPICH's example), counts its own blocks
 * through the counter micro.c keeps. */
#include "prog/bench/blocks.h"

double blocks_cpi(long n) {
  double h = 1.0 / (double)n, sum = 0;
  for (long i = 1; i <= n; i++) {
    double x = h * ((double)i - 0.5);
    sum += 4.0 / (1.0 + x * x);
  }
  return h * sum;
}
