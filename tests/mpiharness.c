/* mpiharness.c -- MPI programs' mains as the ranks of a machine (mpiharness.h). */
#include "tests/mpiharness.h"

#include <stdlib.h>
#include <string.h>

#include "mpi/init.h"
#include "mpi/mpi.h"
#include "mp/mp.h"
#include "mp/threads.h"
#include "util/xmem.h"

void mpih_config_init(mpih_config *cfg, int backend, int ranks) {
  memset(cfg, 0, sizeof *cfg);
  cfg->backend = backend;
  cfg->ranks = ranks;
  sim_config_init(&cfg->sim);
  cfg->sim.procs = ranks;
  cfg->sim.net = SIM_NET_IDEAL;
  cfg->sim.c = 0.125;
  cfg->sim.m = 0.25;
  cfg->sim.per_byte = 0.0625;
  cfg->sim.local = 0.5;
  cfg->sim.warn = NULL;
  cfg->poll_cost = 1e-6;
  cfg->warn = NULL;
}

typedef struct {
  mpih_main main_fn;
  int argc;
  char **argv;
  mpih_fn fn;
  void *ud;
  mpih_result *res;
} job;

static void rank_main(mp *self, void *ud) {
  job *j = ud;
  int r = mp_rank(self);
  /* A rank stopped inside an MPI call never comes back here: its exit
   * stays MPIH_NOEXIT and its end -1. */
  j->res->exit[r] = j->main_fn ? j->main_fn(j->argc, j->argv) : j->fn(j->ud);
  j->res->end[r] = init_rank_end(self);
}

static int run(const mpih_config *cfg, job *j, mpih_result *res);

int mpih_run(const mpih_config *cfg, mpih_main main_fn, int argc, char **argv, mpih_result *res) {
  job j = {main_fn, argc, argv, NULL, NULL, res};
  return run(cfg, &j, res);
}

int mpih_run_fn(const mpih_config *cfg, mpih_fn fn, void *ud, mpih_result *res) {
  job j = {NULL, 0, NULL, fn, ud, res};
  return run(cfg, &j, res);
}

mpih_result mpih_result_of(const mpih_config *cfg, mpih_fn fn, void *ud) {
  mpih_result res;
  mpih_run_fn(cfg, fn, ud, &res);
  return res;
}

int mpih_init(void) {
  int r = -1;
  MPI_Init(NULL, NULL);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

/* What both backends' statistics count, from st into res. */
#define TAKE_COUNTS(res, st)                                                                     \
  ((res)->messages = (st)->messages, (res)->bytes = (st)->bytes, (res)->unread = (st)->unread, \
   (res)->deadlock = (st)->deadlock, (res)->aborted = (st)->aborted, (res)->abort_code = (st)->abort_code)

static int run(const mpih_config *cfg, job *j, mpih_result *res) {
  int n = cfg->ranks;
  memset(res, 0, sizeof *res);
  res->exit = xmallocarray((size_t)n, sizeof *res->exit);
  res->end = xmallocarray((size_t)n, sizeof *res->end);
  res->finish = xcalloc((size_t)n, sizeof *res->finish);
  for (int i = 0; i < n; i++) res->exit[i] = MPIH_NOEXIT, res->end[i] = -1;
  init_set_poll_cost(cfg->poll_cost);
  mp_proc *pr = xmallocarray((size_t)n, sizeof *pr);
  for (int i = 0; i < n; i++) pr[i] = (mp_proc){rank_main, j};
  if (cfg->backend == MPIH_SIM) {
    sim_config sc = cfg->sim;
    sc.warn = cfg->warn;
    sim *s = sim_new(&sc, n, res->err, sizeof res->err);
    if (!s) {
      free(pr);
      return -1;
    }
    res->rc = sim_run(s, pr, res->err, sizeof res->err);
    const sim_stats *st = sim_stats_get(s);
    res->makespan = st->makespan;
    res->pooled = st->pooled;
    TAKE_COUNTS(res, st);
    for (int i = 0; i < n; i++) res->finish[i] = sim_rank(s, i)->finish;
    sim_free(s);
  } else {
    mpt_config tc;
    mpt_config_init(&tc);
    tc.warn = cfg->warn;
    mpt *t = mpt_new(&tc, n, res->err, sizeof res->err);
    if (!t) {
      free(pr);
      return -1;
    }
    res->rc = mpt_run(t, pr, res->err, sizeof res->err);
    TAKE_COUNTS(res, mpt_stats_get(t));
    mpt_free(t);
  }
  free(pr);
  return 0;
}

void mpih_result_free(mpih_result *res) {
  free(res->exit);
  free(res->end);
  free(res->finish);
  res->exit = res->end = NULL;
  res->finish = NULL;
}
