/* judge.h -- the judge of the paper's seven claims (sections 6 and 7):
 * one set of criteria, with their tolerances, for `bench --claims` (sweeps
 * read from CSV) and `bench --claims-map` (sweeps run in memory).
 *
 *   1  2 processors are slightly slower than 1: T(1) < T(2) < 1.05 T(1), every size.
 *   2  a large drop from 2 to 3 processors: T(3) < 0.6 T(2), every size of 200+ points.
 *   3  half: little change 3 -> 4 and 5 -> 6: T(4) > 0.9 T(3), T(6) > 0.9 T(5),
 *      at the largest size.
 *   4  the speedup flattens, and degrades from about 12 processors (half, largest
 *      size): S(16) - S(8) < 0.5 (S(8) - 1), and the best speedup of P = 9..13
 *      above the best of P = 14..16 and no lower than the best of P = 1..8 (the
 *      speedup peaks at 9..13: it "begins to degrade at about 12", not at 4).
 *   5  size beats half, without the plateaus (largest size): size's speedup
 *      summed over P = 1..16 and its best above half's, and size's
 *      T(4) < 0.9 T(3), T(6) < 0.9 T(5).
 *   6  of d in 20, 40, .., 100 at the largest size, d = 80 gives the best time
 *      (the minimum over P).
 *   7  larger contours give larger speedups: the best speedup (half) grows with
 *      the points, size after size.
 *
 * T(P) is the simulated time on P processors, S(P) = T(1)/T(P) of the same
 * allocation.  Claims 1 to 5 need P = 1..16 with both allocations at the
 * largest size (judge_run refuses a sweep without them).  A claim the sweep
 * cannot show is n/a: 2 with no size of 200 points or more, 6 without a d
 * sweep that has d = 80 and another of 20..100, 7 with one size. */
#ifndef BENCH_JUDGE_H
#define BENCH_JUDGE_H

#include <stddef.h>

enum { JUDGE_MAXP = 64, JUDGE_MAXS = 32, JUDGE_MAXD = 128 };
enum { JUDGE_HALF = 0, JUDGE_SIZE = 1 };

typedef struct {
  int sizes[JUDGE_MAXS], nsizes, maxp;    /* sizes in increasing order */
  double T[2][JUDGE_MAXS][JUDGE_MAXP + 1];   /* [alloc][size][P], NAN if absent */
  double dbest[JUDGE_MAXD];   /* d sweep: the best time over P for d, INFINITY if none */
  int dpoints;                /* the d sweep's points (its largest), 0: no d sweep */
} judge_sweep;

/* An empty sweep. */
void judge_init(judge_sweep *s);

/* A run of the d = 1 sweep: points, P, alloc (JUDGE_HALF or JUDGE_SIZE) and
 * its time.  Sizes beyond JUDGE_MAXS and P beyond JUDGE_MAXP are ignored. */
void judge_add(judge_sweep *s, int points, int procs, int alloc, double time);

/* A run of the d sweep: only those at its largest points count (a larger
 * size drops what was there). */
void judge_add_d(judge_sweep *s, int points, int d, double time);

typedef struct {
  int holds[8];           /* [1..7]: 1 holds, 0 fails, -1 n/a */
  char detail[8][400];    /* what the sweep shows, a line each */
  /* The figures behind them, NAN (or 0 for the whole numbers) where absent. */
  int points;             /* the largest size */
  int half_best_p, size_best_p;   /* best P, and its speedup, largest size */
  double half_best, size_best;
  double t2_t1;           /* claim 1: the largest T(2)/T(1) over the sizes */
  double t3_t2;           /* claim 2: the largest T(3)/T(2) over sizes of 200+ */
  double t4_t3, t6_t5;    /* claim 3: half, largest size */
  double size_t4_t3, size_t6_t5;   /* claim 5: size, largest size */
  int best_d;             /* claim 6: the d of the best time, 0 without a d sweep */
} judge_verdict;

/* Judge the sweep.  0, or -1 and a message if it lacks P = 1..16 with both
 * allocations at its largest size. */
int judge_run(const judge_sweep *s, judge_verdict *v, char *err, size_t errlen);

/* The claims' short names, [1..7]. */
extern const char *const judge_name[8];

#endif
