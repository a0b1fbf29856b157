/* micro.c -- micro-benchmarks of the threads backend's messages and of
 * cores working at once (micro.h). */
#include "prog/bench/micro.h"

#include "prog/bench/blocks.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "algo/split.h"
#include "mp/threads.h"
#include "algo/tiling.h"
#include "util/wallclock.h"
#include "util/xmem.h"

static inline void relax(void) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  __builtin_ia32_pause();
#elif defined(__GNUC__) && defined(__aarch64__)
  __asm__ __volatile__("yield");
#endif
}

/* ==== message programs ==================================================== */

enum { PINGPONG, EXCHANGE, STREAM, SLEEPER };
/* The exchange runs on min(4, cores) ranks (at least 2): each rank a core,
 * as the slaves of a run that fits the machine; four threads on a two-core
 * machine measured their partners' descheduling as a receive's cost (4 us
 * against 0.2 us). */
enum { EXCHANGE_RANKS = 4 };

static int exchange_ranks(void) {
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n >= EXCHANGE_RANKS ? EXCHANGE_RANKS : n >= 2 ? (int)n : 2;
}
#define EXCHANGE_DELAY 5e-6   /* between the sends and the receives */

typedef struct {
  int kind, rounds;
  size_t len;
  double idle;              /* SLEEPER: the sender's idle time before a send */
  double t_send[EXCHANGE_RANKS], t_recv[EXCHANGE_RANKS];   /* seconds inside, per call */
  double sent_at;           /* SLEEPER: when rank 0's send began */
  double one_way;           /* SLEEPER: from there to rank 1's recv returning, per round */
  int bad;
} prog;

static void pause_for(double s) {
  double until = wallclock() + s;
  while (wallclock() < until)
    for (int i = 0; i < 16; i++) relax();
}

static void prog_main(mp *self, void *ud) {
  prog *p = ud;
  int me = mp_rank(self), n = mp_size(self);
  unsigned char *buf = xcalloc(p->len ? p->len : 1, 1);
  double in_send = 0, in_recv = 0;
  for (int i = 0; i < p->rounds; i++) {
    if (p->kind == EXCHANGE) {
      int left = (me + n - 1) % n, right = (me + 1) % n;
      double t0 = wallclock();
      p->bad += mp_send(self, left, 0, buf, p->len) != MP_OK;
      p->bad += mp_send(self, right, 0, buf, p->len) != MP_OK;
      double t1 = wallclock();
      pause_for(EXCHANGE_DELAY);
      double t2 = wallclock();
      p->bad += mp_recv(self, left, 0, buf, p->len, NULL) != MP_OK;
      p->bad += mp_recv(self, right, 0, buf, p->len, NULL) != MP_OK;
      in_send += t1 - t0, in_recv += wallclock() - t2;
    } else if (p->kind == STREAM) {
      p->bad += (me == 0 ? mp_send(self, 1, 0, buf, p->len) : mp_recv(self, 0, 0, buf, p->len, NULL)) != MP_OK;
    } else {   /* PINGPONG, SLEEPER */
      buf[0] = (unsigned char)i;
      if (me == 0) {
        if (p->idle > 0) pause_for(p->idle);
        double t0 = wallclock();
        p->sent_at = t0;   /* read by rank 1 after the message: ordered by the mailbox's lock */
        p->bad += mp_send(self, 1, 0, buf, p->len) != MP_OK;
        in_send += wallclock() - t0;
        p->bad += mp_recv(self, 1, 0, buf, p->len, NULL) != MP_OK || buf[0] != (unsigned char)i;
      } else {
        p->bad += mp_recv(self, 0, 0, buf, p->len, NULL) != MP_OK || buf[0] != (unsigned char)i;
        p->one_way += wallclock() - p->sent_at;
        p->bad += mp_send(self, 0, 0, buf, p->len) != MP_OK;
      }
    }
  }
  /* Per call: two sends and two receives a round in the exchange. */
  int calls = p->kind == EXCHANGE ? 2 * p->rounds : p->rounds;
  p->t_send[me] = in_send / calls;
  p->t_recv[me] = in_recv / calls;
  free(buf);
}

/* One run of the program on `ranks` ranks; its wall time, or < 0. */
static double run_prog(prog *p, int ranks, long spin_ns, char *err, size_t errlen) {
  mpt_config cfg;
  mpt_config_init(&cfg);
  cfg.warn = NULL;
  if (spin_ns >= 0) cfg.spin_ns = spin_ns;
  mpt *t = mpt_new(&cfg, ranks, err, errlen);
  if (!t) return -1;
  p->bad = 0;
  p->one_way = 0;
  mp_proc procs[EXCHANGE_RANKS];
  for (int i = 0; i < ranks; i++) procs[i] = (mp_proc){prog_main, p};
  int rc = mpt_run(t, procs, err, errlen);
  double w = mpt_stats_get(t)->wall_s;
  mpt_free(t);
  if (rc != 0 || p->bad) {
    if (rc == 0) snprintf(err, errlen, "a message benchmark delivered wrong messages");
    return -1;
  }
  return w;
}

