/* loader.h -- a program built by tilesim-mpicc, loaded once for all the
 * ranks, each rank with its own copy of the program's writable data (its
 * globals and statics, its GOT) and of its thread-local variables.
 *
 * The program's read-only part (code, constants, unwind tables) is mapped
 * from one anonymous memory file (memfd_create; where Linux has none, a file
 * in $TMPDIR removed as soon as it is mapped, also when a signal ends the
 * loading: nothing is left on any disk) at one address per rank, at a fixed
 * distance from that rank's writable copy, which the code reaches by
 * PC-relative addressing.  tilesim-mpicc links programs with a wide gap
 * between the two parts, so that the ranks' read-only copies lie side by
 * side, as do their writable copies: each group of ranks costs one kernel
 * mapping for its writable copies and a few for its read-only ones (the
 * read-only part is repeated a few times in the memory file when the ranks
 * are many, so that the mappings stay well under vm.max_map_count).  A
 * program linked otherwise is loaded too, at two mappings a rank.
 *
 * The loader relocates the writable part itself, once, into a template; a
 * rank's copy is the template's non-zero pages, its own addresses added
 * where the program holds addresses of itself, and the addresses of its own
 * getopt variables where the program names them (mpirun/libc.h).  Every
 * name the program imports is bound once: its own definitions first, then
 * the per-rank libc (mpirun/libc.h) and C++ runtime (mpirun/cxx.h) names,
 * then what tilesim-mpirun exports (MPI_*, PMPI_*, tilesim_compute,
 * smpi_*) and the libraries (libc, and those the program needs, such as
 * libstdc++, loaded once for all ranks); a name nothing defines is an error
 * before any rank runs, naming it.  Its C++ exception tables are registered
 * with the unwinder, every rank's copy at its address.  The program's
 * thread-local variables get a block per rank, made when the rank first
 * uses one. */
#ifndef TSMPI_LOADER_H
#define TSMPI_LOADER_H

#include <stddef.h>

typedef int (*loader_main_fn)(int argc, char **argv, char **envp);

typedef struct loader loader;

/* The program at path, for n ranks (rlibc_setup(n, ...) first: the
 * ranks' getopt variables are bound now).  NULL and a message naming the
 * program and what is wrong (a name nothing defines, a library that cannot
 * be loaded, a layout that would need more kernel mappings than the system
 * allows, no memory).  One loader at a time. */
loader *loader_new(const char *path, int n, char *err, size_t errlen);

/* Rank r starts (on its own thread or coroutine, before its main): its
 * writable copy is made and the program's constructors run in it, given
 * argc, argv and envp.  Returns the rank's main. */
loader_main_fn loader_start(loader *l, int r, int argc, char **argv, char **envp);

/* Rank r ends (main returned with status, or it called exit(status)): its
 * exit handlers, then the program's destructors, on its own thread or
 * coroutine; once only, however often it is called. */
void loader_finish(loader *l, int r, int status);

/* 1 if the program uses a C++ runtime (it needs libstdc++ or libc++). */
int loader_cxx(const loader *l);

/* A name defined by the libraries the program needs (e.g. libstdc++'s
 * __cxa_get_globals), or NULL. */
void *loader_library_symbol(const loader *l, const char *name);

/* How many kernel mappings the loaded program takes, and how many copies of
 * its read-only part the memory file holds (for the man page's bounds and
 * the benchmark). */
void loader_counts(const loader *l, long *mappings, int *copies);

/* Unmap everything (after the run; no rank may run the program any more). */
void loader_free(loader *l);

#endif
