/* sim.h -- a deterministic discrete-event simulator of a message-passing multiprocessor.
 *
 * It runs an mp program (mp.h): every rank is a coroutine on its own stack,
 * placed on one of `procs` simulated processors, and the simulator charges
 * simulated time for computing (mp_compute) and for messages, after the
 * BBN TC2000 runs of Johnson, Livadas & Talele (1993).  Simulated time is
 * exact and deterministic: events are ordered by (simulated time, sequence
 * number), the host clock never touches it, and two runs with the same
 * inputs give byte-identical results and traces.
 *
 * THE TIMING MODEL (the algorithm's calibration depends on exactly this)
 *
 *   Clocks.  Each rank has a clock `now` (mp_time), from 0.  Each processor
 *   has `busy_until`.  Actions are executed in global (time, seq) order: a
 *   rank acts only when its `now` is the earliest pending time; ties go to
 *   the rank that was queued first.  The running rank is queued again when
 *   its clock moves to (or past) another's pending time, and when it calls
 *   mp_yield while another is due at its time.
 *
 *   Compute.  mp_compute(u): start = max(now, busy_until[proc]);
 *   end = start + u*c; busy_until[proc] = end; now = end.  Ranks that share
 *   a processor share its time, first come first served (the paper's
 *   1-processor run has master and slave on one CPU).  Waiting in recv does
 *   not hold the processor.
 *
 *   Sends are buffered: mp_send returns at once (LogGP: after o), and the
 *   message arrives at `arrival`:
 *     same processor   arrival = now + local, in every network model; it
 *                      never touches the network (no m, per_byte, o, g, L, G).
 *     SIM_NET_IDEAL    arrival = now + m + len*per_byte (no contention).
 *     SIM_NET_BUS      one message in flight in the whole machine at a time,
 *                      later ones queue (the paper's pessimistic model of
 *                      section 7.2, and the TC2000's message queues simulated
 *                      in shared memory):
 *                        start = max(now, bus_free);
 *                        bus_free = start + m + len*per_byte; arrival = bus_free.
 *     SIM_NET_LOGGP    the sender's processor is busy o, reserved like compute:
 *                        s = max(now, busy_until[proc]); busy_until = s + o;
 *                        now = s + o;
 *                        inject = max(now, nic_free[proc]);
 *                        nic_free[proc] = inject + g;
 *                        arrival = inject + (len > 1 ? (len-1)*G : 0) + L.
 *     SIM_NET_TOPOLOGY a topology (cfg.topo, topo.h) of links that are FIFO
 *                      queues: m as latency, then hop_latency r per link and
 *                      per_byte on every link, cut-through or store-and-
 *                      forward (link.h states it exactly); on an idle machine
 *                      m + h*r + len*per_byte over h links, cut-through.
 *   Processor costs (cpu.h, all 0 by default): a send's and a receive's
 *   processor time, per message and per byte, in every model; a receiver
 *   that waited longer than cpu.spin sleeps and runs cpu.wake after the
 *   arrival, its waker paying cpu.o_wake; compute slowed by cpu.slowdown
 *   per other busy processor.
 *   Non-overtaking: messages between one pair of ranks are received in send
 *   order, whatever the model: arrival = max(arrival, last arrival on the
 *   same (src, dst) channel).
 *
 *   Receive.  mp_recv(src, tag): among the matching messages (src or MP_ANY,
 *   tag or MP_ANY) the earliest by (arrival, seq) is taken, seq being the
 *   order of the sends.  If it has arrived (arrival <= now) it is taken at
 *   once; otherwise the rank blocks until a matching message arrives and
 *   now = that arrival (the earliest matching one).  LogGP, and a message
 *   from another processor: the receiver's processor is then busy o:
 *   s = max(now, busy_until[proc]); busy_until = now = s + o.
 *   mp_probe(src, tag) never blocks and sees the messages with arrival <= now.
 *   mp_wait(src, tag) blocks as mp_recv does, until the message mp_recv
 *   would take has arrived, and leaves it there (no overhead is charged).
 *
 *   End.  A rank that returns from its main has finished at its now; the
 *   makespan is the latest finish.
 *
 *   Progress while computing (mp_set_progress): a rank that computes with a
 *   progress function is woken at each message that arrives before the
 *   computing ends (and at once for messages already there); the function
 *   runs with now = the arrival, the processor lent to it: the processor time
 *   its calls charge (x) ends the computing x later.  now = end afterwards.
 *
 *   Sleep.  mp_sleep(s): now += s; the processor is not held.  mp_busy(s)
 *   computes as mp_compute does, for s seconds instead of u*c.  mp_exit ends
 *   a rank at its now, as returning from its main does.
 *
 *   Statistics identity: finish = compute + cpu_wait + overhead + recv_wait
 *   + slept for every rank that returns normally (the only ways its clock
 *   moves).
 *
 * ERRORS
 *
 *   Deadlock: when every live rank waits in mp_recv and no matching message
 *   is in flight, the run stops; sim_run returns -1 with a message naming
 *   each blocked rank and what it waits for, e.g.
 *     deadlock at t=0.0042: rank 1 waits in recv(src=any, tag=3); rank 2 ...
 *   Each blocked mp_recv returns MP_EDEADLOCK, so the rank can clean up and
 *   return; from then on every mp call returns MP_ESTOPPED at once.  A rank
 *   that keeps calling after that (1,000,000 calls) is abandoned: its stack
 *   is dropped without unwinding, and the run reports it.
 *
 *   A send to a rank that does not exist (MP_ERANK), a negative tag or a
 *   negative or non-finite compute (MP_EARG), a recv or probe naming a rank
 *   that does not exist (MP_ERANK): the call fails, the rank goes on, and
 *   sim_run returns -1 naming the rank and the bad argument.
 *
 *   A rank that overflows its stack (cfg.stack): in a run of up to
 *   CORO_GUARDED ranks (coro.h) every stack has a guard page and the
 *   overflow faults (SIGSEGV at an address in [stack_guard, stack_lo) of
 *   the rank's mp, which a crash handler can name).  In a larger run the
 *   stacks share guard pages: an overflow the checks find as it happens
 *   faults the same way, and one that stayed within its stack's soft zone
 *   is found when the run ends, and fails it:
 *     rank 5 overflowed its stack of 256 KiB (--stack sets it)
 *
 *   Warnings (counted in sim_stats.warnings; printed to cfg.warn unless it is
 *   NULL) do not fail the run: a message longer than the recv buffer (the
 *   recv returns MP_ETRUNC, the first cap bytes are copied, the message is
 *   consumed), and messages never received by the end of the run:
 *     sim: warning: rank 3 finished with 2 unread messages (first from rank 1, tag 4)
 *
 *   mp_abort(code, why): the run stops (as after a deadlock, every other
 *   rank's calls return MP_ESTOPPED), sim_run returns -1 quoting why, and
 *   sim_stats has aborted = 1 and the first abort's code.
 *
 *   A rank that calls mp_probe 1,000,000 times in a row at the same clock,
 *   with nothing else in between, can never see a new message (time does not
 *   move unless it computes): the run is stopped with an error.
 *
 * Usage:
 *   sim_config cfg; sim_config_init(&cfg); cfg.procs = 8;
 *   sim *s = sim_new(&cfg, nranks, err, sizeof err);
 *   if (sim_run(s, procs, err, sizeof err) != 0) ...;
 *   double t = sim_stats_get(s)->makespan;
 *   sim_free(s); */
