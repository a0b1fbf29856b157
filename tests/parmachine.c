/* parmachine.c -- the paper's algorithm on a machine, for the tests
 * (parmachine.h). */
#include "tests/parmachine.h"

#include <string.h>

void par_machine_init(par_machine *pm) {
  memset(pm, 0, sizeof *pm);
  machine_config_init(&pm->mc);
  par_config_init(&pm->pc);
}

int par_machine_option(par_machine *pm, const char *opt, const char *val, char *err, size_t errlen) {
  int k = par_config_option(&pm->pc, opt, val, err, errlen);
  return k ? k : machine_option(&pm->mc, opt, val, err, errlen);
}

/* The run on pm's machine, on backend b (-1: pm's own), with x. */
static int run(const par_machine *pm, int b, par_pair *pairs, int npairs, launch_extra x, char *err,
               size_t errlen) {
  machine_config mc = pm->mc;
  mc.trace = NULL;
  if (b >= 0) mc.backend = (machine_backend)b;
  x.periods = pm->pair_net, x.nperiods = npairs;
  launch_job lj = {&mc, &x, NULL};
  par_run r = {&pm->pc, mc.sim.c, mc.procs, launch_period_end, &x, pm->diag_sends, pm->diag_recvs,
               pm->diag_len, launch_job_run, &lj};
  return par_run_pairs(&r, pairs, npairs, err, errlen);
}

int par_machine_run(const par_machine *pm, par_pair *pairs, int npairs, char *err, size_t errlen) {
  return run(pm, -1, pairs, npairs, (launch_extra){0}, err, errlen);
}

int par_machine_sim(const par_machine *pm, par_pair *pairs, int npairs, sim_stats *st, char *err,
                    size_t errlen) {
  return run(pm, MACHINE_SIM, pairs, npairs, (launch_extra){.sim = st}, err, errlen);
}

int par_machine_threads(const par_machine *pm, par_pair *pairs, int npairs, mpt_stats *st, char *err,
                        size_t errlen) {
  return run(pm, MACHINE_THREADS, pairs, npairs, (launch_extra){.threads = st}, err, errlen);
}

static int tile_pairs(void *ud, par_pair *pairs, int npairs, char *err, size_t errlen) {
  return par_machine_run(ud, pairs, npairs, err, errlen);
}

stack_tiler par_machine_tiler(par_machine *pm) { return (stack_tiler){tile_pairs, pm}; }
