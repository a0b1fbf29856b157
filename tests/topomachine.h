/* topomachine.h -- the machines the topology tests run on (test_topo,
 * test_place), and their closed forms worked out here independently of
 * sim/: the documented sizes (topo.h), h(s, d) by each topology's distance
 * formula, and one message's time on an idle machine.  Costs are binary
 * fractions, so the times they give are exact. */
#ifndef TOPOMACHINE_H
#define TOPOMACHINE_H

#include <stddef.h>

#include "mp/mp.h"
#include "sim/sim.h"
#include "sim/topo.h"
#include "tests/simrun.h"

/* m, r, beta (s per byte) and c of every machine here. */
static const double M = 0.25, R = 0.125, BETA = 1.0 / 64, C = 0.125;

typedef struct {
  topo_kind kind;
  int a, b;    /* the spec's size (0: sized to procs) */
  int procs;   /* the run it is sized for */
} machine;

enum { NMACHINES = 16 };
extern const machine machines[NMACHINES];

/* The documented sizes (topo.h), worked out here. */
typedef struct {
  int N, w, h, d, k, n;
} dims;

dims tm_dims(const machine *mc);

/* mc's topology for its run of mc->procs ranks (topo_free it), or NULL
 * with err. */
topo *tm_topo(const machine *mc, char *err, size_t errlen);

/* h(s, d): the table of topo.h. */
int tm_hops(const machine *mc, const dims *x, int s, int d);

/* The simulator's configuration of mc (store-and-forward if saf). */
sim_config tm_netcfg(const machine *mc, int saf);

/* One message on an idle machine, over h links. */
double tm_alone(const machine *mc, int saf, int h, size_t len);

/* The number of bits set in v. */
int tm_popcount(unsigned v);

/* Permutations sent at t = 0: each rank sends one len-byte message (tag 0)
 * to dst, and receives the number expected from anyone. */
enum { PMAX = 64 };

typedef struct {
  int dst[PMAX];      /* each rank's destination, -1: none */
  int expect[PMAX];   /* messages each rank receives */
  double at[PMAX];    /* when the message from rank i was received */
  size_t len;
  int bad;
} perm;

void tm_perm_main(mp *self, void *ud);

/* Run the permutation dst[0..n-1] (identity placement) on mc: dst[i] = i
 * means none; expect, at and bad set before the run; a failed run fails a
 * check.  The simulator after it (sim_free it). */
sim *tm_run_perm(const machine *mc, int saf, perm *p, int n, char *err, size_t errlen);

#endif
