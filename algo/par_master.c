/* par_master.c -- the master: distribution, the divide and conquer over
 * groups of slaves (section 4's findallpaths), path assembly, restriction and
 * processor allocation (sections 5, 7.1). */
#include "algo/par_master.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "algo/band.h"
#include "algo/par_dynamic.h"
#include "algo/par_fit.h"
#include "util/xmem.h"

typedef par_group group;
typedef par_master_ctx master;

#define TRY(call) PAR_TRY(par_master_fail, M, call)

int par_master_fail(master *M, int rc, const char *what) {
  if (!M->arg->failed)
    snprintf(M->arg->err, sizeof M->arg->err, "master: %s: %s", what, mp_strerror(rc));
  M->arg->failed = 1;
  return -1;
}

/* The master's bookkeeping is integer passes over a path's columns, not node
 * evaluations: each unit costs opt.book node units (--master-c / c;
 * par_config.h says where the default comes from). */
int par_master_charge(master *M, uint64_t units) {
  M->own->book += units;
  return mp_compute(M->mp, (double)units * M->arg->opt.book);
}

gpath *par_master_path(master *M, int start) {
  if (M->npaths == M->pcap) {
    M->pcap = M->pcap ? 2 * M->pcap : 16;
    M->paths = xreallocarray(M->paths, (size_t)M->pcap, sizeof *M->paths);
  }
  gpath *p = xmalloc(sizeof *p);
  p->start = start;
  p->col = xmallocarray((size_t)M->T + 1, sizeof *p->col);
  p->cum = xmallocarray((size_t)M->T + 1, sizeof *p->cum);
  M->paths[M->npaths++] = p;
  return p;
}

/* REPORT and QUIT are bookkeeping, not the algorithm's: not counted. */
static int send_task(master *M, int what, int s, int bounded, int g0, int p, int to) {
  int kind = what == PAR_TASK_REPORT || what == PAR_TASK_QUIT ? -1 : PAR_CONTROL;
  par_buf_reset(&M->out);
  par_put_i32(&M->out, what);
  par_put_i32(&M->out, s);
  par_put_i32(&M->out, bounded);
  par_put_i32(&M->out, g0);
  par_put_i32(&M->out, p);
  return par_send(M->mp, M->own, kind, to, PAR_TAG_TASK, &M->out);
}

int par_master_send_bound(master *M, const gpath *P, int as, int to) {
  par_buf_reset(&M->out);
  par_put_i32(&M->out, P->start);
  par_put_i32(&M->out, as);
  par_put_i32s(&M->out, P->col, M->T + 1);
  par_put_f64s(&M->out, P->cum, M->T + 1);
  return par_send(M->mp, M->own, PAR_BOUNDS, to, PAR_TAG_BOUND, &M->out);
}

/* A new group's index: slaves g0.. (p of them), rows lo..hi between U and
 * L, the middle path its first task. */
static int group_new(master *M, int g0, int p, int lo, int hi, const gpath *U, const gpath *L) {
  if (M->ng == M->gcap) {
    M->gcap = M->gcap ? 2 * M->gcap : 16;
    M->g = xreallocarray(M->g, (size_t)M->gcap, sizeof *M->g);
  }
  int gi = M->ng++;
  group *G = &M->g[gi];
  memset(G, 0, sizeof *G);
  *G = (group){g0, p, lo, hi, U, L, lo < 0 ? 0 : tiling_mid(lo, hi), 1, NULL, NULL, 0, NULL, 0};
  return gi;
}

/* Start a group: PATH with two or more slaves, LOCAL with one. */
static int dispatch(master *M, int g0, int p, int lo, int hi, const gpath *U, const gpath *L) {
  int gi = group_new(M, g0, p, lo, hi, U, L);
  group *G = &M->g[gi];
  M->live++;
  for (int r = g0; r < g0 + p; r++) M->group_of[r] = gi;
  if (p == 1 && lo >= 0) return send_task(M, PAR_TASK_LOCAL, 0, 1, g0, 1, g0);
  G->col = xmallocarray((size_t)M->T + 1, sizeof *G->col);
  G->w = xmallocarray((size_t)M->T + 1, sizeof *G->w);
  for (int r = g0; r < g0 + p; r++) TRY(send_task(M, PAR_TASK_PATH, G->mid, lo >= 0, g0, p, r));
  return 0;
}

