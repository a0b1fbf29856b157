/* test_mpiprogs_p2p.c -- the point-to-point, communicator, attribute,
 * error-handler, info and one-sided programs of tests/mpi/ (p2p_*, comm_*,
 * attr_*, err_*, info_*, rma_*) on the simulator on 2 to 16 ranks, and on the
 * threads backend (2, 4 and 7 ranks), where messages arrive in the host's
 * order and the results must not change.
 *
 * Each program checks itself (tests/mpi/mtest.h): a run passes when every
 * rank's main returns 0 and the run ends cleanly.  The programs are linked
 * in with their main renamed tsmpi_main_NAME (the Makefile) and run by
 * tests/mpiharness.c, every rank in this process.  tests/cli_mpiprogs.sh
 * compares their summary lines with Open MPI's.
 *
 *   test_mpiprogs_p2p                         all that
 *   test_mpiprogs_p2p NAME NP [sim|threads]   one program on NP ranks */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "tests/mpiharness.h"
#include "tests/mpiprogs.h"

static int mine(const char *name) {
  return !strncmp(name, "p2p_", 4) || !strncmp(name, "comm_", 5) || !strncmp(name, "attr_", 5) ||
         !strncmp(name, "err_", 4) || !strncmp(name, "info_", 5) || !strncmp(name, "rma_", 4);
}

static void run(int p, int np, int backend) {
  mpih_config cfg;
  mpih_config_init(&cfg, backend, np);
  char *argv[] = {(char *)progs[p].name, NULL};
  mpih_result res;
  int rc = mpih_run(&cfg, progs[p].fn, 1, argv, &res), ok = rc == 0 && res.rc == 0, bad = -1;
  for (int r = 0; r < np && ok; r++)
    if (res.exit[r] != 0 || res.end[r] != 1) ok = 0, bad = r;
  CHECK(ok, "%s on %d ranks (%s): %s (rank %d returned %d)", progs[p].name, np,
        backend == MPIH_SIM ? "simulator" : "threads", rc || res.rc ? res.err : "a check failed", bad,
        bad >= 0 ? res.exit[bad] : 0);
  mpih_result_free(&res);
}

int main(int argc, char **argv) {
  if (argc > 2) {
    for (int p = 0; p < NPROGS; p++) {
      if (strcmp(progs[p].name, argv[1])) continue;
      run(p, atoi(argv[2]), argc > 3 && !strcmp(argv[3], "threads") ? MPIH_THREADS : MPIH_SIM);
      return check_done("test_mpiprogs_p2p");
    }
    fprintf(stderr, "test_mpiprogs_p2p: no program '%s'\n", argv[1]);
    return 2;
  }
  static const int sim_np[] = {2, 3, 4, 5, 7, 8, 13, 16}, threads_np[] = {2, 4, 7};
  int ran = 0;
  for (int p = 0; p < NPROGS; p++) {
    if (!mine(progs[p].name)) continue;
    ran++;
    for (size_t i = 0; i < sizeof sim_np / sizeof *sim_np; i++) run(p, sim_np[i], MPIH_SIM);
    for (size_t i = 0; i < sizeof threads_np / sizeof *threads_np; i++) run(p, threads_np[i], MPIH_THREADS);
  }
  CHECK(ran >= 6, "only %d point-to-point programs in tests/mpi", ran);
  return check_done("test_mpiprogs_p2p");
}
