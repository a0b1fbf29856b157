/* par_slave.c -- a slave: findonepath on its share of each diagonal, the
 * exchange of run-boundary costs, backtracking by message (paper, section 5),
 * and the whole band alone for a one-slave group. */
#include "algo/par_slave.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "algo/band.h"
#include "algo/kernel.h"
#include "algo/par_block.h"
#include "algo/tiling.h"
#include "util/xmem.h"

typedef par_slave_ctx slave;

#define TRY(call) PAR_TRY(par_slave_fail, S, call)

int par_slave_recv(slave *S, int src, int tag, mp_status *st) {
  double t0 = mp_time(S->mp);
  int rc = par_recv(S->mp, src, tag, &S->in, S->maxlen, st);
  S->arg->counts.idle += mp_time(S->mp) - t0;
  return rc;
}

void par_slave_count_diag(slave *S, int t, int sends, int recvs) {
  if (!S->first_path || t >= S->arg->diag_len) return;
  if (S->arg->diag_sends) S->arg->diag_sends[t] += sends;
  if (S->arg->diag_recvs) S->arg->diag_recvs[t] += recvs;
}

int par_slave_send_boundary(slave *S, int i, int t, int n0, int n1) {
  par_buf_reset(&S->out);
  par_put_i32(&S->out, t);
  par_put_i32(&S->out, n0);
  par_put_i32(&S->out, n1);
  par_put_f64s(&S->out, S->prev + n0, n1 - n0 + 1);
  return par_send(S->mp, &S->arg->counts, PAR_BOUNDARY, S->grp[i], PAR_TAG_BOUNDARY, &S->out);
}

int par_slave_recv_boundary(slave *S, int o, int t, int v0, int v1, const char *what) {
  mp_status st;
  TRY(par_slave_recv(S, S->grp[o], PAR_TAG_BOUNDARY, &st));
  par_rd r = {S->in.b, S->in.b + S->in.len};
  int tt = par_get_i32(&r), x0 = par_get_i32(&r), x1 = par_get_i32(&r);
  if (tt != t || x0 != v0 || x1 != v1)
    xpanic("slave %d: %s from %d for t=%d [%d,%d], expected t=%d [%d,%d]", S->rank, what, S->grp[o], tt, x0,
           x1, t, v0, v1);
  par_get_f64s(&r, S->prev + v0, v1 - v0 + 1);
  return 0;
}

int par_slave_fail(slave *S, int rc, const char *what) {
  if (!S->arg->failed)
    snprintf(S->arg->err, sizeof S->arg->err, "slave %d: %s: %s", S->rank, what, mp_strerror(rc));
  S->arg->failed = 1;
  return -1;
}

static void free_pair(slave *S) {
  weights_free(S->w);
  band_ws_free(S->ws);
  free(S->R), free(S->C);
  free(S->U.col), free(S->U.cum), free(S->L.col), free(S->L.cum);
  free(S->type), free(S->a), free(S->b), free(S->q), free(S->c0), free(S->run0), free(S->woff);
  free(S->bits);
  if (S->prev) free(S->prev - 1);
  if (S->cur) free(S->cur - 1);
  free(S->pcol), free(S->pw), free(S->pv);
  free(S->grp);
  par_block_free(S->blk);
  slave keep = *S;
  memset(S, 0, sizeof *S);
  S->mp = keep.mp, S->arg = keep.arg, S->rank = keep.rank, S->in = keep.in, S->out = keep.out;
  S->first_path = keep.first_path;
}

/* POINTS: header {m, n, kind, d} and {zr, zc} (and the shadow's weight
 * when kind carries PAR_SHADOW), then the points. */
