/* par_fit.h -- --alloc fit: processor allocation that never gives a group
 * more slaves than its band's diagonals can use (an answer to sections 6,
 * 8 and 9: "a better heuristic is needed to allocate processors to
 * subgraphs", "a lower bound on computation size").
 *
 * With --min-diag d (section 7.2) a diagonal of D nodes keeps at most D/d
 * slaves busy, and the bands narrow as the divide and conquer goes down:
 * under half or size allocation a group whose band is narrow computes its
 * middle path with one slave while its others wait, and the sibling band,
 * which could use them, goes without.  fit splits a finished group's slaves
 * between the two subgraphs in proportion to their sizes (section 7.1's
 * size), then caps each side at the slaves the widest diagonal of its next
 * path can use (split_usable): the surplus goes to the sibling, as far as
 * the sibling can use it.  Slaves are never idled: one left out of every
 * group would sit out the rest of the pair, where inside one it still
 * serves the subtrees below (so the whole graph's group is not capped). */
#ifndef PAR_FIT_H
#define PAR_FIT_H

#include "algo/par_master.h"

/* At most p slaves for the group of the paths lo+1 .. hi-1 between U and L
 * (lo < 0: mu(0)): those the diagonals of its middle path can use.  The
 * count, or -1 after a failed mp call. */
int par_fit_cap(par_master_ctx *M, int lo, int hi, const gpath *U, const gpath *L, int p);

/* The finished group G has found P = mu(G->mid): *nb slaves for the paths
 * below P and *na above (size's split on entry), capped as above.  0, or
 * -1 after a failed mp call. */
int par_fit_split(par_master_ctx *M, const par_group *G, const gpath *P, int *nb, int *na);

#endif
