/* claims.c -- the paper's claims, read off the sweeps.
 *
 *   bench --claims SPEEDUP.csv [MIN_DIAG.csv] [--require LIST]
 *
 * SPEEDUP.csv: a sweep over points and processors with both allocations
 * (d = 1); MIN_DIAG.csv: a sweep over d at the largest points (size).  One
 * CSV row per claim: claim,holds,detail (claim and detail quoted: they hold
 * commas); holds is yes, no, or n/a when the
 * sweeps cannot show it (one size for claim 7, none of 200+ points for 2, no
 * d sweep for 6).  --require 1,2,3: exit 1 unless
 * those claims hold (make check asserts the ones its reduced sweep can show).
 * The criteria and their tolerances: judge.h (the judge is shared
 * with --claims-map).  MIN_DIAG.csv counts at its largest points only. */
#include "prog/bench/bench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "prog/bench/judge.h"
#include "util/csvtab.h"
#include "util/progname.h"

/* The d = 1 rows of a speedup sweep into s. */
static int read_sweep(const char *path, judge_sweep *s, char *err, size_t errlen) {
  csvtab t;
  if (csvtab_read(path, &t, err, errlen) != 0) return -1;
  int cp = csvtab_col(&t, "points"), cP = csvtab_col(&t, "procs"), ca = csvtab_col(&t, "alloc");
  int ct = csvtab_col(&t, "sim_time"), cd = csvtab_col(&t, "min_diag");
  if (cp < 0 || cP < 0 || ca < 0 || ct < 0 || cd < 0) {
    snprintf(err, errlen, "%s: not a bench sweep (points, procs, alloc, min_diag, sim_time)", path);
    csvtab_free(&t);
    return -1;
  }
  for (int r = 0; r < t.nrow; r++) {
    if (atoi(t.cell[r][cd]) != 1) continue;
    int a = strcmp(t.cell[r][ca], "size") == 0 ? JUDGE_SIZE : strcmp(t.cell[r][ca], "half") == 0 ? JUDGE_HALF : -1;
    judge_add(s, atoi(t.cell[r][cp]), atoi(t.cell[r][cP]), a, atof(t.cell[r][ct]));
  }
  csvtab_free(&t);
  return 0;
}

/* The d sweep's rows into s (its largest points). */
static int read_dsweep(const char *path, judge_sweep *s, char *err, size_t errlen) {
  csvtab t;
  if (csvtab_read(path, &t, err, errlen) != 0) return -1;
  int cp = csvtab_col(&t, "points"), cd = csvtab_col(&t, "min_diag"), ct = csvtab_col(&t, "sim_time");
  if (cp < 0 || cd < 0 || ct < 0) {
    snprintf(err, errlen, "%s: not a bench sweep (points, min_diag, sim_time)", path);
    csvtab_free(&t);
    return -1;
  }
  for (int r = 0; r < t.nrow; r++) judge_add_d(s, atoi(t.cell[r][cp]), atoi(t.cell[r][cd]), atof(t.cell[r][ct]));
  csvtab_free(&t);
  return 0;
}

static const char claims_usage[] =
    "usage: bench --claims SPEEDUP.csv [MIN_DIAG.csv] [--require LIST]   (bench --help: every mode)\n";

static int usage(const char *why, const char *arg) { return args_usage("bench", claims_usage, why, arg); }

int bench_claims(int argc, char **argv) {
  const char *sp = NULL, *md = NULL;
  args_list req = {0};
  char msg[400];
  for (int i = 2; i < argc; i++) {
    const char *a = argv[i];
    if (strcmp(a, "--require") == 0) {
      if (i + 1 == argc) return usage("an option needs a value", a);
      if (args_list_max(a, argv[++i], 1, 1, 7, 7, &req, msg, sizeof msg) != 0) return usage(msg, NULL);
    } else if (a[0] == '-' && a[1] != 0) {
      return usage("unknown option", a);
    } else if (!a[0]) {
      return usage("a sweep is a CSV file name", a);
    } else if (!sp) {
      sp = a;
    } else if (!md) {
      md = a;
    } else {
      return usage("at most two sweeps, SPEEDUP.csv and MIN_DIAG.csv", a);
    }
  }
  if (!sp) return usage("no sweep given", NULL);
  char err[400];
  static judge_sweep s;
  judge_init(&s);
  if (read_sweep(sp, &s, err, sizeof err) != 0 || (md && read_dsweep(md, &s, err, sizeof err) != 0)) {
    progname_eprintf("bench: %s\n", err);
    return 1;
  }
  judge_verdict v;
  if (judge_run(&s, &v, err, sizeof err) != 0) {
    progname_eprintf("bench: %s %s\n", sp, err);
    return 1;
  }
  printf("claim,holds,detail\n");
  int fail = 0;
  for (int c = 1; c <= 7; c++)
    printf("\"%d %s\",%s,\"%s\"\n", c, judge_name[c], v.holds[c] < 0 ? "n/a" : v.holds[c] ? "yes" : "no",
           v.detail[c]);
  for (int i = 0; i < req.n; i++)
    if (v.holds[(int)req.v[i]] != 1) {
      progname_eprintf("bench: claim %d does not hold: %s\n", (int)req.v[i], v.detail[(int)req.v[i]]);
      fail = 1;
    }
  return fail;
}
