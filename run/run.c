/* run.c -- the parallel algorithm on a backend: options, and the drivers
 * for the simulated machine and for threads (MPI's is run_mpi.c). */
#include "run/run.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "machine/launch.h"
#include "algo/par_slave.h"
#include "util/xmem.h"
#ifdef TILESIM_MPI
#include "run/run_mpi.h"
#endif

void run_config_init(run_config *rc) {
  memset(rc, 0, sizeof *rc);
  machine_config_init(&rc->mc);
  rc->opt.alloc = ALLOC_HALF;
  rc->opt.min_diag = 1;
  rc->opt.block = 1;
  rc->opt.schedule = PAR_STATIC;
  rc->kind = COST_AREA;
}

const char run_options_help[] =
    "  --alloc half|size|fit  processor allocation: half (section 4), by size (7.1),\n"
    "                     or fit: by size, no group more slaves than it can use\n"
    "  --min-diag d       at least d nodes of a diagonal per slave (7.2); default 1\n"
    "  --block k          slaves trade run-boundary costs every k diagonals (default 1)\n"
    "  --schedule NAME    static (the paper's groups) or dynamic (bands to free slaves)\n"
    "  --master-c S       seconds per unit of the master's bookkeeping (a column of\n"
    "                     a path it assembles, copies or measures); default c/100\n"
    "  --table-c S        seconds per cell of a slave's weight table (where slaves\n"
    "                     build one); --back-c S: per step of a slave's backtracking;\n"
    "                     default 0: not charged (tilesim-bench --calibrate measures\n"
    "                     both)\n";

/* The seconds options' range: from 0 to a billion seconds (31 years). */
#define RUN_MAX_SECONDS 1e9

static int seconds(const char *opt, const char *val, double hi, double *out, char *err,
                   size_t errlen) {
  return args_real(opt, val, "seconds", 0, hi, out, err, errlen) == 0 ? 1 : -1;
}

static int integer(const char *opt, const char *val, int lo, int hi, int *out, char *err,
                   size_t errlen) {
  long v;
  if (args_long(opt, val, lo, hi, &v, err, errlen) != 0) return -1;
  *out = (int)v;
  return 1;
}

/* The names the allocation parser takes, '|'-separated (so the messages
 * list whatever split.c knows). */
void run_alloc_words(char *buf, size_t len) {
  size_t k = 0;
  buf[0] = 0;
  for (int i = 0; i < 16; i++) {
    const char *n = split_alloc_name((split_alloc)i);
    split_alloc back;
    if (split_alloc_parse(n, &back) != 0 || (int)back != i) continue;
    k += (size_t)snprintf(buf + k, k < len ? len - k : 0, "%s%s", k ? "|" : "", n);
  }
}

int run_option(run_config *rc, const char *opt, const char *val, char *err, size_t errlen) {
  char words[200];
  if (strcmp(opt, "--ranks") == 0) {
    snprintf(err, errlen, "--ranks: the paper's algorithm runs max(2, P) ranks on --procs P processors");
    return -1;
  }
  int k = machine_option(&rc->mc, opt, val, err, errlen);
  if (k != 0) return k;
  if (!val) val = "";
  if (strcmp(opt, "--master-c") == 0) {
    rc->master_c_given = 1;
    return seconds(opt, val, RUN_MAX_SECONDS, &rc->master_c, err, errlen);
  }
  if (strcmp(opt, "--table-c") == 0) return seconds(opt, val, RUN_MAX_SECONDS, &rc->table_c, err, errlen);
  if (strcmp(opt, "--back-c") == 0) return seconds(opt, val, RUN_MAX_SECONDS, &rc->back_c, err, errlen);
  if (strcmp(opt, "--min-diag") == 0)
    return integer(opt, val, 1, 1 << 30, &rc->opt.min_diag, err, errlen);
  if (strcmp(opt, "--block") == 0) return integer(opt, val, 1, 1 << 20, &rc->opt.block, err, errlen);
  if (strcmp(opt, "--schedule") == 0) {
    if (par_schedule_parse(val, &rc->opt.schedule) == 0) return 1;
    args_word(opt, val, "static|dynamic", err, errlen);
    return -1;
  }
  if (strcmp(opt, "--alloc") == 0) {
    if (split_alloc_parse(val, &rc->opt.alloc) == 0) return 1;
    run_alloc_words(words, sizeof words);
    args_word(opt, val, words, err, errlen);
    return -1;
  }
  return 0;
}

double run_master_c(const run_config *rc) {
  return rc->master_c_given ? rc->master_c : RUN_MASTER_SHARE * rc->mc.sim.c;
}

int run_par_options(const run_config *rc, par_options *out, char *err, size_t errlen) {
  *out = rc->opt;
  double c = rc->mc.sim.c, mc = run_master_c(rc);
  if (!rc->master_c_given) out->book = RUN_MASTER_SHARE;
  else if (c > 0) out->book = mc / c;
  else if (mc == 0) out->book = 0;
  else {
    snprintf(err, errlen, "--master-c %g is a price in node units (c), and c is 0", mc);
    return -1;
  }
  static const char *const name[2] = {"--table-c", "--back-c"};
  const double sec[2] = {rc->table_c, rc->back_c};
  double *units[2] = {&out->table, &out->back};
  for (int i = 0; i < 2; i++) {
    *units[i] = sec[i] == 0 ? 0 : c > 0 ? sec[i] / c : -1;
    if (*units[i] < 0) {
      snprintf(err, errlen, "%s %g is a price in node units (c), and c is 0", name[i], sec[i]);
      return -1;
    }
  }
  return 0;
}

