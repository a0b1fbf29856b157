/* run_mpi.c -- the MPI build's driver: process 0 runs the program, the
 * others serve runs of the parallel algorithm as slaves (run_mpi.h). */
#include "run/run_mpi.h"

#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mp/mp_mpi.h"
#include "algo/par_slave.h"
#include "util/xmem.h"

enum { CMD_RUN = 1, CMD_EXIT, CMD_DONE };   /* tags on cmd: process 0's orders, slaves' answers */

typedef struct {   /* a slave's answer after a run */
  int failed;       /* the slave or the backend failed here */
  char err[400];
} answer;

/* The processes and the communicators: cmd for these orders, data and ctl
 * for the backend (mp_mpi.h).  One MPI world per process: module state. */
static struct {
  int size, me;
  MPI_Comm cmd, data, ctl;
} W;

int run_mpi_size(void) { return W.size; }

/* The backend's settings from the run's: warnings, and c for SimGrid. */
static mpm_config backend_config(const run_config *rc) {
  mpm_config cfg;
  mpm_config_init(&cfg);
  cfg.c = rc->mc.sim.c;
  cfg.warn = rc->mc.sim.warn;
  return cfg;
}

int run_mpi_pairs(const run_config *rc, par_pair *pairs, int npairs, char *err, size_t errlen) {
  int k = run_ranks(rc->mc.procs);
  if (W.size == 0) {
    snprintf(err, errlen, "mpi: not started (run_mpi_main)");
    return -1;
  }
  if (k > W.size) {
    snprintf(err, errlen, "--procs %d needs %d MPI processes; mpirun gave %d", rc->mc.procs, k, W.size);
    return -1;
  }
  par_options opt;   /* the master's bookkeeping priced in node units */
  if (run_par_options(rc, &opt, err, errlen) != 0) return -1;
  int order[3] = {k, rc->mc.sim.c > 0 ? 1 : 0, 0};
  double c = rc->mc.sim.c;
  for (int r = 1; r < k; r++) {
    MPI_Send(order, 3, MPI_INT, r, CMD_RUN, W.cmd);
    MPI_Send(&c, 1, MPI_DOUBLE, r, CMD_RUN, W.cmd);
  }
  mpm_config cfg = backend_config(rc);
  mpm *m = mpm_new(&cfg, W.data, W.ctl, k, err, errlen);
  XASSERT(m);   /* k <= size and this is process 0: cannot fail */
  par_master_arg marg = {npairs, pairs, rc->kind, opt, 0, "", rc->progress, rc->progress_ud};
  char berr[512];
  int res = mpm_run(m, par_master, &marg, berr, sizeof berr);
  mpm_free(m);
  if (res != 0) snprintf(err, errlen, "%s", berr);
  if (res == 0 && marg.failed) {
    snprintf(err, errlen, "%s", marg.err);
    res = -1;
  }
  for (int r = 1; r < k; r++) {   /* every answer, in rank order */
    answer a;
    MPI_Recv(&a, (int)sizeof a, MPI_BYTE, r, CMD_DONE, W.cmd, MPI_STATUS_IGNORE);
    if (res == 0 && a.failed) {
      snprintf(err, errlen, "%s", a.err);
      res = -1;
    }
  }
  return res;
}

/* Processes 1..: serve runs until EXIT; 1 if a run failed here. */
static int serve(void) {
  int bad = 0;
  for (;;) {
    int order[3];
    MPI_Status st;
    MPI_Recv(order, 3, MPI_INT, 0, MPI_ANY_TAG, W.cmd, &st);
    if (st.MPI_TAG == CMD_EXIT) return bad;
    double c;
    MPI_Recv(&c, 1, MPI_DOUBLE, 0, CMD_RUN, W.cmd, MPI_STATUS_IGNORE);
    answer a;
    memset(&a, 0, sizeof a);
    mpm_config cfg;
    mpm_config_init(&cfg);
    cfg.c = c;
    mpm *m = mpm_new(&cfg, W.data, W.ctl, order[0], a.err, sizeof a.err);
    if (!m) xpanic("mpi: process %d: %s", W.me, a.err);
    par_slave_arg sarg;
    memset(&sarg, 0, sizeof sarg);
    char berr[400];
    if (mpm_run(m, par_slave, &sarg, berr, sizeof berr) != 0) {
      a.failed = 1;
      snprintf(a.err, sizeof a.err, "%s", berr);
    } else if (sarg.failed) {
      a.failed = 1;
      snprintf(a.err, sizeof a.err, "%s", sarg.err);
    }
    mpm_free(m);
    bad |= a.failed;
    MPI_Send(&a, (int)sizeof a, MPI_BYTE, 0, CMD_DONE, W.cmd);
  }
}

int run_mpi_main(int argc, char **argv, int (*program)(int argc, char **argv)) {
  MPI_Init(&argc, &argv);
  MPI_Comm_size(MPI_COMM_WORLD, &W.size);
  MPI_Comm_rank(MPI_COMM_WORLD, &W.me);
  MPI_Comm_dup(MPI_COMM_WORLD, &W.cmd);
  MPI_Comm_dup(MPI_COMM_WORLD, &W.data);
  MPI_Comm_dup(MPI_COMM_WORLD, &W.ctl);
  /* A truncated receive is mp's MP_ETRUNC, not the end of the program. */
  MPI_Comm_set_errhandler(W.data, MPI_ERRORS_RETURN);
  int status;
  if (W.me == 0) {
    status = program(argc, argv);
    int order[3] = {0, 0, status};
    for (int r = 1; r < W.size; r++) MPI_Send(order, 3, MPI_INT, r, CMD_EXIT, W.cmd);
  } else {
    status = serve();
  }
  MPI_Comm_free(&W.ctl);
  MPI_Comm_free(&W.data);
  MPI_Comm_free(&W.cmd);
  MPI_Finalize();
  return status;
}
