/* ring.c -- how fast the simulator runs: a token ring, and a bare coroutine switch.
 *
 *   rank 0 -> rank 1 -> ... -> rank P-1 -> rank 0     (K laps, P*K messages)
 *
 * Each hop receives the token (an 8-byte counter), computes --work units,
 * increments the counter and sends it on, so after K laps rank 0 holds P*K:
 * that checksum is printed beside the timings, so a fast wrong run shows.
 * On ideal and bus networks the simulated time is exactly P*K*(work*c + m),
 * also checked; on a topology (sim/topo.h) K times the sum over the ring's P
 * hops of work*c + m + h*r + 8*per_byte (store-and-forward: h*(r + 8*per_byte)),
 * h the links between the two ranks' processors.
 *
 * --tokens all: every rank starts with a token; each lap every rank sends
 * its token on and takes its neighbour's, so P messages are in flight at
 * once and share links (contention).  The tokens then sum to P*K. */
#include "prog/bench/bench.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "sim/coro.h"
#include "machine/machine.h"
#include "mp/mp.h"
#include "sim/place.h"
#include "util/progname.h"
#include "sim/sim.h"
#include "sim/trace.h"
#include "util/wallclock.h"
#include "util/xmem.h"

static const char ring_usage[] =
    "usage: bench --ring P --laps K [--net ideal|bus|loggp] [--m S] [--c S] [--work U] "
    "[--profile NAME] [--trace-csv FILE] [--trace-json FILE] [--trace-limit BYTES] [--topology NAME] "
    "[--place NAME] [--hop-latency S] [--per-byte S] [--switching MODE] [--tokens 1|all] "
    "[--stack BYTES] [--print-place]   (bench --help: every mode)\n";
static const char switch_usage[] = "usage: bench --switch N   (bench --help: every mode)\n";

/* The bounds: a ring of at most MACHINE_MAX_RANKS ranks (a million) and a
 * billion laps, and at most RING_MAX_MESSAGES messages in all (P x K:
 * about ten minutes at the simulator's 15-20 million messages a second);
 * at most 1e10 switches (about two minutes at 13 ns). */
#define RING_MAX_MESSAGES 1e10
#define SWITCH_MAX 10000000000ULL

/* Bad usage: "bench: why", arg (or NULL) shown after it, the usage line, 2. */
static int bad(const char *usage, const char *why, const char *arg) { return args_usage("bench", usage, why, arg); }

/* ---- the ring ----------------------------------------------------------- */

typedef struct {
  long laps;
  double work;
  int all;           /* every rank has a token */
  long long token;   /* rank 0's token after the last lap; with all, the sum of all */
  int failed;        /* an mp call failed somewhere */
} ring;

static void ring_rank(mp *self, void *ud) {
  ring *g = ud;
  int me = mp_rank(self), p = mp_size(self);
  int next = (me + 1) % p, prev = (me + p - 1) % p;
  long long tok = 0;
  if (g->all) {   /* every rank: compute, pass on, take the neighbour's */
    for (long k = 0; k < g->laps; k++) {
      if (g->work > 0 && mp_compute(self, g->work) != MP_OK) goto fail;
      tok++;
      if (mp_send(self, next, 0, &tok, sizeof tok) != MP_OK) goto fail;
      if (mp_recv(self, prev, 0, &tok, sizeof tok, NULL) != MP_OK) goto fail;
    }
    g->token += tok;
    return;
  }
  for (long k = 0; k < g->laps; k++) {
    if (me != 0 && mp_recv(self, prev, 0, &tok, sizeof tok, NULL) != MP_OK) goto fail;
    if (g->work > 0 && mp_compute(self, g->work) != MP_OK) goto fail;
    tok++;
    if (mp_send(self, next, 0, &tok, sizeof tok) != MP_OK) goto fail;
    if (me == 0 && mp_recv(self, prev, 0, &tok, sizeof tok, NULL) != MP_OK) goto fail;
  }
  if (me == 0) g->token = tok;
  return;
fail:
  g->failed = 1;
}

