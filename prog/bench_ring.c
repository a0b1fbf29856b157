/* bench_ring.c -- how fast the simulator runs: a token ring, and a bare coroutine switch.
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
#include "bench_ring.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "coro.h"
#include "mp.h"
#include "place.h"
#include "run_net.h"
#include "sim.h"
#include "wallclock.h"
#include "xmem.h"

static const char ring_usage[] =
    "usage: bench --ring P --laps K [--net ideal|bus|loggp] [--m S] [--c S] [--work U] "
    "[--profile NAME] [--trace-csv FILE] [--trace-json FILE] [--topology NAME] [--place NAME] "
    "[--hop-latency S] [--per-byte S] [--switching MODE] [--tokens 1|all] [--print-place]\n";
static const char switch_usage[] = "usage: bench --switch N\n";

/* ---- option values ------------------------------------------------------ */

static int parse_long(const char *s, long lo, long hi, long *out) {
  char *end;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (errno || end == s || *end || v < lo || v > hi) return -1;
  *out = v;
  return 0;
}

static int parse_seconds(const char *s, double *out) {
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (errno || end == s || *end || !(v >= 0) || v > 1e300) return -1;
  *out = v;
  return 0;
}

static int bad(const char *usage, const char *fmt, const char *arg) {
  fputs("bench: ", stderr);
  fprintf(stderr, fmt, arg);
  fputc('\n', stderr);
  fputs(usage, stderr);
  return 2;
}

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

