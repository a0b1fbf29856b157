/* micro.h -- the micro-benchmarks behind bench --calibrate: what one
 * message costs the threads backend's sender, receiver and the time
 * between them, what a sleeping receiver's wake-up costs, and how much
 * cores that work at once slow each other.  None of them runs the
 * parallel algorithm. */
#ifndef BENCH_MICRO_H
#define BENCH_MICRO_H

#include <stddef.h>

#include "geom/geom.h"

/* Messages between ranks of the threads backend (default spin), in four
 * patterns of the Intel MPI Benchmarks' kind:
 *   ping-pong   two ranks, one message in flight, the receiver spinning
 *               (the one-way time: send, latency, receive);
 *   exchange    four ranks in a ring, each sending to both neighbours,
 *               then waiting a few microseconds, then receiving from both
 *               (every message is there by then): the time inside mp_send
 *               and inside mp_recv, with messages crossing and two senders
 *               at each mailbox, as in a parallel program's boundary
 *               exchange;
 *   stream      two ranks, sends back to back, received as they come;
 *   sleeper     a ping-pong whose receivers sleep at once (spin 0), the
 *               sender first idle for `idle` seconds (so the sleeper's core
 *               has gone idle too): the one-way time, and the time inside
 *               the send that wakes it. */
typedef struct {
  size_t small, big;          /* the two message sizes, bytes */
  double pp_small, pp_big;    /* ping-pong, one way */
  double os_small, os_big;    /* exchange: a send's time */
  double or_small, or_big;    /* exchange: a receive's time, the message there */
  double stream;              /* per message of a one-way stream of small ones */
  double idle;                /* the sleeper benchmark's idle time before a send */
  double pp_sleep;            /* sleeper: one way */
  double send_sleep;          /* sleeper: a send that wakes the receiver */
  int exchange_ranks;         /* the exchange's ranks: min(4, cores), at least 2 */
} micro_msgs;

/* Each figure the fastest of `repeat` runs of `rounds` messages (fewer for
 * the big ones and the sleeper).  0, or -1 and a message. */
int micro_messages(int rounds, int repeat, micro_msgs *out, char *err, size_t errlen);

/* The model's parameters derived from them (cpu.h, and LogGP's L, g, G);
 * each clipped at 0:
 *   o_send_byte = (os_big - os_small) / (big - small), o_send = os_small - small * o_send_byte;
 *   o_recv likewise; L = pp_small - os_small - or_small;
 *   G = (pp_big - os_big - or_big - L) / (big - 1);
 *   g = stream, if a stream is slower than its sends and receives (else 0);
 *   o_wake = send_sleep - os_small; wake = pp_sleep - send_sleep - L - or_small. */
typedef struct {
  double o_send, o_send_byte, o_recv, o_recv_byte, L, g, G, o_wake, wake;
} micro_model;

void micro_derive(const micro_msgs *m, micro_model *out);

/* One step of a slave's backtracking (paper, Fig. 14; par_slave.c): the
 * in-edge bit of a node looked up in its diagonal's bit words, the edge's
 * weight computed on the fly (as the slaves of many do), the column and the
 * weight stored for the master.  Walked along the pair's optimal path (n
 * points each, weights on the fly), seconds per step, the fastest of
 * `repeat` walks of a few hundred thousand steps. */
double micro_backtrack(const vec2 *A, const vec2 *B, int n, int repeat);

/* k copies of the serial solver on the pair (n points each, weights table
 * as in weights_new) at once, on k threads; with spinners, one copy and
 * k - 1 threads that spin (pause) instead.  The copies' mean seconds, the
 * fastest of `repeat` rounds; < 0 if a thread could not be started. */
double micro_together(const vec2 *A, const vec2 *B, int n, int table, int k, int spinners,
                      int repeat);

/* The seconds a basic block of a program built by tilesim-mpicc
 * --count-blocks takes on this host (tilesim-mpirun --block-c): cpi's loop,
 * compiled as such a program is, its blocks counted and timed; the fastest
 * of repeat runs.  *blocks gets the count of one run. */
double micro_block(int repeat, unsigned long long *blocks);

#endif
