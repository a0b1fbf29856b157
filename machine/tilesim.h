/* tilesim.h -- your own message-passing program on tilesim's machines.
 *
 * A program is one function per rank, written against mp.h (send, receive,
 * probe, compute, time); tilesim runs it on
 *   - the simulated multiprocessor (the default): deterministic simulated
 *     time, with the machine's costs, network, topology and placement;
 *   - POSIX threads (--backend threads): the same program on this host's
 *     cores, in wall-clock seconds, as a functional check;
 *   - MPI processes (--backend mpi, in an MPI build: mpirun -np N ./prog).
 *
 * The smallest whole program:
 *
 *     #include <tilesim/tilesim.h>
 *
 *     static void ring(mp *self, void *ud) {
 *       int me = mp_rank(self), n = mp_size(self), token = 0;
 *       (void)ud;
 *       if (me == 0) mp_send(self, 1 % n, 0, &token, sizeof token);
 *       mp_recv(self, (me + n - 1) % n, 0, &token, sizeof token, NULL);
 *       if (me != 0) mp_send(self, (me + 1) % n, 0, &token, sizeof token);
 *     }
 *
 *     int main(int argc, char **argv) { return tilesim_main(argc, argv, ring, NULL); }
 *
 *     $ cc ring.c $(pkg-config --cflags --libs tilesim) -o ring
 *     $ ./ring --procs 16 --topology torus:4x4
 *
 * Rules for a rank (they make the same program right on every backend):
 *   - ranks share no memory: state lives on the rank's stack or behind its
 *     ud pointer (read-only if shared), never in mutable globals or statics
 *     (on threads they would race; on the simulator all ranks would share
 *     them);
 *   - charge computing with mp_compute(self, units) (units x --c seconds)
 *     or mp_busy(self, seconds): on the simulator nothing else costs time,
 *     however long the host takes;
 *   - the simulator is deterministic: the same program and options give
 *     byte-identical output, summary and trace; any-source receives take
 *     the earliest arrival, ties in a fixed order.
 * The guide (doc/testbed.md) says more, with the timing model and how to
 * read a trace in Perfetto.
 *
 * Every function below is safe to call from the program's main thread
 * only, outside a run (the ranks call mp.h). */
#ifndef TILESIM_H
#define TILESIM_H

#include <stddef.h>
#include <stdio.h>

#include "mp/mp.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TILESIM_VERSION "1.0.0"
#define TILESIM_VERSION_NUMBER 10000   /* major * 10000 + minor * 100 + patch */

/* TILESIM_VERSION, of the library linked in. */
const char *tilesim_version(void);

/* v in the shortest decimal form that reads back exactly, with a short
 * exponent ("0.1", "2.5e-5", "1e20"): a number for a person to read,
 * where %.17g would print 0.10000000000000001.  Writes at most len bytes into buf (32 hold any
 * double) and returns buf. */
char *tilesim_fmt_double(double v, char *buf, size_t len);

/* ==== a whole program ====================================================
 *
 * tilesim_main(argc, argv, rank_main, ud) is a program's main: it reads
 * the machine's options from argv (every option ./tile and ./bench take
 * for their machine, with the same ranges and messages: --procs, --ranks,
 * --backend, --machine, --net, --m, --c, --per-byte, --local, LogGP's --L
 * --o --g --G, the processor costs, --topology, --hop-latency, --switching,
 * --place, --print-place, --trace, --trace-limit; tilesim(7) lists them),
 * and --stats FILE|-|none (where the summary goes: "-", stdout, is the
 * default) and --help; the arguments after "--" are the program's own
 * (tilesim_argv).  It runs rank_main on --ranks ranks (default: one per
 * processor), each with ud, then writes the summary: a CSV header and one
 * row (tilesim_stats_csv).  Returns the exit status: 0, 1 for a failed run
 * (a deadlock, a rank's bad call, an abort: one line on stderr, naming the
 * ranks), 2 for bad usage (one line and the usage).  A run that a rank
 * aborts with mp_abort(self, code, why) returns code if it is 1 to 255. */
int tilesim_main(int argc, char **argv, mp_main rank_main, void *ud);

/* During tilesim_main's run, in any rank: the program's own arguments,
 * argv[0] its name, then those after "--" (argc in *argc; NULL-terminated).
 * The same, read-only, for every rank. */
char **tilesim_argv(int *argc);

/* The same in two steps, for a program that reads its own arguments before
 * the ranks start (as MPI_Init leaves argv to the program):
 *
 *     tilesim_machine *m;
 *     int status = tilesim_args(&argc, &argv, &m);
 *     if (m == NULL) return status;          (bad usage: 2; --help: 0)
 *     ... read argc, argv: argv[0] and the arguments after "--" ...
 *     return tilesim_exec(m, 0, rank_main, &params);
 *
 * tilesim_args leaves *m NULL after printing the help (status 0) or a bad
 * usage line (status 2); tilesim_exec runs as tilesim_main does on nranks
 * ranks (0: --ranks, or one per processor), writes the summary, frees m and
 * returns the exit status.  *argv is rewritten in place (argv[0] kept). */