#ifndef SIM_H
#define SIM_H

#include <stddef.h>
#include <stdio.h>

#include "sim/cpu.h"
#include "sim/link.h"
#include "mp/mp.h"
#include "mp/stats.h"
#include "sim/topo.h"

/* SIM_NET_TOPOLOGY is set by a topology (cfg.topo), never by name. */
typedef enum { SIM_NET_IDEAL, SIM_NET_BUS, SIM_NET_LOGGP, SIM_NET_TOPOLOGY } sim_net;

typedef struct {
  int procs;          /* processors >= 1 */
  const int *place;   /* place[r] = processor of rank r (copied); NULL: r % procs */
  double c;           /* simulated seconds per compute unit */
  double m;           /* seconds per message (ideal, bus) */
  double per_byte;    /* seconds per byte (ideal, bus) */
  double local;       /* seconds per message between ranks on one processor */
  sim_net net;        /* how messages between processors are charged */
  double L, o, g, G;  /* LogGP: latency, overhead, gap, gap per byte (seconds) */
  topo_spec topo;     /* the interconnect; TOPO_NONE (the default): net decides.
                         Any other: net is SIM_NET_TOPOLOGY, the machine has
                         topo's processors (>= procs), per_byte is every link's */
  double hop_latency; /* topologies: seconds per link a message's head crosses */
  int store_forward;  /* topologies: 1 store-and-forward, 0 cut-through */
  cpu_model cpu;      /* processor overheads, wake-ups, busy neighbours (cpu.h);
                         all 0 by default: none */
  size_t stack;       /* coroutine stack bytes per rank, 0 = 256 KiB */
  FILE *warn;         /* warnings go here (default stderr); NULL: quiet */
} sim_config;

/* The default profile, "tc2000".  Every field is set; change any. */
void sim_config_init(sim_config *cfg);

