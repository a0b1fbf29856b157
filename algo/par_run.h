/* par_run.h -- the paper's algorithm as one mp program over pairs of
 * contours: the master (rank 0) and its slaves, built for a run, handed to
 * a launcher the caller gives (the machine: simulated, threads or MPI; see
 * machine/launch.h), and their failures collected.  This file knows the
 * machine only as that function.
 *
 * Ranks: P processors run max(2, P) ranks, rank 0 the master.  On the
 * simulator P = 1 puts master and slave on one simulated processor.  On
 * threads and MPI there is no processor to share: P = 1 and P = 2 both run
 * the master and one slave, and the operating system places them; the
 * times are real seconds. */
#ifndef PAR_RUN_H
#define PAR_RUN_H

#include <stddef.h>

#include "mp/mp.h"
#include "algo/par_config.h"
#include "algo/par_master.h"

/* The ranks for P processors: max(2, P). */
static inline int par_ranks(int procs) { return procs < 2 ? 2 : procs; }

/* Runs procs[0 .. nranks-1] somewhere: 0, or -1 and a message (the
 * backend's: a deadlock, a machine that cannot be built). */
typedef int par_launch_fn(void *ud, int nranks, const mp_proc *procs, char *err, size_t errlen);

typedef struct {
  const par_config *pc;
  double c;                /* the machine's seconds a node: the prices' unit */
  int procs;               /* P >= 1 processors: par_ranks(P) ranks */
  void (*progress)(void *ud, int done, int total);   /* the master's, on the
                                host, after each pair (its messages all
                                sent), or NULL */
  void *progress_ud;
  int *diag_sends, *diag_recvs;   /* test hook, see par_slave.h (or NULL) */
  int diag_len;
  par_launch_fn *launch;   /* runs the program */
  void *launch_ud;
} par_run;

/* Run the pairs, all in one run of the program (each pair's time is its
 * own: par_pair.time, seconds of the machine's clock).  0, or -1 and a
 * message: a price that cannot be said in node units (par_config_prices,
 * before any launch), the launcher's error, else the master's, else the
 * first slave's (in rank order). */
int par_run_pairs(const par_run *r, par_pair *pairs, int npairs, char *err, size_t errlen);

/* A slave of the runs a launcher starts on processes of their own (MPI's
 * served ranks, machine/launch_mpi.h): serves one run as par_slave does.
 * 0, or -1 and its message. */
int par_run_serve(mp *self, char *err, size_t errlen);

#endif
