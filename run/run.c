/* run.c -- the parallel algorithm on the simulated machine. */
#include "run.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "par_slave.h"
#include "xmem.h"

void run_config_init(run_config *rc) {
  memset(rc, 0, sizeof *rc);
  rc->procs = 1;
  sim_config_init(&rc->machine);
  rc->opt.alloc = ALLOC_HALF;
  rc->opt.min_diag = 1;
  rc->kind = COST_AREA;
}

const char run_options_help[] =
    "  --procs P          simulated processors (P = 1: master and slave share one)\n"
    "  --alloc half|size  processor allocation: half (section 4) or by size (7.1)\n"
    "  --min-diag d       at least d nodes of a diagonal per slave (7.2); default 1\n"
    "  --machine NAME     machine profile: tc2000 (default) or unit\n"
    "  --net MODEL        ideal, bus or loggp\n"
    "  --m S, --c S       seconds per message, per unit of work (node)\n"
    "  --per-byte S       seconds per message byte (ideal, bus)\n"
    "  --local S          seconds per message between ranks on one processor\n"
    "  --L S --o S --g S --G S   LogGP latency, overhead, gap, gap per byte\n";

static int seconds(const char *opt, const char *val, double *out, char *err, size_t errlen) {
  char *end;
  double v = strtod(val, &end);
  if (end == val || *end || !(v >= 0) || v > 1e9) {
    snprintf(err, errlen, "%s takes seconds, a finite number >= 0 (%s)", opt, val);
    return -1;
  }
  *out = v;
  return 1;
}

static int integer(const char *opt, const char *val, int lo, int hi, int *out, char *err,
                   size_t errlen) {
  char *end;
  long v = strtol(val, &end, 10);
  if (end == val || *end || v < lo || v > hi) {
    snprintf(err, errlen, "%s takes a whole number from %d to %d (%s)", opt, lo, hi, val);
    return -1;
  }
  *out = (int)v;
  return 1;
}

int run_option(run_config *rc, const char *opt, const char *val, char *err, size_t errlen) {
  sim_config *c = &rc->machine;
  if (!val) val = "";
  if (strcmp(opt, "--procs") == 0) return integer(opt, val, 1, 4096, &rc->procs, err, errlen);
  if (strcmp(opt, "--min-diag") == 0)
    return integer(opt, val, 1, 1 << 30, &rc->opt.min_diag, err, errlen);
  if (strcmp(opt, "--alloc") == 0) {
    if (split_alloc_parse(val, &rc->opt.alloc) == 0) return 1;
    snprintf(err, errlen, "--alloc is half or size (%s)", val);
    return -1;
  }
  if (strcmp(opt, "--machine") == 0) {
    FILE *warn = c->warn;
    if (sim_profile(val, c) == 0) {
      c->warn = warn;
      return 1;
    }
    snprintf(err, errlen, "unknown machine, use tc2000 or unit (%s)", val);
    return -1;
  }
  if (strcmp(opt, "--net") == 0) {
    if (sim_net_parse(val, &c->net) == 0) return 1;
    snprintf(err, errlen, "--net is ideal, bus or loggp (%s)", val);
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
      return seconds(opt, val, (double *)((char *)c + secs[i].off), err, errlen);
  return 0;
}

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
  par_master_arg marg = {npairs, pairs, rc->kind, rc->opt, 0, "", rc->progress, rc->progress_ud};
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
