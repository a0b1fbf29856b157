/* bench_paper.h -- ./bench's main mode: the paper's experiments on the
 * simulated machine (sections 6 and 7), one CSV row per run. */
#ifndef BENCH_PAPER_H
#define BENCH_PAPER_H

#include "geom.h"

/* The whole command line (no mode option); returns the exit status. */
int bench_paper(int argc, char **argv);

/* The generated pair of `points` points for a seed (two random star-shaped
 * contours, section 6), the same in every mode; the caller frees both. */
void bench_make_pair(unsigned long long seed, int points, vec2 **P, vec2 **Q);

/* The usage text of its options. */
extern const char bench_paper_help[];

#endif
