/* stublib.c -- libtilesim_mpi.so, the library every program tilesim-mpicc
 * links is linked against, as an MPI library's programs are against its
 * libmpi.so.
 *
 * It defines every name tilesim-mpirun gives programs (mpi.h's functions
 * and their PMPI_ names, implemented or not; the predefined attribute
 * callbacks; the compute calls; SimGrid's file-system calls; the
 * basic-block counter of --count-blocks),
 * so that the linker refuses a program that calls a function tilesim has
 * never heard of, naming it, as it would with any MPI.  tilesim-mpirun never
 * loads this library: it provides the names itself.  A program run on its
 * own (./prog) loads it, and its constructor says how to run the program
 * and exits with status 2 before any of the program's code runs. */
#include <string.h>
#include <unistd.h>

#include "mpi/io_sg.h"
#include "mpi/mpi.h"

void __sanitizer_cov_trace_pc(void);

static void say(const char *s) {
  size_t n = strlen(s);
  while (n > 0) {
    ssize_t w = write(2, s, n);
    if (w <= 0) return;
    s += w;
    n -= (size_t)w;
  }
}

/* glibc gives a library's constructors the program's arguments. */
__attribute__((constructor)) static void run_alone(int argc, char **argv) {
  const char *name = argc > 0 && argv && argv[0] ? argv[0] : "PROGRAM";
  say(name);
  say(": an MPI program built for tilesim's simulated machine: run it with\n"
      "  tilesim-mpirun -np N ");
  say(name);
  say("\n");
  _exit(2);
}

static _Noreturn void called(void) {
  say("tilesim: an MPI function was called outside tilesim-mpirun\n");
  _exit(2);
}

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#define TSMPI_FN(impl, chapter, ret, name, params, args) \
  ret name params { called(); }                          \
  ret P##name params { called(); }
#include "mpi/mpi_funcs.h"
#undef TSMPI_FN

void tilesim_compute(double units) { called(); }
void smpi_execute_flops(double flops) { called(); }
void smpi_execute(double seconds) { called(); }
void smpi_execute_benched(double seconds) { called(); }
void __sanitizer_cov_trace_pc(void) { called(); }
io_sg_file *sg_file_open(const char *fullpath, void *data) { called(); }
void sg_file_close(io_sg_file *fd) { called(); }
void sg_file_unlink(io_sg_file *fd) { called(); }
const char *sg_file_get_name(const io_sg_file *fd) { called(); }
unsigned long long sg_file_get_size(const io_sg_file *fd) { called(); }
