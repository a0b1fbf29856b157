/* test_master.c -- the master's bookkeeping at its own price (--master-c):
 * on the simulator, the master's compute time is its bookkeeping units times
 * --master-c, exactly (binary fractions: exact sums), for every allocation,
 * the blocked wavefront and the dynamic schedule, P = 1 (master and slave on
 * one processor) to 9; the slaves' node units and their compute, units
 * times c, are where they were when the bookkeeping cost a node; the default
 * is c/100; a price that c = 0 cannot express is refused.  A slave's weight
 * table (--table-c) and backtracking (--back-c) at their prices, exactly,
 * and nothing when they are 0 (the default, the paper's figures). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/gen.h"
#include "algo/par_slave.h"
#include "util/rng.h"
#include "tests/parmachine.h"
#include "util/xmem.h"

enum { MAXR = 16 };

typedef struct {
  double compute[MAXR];   /* the simulator's per-rank compute seconds */
  double units[MAXR];     /* and units */
  uint64_t slave_units[MAXR], slave_nodes[MAXR];   /* the slaves' own counts */
  par_counts master;      /* the master's own counts */
  double time;
  int nr;
} outcome;

/* One pair on P processors under options given as a user gives them (argv
 * pairs, NULL-terminated), with c = 2^-10 s and m = 2^-9 s; the master's and
 * the slaves' counters and the simulator's per-rank statistics. */
static int run_one(const vec2 *P, int np, const vec2 *Q, int nq, int procs, const char *const *opts,
                   outcome *o, char *err, size_t errlen) {
  par_machine rc;
  par_machine_init(&rc);
  rc.mc.backend = MACHINE_SIM;
  rc.mc.sim.warn = NULL;
  const char *base[] = {"--c", "0.0009765625", "--m", "0.001953125", NULL};
  for (int i = 0; base[i]; i += 2)
    if (par_machine_option(&rc, base[i], base[i + 1], err, errlen) != 1) return -1;
  for (int i = 0; opts[i]; i += 2)
    if (par_machine_option(&rc, opts[i], opts[i + 1], err, errlen) != 1) return -1;
  par_options opt;
  if (par_config_prices(&rc.pc, rc.mc.sim.c, &opt, err, errlen) != 0) return -1;
  int nr = par_ranks(procs), place[MAXR];
  for (int r = 0; r < nr; r++) place[r] = procs == 1 ? 0 : r;
  sim_config cfg = rc.mc.sim;
  cfg.procs = procs;
  cfg.place = place;
  sim *s = sim_new(&cfg, nr, err, errlen);
  if (!s) return -1;
  par_pair pr;
  memset(&pr, 0, sizeof pr);
  pr.P = P, pr.np = np, pr.zp = 0, pr.Q = Q, pr.nq = nq, pr.zq = 2;
  par_master_arg marg;
  memset(&marg, 0, sizeof marg);
  marg.npairs = 1, marg.pairs = &pr, marg.kind = COST_AREA, marg.opt = opt;
  par_slave_arg sarg[MAXR];
  memset(sarg, 0, sizeof sarg);
  mp_proc pv[MAXR];
  pv[0] = (mp_proc){par_master, &marg};
  for (int r = 1; r < nr; r++) pv[r] = (mp_proc){par_slave, &sarg[r]};
  int res = sim_run(s, pv, err, errlen);
  if (res == 0 && marg.failed) snprintf(err, errlen, "%s", marg.err), res = -1;
  memset(o, 0, sizeof *o);
  o->nr = nr;
  for (int r = 0; r < nr; r++) {
    o->compute[r] = sim_rank(s, r)->compute;
    o->units[r] = sim_rank(s, r)->units;
    o->slave_units[r] = sarg[r].total.units;
    o->slave_nodes[r] = sarg[r].total.nodes;
  }
  o->master = pr.master;
  o->time = pr.time;
  if (res == 0) tiling_free(&pr.t);
  sim_free(s);
  return res;
}

