/* calls.h -- the simulator's state (the machine, its ranks) and its side
 * of mp.h (sim_ops: compute, send, recv, probe, ...), private to sim/:
 * sim.c builds and runs the machine, calls.c is what its ranks call. */
#ifndef SIM_CALLS_H
#define SIM_CALLS_H

#include <stdint.h>
#include <stdio.h>

#include "mp/backend.h"
#include "sim/coro.h"
#include "sim/evq.h"
#include "sim/mailbox.h"
#include "sim/sim.h"
#include "sim/trace.h"

enum {
  STOPPED_CALLS_MAX = 1000000, /* calls after a stop before a rank is abandoned */
  PROBE_SPINS_MAX = 1000000    /* fruitless probes at one clock before we stop */
};

/* R_BUSY: computing with a progress function (mp_set_progress), queued at the
 * computing's end or at the next arrival, whichever is first. */
enum { R_READY, R_BLOCKED, R_DONE, R_ABANDONED, R_BUSY };

typedef struct rank rank;
struct rank {
  struct mp base;          /* first: an mp * is a rank * */
  sim *s;
  coro *co;
  int proc;
  int state;               /* R_* */
  double now;              /* the rank's clock */
  /* blocked in recv: */
  int wait_src, wait_tag;  /* what it waits for (MP_ANY = -1) */
  double wake;             /* the time it is queued to wake at, INFINITY if none */
  double since;            /* when it blocked */
  int deadlocked;          /* woken by the deadlock report */
  mbox box;                /* messages sent to it, sent or arrived */
  chanset chans;           /* the latest arrival per destination */
  long stopped_calls;      /* mp calls since the run stopped */
  double call_t0;          /* mp_call_begin: when the outermost call began, */
  long long call_msgs;     /* and the messages sent and received by then */
  int in_progress;         /* its progress function runs (busy_progress) */
  long probe_spins;        /* fruitless probes in a row at probe_at */
  double probe_at;
  sim_rank_stats st;
};

struct sim {
  sim_config cfg;
  int n;                   /* ranks */
  int *place;
  rank *ranks;
  double *busy;            /* per processor: busy_until */
  double *nic;             /* per processor: LogGP NIC free time */
  double bus_free;         /* SIM_NET_BUS */
  topo *topo;              /* SIM_NET_TOPOLOGY: the interconnect and its links */
  links *links;
  evq *q;                  /* ranks that can act, by (time, seq) */
  uint64_t seq;            /* the next sequence number (events and messages) */
  double gtime;            /* the time of the latest event started: never decreases */
  coro *main;              /* sim_run's own context */
  coro_stacks *stacks;     /* the ranks' stacks, one set */
  const mp_proc *procs;
  int live;                /* ranks neither done nor abandoned */
  int stopped;             /* deadlock or error: every mp call fails at once */
  int cpu;                 /* the processor-side model (cpu.h) is on */
  unsigned char *seen;     /* per processor, for slow_factor */
  int ran;
  mstore msgs;             /* spent messages */
  FILE *tcsv, *tjson;
  int count_csv, count_json;   /* sim_trace_count */
  void (*tick)(void *, double, long long);   /* sim_progress */
  void *tick_ud;
  unsigned ticks;
  int limited;                 /* sim_trace_limit */
  unsigned long long trace_limit;
  trace *tr;
  mp_log log;              /* errors (quoted in sim_run's message) and warnings */
  sim_stats st;
};

/* The calls of every rank of the simulator (mp.h's, through mp.c). */
extern const mp_ops sim_ops;

#endif