int par_master_group(master *M, const int *ranks, int p, int lo, int hi, const gpath *U,
                     const gpath *L, int local) {
  int gi = group_new(M, ranks[0], p, lo, hi, U, L);
  group *G = &M->g[gi];
  G->ranks = xmallocarray((size_t)p, sizeof *G->ranks);
  memcpy(G->ranks, ranks, (size_t)p * sizeof *ranks);
  M->live++;
  for (int i = 0; i < p; i++) M->group_of[ranks[i]] = gi;
  if (!local) {
    G->col = xmallocarray((size_t)M->T + 1, sizeof *G->col);
    G->w = xmallocarray((size_t)M->T + 1, sizeof *G->w);
  }
  return gi;
}

/* A path against the best so far; a better one is copied (bookkeeping: a
 * pass over its columns). */
static int consider(master *M, int start, double quanta, const int *col) {
  tiling_best *b = &M->best;
  if (quanta < b->quanta || (quanta == b->quanta && start < b->start)) {
    b->quanta = quanta;
    b->start = start;
    memcpy(b->col, col, (size_t)(M->T + 1) * sizeof *col);
    TRY(par_master_charge(M, (uint64_t)M->T + 1));
  }
  return 0;
}

/* A group's path is complete: end the backtrack, restrict, split (section 4). */
static int finished(master *M, int gi) {
  group G = M->g[gi];
  int T = M->T;
  M->g[gi].live = 0;
  M->live--;
  gpath *P = par_master_path(M, G.mid);
  P->col[0] = G.col[0];
  P->cum[0] = 0;
  for (int t = 1; t <= T; t++) P->col[t] = G.col[t], P->cum[t] = P->cum[t - 1] + G.w[t];
  free(M->g[gi].col);
  free(M->g[gi].w);
  TRY(par_master_charge(M, (uint64_t)T + 1));
  par_buf_reset(&M->out);
  par_put_i32(&M->out, -1);
  for (int i = 0; i < G.p; i++) {
    int r = par_master_member(&G, i);
    M->group_of[r] = -1;
    TRY(par_send(M->mp, M->own, PAR_CONTROL, r, PAR_TAG_BACK, &M->out));
  }
  free(M->g[gi].ranks);
  M->g[gi].ranks = NULL;
  if (consider(M, G.mid, P->cum[T], P->col) != 0) return -1;
  if (G.lo < 0 && M->arg->opt.only_mu0) return 0;
  if (M->arg->opt.schedule == PAR_DYNAMIC) return par_dynamic_path(M, &G, P);
  if (G.lo < 0) {   /* mu(0): T for everyone, and B as its copy m rows down */
    gpath *Pm = par_master_path(M, M->m);
    memcpy(Pm->col, P->col, (size_t)(T + 1) * sizeof *P->col);
    memcpy(Pm->cum, P->cum, (size_t)(T + 1) * sizeof *P->cum);
    TRY(par_master_charge(M, (uint64_t)T + 1));
    for (int r = G.g0; r < G.g0 + G.p; r++) TRY(par_master_send_bound(M, P, PAR_AS_BOTH, r));
    return dispatch(M, G.g0, G.p, 0, M->m, P, Pm);
  }
  /* Paths below mu(mid): (mid, hi), bounded by T = mu(mid); above: (lo, mid),
   * bounded by B = mu(mid). */
  int below_paths = G.hi - G.mid - 1, above_paths = G.mid - G.lo - 1;
  int64_t wa = 0, wb = 0;
  if (M->arg->opt.alloc != ALLOC_HALF) {
    wa = split_region(M->m, M->n, G.U, P);
    wb = split_region(M->m, M->n, P, G.L);
    TRY(par_master_charge(M, 2 * ((uint64_t)T + 1)));
  }
  int nb = split_slaves(M->arg->opt.alloc, G.p, wa, wb, above_paths, below_paths), na = G.p - nb;
  if (M->arg->opt.alloc == ALLOC_FIT && par_fit_split(M, &G, P, &nb, &na) != 0) return -1;
  if (below_paths > 0 && nb > 0) {
    for (int r = G.g0; r < G.g0 + nb; r++) TRY(par_master_send_bound(M, P, PAR_AS_T, r));
    TRY(dispatch(M, G.g0, nb, G.mid, G.hi, P, G.L));
  }
  if (above_paths > 0 && na > 0) {
    for (int r = G.g0 + nb; r < G.g0 + nb + na; r++) TRY(par_master_send_bound(M, P, PAR_AS_B, r));
    TRY(dispatch(M, G.g0 + nb, na, G.lo, G.mid, G.U, P));
  }
  return 0;
}

