/* par_run.c -- the master and the slaves as one mp program (par_run.h). */
#include "algo/par_run.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "algo/par_slave.h"
#include "util/xmem.h"

int par_run_pairs(const par_run *r, par_pair *pairs, int npairs, char *err, size_t errlen) {
  par_options opt;
  if (par_config_prices(r->pc, r->c, &opt, err, errlen) != 0) return -1;
  int nr = par_ranks(r->procs);
  par_master_arg marg = {npairs, pairs, r->pc->kind, opt, 0, "", r->progress, r->progress_ud};
  par_slave_arg *sarg = xcalloc((size_t)nr, sizeof *sarg);   /* sarg[0] unused */
  mp_proc *procs = xmallocarray((size_t)nr, sizeof *procs);
  procs[0] = (mp_proc){par_master, &marg};
  for (int k = 1; k < nr; k++) {
    sarg[k].diag_sends = r->diag_sends;
    sarg[k].diag_recvs = r->diag_recvs;
    sarg[k].diag_len = r->diag_len;
    procs[k] = (mp_proc){par_slave, &sarg[k]};
  }
  int res = r->launch(r->launch_ud, nr, procs, err, errlen);
  if (res == 0 && marg.failed) {
    snprintf(err, errlen, "%s", marg.err);
    res = -1;
  }
  for (int k = 1; res == 0 && k < nr; k++)
    if (sarg[k].failed) {
      snprintf(err, errlen, "%s", sarg[k].err);
      res = -1;
    }
  free(sarg);
  free(procs);
  return res;
}

int par_run_serve(mp *self, char *err, size_t errlen) {
  par_slave_arg sarg;
  memset(&sarg, 0, sizeof sarg);
  par_slave(self, &sarg);
  if (!sarg.failed) return 0;
  snprintf(err, errlen, "%s", sarg.err);
  return -1;
}
