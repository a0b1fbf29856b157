/* bench_paper.h -- ./bench's main mode: the paper's experiments on the
 * simulated machine (sections 6 and 7), one CSV row per run. */
#ifndef BENCH_PAPER_H
#define BENCH_PAPER_H

/* The whole command line (no mode option); returns the exit status. */
int bench_paper(int argc, char **argv);

/* The usage text of its options. */
extern const char bench_paper_help[];

#endif
