/* par_dynamic.h -- --schedule dynamic: the master hands out bands as tasks
 * to whichever slaves are free (an answer to sections 6, 8 and 9: processor
 * allocation, and the work a processor is given).
 *
 * The paper fixes the groups by halving them at every path (section 4), so
 * that a group keeps its slaves however its band turns out.  The generated
 * paths cluster: one band between two neighbouring paths can hold most of a
 * half's nodes, and the group of one slave that gets it re-solves it at
 * every level of its own divide and conquer while the others have finished.
 *
 * Here every band (lo, hi) whose bounds mu(lo), mu(hi) are known is a ready
 * task, with an estimate of its work (the nodes between its bounds times
 * the levels of its divide and conquer) and the most slaves its middle
 * path's diagonals can use under --min-diag.  Whenever slaves are free, the
 * largest ready task goes first:
 *
 *   - a band worth no more than one slave's share of all the work left
 *     (running and ready) goes whole to one slave (LOCAL: its paths by the
 *     serial divide and conquer, only the best comes back);
 *   - a larger band's middle path is split by the wavefront among its share
 *     of the slaves (as many as are free, and its diagonals can use), with
 *     --block k if given; when that path is back its two halves are new
 *     tasks, and the group's slaves are free again.
 *
 * A slave keeps the bounds it was last sent; the master sends only the ones
 * it lacks.  Messages to a group name its slaves (they need not be
 * neighbours).  Every decision is made by the master from integers, so a
 * run is as deterministic as the paper's. */
#ifndef PAR_DYNAMIC_H
#define PAR_DYNAMIC_H

#include "algo/par_master.h"

/* Start a pair: mu(0) with every slave its diagonals can use.  0 or -1. */
int par_dynamic_begin(par_master_ctx *M);

/* The group G (a copy; its slaves are free again) has found P = mu(G->mid):
 * its halves become tasks, and free slaves get work.  0 or -1. */
int par_dynamic_path(par_master_ctx *M, const par_group *G, gpath *P);

/* A slave has finished a LOCAL task of estimated work est.  0 or -1. */
int par_dynamic_local(par_master_ctx *M, int64_t est);

/* End of the pair (or of the run): free the state; NULL state is fine. */
void par_dynamic_end(par_master_ctx *M);

#endif
