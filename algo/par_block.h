/* par_block.h -- the blocked wavefront (--block k): a slave's share of one
 * path, with run-boundary costs exchanged once every k diagonals instead of
 * on every diagonal (an answer to sections 7.2, 8 and 9: fewer messages for
 * a little redundant work).
 *
 * The paper (section 5, Fig. 13) splits every anti-diagonal among the q
 * slaves of a group and trades one cost across each run boundary per
 * diagonal: on a diagonal of D nodes that is cD/q of work against p - 1
 * messages (section 7.2), every diagonal.  Here the diagonals of a path go
 * in blocks of k (cut where the band pinches to one node).  In a block:
 *
 *   - the boundary between slaves j-1 and j is a staircase that moves either
 *     not at all (a fixed column: the "pipelined strip") or one column every
 *     diagonal (a fixed row), chosen per block to follow the paper's even
 *     split at the block's end;
 *
 *        column boundary             row boundary
 *        t0-1  . . . .|o o o         t0-1  . . . .|o o o o
 *        t0    g g g .|o o o         t0    . . . . .|o o o
 *        t0+1    g g .|o o o         t0+1  . . . . x x|o o
 *        t0+2      g .|o o o         t0+2  . . . . x x x|o
 *
 *     dependencies run from column c-1 and c to c (Fig. 11), so across a
 *     column boundary only j needs j-1's costs (the g nodes: a triangle of
 *     ghost nodes it recomputes from j-1's last diagonal), and across a row
 *     boundary only j-1 needs j's (the x nodes);
 *
 *   - so one message crosses each boundary per block, at its first
 *     diagonal, carrying the k costs of the previous diagonal that the
 *     receiver's cone of dependence needs, and nothing moves inside the
 *     block: k times fewer messages than the paper's p - 1 per diagonal,
 *     for about k/2 redundant nodes per boundary and diagonal.
 *
 * Each node is still owned by exactly one slave, which keeps its in-edge bit
 * for backtracking (section 5, Fig. 14); the ghost nodes' values are
 * bit-identical to their owners' (the same IEEE operations on the same
 * inputs), so the path is the serial one bit for bit.  Where the slaves or
 * the band change abruptly (the number of active slaves under --min-diag
 * changes, a pinch), a block starts afresh from the even split and the same
 * cone rule sends whatever each slave lacks, from whoever owns it.
 *
 * k = 1 is not this code: it is the paper's own per-diagonal exchange
 * (par_slave.c), unchanged. */
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