/* Fill cfg with a named profile: "tc2000" (the default, calibrated against
 * the paper: c = 50 us, m = 275 us on a bus, 2.6e-8 s per byte; sim.c and
 * doc/model.md say why) or "unit" (c = m = L = 1 s, no per-byte cost, for reading
 * traces by eye).  0, or -1 for an unknown name (cfg untouched). */
int sim_profile(const char *name, sim_config *cfg);

/* "ideal", "bus", "loggp" ("topology"); sim_net_parse gives 0, or -1 for
 * another name ("topology" included: a topology is set by cfg.topo). */
const char *sim_net_name(sim_net net);
int sim_net_parse(const char *name, sim_net *net);
/* The names sim_net_parse takes, '|'-separated ("ideal|bus|loggp"). */
void sim_net_words(char *buf, size_t len);

typedef struct sim sim;

/* A machine for nranks ranks (>= 1) under cfg (copied, place included).
 * NULL and a message in err (errlen bytes) if cfg is invalid: procs < 1, a
 * negative or non-finite cost, place[r] outside 0..procs-1 (outside the
 * topology's processors with one), an unknown net, a topology too small. */
sim *sim_new(const sim_config *cfg, int nranks, char *err, size_t errlen);

/* The machine's links (link.h: per-link and per-run statistics), or NULL
 * without a topology.  Valid until sim_free. */
links *sim_links(sim *s);

/* Write the timeline of the run to csv and/or json (either may be NULL; see
 * trace.h for the formats).  Call before sim_run; the streams stay the
 * caller's to close. */
void sim_trace(sim *s, FILE *csv, FILE *json);

/* With sim_trace: write the trace only while its bytes stay within limit
 * (trace_new_limited); sim_trace_size then gives the whole trace's bytes
 * and sim_trace_over says whether writing stopped (the caller removes the
 * partial files). */
void sim_trace_limit(sim *s, unsigned long long limit);
int sim_trace_over(const sim *s);

/* Instead of writing a trace, count the bytes a CSV (csv != 0) and a JSON
 * (json != 0) trace of the run would take; sim_trace_size gives them after
 * sim_run (0 without sim_trace_count).  How a program checks a trace's
 * size before it writes one. */
void sim_trace_count(sim *s, int csv, int json);
void sim_trace_size(const sim *s, unsigned long long *csv, unsigned long long *json);

/* How far a long run has got: tick(ud, t, events) is called every 65536
 * switches between ranks, t the simulated time reached and events the mp
 * calls simulated so far (tick = NULL: never).  Call before sim_run. */
void sim_progress(sim *s, void (*tick)(void *ud, double t, long long events), void *ud);

/* Run procs[0..nranks-1] to completion.  Once per sim.  0, or -1 and a
 * message in err: deadlock, a bad argument to an mp call, stacks that could
 * not be mapped, a stack overflow found by a check, a trace that could not
 * be written.  Statistics are available either way. */
int sim_run(sim *s, const mp_proc *procs, char *err, size_t errlen);

enum { SIM_TAGS = 16 };   /* per-tag send counts for tags 0..SIM_TAGS-1 */

typedef struct {
  int proc;                 /* the processor it ran on */
  int done;                 /* 1 once its main returned */
  double finish;            /* its clock when its main returned */
  double units;             /* compute units charged */
  double compute;           /* seconds computing: the sum of units * c */
  double cpu_wait;          /* seconds waiting for its (shared) processor */
  double overhead;          /* seconds of LogGP send and receive overhead o */
  double recv_wait;         /* seconds blocked in mp_recv (and mp_wait) */
  double slept;             /* seconds of mp_sleep */
  long long sent, received; /* messages */
  long long bytes_sent, bytes_received;
  long long sent_tag[SIM_TAGS];  /* messages sent with tag 0..SIM_TAGS-1 */
  long long unread;         /* messages sent to it and never received */
} sim_rank_stats;

typedef struct {
  MP_STATS_GROUP;           /* ranks, messages, ..., wall_s (mp/stats.h);
                               wall_s: host seconds sim_run took */
  int procs;
  double makespan;          /* the latest finish, simulated seconds */
  long long events;         /* mp calls simulated (send, recv, probe, compute) */
  long long switches;       /* context switches between coroutines */
  long long pooled;         /* payload bytes the host copied into the simulator's
                               own memory, to be copied again by their receive:
                               no receive or promise (mp.h) had taken them */
} sim_stats;

/* Statistics of one rank (0 <= rank < nranks) and of the run.  Valid until
 * sim_free; all zero before sim_run. */
const sim_rank_stats *sim_rank(const sim *s, int rank);
const sim_stats *sim_stats_get(const sim *s);

void sim_free(sim *s);   /* NULL is fine */

#endif
