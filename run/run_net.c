/* run_net.c -- the network options of a run, its placement, and the printed map (run_net.h). */
#include "run_net.h"

#include <stdlib.h>
#include <string.h>

#include "args.h"
#include "xmem.h"

const char run_net_help[] =
    "  --topology NAME    the network as links (sim/topo.h): full, bus, line, ring,\n"
    "                     mesh:WxH, torus:WxH, hypercube:d, butterfly:k (unsized:\n"
    "                     fitted to P); replaces --net; --per-byte is then every link's\n"
    "  --hop-latency S    seconds per link a message crosses (topologies; default 0)\n"
    "  --switching MODE   cut-through (default) or store-and-forward (topologies)\n"
    "  --place NAME       the processors' places on the machine: linear (default),\n"
    "                     snake, gray, random:SEED or file:PATH (a processor a line)\n";

/* "--topology: " before the parser's message, so that it names the option. */
static int prefix(const char *opt, char *err, size_t errlen) {
  char *copy = xstrdup(err);
  snprintf(err, errlen, "%s: %s", opt, copy);
  free(copy);
  return -1;
}

int run_net_option(run_config *rc, const char *opt, const char *val, char *err, size_t errlen) {
  sim_config *c = &rc->machine;
  if (!val) val = "";
  if (strcmp(opt, "--topology") == 0) {
    topo_spec sp;
    if (topo_parse(val, &sp, err, errlen) != 0) return prefix(opt, err, errlen);
    c->topo = sp;
    c->net = SIM_NET_TOPOLOGY;
    return 1;
  }
  if (strcmp(opt, "--hop-latency") == 0)
    return args_real(opt, val, "seconds", 0, 1e9, &c->hop_latency, err, errlen) == 0 ? 1 : -1;
  if (strcmp(opt, "--switching") == 0) {
    int w = args_word(opt, val, "cut-through|store-and-forward", err, errlen);
    if (w < 0) return -1;
    c->store_forward = w;
    return 1;
  }
  if (strcmp(opt, "--place") == 0) {
    place_spec p;
    if (place_parse(val, &p, err, errlen) != 0) return prefix(opt, err, errlen);
    rc->place = p;
    return 1;
  }
  return 0;
}

/* The machine of a run on P processors: its topology, or P processors
 * without links when it has none. */
static topo *machine(const run_config *rc, int P, char *err, size_t errlen) {
  topo_spec sp = rc->machine.topo;
  if (sp.kind == TOPO_NONE) sp = (topo_spec){TOPO_FULL, 0, 0};
  return topo_new(&sp, P, err, errlen);
}

/* place[] of the run's ranks, given its machine. */
static int place_on(const run_config *rc, const topo *t, int P, int *place, char *err,
                    size_t errlen) {
  int *map = xmallocarray((size_t)P, sizeof *map);
  int res = place_map(&rc->place, t, P, map, err, errlen);
  for (int r = 0; res == 0 && r < run_ranks(P); r++) place[r] = map[P == 1 ? 0 : r];
  free(map);
  return res;
}

int run_net_place(const run_config *rc, int P, int *place, int *nodes, char *err, size_t errlen) {
  topo *t = machine(rc, P, err, errlen);
  if (!t) return -1;
  *nodes = topo_nodes(t);
  int res = place_on(rc, t, P, place, err, errlen);
  topo_free(t);
  return res;
}

void run_net_print_map(FILE *f, const topo *t, const char *what, const int *place, int nranks) {
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

int run_net_print(FILE *f, const run_config *rc, int P, char *err, size_t errlen) {
  topo *t = machine(rc, P, err, errlen);
  if (!t) return -1;
  int nr = run_ranks(P), *place = xmallocarray((size_t)nr, sizeof *place);
  int res = place_on(rc, t, P, place, err, errlen);
  if (res == 0) {
    char tn[64], pn[PLACE_PATH_MAX + 16], what[PLACE_PATH_MAX + 200];
    topo_spec_str(&rc->machine.topo, tn, sizeof tn);
    place_spec_str(&rc->place, pn, sizeof pn);
    snprintf(what, sizeof what, "%s (P = %d, placement %s)",
             rc->machine.topo.kind == TOPO_NONE ? sim_net_name(rc->machine.net) : tn, P, pn);
    run_net_print_map(f, t, what, place, nr);
  }
  free(place);
  topo_free(t);
  return res;
}
