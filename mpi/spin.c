/* spin.c -- a rank that polls forever (spin.h). */
#include "mpi/spin.h"

#include <stdio.h>

#include "mpi/init.h"

void spin_count(st_rank *R, const char *fn) {
  double t = mp_time(R->self);
  if (t != R->spin_t) {
    R->spin_t = t;
    R->spins = 0;
  }
  if (++R->spins < SPIN_MAX) return;
  char why[400];
  snprintf(why, sizeof why,
           "rank %d: %s called %d times at t=%.9g s without the rank's clock moving: nothing can arrive, it would "
           "poll forever (a polling loop needs a --poll-cost above 0, a loop on the clock a --wtime-cost); run stopped",
           R->wrank, fn, SPIN_MAX, t);
  mp *self = R->self;
  st_release(R);
  mp_set_user(self, INIT_MARK_STOPPED);
  mp_abort(self, 1, why);
}
