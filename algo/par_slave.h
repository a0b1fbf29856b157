/* par_slave.h -- a slave of the parallel algorithm (paper, sections 4 and 5):
 * it computes its runs of each diagonal, trades run-boundary costs with its
 * neighbours, takes part in backtracking, and solves whole bands alone when
 * its group has one slave. */
#ifndef PAR_SLAVE_H
#define PAR_SLAVE_H

#include "mp/mp.h"
#include "algo/par.h"

typedef struct {
  /* Filled by the slave: */
  par_counts counts;   /* since the last STATS report */
  par_counts total;    /* since the start */
  double fp_start, fp_end;   /* the first path of the current pair: when its
                                task came, when my last diagonal was done */
  int failed;          /* 1 if an mp call failed (deadlock, stop) */
  char err[160];
  /* Optional, for tests: if diag_sends is set, the BOUNDARY messages this
   * slave sends for each diagonal t = 0..diag_len-1 of the first path of
   * the run are added to diag_sends[t], and those it receives to
   * diag_recvs[t] (either may be NULL). */
  int *diag_sends, *diag_recvs;
  int diag_len;
} par_slave_arg;

/* The table argument of weights_new (weights.h) a slave of `slaves` uses:
 * -1 (by size) when they are few, 0 (on the fly) when many.  A slave of
 * many evaluates about 1/slaves of the nodes: fewer than the 2 m n weights
 * a table holds.  (bench --calibrate asks, to time the same kernels.) */
int par_slave_table(int slaves);

/* The slave's main: ud is a par_slave_arg.  Serves pairs until QUIT. */
void par_slave(mp *self, void *ud);

/* --- private part: the slave's state, for the variants (par_block.c) ---- */

#include <stdint.h>

#include "algo/band.h"
#include "algo/weights.h"

enum { PAR_D_NORMAL, PAR_D_SINGLE, PAR_D_RUN };   /* how a diagonal is computed */

typedef struct par_slave_ctx {
  mp *mp;
  par_slave_arg *arg;
  int rank;
  par_buf in, out;
  size_t maxlen;
  /* The pair. */
  int m, n, d;
  vec2 *R, *C;
  weights *w;
  band_ws *ws;
  gpath U, L;          /* the group's bounds, each with its own arrays */
  int hasU, hasL;
  /* One path task: per diagonal t = 0..m+n. */
  unsigned char *type;
  int *a, *b, *q;      /* band columns and active slaves */
  int *c0;             /* first column of my run, or -1 */
  int *run0;           /* for PAR_D_RUN diagonals: the first diagonal of the run */
  int64_t *woff;       /* my bits for diagonal t start at this word */
  uint64_t *bits;
  int64_t bitcap;
  double *prev, *cur;  /* costs by column, index -1 .. n+1 */
  int *pcol;           /* a backtrack piece */
  double *pw;
  unsigned char *pv;   /* its steps' in-edges: 1 vertical, 0 horizontal, 2 a run's */
  int first_path;      /* the test hook counts only the first path */
  int *grp;            /* the group of the current task: its slaves' ranks */
  int k;               /* --block k: diagonals between exchanges (1: the paper's) */
  double table, back;  /* the prices of a table cell and a backtracking step
                          (par_options), in node units; 0: not charged */
  struct par_block *blk;   /* the blocked wavefront's state (k > 1), par_block.h */
} par_slave_ctx;

/* Shared with par_block.c: record a failed mp call (returns -1), and join a
 * pinch of path s at diagonal t (returns its last diagonal; see par_slave.c). */
int par_slave_fail(par_slave_ctx *S, int rc, const char *what);
/* par_recv into S->in, the wait counted as idle. */
int par_slave_recv(par_slave_ctx *S, int src, int tag, mp_status *st);
/* The test hook (par_slave_arg.diag_sends, diag_recvs): on the first path,
 * diagonal t's boundary messages sent and received. */
void par_slave_count_diag(par_slave_ctx *S, int t, int sends, int recvs);
/* Send the run-boundary costs S->prev[n0..n1] of diagonal t to group
 * member i (what par_slave_recv_boundary takes).  The send's result. */
int par_slave_send_boundary(par_slave_ctx *S, int i, int t, int n0, int n1);
/* Receive the run-boundary costs of diagonal t, nodes v0..v1, from group
 * member o into S->prev[v0..v1] (section 5: the costs a slave needs from its
 * neighbour's run); a message for anything else is a bug (xpanic, naming
 * `what`).  0, or -1 (par_slave_fail) when the receive fails. */
int par_slave_recv_boundary(par_slave_ctx *S, int o, int t, int v0, int v1, const char *what);
int par_slave_pinch(par_slave_ctx *S, int s, const gpath *U, const gpath *L, int j, int t, int a,
                    int *pa, int *pb);

#endif