static int piece(master *M, int src) {
  int gi = M->group_of[src];
  if (gi < 0 || !M->g[gi].live) xpanic("master: a piece from slave %d, in no group", src);
  group *G = &M->g[gi];
  par_rd r = {M->in.b, M->in.b + M->in.len};
  int t_hi = par_get_i32(&r), len = par_get_i32(&r);
  if (t_hi > M->T || t_hi - len + 1 < 0) xpanic("master: bad piece [%d, %d]", t_hi - len + 1, t_hi);
  for (int i = 0; i < len; i++) G->col[t_hi - i] = par_get_i32(&r);
  for (int i = 0; i < len; i++) G->w[t_hi - i] = par_get_f64(&r);
  G->have += len;
  if (G->have > M->T + 1) xpanic("master: the path has too many nodes");
  return G->have == M->T + 1 ? finished(M, gi) : 0;
}

static int result(master *M, int src) {
  int gi = M->group_of[src];
  if (gi < 0 || !M->g[gi].live) xpanic("master: a result from slave %d, in no group", src);
  par_rd r = {M->in.b, M->in.b + M->in.len};
  int start = par_get_i32(&r);
  double quanta = par_get_f64(&r);
  int *col = xmallocarray((size_t)M->T + 1, sizeof *col);
  par_get_i32s(&r, col, M->T + 1);
  int rc = consider(M, start, quanta, col);
  free(col);
  if (rc != 0) return -1;
  M->g[gi].live = 0;
  M->live--;
  M->group_of[src] = -1;
  free(M->g[gi].ranks);
  M->g[gi].ranks = NULL;
  return M->arg->opt.schedule == PAR_DYNAMIC ? par_dynamic_local(M, M->g[gi].est) : 0;
}

