/* par_block.h -- the blocked wavefront (--block k): a slave's share of one
 * path, with run-boundary costs exchanged once every k diagonals instead of
 * on every diagonal (an answer to sections 7.2, 8 and 9: fewer messages for
 * a little redundant work).  The path found is the serial one bit for bit;
 * k = 1 is not this code but the paper's per-diagonal exchange
 * (par_slave.c).  How the blocks, their staircase boundaries and the ghost
 * nodes work: doc/algorithm.md, "The blocked wavefront". */
#ifndef PAR_BLOCK_H
#define PAR_BLOCK_H

#include "algo/band.h"

typedef struct par_slave_ctx par_slave_ctx;
typedef struct par_block par_block;   /* the blocks of the current path (opaque) */

/* For paths of an m x n pair. */
par_block *par_block_new(int m, int n);
void par_block_free(par_block *b);

/* All diagonals 1..m+n of path s inside (U, L) (NULL for mu(0)), as slave j
 * of the group S->grp[0 .. p-1], in blocks of S->k: fills S->type, a, b,
 * c0, woff, bits as the paper's sweep does.  0, or -1 after a failed mp
 * call (S->arg says why). */
int par_block_sweep(par_slave_ctx *S, int s, const gpath *U, const gpath *L, int j, int p);

/* The slave (0-based in the group) that owns node (t, c) of the last sweep. */
int par_block_owner(const par_slave_ctx *S, int t, int c);

#endif