static int points(slave *S, par_rd *r) {
  free_pair(S);
  int m = par_get_i32(r), n = par_get_i32(r);
  int k = par_get_i32(r);
  cost_kind kind = (cost_kind)(k & ~PAR_SHADOW);
  S->d = par_get_i32(r);
  double zr = par_get_f64(r), zc = par_get_f64(r);
  double shadow = k & PAR_SHADOW ? par_get_f64(r) : 0;
  /* Then --block k (par_block.h), if above 1, and the prices of a table
   * cell and a backtracking step, if either is set: 0, 4, 16 or 20 bytes. */
  S->k = (r->end - r->p) % 8 == 4 ? par_get_i32(r) : 1;
  S->table = S->back = 0;
  if (r->end - r->p >= 16) S->table = par_get_f64(r), S->back = par_get_f64(r);
  S->m = m, S->n = n;
  S->maxlen = par_maxlen(m, n);
  mp_status st;
  TRY(par_recv(S->mp, 0, PAR_TAG_POINTS, &S->in, S->maxlen, &st));
  par_rd pr = {S->in.b, S->in.b + S->in.len};
  S->R = xmallocarray((size_t)m, sizeof *S->R);
  S->C = xmallocarray((size_t)n, sizeof *S->C);
  par_get_f64s(&pr, (double *)S->R, 2 * m);
  par_get_f64s(&pr, (double *)S->C, 2 * n);
  /* Tables only when the slaves are few: par_slave_table. */
  S->w = weights_new_shadow(S->R, m, zr, S->C, n, zc, kind, shadow, par_slave_table(mp_size(S->mp) - 1));
  if (S->table > 0 && weights_has_table(S->w))   /* its build, charged where asked */
    TRY(mp_compute(S->mp, (double)m * (double)(n + 1) * S->table));
  S->ws = band_ws_new(m, n);
  size_t T1 = (size_t)(m + n + 1);
  S->U.col = xmallocarray(T1, sizeof(int)), S->U.cum = xmallocarray(T1, sizeof(double));
  S->L.col = xmallocarray(T1, sizeof(int)), S->L.cum = xmallocarray(T1, sizeof(double));
  S->type = xmalloc(T1);
  S->a = xmallocarray(T1, sizeof(int)), S->b = xmallocarray(T1, sizeof(int));
  S->q = xmallocarray(T1, sizeof(int)), S->c0 = xmallocarray(T1, sizeof(int));
  S->run0 = xmallocarray(T1, sizeof(int)), S->woff = xmallocarray(T1, sizeof(int64_t));
  S->prev = (double *)xmallocarray((size_t)n + 3, sizeof(double)) + 1;
  S->cur = (double *)xmallocarray((size_t)n + 3, sizeof(double)) + 1;
  S->pcol = xmallocarray(T1, sizeof(int));
  S->pw = xmallocarray(T1, sizeof(double));
  S->pv = xmalloc(T1);
  S->grp = xmallocarray((size_t)mp_size(S->mp), sizeof *S->grp);
  if (S->k > 1) S->blk = par_block_new(m, n);
  return 0;
}

/* BOUND: {start, as} + columns + prefix sums. */
static void bound(slave *S, par_rd *r) {
  int start = par_get_i32(r), as = par_get_i32(r), T1 = S->m + S->n + 1;
  gpath *p = as == PAR_AS_B ? &S->L : &S->U;
  p->start = start;
  par_get_i32s(r, p->col, T1);
  par_get_f64s(r, p->cum, T1);
  if (as == PAR_AS_BOTH) {   /* mu(0) as T, and as B its copy m rows down */
    S->L.start = start + S->m;
    memcpy(S->L.col, p->col, (size_t)T1 * sizeof *p->col);
    memcpy(S->L.cum, p->cum, (size_t)T1 * sizeof *p->cum);
  }
  if (as & PAR_AS_T) S->hasU = 1;
  if (as & PAR_AS_B) S->hasL = 1;
}

