/* loader.h -- a program built by tilesim-mpicc, loaded once per rank: each
 * rank its own copy of the program's globals and statics (SMPI's dlopen
 * privatization).
 *
 * The loader cannot open the same file twice (dlopen would give the copy it
 * has), so each rank's copy is a file of its own: an anonymous memory file
 * (memfd_create, opened as /proc/self/fd/N while every copy's is open),
 * where Linux has them; else a file in $TMPDIR (or /tmp), opened with
 * dlopen(RTLD_NOW | RTLD_LOCAL) and removed at once: the mapping stays, no
 * file does, also when a signal ends the loading (util/atomicfile).  The program's references to MPI_* and the
 * runtime (tilesim_mpi.h) bind to what tilesim-mpirun exports; it binds its
 * own names to its own definitions (tilesim-mpicc links with -Bsymbolic). */
#ifndef TSMPI_LOADER_H
#define TSMPI_LOADER_H

#include <stddef.h>

typedef int (*loader_main_fn)(int argc, char **argv);

typedef struct loader loader;

/* n copies of the shared object at path, each with its main.  NULL and a
 * message naming the rank and the loader's words (an undefined symbol, a
 * missing main, a file that cannot be written). */
loader *loader_new(const char *path, int n, char *err, size_t errlen);

/* Rank r's main (0 <= r < n). */
loader_main_fn loader_main(const loader *l, int r);

/* dlclose every copy. */
void loader_free(loader *l);

#endif
