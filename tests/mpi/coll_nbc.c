/* coll_nbc.c -- the 18 nonblocking collectives against their blocking forms: each one at sizes
 * on both sides of MPICH's thresholds, from two roots where there is one, with MPI_IN_PLACE,
 * uneven and zero counts, a non-contiguous type, the non-commutative matrix product, and
 * doubles whose sums show the order of the additions.  The nonblocking call's result must be
 * the blocking call's, byte for byte (on tilesim the floating-point sums too: both run the
 * same algorithm; under another MPI library only near, as its two forms may add in other
 * orders), and the blocking one the serial reference.  Each nonblocking call is completed
 * another way in turn (MPI_Wait, MPI_Waitall with a point-to-point exchange started after it,
 * MPI_Waitany and MPI_Waitsome loops, MPI_Test and MPI_Testall polling), some with two more
 * collectives started behind it on another communicator.  Plain MPI C (mtest.h): the same
 * "coll_nbc: P passed, F failed" line under Open MPI and tilesim. */
#include <math.h>
#include <mpi.h>
#include <string.h>

#include "colldata.h"
#include "mtest.h"

typedef struct {
  mtest *t;
  MPI_Comm other;   /* a duplicate of MPI_COMM_WORLD for the collectives started behind */
  int how;          /* the next way to complete */
} ctx;

/* Complete req (and, by turns, a ring exchange of one int and two more
 * collectives on another communicator started after it). */
static void finish(ctx *c, MPI_Request *req) {
  int me = c->t->rank, size = c->t->size, how = c->how++ % 6;
  MPI_Request r[5] = {*req, MPI_REQUEST_NULL, MPI_REQUEST_NULL, MPI_REQUEST_NULL, MPI_REQUEST_NULL};
  int out = me * 3 + 1, in = -1, n = 1, bsum = -1, bval = how == 1 ? 42 : -1, rc = MPI_SUCCESS;
  if (how >= 1 && how <= 3) {
    MPI_Irecv(&in, 1, MPI_INT, (me + size - 1) % size, 77, MPI_COMM_WORLD, &r[1]);
    MPI_Isend(&out, 1, MPI_INT, (me + 1) % size, 77, MPI_COMM_WORLD, &r[2]);
    n = 3;
  }
  if (how == 1 || how == 4) {   /* two more collectives behind it, on another communicator */
    if (me == 0) bval = 42;
    MPI_Ibcast(&bval, 1, MPI_INT, 0, c->other, &r[n++]);
    MPI_Iallreduce(&me, &bsum, 1, MPI_INT, MPI_SUM, c->other, &r[n++]);
  }
  if (how == 0 || how == 1) {
    rc = how == 0 ? MPI_Wait(&r[0], MPI_STATUS_IGNORE) : MPI_Waitall(n, r, MPI_STATUSES_IGNORE);
  } else if (how == 2) {
    for (int k = 0; k < n && !rc; k++) {
      int idx;
      rc = MPI_Waitany(n, r, &idx, MPI_STATUS_IGNORE);
    }
  } else if (how == 3) {
    int left = n;
    while (left > 0 && !rc) {
      int cnt, idx[5];
      rc = MPI_Waitsome(n, r, &cnt, idx, MPI_STATUSES_IGNORE);
      left -= cnt;
    }
  } else if (how == 4) {   /* a few tries, then the wait (a polling loop's length is the machine's) */
    int flag = 0;
    for (int k = 0; k < 5 && !flag && !rc; k++) rc = MPI_Testall(n, r, &flag, MPI_STATUSES_IGNORE);
    if (!flag && !rc) rc = MPI_Waitall(n, r, MPI_STATUSES_IGNORE);
  } else {
    int flag = 0;
    for (int k = 0; k < 5 && !flag && !rc; k++) rc = MPI_Test(&r[0], &flag, MPI_STATUS_IGNORE);
    if (!flag && !rc) rc = MPI_Wait(&r[0], MPI_STATUS_IGNORE);
  }
  int bad = rc != MPI_SUCCESS || r[0] != MPI_REQUEST_NULL;
  if (how >= 1 && how <= 3) bad |= in != ((me + size - 1) % size) * 3 + 1;
  if (how == 1 || how == 4) bad |= bval != 42 || bsum != size * (size - 1) / 2;
  MCHECK(c->t, !bad, "completing a nonblocking collective (way %d): rc %d, or the requests with it went wrong", how,
         rc);
  *req = MPI_REQUEST_NULL;
}

