/* wrapper.h -- tilesim-mpicc and tilesim-mpicxx: compile and link an MPI
 * program (C or C++) for tilesim-mpirun, as an MPI library's mpicc and
 * mpicxx do for it.
 *
 *   tilesim-mpicc [--count-blocks] [-show] [CC OPTIONS] FILES... [-o PROG]
 *
 * The arguments go to the compiler ($TILESIM_CC, else cc; $TILESIM_CXX,
 * else c++; never $CC or $CXX, which a build may have set to this wrapper)
 * with tilesim's mpi.h on the include path, position-independent code and
 * each function in a section of its own.  With -c, -S, -E, -M or -MM it
 * only compiles; with -shared it links a shared library as the compiler
 * does.  Otherwise it links a position-independent executable against
 * libtilesim_mpi.so (mpirun/stublib.c), so that a function tilesim does not
 * have fails the link, named by the linker; laid out for tilesim-mpirun's
 * loader (mpirun/loader.h: a wide gap between code and data, one writable
 * segment, main exported) with the sections no code reaches dropped; then
 * it lists the MPI functions the program's code calls that tilesim does
 * not implement (a warning: the run stops if it calls one).
 *
 * -show (MPICH), -showme and --showme (Open MPI) print the command instead
 * of running it; --showme:compile and --showme:link the flags added to
 * compiling and to linking; -compile_info and -link_info the command of
 * each.  A compiler that runs the wrapper again (TILESIM_CC naming it, or a
 * script that calls it) is refused, with exit status 2, instead of running
 * without end.  The exit status is the compiler's; 2 for bad usage. */
#ifndef TSMPI_WRAPPER_H
#define TSMPI_WRAPPER_H

typedef enum { WRAP_C, WRAP_CXX } wrap_lang;

/* The whole program: main's argc and argv. */
int wrapper_main(int argc, char **argv, wrap_lang lang);

#endif
