/* blocks.h -- a loop whose basic blocks are counted (blocks.c is
 * compiled with -fsanitize-coverage=trace-pc), for micro_block. */
#ifndef BENCH_BLOCKS_H
#define BENCH_BLOCKS_H

/* cpi's integral of 4 / (1 + x^2) over [0, 1] by n midpoints: pi. */
double blocks_cpi(long n);

#endif
