/* paper.h -- the machinery of ./bench's main mode, the paper's sweeps
 * (bench_paper, bench.h), that other modes use: the generated pairs and
 * runs spread over forked workers. */
#ifndef BENCH_PAPER_H
#define BENCH_PAPER_H

#include "input/contour.h"
#include "geom/geom.h"
#include "run/run.h"

/* The generated pair of `points` points for a seed (two random star-shaped
 * contours, section 6), the same in every mode; the caller frees both. */
void bench_make_pair(unsigned long long seed, int points, vec2 **P, vec2 **Q);

/* The sweeps' machinery for other modes (bench --claims-map): runs, each
 * the paper's algorithm on one pair under one configuration, spread over
 * `jobs` forked workers, their times in run order whatever the workers'
 * speed.  A configuration: the machine and the algorithm's options (rc;
 * procs, alloc and d are each run's) and the pair, generated from a seed or
 * pair K of a stack (kept by the caller). */
typedef struct {
  run_config rc;
  unsigned long long seed;
  const contour_stack *input;   /* NULL: a generated pair of each run's points */
  int pair;
} bench_cfg;

typedef struct {
  int cfg;                  /* its configuration */
  int points, procs, alloc, d;
} bench_run;

/* The simulated times of the n runs into times[]; 0, or -1 and a message
 * naming a failed run. */
int bench_sweep_runs(const bench_cfg *cfgs, const bench_run *runs, int n, int jobs, double *times,
                     char *err, size_t errlen);


#endif
