/* cpuload.h -- are there idle processors to spin on?  What the threads and
 * MPI backends ask before a waiting rank spins (or polls without sleeping).
 *
 * A waiting rank that spins answers a message within a cache-line transfer
 * instead of a wake-up, but only while it has a processor nobody else
 * wants.  When the machine is oversubscribed (more runnable threads than
 * processors: other programs, or more ranks than cores) a spinner takes
 * the processor from a thread that works, maybe the very one it waits for;
 * it must sleep at once instead.
 *
 * The count of runnable threads, machine-wide, is sampled now and then (at
 * most every CPULOAD_PERIOD_S seconds, by whichever caller finds the sample
 * old): on Linux the fourth field of /proc/loadavg, "running/threads", which
 * is the number of runnable tasks right now (not an average).  Elsewhere,
 * or if it cannot be read, the count is unknown (-1) and callers decide
 * from what they know of their own threads.
 *
 * Thread-safe: any thread may call cpuload_running at any time. */
#ifndef CPULOAD_H
#define CPULOAD_H

#include <stdatomic.h>

#define CPULOAD_PERIOD_S 0.005   /* the sample's age at most */
#define CPULOAD_HOG_S 200e-6      /* a yield away this long: something hogs */
#define CPULOAD_HOG_HOLD_S 0.05   /* ... and is believed to, this long */

/* Processors this process may run on (its affinity mask where the system
 * says; else the online processors), >= 1. */
int cpuload_cpus(void);

typedef struct {
  atomic_llong due;      /* when the next sample is due, ns of wallclock */
  atomic_int running;    /* runnable tasks at the last sample, -1 unknown */
  atomic_int base;       /* caller's own runnable count at that sample */
  atomic_int broken;     /* 1: no source; never sample again */
  atomic_llong hogged;   /* until when (ns) a long yield says the processors
                            are taken by threads that do not give them back */
} cpuload;

void cpuload_init(cpuload *l);

/* Runnable threads machine-wide at the latest sample (sampling first if the
 * last is older than CPULOAD_PERIOD_S), or -1 if unknown.  `mine` is how
 * many of those the caller counts as its own right now (its awake threads);
 * it is stored with a new sample, and *others gets the runnable threads that
 * are not the caller's: running - mine at the sample time, >= 0 (0 when
 * unknown). */
int cpuload_running(cpuload *l, int mine, int *others);

/* sched_yield, timed.  A yield that hands the processor to one of our own
 * threads (which soon waits, sends or yields itself) comes back within
 * microseconds; one that comes back after CPULOAD_HOG_S or more gave it to a
 * thread that keeps it for whole time slices (another program, a busy
 * loop): yielding then costs a slice each time, and cpuload_hogged says so
 * for the next CPULOAD_HOG_HOLD_S.  This needs no /proc: it is what tells
 * the backends, anywhere, to sleep rather than yield. */
void cpuload_yield(cpuload *l);
int cpuload_hogged(cpuload *l);

/* Parse the "running/threads" field of a /proc/loadavg line: running, or
 * -1 if the line does not have that form.  (Exposed for the tests.) */
int cpuload_parse(const char *line);

#endif
