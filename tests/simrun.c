/* simrun.c -- the tests' runs of one main on the simulator (simrun.h). */
#include "tests/simrun.h"

#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "util/xmem.h"

sim_config simrun_config(sim_net net, int procs) {
  sim_config cfg;
  sim_config_init(&cfg);
  cfg.procs = procs;
  cfg.net = net;
  cfg.c = 0.125;
  cfg.m = 0.25;
  cfg.per_byte = 0.0625;
  cfg.local = 0;
  cfg.L = 0.5;
  cfg.o = 0.125;
  cfg.g = 0.0625;
  cfg.G = 0.03125;
  cfg.warn = NULL;
  return cfg;
}

sim *simrun(const sim_config *cfg, int n, mp_main fn, void *ud, int *rc, char *err, size_t errlen) {
  sim *s = sim_new(cfg, n, err, errlen);
  CHECK(s != NULL, "sim_new: %s", err);
  if (!s) abort();
  mp_proc *pr = xmallocarray((size_t)n, sizeof *pr);
  for (int i = 0; i < n; i++) pr[i] = (mp_proc){fn, ud};
  err[0] = 0;
  *rc = sim_run(s, pr, err, errlen);
  free(pr);
  return s;
}

void simrun_ring_main(mp *self, void *ud) {
  simrun_ring *g = ud;
  int me = mp_rank(self), p = mp_size(self);
  unsigned char buf[64] = {0};
  long long tok = 0;
  for (int k = 0; k < g->laps; k++) {
    if (me != 0) g->bad |= mp_recv(self, (me + p - 1) % p, 0, buf, sizeof buf, NULL) != MP_OK;
    memcpy(&tok, buf, sizeof tok);
    tok++;
    memcpy(buf, &tok, sizeof tok);
    g->bad |= mp_compute(self, g->work) != MP_OK;
    g->bad |= mp_send(self, (me + 1) % p, 0, buf, g->len) != MP_OK;
    if (me == 0) g->bad |= mp_recv(self, p - 1, 0, buf, sizeof buf, NULL) != MP_OK;
  }
  memcpy(&tok, buf, sizeof tok);
  if (me == 0) g->token = tok;
}
