/* tilesim-mpicxx.c -- compile and link an MPI C++ program for tilesim-mpirun.
 *
 *   tilesim-mpicxx [--count-blocks] [-show] [CXX OPTIONS] FILES... [-o PROG]
 *
 * As mpicxx does for an MPI library (the C bindings, as MPICH and Open MPI
 * ship them for C++): mpirun/wrapper.h says what it adds; tilesim-mpicxx(1)
 * is its manual. */
#include "mpirun/wrapper.h"

int main(int argc, char **argv) { return wrapper_main(argc, argv, WRAP_CXX); }
