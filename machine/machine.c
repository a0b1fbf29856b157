/* machine.c -- the machine's options, its placement and the printed map (machine.h). */
#include "machine/machine.h"

#include <limits.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "sim/trace.h"
#include "util/xmem.h"
#ifdef TILESIM_MPI
#include <mpi.h>
#endif

const char *machine_backend_name(machine_backend b) {
  static const char *const name[] = {"sim", "threads", "mpi"};
  return (unsigned)b < sizeof name / sizeof *name ? name[b] : "?";
}

int machine_backend_ranks(machine_backend b) {
#ifdef TILESIM_MPI
  int up = 0, n = 0;
  if (b == MACHINE_MPI && MPI_Initialized(&up) == MPI_SUCCESS && up) MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
#else
  (void)b;
  return 0;
#endif
}

void machine_config_init(machine_config *mc) {
  memset(mc, 0, sizeof *mc);
  mc->procs = 1;
#ifdef TILESIM_MPI
  mc->backend = MACHINE_MPI;
#else
  mc->backend = MACHINE_SIM;
#endif
  sim_config_init(&mc->sim);
  mpt_config_init(&mc->threads);
  mc->trace_limit = TRACE_LIMIT_DEFAULT;
}

const char machine_ranks_help[] =
    "  --ranks R          ranks (default: one per processor; more ranks than\n"
    "                     processors share them, rank r on processor r mod P)\n";

const char machine_stack_help[] =
    "  --stack BYTES      each rank's stack on the simulator, 16k to 1G (default\n"
    "                     256 KiB): a rank that overflows it is named\n";

const char machine_help[] =
    "  --procs P          processors (default 1; tilesim-mpirun: one per rank)\n"
#ifdef TILESIM_MPI
    "  --backend NAME     mpi (default: the ranks of mpirun), sim or threads\n"
#else
    "  --backend NAME     sim (default: the simulated machine, simulated seconds) or\n"
    "                     threads (a thread per rank, wall-clock seconds)\n"
#endif
    "  --spin S           seconds a waiting rank spins before it sleeps (threads;\n"
    "                     the simulator's --wake model)\n"
    "  --machine NAME     machine profile: tc2000 (default) or unit\n"
    "  --net MODEL        ideal, bus or loggp\n"
    "  --m S, --c S       seconds per message, per unit of work (node)\n"
    "  --per-byte S       seconds per message byte (ideal, bus; a topology's links)\n"
    "  --local S          seconds per message between ranks on one processor\n"
    "  --L S --o S --g S --G S   LogGP latency, overhead, gap, gap per byte\n"
    "  --o-send S --o-recv S   processor seconds a send, a receive costs (any net)\n"
    "  --o-send-byte S --o-recv-byte S   ... and per byte (copying)\n"
    "  --wake S           a receiver that waited longer than --spin sleeps: it runs\n"
    "                     S after its message arrives; --o-wake S: its waker's cost\n"
    "  --slowdown F       computing slows by F (a fraction) per other working\n"
    "                     processor; --slowdown-spin F: per other spinning one\n"
    "  --topology NAME    the network as links (sim/topo.h): full, bus, line, ring,\n"
    "                     mesh:WxH, torus:WxH, hypercube:d, butterfly:k (unsized:\n"
    "                     fitted to P); replaces --net; --per-byte is then every link's\n"
    "  --hop-latency S    seconds per link a message crosses (topologies; default 0)\n"
    "  --switching MODE   cut-through (default) or store-and-forward (topologies)\n"
    "  --place NAME       the processors' places on the machine: linear (default),\n"
    "                     snake, gray, random:SEED or file:PATH (a processor a line)\n"
    "  --print-place      print where the ranks run on the machine (stderr)\n"
    "  --trace FILE       the simulated timeline: CSV, or Chrome trace JSON (.json)\n"
    "  --trace-limit BYTES  the largest trace to write (default 1G; 500M, 5G, none):\n"
    "                     a larger one is refused, and no file is left\n";

/* The seconds options' range: from 0 to a billion seconds (31 years). */
#define MAX_SECONDS 1e9

static int seconds(const char *opt, const char *val, double hi, double *out, char *err, size_t errlen) {
  return args_real(opt, val, "seconds", 0, hi, out, err, errlen) == 0 ? 1 : -1;
}

