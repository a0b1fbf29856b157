/* pool.h -- independent jobs on N threads, the same result on any N.
 *
 * The bands between slices are independent (the paper, section 6: "the
 * pairs of contours ... can be tiled independently"), and so are the slices
 * and the caps: job i is fn(ud, i), run exactly once, on whichever thread
 * takes it; fn writes its result by its index, never by the thread, so the
 * outcome is the same on 1 thread or 64. */
#ifndef POOL_H
#define POOL_H

/* Run fn(ud, i) for i = 0 .. njobs-1 on `threads` threads (the caller's
 * thread is one of them).  order (may be NULL: 0, 1, 2, ...) is the order in
 * which jobs are handed out: the biggest first keeps the threads busy to the
 * end.  Returns when every job is done. */
void pool_run(int threads, int njobs, const int *order, void (*fn)(void *ud, int job), void *ud);

/* The cores this process may run on (at least 1): the default of -j. */
int pool_cores(void);

/* order[0..n-1] = the indices 0..n-1 by decreasing size[i] (ties: the
 * smaller index first). */
void pool_order(const double *size, int n, int *order);

#endif