/* The nonblocking result against the blocking one (n bytes at each). */
static void same(ctx *c, const char *what, const void *nb, const void *b, size_t n, int fp) {
  int ok = memcmp(nb, b, n) == 0;
  if (fp && !TILESIM) {   /* another library may add in another order */
    const double *x = nb, *y = b;
    ok = 1;
    for (size_t i = 0; i < n / sizeof(double); i++) ok &= fabs(x[i] - y[i]) <= 1e-9 * (fabs(y[i]) + 1);
  }
  MCHECK(c->t, ok, "%s on %d ranks: the nonblocking result is not the blocking one", what, c->t->size);
}

/* ==== data movement ======================================================= */

static void bcasts(ctx *c, int count, int root, MPI_Datatype dt, int stride) {
  int me = c->t->rank, n = count * stride;
  int *a = xmalloc_or_abort((size_t)n * sizeof(int)), *b = xmalloc_or_abort((size_t)n * sizeof(int));
  for (int i = 0; i < n; i++) a[i] = b[i] = me == root ? val(root, i) : -5;
  MPI_Request r;
  MPI_Bcast(b, count, dt, root, MPI_COMM_WORLD);
  MPI_Ibcast(a, count, dt, root, MPI_COMM_WORLD, &r);
  finish(c, &r);
  int bad = 0;
  for (int i = 0; i < n; i++) bad |= b[i] != (i % stride && me != root ? -5 : val(root, i));
  MCHECK(c->t, !bad, "bcast of %d from %d: a wrong element", count, root);
  same(c, "ibcast", a, b, (size_t)n * sizeof(int), 0);
  free(a);
  free(b);
}

static void gathers(ctx *c, int count, int root, int in_place, int v) {
  int me = c->t->rank, size = c->t->size, total = 0;
  int *counts = xmalloc_or_abort((size_t)size * sizeof(int)), *displs = xmalloc_or_abort((size_t)size * sizeof(int));
  for (int r = 0; r < size; r++) {
    counts[r] = v ? (r % 3) * count : count;
    displs[r] = total + (v ? 1 : 0);
    total += counts[r] + (v ? 1 : 0);
  }
  int *snd = xmalloc_or_abort((size_t)counts[me] * sizeof(int) + 4);
  int *a = xmalloc_or_abort((size_t)total * sizeof(int) + 4), *b = xmalloc_or_abort((size_t)total * sizeof(int) + 4);
  for (int i = 0; i < counts[me]; i++) snd[i] = val(me, i);
  for (int i = 0; i < total; i++) a[i] = b[i] = -3;
  if (in_place && me == root)
    for (int i = 0; i < counts[me]; i++) a[displs[me] + i] = b[displs[me] + i] = val(me, i);
  const void *sb = in_place && me == root ? MPI_IN_PLACE : snd;
  MPI_Request r;
  if (v) {
    MPI_Gatherv(sb, counts[me], MPI_INT, b, counts, displs, MPI_INT, root, MPI_COMM_WORLD);
    MPI_Igatherv(sb, counts[me], MPI_INT, a, counts, displs, MPI_INT, root, MPI_COMM_WORLD, &r);
  } else {
    MPI_Gather(sb, count, MPI_INT, b, count, MPI_INT, root, MPI_COMM_WORLD);
    MPI_Igather(sb, count, MPI_INT, a, count, MPI_INT, root, MPI_COMM_WORLD, &r);
  }
  finish(c, &r);
  int bad = 0;
  for (int q = 0; q < size && me == root; q++)
    for (int i = 0; i < counts[q]; i++) bad |= b[displs[q] + i] != val(q, i);
  MCHECK(c->t, !bad, "gather%s of %d to %d: a wrong element", v ? "v" : "", count, root);
  same(c, v ? "igatherv" : "igather", a, b, (size_t)total * sizeof(int), 0);
  /* and back: scatter(v) of what was gathered */
  int *sa = xmalloc_or_abort((size_t)counts[me] * sizeof(int) + 4), *sbk = xmalloc_or_abort((size_t)counts[me] * sizeof(int) + 4);
  for (int i = 0; i < counts[me]; i++) sa[i] = sbk[i] = -4;
  void *ra = in_place && me == root ? MPI_IN_PLACE : sa, *rb = in_place && me == root ? MPI_IN_PLACE : sbk;
  if (v) {
    MPI_Scatterv(b, counts, displs, MPI_INT, rb, counts[me], MPI_INT, root, MPI_COMM_WORLD);
    MPI_Iscatterv(b, counts, displs, MPI_INT, ra, counts[me], MPI_INT, root, MPI_COMM_WORLD, &r);
  } else {
    MPI_Scatter(b, count, MPI_INT, rb, count, MPI_INT, root, MPI_COMM_WORLD);
    MPI_Iscatter(b, count, MPI_INT, ra, count, MPI_INT, root, MPI_COMM_WORLD, &r);
  }
  finish(c, &r);
  bad = 0;
  for (int i = 0; i < counts[me] && !(in_place && me == root); i++) bad |= sbk[i] != val(me, i);
  MCHECK(c->t, !bad, "scatter%s of %d from %d: a wrong element", v ? "v" : "", count, root);
  same(c, v ? "iscatterv" : "iscatter", sa, sbk, (size_t)counts[me] * sizeof(int), 0);
  free(counts), free(displs), free(snd), free(a), free(b), free(sa), free(sbk);
}

