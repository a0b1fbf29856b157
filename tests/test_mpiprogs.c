/* test_mpiprogs.c -- the datatype, operation, collective, topology and I/O programs of tests/mpi/
 * on the simulator: on 1 to 16 ranks with MPICH's choices, and on six rank counts each (powers
 * of two and others; the nonblocking collectives' program on 5 and 8) with --coll linear and
 * with each algorithm of each collective they use forced in turn, so that every algorithm runs
 * at the sizes the programs use, on both sides of MPICH's thresholds, blocking and not; and on
 * the threads backend, where messages arrive in the host's order.
 *
 * Each program checks itself (tests/mpi/mtest.h): a run passes when every rank's main returns
 * 0 and the run ends cleanly.  The programs are linked in with their main renamed
 * tsmpi_main_NAME (the Makefile), and run by tests/mpiharness.c, every rank in this process.
 *
 *   test_mpiprogs                      all that
 *   test_mpiprogs NAME [NP [SETTING]]  one program: on 1..16 or NP ranks, under every setting
 *                                      or one --coll SETTING
 *   test_mpiprogs --reports            the errors, deadlock reports and trace only */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/init.h"
#include "mpi/mpi.h"
#include "mpi/settings.h"
#include "tests/check.h"
#include "tests/mpiharness.h"
#include "tests/mpiprogs.h"

/* The programs this driver runs: the datatype, operation, collective,
 * topology and I/O ones (point-to-point's have their own). */
static int mine(const char *name) {
  return !strncmp(name, "coll_", 5) || !strncmp(name, "dtype_", 6) || !strncmp(name, "op_", 3) ||
         !strncmp(name, "topo_", 5) || !strncmp(name, "io_", 3);
}

/* Which collectives a program's checks depend on: the settings worth
 * forcing for it (the others run MPICH's choice and linear only). */
static const struct {
  const char *prefix;
  coll_id colls[COLL_N];
  int n;
  int np[2];   /* forced on these rank counts only (0: on every one of forced_np) */
} uses[] = {
  {"coll_bcast", {COLL_BCAST, COLL_BARRIER}, 2, {0, 0}},
  {"coll_reduce", {COLL_REDUCE, COLL_ALLREDUCE}, 2, {0, 0}},
  {"coll_gather", {COLL_GATHER, COLL_GATHERV, COLL_SCATTER, COLL_SCATTERV, COLL_ALLGATHER, COLL_ALLGATHERV}, 6, {0, 0}},
  {"coll_alltoall", {COLL_ALLTOALL, COLL_ALLTOALLV}, 2, {0, 0}},
  {"coll_scan", {COLL_SCAN, COLL_EXSCAN, COLL_REDUCE_SCATTER, COLL_REDUCE_SCATTER_BLOCK}, 4, {0, 0}},
  {"coll_order", {COLL_REDUCE, COLL_ALLREDUCE, COLL_SCAN, COLL_EXSCAN}, 4, {0, 0}},
  {"coll_nbc", {COLL_BARRIER, COLL_BCAST, COLL_REDUCE, COLL_ALLREDUCE, COLL_GATHER, COLL_SCATTER, COLL_ALLGATHER,
                COLL_ALLGATHERV, COLL_ALLTOALL, COLL_ALLTOALLV, COLL_ALLTOALLW, COLL_SCAN, COLL_EXSCAN,
                COLL_REDUCE_SCATTER, COLL_REDUCE_SCATTER_BLOCK}, 15, {5, 8}},
};

/* Run one program on np ranks under one setting ("mpich", "linear",
 * "bcast=binomial"); 1 if it passed. */
