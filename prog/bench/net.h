/* net.h -- ./bench's network axes: --topology and --place lists, and the network's CSV columns. */
#ifndef BENCH_NET_H
#define BENCH_NET_H

#include <stddef.h>
#include <stdio.h>

#include "sim/link.h"
#include "sim/place.h"
#include "prog/bench/paper.h"
#include "sim/topo.h"

enum { BENCH_NET_MAX = 16 };

typedef struct {
  int n;
  topo_spec v[BENCH_NET_MAX];
} bench_topos;

typedef struct {
  int n;
  place_spec v[BENCH_NET_MAX];
} bench_places;

/* Comma-separated topologies ("line,mesh:4x4,hypercube:4") and placements
 * ("linear,snake,random:1"; a file's path cannot hold a comma).  0, or -1
 * and a message. */
int bench_topos_parse(const char *s, bench_topos *out, char *err, size_t errlen);
int bench_places_parse(const char *s, bench_places *out, char *err, size_t errlen);

/* The columns the network adds to a CSV row, after a comma:
 *   topology,place,hop_latency,switching,hops_per_msg,hop_bytes,max_link_msgs,
 *   max_link_bytes,link_wait
 * topology, hop_latency, switching and the statistics are empty without a
 * topology; place is empty on a measured backend. */
extern const char bench_net_header[];

/* Those fields for a run under rc (the run's machine and placement), with
 * its network statistics ns (NULL: none). */
void bench_net_fields(FILE *f, const bench_machine *rc, const net_stats *ns);

#endif
