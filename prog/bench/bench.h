/* bench.h -- ./bench's modes, one function each, as bench.c's table of
 * modes calls them (git's builtin.h keeps its commands so): each gets the
 * whole command line (argv[1] is the mode's option, none for the paper's
 * sweeps), parses its own options and returns the exit status: 0, 1 (a run
 * failed, or gave a wrong answer), 2 (bad usage, with a usage line on
 * stderr).  The helpers the modes share have headers of their own beside
 * this one (paper.h: the sweeps' machinery; judge.h, net.h, variant.h,
 * micro.h, blocks.h, data.h). */
#ifndef BENCH_BENCH_H
#define BENCH_BENCH_H

/* The paper's experiments on the simulated machine (sections 6 and 7), one
 * CSV row per run: no mode option.  bench_paper_help: the usage text of its
 * options. */
int bench_paper(int argc, char **argv);
extern const char bench_paper_help[];

/* --ring P --laps K [options]: P ranks on P processors pass a token around
 * K times; one CSV row of simulated and host figures: the simulator's
 * speed. */
int bench_ring(int argc, char **argv);
/* --switch N: two coroutines switch to each other N times in all; one CSV
 * row with the nanoseconds per switch. */
int bench_switch(int argc, char **argv);

/* --model: section 7.2's time per diagonal against the simulation. */
int bench_model(int argc, char **argv);
/* --glass: the glass of Fig. 17 as a contour stack. */
int bench_glass(int argc, char **argv);

/* --claims: the paper's seven claims (sections 6 and 7), checked against
 * the sweeps' CSV. */
int bench_claims(int argc, char **argv);
/* --claims-map: the seven claims judged on many machines and pairs at
 * once, one CSV row per configuration. */
int bench_claims_map(int argc, char **argv);

/* --calibrate [--points N] [--procs LIST] [--repeat R] [--seed S]
 * [--messages K]: this host's cost per node and per message, the
 * simulator's options that model it, and the simulator's predictions beside
 * the threads backend's measured times; one CSV row per P. */
int bench_calibrate(int argc, char **argv);

/* --tiler: the exact tiler's speed and memory. */
int bench_tiler(int argc, char **argv);
/* --stack: whole stacks into one surface, on 1, 2, ... threads. */
int bench_stack(int argc, char **argv);
/* --dicom: how fast an RT structure set is read. */
int bench_dicom(int argc, char **argv);
/* --union: the exact union of overlapping contours on one slice. */
int bench_union(int argc, char **argv);

#endif
