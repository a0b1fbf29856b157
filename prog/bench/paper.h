/* paper.h -- the machinery of ./bench's main mode, the paper's sweeps
 * (bench_paper, bench.h), that other modes use: the generated pairs and
 * runs spread over forked workers. */
#ifndef BENCH_PAPER_H
#define BENCH_PAPER_H

#include "input/contour.h"
#include "geom/geom.h"
#include "algo/par_run.h"
#include "machine/launch.h"
#include "machine/machine.h"

/* A run's settings, as bench's options give them: the machine's and the
 * algorithm's. */
typedef struct {
  machine_config mc;
  par_config pc;
} bench_machine;

/* The defaults of both (machine_config_init, par_config_init). */
void bench_machine_init(bench_machine *bm);

/* One option of the algorithm or of the machine: 1, 0 (neither's) or -1 (a
 * bad value), as par_config_option and machine_option say. */
int bench_option(bench_machine *bm, const char *opt, const char *val, char *err, size_t errlen);

/* The pairs by the paper's algorithm on bm's machine (whose --trace bench
 * does not write), with what x adds (NULL: nothing; x->periods: each pair's
 * network statistics).  0, or -1 and a message (par_run_pairs). */
int bench_run_pairs(const bench_machine *bm, par_pair *pairs, int npairs, launch_extra *x, char *err,
                    size_t errlen);

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
  bench_machine rc;
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
