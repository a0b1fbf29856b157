/* kernel.h -- one anti-diagonal of the dynamic program (paper, section 4).
 *
 * Node (r, c) lies on diagonal k = r + c.  Its cost is
 *     C(r,c) = min(C(r-1,c) + V(r-1,c), C(r,c-1) + H(r,c-1))
 * (Fig. 11): both predecessors lie on diagonal k-1, so all nodes of a
 * diagonal are independent and a diagonal can be split between processors
 * (Fig. 12, 13).  Ties go to the vertical edge, everywhere: one global rule. */
#ifndef KERNEL_H
#define KERNEL_H

#include <stdint.h>

#include "algo/weights.h"

/* Evaluate nodes (k-c, c) for columns c = a..b of diagonal k.
 * prev[] and cur[] are indexed by column.  prev[a-1 .. b] must be readable
 * and hold +inf for nodes outside the band.  Writes cur[a..b] and
 * ceil((b-a+1)/64) words of bits: bit i of the block is 1 when node a+i
 * took its vertical in-edge (from (r-1, c)), 0 for the horizontal one. */
void kernel_diag(const weights *w, int k, int a, int b, const double *prev, double *cur,
                 uint64_t *bits);

/* Fill row s (0 <= s < m) of w's tables (weights.h): tv[c], and th[c] for
 * area.  Vectorised like the kernel, with the same arithmetic, so a table
 * entry is bit-identical to the weight computed on the fly. */
void kernel_table_row(const weights *w, int s, double *tv, double *th);

/* Which version runs: want = 1 asks for the SIMD one (AVX2, if the CPU has
 * it), 0 for the portable one, -1 only asks.  Returns 1 if SIMD is in use.
 * All versions give bit-identical results; tests compare them. */
int kernel_simd(int want);

/* Words of bits for a run of len nodes. */
static inline int64_t kernel_words(int64_t len) { return (len + 63) >> 6; }

#endif
