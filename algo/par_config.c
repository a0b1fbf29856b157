/* par_config.c -- the parallel algorithm's options (par_config.h). */
#include "algo/par_config.h"

#include <stdio.h>
#include <string.h>

#include "util/args.h"
#include "util/words.h"

void par_config_init(par_config *pc) {
  memset(pc, 0, sizeof *pc);
  pc->opt.alloc = ALLOC_HALF;
  pc->opt.min_diag = 1;
  pc->opt.block = 1;
  pc->opt.schedule = PAR_STATIC;
  pc->kind = COST_AREA;
}

const char par_config_help[] =
    "  --alloc half|size|fit  processor allocation: half (section 4), by size (7.1),\n"
    "                     or fit: by size, no group more slaves than it can use\n"
    "  --min-diag d       at least d nodes of a diagonal per slave (7.2); default 1\n"
    "  --block k          slaves trade run-boundary costs every k diagonals (default 1)\n"
    "  --schedule NAME    static (the paper's groups) or dynamic (bands to free slaves)\n"
    "  --master-c S       seconds per unit of the master's bookkeeping (a column of\n"
    "                     a path it assembles, copies or measures); default c/100\n"
    "  --table-c S        seconds per cell of a slave's weight table (where slaves\n"
    "                     build one); --back-c S: per step of a slave's backtracking;\n"
    "                     default 0: not charged (tilesim-bench --calibrate measures\n"
    "                     both)\n";

/* The seconds options' range: from 0 to a billion seconds (31 years). */
#define MAX_SECONDS 1e9

static int seconds(const char *opt, const char *val, double *out, char *err, size_t errlen) {
  return args_real(opt, val, "seconds", 0, MAX_SECONDS, out, err, errlen) == 0 ? 1 : -1;
}

static int integer(const char *opt, const char *val, int lo, int hi, int *out, char *err,
                   size_t errlen) {
  long v;
  if (args_long(opt, val, lo, hi, &v, err, errlen) != 0) return -1;
  *out = (int)v;
  return 1;
}

/* The names the allocation parser takes (so the messages list whatever
 * split.c knows). */
void par_config_alloc_words(char *buf, size_t len) {
  words_join(split_alloc_names, SPLIT_ALLOCS, buf, len);
}

int par_config_option(par_config *pc, const char *opt, const char *val, char *err, size_t errlen) {
  char words[200];
  if (strcmp(opt, "--ranks") == 0) {
    snprintf(err, errlen, "--ranks: the paper's algorithm runs max(2, P) ranks on --procs P processors");
    return -1;
  }
  if (!val) val = "";
  if (strcmp(opt, "--master-c") == 0) {
    pc->master_c_given = 1;
    return seconds(opt, val, &pc->master_c, err, errlen);
  }
  if (strcmp(opt, "--table-c") == 0) return seconds(opt, val, &pc->table_c, err, errlen);
  if (strcmp(opt, "--back-c") == 0) return seconds(opt, val, &pc->back_c, err, errlen);
  if (strcmp(opt, "--min-diag") == 0)
    return integer(opt, val, 1, 1 << 30, &pc->opt.min_diag, err, errlen);
  if (strcmp(opt, "--block") == 0) return integer(opt, val, 1, 1 << 20, &pc->opt.block, err, errlen);
  if (strcmp(opt, "--schedule") == 0) {
    if (par_schedule_parse(val, &pc->opt.schedule) == 0) return 1;
    args_word(opt, val, "static|dynamic", err, errlen);
    return -1;
  }
  if (strcmp(opt, "--alloc") == 0) {
    if (split_alloc_parse(val, &pc->opt.alloc) == 0) return 1;
    par_config_alloc_words(words, sizeof words);
    args_word(opt, val, words, err, errlen);
    return -1;
  }
  return 0;
}

double par_config_master_c(const par_config *pc, double c) {
  return pc->master_c_given ? pc->master_c : PAR_MASTER_SHARE * c;
}

int par_config_prices(const par_config *pc, double c, par_options *out, char *err, size_t errlen) {
  *out = pc->opt;
  double mc = par_config_master_c(pc, c);
  if (!pc->master_c_given) out->book = PAR_MASTER_SHARE;
  else if (c > 0) out->book = mc / c;
  else if (mc == 0) out->book = 0;
  else {
    snprintf(err, errlen, "--master-c %g is a price in node units (c), and c is 0", mc);
    return -1;
  }
  static const char *const name[2] = {"--table-c", "--back-c"};
  const double sec[2] = {pc->table_c, pc->back_c};
  double *units[2] = {&out->table, &out->back};
  for (int i = 0; i < 2; i++) {
    *units[i] = sec[i] == 0 ? 0 : c > 0 ? sec[i] / c : -1;
    if (*units[i] < 0) {
      snprintf(err, errlen, "%s %g is a price in node units (c), and c is 0", name[i], sec[i]);
      return -1;
    }
  }
  return 0;
}
