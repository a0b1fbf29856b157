/* iotest.h -- what the MPI-IO programs of tests/mpi/ share: a fresh directory of the host's for
 * their files (rank 0 makes it under $TMPDIR and tells the others, so that it is one directory
 * under any MPI), the bytes of a file as plain C reads them (the independent check of what
 * MPI-IO wrote), and the directory's removal; iotest_main, an I/O program's whole main.  Plain C and MPI: it builds with tilesim's mpi.h
 * and with any MPI's mpicc; no globals (tilesim's driver runs every rank in one process). */
#ifndef IOTEST_H
#define IOTEST_H

#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mtest.h"

typedef struct {
  char dir[512];
} iotest;

/* A new directory, the same on every rank of MPI_COMM_WORLD (collective);
 * 0, or -1 if it could not be made (every rank sees the same). */
static inline int iotest_init(iotest *io, const char *name) {
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  memset(io->dir, 0, sizeof io->dir);
  if (rank == 0) {
    const char *tmp = getenv("TMPDIR");
    snprintf(io->dir, sizeof io->dir, "%s/%s.XXXXXX", tmp && *tmp ? tmp : "/tmp", name);
    if (!mkdtemp(io->dir)) io->dir[0] = '\0';
  }
  MPI_Bcast(io->dir, (int)sizeof io->dir, MPI_CHAR, 0, MPI_COMM_WORLD);
  return io->dir[0] ? 0 : -1;
}

/* The path of file `name` in the directory. */
static inline const char *iotest_path(const iotest *io, const char *name, char *buf, size_t len) {
  snprintf(buf, len, "%s/%s", io->dir, name);
  return buf;
}

/* File `name`'s bytes, at most cap into buf: how many, or -1 if it cannot
 * be read. */
static inline long iotest_read(const iotest *io, const char *name, void *buf, size_t cap) {
  char p[640];
  FILE *f = fopen(iotest_path(io, name, p, sizeof p), "rb");
  if (!f) return -1;
  size_t n = fread(buf, 1, cap, f);
  fclose(f);
  return (long)n;
}

/* 1 if file `name` exists. */
static inline int iotest_exists(const iotest *io, const char *name) {
  char p[640];
  struct stat st;
  return stat(iotest_path(io, name, p, sizeof p), &st) == 0;
}

/* Remove the files named (a NULL-terminated list) and the directory, on
 * rank 0 after every rank is done with them (collective). */
static inline void iotest_done(iotest *io, const char *const *names) {
  int rank;
  char p[640];
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0 || !io->dir[0]) return;
  for (int i = 0; names[i]; i++) remove(iotest_path(io, names[i], p, sizeof p));
  rmdir(io->dir);
}

/* File `name` of the directory opened by every rank, created if need be,
 * read and write (a failed check if not): the handle, or MPI_FILE_NULL. */
static inline MPI_File iotest_open(mtest *t, const iotest *io, const char *name) {
  char p[640];
  MPI_File fh = MPI_FILE_NULL;
  int rc = MPI_File_open(MPI_COMM_WORLD, iotest_path(io, name, p, sizeof p), MPI_MODE_CREATE | MPI_MODE_RDWR,
                         MPI_INFO_NULL, &fh);
  MCHECK(t, rc == MPI_SUCCESS, "open %s: rc %d", name, rc);
  return rc == MPI_SUCCESS ? fh : MPI_FILE_NULL;
}

/* One part of an I/O program's checks, on the program's directory. */
typedef void (*iotest_fn)(mtest *t, const iotest *io);

/* An I/O program's main: mtest_begin; a directory named for the program
 * (a failed check if it cannot be made, and nothing else), each function of
 * the NULL-terminated table on it in turn, and the files named (a
 * NULL-terminated list) and the directory removed; mtest_end. */
static inline int iotest_main(int *argc, char ***argv, const char *name, const iotest_fn *fns,
                              const char *const *files) {
  mtest t;
  iotest io;
  if (!mtest_begin(&t, argc, argv, name, 1, 0)) return 1;
  if (iotest_init(&io, name) != 0) {
    MCHECK(&t, 0, "no directory for the files under $TMPDIR");
  } else {
    for (int i = 0; fns[i]; i++) fns[i](&t, &io);
    iotest_done(&io, files);
  }
  return mtest_end(&t, 0);
}

#endif
