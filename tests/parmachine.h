/* parmachine.h -- for the tests: the paper's algorithm (algo/par_run.h) on
 * a machine (machine/launch.h), composed as ./tile and ./bench compose it,
 * with the tests' hooks.  One value holds the machine, the algorithm's
 * settings and the hooks. */
#ifndef PARMACHINE_H
#define PARMACHINE_H

#include <stddef.h>

#include "algo/par_run.h"
#include "machine/launch.h"
#include "machine/machine.h"
#include "surface/stack.h"

typedef struct {
  machine_config mc;   /* mc.procs: P; its trace is not written */
  par_config pc;
  int *diag_sends, *diag_recvs;   /* the slaves' test hook (par_slave.h), or NULL */
  int diag_len;
  net_stats *pair_net;            /* the simulator on a topology: each pair's
                                     network statistics, or NULL */
} par_machine;

/* machine_config_init's machine, par_config_init's algorithm, no hooks. */
void par_machine_init(par_machine *pm);

/* One option of the algorithm or of the machine, as the programs take it:
 * par_config_option, then machine_option. */
int par_machine_option(par_machine *pm, const char *opt, const char *val, char *err, size_t errlen);

/* The pairs on pm's backend; par_machine_sim on the simulator and
 * par_machine_threads on threads whatever mc.backend says, with the
 * backend's statistics in *st (may be NULL).  0, or -1 and a message. */
int par_machine_run(const par_machine *pm, par_pair *pairs, int npairs, char *err, size_t errlen);
int par_machine_sim(const par_machine *pm, par_pair *pairs, int npairs, sim_stats *st, char *err,
                    size_t errlen);
int par_machine_threads(const par_machine *pm, par_pair *pairs, int npairs, mpt_stats *st, char *err,
                        size_t errlen);

/* A surface's tiler (surface/stack.h) that runs the bands on pm. */
stack_tiler par_machine_tiler(par_machine *pm);

#endif