int bench_ring_main(int argc, char **argv) {
  long procs = 0, laps = 0;
  double work = 1;
  int all = 0, print_place = 0, net_given = 0;
  place_spec place = {PLACE_LINEAR, 0, ""};
  const char *tcsv = NULL, *tjson = NULL;
  sim_config cfg;
  sim_config_init(&cfg);
  /* --profile first, so that the other options override it wherever it is. */
  for (int i = 2; i + 1 < argc; i++)
    if (strcmp(argv[i], "--profile") == 0 && sim_profile(argv[i + 1], &cfg) != 0)
      return bad(ring_usage, "unknown profile '%s'", argv[i + 1]);
  char err[512];
  for (int i = 1; i < argc; i += 2) {
    const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (strcmp(o, "--print-place") == 0) {
      print_place = 1;
      i--;
      continue;
    }
    if (!v) return bad(ring_usage, "%s needs a value", o);
    if (strcmp(o, "--ring") == 0) {
      if (parse_long(v, 1, 1000000, &procs)) return bad(ring_usage, "--ring %s: need 1..1000000 ranks", v);
    } else if (strcmp(o, "--laps") == 0) {
      if (parse_long(v, 1, LONG_MAX, &laps)) return bad(ring_usage, "--laps %s: need a count >= 1", v);
    } else if (strcmp(o, "--net") == 0) {
      if (sim_net_parse(v, &cfg.net)) return bad(ring_usage, "--net %s: ideal, bus or loggp", v);
      net_given = 1;
    } else if (strcmp(o, "--m") == 0) {
      if (parse_seconds(v, &cfg.m)) return bad(ring_usage, "--m %s: need seconds >= 0", v);
    } else if (strcmp(o, "--c") == 0) {
      if (parse_seconds(v, &cfg.c)) return bad(ring_usage, "--c %s: need seconds >= 0", v);
    } else if (strcmp(o, "--work") == 0) {
      if (parse_seconds(v, &work)) return bad(ring_usage, "--work %s: need units >= 0", v);
    } else if (strcmp(o, "--per-byte") == 0) {
      if (parse_seconds(v, &cfg.per_byte)) return bad(ring_usage, "--per-byte %s: need seconds >= 0", v);
    } else if (strcmp(o, "--hop-latency") == 0) {
      if (parse_seconds(v, &cfg.hop_latency)) return bad(ring_usage, "--hop-latency %s: need seconds >= 0", v);
    } else if (strcmp(o, "--topology") == 0) {
      if (topo_parse(v, &cfg.topo, err, sizeof err)) return bad(ring_usage, "%s", err);
    } else if (strcmp(o, "--place") == 0) {
      if (place_parse(v, &place, err, sizeof err)) return bad(ring_usage, "%s", err);
    } else if (strcmp(o, "--switching") == 0) {
      if (strcmp(v, "cut-through") == 0) cfg.store_forward = 0;
      else if (strcmp(v, "store-and-forward") == 0) cfg.store_forward = 1;
      else return bad(ring_usage, "--switching %s: cut-through or store-and-forward", v);
    } else if (strcmp(o, "--tokens") == 0) {
      if (strcmp(v, "all") == 0) all = 1;
      else if (strcmp(v, "1") == 0) all = 0;
      else return bad(ring_usage, "--tokens %s: 1 or all", v);
    } else if (strcmp(o, "--trace-csv") == 0) {
      tcsv = v;
    } else if (strcmp(o, "--trace-json") == 0) {
      tjson = v;
    } else if (strcmp(o, "--profile") != 0) {
      return bad(ring_usage, "unknown option '%s'", o);
    }
  }
  if (!procs || !laps) return bad(ring_usage, "%s", "--ring P and --laps K are needed");
  if (cfg.topo.kind != TOPO_NONE && net_given)
    return bad(ring_usage, "%s", "--net and --topology both choose the network: give one");
  cfg.procs = (int)procs;
  cfg.warn = stderr;

  /* The placement: rank r on processor map[r] of the machine. */
  topo_spec msp = cfg.topo.kind != TOPO_NONE ? cfg.topo : (topo_spec){TOPO_FULL, 0, 0};
  topo *mach = topo_new(&msp, (int)procs, err, sizeof err);
  if (!mach) return bad(ring_usage, "%s", err);
  int *map = xmallocarray((size_t)procs, sizeof *map);
  if (place_map(&place, mach, (int)procs, map, err, sizeof err) != 0) {
    free(map);
    topo_free(mach);
    return bad(ring_usage, "%s", err);
  }
  if (print_place) {
    char what[PLACE_PATH_MAX + 200], tn[64], pn[PLACE_PATH_MAX + 16];
    topo_spec_str(&cfg.topo, tn, sizeof tn);
    place_spec_str(&place, pn, sizeof pn);
    snprintf(what, sizeof what, "%s (placement %s)", cfg.topo.kind != TOPO_NONE ? tn : sim_net_name(cfg.net), pn);
    run_net_print_map(stderr, mach, what, map, (int)procs);
  }
  topo_free(mach);
  cfg.place = map;
  sim *s = sim_new(&cfg, (int)procs, err, sizeof err);
  free(map);
  if (!s) {
    fprintf(stderr, "bench: %s\n", err);
    return 1;
  }
  FILE *fc = NULL, *fj = NULL;
  if (tcsv && !(fc = fopen(tcsv, "w"))) {
    fprintf(stderr, "bench: cannot write %s: %s\n", tcsv, strerror(errno));
    sim_free(s);
    return 1;
  }
  if (tjson && !(fj = fopen(tjson, "w"))) {
    fprintf(stderr, "bench: cannot write %s: %s\n", tjson, strerror(errno));
    if (fc) fclose(fc);
    sim_free(s);
    return 1;
  }
  sim_trace(s, fc, fj);
  ring g = {laps, work, all, 0, 0};
  mp_proc *pr = xmallocarray((size_t)procs, sizeof *pr);
  for (long r = 0; r < procs; r++) pr[r] = (mp_proc){ring_rank, &g};
  int rc = sim_run(s, pr, err, sizeof err);
  int status = 0;
  if ((fc && fclose(fc) != 0) || (fj && fclose(fj) != 0)) {
    fprintf(stderr, "bench: cannot write a trace file\n");
    status = 1;
  }
  const sim_stats *st = sim_stats_get(s);
  long long msgs = st->messages;
  links *net = sim_links(s);
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
  if (rc != 0) {
    fprintf(stderr, "bench: %s\n", err);
    status = 1;
  } else if (g.failed || g.token != (long long)procs * laps) {
    fprintf(stderr, "bench: wrong checksum %lld, expected %lld\n", g.token,
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
      fprintf(stderr, "bench: simulated time %.9g, the model says %.9g\n", st->makespan, want);
      status = 1;
    }
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

int bench_switch_main(int argc, char **argv) {
  long n;
  if (argc != 3 || parse_long(argv[2], 2, LONG_MAX, &n))
    return bad(switch_usage, "%s", "--switch needs a count N >= 2");
  char err[256];
  duo d = {coro_main_new(), NULL, NULL, n / 2};
  d.a = coro_new(duo_a, &d, 0, err, sizeof err);
  d.b = d.a ? coro_new(duo_b, &d, 0, err, sizeof err) : NULL;
  if (!d.a || !d.b) {
    fprintf(stderr, "bench: %s\n", err);
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