static void allgathers(ctx *c, int count, int in_place, int v) {
  int me = c->t->rank, size = c->t->size, total = 0;
  int *counts = xmalloc_or_abort((size_t)size * sizeof(int)), *displs = xmalloc_or_abort((size_t)size * sizeof(int));
  for (int r = 0; r < size; r++) {
    counts[r] = v ? ((r + 1) % 3) * count : count;
    displs[r] = total;
    total += counts[r];
  }
  int *snd = xmalloc_or_abort((size_t)counts[me] * sizeof(int) + 4);
  int *a = xmalloc_or_abort((size_t)total * sizeof(int) + 4), *b = xmalloc_or_abort((size_t)total * sizeof(int) + 4);
  for (int i = 0; i < counts[me]; i++) snd[i] = val(me, i);
  for (int i = 0; i < total; i++) a[i] = b[i] = -3;
  if (in_place)
    for (int i = 0; i < counts[me]; i++) a[displs[me] + i] = b[displs[me] + i] = val(me, i);
  const void *sb = in_place ? MPI_IN_PLACE : snd;
  MPI_Request r;
  if (v) {
    MPI_Allgatherv(sb, counts[me], MPI_INT, b, counts, displs, MPI_INT, MPI_COMM_WORLD);
    MPI_Iallgatherv(sb, counts[me], MPI_INT, a, counts, displs, MPI_INT, MPI_COMM_WORLD, &r);
  } else {
    MPI_Allgather(sb, count, MPI_INT, b, count, MPI_INT, MPI_COMM_WORLD);
    MPI_Iallgather(sb, count, MPI_INT, a, count, MPI_INT, MPI_COMM_WORLD, &r);
  }
  finish(c, &r);
  int bad = 0;
  for (int q = 0; q < size; q++)
    for (int i = 0; i < counts[q]; i++) bad |= b[displs[q] + i] != val(q, i);
  MCHECK(c->t, !bad, "allgather%s of %d: a wrong element", v ? "v" : "", count);
  same(c, v ? "iallgatherv" : "iallgather", a, b, (size_t)total * sizeof(int), 0);
  free(counts), free(displs), free(snd), free(a), free(b);
}

/* Alltoall, alltoallv (uneven counts) and alltoallw (each block its own
 * type: ints or doubles by the pair's parity, byte displacements). */
