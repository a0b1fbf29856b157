/* bench_claims.c -- the paper's claims, read off the sweeps.
 *
 *   bench --claims SPEEDUP.csv [MIN_DIAG.csv] [--require LIST]
 *
 * SPEEDUP.csv: a sweep over points and processors with both allocations
 * (d = 1); MIN_DIAG.csv: a sweep over d at the largest points (size).  One
 * CSV row per claim: claim,holds,detail; holds is yes, no, or n/a when the
 * sweeps cannot show it (one size for claim 7, none of 200+ points for 2, no
 * d sweep for 6).  --require 1,2,3: exit 1 unless
 * those claims hold (make check asserts the ones its reduced sweep can show).
 *
 *   1  2 processors are slightly slower than 1: T(1) < T(2) < 1.05 T(1), every size.
 *   2  a large drop from 2 to 3 processors: T(3) < 0.6 T(2), every size of 200+ points.
 *   3  half: little change 3 -> 4 and 5 -> 6: T(4) > 0.9 T(3), T(6) > 0.9 T(5),
 *      at the largest size.
 *   4  the speedup flattens, and degrades from about 12 processors (half, largest
 *      size): the processors past 8 add less than half what the first 8 did, and
 *      the best of P = 9..13 beats P = 16 and every P of 14..16.
 *   5  size beats half, without the plateaus: its speedup summed over P and its
 *      best are higher at the largest size, and T(4) < 0.9 T(3), T(6) < 0.9 T(5).
 *   6  of d in 20..100 at the largest size, d = 80 gives the best time (the
 *      minimum over P).
 *   7  larger contours give larger speedups: the best speedup (half) grows with
 *      the points. */
#include "bench_claims.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_list.h"
#include "csvtab.h"

enum { MAXP = 64, MAXS = 32 };

typedef struct {
  int sizes[MAXS], nsizes, maxp;
  double T[2][MAXS][MAXP + 1];   /* [alloc][size][procs] sim_time, NAN if absent */
} sweep;

static int read_sweep(const char *path, sweep *s, char *err, size_t errlen) {
  csvtab t;
  if (csvtab_read(path, &t, err, errlen) != 0) return -1;
  int cp = csvtab_col(&t, "points"), cP = csvtab_col(&t, "procs"), ca = csvtab_col(&t, "alloc");
  int ct = csvtab_col(&t, "sim_time"), cd = csvtab_col(&t, "min_diag");
  if (cp < 0 || cP < 0 || ca < 0 || ct < 0 || cd < 0) {
    snprintf(err, errlen, "%s: not a bench sweep (points, procs, alloc, min_diag, sim_time)", path);
    csvtab_free(&t);
    return -1;
  }
  memset(s, 0, sizeof *s);
  for (int a = 0; a < 2; a++)
    for (int i = 0; i < MAXS; i++)
      for (int p = 0; p <= MAXP; p++) s->T[a][i][p] = NAN;
  for (int r = 0; r < t.nrow; r++) {
    int pts = atoi(t.cell[r][cp]), P = atoi(t.cell[r][cP]), a = strcmp(t.cell[r][ca], "size") == 0;
    if (atoi(t.cell[r][cd]) != 1 || P < 1 || P > MAXP) continue;
    int i = 0;
    while (i < s->nsizes && s->sizes[i] != pts) i++;
    if (i == s->nsizes) {
      if (s->nsizes == MAXS) continue;
      s->sizes[s->nsizes++] = pts;
    }
    s->T[a][i][P] = atof(t.cell[r][ct]);
    if (P > s->maxp) s->maxp = P;
  }
  csvtab_free(&t);
  /* sizes in increasing order */
  for (int i = 0; i < s->nsizes; i++)
    for (int j = i + 1; j < s->nsizes; j++)
      if (s->sizes[j] < s->sizes[i]) {
        int x = s->sizes[i];
        s->sizes[i] = s->sizes[j], s->sizes[j] = x;
        for (int a = 0; a < 2; a++)
          for (int p = 0; p <= MAXP; p++) {
            double y = s->T[a][i][p];
            s->T[a][i][p] = s->T[a][j][p], s->T[a][j][p] = y;
          }
      }
  return 0;
}