/* The columns slave j of q owns on diagonal t (j < q), or an empty range. */
static void owned(const slave *S, int t, int j, int *u0, int *u1) {
  if (S->type[t] != PAR_D_NORMAL) {   /* a single node: the group's first slave */
    *u0 = j == 0 ? S->a[t] : 1, *u1 = j == 0 ? S->a[t] : 0;
    return;
  }
  int a = S->a[t], len = S->b[t] - a + 1, q = S->q[t];
  if (j >= q) {
    *u0 = 1, *u1 = 0;
    return;
  }
  *u0 = a + split_n(len, q, j);   /* the paper's N_j (split.h) */
  *u1 = a + split_n(len, q, j + 1) - 1;
}

static int owner(const slave *S, int t, int c) {
  if (S->k > 1) return par_block_owner(S, t, c);
  if (S->type[t] != PAR_D_NORMAL) return 0;
  return split_owner(S->a[t], S->b[t], S->q[t], c);
}

/* Before computing normal diagonal t: send the costs of diagonal t-1 that
 * others need, then receive those I need (sends never block). */
static int exchange(slave *S, int t, int j) {
  int a = S->a[t], b = S->b[t], pa = S->a[t - 1], pb = S->b[t - 1];
  int sends = 0, recvs = 0;
  int u0, u1;
  owned(S, t - 1, j, &u0, &u1);
  if (u0 <= u1) {
    /* Slaves i of diagonal t need columns [own0_i - 1, own1_i]: only those
     * whose runs touch [u0, u1 + 1] can need mine. */
    int lo = owner(S, t, u0 < a ? a : u0 > b ? b : u0);
    int hi = owner(S, t, u1 + 1 < a ? a : u1 + 1 > b ? b : u1 + 1);
    for (int i = lo; i <= hi; i++) {
      if (i == j) continue;
      int n0, n1;
      owned(S, t, i, &n0, &n1);
      n0 = n0 - 1 > u0 ? n0 - 1 : u0;
      n1 = n1 < u1 ? n1 : u1;
      if (n0 > n1) continue;
      TRY(par_slave_send_boundary(S, i, t, n0, n1));
      sends++;
    }
  }
  int c0, c1;
  owned(S, t, j, &c0, &c1);
  if (c0 <= c1) {
    /* I need [c0-1, c1] of diagonal t-1; outside its band they are +inf. */
    int n0 = c0 - 1 < pa ? pa : c0 - 1, n1 = c1 < pb ? c1 : pb;
    if (c0 - 1 < pa) S->prev[c0 - 1] = HUGE_VAL;
    if (c1 > pb) S->prev[c1] = HUGE_VAL;
    if (n0 <= n1) {
      int lo = owner(S, t - 1, n0), hi = owner(S, t - 1, n1);
      for (int o = lo; o <= hi; o++) {
        if (o == j) continue;
        int v0, v1;
        owned(S, t - 1, o, &v0, &v1);
        v0 = v0 > n0 ? v0 : n0;
        v1 = v1 < n1 ? v1 : n1;
        if (v0 > v1) continue;
        if (par_slave_recv_boundary(S, o, t, v0, v1, "boundary") != 0) return -1;
        recvs++;
      }
    }
  }
  par_slave_count_diag(S, t, sends, recvs);
  return 0;
}

/* Send the piece pcol/pw for diagonals t_hi down to t_hi-len+1 to the master. */
static int send_piece(slave *S, int t_hi, int len) {
  par_buf_reset(&S->out);
  par_put_i32(&S->out, t_hi);
  par_put_i32(&S->out, len);
  par_put_i32s(&S->out, S->pcol, len);
  par_put_f64s(&S->out, S->pw, len);
  return par_send(S->mp, &S->arg->counts, PAR_BACKTRACK, 0, PAR_TAG_PIECE, &S->out);
}

/* Backtrack from node (t, c), which is mine (Fig. 14), until the path leaves
 * my nodes or reaches the start node.  The paper's slave sends its piece
 * with its edge weights, then passes control on.  Under --block k (par_block.h)
 * control passes first: the walk only reads edge bits, and the weights are
 * computed and the piece sent while the next slave walks on (a chain of
 * re-solved bands is the variants' critical path, and every path of it is
 * backtracked through all its slaves in turn). */
