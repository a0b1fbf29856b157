/* run.c -- the parallel algorithm on a backend: options, and the drivers
 * for the simulated machine and for threads (MPI's is run_mpi.c). */
#include "run.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "args.h"
#include "par_slave.h"
#include "run_net.h"
#include "xmem.h"
#ifdef TILESIM_MPI
#include "run_mpi.h"
#endif

const char *run_backend_name(run_backend b) {
  static const char *const name[] = {"sim", "threads", "mpi"};
  return (unsigned)b < sizeof name / sizeof *name ? name[b] : "?";
}

int run_backend_ranks(run_backend b) {
#ifdef TILESIM_MPI
  if (b == RUN_MPI) return run_mpi_size();
#else
  (void)b;
#endif
  return 0;
}

void run_config_init(run_config *rc) {
  memset(rc, 0, sizeof *rc);
  rc->procs = 1;
#ifdef TILESIM_MPI
  rc->backend = RUN_MPI;
#else
  rc->backend = RUN_SIM;
#endif
  sim_config_init(&rc->machine);
  mpt_config_init(&rc->threads);
  rc->opt.alloc = ALLOC_HALF;
  rc->opt.min_diag = 1;
  rc->opt.block = 1;
  rc->opt.schedule = PAR_STATIC;
  rc->kind = COST_AREA;
}

const char run_options_help[] =
    "  --procs P          processors (P = 1: master and slave share one); ranks max(2, P)\n"
#ifdef TILESIM_MPI
    "  --backend NAME     mpi (default: the ranks of mpirun), sim or threads\n"
#else
    "  --backend NAME     sim (default: the simulated machine, simulated seconds) or\n"
    "                     threads (a thread per rank, wall-clock seconds)\n"
#endif
    "  --spin S           seconds a waiting rank spins before it sleeps (threads;\n"
    "                     the simulator's --wake model)\n"
    "  --alloc half|size|fit  processor allocation: half (section 4), by size (7.1),\n"
    "                     or fit: by size, no group more slaves than it can use\n"
    "  --min-diag d       at least d nodes of a diagonal per slave (7.2); default 1\n"
    "  --block k          slaves trade run-boundary costs every k diagonals (default 1)\n"
    "  --schedule NAME    static (the paper's groups) or dynamic (bands to free slaves)\n"
    "  --machine NAME     machine profile: tc2000 (default) or unit\n"
    "  --net MODEL        ideal, bus or loggp\n"
    "  --m S, --c S       seconds per message, per unit of work (node)\n"
    "  --master-c S       seconds per unit of the master's bookkeeping (a column of\n"
    "                     a path it assembles, copies or measures); default c/100\n"
    "  --table-c S        seconds per cell of a slave's weight table (where slaves\n"
    "                     build one); --back-c S: per step of a slave's backtracking;\n"
    "                     default 0: not charged (bench --calibrate measures both)\n"
    "  --per-byte S       seconds per message byte (ideal, bus; a topology's links)\n"
    "  --local S          seconds per message between ranks on one processor\n"
    "  --L S --o S --g S --G S   LogGP latency, overhead, gap, gap per byte\n"
    "  --o-send S --o-recv S   processor seconds a send, a receive costs (any net)\n"
    "  --o-send-byte S --o-recv-byte S   ... and per byte (copying)\n"
    "  --wake S           a receiver that waited longer than --spin sleeps: it runs\n"
    "                     S after its message arrives; --o-wake S: its waker's cost\n"
    "  --slowdown F       computing slows by F (a fraction) per other working\n"
    "                     processor; --slowdown-spin F: per other spinning one\n";

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

/* The names the allocation and network parsers take, '|'-separated (so the
 * messages list whatever split.c and sim.c know). */
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

static void net_words(char *buf, size_t len) {
  size_t k = 0;
  buf[0] = 0;
  for (int i = 0; i < 16; i++) {
    const char *n = sim_net_name((sim_net)i);
    sim_net back;
    if (sim_net_parse(n, &back) != 0 || (int)back != i) continue;
    k += (size_t)snprintf(buf + k, k < len ? len - k : 0, "%s%s", k ? "|" : "", n);
  }
}

