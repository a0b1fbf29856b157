/* launch_mpi.h -- launch_run's MPI backend (MPI builds only, make mpi), in
 * one of two worlds:
 *
 *   one rank a process: every process of the mpirun runs its own rank of the
 *   program (a user's program, machine/tilesim.h);
 *
 *   served (launch_mpi_main): process 0 runs the program's main, and each
 *   run it launches takes processes 0 .. nranks-1: process 0 runs procs[0],
 *   and processes 1 .. nranks-1, told so by a message, run the serving
 *   function given to launch_mpi_main (the others wait), then tell process 0
 *   how their part went.  When the main returns, every process is told to
 *   exit.  How ./tile-mpi and ./bench-mpi run the paper's algorithm:
 *
 *     mpirun -np N tile-mpi STACK ...
 */
#ifndef LAUNCH_MPI_H
#define LAUNCH_MPI_H

#include <stddef.h>

#include "machine/launch.h"

/* A served rank's part of a run: 0, or -1 and a message. */
typedef int launch_serve_fn(mp *self, char *err, size_t errlen);

/* MPI_Init; process 0 runs program(argc, argv), the others serve its runs
 * with serve until it is done; MPI_Finalize.  Returns this process's exit
 * status: the program's on process 0, 0 or 1 (a run failed here) on the
 * others. */
int launch_mpi_main(int argc, char **argv, int (*program)(int argc, char **argv),
                    launch_serve_fn *serve);

/* MPI must be initialised.  One rank a process: nranks must be the
 * mpirun's size; this process runs procs[its rank].  Rank 0's *st is the
 * whole run's (messages, bytes, unread, deadlock), the others' their own;
 * makespan is this process's wall-clock seconds in the run.  Served: on
 * process 0, nranks from 1 to the mpirun's size; procs[0] runs here, the
 * served ranks' entries are not used; the error is the backend's, then the
 * first served rank's (in rank order). */
int launch_mpi_run(const machine_config *mc, int nranks, const mp_proc *procs, tilesim_stats *st,
                   char *err, size_t errlen);

#endif
