/* threads_calls.h -- the threads backend's state (the machine, its ranks)
 * and its side of mp.h (mpt_ops), private to mp/: threads.c builds and
 * runs the machine, threads_calls.c is what its ranks call. */
#ifndef THREADS_CALLS_H
#define THREADS_CALLS_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>

#include "mp/backend.h"
#include "mp/chan.h"
#include "mp/cpuload.h"
#include "mp/threads.h"

typedef struct rank rank;
struct rank {
  struct mp base;              /* first: an mp * is a rank * */
  mpt *t;
  pthread_t thread;
  /* Owned by the rank's own thread. */
  chan **out;                  /* [dst]: my channel to dst, or NULL (created at the first send) */
  uint64_t clock;              /* Lamport */
  struct chan *pin_q;          /* the message the latest probe from any source */
  struct rec *pin_x;           /* showed, until it is taken (NULL: none), and */
  int pin_tag;                 /* that probe's tag: see look() */
  ticket *refs;                /* its sends by reference not yet settled or withdrawn */
  mpt_rank_stats st;
  /* Its channels in, by source, and in order of creation: written by the
   * senders (under mu), read by the rank. */
  _Alignas(LINE) _Atomic(chan *) *in;
  chan **inlist;
  _Atomic int nin;
  /* Sleeping, under mu; `sleeping` is read by every sender. */
  _Alignas(LINE) pthread_mutex_t mu;
  pthread_cond_t cv;
  _Atomic int sleeping;        /* registered as sleeping in recv (counted in t->sleeping) */
  int wait_src, wait_tag;      /* what it sleeps for */
  int deadlocked;              /* its recv is to return MP_EDEADLOCK */
  double woken_at;             /* wallclock() when a sender woke it */
  char pad[LINE];
};

struct mpt {
  mpt_config cfg;
  int n;
  rank *ranks;
  const mp_proc *procs;
  int cpus;                    /* processors this process may use */
  double t0;                   /* wallclock() at the start */
  _Alignas(LINE) atomic_int stopped;   /* deadlock: every mp call fails at once (read by every call) */
  _Alignas(LINE) atomic_int awake;     /* live - sleeping, for the spinners to read */
  cpuload load;                /* the machine's runnable threads, sampled */
  /* The start gate: threads wait here until all are created. */
  pthread_mutex_t gate_mu;
  pthread_cond_t gate_cv;
  int gate;                    /* 0: wait, 1: go, -1: do not run main */
  /* Under g. */
  pthread_mutex_t g;
  int live;                    /* ranks whose main has not returned */
  int sleeping;                /* ranks sleeping in recv without a matching message */
  mp_log log;                  /* errors (quoted in mpt_run's message) and warnings */
  int ran;
  mpt_stats st;                /* errors and warnings under g; the rest after the run */
};

/* The run has stopped (a deadlock, an abort): every mp call fails at once. */
static inline int stopped(const mpt *t) { return atomic_load_explicit(&t->stopped, memory_order_acquire); }

/* The calls of every rank on threads (mp.h's, through mp.c). */
extern const mp_ops mpt_ops;

/* The run's errors and warnings (t->log), under t->g. */
void mpt_fail_text(mpt *t, const char *text, int always);
MP_PRINTF(2, 3) void mpt_warn(mpt *t, const char *fmt, ...);

/* Every live rank sleeps in recv (the caller holds g): stop the run, mark
 * the sleepers deadlocked, say who waits for what. */
void mpt_deadlock_locked(mpt *t);

/* After a stop: wake every sleeper so that it sees it (holding no lock). */
void mpt_wake_all(mpt *t);

#endif
