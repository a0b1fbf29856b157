/* launch_mpi.h -- launch_run's MPI backend (MPI builds only, make mpi): every
 * process of the mpirun runs its own rank of the program (mp/mp_mpi.h). */
#ifndef LAUNCH_MPI_H
#define LAUNCH_MPI_H

#include <stddef.h>

#include "machine/launch.h"

/* MPI must be initialised.  nranks must be the mpirun's size; this process
 * runs procs[its rank].  Rank 0's *st is the whole run's (messages, bytes,
 * unread, deadlock), the others' their own; makespan is this process's
 * wall-clock seconds in the run. */
int launch_mpi_run(const machine_config *mc, int nranks, const mp_proc *procs, tilesim_stats *st,
                   char *err, size_t errlen);

#endif
