/* threads.h -- the message-passing interface (mp.h) on POSIX threads: one
 * thread per rank, real message queues, real time.
 *
 * The same mp program that runs on the simulator (sim/) runs here unchanged:
 * every rank is a thread of this process, a message is copied into a
 * channel to the receiver at mp_send and out of it at mp_recv, mp_compute does
 * nothing (the work a rank does is the work it really does), and mp_time is
 * wall-clock seconds since the run began.
 *
 * SEMANTICS (mp.h's contract, as this backend keeps it)
 *
 *   Channels.  Each ordered pair of ranks that talks has a queue with one
 *   writer and one reader (no lock, no read-modify-write operation on a
 *   send: mp/threads.c), so messages between one pair arrive, and are
 *   received, in send order; a recv from one source takes the first
 *   message of that channel that matches its tag.  A recv from MP_ANY
 *   takes, among the first matches of every channel, the one with the
 *   least Lamport stamp (each send carries its sender's clock, a receive
 *   advances the receiver's), ties to the lower source: a message is never
 *   taken before one sent before its sender heard (directly or through a
 *   chain of messages) from that one's sender, as from a single mailbox in
 *   arrival order.  Which of
 *   two racing senders comes first is the machine's business: it may
 *   change from run to run (mp.h only promises determinism of
 *   deterministic backends; the paper's algorithm gives the same result
 *   whatever the order).  A probe that shows a message advances the
 *   prober's clock as a receive does (what it sends afterwards comes after
 *   that message).  The message a probe shows is the one a receive by the
 *   status's source and tag then takes (as in MPI); after a probe from
 *   MP_ANY, a receive from MP_ANY with the probe's tag takes it too (as
 *   from one mailbox: what came into view after the probe arrived after
 *   it, whatever its stamp), unless a later probe from MP_ANY intervened.
 *
 *   Waiting.  A recv that finds nothing spins, watching its channels, for
 *   a bounded time (cfg.spin_ns), and only then sleeps on a condition
 *   variable; the sender wakes it.  How it spins is decided again and
 *   again from what runs on the machine (mp/cpuload.h: the runnable
 *   threads machine-wide, sampled every 5 ms from /proc/loadavg where
 *   there is one):
 *     pause instructions while no more of this run's threads are awake
 *       than there are processors that other programs leave idle;
 *     sched_yield while more of them are awake than there are processors
 *       but nothing else wants the processors (16 ranks on 2 cores), so
 *       that the rank that will send gets the processor (for at most 50 us:
 *       ranks that yield to each other for long starve those that work);
 *     pause for at most 20 us while other programs want the processors
 *       but this run's ranks alone would fit on them (all but one, a
 *       master that mostly waits): two slaves
 *       that the scheduler has on processors at once keep trading their
 *       boundaries at full speed, and one whose partner lost its
 *       processor soon sleeps;
 *     no spin at all, straight to sleep, while this run's threads and
 *       other programs' together crowd the processors (or a yield lately
 *       came back late): a spinner or yielder would take the processor
 *       from a thread that works, perhaps the very one it waits for, for
 *       whole time slices.
 *   A condition-variable wake-up costs microseconds (tens of them in a
 *   virtual machine), more than the work between two of the algorithm's
 *   boundary messages; a short spin catches those messages within a
 *   cache-line transfer.  A rank that waits long (the master, mostly)
 *   sleeps and leaves its core to the others.  Beside busy programs a run
 *   takes a small multiple of its time alone (make bench-load) instead of
 *   a hundred times it.
 *
 *   Deadlock.  When every live thread sleeps in recv with no matching
 *   message in its channels (messages are never in flight here: a send
 *   delivers at once), the run is stopped: each of those recvs returns
 *   MP_EDEADLOCK, every later mp call MP_ESTOPPED, and mpt_run returns -1
 *   with a message naming each blocked rank and what it waits for:
 *     deadlock after 0.0042 s: rank 1 waits in recv(src=any, tag=3); rank 2 ...
 *   A rank must return once its calls fail; one that loops forever keeps
 *   the run from ending (threads cannot be abandoned the way the
 *   simulator abandons a coroutine).
 *
 *   Messages without copies (mp.h).  A send by reference leaves the
 *   payload in the sender's buffer (up to about 1 KiB it is copied into
 *   the record all the same) with a ticket the sender and the receiver
 *   share (chan.h): a receive that comes first copies straight from the
 *   sender's buffer, a settle that comes first copies it out; a message a
 *   receive has looked at (found by a recv, probe or wait) can no longer
 *   be withdrawn, one taken by mp_recv_msg can until it is read.
 *   Promises are ignored (mp_promise_make gives NULL): a receiver here
 *   takes a message when it comes, often before its sender settles it.
 *
 *   Errors, as on the simulator: a send to, or a recv or probe from, a rank
 *   that does not exist (MP_ERANK), a negative tag, a negative or non-finite
 *   compute, a NULL buffer with a length (MP_EARG): the call fails, the rank
 *   goes on, and mpt_run returns -1 naming the rank and the argument.
 *
 *   Warnings (counted in mpt_stats.warnings, printed to cfg.warn unless it is
 *   NULL): a message longer than the recv buffer (MP_ETRUNC, the first cap
 *   bytes copied, the message consumed), and messages never received:
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
