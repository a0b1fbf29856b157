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
 * whose trips vary counts its failures and checks once.
 *
 * TILESIM is 1 under tilesim's mpi.h, 0 under another MPI's; SCHECK is a
 * check that counts only when it fails (for what only some MPIs do, so that
 * the summary lines still agree).  mtest_main is a program's whole main:
 * its checks are a table of functions. */
#ifndef MTEST_H
#define MTEST_H

#include <mpi.h>
#include <stdio.h>

#ifdef TSMPI_MPI_H
#define TILESIM 1
#else
#define TILESIM 0
#endif

typedef struct {
  const char *name;
  const char *arg;   /* the program's first argument, or NULL (set by mtest_begin) */
  int rank, size;
  int passed, failed;
  MPI_Comm comm;   /* the counts' own communicator */
} mtest;

static inline void mtest_init(mtest *t, const char *name) {
  t->name = name;
  t->arg = NULL;
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

#define SCHECK(t, cond, ...)                  \
  do {                                        \
    if (!(cond)) MCHECK(t, 0, __VA_ARGS__);   \
  } while (0)

static inline int mtest_done(mtest *t) {
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

/* A check that group g (freed here) is MPI_COMM_WORLD's. */
static inline void mtest_world_group(mtest *t, MPI_Group g, const char *what) {
  MPI_Group w;
  int same = -1;
  MPI_Comm_group(MPI_COMM_WORLD, &w);
  MPI_Group_compare(g, w, &same);
  MCHECK(t, same == MPI_IDENT, "%s against MPI_COMM_WORLD's: %d", what, same);
  MPI_Group_free(&g);
  MPI_Group_free(&w);
}

/* One part of a program's checks, run by mtest_main. */
typedef void (*mtest_fn)(mtest *t);

enum {
  MTEST_ERRORS_RETURN = 1,   /* MPI_ERRORS_RETURN on MPI_COMM_WORLD before the checks */
  MTEST_BARRIER = 2          /* a barrier after them (requests the checks left are done) */
};

/* A program's start: MPI_Init and mtest_init; on fewer than min_ranks
 * ranks, rank 0 says "NAME: needs N ranks or more", MPI_Finalize, and 0;
 * else the settings of flags, and 1. */
static inline int mtest_begin(mtest *t, int *argc, char ***argv, const char *name, int min_ranks, int flags) {
  MPI_Init(argc, argv);
  mtest_init(t, name);
  t->arg = *argc > 1 ? (*argv)[1] : NULL;
  if (t->size < min_ranks) {
    if (t->rank == 0) printf("%s: needs %d ranks or more\n", name, min_ranks);
    MPI_Comm_free(&t->comm);
    MPI_Finalize();
    return 0;
  }
  if (flags & MTEST_ERRORS_RETURN) MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  return 1;
}

/* A program's end: the flags' barrier, mtest_done, MPI_Finalize; what
 * main returns. */
static inline int mtest_end(mtest *t, int flags) {
  if (flags & MTEST_BARRIER) MPI_Barrier(MPI_COMM_WORLD);
  int rc = mtest_done(t);
  MPI_Finalize();
  return rc;
}

/* Markers in a table of mtest_main's: the functions after mtest_rank0 run
 * on rank 0 alone (the other ranks skip them), up to mtest_every_rank. */
static inline void mtest_rank0(mtest *t) { (void)t; }
static inline void mtest_every_rank(mtest *t) { (void)t; }

/* A program's main: mtest_begin, each function of the NULL-terminated
 * table in turn, mtest_end; 1 on too few ranks. */
static inline int mtest_main(int *argc, char ***argv, const char *name, int min_ranks, int flags,
                             const mtest_fn *fns) {
  mtest t;
  if (!mtest_begin(&t, argc, argv, name, min_ranks, flags)) return 1;
  int alone = 0;
  for (int i = 0; fns[i]; i++) {
    if (fns[i] == mtest_rank0 || fns[i] == mtest_every_rank)
      alone = fns[i] == mtest_rank0;
    else if (!alone || t.rank == 0)
      fns[i](&t);
  }
  return mtest_end(&t, flags);
}

#endif