static void check_prices(rng *g) {
  int np = 90, nq = 107;
  vec2 *P = xmallocarray((size_t)np, sizeof *P), *Q = xmallocarray((size_t)nq, sizeof *Q);
  gen_star(g, P, np, 0, 0, 10, 0.3);
  gen_star(g, Q, nq, 1, 0, 9, 0.3);
  static const char *const variants[][6] = {
      {"--alloc", "half", NULL},
      {"--alloc", "size", NULL},
      {"--alloc", "fit", "--min-diag", "20", NULL},
      {"--alloc", "size", "--block", "4", NULL},
      {"--alloc", "size", "--schedule", "dynamic", NULL},
  };
  const double c = 0x1p-10, price = 0x1p-17;   /* the master's: 2^-7 of a node */
  for (size_t v = 0; v < sizeof variants / sizeof variants[0]; v++)
    for (int procs = 1; procs <= 9; procs += 4) {
      const char *const *opt = variants[v];
      int dynamic = opt[2] && strcmp(opt[2], "--schedule") == 0;
      const char *cheap[12], *node[12], *deflt[12], *zero[12];
      int k = 0;
      for (; opt[k]; k++) cheap[k] = node[k] = deflt[k] = zero[k] = opt[k];
      cheap[k] = "--master-c", cheap[k + 1] = "7.62939453125e-06", cheap[k + 2] = NULL;   /* 2^-17 */
      node[k] = "--master-c", node[k + 1] = "0.0009765625", node[k + 2] = NULL;           /* c */
      zero[k] = "--master-c", zero[k + 1] = "0", zero[k + 2] = NULL;
      deflt[k] = NULL;
      char err[300];
      outcome a, b, d, z;
      int ok = run_one(P, np, Q, nq, procs, cheap, &a, err, sizeof err) == 0;
      CHECK(ok, "%s %s P=%d: %s", opt[1], opt[2] ? opt[3] : "", procs, err);
      ok = ok && run_one(P, np, Q, nq, procs, node, &b, err, sizeof err) == 0;
      ok = ok && run_one(P, np, Q, nq, procs, deflt, &d, err, sizeof err) == 0;
      ok = ok && run_one(P, np, Q, nq, procs, zero, &z, err, sizeof err) == 0;
      CHECK(ok, "%s P=%d: %s", opt[1], procs, err);
      if (!ok) continue;
      /* The master's compute is its bookkeeping units times the price. */
      CHECK(a.master.book > 0 && a.master.units == 0 && a.master.nodes == 0,
            "%s P=%d: master book %llu units %llu", opt[1], procs, (unsigned long long)a.master.book,
            (unsigned long long)a.master.units);
      CHECK(a.compute[0] == price * (double)a.master.book,
            "%s P=%d: master compute %.17g s, %llu units x 2^-17 s = %.17g s", opt[1], procs, a.compute[0],
            (unsigned long long)a.master.book, price * (double)a.master.book);
      CHECK(b.compute[0] == c * (double)b.master.book, "%s P=%d: at the node price %.17g s, %llu units x c",
            opt[1], procs, b.compute[0], (unsigned long long)b.master.book);
      CHECK(z.compute[0] == 0 && z.master.book > 0, "%s P=%d: --master-c 0 still charged %.17g s", opt[1],
            procs, z.compute[0]);
      CHECK(fabs(d.compute[0] - c / 100 * (double)d.master.book) <= 1e-12 * d.compute[0] &&
                d.compute[0] > 0,
            "%s P=%d: default %.17g s, c/100 x %llu units = %.17g s", opt[1], procs, d.compute[0],
            (unsigned long long)d.master.book, c / 100 * (double)d.master.book);
      /* The slaves: units times c, and (a static schedule: no decision rests
       * on the clock) the same units and compute at either price. */
      for (int r = 1; r < a.nr; r++) {
        CHECK(a.compute[r] == c * (double)a.slave_units[r] && a.units[r] == (double)a.slave_units[r],
              "%s P=%d slave %d: compute %.17g s, c x %llu units", opt[1], procs, r, a.compute[r],
              (unsigned long long)a.slave_units[r]);
        if (!dynamic)
          CHECK(a.slave_units[r] == b.slave_units[r] && a.slave_nodes[r] == b.slave_nodes[r] &&
                    a.compute[r] == b.compute[r],
                "%s P=%d slave %d: %llu units at one price, %llu at the other", opt[1], procs, r,
                (unsigned long long)a.slave_units[r], (unsigned long long)b.slave_units[r]);
      }
      if (!dynamic)
        CHECK(a.master.book == b.master.book && a.master.book == z.master.book,
              "%s P=%d: bookkeeping %llu, %llu, %llu units at three prices", opt[1], procs,
              (unsigned long long)a.master.book, (unsigned long long)b.master.book,
              (unsigned long long)z.master.book);
    }
  free(P);
  free(Q);
}