static int run(const char *name, mpih_main fn, int np, const char *setting, int backend) {
  char err[256];
  coll_reset();
  if (coll_option(setting, err, sizeof err) != 0) {
    CHECK(0, "%s: %s", name, err);
    return 0;
  }
  mpih_config cfg;
  mpih_config_init(&cfg, backend, np);
  char *argv[] = {(char *)name, (char *)setting, NULL};
  mpih_result res;
  int rc = mpih_run(&cfg, fn, 2, argv, &res), ok = rc == 0 && res.rc == 0;
  int bad = -1;
  for (int r = 0; r < np && ok; r++)
    if (res.exit[r] != 0) ok = 0, bad = r;
  CHECK(ok, "%s on %d ranks (%s, --coll %s): %s%s (rank %d returned %d)", name, np,
        backend == MPIH_SIM ? "simulator" : "threads", setting, rc ? "bad configuration: " : "",
        rc || res.rc ? res.err : "a check failed", bad, bad >= 0 ? res.exit[bad] : 0);
  mpih_result_free(&res);
  coll_reset();
  return ok;
}

/* The settings for program p on np ranks: MPICH's choices always; linear
 * and each algorithm forced (all: or only) on some rank counts, powers of
 * two and others, small and large (the time of make check). */
static int in(int np, const int *set, int n) {
  for (int i = 0; i < n; i++)
    if (set[i] == np) return 1;
  return 0;
}

static void settings(int p, int np, int all) {
  static const int linear_np[] = {1, 3, 5, 8, 13, 16}, forced_np[] = {2, 3, 5, 8, 11, 16};
  run(progs[p].name, progs[p].fn, np, "mpich", MPIH_SIM);
  if (all || in(np, linear_np, 6)) run(progs[p].name, progs[p].fn, np, "linear", MPIH_SIM);
  if (!all && !in(np, forced_np, 6)) return;
  for (size_t u = 0; u < sizeof uses / sizeof uses[0]; u++) {
    if (strncmp(progs[p].name, uses[u].prefix, strlen(uses[u].prefix))) continue;
    if (!all && uses[u].np[0] && np != uses[u].np[0] && np != uses[u].np[1]) continue;
    for (int c = 0; c < uses[u].n; c++) {
      coll_id coll = uses[u].colls[c];
      for (int a = ALG_DISSEMINATION; a < ALG_N; a++) {
        char setting[96], err[256];
        snprintf(setting, sizeof setting, "%s=%s", coll_name(coll), coll_alg_name((coll_alg)a));
        if (coll_option(setting, err, sizeof err) != 0) continue;   /* not one of its algorithms */
        coll_reset();
        run(progs[p].name, progs[p].fn, np, setting, MPIH_SIM);
      }
    }
  }
}

/* ==== what a run of collectives reports ================================== */

/* Every rank broadcasts from a root that does not exist: the first to
 * check stops the run (MPI_ERRORS_ARE_FATAL, exit code 1). */