static void alltoalls(ctx *c, int count, int in_place, int kind) {
  int me = c->t->rank, size = c->t->size;
  int *sc = xmalloc_or_abort((size_t)size * sizeof(int)), *sd = xmalloc_or_abort((size_t)size * sizeof(int));
  int *rcn = xmalloc_or_abort((size_t)size * sizeof(int)), *rd = xmalloc_or_abort((size_t)size * sizeof(int));
  MPI_Datatype *st = xmalloc_or_abort((size_t)size * sizeof *st), *rt = xmalloc_or_abort((size_t)size * sizeof *rt);
  int stot = 0, rtot = 0, unit = kind == 2 ? 8 : 4;   /* in bytes; alltoallw's room fits a double */
  for (int q = 0; q < size; q++) {
    int dbl = kind == 2 && (me + q) % 2;
    /* what me sends to q equals what q receives from me (symmetric, as
     * MPI_IN_PLACE needs) */
    sc[q] = rcn[q] = kind == 0 ? count : ((me + q) % 3) * count;
    st[q] = rt[q] = dbl ? MPI_DOUBLE : MPI_INT;
    sd[q] = kind == 2 ? stot : stot / (int)sizeof(int);
    rd[q] = kind == 2 ? rtot : rtot / (int)sizeof(int);
    stot += sc[q] * unit;
    rtot += rcn[q] * unit;
  }
  char *snd = xmalloc_or_abort((size_t)stot + 8), *a = xmalloc_or_abort((size_t)rtot + 8),
       *b = xmalloc_or_abort((size_t)rtot + 8);
  memset(a, 0x5a, (size_t)rtot + 8);
  memset(b, 0x5a, (size_t)rtot + 8);
  /* rank me's block for q: element i is val(me * 100 + q, i) */
  for (int q = 0; q < size; q++) {
    char *dst = in_place ? a : snd;
    int off = kind == 2 ? (in_place ? rd[q] : sd[q]) : (in_place ? rd[q] : sd[q]) * (int)sizeof(int);
    for (int i = 0; i < sc[q]; i++) {
      if (st[q] == MPI_DOUBLE)
        ((double *)(void *)(dst + off))[i] = dval(me * 100 + q, i);
      else
        ((int *)(void *)(dst + off))[i] = val(me * 100 + q, i);
    }
  }
  if (in_place) memcpy(b, a, (size_t)rtot);
  const void *sb = in_place ? MPI_IN_PLACE : snd;
  MPI_Request r;
  if (kind == 0) {
    MPI_Alltoall(sb, count, MPI_INT, b, count, MPI_INT, MPI_COMM_WORLD);
    MPI_Ialltoall(sb, count, MPI_INT, a, count, MPI_INT, MPI_COMM_WORLD, &r);
  } else if (kind == 1) {
    MPI_Alltoallv(sb, sc, sd, MPI_INT, b, rcn, rd, MPI_INT, MPI_COMM_WORLD);
    MPI_Ialltoallv(sb, sc, sd, MPI_INT, a, rcn, rd, MPI_INT, MPI_COMM_WORLD, &r);
  } else {
    MPI_Alltoallw(sb, sc, sd, st, b, rcn, rd, rt, MPI_COMM_WORLD);
    MPI_Ialltoallw(sb, sc, sd, st, a, rcn, rd, rt, MPI_COMM_WORLD, &r);
  }
  finish(c, &r);
  int bad = 0;
  for (int q = 0; q < size; q++) {
    int off = kind == 2 ? rd[q] : rd[q] * (int)sizeof(int);
    for (int i = 0; i < rcn[q]; i++) {
      if (rt[q] == MPI_DOUBLE)
        bad |= ((double *)(void *)(b + off))[i] != dval(q * 100 + me, i);
      else
        bad |= ((int *)(void *)(b + off))[i] != val(q * 100 + me, i);
    }
  }
  static const char *const names[] = {"alltoall", "alltoallv", "alltoallw"};
  MCHECK(c->t, !bad, "%s of %d%s: a wrong element", names[kind], count, in_place ? " in place" : "");
  same(c, names[kind], a, b, (size_t)rtot, 0);
  free(sc), free(sd), free(rcn), free(rd), free(st), free(rt), free(snd), free(a), free(b);
}

/* ==== reductions ========================================================== */

/* Rank r's double i: mixed signs and exponents, so that the order of the
 * additions shows in the result. */
static double xv(int r, int i) {
  double m = 1.0 + (double)(((long long)r * 7919 + (long long)i * 104729) % 1000) / 1000.0;
  return ((r + i) % 2 ? -1 : 1) * ldexp(m, (r * 31 + i * 17) % 41 - 20);
}

enum { K_INT, K_DBL, K_MAT };

/* One reduction, blocking and not: which 0 reduce, 1 allreduce, 2 scan,
 * 3 exscan, 4 reduce_scatter_block, 5 reduce_scatter. */
