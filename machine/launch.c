/* launch.c -- an mp program on the simulator, threads or MPI (launch.h). */
#include "machine/launch.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "util/atomicfile.h"
#include "util/progress.h"
#include "sim/trace.h"
#include "util/wallclock.h"
#include "util/xmem.h"
#ifdef TILESIM_MPI
#include "machine/launch_mpi.h"
#endif

sim *launch_sim_new(const machine_config *mc, int nranks, char *err, size_t errlen) {
  int *place = xmallocarray((size_t)nranks, sizeof *place), nodes;
  if (machine_place(mc, nranks, place, &nodes, err, errlen) != 0) {
    free(place);
    return NULL;
  }
  sim_config cfg = mc->sim;
  cfg.procs = mc->procs;
  cfg.place = place;
  sim *s = sim_new(&cfg, nranks, err, errlen);
  free(place);
  return s;
}

static void stats_begin(tilesim_stats *st, const machine_config *mc, int nranks) {
  memset(st, 0, sizeof *st);
  st->backend = machine_backend_name(mc->backend);
  st->ranks = nranks;
  st->procs = mc->backend == MACHINE_SIM ? mc->procs : nranks;
}

/* The figures every backend counts (mp/stats.h). */
void launch_stats_run(tilesim_stats *st, const mp_stats *run) {
  st->messages = run->messages;
  st->bytes = run->bytes;
  st->unread = run->unread;
  st->deadlock = run->deadlock;
  st->aborted = run->aborted;
  st->abort_code = run->abort_code;
}

/* Sum and largest of one figure over the ranks. */
static void add(double v, double *sum, double *max) {
  *sum += v;
  if (v > *max) *max = v;
}

/* A long run's progress: the simulated time and the calls so far. */
static void tick(void *ud, double t, long long events) {
  char text[96];
  snprintf(text, sizeof text, "simulated %.6g s, %.3g M calls", t, (double)events * 1e-6);
  progress_note(ud, text);
}

void launch_period_end(void *ud, int done, int total) {
  launch_extra *x = ud;
  if (x->links && x->periods) links_period(x->links, &x->periods[done - 1]);
  if (x->next) x->next(x->next_ud, done, total);
}

/* What x asks of the simulator s before its run. */
static void sim_extra(sim *s, launch_extra *x) {
  if (x->trace_csv || x->trace_json) sim_trace(s, x->trace_csv, x->trace_json);
  if (x->count_csv || x->count_json) sim_trace_count(s, x->count_csv, x->count_json);
  x->links = sim_links(s);
  if (x->links && x->periods) memset(x->periods, 0, (size_t)x->nperiods * sizeof *x->periods);
}

static int run_sim(const machine_config *mc, int nranks, const mp_proc *procs, launch_extra *x,
                   tilesim_stats *st, char *err, size_t errlen) {
  sim *s = launch_sim_new(mc, nranks, err, errlen);
  if (!s) return -1;
  if (x) {
    XASSERT(!mc->trace || !(x->trace_csv || x->trace_json));   /* one trace a run */
    sim_extra(s, x);
  }
  progress *pg = mc->name ? progress_new(mc->name, "run", 0) : NULL;
  if (pg) sim_progress(s, tick, pg);
  atomicfile tf = {NULL, NULL, NULL};
  if (mc->trace) {
    size_t tl = strlen(mc->trace);
    int json = tl >= 5 && strcmp(mc->trace + tl - 5, ".json") == 0;
    if (atomicfile_open(&tf, mc->trace, "w", err, errlen) != 0) {
      sim_free(s);
      return -1;
    }
    sim_trace(s, json ? NULL : tf.f, json ? tf.f : NULL);
    if (mc->trace_limit != ULLONG_MAX) sim_trace_limit(s, mc->trace_limit);
  }
  int res = sim_run(s, procs, err, errlen);
  progress_end(pg);
  const sim_stats *ss = sim_stats_get(s);
  if (x) {
    if (x->count_csv || x->count_json) sim_trace_size(s, &x->csv_bytes, &x->json_bytes);
    if (x->sim) *x->sim = *ss;
    x->links = NULL;
  }
  launch_stats_run(st, &ss->run);
  st->makespan = ss->makespan;
  st->measured = 2;
  for (int r = 0; r < nranks; r++) {
    const sim_rank_stats *rs = sim_rank(s, r);
    add(rs->compute, &st->compute_sum, &st->compute_max);
    add(rs->recv_wait, &st->wait_sum, &st->wait_max);
    add(rs->cpu_wait, &st->cpu_wait_sum, &st->cpu_wait_max);
    add(rs->overhead, &st->overhead_sum, &st->overhead_max);
    st->slept_sum += rs->slept;
  }
  if (tf.f) {
    unsigned long long c, j;
    sim_trace_size(s, &c, &j);
    st->trace_bytes = c + j;
    char why[512];
    int over = sim_trace_over(s);
    if (over && res == 0) {
      trace_over_limit(c + j, mc->trace_limit, why, sizeof why);
      snprintf(err, errlen, "%s: %s", mc->trace, why);
      res = -1;
    }
    if (atomicfile_close(&tf, res == 0 && !over, why, sizeof why) != 0 && res == 0) {
      snprintf(err, errlen, "%s", why);
      res = -1;
    }
  }
  sim_free(s);
  return res;
}

