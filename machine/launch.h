/* launch.h -- running an mp program (mp.h) on a machine (machine.h): the
 * simulator, threads or MPI, with its trace and statistics.
 *
 * Rank r runs procs[r].main(self, procs[r].ud).  On the simulator rank r
 * runs on the processor machine_place gives it (ranks may outnumber
 * processors); on threads and MPI the operating system places them.  The
 * machine's --trace (simulator only) is written beside its target and
 * renamed into place when the run has succeeded and the trace is within
 * --trace-limit; otherwise no file is left. */
#ifndef LAUNCH_H
#define LAUNCH_H

#include <stddef.h>

#include "machine/machine.h"
#include "machine/tilesim.h"
#include "mp/stats.h"

/* The simulator of mc for nranks ranks, placed by machine_place (no trace:
 * launch_run adds mc's).  NULL and a message if it cannot be built. */
sim *launch_sim_new(const machine_config *mc, int nranks, char *err, size_t errlen);

/* Run procs[0..nranks-1] on mc's backend.  *st (may be NULL) gets the
 * statistics, also when the run fails.  0, or -1 and a message in err: a
 * deadlock, an error of a rank, an abort, a machine that cannot be built (a
 * topology too small, a placement file that does not fit), a trace over its
 * limit or one that cannot be written, --trace or --topology on a real
 * backend.  On MPI, nranks must be the size of the mpirun and this process
 * runs only its own rank; rank 0's statistics are the whole run's. */
int launch_run(const machine_config *mc, int nranks, const mp_proc *procs, tilesim_stats *st,
               char *err, size_t errlen);

/* Into *st: the figures every backend counts of a run (mp/stats.h: the
 * messages, bytes and unread ones, a deadlock, an abort's code). */
void launch_stats_run(tilesim_stats *st, const mp_stats *run);

#endif
