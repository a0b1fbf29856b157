/* topomachine.c -- the machines of the topology tests and their closed
 * forms (topomachine.h). */
#include "tests/topomachine.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "tests/simrun.h"
#include "util/xmem.h"

const machine machines[] = {
    {TOPO_BUS, 0, 0, 5},       {TOPO_FULL, 0, 0, 5},      {TOPO_LINE, 0, 0, 7},
    {TOPO_RING, 0, 0, 7},      {TOPO_RING, 0, 0, 8},      {TOPO_MESH, 4, 3, 12},
    {TOPO_TORUS, 4, 3, 12},    {TOPO_TORUS, 5, 4, 20},    {TOPO_HYPERCUBE, 3, 0, 8},
    {TOPO_BUTTERFLY, 2, 0, 8}, {TOPO_BUTTERFLY, 3, 0, 9}, {TOPO_MESH, 0, 0, 7},
    {TOPO_LINE, 9, 0, 4},      {TOPO_HYPERCUBE, 0, 0, 5}, {TOPO_TORUS, 2, 2, 4},
    {TOPO_BUTTERFLY, 4, 0, 13},
};
_Static_assert(sizeof machines / sizeof *machines == NMACHINES, "NMACHINES counts machines[]");

dims tm_dims(const machine *mc) {
  dims x = {0, 0, 1, 0, 0, 0};
  int P = mc->procs;
  switch (mc->kind) {
  case TOPO_MESH:
  case TOPO_TORUS:
    if (mc->a) {
      x.w = mc->a, x.h = mc->b;
    } else {
      x.w = (int)ceil(sqrt((double)P));
      x.h = (P + x.w - 1) / x.w;
    }
    x.N = x.w * x.h;
    break;
  case TOPO_HYPERCUBE:
    x.d = mc->a ? mc->a : (int)ceil(log2((double)P));
    x.N = 1 << x.d;
    break;
  case TOPO_BUTTERFLY:
    x.k = mc->a ? mc->a : 2;
    for (x.N = 1; x.N < P; x.N *= x.k) x.n++;
    break;
  default:
    x.N = x.w = mc->a ? mc->a : P;
  }
  return x;
}

static int dist1(int n, int a, int b, int wrap) {
  int d = abs(a - b);
  return wrap && n - d < d ? n - d : d;
}

topo *tm_topo(const machine *mc, char *err, size_t errlen) {
  topo_spec sp = {mc->kind, mc->a, mc->b};
  return topo_new(&sp, mc->procs, err, errlen);
}

int tm_popcount(unsigned v) {
  int c = 0;
  for (; v; v &= v - 1) c++;
  return c;
}

/* h(s, d): the table of topo.h. */
int tm_hops(const machine *mc, const dims *x, int s, int d) {
  if (s == d) return 0;
  switch (mc->kind) {
  case TOPO_BUS: return 1;
  case TOPO_FULL: return 2;
  case TOPO_LINE: return abs(s - d);
  case TOPO_RING: return dist1(x->N, s, d, 1);
  case TOPO_MESH:
  case TOPO_TORUS: {
    int wrap = mc->kind == TOPO_TORUS;
    return dist1(x->w, s % x->w, d % x->w, wrap) + dist1(x->h, s / x->w, d / x->w, wrap);
  }
  case TOPO_HYPERCUBE: return tm_popcount((unsigned)(s ^ d));
  case TOPO_BUTTERFLY: return x->n + 1;
  default: return -1;
  }
}

sim_config tm_netcfg(const machine *mc, int saf) {
  sim_config cfg;
  sim_config_init(&cfg);
  cfg.procs = mc->procs;
  cfg.topo = (topo_spec){mc->kind, mc->a, mc->b};
  cfg.m = M;
  cfg.hop_latency = R;
  cfg.per_byte = BETA;
  cfg.c = C;
  cfg.local = 0;
  cfg.store_forward = saf;
  cfg.stack = 64 * 1024;
  cfg.warn = NULL;
  return cfg;
}

/* One message on an idle machine, over h links. */
double tm_alone(const machine *mc, int saf, int h, size_t len) {
  double lb = (double)len * BETA;
  if (mc->kind == TOPO_BUS) return M + R + lb;
  return saf ? M + h * (R + lb) : M + h * R + lb;
}

void tm_perm_main(mp *self, void *ud) {
  perm *p = ud;
  int me = mp_rank(self);
  char buf[64] = {0};
  if (p->dst[me] >= 0) p->bad |= mp_send(self, p->dst[me], 0, buf, p->len) != MP_OK;
  for (int k = 0; k < p->expect[me]; k++) {
    mp_status st;
    p->bad |= mp_recv(self, MP_ANY, 0, buf, sizeof buf, &st) != MP_OK;
    p->at[st.source] = mp_time(self);
  }
}

sim *tm_run_perm(const machine *mc, int saf, perm *p, int n, char *err, size_t errlen) {
  sim_config cfg = tm_netcfg(mc, saf);
  memset(p->expect, 0, sizeof p->expect);
  for (int i = 0; i < n; i++) {
    if (p->dst[i] == i) p->dst[i] = -1;
    if (p->dst[i] >= 0) p->expect[p->dst[i]]++;
    p->at[i] = -1;
  }
  p->bad = 0;
  int rc;
  sim *s = simrun(&cfg, n, tm_perm_main, p, &rc, err, errlen);
  CHECK(rc == 0 && !p->bad, "permutation run: %s", err);
  return s;
}