/* --table-c and --back-c (par_options.table, back): a slave that builds a
 * weight table pays m (n+1) cells times the price, exactly, once a pair (a
 * binary fraction: exact sums), and only where the slaves use tables (P <= 5
 * here, tiny contours); backtracking costs its steps times the price: the
 * slaves' extra compute is a whole number of paths of m + n steps, one (mu(0),
 * always a path task) when one slave does everything (P <= 2), more beyond.  The node units stay, and with
 * both prices 0 every time is the default run's bit for bit. */
static void check_slave_prices(rng *g) {
  int np = 90, nq = 107, m = np < nq ? np : nq, n = np < nq ? nq : np;
  vec2 *P = xmallocarray((size_t)np, sizeof *P), *Q = xmallocarray((size_t)nq, sizeof *Q);
  gen_star(g, P, np, 0, 0, 10, 0.3);
  gen_star(g, Q, nq, 1, 0, 9, 0.3);
  const double tc = 0x1p-12, bc = 0x1p-14;
  for (int v = 0; v < 3; v++)
    for (int procs = 1; procs <= 9; procs += 2) {
      const char *var[3][4] = {{"--alloc", "half", NULL}, {"--block", "4", NULL}, {"--alloc", "size", NULL}};
      const char *plain[8], *zero[8], *table[8], *back[8];
      int k = 0;
      for (; var[v][k]; k++) plain[k] = zero[k] = table[k] = back[k] = var[v][k];
      plain[k] = NULL;
      zero[k] = "--table-c", zero[k + 1] = "0", zero[k + 2] = "--back-c", zero[k + 3] = "0", zero[k + 4] = NULL;
      table[k] = "--table-c", table[k + 1] = "0.000244140625", table[k + 2] = NULL;   /* 2^-12 */
      back[k] = "--back-c", back[k + 1] = "6.103515625e-05", back[k + 2] = NULL;      /* 2^-14 */
      char err[300];
      outcome a, z, t, b;
      int ok = run_one(P, np, Q, nq, procs, plain, &a, err, sizeof err) == 0 &&
               run_one(P, np, Q, nq, procs, zero, &z, err, sizeof err) == 0 &&
               run_one(P, np, Q, nq, procs, table, &t, err, sizeof err) == 0 &&
               run_one(P, np, Q, nq, procs, back, &b, err, sizeof err) == 0;
      CHECK(ok, "%s P=%d: %s", var[v][1], procs, err);
      if (!ok) continue;
      CHECK(z.time == a.time, "%s P=%d: prices 0 changed the time: %.17g against %.17g", var[v][1], procs,
            z.time, a.time);
      int slaves = a.nr - 1, tables = par_slave_table(slaves) != 0;
      int paths = 0, whole = 1;
      for (int r = 1; r < a.nr; r++) {
        CHECK(z.compute[r] == a.compute[r] && t.slave_units[r] == a.slave_units[r] &&
                  b.slave_units[r] == a.slave_units[r],
              "%s P=%d slave %d: node units or times moved", var[v][1], procs, r);
        double want = a.compute[r] + (tables ? (double)m * (n + 1) * tc : 0);
        CHECK(t.compute[r] == want, "%s P=%d slave %d: with --table-c 2^-12 s %.17g s, want %.17g s (%s)",
              var[v][1], procs, r, t.compute[r], want, tables ? "a table" : "no table");
        double steps = (b.compute[r] - a.compute[r]) / bc;
        whole &= steps >= 0 && steps == floor(steps);
        paths += (int)steps;
      }
      CHECK(whole && paths % (m + n) == 0, "%s P=%d: backtracking charged %d steps, not whole paths of %d",
            var[v][1], procs, paths, m + n);
      CHECK(procs <= 2 ? paths == m + n : paths > m + n, "%s P=%d: %d backtracking steps charged", var[v][1],
            procs, paths);
    }
  free(P);
  free(Q);
}