int run_option(run_config *rc, const char *opt, const char *val, char *err, size_t errlen) {
  sim_config *c = &rc->machine;
  char words[200];
  if (!val) val = "";
  int k = run_net_option(rc, opt, val, err, errlen);   /* topology and placement */
  if (k != 0) return k;
  if (strcmp(opt, "--procs") == 0) return integer(opt, val, 1, RUN_MAX_PROCS, &rc->procs, err, errlen);
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
  if (strcmp(opt, "--backend") == 0) {
#ifdef TILESIM_MPI
    int b = args_word(opt, val, "mpi|sim|threads", err, errlen);
    if (b < 0) return -1;
    rc->backend = b == 0 ? RUN_MPI : b == 1 ? RUN_SIM : RUN_THREADS;
#else
    int b = args_word(opt, val, "sim|threads", err, errlen);
    if (b < 0) {
      if (strcmp(val, "mpi") == 0)
        snprintf(err, errlen, "--backend takes sim or threads (mpi: the MPI backend is in the MPI "
                              "build, make mpi)");
      return -1;
    }
    rc->backend = b == 0 ? RUN_SIM : RUN_THREADS;
#endif
    return 1;
  }
  if (strcmp(opt, "--spin") == 0) {
    double v;
    if (seconds(opt, val, 10, &v, err, errlen) < 0) return -1;
    rc->threads.spin_ns = (long)(v * 1e9 + 0.5);
    c->cpu.spin = v;   /* the simulator's model of that waiting (cpu.h) */
    return 1;
  }
  if (strcmp(opt, "--alloc") == 0) {
    if (split_alloc_parse(val, &rc->opt.alloc) == 0) return 1;
    run_alloc_words(words, sizeof words);
    args_word(opt, val, words, err, errlen);
    return -1;
  }
  if (strcmp(opt, "--machine") == 0) {
    FILE *warn = c->warn;
    if (sim_profile(val, c) == 0) {
      c->warn = warn;
      return 1;
    }
    args_word(opt, val, "tc2000|unit", err, errlen);
    return -1;
  }
  if (strcmp(opt, "--net") == 0) {
    c->topo.kind = TOPO_NONE;   /* --net and --topology: the last one given */
    if (sim_net_parse(val, &c->net) == 0) return 1;
    net_words(words, sizeof words);
    args_word(opt, val, words, err, errlen);
    return -1;
  }
  static const struct { const char *name; size_t off; } secs[] = {
      {"--m", offsetof(sim_config, m)},         {"--c", offsetof(sim_config, c)},
      {"--per-byte", offsetof(sim_config, per_byte)}, {"--local", offsetof(sim_config, local)},
      {"--L", offsetof(sim_config, L)},         {"--o", offsetof(sim_config, o)},
      {"--g", offsetof(sim_config, g)},         {"--G", offsetof(sim_config, G)},
  };
  for (size_t i = 0; i < sizeof secs / sizeof secs[0]; i++)
    if (strcmp(opt, secs[i].name) == 0)
      return seconds(opt, val, RUN_MAX_SECONDS, (double *)((char *)c + secs[i].off), err, errlen);
  double *cpu = cpu_model_field(&c->cpu, opt);   /* --o-send, --wake, --slowdown, ... */
  if (cpu) {
    if (strncmp(opt, "--slowdown", 10) == 0)   /* factors, not seconds */
      return args_real(opt, val, "a factor", 0, 1e3, cpu, err, errlen) == 0 ? 1 : -1;
    return seconds(opt, val, strcmp(opt, "--spin") == 0 ? 10 : RUN_MAX_SECONDS, cpu, err, errlen);
  }
  return 0;
}

double run_master_c(const run_config *rc) {
  return rc->master_c_given ? rc->master_c : RUN_MASTER_SHARE * rc->machine.c;
}

int run_par_options(const run_config *rc, par_options *out, char *err, size_t errlen) {
  *out = rc->opt;
  double c = rc->machine.c, mc = run_master_c(rc);
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
  int P = rc->procs, nr = run_ranks(P), nodes;
  par_options opt;
  if (run_par_options(rc, &opt, err, errlen) != 0) return -1;
  sim_config cfg = rc->machine;
  int *place = xmallocarray((size_t)nr, sizeof *place);
  if (run_net_place(rc, P, place, &nodes, err, errlen) != 0) {
    free(place);
    return -1;
  }
  cfg.procs = P;
  cfg.place = place;
  sim *s = sim_new(&cfg, nr, err, errlen);
  free(place);
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
  int nr = run_ranks(rc->procs);
  par_options opt;
  if (run_par_options(rc, &opt, err, errlen) != 0) return -1;
  mpt_config cfg = rc->threads;
  cfg.warn = rc->machine.warn;
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
  if (rc->backend != RUN_SIM && rc->machine.topo.kind != TOPO_NONE) {
    snprintf(err, errlen, "--topology describes the simulated machine; --backend %s measures this one",
             run_backend_name(rc->backend));
    return -1;
  }
  switch (rc->backend) {
  case RUN_SIM: return run_sim(rc, pairs, npairs, NULL, err, errlen);
  case RUN_THREADS: return run_threads(rc, pairs, npairs, NULL, err, errlen);
  case RUN_MPI:
#ifdef TILESIM_MPI
    return run_mpi_pairs(rc, pairs, npairs, err, errlen);
#else
    break;
#endif
  }
  snprintf(err, errlen, "run: backend %s is not built in (make mpi builds the MPI programs)",
           run_backend_name(rc->backend));
  return -1;
}
