/* mpibench.h -- the start the benchmark's MPI programs (allreduce.c,
 * alltoall.c, bcast.c, bw.c, ring.c) share: MPI_Init, the rank and the number of
 * ranks, the numeric arguments by position with their defaults, and the
 * refusal of bad ones (one line from rank 0 on stderr, MPI_Abort with 2).
 * Plain MPI C, header only: tilesim-mpicc and smpicc build the programs
 * from their one source file. */
#ifndef MPIBENCH_H
#define MPIBENCH_H

#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct {
  int r, p;   /* this rank, the number of ranks */
  int argc;
  char **argv;
} mpibench;

static inline void mpibench_init(mpibench *b, int *argc, char ***argv) {
  MPI_Init(argc, argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &b->r);
  MPI_Comm_size(MPI_COMM_WORLD, &b->p);
  b->argc = *argc;
  b->argv = *argv;
}

/* Argument i (1 is the first), or dflt where there are fewer. */
static inline long mpibench_arg(const mpibench *b, int i, long dflt) {
  return b->argc > i ? atol(b->argv[i]) : dflt;
}

/* Where bad, rank 0 says "NAME: RULE" and the run aborts with 2. */
static inline void mpibench_refuse(const mpibench *b, int bad, const char *name, const char *rule) {
  if (!bad) return;
  if (b->r == 0) fprintf(stderr, "%s: %s\n", name, rule);
  MPI_Abort(MPI_COMM_WORLD, 2);
}

/* The end the checked programs share (alltoall.c, bcast.c): every rank's
 * checksum and count of wrong items summed at rank 0 (an MPI_Reduce), which
 * prints "NAME: P ranks, SIZE bytes, ITERS iterations: checksum C, T s" or
 * "NAME: wrong: N WRONG"; main's exit status (rank 0: 1 if anything was
 * wrong). */
static inline int mpibench_report(const mpibench *b, const char *name, uint64_t sum, uint64_t bad, const char *wrong,
                                  long size, long iters, double t) {
  uint64_t mine[2] = {sum, bad}, all[2] = {0, 0};
  MPI_Reduce(mine, all, 2, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
  if (b->r == 0 && all[1] != 0) printf("%s: wrong: %llu %s\n", name, (unsigned long long)all[1], wrong);
  if (b->r == 0 && all[1] == 0)
    printf("%s: %d ranks, %ld bytes, %ld iterations: checksum %llu, %.17g s\n", name, b->p, size, iters,
           (unsigned long long)all[0], t);
  return all[1] != 0;
}

#endif
