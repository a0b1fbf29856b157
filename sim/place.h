/* place.h -- placing a run's processors on a topology's: linear, snake, gray, random, from a file.
 *
 * A run on P processors numbers them 0..P-1 (processor v runs rank v; P = 1
 * puts master and slave on processor 0).  A placement maps each v to a
 * distinct processor of the machine (topo.h, N >= P):
 *
 *   linear         v -> v (row-major on a mesh or torus)
 *   snake          v -> the v-th processor of the boustrophedon order on a mesh
 *                  or torus: row 0 left to right, row 1 right to left, ...  The
 *                  algorithm's line of processors then has dilation 1.  Other
 *                  topologies have no rows: linear.
 *   gray           v -> the v-th binary-reflected Gray code g(i) = i ^ (i >> 1)
 *                  below N (all of them when N is a power of two): on a
 *                  hypercube, neighbours v and v+1 are neighbours, and so are
 *                  P-1 and 0 when P is a power of two.
 *   random:SEED    the first P of a random permutation of 0..N-1 (seeded,
 *                  the same on every platform)
 *   file:PATH      line v of PATH holds v's processor, a whole number; blank
 *                  lines and lines starting with '#' are skipped; the first P
 *                  are used.  A processor named twice, or not a whole number,
 *                  or outside the machine, is refused with PATH:LINE.
 *
 * The placement changes where ranks run, so it changes only times, never a
 * result. */
#ifndef PLACE_H
#define PLACE_H

#include <stddef.h>

#include "sim/topo.h"

typedef enum { PLACE_LINEAR, PLACE_SNAKE, PLACE_GRAY, PLACE_RANDOM, PLACE_FILE } place_kind;

enum { PLACE_PATH_MAX = 1024 };

/* A placement by name: a plain value (a file is read when parsed, to check
 * it, and again by place_map). */
typedef struct {
  place_kind kind;
  unsigned long long seed;     /* random */
  char path[PLACE_PATH_MAX];   /* file */
} place_spec;

/* "linear", "snake", "gray", "random:SEED", "file:PATH" (the file is read
 * and checked here).  0, or -1 and a message ("PATH:LINE: ..." for a bad
 * file). */
int place_parse(const char *s, place_spec *out, char *err, size_t errlen);

/* The name place_parse reads back. */
void place_spec_str(const place_spec *p, char *buf, size_t len);

/* map[v] for v = 0..n-1 on the N processors of t: distinct, 0..N-1.
 * 0, or -1 and a message (n > N; a file that is bad, too short or names a
 * processor outside the machine). */
int place_map(const place_spec *p, const topo *t, int n, int *map, char *err, size_t errlen);

#endif
