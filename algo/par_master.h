/* par_master.h -- the master of the parallel algorithm (paper, sections 4, 5
 * and 7): it distributes the points, runs the divide and conquer over groups
 * of slaves, assembles the paths backtracked to it, restricts the graph and
 * splits the groups. */
#ifndef PAR_MASTER_H
#define PAR_MASTER_H

#include "mp/mp.h"
#include "algo/par.h"
#include "algo/tiling.h"

typedef struct {
  /* In: one pair of contours. */
  const vec2 *P;
  int np;
  double zp;
  const vec2 *Q;
  int nq;
  double zq;
  double shadow;       /* the weights' (weights_new_shadow), 0 for the paper's areas */
  /* Out. */
  tiling t;            /* the optimum and its path, as tiling_solve gives it;
                          t.count.nodes and t.count.paths summed over the slaves */
  double time;         /* the master's clock from sending the points to holding the
                          optimum (simulated seconds on the simulator) */
  double mu0_time;     /* the slaves' time on the diagonals of mu(0): from the
                          first one's task to the last one's last diagonal */
  par_counts counts;   /* every rank's counters for this pair, master included */
  par_counts master;   /* the master's own */
} par_pair;

typedef struct {
  int npairs;
  par_pair *pairs;
  cost_kind kind;
  par_options opt;
  int failed;          /* 1 if an mp call failed */
  char err[160];
  /* Optional: called after each pair (on the host, for a progress line). */
  void (*progress)(void *ud, int done, int total);
  void *progress_ud;
} par_master_arg;

/* The master's main: ud is a par_master_arg.  The slaves are ranks
 * 1 .. mp_size-1; at the end they are told to quit. */
void par_master(mp *self, void *ud);

/* --- private part: the master's state, for the variants (par_dynamic.c) -- */

typedef struct {
  int g0, p;           /* slaves g0 .. g0+p-1 */
  int lo, hi;          /* the paths lo+1 .. hi-1 are its to find; lo < 0: mu(0) */
  const gpath *U, *L;  /* its bounds T = mu(lo), B = mu(hi) */
  int mid;             /* the path it computes (PATH) */
  int live;
  int *col;            /* the path being backtracked to us */
  double *w;
  int have;
  int *ranks;          /* its slaves' ranks, or NULL for g0 .. g0+p-1 */
  int64_t est;         /* --schedule dynamic: its estimated work, in nodes */
} par_group;

typedef struct par_master_ctx {
  mp *mp;
  par_master_arg *arg;
  par_pair *pr;
  int S;               /* slaves */
  int m, n, T;
  par_buf in, out;
  size_t maxlen;
  par_group *g;
  int ng, gcap, live;
  int *group_of;       /* slave rank -> its group, or -1 */
  gpath **paths;       /* every path computed, freed at the end of the pair */
  int npaths, pcap;
  tiling_best best;
  par_counts *own;
  struct par_dyn *dyn; /* --schedule dynamic's state (par_dynamic.c) */
} par_master_ctx;

/* Shared with the variants (par_fit.c, par_dynamic.c). */
static inline int par_master_member(const par_group *G, int i) {
  return G->ranks ? G->ranks[i] : G->g0 + i;
}
/* The master's bookkeeping (assembling, copying and comparing paths,
 * measuring bands): every unit of it, one column of a pass over a path, is
 * charged here and only here, at opt.book node units each, and counted in
 * par_counts.book.  0 or a negative mp status. */
int par_master_charge(par_master_ctx *M, uint64_t units);
int par_master_fail(par_master_ctx *M, int rc, const char *what);   /* -1 */
gpath *par_master_path(par_master_ctx *M, int start);   /* a new path, freed with the pair */
int par_master_send_bound(par_master_ctx *M, const gpath *P, int as, int to);
/* A new live group of the p slaves ranks[] (copied) for the paths lo+1 ..
 * hi-1 between U and L; path arrays for a PATH task.  Returns its index. */
int par_master_group(par_master_ctx *M, const int *ranks, int p, int lo, int hi, const gpath *U,
                     const gpath *L, int local);

#endif
