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

#include "par_master.h"
#include "place.h"
#include "sim.h"
#include "threads.h"

typedef enum {
  RUN_SIM,       /* the simulated machine: simulated seconds */
  RUN_THREADS,   /* one POSIX thread per rank: wall-clock seconds */
  RUN_MPI        /* one MPI process per rank (MPI build only): wall-clock seconds */
} run_backend;

/* "sim", "threads", "mpi". */
const char *run_backend_name(run_backend b);

/* How many ranks the backend can run: 0 for no limit (sim, threads); for
 * MPI the size of the mpirun (0 outside the MPI build). */
int run_backend_ranks(run_backend b);

/* A trace's size, counted by a run that writes none (run_config.trace_size). */
typedef struct {
  int csv, json;                        /* which traces to count */
  unsigned long long csv_bytes, json_bytes;   /* their bytes, after the run */
} run_trace_size;

typedef struct {
  int procs;            /* P >= 1: P = 1 puts master and slave on one processor,
                           P >= 2 gives the master one and P-1 slaves one each */
  run_backend backend;  /* what runs the ranks (default: sim; mpi in MPI builds) */
  sim_config machine;   /* the machine model (procs and place are set here) */
  mpt_config threads;   /* the threads backend's settings (its warnings go
                           where machine.warn says, as every backend's do) */
  par_options opt;
  cost_kind kind;
  FILE *trace_csv, *trace_json;   /* a timeline, or NULL */
  run_trace_size *trace_size;     /* or: count the bytes of one (sim only), or NULL */
  int *diag_sends, *diag_recvs;   /* test hook, see par_slave.h (or NULL) */
  int diag_len;
  void (*progress)(void *ud, int done, int total);   /* after each pair, or NULL */
  void *progress_ud;
  place_spec place;               /* where the P processors go on the machine (run_net.h) */
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
 * (README, "The master's bookkeeping"). */
#define RUN_MASTER_SHARE 0.01

/* The seconds one unit of the master's bookkeeping costs under rc. */
double run_master_c(const run_config *rc);

/* rc->opt with the price of the master's bookkeeping in node units
 * (par_options.book = run_master_c / c), and those of a slave's table cell
 * and backtracking step (table = table_c / c, back = back_c / c): what every
 * backend's ranks get.  -1 and a message if one cannot be said in node units
 * (c = 0 and a price above 0). */
int run_par_options(const run_config *rc, par_options *out, char *err, size_t errlen);

/* A run_config with the defaults: 1 processor, the simulator (MPI in an
 * MPI build) with the tc2000 machine, half allocation, d = 1, area cost. */
void run_config_init(run_config *rc);

/* The most processors an option may ask for. */
enum { RUN_MAX_PROCS = 4096 };

/* Take one command-line option of the machine or the algorithm:
 *   --procs P  --alloc half|size|fit  --min-diag d  --block k  --schedule static|dynamic
 *   --master-c S  --table-c S  --back-c S
 *   --machine NAME  --net ideal|bus|loggp
 *   --m S  --c S  --per-byte S  --local S  --L S  --o S  --g S  --G S
 *   --o-send S  --o-send-byte S  --o-recv S  --o-recv-byte S  --wake S
 *   --o-wake S  --slowdown F  --slowdown-spin F (the processor-side model, sim/cpu.h)
 *   --backend sim|threads (|mpi in MPI builds)
 *   --spin S (threads; and the simulator's sleep threshold, cpu.h)
 *   --topology NAME  --hop-latency S  --switching MODE  --place NAME (run_net.h)
 * (--machine sets every machine parameter; give it before the others).
 * Values are read strictly (util/args.h): P from 1 to RUN_MAX_PROCS, d from
 * 1 to 2^30, seconds from 0 to 1e9 (--spin: to 10).
 * Returns 1 if opt is one of these (val consumed), 0 if not, -1 for a bad
 * value, with a message in err ("--procs takes a whole number from 1 to
 * 4096 (0)"). */
int run_option(run_config *rc, const char *opt, const char *val, char *err, size_t errlen);

/* The names --alloc takes, '|'-separated ("half|size"), for util/args. */
void run_alloc_words(char *buf, size_t len);

/* The usage text of those options, one per line, indented. */
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
 * its optimum).  rc->machine is not used.  *stats (may be NULL) gets the
 * backend's statistics. */
int run_threads(const run_config *rc, par_pair *pairs, int npairs, mpt_stats *stats, char *err,
                size_t errlen);

/* The pairs on rc->backend: run_sim, run_threads or (MPI build) run_mpi_pairs. */
int run_pairs(const run_config *rc, par_pair *pairs, int npairs, char *err, size_t errlen);

#endif
