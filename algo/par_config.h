/* par_config.h -- the parallel algorithm's settings as a program's options
 * give them (prices in seconds), parsed in one place, and turned into the
 * par_options its ranks get (prices in node units of the machine's c).
 *
 *   --alloc half|size|fit  --min-diag d  --block k  --schedule static|dynamic
 *   --master-c S  --table-c S  --back-c S
 *
 * The machine's options (machine/machine.h) are parsed beside these: a
 * program asks par_config_option first, then machine_option. */
#ifndef PAR_CONFIG_H
#define PAR_CONFIG_H

#include <stddef.h>

#include "algo/par.h"
#include "algo/weights.h"

typedef struct {
  par_options opt;     /* alloc, min_diag, block, schedule (book, table and
                          back: par_config_prices) */
  cost_kind kind;      /* the tiles' cost */
  double master_c;     /* --master-c: seconds per unit of the master's
                          bookkeeping, when master_c_given; otherwise
                          PAR_MASTER_SHARE of the machine's c */
  int master_c_given;
  double table_c, back_c;   /* --table-c, --back-c: seconds per cell of a
                               slave's weight table, per step of its
                               backtracking; 0 (default): not charged */
} par_config;

/* The master's bookkeeping (par_master_charge: one unit a column of an
 * integer pass over a path, to assemble, copy, compare it or measure the band
 * beside it) against a node (two triangle areas with a software square root
 * and a comparison, c): on the 88100, which issues one instruction a clock, a
 * column is a few loads and stores, an add or a compare and the loop's
 * branch, about 10 clocks, and a node about 1,000 (sim.c, the tc2000's c =
 * 50 us at 20 MHz).  So by default a unit costs c/100: 0.5 us on the tc2000
 * (doc/model.md, "The master's bookkeeping"). */
#define PAR_MASTER_SHARE 0.01

/* The defaults: half allocation, d = 1, k = 1, static schedule, area cost,
 * the master's bookkeeping at PAR_MASTER_SHARE, tables and backtracking free. */
void par_config_init(par_config *pc);

/* Take one command-line option of the algorithm (the list above), or
 * refuse --ranks (the algorithm decides its ranks: par_ranks).  Values are
 * read strictly (util/args.h): d from 1 to 2^30, seconds from 0 to 1e9; val
 * NULL reads as "".  Returns 1 if opt is one of these (val consumed), 0 if
 * not, -1 for a bad value or --ranks, with a message in err ("--min-diag
 * takes a whole number from 1 to 1073741824 (0)"). */
int par_config_option(par_config *pc, const char *opt, const char *val, char *err, size_t errlen);

/* The names --alloc takes, '|'-separated ("half|size|fit"), for util/args. */
void par_config_alloc_words(char *buf, size_t len);

/* The usage text of the algorithm's options, one per line, indented (the
 * machine's: machine_help). */
extern const char par_config_help[];

/* The seconds one unit of the master's bookkeeping costs on a machine whose
 * node costs c seconds. */
double par_config_master_c(const par_config *pc, double c);

/* pc->opt with the price of the master's bookkeeping in node units
 * (book = par_config_master_c / c), and those of a slave's table cell and
 * backtracking step (table = table_c / c, back = back_c / c): what the ranks
 * get.  0, or -1 and a message if one cannot be said in node units (c = 0
 * and a price above 0). */
int par_config_prices(const par_config *pc, double c, par_options *out, char *err, size_t errlen);

#endif