static void keep_min(double *best, double v) {
  if (*best < 0 || v < *best) *best = v;
}

static double mean(const double *v, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += v[i];
  return s / n;
}

int micro_messages(int rounds, int repeat, micro_msgs *o, char *err, size_t errlen) {
  memset(o, 0, sizeof *o);
  o->small = 20;   /* a boundary message of one cost: t, n0, n1 and a double */
  o->big = 65536;
  o->idle = 1e-3;  /* long enough for an idle core to doze */
  int big_rounds = rounds / 20 + 10, x_rounds = rounds / 4 + 10, sleep_rounds = rounds / 1000 + 50;
  double v[9];
  int xr = exchange_ranks();
  o->exchange_ranks = xr;
  for (int i = 0; i < 9; i++) v[i] = -1;
  for (int r = 0; r < repeat; r++) {   /* in rounds: a slow spell touches every figure alike */
    prog p;
    double w;
    memset(&p, 0, sizeof p);
    p.kind = PINGPONG, p.rounds = rounds, p.len = o->small;
    if ((w = run_prog(&p, 2, -1, err, errlen)) < 0) return -1;
    keep_min(&v[0], w / (2.0 * rounds));
    p.rounds = big_rounds, p.len = o->big;
    if ((w = run_prog(&p, 2, -1, err, errlen)) < 0) return -1;
    keep_min(&v[1], w / (2.0 * big_rounds));
    p.kind = EXCHANGE, p.rounds = x_rounds, p.len = o->small;
    if (run_prog(&p, xr, -1, err, errlen) < 0) return -1;
    keep_min(&v[2], mean(p.t_send, xr));
    keep_min(&v[3], mean(p.t_recv, xr));
    p.rounds = big_rounds, p.len = o->big;
    if (run_prog(&p, xr, -1, err, errlen) < 0) return -1;
    keep_min(&v[4], mean(p.t_send, xr));
    keep_min(&v[5], mean(p.t_recv, xr));
    p.kind = STREAM, p.rounds = rounds, p.len = o->small;
    if ((w = run_prog(&p, 2, -1, err, errlen)) < 0) return -1;
    keep_min(&v[6], w / rounds);
    p.kind = SLEEPER, p.rounds = sleep_rounds, p.idle = o->idle;
    if (run_prog(&p, 2, 0, err, errlen) < 0) return -1;
    keep_min(&v[7], p.one_way / sleep_rounds);
    keep_min(&v[8], p.t_send[0]);
  }
  o->pp_small = v[0], o->pp_big = v[1];
  o->os_small = v[2], o->or_small = v[3], o->os_big = v[4], o->or_big = v[5];
  o->stream = v[6], o->pp_sleep = v[7], o->send_sleep = v[8];
  return 0;
}

static double pos(double x) { return x > 0 ? x : 0; }

void micro_derive(const micro_msgs *m, micro_model *d) {
  double db = (double)(m->big - m->small);
  d->o_send_byte = pos((m->os_big - m->os_small) / db);
  d->o_send = pos(m->os_small - (double)m->small * d->o_send_byte);
  d->o_recv_byte = pos((m->or_big - m->or_small) / db);
  d->o_recv = pos(m->or_small - (double)m->small * d->o_recv_byte);
  d->L = pos(m->pp_small - m->os_small - m->or_small);
  d->G = pos((m->pp_big - m->os_big - m->or_big - d->L) / (double)(m->big - 1));
  double busy = m->os_small > m->or_small ? m->os_small : m->or_small;
  d->g = m->stream > busy ? m->stream : 0;
  d->o_wake = pos(m->send_sleep - m->os_small);
  d->wake = pos(m->pp_sleep - m->send_sleep - d->L - m->or_small);
}

/* ==== a backtracking step ================================================= */