/* c = 0 cannot price a bookkeeping unit above 0 in node units: refused with
 * a message, before any run; --master-c 0 there is fine. */
static void check_refusal(void) {
  par_machine rc;
  par_machine_init(&rc);
  rc.mc.sim.warn = NULL;
  char err[300] = "";
  par_options opt;
  CHECK(par_machine_option(&rc, "--c", "0", err, sizeof err) == 1 && par_machine_option(&rc, "--master-c", "1e-6", err, sizeof err) == 1,
        "options: %s", err);
  CHECK(par_config_prices(&rc.pc, rc.mc.sim.c, &opt, err, sizeof err) == -1 && strstr(err, "--master-c") && strstr(err, "c is 0"),
        "c = 0 with --master-c 1e-6: '%s'", err);
  vec2 P[3] = {{0, 0}, {1, 0}, {0, 1}}, Q[3] = {{0, 0}, {1, 0}, {0, 1}};
  par_pair pr;
  memset(&pr, 0, sizeof pr);
  pr.P = P, pr.np = 3, pr.Q = Q, pr.nq = 3, pr.zq = 1;
  err[0] = 0;
  CHECK(par_machine_run(&rc, &pr, 1, err, sizeof err) == -1 && strstr(err, "c is 0"), "par_machine_run: '%s'", err);
  CHECK(par_machine_option(&rc, "--master-c", "0", err, sizeof err) == 1 && par_config_prices(&rc.pc, rc.mc.sim.c, &opt, err, sizeof err) == 0 &&
            opt.book == 0,
        "c = 0 with --master-c 0: %s", err);
  CHECK(par_machine_option(&rc, "--master-c", "-1", err, sizeof err) == -1, "--master-c -1 accepted");
  CHECK(par_machine_option(&rc, "--back-c", "1e-9", err, sizeof err) == 1 && par_config_prices(&rc.pc, rc.mc.sim.c, &opt, err, sizeof err) == -1 &&
            strstr(err, "--back-c") && strstr(err, "c is 0"),
        "c = 0 with --back-c 1e-9: '%s'", err);
  CHECK(par_machine_option(&rc, "--back-c", "0", err, sizeof err) == 1 && par_machine_option(&rc, "--table-c", "2e-9", err, sizeof err) == 1 &&
            par_config_prices(&rc.pc, rc.mc.sim.c, &opt, err, sizeof err) == -1 && strstr(err, "--table-c"),
        "c = 0 with --table-c 2e-9: '%s'", err);
  CHECK(par_machine_option(&rc, "--table-c", "x", err, sizeof err) == -1, "--table-c x accepted");
  par_machine_init(&rc);
  CHECK(par_config_prices(&rc.pc, rc.mc.sim.c, &opt, err, sizeof err) == 0 && opt.book == PAR_MASTER_SHARE &&
            par_config_master_c(&rc.pc, rc.mc.sim.c) == PAR_MASTER_SHARE * rc.mc.sim.c,
        "default: book %g", opt.book);
}

int main(void) {
  rng g;
  rng_seed(&g, 88100);
  check_prices(&g);
  check_slave_prices(&g);
  check_refusal();
  return check_done("test_master");
}
