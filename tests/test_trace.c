/* test_trace.c -- a trace's size known before it is written: the count mode
 * (sim_trace_count) against the bytes the same run really writes, CSV and
 * JSON, byte for byte, over random programs on every network model, shared
 * processors (cpuwait), any-source waits, and clocks from microseconds to
 * millions of seconds (times of every width). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "tests/randprog.h"
#include "sim/sim.h"
#include "sim/trace.h"

/* One run: written (counted == 0) or counted; the two sizes. */
static int run(const sim_config *cfg, int nranks, uint64_t seed, int counted, long *csv, long *json) {
  char err[512];
  randprog p;
  randprog_make(&p, seed, nranks);
  sim *s = sim_new(cfg, nranks, err, sizeof err);
  if (!s) return -1;
  FILE *fc = NULL, *fj = NULL;
  if (counted) sim_trace_count(s, 1, 1);
  else {
    fc = tmpfile();
    fj = tmpfile();
    if (!fc || !fj) return -1;
    sim_trace(s, fc, fj);
  }
  mp_proc procs[RANDPROG_RANKS];
  for (int r = 0; r < nranks; r++) procs[r] = (mp_proc){randprog_main, &p};
  int rc = sim_run(s, procs, err, sizeof err);
  if (counted) {
    unsigned long long a, b;
    sim_trace_size(s, &a, &b);
    *csv = (long)a, *json = (long)b;
  } else {
    fseek(fc, 0, SEEK_END);
    fseek(fj, 0, SEEK_END);
    *csv = ftell(fc), *json = ftell(fj);
    fclose(fc);
    fclose(fj);
  }
  sim_free(s);
  return rc;
}

/* The bytes of a stream written so far. */
static char *slurp(FILE *f, long *n) {
  fflush(f);
  *n = ftell(f);
  char *b = malloc((size_t)*n + 1);
  rewind(f);
  if (fread(b, 1, (size_t)*n, f) != (size_t)*n) *n = -1;
  return b;
}

/* A limited trace (sim_trace_limit): within its limit, the bytes of the
 * unlimited trace; past it, a prefix of them no longer than the limit, the
 * whole trace's size counted, and trace_over set -- for limits around the
 * trace's size, CSV and JSON together. */
static void test_limited(uint64_t seed, int topology) {
  sim_config cfg;
  sim_config_init(&cfg);
  cfg.warn = NULL;
  char err[512];
  if (topology) topo_parse("ring", &cfg.topo, err, sizeof err);
  int nranks = 6;
  cfg.procs = 6;
  randprog p;
  randprog_make(&p, seed, nranks);
  mp_proc procs[RANDPROG_RANKS];
  for (int r = 0; r < nranks; r++) procs[r] = (mp_proc){randprog_main, &p};
  char *full[2] = {NULL, NULL};
  long nfull[2] = {0, 0};
  for (int pass = 0; pass < 8; pass++) {
    /* pass 0: unlimited; then limits 0, a third, all but one byte, exactly, one more, huge */
    long total = nfull[0] + nfull[1];
    unsigned long long lim = pass == 1 ? 0 : pass == 2 ? (unsigned long long)total / 3
                             : pass == 3 ? (unsigned long long)total - 1 : pass == 4 ? (unsigned long long)total
                             : pass == 5 ? (unsigned long long)total + 1 : pass == 6 ? (unsigned long long)nfull[0]
                                                                         : 1ULL << 40;
    sim *s = sim_new(&cfg, nranks, err, sizeof err);
    FILE *fc = tmpfile(), *fj = tmpfile();
    if (!s || !fc || !fj) abort();
    sim_trace(s, fc, fj);
    if (pass > 0) sim_trace_limit(s, lim);
    CHECK(sim_run(s, procs, err, sizeof err) == 0, "limited seed %llu: %s", (unsigned long long)seed, err);
    unsigned long long cc, cj;
    sim_trace_size(s, &cc, &cj);
    int over = sim_trace_over(s);
    long n[2];
    char *got[2] = {slurp(fc, &n[0]), slurp(fj, &n[1])};
    fclose(fc);
    fclose(fj);
    if (pass == 0) {
      full[0] = got[0], full[1] = got[1], nfull[0] = n[0], nfull[1] = n[1];
      CHECK(!over && cc == 0 && cj == 0, "an unlimited trace is not over and counts nothing");
    } else {
      int within = (unsigned long long)total <= lim;
      CHECK(over == !within, "seed %llu limit %llu of %ld: over %d", (unsigned long long)seed, lim, total, over);
      CHECK(cc == (unsigned long long)nfull[0] && cj == (unsigned long long)nfull[1],
            "seed %llu limit %llu: counted %llu + %llu, the trace has %ld + %ld", (unsigned long long)seed, lim, cc,
            cj, nfull[0], nfull[1]);
      int prefix = n[0] <= nfull[0] && n[1] <= nfull[1] && memcmp(got[0], full[0], (size_t)n[0]) == 0 &&
                   memcmp(got[1], full[1], (size_t)n[1]) == 0;
      CHECK(prefix, "seed %llu limit %llu: what was written is not the trace's beginning", (unsigned long long)seed, lim);
      if (within) CHECK(n[0] == nfull[0] && n[1] == nfull[1], "seed %llu limit %llu: within the limit, not all written",
                        (unsigned long long)seed, lim);
      else CHECK((unsigned long long)(n[0] + n[1]) <= lim, "seed %llu limit %llu: %ld bytes written", (unsigned long long)seed,
                 lim, n[0] + n[1]);
      free(got[0]);
      free(got[1]);
    }
    sim_free(s);
  }
  free(full[0]);
  free(full[1]);
}