int bench_ring(int argc, char **argv) {
  long procs = 0, laps = 0;
  double work = 1;
  int all = 0, print_place = 0, net_given = 0, topo_given = 0;
  place_spec place = {PLACE_LINEAR, 0, ""};
  const char *tcsv = NULL, *tjson = NULL;
  unsigned long long limit = TRACE_LIMIT_DEFAULT;
  sim_config cfg;
  sim_config_init(&cfg);
  char err[512];
  /* The ring's own options; the machine's are machine_option's (the same
   * ranges and messages as every program's), but for those the ring sets
   * itself: its ranks and processors (--ring P), its traces (--trace-csv,
   * --trace-json) and the backend (the simulator). */
  static const char *const opts[] = {"--ring", "--laps", "--work", "--tokens", "--profile", "--trace-csv",
                                     "--trace-json"};
  static const char *const theirs[] = {"--procs", "--ranks", "--backend", "--trace"};
  static const char *const ours[] = {"--net", "--m", "--c", "--per-byte", "--hop-latency", "--topology",
                                     "--place", "--switching", "--trace-limit", "--machine", "--stack"};
  machine_config mc;
  machine_config_init(&mc);
  /* First every value checked; --profile (or --machine) set first, wherever
   * it is, since it sets every machine parameter and the others change one
   * each. */
  for (int i = 1; i < argc; i += 2) {
    const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int known = 0;
    if (machine_option_flag(o)) {   /* --print-place */
      i--;
      continue;
    }
    for (size_t k = 0; k < sizeof theirs / sizeof *theirs; k++)
      if (strcmp(o, theirs[k]) == 0) {
        snprintf(err, sizeof err, "%s: bench --ring P runs P ranks on P simulated processors, "
                                  "traced by --trace-csv and --trace-json", o);
        return bad(ring_usage, err, NULL);
      }
    for (size_t k = 0; k < sizeof opts / sizeof *opts; k++) known |= strcmp(o, opts[k]) == 0;
    if (!known && o[0] == '-') {
      machine_config scratch = mc;
      known = machine_option(&scratch, o, v ? v : "", err, sizeof err) != 0;
      int modelled = 0;   /* the machine options bench_ring_model knows */
      for (size_t k = 0; k < sizeof ours / sizeof *ours; k++) modelled |= strcmp(o, ours[k]) == 0;
      if (known && !modelled) {
        snprintf(err, sizeof err, "%s: bench --ring checks its time against a model without it "
                                  "(a program of your own on tilesim.h takes every machine option)", o);
        return bad(ring_usage, err, NULL);
      }
    }
    if (!known) return bad(ring_usage, o[0] == '-' ? "unknown option" : "unexpected argument", o);
    if (!v) return bad(ring_usage, "an option needs a value", o);
    if ((strcmp(o, "--profile") == 0 || strcmp(o, "--machine") == 0) && sim_profile(v, &mc.sim) != 0) {
      args_word(o, v, "tc2000|unit", err, sizeof err);
      return bad(ring_usage, err, NULL);
    }
  }
  for (int i = 1; i < argc; i += 2) {
    const char *o = argv[i], *v = argv[i + 1];
    int no = 0;
    if (machine_option_flag(o)) {   /* --print-place */
      machine_option(&mc, o, NULL, err, sizeof err);
      i--;
      continue;
    }
    if (strcmp(o, "--ring") == 0) no = args_long(o, v, 1, MACHINE_MAX_RANKS, &procs, err, sizeof err);
    else if (strcmp(o, "--laps") == 0) no = args_long(o, v, 1, 1000000000, &laps, err, sizeof err);
    else if (strcmp(o, "--work") == 0) no = args_real(o, v, "units", 0, 1e9, &work, err, sizeof err);
    else if (strcmp(o, "--profile") == 0 || strcmp(o, "--machine") == 0) no = 0;   /* set above */
    else if (strcmp(o, "--tokens") == 0) {
      int w = args_word(o, v, "1|all", err, sizeof err);
      no = w < 0;
      if (w >= 0) all = w;
    } else if (strcmp(o, "--trace-csv") == 0) no = args_name(o, v, "a file name", 0, err, sizeof err), tcsv = v;
    else if (strcmp(o, "--trace-json") == 0) no = args_name(o, v, "a file name", 0, err, sizeof err), tjson = v;
    else {
      no = machine_option(&mc, o, v, err, sizeof err) < 0;
      net_given |= strcmp(o, "--net") == 0;
      topo_given |= strcmp(o, "--topology") == 0;
    }
    if (no) return bad(ring_usage, err, NULL);
  }
  cfg = mc.sim;
  place = mc.place;
  print_place = mc.print_place;
  limit = mc.trace_limit;
  if (!procs || !laps) return bad(ring_usage, "--ring P and --laps K are needed", NULL);
  if ((double)procs * (double)laps > RING_MAX_MESSAGES) {
    snprintf(err, sizeof err, "--ring P --laps K sends P x K messages, at most 1e10 (%ld x %ld)", procs, laps);
    return bad(ring_usage, err, NULL);
  }
  if (topo_given && net_given)
    return bad(ring_usage, "--net and --topology both choose the network: give one", NULL);
  cfg.procs = (int)procs;
  cfg.warn = stderr;

  /* The placement: rank r on processor map[r] of the machine. */
  topo_spec msp = cfg.topo.kind != TOPO_NONE ? cfg.topo : (topo_spec){TOPO_FULL, 0, 0};
  topo *mach = topo_new(&msp, (int)procs, err, sizeof err);
  if (!mach) return bad(ring_usage, err, NULL);
  int *map = xmallocarray((size_t)procs, sizeof *map);
  if (place_map(&place, mach, (int)procs, map, err, sizeof err) != 0) {
    free(map);
    topo_free(mach);
    return bad(ring_usage, err, NULL);
  }
  if (print_place) {
    char what[PLACE_PATH_MAX + 200], tn[64], pn[PLACE_PATH_MAX + 16];
    topo_spec_str(&cfg.topo, tn, sizeof tn);
    place_spec_str(&place, pn, sizeof pn);
    snprintf(what, sizeof what, "%s (placement %s)", cfg.topo.kind != TOPO_NONE ? tn : sim_net_name(cfg.net), pn);
    machine_print_map(stderr, mach, what, map, (int)procs);
  }
  topo_free(mach);
  cfg.place = map;
  ring g = {laps, work, all, 0, 0};
  mp_proc *pr = xmallocarray((size_t)procs, sizeof *pr);
  for (long r = 0; r < procs; r++) pr[r] = (mp_proc){ring_rank, &g};
  const char *outs[2] = {tcsv, tjson};
  for (int k = 0; k < 2; k++)   /* the traces can be written, before any work */
    if (outs[k] && atomicfile_check(outs[k], err, sizeof err) != 0) {
      progname_eprintf("bench: %s\n", err);
      free(map);
      free(pr);
      return 1;
    }
  /* With a trace: its size first, by the same run writing none (the
   * simulator is deterministic), and none above the limit. */
  if ((tcsv || tjson) && limit != ULLONG_MAX) {
    sim_config quiet = cfg;
    quiet.warn = NULL;
    sim *dry = sim_new(&quiet, (int)procs, err, sizeof err);
    unsigned long long nc = 0, nj = 0;
    if (dry) {
      sim_trace_count(dry, tcsv != NULL, tjson != NULL);
      int ok = sim_run(dry, pr, err, sizeof err) == 0;
      sim_trace_size(dry, &nc, &nj);
      sim_free(dry);
      if (ok && trace_over_limit(nc + nj, limit, err, sizeof err) != 0) {
        progname_eprintf("bench: %s%s%s: %s\n", tcsv ? tcsv : "", tcsv && tjson ? " and " : "",
                tjson ? tjson : "", err);
        free(map);
        free(pr);
        return 1;
      }
    }
    g.token = 0, g.failed = 0;
  }
  sim *s = sim_new(&cfg, (int)procs, err, sizeof err);
  free(map);
  if (!s) {
    progname_eprintf("bench: %s\n", err);
    free(pr);
    return 1;
  }
  /* The traces: temporary files beside the targets, renamed into place
   * only when the run has succeeded (a failed run leaves the targets as
   * they were). */
  atomicfile ac = {NULL, NULL, NULL}, aj = {NULL, NULL, NULL};
  if ((tcsv && atomicfile_open(&ac, tcsv, "w", err, sizeof err) != 0) ||
      (tjson && atomicfile_open(&aj, tjson, "w", err, sizeof err) != 0)) {
    progname_eprintf("bench: %s\n", err);
    if (ac.f) atomicfile_close(&ac, 0, err, sizeof err);
    sim_free(s);
    free(pr);
    return 1;
  }
  sim_trace(s, ac.f, aj.f);
  int rc = sim_run(s, pr, err, sizeof err);
  int status = 0;
  const sim_stats *st = sim_stats_get(s);
  links *net = sim_links(s);
  if (rc != 0) {
    progname_eprintf("bench: %s\n", err);
    status = 1;
  } else if (g.failed || g.token != (long long)procs * laps) {
    progname_eprintf("bench: wrong checksum %lld, expected %lld\n", g.token,
            (long long)procs * laps);
    status = 1;
  } else if (cfg.net != SIM_NET_LOGGP && !all) {
    /* One message at a time around the ring: P*K hops of work*c + m (and the
     * token's bytes) each; on a topology each hop as link.h's idle machine. */
    double lb = (double)sizeof g.token * cfg.per_byte, hop = procs > 1 ? cfg.m + lb : cfg.local;
    double want = (double)procs * (double)laps * (work * cfg.c + hop);
    if (net && procs > 1) {
      const topo *t = links_topo(net);
      int *route = xmallocarray((size_t)topo_max_hops(t), sizeof *route);
      double lap = 0;
      for (long r = 0; r < procs; r++) {
        int a = sim_rank(s, (int)r)->proc, b = sim_rank(s, (int)((r + 1) % procs))->proc;
        double h = a == b ? 0 : topo_route(t, a, b, route);
        double net_s = topo_kind_of(t) == TOPO_BUS ? cfg.hop_latency + lb
                       : cfg.store_forward        ? h * (cfg.hop_latency + lb)
                                                  : h * cfg.hop_latency + lb;
        lap += work * cfg.c + (a == b ? cfg.local : cfg.m + net_s);
      }
      free(route);
      want = (double)laps * lap;
    }
    double diff = st->makespan - want;
    if (diff < 0) diff = -diff;
    if (diff > 1e-9 * want) {
      progname_eprintf("bench: simulated time %.9g, the model says %.9g\n", st->makespan, want);
      status = 1;
    }
  }
  if (ac.f && atomicfile_close(&ac, status == 0, err, sizeof err) != 0 && status == 0) {
    progname_eprintf("bench: %s\n", err);
    status = 1;
  }
  if (aj.f && atomicfile_close(&aj, status == 0, err, sizeof err) != 0 && status == 0) {
    progname_eprintf("bench: %s\n", err);
    status = 1;
  }
  if (status == 0) {   /* a failed run prints no data row */
    long long msgs = st->messages;
    net_stats ns = {0};
    if (net) links_total(net, &ns);
    char tn[64] = "", pn[PLACE_PATH_MAX + 16];
    if (net) topo_spec_str(&cfg.topo, tn, sizeof tn);
    place_spec_str(&place, pn, sizeof pn);
    printf("procs,laps,net,m,c,work,messages,sim_time,topology,place,tokens,hops_per_msg,max_link_msgs,"
           "link_wait,events,switches,wall_s,messages_per_s,ns_per_message,checksum\n");
    printf("%ld,%ld,%s,%.9g,%.9g,%.9g,%lld,%.9f,%s,%s,%s,", procs, laps,
           sim_net_name(net ? SIM_NET_TOPOLOGY : cfg.net), cfg.m, cfg.c, work, msgs, st->makespan, tn,
           pn, all ? "all" : "1");
    if (net)
      printf("%.6f,%lld,%.9f,", ns.messages ? (double)ns.hops / (double)ns.messages : 0.0,
             ns.max_link_msgs, ns.link_wait);
    else
      printf(",,,");
    printf("%lld,%lld,%.6f,%.0f,%.1f,%lld\n", st->events, st->switches, st->wall_s,
           st->wall_s > 0 ? (double)msgs / st->wall_s : 0.0, msgs ? st->wall_s * 1e9 / (double)msgs : 0.0,
           g.token);
  }
  free(pr);
  sim_free(s);
  return status;
}