typedef struct tilesim_machine tilesim_machine;
int tilesim_args(int *argc, char ***argv, tilesim_machine **m);
int tilesim_exec(tilesim_machine *m, int nranks, mp_main rank_main, void *ud);

/* ==== many runs in one process (a sweep) ==================================
 *
 *     tilesim_machine *m = tilesim_machine_new();
 *     char err[512];
 *     if (tilesim_machine_option(m, "--topology", "torus:4x4", err, sizeof err) != 1) ...
 *     for (...) {
 *       tilesim_machine_option(m, "--m", "2e-6", err, sizeof err);
 *       tilesim_stats st;
 *       if (tilesim_run(m, 16, rank_main, &params, &st, err, sizeof err) != 0) ...
 *       printf("%g\n", st.makespan);
 *     }
 *     tilesim_machine_free(m); */

/* A machine with the defaults: 1 processor, the simulator with the tc2000
 * profile (MPI in an MPI build), linear placement, no trace.  Never NULL. */
tilesim_machine *tilesim_machine_new(void);
void tilesim_machine_free(tilesim_machine *m);   /* NULL is fine */

/* Set one option as on the command line ("--procs", "16").  1 if it is a
 * machine option (tilesim_machine_flag: one that takes no value), 0 if
 * not, -1 for a bad value with one line in err ("--procs takes a whole
 * number from 1 to 4096 (0)").  Options apply in order: --machine first
 * (it sets every cost).  val is kept (not copied) for --trace. */
int tilesim_machine_option(tilesim_machine *m, const char *opt, const char *val, char *err,
                           size_t errlen);
int tilesim_machine_flag(const char *opt);

/* The ranks a run gets by default: --ranks, or one per --procs processor. */
int tilesim_machine_ranks(const tilesim_machine *m);

/* The machine options' usage text, a line each, indented two spaces. */
const char *tilesim_machine_help(void);

/* A run's statistics: plain values. */
typedef struct {
  const char *backend;             /* "sim", "threads" or "mpi" */
  int ranks, procs;
  double makespan;                 /* the last rank's end: simulated seconds on the
                                      simulator, wall-clock seconds otherwise */
  long long messages, bytes;       /* sent by all ranks */
  int measured;                    /* 2 (the simulator): every figure below is
                                      measured; 1 (threads): wait_* only; 0 (MPI): none */
  double compute_sum, compute_max; /* seconds computing (mp_compute, mp_busy):
                                      the sum over the ranks, the largest rank's */
  double wait_sum, wait_max;       /* seconds blocked for messages (mp_recv, mp_wait) */
  double cpu_wait_sum, cpu_wait_max;   /* seconds waiting for a shared processor */
  double overhead_sum, overhead_max;   /* seconds of send and receive overhead */
  double slept_sum;                /* seconds of mp_sleep */
  long long unread;                /* messages sent and never received */
  int deadlock;                    /* 1: the run ended in a deadlock */
  int aborted, abort_code;         /* a rank called mp_abort: the first one's code */
  unsigned long long trace_bytes;  /* the trace's bytes (0 without --trace) */
  double wall_s;                   /* host seconds the run took (never simulated) */
} tilesim_stats;

/* Run rank_main on nranks ranks (each with ud), or procs[r].main with
 * procs[r].ud per rank, on m.  *st (may be NULL) gets the statistics, also
 * of a failed run.  0, or -1 and one line in err (a deadlock naming every
 * blocked rank and what it waits for; a rank's bad call; an abort; a
 * machine that cannot be built; a trace over --trace-limit).  Writes
 * --trace if set: beside its target, renamed into place only when complete
 * and within the limit. */
int tilesim_run(const tilesim_machine *m, int nranks, mp_main rank_main, void *ud,
                tilesim_stats *st, char *err, size_t errlen);
int tilesim_run_procs(const tilesim_machine *m, int nranks, const mp_proc *procs,
                      tilesim_stats *st, char *err, size_t errlen);

/* The summary as CSV: the header line (header != 0) and one row:
 *   backend,ranks,procs,makespan,messages,bytes,compute_sum,compute_max,
 *   wait_sum,wait_max,cpu_wait_sum,cpu_wait_max,overhead_sum,overhead_max,
 *   unread,deadlock,abort_code
 * numbers in the shortest form that reads back exactly; a figure the
 * backend does not measure is empty. */
void tilesim_stats_csv(FILE *f, const tilesim_stats *st, int header);

#ifdef __cplusplus
}
#endif

#endif
