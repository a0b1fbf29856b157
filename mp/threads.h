/* threads.h -- the message-passing interface (mp.h) on POSIX threads: one
 * thread per rank, real message queues, real time.
 *
 * The same mp program that runs on the simulator (sim/) runs here unchanged:
 * every rank is a thread of this process, a message is copied into a
 * channel to the receiver at mp_send and out of it at mp_recv, mp_compute
 * does nothing (the work a rank does is the work it really does), and
 * mp_time is wall-clock seconds since the run began.  Messages between one
 * pair arrive in send order; which of two racing senders comes first may
 * change from run to run (mp.h promises determinism only of deterministic
 * backends); promises are ignored (mp_promise_make gives NULL).  How the
 * channels, a receive from any source and the waiting work:
 * doc/backends.md, "Threads".
 *
 * A deadlock (every live thread sleeps in recv with no matching message)
 * stops the run: each of those recvs returns MP_EDEADLOCK, every later mp
 * call MP_ESTOPPED, and mpt_run returns -1 naming each blocked rank:
 *     deadlock after 0.0042 s: rank 1 waits in recv(src=any, tag=3); rank 2 ...
 * A rank must return once its calls fail (a thread cannot be abandoned as
 * the simulator abandons a coroutine).  A bad argument fails the call and
 * the run (mpt_run names the rank and the argument); a truncated message
 * and messages never received are warnings (mpt_stats.warnings, printed to
 * cfg.warn unless it is NULL):
 *     threads: warning: rank 3 finished with 2 unread messages (first from rank 1, tag 4)
 *
 * Usage:
 *   mpt_config cfg; mpt_config_init(&cfg);
 *   mpt *t = mpt_new(&cfg, nranks, err, sizeof err);
 *   if (mpt_run(t, procs, err, sizeof err) != 0) ...;
 *   double wall = mpt_stats_get(t)->wall_s;
 *   mpt_free(t); */
#ifndef THREADS_H
#define THREADS_H

#include <stddef.h>
#include <stdio.h>

#include "mp/mp.h"
#include "mp/stats.h"

typedef struct {
  long spin_ns;   /* how long a waiting recv watches its channels before it
                     sleeps, nanoseconds (>= 0; 0: sleep at once), while
                     the machine has room for spinning (above); at most
                     50 us while the run has more ranks than processors
                     (they would starve the ranks that work).  A wait
                     longer than the work between two messages is common
                     (a slave waits for the others' backtracking, for its
                     next task): sleeping then costs a wake-up of tens of
                     microseconds in a virtual machine, now and then
                     milliseconds, and a group in lock-step waits for its
                     slowest member's */
  FILE *warn;     /* warnings go here (default stderr); NULL: quiet */
} mpt_config;

/* The defaults: spin_ns = 1 ms, warn = stderr. */
void mpt_config_init(mpt_config *cfg);

typedef struct mpt mpt;

/* A machine of nranks (>= 1) threads under cfg (copied).  NULL and a
 * message in err if nranks < 1 or spin_ns < 0. */
mpt *mpt_new(const mpt_config *cfg, int nranks, char *err, size_t errlen);

/* Run procs[0..nranks-1], one thread each, and return when every one has
 * returned.  Once per machine.  0, or -1 and a message in err: deadlock, a
 * bad argument to an mp call, a thread that could not be started.
 * Statistics are available either way. */
int mpt_run(mpt *t, const mp_proc *procs, char *err, size_t errlen);

typedef struct {
  int done;                   /* 1 once its main returned */
  double finish;              /* wall seconds from the start when it returned */
  double recv_wait;           /* wall seconds inside mp_recv without a message */
  long long sleeps;           /* recvs that went to sleep after spinning */
  long long wakes;            /* of those, woken by a sender's message */
  double wake_s;              /* wall seconds from those senders' signals to
                                 the sleepers running again (wake-up latency) */
  long long sent, received;   /* messages */
  long long bytes_sent, bytes_received;
  long long unread;           /* messages sent to it and never received */
} mpt_rank_stats;

typedef struct {
  MP_STATS_GROUP;             /* ranks, messages, ..., wall_s (mp/stats.h);
                                 wall_s: from the start to the last return */
  long long sleeps;           /* recvs that slept, all ranks */
  long long wakes;            /* sleepers woken by a message, all ranks */
  double wake_s;              /* their wake-up latencies, summed */
} mpt_stats;

/* Statistics of one rank (0 <= rank < nranks) and of the run: valid after
 * mpt_run, until mpt_free; all zero before. */
const mpt_rank_stats *mpt_rank(const mpt *t, int rank);
const mpt_stats *mpt_stats_get(const mpt *t);

void mpt_free(mpt *t);   /* NULL is fine */

#endif