double micro_backtrack(const vec2 *A, const vec2 *B, int n, int repeat) {
  tiling t;
  tiling_solve(A, n, 0, B, n, 5, COST_AREA, 0, &t);
  weights *w = t.transposed ? weights_new(B, n, 5, A, n, 0, COST_AREA, 0) : weights_new(A, n, 0, B, n, 5, COST_AREA, 0);
  int T = t.m + t.n, s = t.start;
  /* Bit words per diagonal, as a slave keeps them: its run of a diagonal
   * (a quarter of the n columns, as one of four slaves), the path's node
   * somewhere in it; bit set = vertical in-edge.  The owner of each node
   * is checked as the paper's slave does (split_owner: the even split of
   * the diagonal [0, n] among four). */
  int W = n / 256 > 1 ? n / 256 : 1;
  int64_t *woff = xmallocarray((size_t)T + 1, sizeof *woff);
  int *c0 = xmallocarray((size_t)T + 1, sizeof *c0), *pcol = xmallocarray((size_t)T + 1, sizeof *pcol);
  uint64_t *bits = xcalloc((size_t)(T + 1) * (size_t)W, sizeof *bits);
  double *pw = xmallocarray((size_t)T + 1, sizeof *pw);
  for (int u = 1; u <= T; u++) {
    int back = (u * 37) % (64 * W);
    woff[u] = (int64_t)u * W;
    c0[u] = t.col[u] - (back < t.col[u] ? back : t.col[u]);
    int i = t.col[u] - c0[u];
    if (t.col[u - 1] == t.col[u]) bits[woff[u] + (i >> 6)] |= 1ull << (i & 63);
  }
  int walks = 300000 / T + 1;
  double best = -1, sink = 0;
  for (int r = 0; r < repeat; r++) {
    double t0 = wallclock();
    for (int k = 0; k < walks; k++) {
      int c = t.n, owners = 0;
      for (int u = T; u >= 1; u--) {
        owners += split_owner(0, t.n, 4, c);
        int i = c - c0[u];
        int vert = (int)((bits[woff[u] + (i >> 6)] >> (i & 63)) & 1);
        pcol[T - u] = c;
        pw[T - u] = weights_in(w, s + u, c, vert);
        if (!vert) c--;
      }
      sink += pw[T / 2] + pcol[T - 1] + owners;
    }
    double x = (wallclock() - t0) / ((double)walks * T);
    if (best < 0 || x < best) best = x;
  }
  if (sink == -1) best = -1;   /* keeps the walk */
  free(woff), free(c0), free(pcol), free(bits), free(pw);
  weights_free(w);
  tiling_free(&t);
  return best;
}

/* ==== cores at work together ============================================== */

typedef struct {
  const vec2 *A, *B;
  int n, table, solve;
  atomic_int *ready, *done;
  int k;
  double wall;
} worker;

static void *work(void *ud) {
  worker *w = ud;
  atomic_fetch_add(w->ready, 1);
  while (atomic_load(w->ready) < w->k) relax();   /* start together */
  if (w->solve) {
    tiling t;
    double t0 = wallclock();
    tiling_solve(w->A, w->n, 0, w->B, w->n, 5, COST_AREA, w->table, &t);
    w->wall = wallclock() - t0;
    tiling_free(&t);
    atomic_fetch_add(w->done, 1);
  } else {
    while (!atomic_load(w->done)) relax();   /* spin beside the solver until it is done */
  }
  return NULL;
}

double micro_together(const vec2 *A, const vec2 *B, int n, int table, int k, int spinners, int repeat) {
  double best = -1;
  worker *w = xcalloc((size_t)k, sizeof *w);
  pthread_t *th = xcalloc((size_t)k, sizeof *th);
  for (int r = 0; r < repeat; r++) {
    atomic_int ready, done;
    atomic_init(&ready, 0);
    atomic_init(&done, 0);
    int made = 0;
    for (; made < k; made++) {
      w[made] = (worker){A, B, n, table, !spinners || made == 0, &ready, &done, k, 0};
      if (pthread_create(&th[made], NULL, work, &w[made]) != 0) break;
    }
    if (made < k) {   /* let the started ones go: count the missing as ready, the solvers as done */
      atomic_fetch_add(&ready, k - made);
      atomic_store(&done, k);
    }
    for (int i = 0; i < made; i++) pthread_join(th[i], NULL);
    if (made < k) {
      best = -1;
      break;
    }
    double sum = 0;
    int solvers = spinners ? 1 : k;
    for (int i = 0; i < solvers; i++) sum += w[i].wall;
    keep_min(&best, sum / solvers);
  }
  free(w);
  free(th);
  return best;
}

/* ==== a basic block (tilesim-mpirun --compute blocks) ===================== */

/* The counter the instrumented loop (blocks.c) calls at every block. */
static unsigned long long counted;
void __sanitizer_cov_trace_pc(void);
void __sanitizer_cov_trace_pc(void) { counted++; }

double micro_block(int repeat, unsigned long long *blocks) {
  double best = 1e300;
  volatile double pi = 0;
  for (int k = 0; k < repeat; k++) {
    counted = 0;
    double t0 = wallclock();
    pi = blocks_cpi(2000000);
    double t = wallclock() - t0;
    if (counted > 0 && t / (double)counted < best) best = t / (double)counted;
    *blocks = counted;
  }
  (void)pi;
  return best < 1e300 ? best : 0;
}
