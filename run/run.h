/* run.h -- running the parallel algorithm (algo/par_*.c) on a backend: the
 * simulated machine (sim/) for now.  The algorithm itself knows nothing of
 * what runs it; this is where ranks meet processors. */
#ifndef RUN_H
#define RUN_H

#include <stdio.h>

#include "par_master.h"
#include "sim.h"

typedef struct {
  int procs;            /* P >= 1: P = 1 puts master and slave on one processor,
                           P >= 2 gives the master one and P-1 slaves one each */
  sim_config machine;   /* the machine model (procs and place are set here) */
  par_options opt;
  cost_kind kind;
  FILE *trace_csv, *trace_json;   /* a timeline, or NULL */
  int *diag_sends, *diag_recvs;   /* test hook, see par_slave.h (or NULL) */
  int diag_len;
} run_config;

/* The ranks for P processors: max(2, P). */
static inline int run_ranks(int procs) { return procs < 2 ? 2 : procs; }

/* Run the pairs on the simulated machine, one simulation for all of them
 * (each pair's time is its own: par_pair.time).  Returns 0, or -1 and a
 * message.  *stats (may be NULL) gets the simulator's statistics. */
int run_sim(const run_config *rc, par_pair *pairs, int npairs, sim_stats *stats, char *err,
            size_t errlen);

#endif
