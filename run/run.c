/* run.c -- the parallel algorithm on the simulated machine. */
#include "run.h"

#include <stdlib.h>
#include <string.h>

#include "par_slave.h"
#include "xmem.h"

int run_sim(const run_config *rc, par_pair *pairs, int npairs, sim_stats *stats, char *err,
            size_t errlen) {
  int P = rc->procs, nr = run_ranks(P);
  sim_config cfg = rc->machine;
  int *place = xmallocarray((size_t)nr, sizeof *place);
  for (int r = 0; r < nr; r++) place[r] = P == 1 ? 0 : r;
  cfg.procs = P;
  cfg.place = place;
  sim *s = sim_new(&cfg, nr, err, errlen);
  free(place);
  if (!s) return -1;
  if (rc->trace_csv || rc->trace_json) sim_trace(s, rc->trace_csv, rc->trace_json);
  par_master_arg marg = {npairs, pairs, rc->kind, rc->opt, 0, ""};
  par_slave_arg *sarg = xcalloc((size_t)nr, sizeof *sarg);
  mp_proc *procs = xmallocarray((size_t)nr, sizeof *procs);
  procs[0] = (mp_proc){par_master, &marg};
  for (int r = 1; r < nr; r++) {
    sarg[r].diag_sends = rc->diag_sends;
    sarg[r].diag_recvs = rc->diag_recvs;
    sarg[r].diag_len = rc->diag_len;
    procs[r] = (mp_proc){par_slave, &sarg[r]};
  }
  int res = sim_run(s, procs, err, errlen);
  if (res == 0 && marg.failed) {
    snprintf(err, errlen, "%s", marg.err);
    res = -1;
  }
  for (int r = 1; res == 0 && r < nr; r++)
    if (sarg[r].failed) {
      snprintf(err, errlen, "%s", sarg[r].err);
      res = -1;
    }
  if (stats) *stats = *sim_stats_get(s);
  sim_free(s);
  free(sarg);
  free(procs);
  return res;
}
