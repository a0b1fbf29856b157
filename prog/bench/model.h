/* bench_model.h -- ./bench --model (section 7.2's time per diagonal against
 * the simulation) and ./bench --glass (the glass of Fig. 17 as a stack). */
#ifndef BENCH_MODEL_H
#define BENCH_MODEL_H

/* The whole command line (argv[1] is the mode); the exit status. */
int bench_model(int argc, char **argv);
int bench_glass(int argc, char **argv);

#endif
