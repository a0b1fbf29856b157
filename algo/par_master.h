/* par_master.h -- the master of the parallel algorithm (paper, sections 4, 5
 * and 7): it distributes the points, runs the divide and conquer over groups
 * of slaves, assembles the paths backtracked to it, restricts the graph and
 * splits the groups. */
#ifndef PAR_MASTER_H
#define PAR_MASTER_H

#include "mp.h"
#include "par.h"
#include "tiling.h"

typedef struct {
  /* In: one pair of contours. */
  const vec2 *P;
  int np;
  double zp;
  const vec2 *Q;
  int nq;
  double zq;
  /* Out. */
  tiling t;            /* the optimum and its path, as tiling_solve gives it;
                          t.count.nodes and t.count.paths summed over the slaves */
  double time;         /* the master's clock from sending the points to holding the
                          optimum (simulated seconds on the simulator) */
  double mu0_time;     /* the slaves' time on the diagonals of mu(0): from the
                          first one's task to the last one's last diagonal */
  par_counts counts;   /* every rank's counters for this pair, master included */
  par_counts master;   /* the master's own */
} par_pair;

typedef struct {
  int npairs;
  par_pair *pairs;
  cost_kind kind;
  par_options opt;
  int failed;          /* 1 if an mp call failed */
  char err[160];
  /* Optional: called after each pair (on the host, for a progress line). */
  void (*progress)(void *ud, int done, int total);
  void *progress_ud;
} par_master_arg;

/* The master's main: ud is a par_master_arg.  The slaves are ranks
 * 1 .. mp_size-1; at the end they are told to quit. */
void par_master(mp *self, void *ud);

#endif