static int integer(const char *opt, const char *val, int lo, int hi, int *out, char *err, size_t errlen) {
  long v;
  if (args_long(opt, val, lo, hi, &v, err, errlen) != 0) return -1;
  *out = (int)v;
  return 1;
}


/* "--topology: " before the parser's message, so that it names the option. */
static int prefix(const char *opt, char *err, size_t errlen) {
  char *copy = xstrdup(err);
  snprintf(err, errlen, "%s: %s", opt, copy);
  free(copy);
  return -1;
}

int machine_option_flag(const char *opt) { return strcmp(opt, "--print-place") == 0; }

int machine_option(machine_config *mc, const char *opt, const char *val, char *err, size_t errlen) {
  sim_config *c = &mc->sim;
  char words[200];
  if (strcmp(opt, "--print-place") == 0) {
    mc->print_place = 1;
    return 1;
  }
  if (!val) val = "";
  if (strcmp(opt, "--procs") == 0) return integer(opt, val, 1, MACHINE_MAX_PROCS, &mc->procs, err, errlen);
  if (strcmp(opt, "--ranks") == 0) return integer(opt, val, 1, MACHINE_MAX_RANKS, &mc->ranks, err, errlen);
  if (strcmp(opt, "--stack") == 0) {
    unsigned long long b;
    if (args_bytes(opt, val, &b, err, errlen) != 0 || b < MACHINE_STACK_MIN || b > MACHINE_STACK_MAX) {
      char shown[80];
      args_show(val, shown, sizeof shown);
      snprintf(err, errlen, "%s takes bytes from 16k to 1G, like 256k or 1M (%s)", opt, shown);
      return -1;
    }
    c->stack = (size_t)b;
    return 1;
  }
  if (strcmp(opt, "--backend") == 0) {
#ifdef TILESIM_MPI
    int b = args_word(opt, val, "mpi|sim|threads", err, errlen);
    if (b < 0) return -1;
    mc->backend = b == 0 ? MACHINE_MPI : b == 1 ? MACHINE_SIM : MACHINE_THREADS;
#else
    int b = args_word(opt, val, "sim|threads", err, errlen);
    if (b < 0) {
      if (strcmp(val, "mpi") == 0)
        snprintf(err, errlen, "--backend takes sim or threads (mpi: the MPI backend is in the MPI "
                              "build, make mpi)");
      return -1;
    }
    mc->backend = b == 0 ? MACHINE_SIM : MACHINE_THREADS;
#endif
    return 1;
  }
  if (strcmp(opt, "--spin") == 0) {
    double v;
    if (seconds(opt, val, 10, &v, err, errlen) < 0) return -1;
    mc->threads.spin_ns = (long)(v * 1e9 + 0.5);
    c->cpu.spin = v;   /* the simulator's model of that waiting (cpu.h) */
    return 1;
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
    sim_net_words(words, sizeof words);
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
      return seconds(opt, val, MAX_SECONDS, (double *)((char *)c + secs[i].off), err, errlen);
  double *cpu = cpu_model_field(&c->cpu, opt);   /* --o-send, --wake, --slowdown, ... */
  if (cpu) {
    if (strncmp(opt, "--slowdown", 10) == 0)   /* factors, not seconds */
      return args_real(opt, val, "a factor", 0, 1e3, cpu, err, errlen) == 0 ? 1 : -1;
    return seconds(opt, val, MAX_SECONDS, cpu, err, errlen);
  }
  if (strcmp(opt, "--topology") == 0) {
    topo_spec sp;
    if (topo_parse(val, &sp, err, errlen) != 0) return prefix(opt, err, errlen);
    c->topo = sp;
    c->net = SIM_NET_TOPOLOGY;
    return 1;
  }
  if (strcmp(opt, "--hop-latency") == 0)
    return args_real(opt, val, "seconds", 0, MAX_SECONDS, &c->hop_latency, err, errlen) == 0 ? 1 : -1;
  if (strcmp(opt, "--switching") == 0) {
    int w = args_word(opt, val, "cut-through|store-and-forward", err, errlen);
    if (w < 0) return -1;
    c->store_forward = w;
    return 1;
  }
  if (strcmp(opt, "--place") == 0) {
    place_spec p;
    if (place_parse(val, &p, err, errlen) != 0) return prefix(opt, err, errlen);
    mc->place = p;
    return 1;
  }
  if (strcmp(opt, "--trace") == 0) {
    if (args_name(opt, val, "a file name", 0, err, errlen) != 0) return -1;
    mc->trace = val;
    return 1;
  }
  if (strcmp(opt, "--trace-limit") == 0) {
    if (args_bytes(opt, val, &mc->trace_limit, err, errlen) != 0) return -1;
    mc->trace_limit_given = 1;
    return 1;
  }
  return 0;
}

/* ==== placement =========================================================== */

/* The machine of a run on P processors: its topology, or P processors
 * without links when it has none. */
static topo *machine_topo(const machine_config *mc, char *err, size_t errlen) {
  topo_spec sp = mc->sim.topo;
  if (sp.kind == TOPO_NONE) sp = (topo_spec){TOPO_FULL, 0, 0};
  return topo_new(&sp, mc->procs, err, errlen);
}

/* place[] of nranks ranks, given the machine. */
static int place_on(const machine_config *mc, const topo *t, int nranks, int *place, char *err,
                    size_t errlen) {
  int P = mc->procs;
  int *map = xmallocarray((size_t)P, sizeof *map);
  int res = place_map(&mc->place, t, P, map, err, errlen);
  for (int r = 0; res == 0 && r < nranks; r++) place[r] = map[r % P];
  free(map);
  return res;
}

int machine_place(const machine_config *mc, int nranks, int *place, int *nodes, char *err,
                  size_t errlen) {
  topo *t = machine_topo(mc, err, errlen);
  if (!t) return -1;
  *nodes = topo_nodes(t);
  int res = place_on(mc, t, nranks, place, err, errlen);
  topo_free(t);
  return res;
}

void machine_print_map(FILE *f, const topo *t, const char *what, const int *place, int nranks) {
  int N = topo_nodes(t), w, h;
  int grid = topo_grid(t, &w, &h);
  fprintf(f, "place: %d ranks on %s, %d processor%s\n", nranks, what, N, N == 1 ? "" : "s");
  for (int r = 0; r < nranks; r++) {
    fprintf(f, "place: rank %d -> processor %d", r, place[r]);
    if (grid && h > 1) fprintf(f, " (x %d, y %d)", place[r] % w, place[r] / w);
    fputc('\n', f);
  }
  if (!grid || w > 64 || h > 64) return;
  /* The grid: the lowest rank on each processor, '*' when it shares it. */
  int *first = xmallocarray((size_t)N, sizeof *first), *count = xcalloc((size_t)N, sizeof *count);
  for (int p = 0; p < N; p++) first[p] = -1;
  for (int r = 0; r < nranks; r++) {
    if (first[place[r]] < 0) first[place[r]] = r;
    count[place[r]]++;
  }
  int width = 3;
  for (int n = nranks; n >= 100; n /= 10) width++;
  for (int y = 0; y < h; y++) {
    fputs("place:", f);
    for (int x = 0; x < w; x++) {
      int p = y * w + x;
      if (first[p] < 0) fprintf(f, " %*s", width, ".");
      else if (count[p] > 1) fprintf(f, " %*d*", width - 1, first[p]);
      else fprintf(f, " %*d", width, first[p]);
    }
    fputc('\n', f);
  }
  free(first);
  free(count);
}

int machine_print_place(FILE *f, const machine_config *mc, int nranks, char *err, size_t errlen) {
  topo *t = machine_topo(mc, err, errlen);
  if (!t) return -1;
  int *place = xmallocarray((size_t)nranks, sizeof *place);
  int res = place_on(mc, t, nranks, place, err, errlen);
  if (res == 0) {
    char tn[64], pn[PLACE_PATH_MAX + 16], what[PLACE_PATH_MAX + 200];
    topo_spec_str(&mc->sim.topo, tn, sizeof tn);
    place_spec_str(&mc->place, pn, sizeof pn);
    snprintf(what, sizeof what, "%s (P = %d, placement %s)",
             mc->sim.topo.kind == TOPO_NONE ? sim_net_name(mc->sim.net) : tn, mc->procs, pn);
    machine_print_map(f, t, what, place, nranks);
  }
  free(place);
  topo_free(t);
  return res;
}
