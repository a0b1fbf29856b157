/* bench_union.h -- ./bench --union: the exact union of overlapping contours on one slice. */
#ifndef BENCH_UNION_H
#define BENCH_UNION_H

/* The whole command line (argv[1] is "--union"); returns the exit status. */
int bench_union(int argc, char **argv);

#endif
