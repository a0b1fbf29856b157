/* mpibench.h -- the start the benchmark's MPI programs (allreduce.c,
 * alltoall.c, bw.c, ring.c) share: MPI_Init, the rank and the number of
 * ranks, the numeric arguments by position with their defaults, and the
 * refusal of bad ones (one line from rank 0 on stderr, MPI_Abort with 2).
 * Plain MPI C, header only: tilesim-mpicc and smpicc build the programs
 * from their one source file. */
#ifndef MPIBENCH_H
#define MPIBENCH_H

#include <mpi.h>
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

#endif
