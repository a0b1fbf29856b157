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

/* What a caller adds to a run beyond mc's options (launch_run_with).  Zero
 * it, then set what the run needs. */
typedef struct {
  FILE *trace_csv, *trace_json;   /* the simulator's timeline into these streams
                                     (the caller's to close), or NULL; with
                                     either, mc->trace must be NULL */
  int count_csv, count_json;      /* the simulator counts the bytes a trace of
                                     these kinds would take, writing none */
  unsigned long long csv_bytes, json_bytes;   /* out: the bytes counted */
  net_stats *periods;             /* the simulator on a topology: the network's
                                     statistics of each period of the run
                                     (launch_period_end), nperiods of them,
                                     zeroed first; or NULL */
  int nperiods;
  void (*next)(void *ud, int done, int total);   /* launch_period_end calls it
                                                   after, or NULL */
  void *next_ud;
  sim_stats *sim;                 /* out, or NULL: the simulator's statistics */
  mpt_stats *threads;             /* out, or NULL: the threads backend's */
  links *links;                   /* the run's network, while it runs (set by
                                     the launcher; NULL without a topology) */
} launch_extra;

/* A progress callback for a rank of the program to call (ud: the
 * launch_extra) as period `done` of `total` ends, on the host, with all that
 * period's messages sent: the network's statistics since the previous
 * period into periods[done - 1] (on a topology, with periods), then
 * next(next_ud, done, total). */
void launch_period_end(void *ud, int done, int total);

/* Run procs[0..nranks-1] on mc's backend.  *st (may be NULL) gets the
 * statistics, also when the run fails.  0, or -1 and a message in err: a
 * deadlock, an error of a rank, an abort, a machine that cannot be built (a
 * topology too small, a placement file that does not fit), a trace over its
 * limit or one that cannot be written, --trace or --topology on a real
 * backend.  On MPI, nranks must be the size of the mpirun and this process
 * runs only its own rank; rank 0's statistics are the whole run's. */
int launch_run(const machine_config *mc, int nranks, const mp_proc *procs, tilesim_stats *st,
               char *err, size_t errlen);

/* The same with what x adds (x may be NULL: launch_run). */
int launch_run_with(const machine_config *mc, int nranks, const mp_proc *procs, launch_extra *x,
                    tilesim_stats *st, char *err, size_t errlen);

/* A run as one value, for a caller that hands the launching to code that
 * knows only mp.h (a program's composition of an algorithm and a machine):
 * launch_job_run(job, nranks, procs, err, errlen) is
 * launch_run_with(job->mc, nranks, procs, job->x, job->st, err, errlen). */
typedef struct {
  const machine_config *mc;
  launch_extra *x;    /* or NULL */
  tilesim_stats *st;  /* or NULL */
} launch_job;

int launch_job_run(void *job, int nranks, const mp_proc *procs, char *err, size_t errlen);

/* Into *st: the figures every backend counts of a run (mp/stats.h: the
 * messages, bytes and unread ones, a deadlock, an abort's code). */
void launch_stats_run(tilesim_stats *st, const mp_stats *run);

#endif
