/* par_slave.h -- a slave of the parallel algorithm (paper, sections 4 and 5):
 * it computes its runs of each diagonal, trades run-boundary costs with its
 * neighbours, takes part in backtracking, and solves whole bands alone when
 * its group has one slave. */
#ifndef PAR_SLAVE_H
#define PAR_SLAVE_H

#include "mp.h"
#include "par.h"

typedef struct {
  /* Filled by the slave: */
  par_counts counts;   /* since the last STATS report */
  par_counts total;    /* since the start */
  double fp_start, fp_end;   /* the first path of the current pair: when its
                                task came, when my last diagonal was done */
  int failed;          /* 1 if an mp call failed (deadlock, stop) */
  char err[160];
  /* Optional, for tests: if diag_sends is set, the BOUNDARY messages this
   * slave sends for each diagonal t = 0..diag_len-1 of the first path of
   * the run are added to diag_sends[t], and those it receives to
   * diag_recvs[t] (either may be NULL). */
  int *diag_sends, *diag_recvs;
  int diag_len;
} par_slave_arg;

/* The slave's main: ud is a par_slave_arg.  Serves pairs until QUIT. */
void par_slave(mp *self, void *ud);

#endif
