/* bench_ring.h -- bench's simulator-speed modes: the token ring and the bare coroutine switch. */
#ifndef BENCH_RING_H
#define BENCH_RING_H

/* bench --ring P --laps K [options]: P ranks on P processors pass a token
 * around K times; one CSV row of simulated and host figures.  argv[1] is
 * "--ring".  Returns the exit status: 0, 1 (the run failed or gave a wrong
 * token), 2 (bad usage, with a usage line on stderr). */
int bench_ring_main(int argc, char **argv);

/* bench --switch N: two coroutines switch to each other N times in all; one
 * CSV row with the nanoseconds per switch.  Exit status as above. */
int bench_switch_main(int argc, char **argv);

#endif
