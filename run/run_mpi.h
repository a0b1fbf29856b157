/* run_mpi.h -- the programs' MPI build: rank 0 runs the program, the other
 * processes serve as the parallel algorithm's slaves (mp/mp_mpi.h).  Built
 * only by mpicc (make mpi), with -DTILESIM_MPI.
 *
 *   mpirun -np N tile-mpi STACK ...
 *
 * Process 0 runs the program's usual main (reads the input, prints the
 * report, writes the mesh).  Each time it runs pairs on the MPI backend
 * (run_pairs with MACHINE_MPI) it sends RUN(k) to processes 1 .. k-1, k =
 * max(2, P): they become the slaves of that run (the others wait), and
 * tell it how their part went.  When process 0's main returns, it sends
 * EXIT to all; each process returns the exit status to give. */
#ifndef RUN_MPI_H
#define RUN_MPI_H

#include <stddef.h>

#include "run/run.h"

/* MPI_Init; process 0 runs program(argc, argv), the others serve runs until
 * process 0 is done; MPI_Finalize.  Returns this process's exit status:
 * the program's on process 0, 0 or 1 (a run failed here) on the others. */
int run_mpi_main(int argc, char **argv, int (*program)(int argc, char **argv));

/* The number of MPI processes (0 before run_mpi_main). */
int run_mpi_size(void);

/* Process 0: the pairs on the first max(2, rc->procs) processes (see
 * run_pairs).  0, or -1 and a message (the whole run's errors). */
int run_mpi_pairs(const run_config *rc, par_pair *pairs, int npairs, char *err, size_t errlen);

#endif