static int run_threads(const machine_config *mc, int nranks, const mp_proc *procs, launch_extra *x,
                       tilesim_stats *st, char *err, size_t errlen) {
  mpt_config cfg = mc->threads;
  cfg.warn = mc->sim.warn;
  /* No simulated clock to show: the ranks and the time so far. */
  progress *pg = mc->name ? progress_new(mc->name, "run", 0) : NULL;
  char text[96];
  snprintf(text, sizeof text, "%d rank%s on threads", nranks, nranks == 1 ? "" : "s");
  progress_note(pg, text);
  mpt *t = mpt_new(&cfg, nranks, err, errlen);
  if (!t) {
    progress_end(pg);
    return -1;
  }
  int res = mpt_run(t, procs, err, errlen);
  progress_end(pg);
  const mpt_stats *ts = mpt_stats_get(t);
  if (x && x->threads) *x->threads = *ts;
  launch_stats_run(st, &ts->run);
  st->makespan = ts->wall_s;
  st->measured = 1;
  for (int r = 0; r < nranks; r++) add(mpt_rank(t, r)->recv_wait, &st->wait_sum, &st->wait_max);
  mpt_free(t);
  return res;
}

int launch_run(const machine_config *mc, int nranks, const mp_proc *procs, tilesim_stats *st,
               char *err, size_t errlen) {
  return launch_run_with(mc, nranks, procs, NULL, st, err, errlen);
}

int launch_job_run(void *job, int nranks, const mp_proc *procs, char *err, size_t errlen) {
  const launch_job *j = job;
  return launch_run_with(j->mc, nranks, procs, j->x, j->st, err, errlen);
}

int launch_run_with(const machine_config *mc, int nranks, const mp_proc *procs, launch_extra *x,
                    tilesim_stats *st, char *err, size_t errlen) {
  tilesim_stats scratch;
  if (!st) st = &scratch;
  stats_begin(st, mc, nranks);
  if (nranks < 1 || nranks > MACHINE_MAX_RANKS) {
    snprintf(err, errlen, "%d ranks: a run has 1 to %d", nranks, MACHINE_MAX_RANKS);
    return -1;
  }
  if (mc->backend == MACHINE_THREADS && nranks > MACHINE_MAX_THREADS) {
    snprintf(err, errlen, "%d ranks: --backend threads runs 1 to %d (a thread each); the simulator up to %d",
             nranks, MACHINE_MAX_THREADS, MACHINE_MAX_RANKS);
    return -1;
  }
  if (mc->backend != MACHINE_SIM && mc->sim.topo.kind != TOPO_NONE) {
    snprintf(err, errlen, "--topology describes the simulated machine; --backend %s measures this one",
             machine_backend_name(mc->backend));
    return -1;
  }
  if (mc->backend != MACHINE_SIM && mc->trace) {
    snprintf(err, errlen, "--trace traces the simulated machine (--backend sim)");
    return -1;
  }
  double w0 = wallclock();
  int res;
  switch (mc->backend) {
  case MACHINE_SIM: res = run_sim(mc, nranks, procs, x, st, err, errlen); break;
  case MACHINE_THREADS: res = run_threads(mc, nranks, procs, x, st, err, errlen); break;
  default:
#ifdef TILESIM_MPI
    res = launch_mpi_run(mc, nranks, procs, st, err, errlen);
#else
    snprintf(err, errlen, "--backend mpi: the MPI backend is in the MPI build (make mpi)");
    res = -1;
#endif
  }
  st->wall_s = wallclock() - w0;
  return res;
}
