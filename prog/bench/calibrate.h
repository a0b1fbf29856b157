/* bench_calibrate.h -- bench --calibrate: this host's cost per node and per
 * message, the simulator's options that model it, and the simulator's
 * predictions beside the threads backend's measured times. */
#ifndef BENCH_CALIBRATE_H
#define BENCH_CALIBRATE_H

/* bench --calibrate [--points N] [--procs LIST] [--repeat R] [--seed S]
 * [--messages K]: one CSV row per P.  argv[1] is "--calibrate".  Returns
 * the exit status: 0, 1 (a run failed), 2 (bad usage). */
int bench_calibrate(int argc, char **argv);

#endif
