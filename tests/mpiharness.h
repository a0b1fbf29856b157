/* mpiharness.h -- run an MPI program's main as every rank of the simulator
 * or of the threads backend, in this process: the tests' driver for the
 * MPI layer (tilesim-mpirun does it for users, with a copy of the program
 * per rank).  The programs must then have no mutable globals: every rank
 * runs the same copy. */
#ifndef MPIHARNESS_H
#define MPIHARNESS_H

#include <stdio.h>

#include "sim/sim.h"

typedef int (*mpih_main)(int argc, char **argv);

enum { MPIH_SIM, MPIH_THREADS };

typedef struct {
  int backend;          /* MPIH_SIM or MPIH_THREADS */
  int ranks;            /* >= 1 */
  sim_config sim;       /* the simulator's machine (mpih_config_init: --net
                           ideal, binary-fraction costs, one processor per rank) */
  double poll_cost;     /* init_set_poll_cost (default 1e-6) */
  FILE *warn;           /* the backend's warnings (default NULL: quiet) */
} mpih_config;

void mpih_config_init(mpih_config *cfg, int backend, int ranks);

typedef struct {
  int rc;               /* sim_run / mpt_run: 0, or -1 with err */
  char err[2048];
  int *exit;            /* per rank: main's return value, or MPIH_NOEXIT */
  int *end;             /* per rank: init_rank_end's answer (TSMPI_*) */
  double *finish;       /* per rank: simulated finish (the simulator) */
  double makespan;      /* the simulator's */
  long long pooled;     /* the simulator's payload bytes copied twice (sim_stats) */
  long long messages;   /* mp messages sent */
  long long bytes;
  long long unread;
  int deadlock, aborted, abort_code;
} mpih_result;

enum { MPIH_NOEXIT = -1000000 };   /* the rank never returned from main */

/* Run main(argc, argv) on every rank (argv shared, read-only).  0, or -1
 * (a bad configuration, err filled).  Free the result with
 * mpih_result_free. */
int mpih_run(const mpih_config *cfg, mpih_main main_fn, int argc, char **argv, mpih_result *res);

/* The same with fn(ud) as every rank's main (a test's own program). */
typedef int (*mpih_fn)(void *ud);
int mpih_run_fn(const mpih_config *cfg, mpih_fn fn, void *ud, mpih_result *res);
void mpih_result_free(mpih_result *res);

/* mpih_run_fn's result, returned (mpih_run_fn's answer is res.rc). */
mpih_result mpih_result_of(const mpih_config *cfg, mpih_fn fn, void *ud);

/* For a test's own program: MPI_Init(NULL, NULL), then this rank's number
 * in MPI_COMM_WORLD. */
int mpih_init(void);

#endif
