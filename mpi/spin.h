/* spin.h -- a rank that polls forever: MPI_Test, MPI_Iprobe, MPI_Wtime and
 * their kind called again and again without the rank's clock moving (a
 * poll cost and a wtime cost of 0, tilesim-mpirun's --poll-cost 0 and the
 * default --wtime-cost 0).  On the simulator nothing can arrive then: the
 * clock stands still and no other rank runs until this one waits.  After
 * SPIN_MAX such calls in a row the run stops with one line naming the
 * rank, the call and the clock:
 *   rank 1: MPI_Iprobe called 100000 times at t=0.25 s without the rank's
 *   clock moving: nothing can arrive, it would poll forever (a polling loop
 *   needs a --poll-cost above 0, or --wtime-cost for MPI_Wtime); run stopped
 * A call that finds something, or a clock that moves, starts the count
 * again. */
#ifndef TSMPI_SPIN_H
#define TSMPI_SPIN_H

#include "mpi/state.h"

enum { SPIN_MAX = 100000 };

/* A poll of call fn found nothing (after charging its cost, if any). */
void spin_count(st_rank *R, const char *fn);

/* The same for a rank outside MPI (before MPI_Init, after MPI_Finalize):
 * its reads of the clock. */
void spin_count_outside(mp *self, const char *fn);

/* A poll found something. */
static inline void spin_reset(st_rank *R) { R->spins = 0; }

#endif