static int has(const sweep *s, int a, int i, int from, int to) {
  for (int p = from; p <= to; p++)
    if (isnan(s->T[a][i][p])) return 0;
  return 1;
}

static double best_speedup(const sweep *s, int a, int i, int *at) {
  double b = 0;
  for (int p = 1; p <= s->maxp; p++)
    if (!isnan(s->T[a][i][p]) && s->T[a][i][1] / s->T[a][i][p] > b) b = s->T[a][i][1] / s->T[a][i][p], *at = p;
  return b;
}

int bench_claims(int argc, char **argv) {
  const char *sp = NULL, *md = NULL;
  bench_list req = {0};
  for (int i = 2; i < argc; i++) {
    if (strcmp(argv[i], "--require") == 0 && i + 1 < argc) {
      if (bench_list_parse(argv[++i], &req, 1, 1, 7) != 0) {
        fprintf(stderr, "bench: --require takes claim numbers 1..7 (%s)\n", argv[i]);
        return 2;
      }
    } else if (!sp) sp = argv[i];
    else if (!md) md = argv[i];
    else {
      fprintf(stderr, "usage: bench --claims SPEEDUP.csv [MIN_DIAG.csv] [--require LIST]\n");
      return 2;
    }
  }
  if (!sp) {
    fprintf(stderr, "usage: bench --claims SPEEDUP.csv [MIN_DIAG.csv] [--require LIST]\n");
    return 2;
  }
  char err[400];
  static sweep s;
  if (read_sweep(sp, &s, err, sizeof err) != 0) {
    fprintf(stderr, "bench: %s\n", err);
    return 1;
  }
  int L = s.nsizes - 1, holds[8] = {0};
  char detail[8][400];
  memset(detail, 0, sizeof detail);
  if (L < 0 || s.maxp < 16 || !has(&s, 0, L, 1, 16) || !has(&s, 1, L, 1, 16)) {
    fprintf(stderr, "bench: %s needs procs 1..16 with both allocations\n", sp);
    return 1;
  }
  double(*H)[MAXP + 1] = s.T[0], (*Z)[MAXP + 1] = s.T[1];

  holds[1] = 1;
  int k = 0;
  for (int i = 0; i <= L; i++) {
    holds[1] &= H[i][2] > H[i][1] && H[i][2] < 1.05 * H[i][1];
    k += snprintf(detail[1] + k, sizeof detail[1] - (size_t)k, "%s%d pts: T(2)/T(1) = %.5f", i ? "; " : "",
                  s.sizes[i], H[i][2] / H[i][1]);
  }
  holds[2] = -1, k = 0;
  for (int i = 0; i <= L; i++) {
    if (s.sizes[i] >= 200) holds[2] = (holds[2] != 0) && H[i][3] < 0.6 * H[i][2];
    k += snprintf(detail[2] + k, sizeof detail[2] - (size_t)k, "%s%d pts: T(3)/T(2) = %.3f", i ? "; " : "",
                  s.sizes[i], H[i][3] / H[i][2]);
  }
  holds[3] = H[L][4] > 0.9 * H[L][3] && H[L][6] > 0.9 * H[L][5];
  snprintf(detail[3], sizeof detail[3], "%d pts, half: T(4)/T(3) = %.3f, T(6)/T(5) = %.3f", s.sizes[L],
           H[L][4] / H[L][3], H[L][6] / H[L][5]);
  {
    double S1 = 1, S8 = H[L][1] / H[L][8], S16 = H[L][1] / H[L][16], mid = 0, late = 0;
    int bp = 0;
    for (int p = 9; p <= 13; p++)
      if (H[L][1] / H[L][p] > mid) mid = H[L][1] / H[L][p], bp = p;
    for (int p = 14; p <= 16; p++)
      if (H[L][1] / H[L][p] > late) late = H[L][1] / H[L][p];
    holds[4] = S16 - S8 < 0.5 * (S8 - S1) && mid > late;
    int at = 0;
    double top = best_speedup(&s, 0, L, &at);
    snprintf(detail[4], sizeof detail[4],
             "%d pts, half: speedup %.2f at 8, %.2f at 16; best of 9..13 %.2f at %d, of 14..16 %.2f; "
             "best overall %.2f at %d",
             s.sizes[L], S8, S16, mid, bp, late, top, at);
  }
  {
    double sh = 0, sz = 0;
    for (int p = 1; p <= 16; p++) sh += H[L][1] / H[L][p], sz += Z[L][1] / Z[L][p];
    int a1 = 0, a2 = 0;
    double bh = best_speedup(&s, 0, L, &a1), bz = best_speedup(&s, 1, L, &a2);
    int better = sz > sh && bz > bh, noplateau = Z[L][4] < 0.9 * Z[L][3] && Z[L][6] < 0.9 * Z[L][5];
    holds[5] = better && noplateau;
    snprintf(detail[5], sizeof detail[5],
             "%d pts: summed speedup size %.1f, half %.1f; best size %.2f, half %.2f; size T(4)/T(3) = %.3f, "
             "T(6)/T(5) = %.3f (%s%s)",
             s.sizes[L], sz, sh, bz, bh, Z[L][4] / Z[L][3], Z[L][6] / Z[L][5], better ? "better" : "not better",
             noplateau ? ", no plateaus" : ", the plateaus remain");
  }
  if (md) {
    csvtab t;
    if (csvtab_read(md, &t, err, sizeof err) != 0) {
      fprintf(stderr, "bench: %s\n", err);
      return 1;
    }
    int cd = csvtab_col(&t, "min_diag"), ct = csvtab_col(&t, "sim_time");
    double best[128];
    for (int d = 0; d < 128; d++) best[d] = INFINITY;
    for (int r = 0; cd >= 0 && ct >= 0 && r < t.nrow; r++) {
      int d = atoi(t.cell[r][cd]);
      double x = atof(t.cell[r][ct]);
      if (d >= 0 && d < 128 && x < best[d]) best[d] = x;
    }
    csvtab_free(&t);
    int bd = -1;
    k = 0;
    for (int d = 20; d <= 100; d += 20) {
      if (isinf(best[d])) continue;
      if (bd < 0 || best[d] < best[bd]) bd = d;
      k += snprintf(detail[6] + k, sizeof detail[6] - (size_t)k, "%sd=%d %.1f s", k ? ", " : "best times: ", d, best[d]);
    }
    holds[6] = bd == 80;
    snprintf(detail[6] + k, sizeof detail[6] - (size_t)k, "; the best is d=%d", bd);
  } else {
    holds[6] = -1;
    snprintf(detail[6], sizeof detail[6], "no min-diag sweep given");
  }
  holds[7] = L > 0 ? 1 : -1, k = 0;
  double prev = 0;
  for (int i = 0; i <= L; i++) {
    int at = 0;
    double b = best_speedup(&s, 0, i, &at);
    if (i && b <= prev) holds[7] = 0;
    prev = b;
    k += snprintf(detail[7] + k, sizeof detail[7] - (size_t)k, "%s%d pts %.2f", i ? ", " : "best speedups (half): ",
                  s.sizes[i], b);
  }
  static const char *name[8] = {"", "2 processors slightly slower than 1", "large drop from 2 to 3",
                                "half: little change 3-4 and 5-6", "speedup flattens, degrades from about 12",
                                "size better than half, no plateaus", "d = 80 gives the best time",
                                "larger contours, larger speedups"};
  printf("claim,holds,detail\n");
  int fail = 0;
  for (int c = 1; c <= 7; c++) {
    printf("%d %s,%s,%s\n", c, name[c], holds[c] < 0 ? "n/a" : holds[c] ? "yes" : "no", detail[c]);
  }
  for (int i = 0; i < req.n; i++)
    if (holds[(int)req.v[i]] != 1) {
      fprintf(stderr, "bench: claim %d does not hold: %s\n", (int)req.v[i], detail[(int)req.v[i]]);
      fail = 1;
    }
  return fail;
}