static void reduction(ctx *c, int which, int count, int kind, int root, int in_place, MPI_Op matop,
                      MPI_Datatype m4) {
  int me = c->t->rank, size = c->t->size, total = 0;
  int *rcounts = xmalloc_or_abort((size_t)size * sizeof(int));
  for (int r = 0; r < size; r++) rcounts[r] = which == 5 ? (r % 2 ? 2 * count : 0) : count;
  for (int r = 0; r < size; r++) total += rcounts[r];
  if (which < 4) total = count;
  int mine = which >= 4 ? rcounts[me] : count;
  size_t esz = kind == K_INT ? sizeof(int) : kind == K_DBL ? sizeof(double) : 4 * sizeof(int);
  MPI_Datatype dt = kind == K_INT ? MPI_INT : kind == K_DBL ? MPI_DOUBLE : m4;
  MPI_Op op = kind == K_MAT ? matop : MPI_SUM;
  char *in = xmalloc_or_abort((size_t)total * esz + 8), *a = xmalloc_or_abort((size_t)total * esz + 8),
       *b = xmalloc_or_abort((size_t)total * esz + 8);
  for (int i = 0; i < total; i++) {
    if (kind == K_INT) ((int *)(void *)in)[i] = val(me, i);
    else if (kind == K_DBL) ((double *)(void *)in)[i] = xv(me, i);
    else mat(me, i, (int *)(void *)in + 4 * i);
  }
  memset(a, 0x33, (size_t)total * esz + 8);
  memset(b, 0x33, (size_t)total * esz + 8);
  int ip = in_place && (which != 0 || me == root);
  if (ip) {
    memcpy(a, in, (size_t)total * esz);
    memcpy(b, in, (size_t)total * esz);
  }
  const void *sb = ip ? MPI_IN_PLACE : in;
  MPI_Request r;
  switch (which) {
  case 0:
    MPI_Reduce(sb, b, count, dt, op, root, MPI_COMM_WORLD);
    MPI_Ireduce(sb, a, count, dt, op, root, MPI_COMM_WORLD, &r);
    break;
  case 1:
    MPI_Allreduce(sb, b, count, dt, op, MPI_COMM_WORLD);
    MPI_Iallreduce(sb, a, count, dt, op, MPI_COMM_WORLD, &r);
    break;
  case 2:
    MPI_Scan(sb, b, count, dt, op, MPI_COMM_WORLD);
    MPI_Iscan(sb, a, count, dt, op, MPI_COMM_WORLD, &r);
    break;
  case 3:
    MPI_Exscan(sb, b, count, dt, op, MPI_COMM_WORLD);
    MPI_Iexscan(sb, a, count, dt, op, MPI_COMM_WORLD, &r);
    break;
  case 4:
    MPI_Reduce_scatter_block(sb, b, count, dt, op, MPI_COMM_WORLD);
    MPI_Ireduce_scatter_block(sb, a, count, dt, op, MPI_COMM_WORLD, &r);
    break;
  default:
    MPI_Reduce_scatter(sb, b, rcounts, dt, op, MPI_COMM_WORLD);
    MPI_Ireduce_scatter(sb, a, rcounts, dt, op, MPI_COMM_WORLD, &r);
    break;
  }
  finish(c, &r);
  /* the blocking result against the serial one: ranks lo..hi-1 combined */
  int lo = 0, hi = size, off = 0, n = which >= 4 ? mine : count, check = !(which == 0 && me != root);
  if (which == 2) hi = me + 1;
  if (which == 3) hi = me, check = me > 0;
  if (which >= 4)
    for (int q = 0; q < me; q++) off += rcounts[q];
  int bad = 0;
  for (int i = 0; i < n && check; i++) {
    int e = off + i;
    if (kind == K_INT) {
      unsigned s = 0;
      for (int q = lo; q < hi; q++) s += (unsigned)val(q, e);
      bad |= ((int *)(void *)b)[i] != (int)s;
    } else if (kind == K_DBL) {
      double s = 0, m = 0;
      for (int q = lo; q < hi; q++) s += xv(q, e), m = fmax(m, fabs(xv(q, e)));
      bad |= fabs(((double *)(void *)b)[i] - s) > 1e-12 * m * size;
    } else {
      int p[4];
      matprod(lo, hi, e, p);
      bad |= memcmp((int *)(void *)b + 4 * i, p, sizeof p) != 0;
    }
  }
  static const char *const names[] = {"reduce", "allreduce", "scan", "exscan", "reduce_scatter_block",
                                      "reduce_scatter"};
  static const char *const kinds[] = {"ints", "doubles", "matrices"};
  MCHECK(c->t, !bad, "%s of %d %s%s: a wrong element", names[which], count, kinds[kind], ip ? " in place" : "");
  if (check) same(c, names[which], a, b, (size_t)n * esz, kind == K_DBL);
  else MCHECK(c->t, 1, "nothing to compare");
  free(rcounts), free(in), free(a), free(b);
}

