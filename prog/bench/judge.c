/* judge.c -- the paper's seven claims judged on a sweep held in memory
 * (judge.h states the criteria; doc/paper.md, "The paper's claims"). */
#include "prog/bench/judge.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *const judge_name[8] = {"",
                                   "2 processors slightly slower than 1",
                                   "large drop from 2 to 3",
                                   "half: little change 3-4 and 5-6",
                                   "speedup flattens, degrades from about 12",
                                   "size better than half, no plateaus",
                                   "d = 80 gives the best time",
                                   "larger contours, larger speedups"};

void judge_init(judge_sweep *s) {
  memset(s, 0, sizeof *s);
  for (int a = 0; a < 2; a++)
    for (int i = 0; i < JUDGE_MAXS; i++)
      for (int p = 0; p <= JUDGE_MAXP; p++) s->T[a][i][p] = NAN;
  for (int d = 0; d < JUDGE_MAXD; d++) s->dbest[d] = INFINITY;
}

void judge_add(judge_sweep *s, int points, int procs, int alloc, double time) {
  if (procs < 1 || procs > JUDGE_MAXP || (alloc != JUDGE_HALF && alloc != JUDGE_SIZE)) return;
  int i = 0;
  while (i < s->nsizes && s->sizes[i] < points) i++;
  if (i == s->nsizes || s->sizes[i] != points) {   /* a new size, kept in order */
    if (s->nsizes == JUDGE_MAXS) return;
    for (int j = s->nsizes; j > i; j--) {
      s->sizes[j] = s->sizes[j - 1];
      for (int a = 0; a < 2; a++) memcpy(s->T[a][j], s->T[a][j - 1], sizeof s->T[a][j]);
    }
    s->sizes[i] = points;
    for (int a = 0; a < 2; a++)
      for (int p = 0; p <= JUDGE_MAXP; p++) s->T[a][i][p] = NAN;
    s->nsizes++;
  }
  s->T[alloc][i][procs] = time;
  if (procs > s->maxp) s->maxp = procs;
}

void judge_add_d(judge_sweep *s, int points, int d, double time) {
  if (points < s->dpoints) return;
  if (points > s->dpoints) {
    for (int k = 0; k < JUDGE_MAXD; k++) s->dbest[k] = INFINITY;
    s->dpoints = points;
  }
  if (d >= 0 && d < JUDGE_MAXD && time < s->dbest[d]) s->dbest[d] = time;
}

static int has(const judge_sweep *s, int a, int i, int from, int to) {
  for (int p = from; p <= to; p++)
    if (isnan(s->T[a][i][p])) return 0;
  return 1;
}

/* The best speedup T(1)/T(P) over the sweep's P, and the first P at it. */
static double best_speedup(const judge_sweep *s, int a, int i, int *at) {
  double b = 0;
  *at = 0;
  for (int p = 1; p <= s->maxp; p++)
    if (!isnan(s->T[a][i][p]) && s->T[a][i][1] / s->T[a][i][p] > b) b = s->T[a][i][1] / s->T[a][i][p], *at = p;
  return b;
}

/* Appends to a detail line (*k: its length so far, -1 once it failed). */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static void add(char *buf, size_t cap, int *k, const char *fmt, ...) {
  if (*k < 0 || (size_t)*k >= cap) return;
  va_list ap;
  va_start(ap, fmt);
  int w = vsnprintf(buf + *k, cap - (size_t)*k, fmt, ap);
  va_end(ap);
  *k = w < 0 ? -1 : *k + w;
}

