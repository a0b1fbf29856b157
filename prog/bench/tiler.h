/* bench_tiler.h -- ./bench --tiler: the exact tiler's speed and memory. */
#ifndef BENCH_TILER_H
#define BENCH_TILER_H

/* The whole command line (argv[1] is "--tiler"); returns the exit status. */
int bench_tiler(int argc, char **argv);

#endif
