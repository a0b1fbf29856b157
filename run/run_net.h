/* run_net.h -- a run's network options (topology, hop latency, switching, placement) and where its ranks go. */
#ifndef RUN_NET_H
#define RUN_NET_H

#include <stddef.h>
#include <stdio.h>

#include "run.h"

/* Take one of the network options of a run (run_option calls this first):
 *   --topology NAME  --hop-latency S  --switching cut-through|store-and-forward
 *   --place linear|snake|gray|random:SEED|file:PATH
 * Returns 1 if opt is one of them (val consumed), 0 if not, -1 for a bad
 * value with a message in err. */
int run_net_option(run_config *rc, const char *opt, const char *val, char *err,
                   size_t errlen);

/* The usage lines of those options. */
extern const char run_net_help[];

/* The processors of a simulated run on P processors (run_ranks(P) ranks):
 * place[r] for every rank, on the machine's N processors (*nodes: the
 * topology's, or P without one).  0, or -1 and a message. */
int run_net_place(const run_config *rc, int P, int *place, int *nodes, char *err,
                  size_t errlen);

/* Print where the ranks of a run on P processors go (--print-place): a
 * header line, one line per rank, and on a line, ring, mesh or torus the
 * grid of processors with the rank on each ('.': none).  0, or -1 and a
 * message (a bad placement). */
int run_net_print(FILE *f, const run_config *rc, int P, char *err, size_t errlen);

/* The same for any machine: nranks ranks on processors place[] of topology t. */
void run_net_print_map(FILE *f, const topo *t, const char *what, const int *place, int nranks);

#endif
