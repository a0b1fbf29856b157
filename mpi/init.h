/* init.h -- what the runner (tilesim-mpirun, a test driver) does with the MPI
 * layer's point-to-point part: per-run settings before the ranks start, and
 * each rank's end.
 *
 * THE RANKS.  Each rank runs the program's main through mp (sim_run or
 * mpt_run), so that mp_self() names it.  The layer keeps the rank's whole
 * state in mp_user(self), which must be NULL when main starts: MPI_Init
 * sets it, MPI_Finalize leaves a mark there (MPI_Finalized), and
 * init_rank_end clears it.  Nothing else may use that slot.
 *
 * A run stopped by one rank (MPI_Abort, an error under
 * MPI_ERRORS_ARE_FATAL: mp_abort with exit status 1, or the code given to
 * MPI_Abort) or by the simulator (a deadlock) ends every other rank inside
 * its next MPI call: its state is released and mp_exit never returns to
 * the program. */
#ifndef TSMPI_INIT_H
#define TSMPI_INIT_H

#include "mp/mp.h"

/* ==== per-run settings (before the ranks start; they are read by every
 * rank and written by none) ================================================ */

/* Seconds of processor time charged to a rank for each MPI_Test, Testany,
 * Testall, Testsome or MPI_Iprobe that finds nothing (mp_busy), so that a
 * polling loop moves the simulated clock and sees the messages that arrive
 * meanwhile (without it the simulator stops a rank that polls a million
 * times at one clock).  Default 1e-6 s; 0: none.  Returns -1 (and changes
 * nothing) for a negative or non-finite value. */
int init_set_poll_cost(double seconds);
double init_poll_cost(void);

/* Seconds charged by each MPI_Wtime (mp_busy), so that a loop that waits
 * for the clock ends.  Default 0 (MPI_Wtime reads the clock and costs
 * nothing, so closed forms over timed sections hold exactly).  -1 for a
 * negative or non-finite value. */
int init_set_wtime_cost(double seconds);

/* A read of the rank's clock by the program's call fn ("MPI_Wtime",
 * "gettimeofday", ...): the clock, the wtime cost charged after; a loop
 * that reads it SPIN_MAX times in a row without it moving is stopped,
 * naming fn (mpi/spin.h), as a polling loop is, inside MPI or out. */
double init_clock_read(mp *self, const char *fn);

/* ==== a rank's end ======================================================== */

enum {
  INIT_NEVER = 0,        /* it never called MPI_Init */
  INIT_FINALIZED = 1,    /* it called MPI_Init and MPI_Finalize */
  INIT_UNFINALIZED = 2   /* it called MPI_Init, not MPI_Finalize (or was stopped
                             inside an MPI call, its state already released) */
};

/* Call once a rank's main has returned (or the rank ended by mp_exit):
 * what it did with MPI, and every byte of its MPI state released
 * (mp_user(self) is NULL after).  A program that returns from main
 * without MPI_Finalize is erroneous: the runner reports it. */
int init_rank_end(mp *self);

/* --- private part: for the layer's own files ------------------------------ */

/* The marks mp_user holds after MPI_Finalize and after a stop (INIT_MARK_*)
 * are state.h's: st_need tests them inline. */

#endif
