/* cpu.h -- the processor side of a message and of computing, for the
 * simulator (sim.h): what a real core pays that a network model does not.
 *
 * The network models (ideal, bus, LogGP, topologies) say when a message
 * arrives.  On real cores sending and receiving also cost the processors
 * time (copying, allocating, locking, waking a sleeper), a receiver that
 * waited long has gone to sleep and is woken late, and cores that all work
 * slow each other down (shared caches, memory, clock).  This module holds
 * those costs, every one 0 by default: with all of them 0 the simulator is
 * exactly what it was without this module (sim.c calls nothing then), so
 * the tc2000 profile and every model's times are unchanged bit for bit.
 *
 * THE MODEL (between ranks on different processors; ranks that share a
 * processor exchange as before, at cfg.local)
 *
 *   Send of len bytes: the sender's processor is busy
 *       os(len) = o_send + len * o_send_byte
 *   (reserved like compute; LogGP's o, if any, on top), and the message
 *   leaves at the end of it: the network model's arrival is computed from
 *   there.
 *
 *   Receive: taking a message of len bytes keeps the receiver's processor
 *   busy or(len) = o_recv + len * o_recv_byte once the message has arrived.
 *
 *   Sleep and wake-up: a receiver blocked in recv since time b watches its
 *   mailbox for `spin` seconds, then sleeps.  A message that arrives at a
 *   with a - b > spin finds it asleep: the receiver runs again only at
 *   a + wake, and the sender of the first matching message sent while it
 *   sleeps pays o_wake more processor time (the system call that wakes it),
 *   right after its send overhead.  (spin is the threads backend's --spin.)
 *
 *   Busy neighbours: a compute of u units on processor p that starts at t
 *   takes u * c * (1 + slowdown * k + slowdown_spin * j), k the number of
 *   other processors whose rank is working at t (not finished and not
 *   blocked in recv: computing, sending or receiving, or queued to act), j
 *   the number of others whose rank is blocked but still spinning (blocked
 *   no longer than spin); a sleeping or finished rank's processor counts for
 *   nothing.  Cores that work slow each other (shared caches and memory, a
 *   shared clock and power budget); whether a spinning core does is the
 *   machine's business: bench --calibrate measures both, by running copies
 *   of the serial solver at once, and one copy beside spinning threads.
 *
 * All of it is deterministic: no host clock, the same inputs give the same
 * simulated times. */
#ifndef CPU_H
#define CPU_H

#include <stddef.h>

typedef struct {
  double o_send, o_send_byte;   /* sender's processor, per message and per byte */
  double o_recv, o_recv_byte;   /* receiver's processor, per message and per byte */
  double spin;                  /* a blocked receiver sleeps after this long */
  double wake;                  /* a sleeping receiver runs this long after arrival */
  double o_wake;                /* the sender's processor, to wake a sleeper */
  double slowdown;              /* per other computing processor, a fraction of c */
  double slowdown_spin;         /* per other spinning processor, a fraction of c */
} cpu_model;

/* The defaults: every cost 0; spin = 1 ms, the threads backend's (it only
 * matters once wake or o_wake is set). */
void cpu_model_init(cpu_model *m);

/* 1 if any cost is set (sim.c skips the module otherwise). */
int cpu_model_on(const cpu_model *m);

/* 0, or -1 and a message naming the field if a value is negative or not
 * finite. */
int cpu_model_check(const cpu_model *m, char *err, size_t errlen);

/* os(len) and or(len). */
static inline double cpu_send_cost(const cpu_model *m, size_t len) {
  return m->o_send + (double)len * m->o_send_byte;
}
static inline double cpu_recv_cost(const cpu_model *m, size_t len) {
  return m->o_recv + (double)len * m->o_recv_byte;
}

/* A message arriving at `arrival` for a receiver blocked since `since`:
 * 1 if the receiver is asleep by then (waited longer than spin) and wake or
 * o_wake is set. */
static inline int cpu_asleep(const cpu_model *m, double since, double arrival) {
  return (m->wake > 0 || m->o_wake > 0) && arrival - since > m->spin;
}

/* When the receiver blocked since `since` runs again for a message
 * arriving at `arrival`: arrival, or arrival + wake if it slept. */
static inline double cpu_resume(const cpu_model *m, double since, double arrival) {
  return cpu_asleep(m, since, arrival) ? arrival + m->wake : arrival;
}

/* The command-line options of the model, for machine_option: the field for
 * opt ("--o-send", ...), or NULL.  Every value is seconds (slowdown: a
 * fraction), finite and >= 0. */
double *cpu_model_field(cpu_model *m, const char *opt);

#endif
