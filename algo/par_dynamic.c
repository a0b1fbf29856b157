/* par_dynamic.c -- --schedule dynamic: bands as tasks to free slaves
 * (par_dynamic.h; the paper's sections 4, 6, 8 and 9). */
#include "algo/par_dynamic.h"

#include <stdlib.h>
#include <string.h>

#include "algo/split.h"
#include "algo/tiling.h"
#include "util/xmem.h"

typedef struct {
  int lo, hi;          /* the paths lo+1 .. hi-1 */
  const gpath *U, *L;  /* between mu(lo) and mu(hi) */
  int64_t est;         /* its work, estimated: nodes between U and L x levels */
  int usable;          /* the slaves its middle path's diagonals can use */
} task;

struct par_dyn {
  task *ready;
  int nready, rcap;
  const gpath **hu, **hl;   /* [rank]: the bounds T and B that slave holds */
  const gpath *mu0, *mum;   /* mu(0) and its copy m rows down */
  int64_t run;              /* the estimated work of the running tasks */
  int *free;                /* scratch: the free slaves, by rank */
};

#define TRY(call) PAR_TRY(par_master_fail, M, call)

/* floor(log2(paths)) + 1: the levels of the divide and conquer over them. */
static int levels(int paths) {
  int l = 0;
  for (; paths > 0; paths >>= 1) l++;
  return l;
}

/* The band of the paths lo+1 .. hi-1 between U and L, if any, as a ready task. */
static int add(par_master_ctx *M, int lo, int hi, const gpath *U, const gpath *L) {
  struct par_dyn *D = M->dyn;
  if (hi - lo < 2) return 0;
  TRY(par_master_charge(M, 2 * ((uint64_t)M->T + 1)));
  if (D->nready == D->rcap) {
    D->rcap = D->rcap ? 2 * D->rcap : 16;
    D->ready = xreallocarray(D->ready, (size_t)D->rcap, sizeof *D->ready);
  }
  int64_t region = split_region(M->m, M->n, U, L);
  int use = split_usable(M->m, M->n, tiling_mid(lo, hi), U, L, M->arg->opt.min_diag);
  D->ready[D->nready++] = (task){lo, hi, U, L, region * levels(hi - lo - 1), use};
  return 0;
}

/* Send slave r the bounds U and L it lacks. */
static int bounds(par_master_ctx *M, int r, const gpath *U, const gpath *L) {
  struct par_dyn *D = M->dyn;
  if (D->hu[r] != U && D->hl[r] != L && U == D->mu0 && L == D->mum) {
    TRY(par_master_send_bound(M, U, PAR_AS_BOTH, r));
  } else {
    if (D->hu[r] != U) TRY(par_master_send_bound(M, U, PAR_AS_T, r));
    if (D->hl[r] != L) TRY(par_master_send_bound(M, L, PAR_AS_B, r));
  }
  D->hu[r] = U, D->hl[r] = L;
  return 0;
}

/* Give the band (lo, hi) to the q slaves ranks[]: its middle path (PATH; lo
 * < 0: mu(0)), or all of it to one (LOCAL).  The task names the group. */
static int start(par_master_ctx *M, int lo, int hi, const gpath *U, const gpath *L, int64_t est,
                 const int *ranks, int q, int local) {
  struct par_dyn *D = M->dyn;
  int gi = par_master_group(M, ranks, q, lo, hi, U, L, local);
  M->g[gi].est = est;
  D->run += est;
  if (lo >= 0)
    for (int i = 0; i < q; i++) TRY(bounds(M, ranks[i], U, L));
  par_buf_reset(&M->out);
  par_put_i32(&M->out, local ? PAR_TASK_LOCAL : PAR_TASK_PATH);
  par_put_i32(&M->out, M->g[gi].mid);
  par_put_i32(&M->out, lo >= 0);
  par_put_i32(&M->out, -1);   /* no first rank: a list follows */
  par_put_i32(&M->out, q);
  par_put_i32s(&M->out, ranks, q);
  for (int i = 0; i < q; i++) TRY(par_send(M->mp, M->own, PAR_CONTROL, ranks[i], PAR_TAG_TASK, &M->out));
  return 0;
}

/* While slaves are free and bands ready: the largest band first, to its
 * share of the slaves (see par_dynamic.h). */
static int schedule(par_master_ctx *M) {
  struct par_dyn *D = M->dyn;
  while (D->nready > 0) {
    int nfree = 0;
    for (int r = 1; r <= M->S; r++)
      if (M->group_of[r] < 0) D->free[nfree++] = r;
    if (nfree == 0) return 0;
    int bi = 0;
    int64_t ready = 0;
    for (int i = 0; i < D->nready; i++) {
      const task *t = &D->ready[i], *b = &D->ready[bi];
      ready += t->est;
      if (t->est > b->est || (t->est == b->est && t->lo < b->lo)) bi = i;
    }
    int64_t all = D->run + ready;
    task t = D->ready[bi];
    D->ready[bi] = D->ready[--D->nready];
    /* Its share of the free slaves, by the work of the ready bands (the
     * running ones have theirs): nfree est / ready, rounded. */
    int q = ready > 0 ? (int)((2 * (int64_t)nfree * t.est + ready) / (2 * ready)) : 1;
    if (q > t.usable) q = t.usable;
    if (q > nfree) q = nfree;
    if (q < 1) q = 1;
    int local = t.est * M->S <= all || (q == 1 && t.hi - t.lo == 2);
    if (start(M, t.lo, t.hi, t.U, t.L, t.est, D->free, local ? 1 : q, local) != 0) return -1;
  }
  return 0;
}

int par_dynamic_begin(par_master_ctx *M) {
  struct par_dyn *D = xcalloc(1, sizeof *D);
  M->dyn = D;
  D->hu = xcalloc((size_t)M->S + 1, sizeof *D->hu);
  D->hl = xcalloc((size_t)M->S + 1, sizeof *D->hl);
  D->free = xmallocarray((size_t)M->S + 1, sizeof *D->free);
  TRY(par_master_charge(M, (uint64_t)M->T + 1));
  int q = split_usable(M->m, M->n, 0, NULL, NULL, M->arg->opt.min_diag);
  if (q > M->S) q = M->S;
  for (int i = 0; i < q; i++) D->free[i] = i + 1;
  return start(M, -1, -1, NULL, NULL, 0, D->free, q, 0);
}

int par_dynamic_path(par_master_ctx *M, const par_group *G, gpath *P) {
  struct par_dyn *D = M->dyn;
  D->run -= G->est;
  if (G->lo < 0) {   /* mu(0): the whole graph is the band (0, m) */
    gpath *Pm = par_master_path(M, M->m);
    memcpy(Pm->col, P->col, (size_t)(M->T + 1) * sizeof *P->col);
    memcpy(Pm->cum, P->cum, (size_t)(M->T + 1) * sizeof *P->cum);
    D->mu0 = P, D->mum = Pm;
    if (add(M, 0, M->m, P, Pm) != 0) return -1;
  } else if (add(M, G->lo, G->mid, G->U, P) != 0 || add(M, G->mid, G->hi, P, G->L) != 0) {
    return -1;
  }
  return schedule(M);
}

int par_dynamic_local(par_master_ctx *M, int64_t est) {
  M->dyn->run -= est;
  return schedule(M);
}

void par_dynamic_end(par_master_ctx *M) {
  struct par_dyn *D = M->dyn;
  if (!D) return;
  free(D->ready), free(D->hu), free(D->hl), free(D->free);
  free(D);
  M->dyn = NULL;
}