int main(void) {
  for (uint64_t seed = 1; seed <= 4; seed++) test_limited(seed, seed % 2);
  int cases = 0, bad = 0;
  static const double scale[] = {1e-6, 1, 3.7e5, 123456.789};
  for (int net = 0; net < 3; net++)
    for (int k = 0; k < 4; k++)
      for (uint64_t seed = 1; seed <= 6; seed++) {
        sim_config cfg;
        sim_config_init(&cfg);
        cfg.warn = NULL;
        cfg.net = (sim_net)net;
        cfg.c *= scale[k], cfg.m *= scale[k], cfg.L *= scale[k];
        cfg.o = net == 2 ? cfg.m / 7 : 0;
        cfg.g = net == 2 ? cfg.m / 3 : 0;
        int nranks = 2 + (int)(seed * 5 % (RANDPROG_RANKS - 1));
        cfg.procs = seed % 2 ? nranks : (nranks + 1) / 2;   /* ranks share processors */
        long wc, wj, cc, cj;
        int r1 = run(&cfg, nranks, seed * 31 + (uint64_t)k, 0, &wc, &wj);
        int r2 = run(&cfg, nranks, seed * 31 + (uint64_t)k, 1, &cc, &cj);
        cases++;
        CHECK(r1 == 0 && r2 == 0, "net %d scale %g seed %llu: the runs failed", net, scale[k],
              (unsigned long long)seed);
        if (wc != cc || wj != cj) {
          if (bad++ < 5)
            CHECK(0, "net %d scale %g seed %llu: counted CSV %ld, JSON %ld; written %ld, %ld", net, scale[k],
                  (unsigned long long)seed, cc, cj, wc, wj);
        }
      }
  /* Topologies: link tracks and link rows too. */
  static const char *const topos[] = {"ring", "mesh:3x4", "hypercube", "butterfly", "full", "line"};
  for (size_t t = 0; t < sizeof topos / sizeof *topos; t++)
    for (uint64_t seed = 1; seed <= 3; seed++) {
      sim_config cfg;
      sim_config_init(&cfg);
      cfg.warn = NULL;
      char err[256];
      int ok = topo_parse(topos[t], &cfg.topo, err, sizeof err) == 0;
      CHECK(ok, "topology %s: %s", topos[t], err);
      if (!ok) continue;
      cfg.store_forward = (int)(seed % 2);
      cfg.hop_latency = cfg.m / 10;
      int nranks = 12;
      cfg.procs = seed == 3 ? 8 : 12;
      if (strcmp(topos[t], "hypercube") == 0 || strcmp(topos[t], "butterfly") == 0) cfg.procs = 8, nranks = 8;
      long wc, wj, cc, cj;
      int r1 = run(&cfg, nranks, seed * 7 + t, 0, &wc, &wj);
      int r2 = run(&cfg, nranks, seed * 7 + t, 1, &cc, &cj);
      cases++;
      CHECK(r1 == 0 && r2 == 0, "%s seed %llu: the runs failed", topos[t], (unsigned long long)seed);
      if (wc != cc || wj != cj) {
        if (bad++ < 8)
          CHECK(0, "%s seed %llu: counted CSV %ld, JSON %ld; written %ld, %ld", topos[t],
                (unsigned long long)seed, cc, cj, wc, wj);
      }
    }
  CHECK(bad == 0, "%d of %d runs counted a size other than the one written", bad, cases);

  char buf[40];
  trace_fmt_bytes(512, buf, sizeof buf);
  CHECK(strcmp(buf, "512 bytes") == 0, "%s", buf);
  trace_fmt_bytes(4312345678ULL, buf, sizeof buf);
  CHECK(strcmp(buf, "4.3 GB") == 0, "%s", buf);
  trace_fmt_bytes(183000000ULL, buf, sizeof buf);
  CHECK(strcmp(buf, "183 MB") == 0, "%s", buf);
  return check_done("test_trace");
}
