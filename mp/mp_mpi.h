/* mp_mpi.h -- the message-passing interface (mp.h) over MPI: one rank per
 * MPI process, across processes and, on a cluster, across machines.
 * Built only by mpicc (or SimGrid's smpicc): `make mpi`.
 *
 * A machine is the first `nranks` processes of a pair of communicators the
 * caller reserves for it (MPI_Comm_dup of MPI_COMM_WORLD, say): `data` for
 * the program's messages, `ctl` for the backend's own.  Every process of
 * the run calls mpm_new and mpm_run with the same nranks; each runs its own
 * rank's main.
 *
 * SEMANTICS (mp.h's contract, as this backend keeps it)
 *
 *   Sends are buffered: mp_send copies the message, starts an MPI_Isend of
 *   the copy and returns; the copies wait in a pool, reaped with
 *   MPI_Testsome, until MPI has delivered them (MPI_Waitall at the end of
 *   the run).  So two ranks that send to each other before receiving do not
 *   deadlock, whether MPI uses eager or rendezvous transfers.  An mp tag is
 *   the MPI tag: 0 .. MPM_TAG_MAX.
 *
 *   Receives (MPI): every message that has arrived is pulled into the rank's
 *   mailbox (MPI_Iprobe from any source with any tag, then MPI_Recv of the
 *   probed message), in the order MPI matches them: per-pair FIFO is MPI's
 *   non-overtaking rule, and a recv takes the first message in the mailbox
 *   that matches, the earliest arrival.  Waiting is a poll of MPI_Iprobe:
 *   busy for 50 us while the machine has a processor for every runnable
 *   thread (mp/cpuload.h), then with sched_yield up to 2 ms unless a yield
 *   lately came back late (another program's busy thread took the
 *   processor for a time slice), then with sleeps of an eighth of the wait
 *   so far (20 us to 1 ms), so that a rank that waits long (the master)
 *   leaves the cores to those that work, and no rank polls or yields
 *   against busy programs.  (Open MPI's own mpi_yield_when_idle, which
 *   --oversubscribe turns on, makes every empty MPI_Iprobe a sched_yield
 *   system call: the boundary exchange then slows down several times; run
 *   with --mca mpi_yield_when_idle 0.)
 *
 *   Deadlock (MPI): a rank that has waited 2 ms in recv reports to rank 0
 *   that it is blocked, with its counts of messages sent to and pulled from
 *   every rank; ranks that have returned report as done.  When rank 0 sees
 *   every rank blocked or done, at least one blocked, and for every pair of
 *   ranks as many messages sent as arrived (nothing in flight), the run is
 *   stopped exactly as on the other backends: each blocked recv returns
 *   MP_EDEADLOCK, every later call MP_ESTOPPED, and the run fails with the
 *   blocked ranks named:
 *     deadlock after 0.0042 s: rank 1 waits in recv(src=any, tag=3); ...
 *   (Per-pair counts make a stale report harmless: a rank that left recv
 *   did so for a message whose sender's counts then disagree with its own.)
 *
 *   Under SimGrid (smpicc, SMPI_H defined by its mpi.h) a recv is one
 *   blocking MPI_Recv, so that the simulated clock moves only with the
 *   simulated messages (SMPI charges simulated time for every MPI_Iprobe);
 *   SimGrid detects deadlocks itself.  mp_compute(u) then executes u * cfg.c
 *   simulated seconds on the rank's host (smpi_execute_benched): compute is
 *   charged explicitly, as on tilesim's simulator.  On real MPI it does
 *   nothing.
 *
 *   mp_time is MPI_Wtime since the rank's mpm_run began (simulated time
 *   under SimGrid).  Clocks of different processes are not synchronised.
 *
 *   Errors and warnings as on the other backends: bad ranks (MP_ERANK), bad
 *   tags, lengths and computes (MP_EARG) fail the call and the run, named;
 *   truncation (MP_ETRUNC) and unread messages are warnings.  At the end of
 *   the run every rank sends rank 0 its counts and errors: rank 0's mpm_run
 *   reports the whole run, the others their own part. */
#ifndef MP_MPI_H
#define MP_MPI_H

#include <mpi.h>
#include <stddef.h>
#include <stdio.h>

#include "mp/mp.h"
#include "mp/stats.h"

enum { MPM_TAG_MAX = 32767 - 16 };   /* the largest mp tag (MPI guarantees 32767) */

typedef struct {
  double c;     /* seconds per compute unit, charged under SimGrid only */
  FILE *warn;   /* warnings go here (default stderr); NULL: quiet */
} mpm_config;

/* The defaults: c = 0, warn = stderr. */
void mpm_config_init(mpm_config *cfg);

typedef struct mpm mpm;

/* This process's rank of a machine of nranks (>= 1) processes: ranks 0 ..
 * nranks-1 of data and ctl (two communicators of the same processes, for
 * this machine alone).  Local: no communication.  NULL and a message if
 * this process is not among them, or nranks is not in 1 .. the size. */
mpm *mpm_new(const mpm_config *cfg, MPI_Comm data, MPI_Comm ctl, int nranks, char *err,
             size_t errlen);

/* Run main(self, ud) as this rank, then the end of the run: every rank
 * waits until all have returned, unread messages are counted, pending sends
 * completed.  0, or -1 and a message: on rank 0 for the whole run, on the
 * others for their own calls.  Once per machine.  Machines on the same
 * communicators must not overlap: a process starts the next one's mpm_run
 * only once rank 0's mpm_run of the last has returned (launch_mpi.c orders
 * runs with messages of its own; a barrier does too). */
int mpm_run(mpm *m, mp_main main, void *ud, char *err, size_t errlen);

/* The figures of mp/stats.h: this rank's, and on rank 0 the run's (by all
 * ranks); wall_s: this rank's seconds in mpm_run; aborted and abort_code
 * stay 0 (mp_abort is MPI_Abort: the run ends). */
typedef struct {
  MP_STATS_GROUP;
} mpm_stats;

/* After mpm_run: on rank 0 the whole run's figures, on others their own. */
const mpm_stats *mpm_stats_get(const mpm *m);

void mpm_free(mpm *m);   /* NULL is fine */

#endif
