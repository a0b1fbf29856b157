/* link.h -- the network's links as deterministic FIFO queues: when a message arrives, and link statistics.
 *
 * THE MODEL (sim.h refers here).  A message of L bytes from processor s to
 * processor d != s, sent at t0, on a topology (topo.h) with hop latency r,
 * seconds per byte beta (sim_config.per_byte) and message cost m:
 *
 *   m, the software cost of a message, is paid first, as latency: the
 *   message enters the network at t = t0 + m (the sender's clock does not
 *   move: sends are buffered, as on the ideal network).  Then, for each link
 *   l_1 .. l_h of its route, in order:
 *     s_i = max(t, free[l_i])          it waits for the link to be free
 *     free[l_i] = s_i + L*beta         the link carries it for L*beta
 *     t = s_i + r                      cut-through: the head goes on
 *     t = s_i + r + L*beta             store-and-forward: the whole message
 *   and it arrives at s_h + r + L*beta.  On an idle machine that is
 *     cut-through        m + h*r + L*beta
 *     store-and-forward  m + h*(r + L*beta).
 *   (Virtual cut-through: a blocked message waits whole in a switch buffer,
 *   so it holds one link at a time.)
 *
 *   bus: the one shared link carries the whole message, software included,
 *   as the TC2000's message queues in shared memory did (the paper's
 *   pessimistic model, section 7.2): s = max(t0, free); free = s + m + r +
 *   L*beta; it arrives at free.  With r = 0 this is sim.h's SIM_NET_BUS bit
 *   for bit.
 *
 *   Links are reserved when the message is sent, in the simulator's global
 *   (time, sequence) order, so every link serves messages first come (by
 *   send), first served; a link is not lent to a later message during an
 *   idle gap before an earlier message's reservation.  Deterministic.
 *
 * Statistics: per link the messages, bytes and busy seconds; per run the
 * hops, hop-bytes, the busiest link and the seconds messages waited for
 * links. */
#ifndef LINK_H
#define LINK_H

#include <stddef.h>
#include <stdint.h>

#include "sim/topo.h"

struct trace;   /* trace.h */

typedef struct links links;

/* The links of t (which the caller keeps alive and frees after links_free). */
links *links_new(const topo *t, double m, double r, double beta, int store_forward);
void links_free(links *n);   /* NULL is fine */

/* Carry a len-byte message from processor s to d (s != d), sent at t0: its
 * arrival.  With tr, each link's occupancy is written to the trace (rank,
 * dst, tag and id say which message). */
double links_send(links *n, int s, int d, double t0, size_t len, struct trace *tr, int rank, int dst,
                  int tag, uint64_t id);

typedef struct {
  long long msgs, bytes;   /* messages and bytes the link carried */
  double busy;             /* seconds it was carrying one: bytes*beta (the bus:
                              msgs*(m + r) + bytes*beta) */
} link_stats;

typedef struct {
  long long messages;        /* messages that crossed the network */
  long long hops;            /* links crossed, summed over those messages */
  long long hop_bytes;       /* bytes times links crossed, summed */
  long long max_link_msgs;   /* the most messages one link carried */
  long long max_link_bytes;  /* the most bytes one link carried */
  double link_wait;          /* seconds messages waited for busy links, summed */
} net_stats;

const topo *links_topo(const links *n);
link_stats links_get(const links *n, int l);   /* 0 <= l < topo_nlinks */

/* The statistics of the whole run so far. */
void links_total(const links *n, net_stats *out);

/* The statistics since the previous call (or the start), which then
 * begins the next period: a run's pairs one by one. */
void links_period(links *n, net_stats *out);

#endif
