/* split.h -- who computes what: a diagonal's nodes among the slaves of a group
 * (section 5, Fig. 13; section 7.2's minimum of d nodes), and the slaves of a
 * group between the two halves of the graph (section 4's half, section 7.1's
 * size).  Pure functions: every slave and the master compute the same answer
 * without asking anyone. */
#ifndef SPLIT_H
#define SPLIT_H

#include <stdint.h>

#include "algo/band.h"

typedef enum { ALLOC_HALF, ALLOC_SIZE, ALLOC_FIT } split_alloc;
enum { SPLIT_ALLOCS = 3 };

/* The allocations' names, in the enumeration's order. */
extern const char *const split_alloc_names[SPLIT_ALLOCS];

/* The slaves active on a diagonal of `len` nodes in a group of p slaves, when
 * each must be given at least d nodes (d = 1: everyone while there are nodes
 * enough): max(1, min(p, len / d)). */
int split_active(int len, int p, int d);

/* The paper's N_i: N_0 = 0, N_i = (len - N_{i-1}) / (q - i + 1) + N_{i-1},
 * i = 1..q: active slave i-1 computes positions N_{i-1} .. N_i - 1 of the
 * diagonal (counted from its first column).  Writes N[0..q]. */
void split_positions(int len, int q, int *N);

/* The same N_i in closed form: with len = a q + r (0 <= r < q), the first
 * q - r slaves get a nodes and the last r get a + 1, so
 * N_i = i a + max(0, i - (q - r)).  (test_split checks it against the
 * recurrence.) */
static inline int split_n(int len, int q, int i) {
  int a = len / q, r = len % q, extra = i - (q - r);
  return i * a + (extra > 0 ? extra : 0);
}

/* The slave (0-based in the group) that computes column c of a diagonal whose
 * band is [a, b], split q ways. */
int split_owner(int a, int b, int q, int c);

/* Slaves for the paths below mu(mid), i.e. (mid, hi), out of p >= 2; the rest
 * take the paths above, (lo, mid).  half: ceil(p/2) (section 4).  size (and
 * fit, before its caps: par_fit.h): in proportion to the nodes of the two
 * subgraphs (section 7.1), at least one each when both have paths; a side
 * without paths gets none. */
int split_slaves(split_alloc how, int p, int64_t w_above, int64_t w_below, int paths_above,
                 int paths_below);

/* |W|: the nodes of the subgraph between U and L, where the paths
 * U->start+1 .. L->start-1 will be found, cut edges not counted (section 8);
 * 0 when there are no such paths. */
int64_t split_region(int m, int n, const gpath *U, const gpath *L);

/* The most slaves any diagonal of the band (s, U, L) keeps busy when each
 * must have at least d nodes: max over its diagonals of split_active(len,
 * oo, d), pinches excluded, at least 1. */
int split_usable(int m, int n, int s, const gpath *U, const gpath *L, int d);

const char *split_alloc_name(split_alloc a);   /* "half", "size", "fit" */
int split_alloc_parse(const char *s, split_alloc *a);

#endif