static int bad_root(int argc, char **argv) {
  int x = 0;
  MPI_Init(&argc, &argv);
  MPI_Bcast(&x, 1, MPI_INT, 7, MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}

/* Rank 0 waits for a message rank 1 never sends, rank 1 in a collective:
 * the deadlock report names the collective each waits in. */
static int stuck(int argc, char **argv) {
  int x = 0, rank;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) MPI_Recv(&x, 1, MPI_INT, 1, 5, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  else if (!strcmp(argv[1], "barrier")) MPI_Barrier(MPI_COMM_WORLD);
  else MPI_Bcast(&x, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}

/* A broadcast and an allreduce: the simulator's trace shows each as a
 * slice named by the call (mp_call_begin). */
static int traced_main(int argc, char **argv) {
  int x = 3, y = 0;
  MPI_Init(&argc, &argv);
  MPI_Bcast(&x, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Allreduce(&x, &y, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  MPI_Finalize();
  return y != 9;
}
static void traced_rank(mp *self, void *ud) {
  char *argv[] = {"traced", NULL};
  ((int *)ud)[mp_rank(self)] = traced_main(1, argv);
  init_rank_end(self);
}

static void trace_names_calls(void) {
  sim_config cfg;
  sim_config_init(&cfg);
  cfg.procs = 3;
  cfg.warn = NULL;
  char err[512];
  int rc[3] = {-1, -1, -1};
  sim *s = sim_new(&cfg, 3, err, sizeof err);
  FILE *csv = tmpfile();
  if (!s || !csv) {
    CHECK(0, "a simulator and a trace file: %s", s ? "tmpfile failed" : err);
    if (s) sim_free(s);
    if (csv) fclose(csv);
    return;
  }
  sim_trace(s, csv, NULL);
  mp_proc procs[3] = {{traced_rank, rc}, {traced_rank, rc}, {traced_rank, rc}};
  int ok = sim_run(s, procs, err, sizeof err) == 0 && !rc[0] && !rc[1] && !rc[2];
  char line[512];
  int bcast = 0, allreduce = 0;
  rewind(csv);
  while (fgets(line, sizeof line, csv)) {
    bcast += strstr(line, "MPI_Bcast") != NULL;
    allreduce += strstr(line, "MPI_Allreduce") != NULL;
  }
  CHECK(ok && bcast >= 2 && allreduce >= 3, "the trace of a broadcast and an allreduce on 3 ranks: run %s, %d lines "
        "name MPI_Bcast, %d MPI_Allreduce", ok ? "ok" : err, bcast, allreduce);
  fclose(csv);
  sim_free(s);
}

static void reports(void) {
  mpih_config cfg;
  mpih_result res;
  char *argv[] = {"bad_root", NULL};
  mpih_config_init(&cfg, MPIH_SIM, 3);
  mpih_run(&cfg, bad_root, 1, argv, &res);
  CHECK(res.rc != 0 && res.aborted && res.abort_code == 1 && strstr(res.err, "MPI_Bcast") && strstr(res.err, "7"),
        "MPI_Bcast from root 7 of 3: rc %d, aborted %d (code %d), \"%s\"", res.rc, res.aborted, res.abort_code, res.err);
  mpih_result_free(&res);
  static const char *const coll[2] = {"barrier", "bcast"};
  static const char *const words[2] = {"MPI_Barrier(MPI_COMM_WORLD)", "MPI_Bcast(root=0, MPI_COMM_WORLD)"};
  for (int k = 0; k < 2; k++) {
    char *av[] = {"stuck", (char *)coll[k], NULL};
    mpih_config_init(&cfg, MPIH_SIM, 2);
    mpih_run(&cfg, stuck, 2, av, &res);
    CHECK(res.rc != 0 && res.deadlock && strstr(res.err, words[k]), "a deadlock in %s: rc %d, deadlock %d, \"%s\"",
          words[k], res.rc, res.deadlock, res.err);
    mpih_result_free(&res);
  }
}

int main(int argc, char **argv) {
  if (argc == 2 && !strcmp(argv[1], "--reports")) {
    reports();
    trace_names_calls();
    return check_done("test_mpiprogs");
  }
  if (argc > 1) {
    for (int p = 0; p < NPROGS; p++) {
      if (strcmp(progs[p].name, argv[1])) continue;
      if (argc > 3) run(progs[p].name, progs[p].fn, atoi(argv[2]), argv[3], MPIH_SIM);
      else if (argc > 2) settings(p, atoi(argv[2]), 1);
      else
        for (int np = 1; np <= 16; np++) settings(p, np, 1);
      return check_done("test_mpiprogs");
    }
    fprintf(stderr, "test_mpiprogs: no program '%s'\n", argv[1]);
    return 2;
  }
  for (int p = 0; p < NPROGS; p++)
    for (int np = 1; np <= 16 && mine(progs[p].name); np++) settings(p, np, 0);
  reports();
  trace_names_calls();
  /* The threads backend: arrival order changes with the host's timing,
   * the results must not. */
  for (int p = 0; p < NPROGS; p++) {
    if (!mine(progs[p].name)) continue;
    run(progs[p].name, progs[p].fn, 4, "mpich", MPIH_THREADS);
    run(progs[p].name, progs[p].fn, 7, "mpich", MPIH_THREADS);
  }
  return check_done("test_mpiprogs");
}