int judge_run(const judge_sweep *s, judge_verdict *v, char *err, size_t errlen) {
  memset(v, 0, sizeof *v);
  int L = s->nsizes - 1;
  if (L < 0 || s->maxp < 16 || !has(s, JUDGE_HALF, L, 1, 16) || !has(s, JUDGE_SIZE, L, 1, 16)) {
    snprintf(err, errlen, "needs procs 1..16 with both allocations");
    return -1;
  }
  const double(*H)[JUDGE_MAXP + 1] = s->T[JUDGE_HALF], (*Z)[JUDGE_MAXP + 1] = s->T[JUDGE_SIZE];
  v->points = s->sizes[L];
  v->t2_t1 = v->t3_t2 = NAN;
  int k;

  /* 1: every size that has T(1) and T(2). */
  v->holds[1] = 1, k = 0;
  for (int i = 0; i <= L; i++) {
    if (!has(s, JUDGE_HALF, i, 1, 2)) continue;
    double r = H[i][2] / H[i][1];
    v->holds[1] &= H[i][2] > H[i][1] && H[i][2] < 1.05 * H[i][1];
    if (isnan(v->t2_t1) || r > v->t2_t1) v->t2_t1 = r;
    add(v->detail[1], sizeof v->detail[1], &k, "%s%d pts: T(2)/T(1) = %.5f", k ? "; " : "", s->sizes[i], r);
  }
  /* 2: every size of 200 points or more; n/a without one. */
  v->holds[2] = -1, k = 0;
  for (int i = 0; i <= L; i++) {
    if (!has(s, JUDGE_HALF, i, 2, 3)) continue;
    double r = H[i][3] / H[i][2];
    if (s->sizes[i] >= 200) {
      v->holds[2] = (v->holds[2] != 0) && H[i][3] < 0.6 * H[i][2];
      if (isnan(v->t3_t2) || r > v->t3_t2) v->t3_t2 = r;
    }
    add(v->detail[2], sizeof v->detail[2], &k, "%s%d pts: T(3)/T(2) = %.3f", k ? "; " : "", s->sizes[i], r);
  }
  /* 3: half, the largest size. */
  v->t4_t3 = H[L][4] / H[L][3], v->t6_t5 = H[L][6] / H[L][5];
  v->holds[3] = H[L][4] > 0.9 * H[L][3] && H[L][6] > 0.9 * H[L][5];
  snprintf(v->detail[3], sizeof v->detail[3], "%d pts, half: T(4)/T(3) = %.3f, T(6)/T(5) = %.3f", s->sizes[L],
           v->t4_t3, v->t6_t5);
  /* 4: half, the largest size. */
  {
    double S1 = 1, S8 = H[L][1] / H[L][8], S16 = H[L][1] / H[L][16], early = 0, mid = 0, late = 0;
    int bp = 0;
    for (int p = 1; p <= 8; p++)
      if (H[L][1] / H[L][p] > early) early = H[L][1] / H[L][p];
    for (int p = 9; p <= 13; p++)
      if (H[L][1] / H[L][p] > mid) mid = H[L][1] / H[L][p], bp = p;
    for (int p = 14; p <= 16; p++)
      if (H[L][1] / H[L][p] > late) late = H[L][1] / H[L][p];
    v->holds[4] = S16 - S8 < 0.5 * (S8 - S1) && mid > late && mid >= early;
    v->half_best = best_speedup(s, JUDGE_HALF, L, &v->half_best_p);
    snprintf(v->detail[4], sizeof v->detail[4],
             "%d pts, half: speedup %.2f at 8, %.2f at 16; best of 1..8 %.2f, of 9..13 %.2f at %d, of 14..16 "
             "%.2f; best overall %.2f at %d",
             s->sizes[L], S8, S16, early, mid, bp, late, v->half_best, v->half_best_p);
  }
  /* 5: size against half, the largest size. */
  {
    double sh = 0, sz = 0;
    for (int p = 1; p <= 16; p++) sh += H[L][1] / H[L][p], sz += Z[L][1] / Z[L][p];
    double bh = v->half_best, bz = best_speedup(s, JUDGE_SIZE, L, &v->size_best_p);
    v->size_best = bz;
    v->size_t4_t3 = Z[L][4] / Z[L][3], v->size_t6_t5 = Z[L][6] / Z[L][5];
    int better = sz > sh && bz > bh, noplateau = Z[L][4] < 0.9 * Z[L][3] && Z[L][6] < 0.9 * Z[L][5];
    v->holds[5] = better && noplateau;
    snprintf(v->detail[5], sizeof v->detail[5],
             "%d pts: summed speedup size %.1f, half %.1f; best size %.2f, half %.2f; size T(4)/T(3) = %.3f, "
             "T(6)/T(5) = %.3f (%s%s)",
             s->sizes[L], sz, sh, bz, bh, v->size_t4_t3, v->size_t6_t5, better ? "better" : "not better",
             noplateau ? ", no plateaus" : ", the plateaus remain");
  }
  /* 6: the d sweep; n/a without d = 80 and another d of 20..100. */
  if (s->dpoints > 0) {
    int bd = 0, nd = 0;
    k = 0;
    for (int d = 20; d <= 100; d += 20) {
      if (isinf(s->dbest[d])) continue;
      nd++;
      if (bd == 0 || s->dbest[d] < s->dbest[bd]) bd = d;
      add(v->detail[6], sizeof v->detail[6], &k, "%sd=%d %.1f s", k ? ", " : "best times: ", d, s->dbest[d]);
    }
    if (isinf(s->dbest[80]) || nd < 2) {
      v->holds[6] = -1;
      snprintf(v->detail[6], sizeof v->detail[6], "the d sweep (%d pts) lacks d = 80 or another d of 20..100",
               s->dpoints);
    } else {
      v->holds[6] = bd == 80;
      v->best_d = bd;
      add(v->detail[6], sizeof v->detail[6], &k, "; the best is d=%d", bd);
    }
  } else {
    v->holds[6] = -1;
    snprintf(v->detail[6], sizeof v->detail[6], "no min-diag sweep given");
  }
  /* 7: the best speedup (half) size after size; n/a with one size. */
  v->holds[7] = L > 0 ? 1 : -1, k = 0;
  double prev = 0;
  for (int i = 0; i <= L; i++) {
    int at;
    double b = best_speedup(s, JUDGE_HALF, i, &at);
    if (i && b <= prev) v->holds[7] = 0;
    prev = b;
    add(v->detail[7], sizeof v->detail[7], &k, "%s%d pts %.2f", i ? ", " : "best speedups (half): ", s->sizes[i], b);
  }
  return 0;
}