static int backtrack(slave *S, int s, int t, int c, int j) {
  int len = 0, t_hi = t, du = s - S->U.start, late = S->k > 1;
  while (t > 0 && owner(S, t, c) == j) {
    int k = s + t;
    if (S->type[t] == PAR_D_RUN) {   /* a run joined from T: its nodes and weights are T's */
      int t0 = S->run0[t];
      for (int u = t; u >= t0; u--) {
        S->pv[len] = 2;
        S->pcol[len] = S->U.col[u + du];
        S->pw[len++] = S->U.cum[u + du] - S->U.cum[u - 1 + du];
      }
      t = t0 - 1;
      c = S->U.col[t + du];
      continue;
    }
    int vert;
    if (S->type[t] == PAR_D_SINGLE) {
      vert = band_cut_vertical(S->a[t - 1], S->a[t]);
    } else {
      int i = c - S->c0[t];
      vert = (int)((S->bits[S->woff[t] + (i >> 6)] >> (i & 63)) & 1);
    }
    S->pv[len] = (unsigned char)vert;
    S->pcol[len] = c;
    S->pw[len++] = late ? 0 : weights_in(S->w, k, c, vert);
    if (!vert) c--;
    t--;
  }
  if (t > 0 && late) {   /* control first */
    par_buf_reset(&S->out);
    par_put_i32(&S->out, t);
    par_put_i32(&S->out, c);
    TRY(par_send(S->mp, &S->arg->counts, PAR_BACKTRACK, S->grp[owner(S, t, c)], PAR_TAG_BACK, &S->out));
  }
  if (late)
    for (int i = 0; i < len; i++)
      if (S->pv[i] != 2) S->pw[i] = weights_in(S->w, s + t_hi - i, S->pcol[i], S->pv[i]);
  if (S->back > 0) TRY(mp_compute(S->mp, (double)len * S->back));   /* the walk, charged where asked */
  if (t == 0) {
    S->pcol[len] = 0;
    S->pw[len++] = 0;
    return send_piece(S, t_hi, len);
  }
  TRY(send_piece(S, t_hi, len));
  if (late) return 0;
  par_buf_reset(&S->out);
  par_put_i32(&S->out, t);
  par_put_i32(&S->out, c);
  return par_send(S->mp, &S->arg->counts, PAR_BACKTRACK, S->grp[owner(S, t, c)], PAR_TAG_BACK, &S->out);
}

/* Diagonal t of path s is a pinch (one node, as was t-1): join the run where
 * T and B coincide, or the single cut edge (section 8); the group's first
 * slave carries the cost.  Returns the last diagonal joined. */
int par_slave_pinch(slave *S, int s, const gpath *U, const gpath *L, int j, int t, int a, int *pa,
                    int *pb) {
  int m = S->m, n = S->n, k = s + t;
  int t1 = band_shared_until(m, n, s, U, L, t);
  if (t1 > t) {   /* a run where T and B coincide: joined at once */
    int du = s - U->start;
    for (int u = t; u <= t1; u++) {
      S->type[u] = PAR_D_RUN, S->run0[u] = t, S->q[u] = 1;
      S->a[u] = S->b[u] = U->col[u + du];
    }
    if (j == 0) {
      double v = S->prev[*pa] + (U->cum[t1 + du] - U->cum[t - 1 + du]);
      int c = S->a[t1];
      S->prev[c - 1] = S->prev[c + 1] = HUGE_VAL;
      S->prev[c] = v;
    }
    *pa = *pb = S->a[t1];
    return t1;
  }
  /* A cut edge (section 8): joined by the group's first slave. */
  S->type[t] = PAR_D_SINGLE, S->a[t] = S->b[t] = a, S->q[t] = 1;
  if (j == 0) {
    double v = S->prev[*pa] + weights_in(S->w, k, a, band_cut_vertical(*pa, a));
    S->prev[a - 1] = S->prev[a + 1] = HUGE_VAL;
    S->prev[a] = v;
  }
  *pa = *pb = a;
  return t;
}

