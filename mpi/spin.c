/* spin.c -- a rank that polls forever (spin.h). */
#include "mpi/spin.h"

#include <stdio.h>

#include "mpi/init.h"

/* The run's end for a rank that called fn SPIN_MAX times at clock t. */
static void stop(mp *self, int rank, const char *fn, double t) {
  char why[400];
  snprintf(why, sizeof why,
           "rank %d: %s called %d times at t=%.9g s without the rank's clock moving: nothing can arrive, it would "
           "poll forever (a polling loop needs a --poll-cost above 0, a loop on the clock a --wtime-cost); run stopped",
           rank, fn, SPIN_MAX, t);
  mp_abort(self, 1, why);
}

void spin_count(st_rank *R, const char *fn) {
  double t = mp_time(R->self);
  if (t != R->spin_t) {
    R->spin_t = t;
    R->spins = 0;
  }
  if (++R->spins < SPIN_MAX) return;
  mp *self = R->self;
  int rank = R->wrank;
  st_release(R);
  mp_set_user(self, INIT_MARK_STOPPED);
  stop(self, rank, fn, t);
}

/* Outside MPI there is no rank state to count in: the thread's count, for
 * the rank that called last (the simulator runs every rank on one thread,
 * and a rank that spins calls nothing else meanwhile; threads, one rank
 * each). */
static _Thread_local struct {
  int rank;
  double t;
  long n;
} outside = {-1, 0, 0};

void spin_count_outside(mp *self, const char *fn) {
  double t = mp_time(self);
  int rank = mp_rank(self);
  if (rank != outside.rank || t != outside.t) {
    outside.rank = rank;
    outside.t = t;
    outside.n = 0;
  }
  if (++outside.n >= SPIN_MAX) stop(self, rank, fn, t);
}
