/* profile.c -- the simulator's configurations (profile.h). */
#include "sim/profile.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "util/words.h"

/* "tc2000": the BBN TC2000 of Johnson, Livadas & Talele (1993), calibrated
 * so that the paper's experiments (sections 6 and 7) show what it reports
 * (doc/model.md, "Calibration: the tc2000 profile").
 *   c = 50 us per node: a node is two triangle areas and a comparison, about
 *       1,000 cycles of the 20 MHz Motorola 88100 with its square root in
 *       software.
 *   m = 275 us per message, on a bus: the paper's message queues were
 *       simulated in the TC2000's shared memory, so a message is a locked
 *       enqueue and dequeue, one at a time, and later ones wait; 275 us puts
 *       the speedup's flattening and decline near 12 processors (section 6).
 *   per_byte = 2.6e-8 s: the butterfly switch's 38 MB/s.
 *   local = 0: master and slave on one processor exchange for free.
 * The LogGP fields, for --net loggp: L = m, no overhead, gap or per-byte gap. */
static void profile_tc2000(sim_config *cfg) {
  *cfg = (sim_config){0};
  cfg->procs = 1;
  cfg->place = NULL;
  cfg->c = 50e-6;          /* seconds per compute unit (a node) */
  cfg->m = 275e-6;         /* seconds per message */
  cfg->per_byte = 2.6e-8;  /* seconds per byte */
  cfg->local = 0;          /* seconds per message on one processor */
  cfg->net = SIM_NET_BUS;
  cfg->L = 275e-6;         /* LogGP latency */
  cfg->o = 0;              /* LogGP overhead */
  cfg->g = 0;              /* LogGP gap */
  cfg->G = 0;              /* LogGP gap per byte */
  cpu_model_init(&cfg->cpu);  /* no processor overheads, wake-ups or slowdown */
  cfg->stack = 0;
  cfg->warn = stderr;
}

/* "unit": whole seconds, for reading a trace by eye. */
static void profile_unit(sim_config *cfg) {
  profile_tc2000(cfg);
  cfg->c = 1;
  cfg->m = 1;
  cfg->per_byte = 0;
  cfg->L = 1;
}

void sim_config_init(sim_config *cfg) { profile_tc2000(cfg); }

int sim_profile(const char *name, sim_config *cfg) {
  if (strcmp(name, "tc2000") == 0)
    profile_tc2000(cfg);
  else if (strcmp(name, "unit") == 0)
    profile_unit(cfg);
  else
    return -1;
  return 0;
}

static const char *const net_names[] = {"ideal", "bus", "loggp", "topology"};

const char *sim_net_name(sim_net net) {
  return (unsigned)net < sizeof net_names / sizeof *net_names ? net_names[net] : "?";
}

int sim_net_parse(const char *name, sim_net *net) {
  int i = words_find(net_names, SIM_NET_TOPOLOGY, name);
  return i < 0 ? -1 : (*net = (sim_net)i, 0);
}

void sim_net_words(char *buf, size_t len) { words_join(net_names, SIM_NET_TOPOLOGY, buf, len); }

int sim_config_check(const sim_config *cfg, int nranks, topo **tp, int *procs, char *err, size_t errlen) {
  if (cfg->procs < 1) {
    snprintf(err, errlen, "sim: %d processors: need at least 1", cfg->procs);
    return -1;
  }
  const struct {
    const char *name;
    double v;
  } costs[] = {{"c", cfg->c},          {"m", cfg->m}, {"per_byte", cfg->per_byte},
               {"local", cfg->local},  {"L", cfg->L}, {"o", cfg->o},
               {"g", cfg->g},          {"G", cfg->G}, {"hop_latency", cfg->hop_latency}};
  for (size_t i = 0; i < sizeof costs / sizeof *costs; i++) {
    if (!(costs[i].v >= 0) || isinf(costs[i].v)) {
      snprintf(err, errlen, "sim: cost %s = %g: must be finite and >= 0", costs[i].name,
               costs[i].v);
      return -1;
    }
  }
  if (cpu_model_check(&cfg->cpu, err, errlen) != 0) return -1;
  if ((unsigned)cfg->net > SIM_NET_TOPOLOGY ||
      (cfg->net == SIM_NET_TOPOLOGY && cfg->topo.kind == TOPO_NONE)) {
    snprintf(err, errlen, "sim: unknown network model %d", (int)cfg->net);
    return -1;
  }
  /* A topology: its processors (at least procs), its links. */
  *tp = NULL;
  *procs = cfg->procs;
  if (cfg->topo.kind != TOPO_NONE) {
    char terr[200];
    if (!(*tp = topo_new(&cfg->topo, cfg->procs, terr, sizeof terr))) {
      snprintf(err, errlen, "sim: %s", terr);
      return -1;
    }
    *procs = topo_nodes(*tp);
  }
  if (cfg->place) {
    for (int r = 0; r < nranks; r++) {
      if (cfg->place[r] < 0 || cfg->place[r] >= *procs) {
        snprintf(err, errlen, "sim: place[%d] = %d: processors are 0..%d", r, cfg->place[r],
                 *procs - 1);
        topo_free(*tp);
        *tp = NULL;
        return -1;
      }
    }
  }
  return 0;
}