/* The paper's sweep over diagonals 1..m+n of path s: each split among the
 * active slaves (N_i, at least d nodes each), one exchange per diagonal. */
static int paper_sweep(slave *S, int s, const gpath *U, const gpath *L, int j, int p) {
  int m = S->m, n = S->n, T = m + n;
  int64_t wo = 0;
  S->type[0] = PAR_D_SINGLE, S->a[0] = S->b[0] = 0, S->q[0] = 1;
  S->prev[-1] = S->prev[0] = S->prev[1] = HUGE_VAL;
  if (j == 0) S->prev[0] = 0;
  int pa = 0, pb = 0;
  for (int t = 1; t <= T; t++) {
    int k = s + t, a, b;
    band_range(m, n, s, U, L, k, &a, &b);
    if (a == b && pa == pb) {
      t = par_slave_pinch(S, s, U, L, j, t, a, &pa, &pb);
      continue;
    }
    S->type[t] = PAR_D_NORMAL, S->a[t] = a, S->b[t] = b;
    S->q[t] = split_active(b - a + 1, p, S->d);
    if (exchange(S, t, j) != 0) return -1;
    int c0, c1;
    owned(S, t, j, &c0, &c1);
    S->c0[t] = c0;
    if (c0 <= c1) {
      int64_t words = kernel_words(c1 - c0 + 1);
      if (wo + words > S->bitcap) {
        S->bitcap = 2 * (wo + words) + 1024;
        S->bits = xreallocarray(S->bits, (size_t)S->bitcap, sizeof *S->bits);
      }
      kernel_diag(S->w, k, c0, c1, S->prev, S->cur, S->bits + wo);
      S->woff[t] = wo;
      wo += words;
      S->arg->counts.nodes += (uint64_t)(c1 - c0 + 1);
      TRY(par_compute(S->mp, &S->arg->counts, (uint64_t)(c1 - c0 + 1)));
    }
    double *x = S->prev;
    S->prev = S->cur;
    S->cur = x;
    pa = a, pb = b;
  }
  return 0;
}

/* findonepath(s) with the group's slaves S->grp[0 .. p-1] (sections 4 and 5):
 * the paper's sweep, or the blocked wavefront (par_block.h) with --block
 * k > 1; then backtracking. */
static int path_task(slave *S, int s, int bounded, int p) {
  int n = S->n, T = S->m + n, j = 0;
  while (j < p && S->grp[j] != S->rank) j++;
  if (j == p) xpanic("slave %d: a task for a group without it", S->rank);
  const gpath *U = bounded ? &S->U : NULL, *L = bounded ? &S->L : NULL;
  if (!bounded) S->arg->fp_start = mp_time(S->mp);
  if ((S->k > 1 ? par_block_sweep(S, s, U, L, j, p) : paper_sweep(S, s, U, L, j, p)) != 0) return -1;
  if (!bounded) S->arg->fp_end = mp_time(S->mp);
  S->first_path = 0;
  if (j == 0) S->arg->counts.paths++;
  /* The terminal node (s+m, n) is alone on its diagonal: the first slave's. */
  if (owner(S, T, n) == j && backtrack(S, s, T, n, j) != 0) return -1;
  for (;;) {   /* wait for control, or the end (BACK with t < 0, from the master) */
    mp_status st;
    TRY(par_slave_recv(S, MP_ANY, PAR_TAG_BACK, &st));
    par_rd r = {S->in.b, S->in.b + S->in.len};
    int t = par_get_i32(&r);
    if (t < 0) return 0;
    int c = par_get_i32(&r);
    if (backtrack(S, s, t, c, j) != 0) return -1;
  }
}

