/* tilesim-mpicc.c -- compile and link an MPI C program for tilesim-mpirun.
 *
 *   tilesim-mpicc [--count-blocks] [-show] [CC OPTIONS] FILES... [-o PROG]
 *
 * As mpicc does for an MPI library: mpirun/wrapper.h says what it adds;
 * tilesim-mpicc(1) is its manual. */
#include "mpirun/wrapper.h"

int main(int argc, char **argv) { return wrapper_main(argc, argv, WRAP_C); }