/* One pair: the whole protocol of par.h. */
static int one_pair(master *M, par_pair *pr, cost_kind kind) {
  int tr = pr->nq < pr->np;   /* the smaller contour gives the rows */
  const vec2 *R = tr ? pr->Q : pr->P, *C = tr ? pr->P : pr->Q;
  int m = tr ? pr->nq : pr->np, n = tr ? pr->np : pr->nq;
  double zr = tr ? pr->zq : pr->zp, zc = tr ? pr->zp : pr->zq;
  M->pr = pr;
  M->own = &pr->master;
  M->m = m, M->n = n, M->T = m + n;
  M->maxlen = par_maxlen(m, n);
  double t0 = mp_time(M->mp);
  weights *w = weights_new_shadow(R, m, zr, C, n, zc, kind, pr->shadow, 0);   /* for the quantum */
  memset(&pr->t, 0, sizeof pr->t);
  pr->t.m = m, pr->t.n = n, pr->t.transposed = tr, pr->t.quantum = weights_quantum(w);
  pr->t.shadow = w->shadow;
  pr->t.qexp = weights_qexp(w);
  pr->t.col = xmallocarray((size_t)M->T + 1, sizeof *pr->t.col);
  weights_free(w);
  M->best = (tiling_best){HUGE_VAL, 0, pr->t.col};

  /* The points, to every slave (section 5). */
  for (int r = 1; r <= M->S; r++) {
    par_buf_reset(&M->out);
    par_put_i32(&M->out, m);
    par_put_i32(&M->out, n);
    par_put_i32(&M->out, (int)kind | (pr->t.shadow != 0 ? PAR_SHADOW : 0));
    par_put_i32(&M->out, M->arg->opt.min_diag);
    par_put_f64(&M->out, zr);
    par_put_f64(&M->out, zc);
    if (pr->t.shadow != 0) par_put_f64(&M->out, pr->t.shadow);   /* only then: the paper's bytes stay */
    if (M->arg->opt.block > 1) par_put_i32(&M->out, M->arg->opt.block);   /* par_block.h */
    if (M->arg->opt.table > 0 || M->arg->opt.back > 0) {   /* only then: the paper's bytes stay */
      par_put_f64(&M->out, M->arg->opt.table);
      par_put_f64(&M->out, M->arg->opt.back);
    }
    TRY(par_send(M->mp, M->own, PAR_CONTROL, r, PAR_TAG_POINTS, &M->out));
    par_buf_reset(&M->out);
    par_put_f64s(&M->out, (const double *)R, 2 * m);
    par_put_f64s(&M->out, (const double *)C, 2 * n);
    TRY(par_send(M->mp, M->own, PAR_CONTROL, r, PAR_TAG_POINTS, &M->out));
  }
  /* shortestpath: mu(0) with every slave, then findallpaths(0, m). */
  if (M->arg->opt.schedule == PAR_DYNAMIC) {
    TRY(par_dynamic_begin(M));
  } else {
    TRY(dispatch(M, 1, M->S, -1, -1, NULL, NULL));
  }
  while (M->live > 0) {
    mp_status st;
    TRY(par_recv(M->mp, MP_ANY, MP_ANY, &M->in, M->maxlen, &st));
    if (st.tag == PAR_TAG_PIECE) {
      if (piece(M, st.source) != 0) return -1;
    } else if (st.tag == PAR_TAG_RESULT) {
      if (result(M, st.source) != 0) return -1;
    } else {
      xpanic("master: unexpected tag %d from rank %d", st.tag, st.source);
    }
  }
  par_dynamic_end(M);
  pr->time = mp_time(M->mp) - t0;
  pr->t.quanta = M->best.quanta;
  pr->t.start = M->best.start;
  pr->t.cost = ldexp(pr->t.quanta, pr->t.qexp);

  /* Everyone's counters for this pair. */
  pr->counts = pr->master;
  double first = 0, last = 0;
  for (int r = 1; r <= M->S; r++) TRY(send_task(M, PAR_TASK_REPORT, 0, 0, 0, 0, r));
  for (int i = 0; i < M->S; i++) {
    mp_status st;
    TRY(par_recv(M->mp, MP_ANY, PAR_TAG_STATS, &M->in, M->maxlen, &st));
    par_rd r = {M->in.b, M->in.b + M->in.len};
    par_counts c;
    memset(&c, 0, sizeof c);   /* a slave keeps no bookkeeping units */
    for (int k = 0; k < PAR_KINDS; k++) c.msgs[k] = (uint64_t)par_get_f64(&r);
    for (int k = 0; k < PAR_KINDS; k++) c.bytes[k] = (uint64_t)par_get_f64(&r);
    c.nodes = (uint64_t)par_get_f64(&r);
    c.units = (uint64_t)par_get_f64(&r);
    c.paths = (uint64_t)par_get_f64(&r);
    c.idle = par_get_f64(&r);
    double f0 = par_get_f64(&r), f1 = par_get_f64(&r);
    if (i == 0 || f0 < first) first = f0;
    if (i == 0 || f1 > last) last = f1;
    par_counts_add(&pr->counts, &c);
  }
  pr->mu0_time = last - first;
  pr->t.count.nodes = pr->counts.nodes;
  pr->t.count.paths = pr->counts.paths;
  for (int i = 0; i < M->npaths; i++) {
    free(M->paths[i]->col);
    free(M->paths[i]->cum);
    free(M->paths[i]);
  }
  M->npaths = 0;
  M->ng = 0;
  return 0;
}

void par_master(mp *self, void *ud) {
  par_master_arg *arg = ud;
  master M0, *M = &M0;
  memset(M, 0, sizeof *M);
  M->mp = self;
  M->arg = arg;
  M->S = mp_size(self) - 1;
  if (M->S < 1) {
    snprintf(arg->err, sizeof arg->err, "master: no slaves (%d ranks)", mp_size(self));
    arg->failed = 1;
    return;
  }
  M->group_of = xmallocarray((size_t)M->S + 1, sizeof *M->group_of);
  for (int r = 0; r <= M->S; r++) M->group_of[r] = -1;
  for (int i = 0; i < arg->npairs; i++) {
    memset(&arg->pairs[i].master, 0, sizeof arg->pairs[i].master);
    if (one_pair(M, &arg->pairs[i], arg->kind) != 0) break;
    if (arg->progress) arg->progress(arg->progress_ud, i + 1, arg->npairs);
  }
  for (int r = 1; r <= M->S; r++) send_task(M, PAR_TASK_QUIT, 0, 0, 0, 0, r);
  for (int i = 0; i < M->npaths; i++) {
    free(M->paths[i]->col);
    free(M->paths[i]->cum);
    free(M->paths[i]);
  }
  for (int i = 0; i < M->ng; i++) free(M->g[i].col), free(M->g[i].w), free(M->g[i].ranks);
  par_dynamic_end(M);
  free(M->paths);
  free(M->g);
  free(M->group_of);
  par_buf_free(&M->in);
  par_buf_free(&M->out);
}
