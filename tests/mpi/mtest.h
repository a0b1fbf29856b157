/* mtest.h -- checks for the self-checking MPI programs of tests/mpi/: plain
 * MPI C that builds with tilesim's mpi.h and with any MPI's mpicc.
 *
 * No globals (tilesim's test driver runs every rank in one process): the
 * counts live in an mtest on main's stack.  A failed check prints
 * "NAME: rank R: file:line: what" on stdout; mtest_done gathers the counts
 * at rank 0 (point-to-point only, on a duplicate of MPI_COMM_WORLD made by
 * mtest_init, so that no receive of the program's can take them), which
 * prints "NAME: P passed, F failed"; main returns mtest_done's answer: 1 on
 * rank 0 if any rank failed a check, else 0.  A check's count must not
 * depend on timing (the line is compared between MPI libraries): a loop
 * whose trips vary counts its failures and checks once. */
#ifndef MTEST_H
#define MTEST_H

#include <mpi.h>
#include <stdio.h>

typedef struct {
  const char *name;
  int rank, size;
  int passed, failed;
  MPI_Comm comm;   /* the counts' own communicator */
} mtest;

static void mtest_init(mtest *t, const char *name) {
  t->name = name;
  t->passed = t->failed = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &t->rank);
  MPI_Comm_size(MPI_COMM_WORLD, &t->size);
  MPI_Comm_dup(MPI_COMM_WORLD, &t->comm);
}

#define MCHECK(t, cond, ...)                                                          \
  do {                                                                                \
    if (cond) {                                                                       \
      (t)->passed++;                                                                  \
    } else {                                                                          \
      (t)->failed++;                                                                  \
      printf("%s: rank %d: %s:%d: ", (t)->name, (t)->rank, __FILE__, __LINE__);       \
      printf(__VA_ARGS__);                                                            \
      printf("\n");                                                                   \
      fflush(stdout);                                                                 \
    }                                                                                 \
  } while (0)

static int mtest_done(mtest *t) {
  int counts[2] = {t->passed, t->failed};
  if (t->rank != 0) {
    MPI_Send(counts, 2, MPI_INT, 0, 0, t->comm);
    MPI_Comm_free(&t->comm);
    return 0;
  }
  for (int r = 1; r < t->size; r++) {
    int other[2];
    MPI_Recv(other, 2, MPI_INT, r, 0, t->comm, MPI_STATUS_IGNORE);
    counts[0] += other[0];
    counts[1] += other[1];
  }
  MPI_Comm_free(&t->comm);
  printf("%s: %d passed, %d failed\n", t->name, counts[0], counts[1]);
  fflush(stdout);
  return counts[1] > 0;
}

#endif