/* A group of one: every path between T and B by the serial divide and
 * conquer; only the best goes to the master (section 5). */
static int local_task(slave *S) {
  int T1 = S->m + S->n + 1;
  tiling_best best = {HUGE_VAL, 0, S->pcol};
  band_count cnt = {0, 0, 0};
  tiling_range(S->w, S->ws, &S->U, &S->L, &best, &cnt);
  S->arg->counts.nodes += cnt.nodes;
  S->arg->counts.paths += cnt.paths;
  TRY(par_compute(S->mp, &S->arg->counts, cnt.nodes));
  par_buf_reset(&S->out);
  par_put_i32(&S->out, best.start);
  par_put_f64(&S->out, best.quanta);
  par_put_i32s(&S->out, best.col, T1);
  return par_send(S->mp, &S->arg->counts, PAR_CONTROL, 0, PAR_TAG_RESULT, &S->out);
}

static int report(slave *S) {
  par_counts *c = &S->arg->counts;
  par_buf_reset(&S->out);
  for (int k = 0; k < PAR_KINDS; k++) par_put_f64(&S->out, (double)c->msgs[k]);
  for (int k = 0; k < PAR_KINDS; k++) par_put_f64(&S->out, (double)c->bytes[k]);
  par_put_f64(&S->out, (double)c->nodes);
  par_put_f64(&S->out, (double)c->units);
  par_put_f64(&S->out, (double)c->paths);
  par_put_f64(&S->out, c->idle);
  par_put_f64(&S->out, S->arg->fp_start);
  par_put_f64(&S->out, S->arg->fp_end);
  par_counts_add(&S->arg->total, c);
  memset(c, 0, sizeof *c);
  return par_send(S->mp, c, -1, 0, PAR_TAG_STATS, &S->out);
}

int par_slave_table(int slaves) { return slaves <= 4 ? -1 : 0; }

void par_slave(mp *self, void *ud) {
  slave S0, *S = &S0;
  memset(S, 0, sizeof *S);
  S->mp = self;
  S->arg = ud;
  S->rank = mp_rank(self);
  S->first_path = 1;
  S->maxlen = 64;
  for (;;) {
    mp_status st;
    double t0 = mp_time(self);
    int rc = par_recv(self, 0, MP_ANY, &S->in, S->maxlen, &st);
    if (rc == MP_OK && st.tag != PAR_TAG_POINTS) S->arg->counts.idle += mp_time(self) - t0;
    if (rc < 0) {
      par_slave_fail(S, rc, "waiting for the master");
      break;
    }
    par_rd r = {S->in.b, S->in.b + S->in.len};
    if (st.tag == PAR_TAG_POINTS) {
      if (points(S, &r) != 0) break;
    } else if (st.tag == PAR_TAG_BOUND) {
      bound(S, &r);
    } else if (st.tag == PAR_TAG_TASK) {
      int what = par_get_i32(&r);
      if (what == PAR_TASK_QUIT) break;
      if (what == PAR_TASK_REPORT) {
        if (report(S) != 0) break;
        continue;
      }
      int s = par_get_i32(&r), bounded = par_get_i32(&r), g0 = par_get_i32(&r), p = par_get_i32(&r);
      if (p < 1 || p >= mp_size(self)) xpanic("slave %d: a group of %d slaves", S->rank, p);
      if (g0 > 0)   /* slaves g0 .. g0+p-1 */
        for (int i = 0; i < p; i++) S->grp[i] = g0 + i;
      else          /* a list of ranks (--schedule dynamic, par_dynamic.h) */
        par_get_i32s(&r, S->grp, p);
      if (what == PAR_TASK_PATH ? path_task(S, s, bounded, p) : local_task(S)) break;
    } else {
      xpanic("slave %d: unexpected tag %d from the master", S->rank, st.tag);
    }
  }
  free_pair(S);
  par_buf_free(&S->in);
  par_buf_free(&S->out);
}