/* The master's and the slaves' arguments and the mp program of nr ranks. */
typedef struct {
  par_master_arg marg;
  par_slave_arg *sarg;   /* [nr]; sarg[0] unused */
  mp_proc *procs;        /* [nr] */
  int nr;
} program;

static void program_init(program *p, const run_config *rc, par_pair *pairs, int npairs, int nr) {
  par_options opt;
  run_par_options(rc, &opt, NULL, 0);   /* checked in run_pairs and run_sim */
  p->marg = (par_master_arg){npairs, pairs, rc->kind, opt, 0, "", rc->progress, rc->progress_ud};
  p->nr = nr;
  p->sarg = xcalloc((size_t)nr, sizeof *p->sarg);
  p->procs = xmallocarray((size_t)nr, sizeof *p->procs);
  p->procs[0] = (mp_proc){par_master, &p->marg};
  for (int r = 1; r < nr; r++) {
    p->sarg[r].diag_sends = rc->diag_sends;
    p->sarg[r].diag_recvs = rc->diag_recvs;
    p->sarg[r].diag_len = rc->diag_len;
    p->procs[r] = (mp_proc){par_slave, &p->sarg[r]};
  }
}

/* After the run (res from the backend): a failure of the master or of a
 * slave becomes the error.  Frees p; returns res. */
static int program_finish(program *p, int res, char *err, size_t errlen) {
  if (res == 0 && p->marg.failed) {
    snprintf(err, errlen, "%s", p->marg.err);
    res = -1;
  }
  for (int r = 1; res == 0 && r < p->nr; r++)
    if (p->sarg[r].failed) {
      snprintf(err, errlen, "%s", p->sarg[r].err);
      res = -1;
    }
  free(p->sarg);
  free(p->procs);
  return res;
}

/* The master ends a pair (all its messages are sent by then): that pair's
 * share of the network's statistics, then the caller's progress. */
typedef struct {
  links *links;
  net_stats *out;
  void (*progress)(void *ud, int done, int total);
  void *progress_ud;
} pair_net;

static void pair_done(void *ud, int done, int total) {
  pair_net *pn = ud;
  links_period(pn->links, &pn->out[done - 1]);
  if (pn->progress) pn->progress(pn->progress_ud, done, total);
}

int run_sim(const run_config *rc, par_pair *pairs, int npairs, sim_stats *stats, char *err,
            size_t errlen) {
  int nr = run_ranks(rc->mc.procs);
  par_options opt;
  if (run_par_options(rc, &opt, err, errlen) != 0) return -1;
  sim *s = launch_sim_new(&rc->mc, nr, err, errlen);   /* rank r on processor r mod P */
  if (!s) return -1;
  if (rc->trace_csv || rc->trace_json) sim_trace(s, rc->trace_csv, rc->trace_json);
  if (rc->trace_size) sim_trace_count(s, rc->trace_size->csv, rc->trace_size->json);
  program p;
  program_init(&p, rc, pairs, npairs, nr);
  pair_net pn = {sim_links(s), rc->pair_net, rc->progress, rc->progress_ud};
  if (pn.links && pn.out) {   /* each pair's network statistics, as it ends */
    memset(pn.out, 0, (size_t)npairs * sizeof *pn.out);
    p.marg.progress = pair_done;
    p.marg.progress_ud = &pn;
  }
  int res = program_finish(&p, sim_run(s, p.procs, err, errlen), err, errlen);
  if (rc->trace_size) sim_trace_size(s, &rc->trace_size->csv_bytes, &rc->trace_size->json_bytes);
  if (stats) *stats = *sim_stats_get(s);
  sim_free(s);
  return res;
}

int run_threads(const run_config *rc, par_pair *pairs, int npairs, mpt_stats *stats, char *err,
                size_t errlen) {
  int nr = run_ranks(rc->mc.procs);
  par_options opt;
  if (run_par_options(rc, &opt, err, errlen) != 0) return -1;
  mpt_config cfg = rc->mc.threads;
  cfg.warn = rc->mc.sim.warn;
  mpt *t = mpt_new(&cfg, nr, err, errlen);
  if (!t) return -1;
  program p;
  program_init(&p, rc, pairs, npairs, nr);
  int res = program_finish(&p, mpt_run(t, p.procs, err, errlen), err, errlen);
  if (stats) *stats = *mpt_stats_get(t);
  mpt_free(t);
  return res;
}

int run_pairs(const run_config *rc, par_pair *pairs, int npairs, char *err, size_t errlen) {
  if (rc->mc.backend != MACHINE_SIM && rc->mc.sim.topo.kind != TOPO_NONE) {
    snprintf(err, errlen, "--topology describes the simulated machine; --backend %s measures this one",
             machine_backend_name(rc->mc.backend));
    return -1;
  }
  switch (rc->mc.backend) {
  case MACHINE_SIM: return run_sim(rc, pairs, npairs, NULL, err, errlen);
  case MACHINE_THREADS: return run_threads(rc, pairs, npairs, NULL, err, errlen);
  case MACHINE_MPI:
#ifdef TILESIM_MPI
    return run_mpi_pairs(rc, pairs, npairs, err, errlen);
#else
    break;
#endif
  }
  snprintf(err, errlen, "run: backend %s is not built in (make mpi builds the MPI programs)",
           machine_backend_name(rc->mc.backend));
  return -1;
}
