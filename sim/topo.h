/* topo.h -- the machine's interconnect: topologies, their directed links and fixed routes.
 *
 * A topology joins N processors (0..N-1) by directed links (full duplex: a
 * link each way).  Every pair of processors has one fixed route, a list of
 * links; routing is deterministic and documented here, so that a run is
 * reproducible and its closed forms can be checked by hand.
 *
 *   name            N                 links and route from s to d (h = links crossed)
 *   bus             procs             one shared link; h = 1
 *   full            procs             a crossbar: s's injection link into one switch,
 *                                     then d's ejection link; h = 2
 *   line[:N]        procs, or N       s -> s+1 -> ... -> d; h = |s - d|
 *   ring[:N]        procs, or N       the shorter way round; exactly half way round
 *                                     goes up (s+1 first); h = min(|s-d|, N-|s-d|)
 *   mesh[:WxH]      W*H               processor x + W*y; X first, then Y (dimension
 *                                     order); h = |dx| + |dy|
 *   torus[:WxH]     W*H               as mesh, each dimension the shorter way round,
 *                                     half way going up
 *   hypercube[:d]   2^d               lowest differing bit first (e-cube); h = popcount(s^d)
 *   butterfly[:k]   k^n, n = ceil(log_k procs)
 *                                     a k-ary n-fly: n stages of k^(n-1) k-by-k
 *                                     switches, processors on both sides (the TC2000's
 *                                     network); destination-tag routing; h = n + 1
 *
 * Unsized names are sized to the run: line, ring, full and bus get one processor
 * per processor of the run; mesh and torus W = ceil(sqrt(procs)), H =
 * ceil(procs / W); hypercube the least d with 2^d >= procs; butterfly k = 2.
 *
 * Butterfly wires: the links of level l (0..n) are numbered by an n-digit
 * radix-k wire w; on the route from s to d, w at level l is the top l digits
 * of d followed by the bottom n-l digits of s (level 0, injection: w = s;
 * level n, ejection: w = d).  The stage-l switch (l = 0..n-1) joins the k
 * wires of level l that differ only in digit n-1-l to the k of level l+1. */
#ifndef TOPO_H
#define TOPO_H

#include <stddef.h>

typedef enum {
  TOPO_NONE,        /* no topology: sim_config.net decides */
  TOPO_BUS,
  TOPO_FULL,
  TOPO_LINE,
  TOPO_RING,
  TOPO_MESH,
  TOPO_TORUS,
  TOPO_HYPERCUBE,
  TOPO_BUTTERFLY
} topo_kind;

enum { TOPO_MAX_NODES = 1 << 22 };

/* A topology by name, before it is sized: a plain value. */
typedef struct {
  topo_kind kind;
  int a, b;   /* size, 0 = sized to the run: line/ring/full/bus N (a);
                 mesh/torus W, H; hypercube d; butterfly k */
} topo_spec;

/* "mesh:4x4", "line", "hypercube:4", ...  0, or -1 and a message. */
int topo_parse(const char *s, topo_spec *out, char *err, size_t errlen);

/* The name topo_parse reads back ("mesh:4x4"; "none" for TOPO_NONE). */
void topo_spec_str(const topo_spec *sp, char *buf, size_t len);

typedef struct topo topo;

/* The topology of sp for a run on `procs` processors: N >= procs (a sized
 * topology too small for the run is an error).  NULL and a message if not. */
topo *topo_new(const topo_spec *sp, int procs, char *err, size_t errlen);
void topo_free(topo *t);   /* NULL is fine */

topo_kind topo_kind_of(const topo *t);
int topo_nodes(const topo *t);     /* N */
int topo_nlinks(const topo *t);    /* link ids are 0..nlinks-1 (some may not exist) */
int topo_max_hops(const topo *t);  /* the longest route */

/* The route from processor s to d (s != d): its h links into links[0..h-1]
 * (room for topo_max_hops); returns h. */
int topo_route(const topo *t, int s, int d, int *links);

/* Whether link l joins two processors or switches of this machine. */
int topo_link_exists(const topo *t, int l);

/* A link's name: "3>4" (processor to processor), "bus", "3>sw" and "sw>3"
 * (full), "in 3", "L1 w5", "out 3" (butterfly level 0, level 1 wire 5, level n). */
void topo_link_name(const topo *t, int l, char *buf, size_t len);

/* The grid the processors lie on: W and H for mesh and torus, N and 1 for
 * line and ring; 0 (and N, 1) for the others, which have no rows. */
int topo_grid(const topo *t, int *w, int *h);

#endif
