/* launch_mpi.c -- launch_run on MPI processes (launch_mpi.h). */
#include "machine/launch_mpi.h"

#include <mpi.h>

#include "mp/mp_mpi.h"

int launch_mpi_run(const machine_config *mc, int nranks, const mp_proc *procs, tilesim_stats *st,
                   char *err, size_t errlen) {
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
  mpm_config cfg;
  mpm_config_init(&cfg);
  cfg.c = mc->sim.c;
  cfg.warn = mc->sim.warn;
  int res = -1;
  mpm *m = mpm_new(&cfg, data, ctl, nranks, err, errlen);
  if (m) {
    res = mpm_run(m, procs[me].main, procs[me].ud, err, errlen);
    const mpm_stats *ms = mpm_stats_get(m);
    launch_stats_run(st, &ms->run);
    st->makespan = ms->wall_s;
    mpm_free(m);
  }
  MPI_Comm_free(&ctl);
  MPI_Comm_free(&data);
  return res;
}