/* ---- the bare switch ---------------------------------------------------- */

typedef struct {
  coro *main, *a, *b;
  long rounds;
} duo;

static coro *duo_a(void *ud) {
  duo *d = ud;
  for (long i = 0; i < d->rounds; i++) coro_switch(d->a, d->b);
  return d->b;
}

static coro *duo_b(void *ud) {
  duo *d = ud;
  for (long i = 0; i < d->rounds; i++) coro_switch(d->b, d->a);
  return d->main;
}

int bench_switch(int argc, char **argv) {
  unsigned long long un;
  char msg[300];
  if (argc < 3) return bad(switch_usage, "an option needs a value", argv[1]);
  if (argc > 3) return bad(switch_usage, argv[3][0] == '-' ? "unknown option" : "unexpected argument", argv[3]);
  if (args_u64(argv[1], argv[2], 2, SWITCH_MAX, &un, msg, sizeof msg) != 0) return bad(switch_usage, msg, NULL);
  long n = (long)un;
  char err[256];
  duo d = {coro_main_new(), NULL, NULL, n / 2};
  d.a = coro_new(duo_a, &d, 0, err, sizeof err);
  d.b = d.a ? coro_new(duo_b, &d, 0, err, sizeof err) : NULL;
  if (!d.a || !d.b) {
    progname_eprintf("bench: %s\n", err);
    return 1;
  }
  double t0 = wallclock();
  coro_switch(d.main, d.a);
  double wall = wallclock() - t0;
  /* Switches: main->a, then a->b and b->a each rounds times (the last a->b
   * is a's exit), then b's exit to main. */
  long long switches = 2 * (long long)d.rounds + 2;
  printf("backend,switches,wall_s,ns_per_switch\n");
  printf("%s,%lld,%.6f,%.2f\n", coro_backend(), switches, wall, wall * 1e9 / (double)switches);
  coro_free(d.a);
  coro_free(d.b);
  coro_free(d.main);
  return 0;
}
