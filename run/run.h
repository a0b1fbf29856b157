/* run.h -- running the parallel algorithm (algo/par_*.c) on a backend: the
 * simulated machine (sim/), POSIX threads (mp/threads.h) or, in the MPI
 * build, MPI processes (run_mpi.h).  The algorithm itself knows nothing of
 * what runs it; this is where ranks meet processors.
 *
 * Ranks: P processors run max(2, P) ranks, rank 0 the master.  On the
 * simulator P = 1 puts master and slave on one simulated processor.  On
 * threads and MPI there is no processor to share: P = 1 and P = 2 both run
 * the master and one slave, and the operating system places them; the
 * times are real seconds. */
#ifndef RUN_H
#define RUN_H

#include <stdio.h>

#include "machine/machine.h"
#include "algo/par_master.h"

/* A trace's size, counted by a run that writes none (run_config.trace_size). */
typedef struct {
  int csv, json;                        /* which traces to count */
  unsigned long long csv_bytes, json_bytes;   /* their bytes, after the run */
} run_trace_size;

typedef struct {
  machine_config mc;    /* the machine (machine/machine.h): mc.procs = P >= 1
                           processors; P = 1 puts master and slave on one
                           processor, P >= 2 gives the master one and P-1
                           slaves one each; mc.ranks is not used (run_ranks);
                           the threads backend's warnings go where
                           mc.sim.warn says, as every backend's do */
  par_options opt;
  cost_kind kind;
  FILE *trace_csv, *trace_json;   /* a timeline, or NULL */
  run_trace_size *trace_size;     /* or: count the bytes of one (sim only), or NULL */
  int *diag_sends, *diag_recvs;   /* test hook, see par_slave.h (or NULL) */
  int diag_len;
  void (*progress)(void *ud, int done, int total);   /* after each pair, or NULL */
  void *progress_ud;
  net_stats *pair_net;            /* simulator on a topology: each pair's network
                                     statistics (npairs of them), or NULL */
  double master_c;                /* --master-c: seconds per unit of the master's
                                     bookkeeping, when master_c_given; otherwise
                                     RUN_MASTER_SHARE of the machine's c */
  int master_c_given;
  double table_c, back_c;         /* --table-c, --back-c: seconds per cell of a
                                     slave's weight table, per step of its
                                     backtracking; 0 (default): not charged */
} run_config;

/* The master's bookkeeping (par_master_charge: one unit a column of an
 * integer pass over a path, to assemble, copy, compare it or measure the band
 * beside it) against a node (two triangle areas with a software square root
 * and a comparison, c): on the 88100, which issues one instruction a clock, a
 * column is a few loads and stores, an add or a compare and the loop's
 * branch, about 10 clocks, and a node about 1,000 (sim.c, the tc2000's c =
 * 50 us at 20 MHz).  So by default a unit costs c/100: 0.5 us on the tc2000
 * (doc/model.md, "The master's bookkeeping"). */
#define RUN_MASTER_SHARE 0.01

/* The seconds one unit of the master's bookkeeping costs under rc. */
double run_master_c(const run_config *rc);

/* rc->opt with the price of the master's bookkeeping in node units
 * (par_options.book = run_master_c / c), and those of a slave's table cell
 * and backtracking step (table = table_c / c, back = back_c / c): what every
 * backend's ranks get.  -1 and a message if one cannot be said in node units
 * (c = 0 and a price above 0). */
int run_par_options(const run_config *rc, par_options *out, char *err, size_t errlen);

/* A run_config with the defaults: machine_config_init's machine (1
 * processor, the simulator or MPI, tc2000), half allocation, d = 1, area
 * cost. */
void run_config_init(run_config *rc);

/* Take one command-line option of the machine (machine_option: every
 * option machine.h lists but --ranks, which the algorithm decides) or of
 * the algorithm:
 *   --alloc half|size|fit  --min-diag d  --block k  --schedule static|dynamic
 *   --master-c S  --table-c S  --back-c S
 * Values are read strictly (util/args.h): d from 1 to 2^30, seconds from 0
 * to 1e9.  Returns 1 if opt is one of these (val consumed, or none for a
 * flag: machine_option_flag), 0 if not, -1 for a bad value, with a message
 * in err ("--min-diag takes a whole number from 1 to 1073741824 (0)"). */
int run_option(run_config *rc, const char *opt, const char *val, char *err, size_t errlen);

/* The names --alloc takes, '|'-separated ("half|size"), for util/args. */
void run_alloc_words(char *buf, size_t len);

/* The usage text of the algorithm's options, one per line, indented (the
 * machine's: machine_help). */
extern const char run_options_help[];

/* The ranks for P processors: max(2, P). */
static inline int run_ranks(int procs) { return procs < 2 ? 2 : procs; }

/* Run the pairs on the simulated machine, one simulation for all of them
 * (each pair's time is its own: par_pair.time).  Returns 0, or -1 and a
 * message.  *stats (may be NULL) gets the simulator's statistics. */
int run_sim(const run_config *rc, par_pair *pairs, int npairs, sim_stats *stats, char *err,
            size_t errlen);

/* The same on POSIX threads, one run for all the pairs: par_pair.time is
 * wall-clock seconds (the master's, from sending a pair's points to holding
 * its optimum).  rc->mc.sim is not used.  *stats (may be NULL) gets the
 * backend's statistics. */
int run_threads(const run_config *rc, par_pair *pairs, int npairs, mpt_stats *stats, char *err,
                size_t errlen);

/* The pairs on rc->backend: run_sim, run_threads or (MPI build) run_mpi_pairs. */
int run_pairs(const run_config *rc, par_pair *pairs, int npairs, char *err, size_t errlen);

#endif
