/* launch_mpi.c -- launch_run on MPI processes, one rank a process or served
 * (launch_mpi.h). */
#include "machine/launch_mpi.h"

#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mp/mp_mpi.h"
#include "util/xmem.h"

enum { CMD_RUN = 1, CMD_EXIT, CMD_DONE };   /* tags on cmd: process 0's orders, the answers */

typedef struct {   /* a served rank's answer after a run */
  int failed;       /* its part or the backend failed there */
  char err[400];
} answer;

/* The served world (launch_mpi_main): the processes, and the communicators:
 * cmd for the orders, data and ctl for the backend (mp_mpi.h).  One MPI
 * world per process: module state.  size 0: not served. */
static struct {
  int size, me;
  MPI_Comm cmd, data, ctl;
  launch_serve_fn *serve;
} W;

/* The backend's settings: warnings, and c for SimGrid. */
static mpm_config backend_config(double c, FILE *warn) {
  mpm_config cfg;
  mpm_config_init(&cfg);
  cfg.c = c;
  cfg.warn = warn;
  return cfg;
}

static void stats_of(const mpm *m, tilesim_stats *st) {
  const mpm_stats *ms = mpm_stats_get(m);
  launch_stats_run(st, &ms->run);
  st->makespan = ms->wall_s;
}

/* Process 0 of the served world: the order to processes 1 .. nranks-1, the
 * run, their answers. */
static int served_run(const machine_config *mc, int nranks, const mp_proc *procs, tilesim_stats *st,
                      char *err, size_t errlen) {
  if (nranks > W.size) {
    snprintf(err, errlen, "%d ranks need %d MPI processes; mpirun gave %d", nranks, nranks, W.size);
    return -1;
  }
  double c = mc->sim.c;
  for (int r = 1; r < nranks; r++) {
    MPI_Send(&nranks, 1, MPI_INT, r, CMD_RUN, W.cmd);
    MPI_Send(&c, 1, MPI_DOUBLE, r, CMD_RUN, W.cmd);
  }
  mpm_config cfg = backend_config(c, mc->sim.warn);
  mpm *m = mpm_new(&cfg, W.data, W.ctl, nranks, err, errlen);
  XASSERT(m);   /* nranks <= size and this is process 0: cannot fail */
  char berr[512];
  int res = mpm_run(m, procs[0].main, procs[0].ud, berr, sizeof berr);
  stats_of(m, st);
  mpm_free(m);
  if (res != 0) snprintf(err, errlen, "%s", berr);
  for (int r = 1; r < nranks; r++) {   /* every answer, in rank order */
    answer a;
    MPI_Recv(&a, (int)sizeof a, MPI_BYTE, r, CMD_DONE, W.cmd, MPI_STATUS_IGNORE);
    if (res == 0 && a.failed) {
      snprintf(err, errlen, "%s", a.err);
      res = -1;
    }
  }
  return res;
}

int launch_mpi_run(const machine_config *mc, int nranks, const mp_proc *procs, tilesim_stats *st,
                   char *err, size_t errlen) {
  if (W.size) return served_run(mc, nranks, procs, st, err, errlen);
  int size = 0, me = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  if (nranks != size) {
    snprintf(err, errlen, "--backend mpi runs one rank per MPI process: %d ranks, and mpirun gave %d",
             nranks, size);
    return -1;
  }
  MPI_Comm data, ctl;
  MPI_Comm_dup(MPI_COMM_WORLD, &data);
  MPI_Comm_dup(MPI_COMM_WORLD, &ctl);
  /* A truncated receive is mp's MP_ETRUNC, not the end of the program. */
  MPI_Comm_set_errhandler(data, MPI_ERRORS_RETURN);
  mpm_config cfg = backend_config(mc->sim.c, mc->sim.warn);
  int res = -1;
  mpm *m = mpm_new(&cfg, data, ctl, nranks, err, errlen);
  if (m) {
    res = mpm_run(m, procs[me].main, procs[me].ud, err, errlen);
    stats_of(m, st);
    mpm_free(m);
  }
  MPI_Comm_free(&ctl);
  MPI_Comm_free(&data);
  return res;
}

/* A served rank's part: the serving function, its result kept. */
typedef struct {
  int res;
  char err[400];
} part;

static void serve_main(mp *self, void *ud) {
  part *p = ud;
  p->res = W.serve(self, p->err, sizeof p->err);
}

/* Processes 1..: serve runs until EXIT; 1 if a run failed here. */
static int serve(void) {
  int bad = 0;
  for (;;) {
    int nranks;
    MPI_Status st;
    MPI_Recv(&nranks, 1, MPI_INT, 0, MPI_ANY_TAG, W.cmd, &st);
    if (st.MPI_TAG == CMD_EXIT) return bad;
    double c;
    MPI_Recv(&c, 1, MPI_DOUBLE, 0, CMD_RUN, W.cmd, MPI_STATUS_IGNORE);
    answer a;
    memset(&a, 0, sizeof a);
    mpm_config cfg = backend_config(c, stderr);
    mpm *m = mpm_new(&cfg, W.data, W.ctl, nranks, a.err, sizeof a.err);
    if (!m) xpanic("mpi: process %d: %s", W.me, a.err);
    part p;
    memset(&p, 0, sizeof p);
    char berr[400];
    if (mpm_run(m, serve_main, &p, berr, sizeof berr) != 0) {
      a.failed = 1;
      snprintf(a.err, sizeof a.err, "%s", berr);
    } else if (p.res != 0) {
      a.failed = 1;
      snprintf(a.err, sizeof a.err, "%s", p.err);
    }
    mpm_free(m);
    bad |= a.failed;
    MPI_Send(&a, (int)sizeof a, MPI_BYTE, 0, CMD_DONE, W.cmd);
  }
}

int launch_mpi_main(int argc, char **argv, int (*program)(int argc, char **argv),
                    launch_serve_fn *serve_fn) {
  MPI_Init(&argc, &argv);
  MPI_Comm_size(MPI_COMM_WORLD, &W.size);
  MPI_Comm_rank(MPI_COMM_WORLD, &W.me);
  MPI_Comm_dup(MPI_COMM_WORLD, &W.cmd);
  MPI_Comm_dup(MPI_COMM_WORLD, &W.data);
  MPI_Comm_dup(MPI_COMM_WORLD, &W.ctl);
  W.serve = serve_fn;
  /* A truncated receive is mp's MP_ETRUNC, not the end of the program. */
  MPI_Comm_set_errhandler(W.data, MPI_ERRORS_RETURN);
  int status;
  if (W.me == 0) {
    status = program(argc, argv);
    for (int r = 1; r < W.size; r++) MPI_Send(&status, 1, MPI_INT, r, CMD_EXIT, W.cmd);
  } else {
    status = serve();
  }
  MPI_Comm_free(&W.ctl);
  MPI_Comm_free(&W.data);
  MPI_Comm_free(&W.cmd);
  MPI_Finalize();
  return status;
}
