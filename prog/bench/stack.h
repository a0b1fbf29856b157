/* bench_stack.h -- ./bench --stack: whole stacks into one surface, on 1, 2, ... threads. */
#ifndef BENCH_STACK_H
#define BENCH_STACK_H

/* The whole command line (argv[1] is "--stack"); returns the exit status. */
int bench_stack(int argc, char **argv);

#endif
