/* simrun.h -- the tests' runs of one main on the simulator: a quiet
 * configuration with exact binary-fraction costs, and n ranks of one main
 * run on it. */
#ifndef SIMRUN_H
#define SIMRUN_H

#include <stddef.h>

#include "mp/mp.h"
#include "sim/sim.h"

/* net with procs processors, no warnings, and costs that are binary
 * fractions (every simulated time exact): c 1/8, m 1/4, per_byte 1/16,
 * local 0, L 1/2, o 1/8, g 1/16, G 1/32; a test changes what it needs. */
sim_config simrun_config(sim_net net, int procs);

/* n ranks of fn, each with ud, on cfg: the simulator after the run, for its
 * statistics (sim_free it); sim_run's answer in *rc, its message in err.  A
 * configuration sim_new refuses fails a check and aborts. */
sim *simrun(const sim_config *cfg, int n, mp_main fn, void *ud, int *rc, char *err, size_t errlen);

/* A token around the ring of ranks, laps times: each rank takes it from the
 * one before (rank 0 starts it), adds one, computes work units and passes it
 * on in a len-byte message (8 <= len <= 64).  bad is set by a failed call;
 * token is rank 0's count at the end (ranks x laps). */
typedef struct {
  int laps;
  double work;
  size_t len;
  long long token;
  int bad;
} simrun_ring;

void simrun_ring_main(mp *self, void *ud);

#endif
