/* machine.h -- the machine a program runs on, and the options every tilesim
 * program takes to describe it, parsed in one place.
 *
 * A machine is a backend -- the simulated multiprocessor (sim/), POSIX
 * threads (mp/threads.h) or, in an MPI build, MPI processes -- with, for the
 * simulator, its costs, network, topology and the places of its processors.
 * ./tile, ./bench and users' programs (tilesim.h) take the same options with
 * the same ranges and messages:
 *
 *   --procs P  --ranks R  --backend sim|threads(|mpi)  --spin S
 *   --machine NAME  --net ideal|bus|loggp  --m S  --c S  --per-byte S  --local S
 *   --L S  --o S  --g S  --G S
 *   --o-send S  --o-send-byte S  --o-recv S  --o-recv-byte S  --wake S  --o-wake S
 *   --slowdown F  --slowdown-spin F        (the processor-side model, sim/cpu.h)
 *   --topology NAME  --hop-latency S  --switching MODE  --place NAME  --print-place
 *   --trace FILE.csv|FILE.json  --trace-limit BYTES
 *
 * (--machine sets every parameter of the simulated machine: give it before
 * the others).  Nothing here knows the paper's algorithm: its options live
 * in algo/par_config.h, parsed beside these by the programs. */
#ifndef MACHINE_H
#define MACHINE_H

#include <stddef.h>
#include <stdio.h>

#include "sim/place.h"
#include "sim/sim.h"
#include "mp/threads.h"

typedef enum {
  MACHINE_SIM,       /* the simulated machine: simulated seconds */
  MACHINE_THREADS,   /* one POSIX thread per rank: wall-clock seconds */
  MACHINE_MPI        /* one MPI process per rank (MPI builds only): wall-clock seconds */
} machine_backend;

/* "sim", "threads", "mpi". */
const char *machine_backend_name(machine_backend b);

/* The most ranks a run may have (--ranks); on the threads backend, whose
 * every rank is a thread of the host (with a stack and two mappings of its
 * own: 32,000 of them took 18 GB here before the host refused more); and the
 * most processors an option may ask for (--procs; ranks beyond share them). */
enum { MACHINE_MAX_RANKS = 1000000, MACHINE_MAX_THREADS = 4096, MACHINE_MAX_PROCS = 4096 };

/* --stack's bounds: each rank's stack on the simulator, in bytes, 16k to
 * 1G as the byte parser reads them (k = 10^3, G = 10^9). */
#define MACHINE_STACK_MIN 16000ULL
#define MACHINE_STACK_MAX 1000000000ULL

typedef struct {
  int procs;                      /* --procs: processors, >= 1 */
  int ranks;                      /* --ranks: a program's ranks (0: one per processor);
                                     the paper's algorithm sets its own */
  machine_backend backend;        /* --backend (default: sim; mpi in MPI builds) */
  sim_config sim;                 /* the simulated machine (procs and place are
                                     set per run); its warn is every backend's */
  mpt_config threads;             /* the threads backend (--spin) */
  place_spec place;               /* --place: where the processors go on the machine */
  const char *trace;              /* --trace FILE.csv|FILE.json, or NULL */
  unsigned long long trace_limit; /* --trace-limit (TRACE_LIMIT_DEFAULT; none: ULLONG_MAX) */
  int trace_limit_given;
  int print_place;                /* --print-place */
  const char *name;               /* the program's name: a long simulated run says
                                     how far it has got on stderr (util/progress.h);
                                     NULL: silent */
} machine_config;

/* The defaults: 1 processor, the simulator (MPI in an MPI build) with the
 * tc2000 profile, linear placement, no trace. */
void machine_config_init(machine_config *mc);

/* Take one option of the machine (the list above): 1 if opt is one (val
 * consumed, or none for --print-place: say so with machine_option_flag), 0
 * if not, -1 for a bad value with one line in err ("--procs takes a whole
 * number from 1 to 4096 (0)").  Values are read strictly (util/args.h). */
int machine_option(machine_config *mc, const char *opt, const char *val, char *err, size_t errlen);

/* 1 if opt is a machine option that takes no value (--print-place). */
int machine_option_flag(const char *opt);

/* The usage lines of the machine's options, indented two spaces; --ranks
 * and --stack apart (the paper's algorithm decides its ranks; tilesim-mpirun
 * has its own default stack). */
extern const char machine_help[];
extern const char machine_ranks_help[];
extern const char machine_stack_help[];

/* How many ranks the backend can run: 0 for no limit (sim, threads); for
 * MPI the size of the mpirun (0 outside an MPI build). */
int machine_backend_ranks(machine_backend b);

/* Where nranks ranks run on a simulated machine of P = mc->procs
 * processors: rank r on the processor --place gives the (r % P)-th; *nodes
 * is the machine's processors (the topology's, or P without one).  0, or
 * -1 and a message (a topology too small for P, a bad placement file). */
int machine_place(const machine_config *mc, int nranks, int *place, int *nodes, char *err,
                  size_t errlen);

/* Print where nranks ranks run (--print-place): a header line, one line per
 * rank, and on a line, ring, mesh or torus the grid of processors with the
 * lowest rank on each ('*': shared, '.': none).  0, or -1 and a message. */
int machine_print_place(FILE *f, const machine_config *mc, int nranks, char *err, size_t errlen);

/* The same for any machine: nranks ranks on processors place[] of topology t. */
void machine_print_map(FILE *f, const topo *t, const char *what, const int *place, int nranks);

#endif