/* Two nonblocking collectives at once on one communicator, completed in the
 * other order, then a barrier overlapped with a blocking allreduce. */
static void overlapped(ctx *c) {
  int me = c->t->rank, size = c->t->size, x = me == size - 1 ? 7 : 0, sum = 0, sum2 = 0;
  MPI_Request r[3];
  MPI_Ibcast(&x, 1, MPI_INT, size - 1, MPI_COMM_WORLD, &r[0]);
  MPI_Iallreduce(&me, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD, &r[1]);
  MPI_Wait(&r[1], MPI_STATUS_IGNORE);
  MPI_Wait(&r[0], MPI_STATUS_IGNORE);
  MPI_Ibarrier(MPI_COMM_WORLD, &r[2]);
  MPI_Allreduce(&me, &sum2, 1, MPI_INT, MPI_SUM, c->other);
  MPI_Wait(&r[2], MPI_STATUS_IGNORE);
  MCHECK(c->t, x == 7 && sum == size * (size - 1) / 2 && sum2 == sum, "overlapped: x %d sum %d sum2 %d", x, sum, sum2);
}

/* Every nonblocking collective, at sizes that pick each algorithm. */
static void nonblocking(mtest *t) {
  ctx c = {t, MPI_COMM_NULL, 0};
  MPI_Comm_dup(MPI_COMM_WORLD, &c.other);
  int size = t->size, roots[2] = {0, size - 1};
  MPI_Datatype evens, m4;
  MPI_Type_create_resized(MPI_INT, 0, 2 * (MPI_Aint)sizeof(int), &evens);
  MPI_Type_commit(&evens);
  MPI_Type_contiguous(4, MPI_INT, &m4);
  MPI_Type_commit(&m4);
  MPI_Op matop;
  MPI_Op_create(matmul_fn, 0, &matop);

  MPI_Request r;
  MPI_Ibarrier(MPI_COMM_WORLD, &r);
  finish(&c, &r);
  for (int k = 0; k < 2; k++) {
    bcasts(&c, 5, roots[k], MPI_INT, 1);
    bcasts(&c, 3072, roots[k], MPI_INT, 1);   /* 12288 bytes: the long-message bcasts on 8 ranks */
    bcasts(&c, 100, roots[k], evens, 2);
    for (int v = 0; v < 2; v++) {
      gathers(&c, 3, roots[k], 0, v);
      gathers(&c, 700, roots[k], 1, v);
    }
    reduction(&c, 0, 7, K_INT, roots[k], 0, matop, m4);
    reduction(&c, 0, 600, K_DBL, roots[k], k, matop, m4);   /* 4800 bytes: Rabenseifner's */
    reduction(&c, 0, 5, K_MAT, roots[k], 0, matop, m4);
  }
  bcasts(&c, 140000, size / 2, MPI_INT, 1);   /* 560000 bytes: scatter and ring */
  for (int v = 0; v < 2; v++) {
    allgathers(&c, 2, 0, v);
    allgathers(&c, 3000, 1, v);   /* 12000 bytes a block: on 8 ranks Bruck's, the ring beyond */
    allgathers(&c, 0, 0, v);
  }
  allgathers(&c, 20000, 0, 1);   /* the pipelined ring */
  for (int kind = 0; kind < 3; kind++) {
    alltoalls(&c, 3, 0, kind);
    alltoalls(&c, 100, 1, kind);
    alltoalls(&c, 9000, 0, kind);   /* 36000 bytes a block: pairwise */
  }
  for (int which = 1; which < 6; which++) {
    reduction(&c, which, 3, K_INT, 0, 0, matop, m4);
    reduction(&c, which, 700, K_DBL, 0, which != 3, matop, m4);
    reduction(&c, which, 4, K_MAT, 0, 0, matop, m4);
  }
  reduction(&c, 1, 70000, K_INT, 0, 0, matop, m4);   /* 280000 bytes */
  reduction(&c, 4, 20000, K_INT, 0, 0, matop, m4);   /* 80000 bytes a block: pairwise beyond 6 ranks */
  overlapped(&c);

  MPI_Op_free(&matop);
  MPI_Type_free(&m4);
  MPI_Type_free(&evens);
  MPI_Comm_free(&c.other);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {nonblocking, NULL};
  return mtest_main(&argc, &argv, "coll_nbc", 1, 0, checks);
}
