/* comm_inter.c -- intercommunicators, checked by themselves on any number of
 * ranks >= 2, for two ways of cutting MPI_COMM_WORLD in two (even and odd
 * ranks; the first third and the rest): MPI_Intercomm_create, the queries
 * (MPI_Comm_test_inter, sizes, MPI_Comm_remote_group against the world
 * ranks expected), point-to-point naming the remote group (MPI_ANY_SOURCE's
 * status included), MPI_Intercomm_merge's order, MPI_Comm_dup (its messages
 * apart from the original's), MPI_Comm_split and MPI_Comm_create on an
 * intercommunicator, MPI_Comm_compare, and every collective on it in both
 * directions (MPI_ROOT, MPI_PROC_NULL), each result computed here from the
 * other group's ranks; then intercommunicators made and freed in turn. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

/* One cut: the calling rank's color (0 or 1) and the world ranks of each
 * side, in order. */
typedef struct {
  int color;
  int n[2];
  int *w[2];
} cut;

static void cut_make(cut *c, mtest *t, int how) {
  c->n[0] = c->n[1] = 0;
  c->w[0] = malloc((size_t)t->size * sizeof(int));
  c->w[1] = malloc((size_t)t->size * sizeof(int));
  int third = t->size / 3 > 0 ? t->size / 3 : 1;
  for (int r = 0; r < t->size; r++) {
    int col = how == 0 ? r % 2 : r >= third;
    c->w[col][c->n[col]++] = r;
    if (r == t->rank) c->color = col;
  }
}

static void cut_free(cut *c) {
  free(c->w[0]);
  free(c->w[1]);
}

/* The intercommunicator of the cut: local groups by a split of the world,
 * leaders their rank 0, the peer MPI_COMM_WORLD. */
static MPI_Comm ic_make(const cut *c, mtest *t, int tag) {
  MPI_Comm local, ic;
  MPI_Comm_split(MPI_COMM_WORLD, c->color, t->rank, &local);
  MPI_Intercomm_create(local, 0, MPI_COMM_WORLD, c->w[1 - c->color][0], tag, &ic);
  MPI_Comm_free(&local);
  return ic;
}

/* A value for element i of world rank w. */
static int val(int w, int i) { return 1000 * w + i; }

/* ==== queries and point-to-point ========================================== */

static void ic_queries(mtest *t, const cut *c, MPI_Comm ic) {
  int flag = 0, size = -1, rank = -1, rsize = -1, me = c->color, other = 1 - me;
  MPI_Comm_test_inter(ic, &flag);
  MPI_Comm_size(ic, &size);
  MPI_Comm_rank(ic, &rank);
  MPI_Comm_remote_size(ic, &rsize);
  MCHECK(t, flag && size == c->n[me] && rsize == c->n[other] && c->w[me][rank] == t->rank,
         "queries: inter %d size %d rank %d remote size %d", flag, size, rank, rsize);
  MPI_Comm_test_inter(MPI_COMM_WORLD, &flag);
  MCHECK(t, !flag, "MPI_COMM_WORLD is an intercommunicator");
  /* The remote group and the local one, as world ranks. */
  MPI_Group rg, lg, wg;
  MPI_Comm_remote_group(ic, &rg);
  MPI_Comm_group(ic, &lg);
  MPI_Comm_group(MPI_COMM_WORLD, &wg);
  int bad = 0, n = -1;
  MPI_Group_size(rg, &n);
  bad += n != c->n[other];
  for (int i = 0; i < n && !bad; i++) {
    int w = -1;
    MPI_Group_translate_ranks(rg, 1, &i, wg, &w);
    bad += w != c->w[other][i];
  }
  MPI_Group_size(lg, &n);
  bad += n != c->n[me];
  for (int i = 0; i < n && !bad; i++) {
    int w = -1;
    MPI_Group_translate_ranks(lg, 1, &i, wg, &w);
    bad += w != c->w[me][i];
  }
  MCHECK(t, bad == 0, "the groups' ranks");
  MPI_Group_free(&rg);
  MPI_Group_free(&lg);
  MPI_Group_free(&wg);
}

/* Local rank i sends its world rank to remote rank i % remote size; each
 * rank takes, from MPI_ANY_SOURCE, the messages of the remote ranks j with
 * j % its group's size equal to its rank. */
static void ic_p2p(mtest *t, const cut *c, MPI_Comm ic, int tag) {
  int rank, me = c->color, other = 1 - me, ln = c->n[me], rn = c->n[other];
  MPI_Comm_rank(ic, &rank);
  MPI_Request req;
  MPI_Isend(&t->rank, 1, MPI_INT, rank % rn, tag, ic, &req);
  int bad = 0, due = 0;
  for (int j = 0; j < rn; j++) due += j % ln == rank;
  for (int k = 0; k < due; k++) {
    int w = -1;
    MPI_Status st;
    MPI_Recv(&w, 1, MPI_INT, MPI_ANY_SOURCE, tag, ic, &st);
    bad += st.MPI_SOURCE < 0 || st.MPI_SOURCE >= rn || st.MPI_SOURCE % ln != rank || c->w[other][st.MPI_SOURCE] != w;
  }
  MPI_Wait(&req, MPI_STATUS_IGNORE);
  MCHECK(t, bad == 0, "%d of %d messages from the remote group wrong", bad, due);
}

/* ==== merge, dup, split, create, compare ================================== */

static void ic_merge(mtest *t, const cut *c, MPI_Comm ic) {
  for (int high = 0; high < 2; high++) {
    /* Color `high` passes high = 1 this time: its group comes second. */
    MPI_Comm m;
    MPI_Intercomm_merge(ic, c->color == high, &m);
    int first = 1 - high, rank = -1, size = -1, bad = 0;
    MPI_Comm_rank(m, &rank);
    MPI_Comm_size(m, &size);
    int *order = malloc((size_t)t->size * sizeof *order), k = 0;
    for (int i = 0; i < c->n[first]; i++) order[k++] = c->w[first][i];
    for (int i = 0; i < c->n[1 - first]; i++) order[k++] = c->w[1 - first][i];
    bad += size != t->size || order[rank] != t->rank;
    /* Every rank's world rank in merged order, gathered. */
    int *got = malloc((size_t)t->size * sizeof *got);
    MPI_Allgather(&t->rank, 1, MPI_INT, got, 1, MPI_INT, m);
    for (int i = 0; i < t->size; i++) bad += got[i] != order[i];
    MCHECK(t, bad == 0, "merge with high on color %d: rank %d of %d", high, rank, size);
    free(order);
    free(got);
    MPI_Comm_free(&m);
  }
}

static void ic_dup(mtest *t, const cut *c, MPI_Comm ic) {
  MPI_Comm d;
  MPI_Comm_dup(ic, &d);
  int flag = 0, cmp = -1, rsize = -1;
  MPI_Comm_test_inter(d, &flag);
  MPI_Comm_remote_size(d, &rsize);
  MPI_Comm_compare(ic, d, &cmp);
  MCHECK(t, flag && rsize == c->n[1 - c->color] && cmp == MPI_CONGRUENT, "dup: inter %d remote size %d compare %d",
         flag, rsize, cmp);
  MPI_Comm_compare(ic, ic, &cmp);
  MCHECK(t, cmp == MPI_IDENT, "compare with itself: %d", cmp);
  MPI_Comm_compare(ic, MPI_COMM_WORLD, &cmp);
  MCHECK(t, cmp == MPI_UNEQUAL, "compare with the world: %d", cmp);
  /* Local rank 0 of each side sends remote rank 0 one message on the
   * original and then one on the dup; the dup's receive (from any source)
   * takes the dup's. */
  int rank;
  MPI_Comm_rank(ic, &rank);
  if (rank == 0) {
    int a = 1, b = 2, x = 0, y = 0;
    MPI_Send(&a, 1, MPI_INT, 0, 4, ic);
    MPI_Send(&b, 1, MPI_INT, 0, 4, d);
    MPI_Recv(&y, 1, MPI_INT, MPI_ANY_SOURCE, 4, d, MPI_STATUS_IGNORE);
    MPI_Recv(&x, 1, MPI_INT, MPI_ANY_SOURCE, 4, ic, MPI_STATUS_IGNORE);
    MCHECK(t, x == 1 && y == 2, "dup's messages apart: %d %d", x, y);
  }
  ic_p2p(t, c, d, 9);
  MPI_Comm_free(&d);
  MCHECK(t, d == MPI_COMM_NULL, "freed dup not nulled");
}

/* Split: color local rank % 2, key minus the local rank (the order
 * reversed); a color the other group lacks gives MPI_COMM_NULL. */
static void ic_split(mtest *t, const cut *c, MPI_Comm ic) {
  int rank, me = c->color, other = 1 - me;
  MPI_Comm_rank(ic, &rank);
  int col = rank % 2, ln = 0, lr = 0, rn = 0;
  for (int i = 0; i < c->n[me]; i++) {
    ln += i % 2 == col;
    lr += i % 2 == col && i > rank;
  }
  for (int i = 0; i < c->n[other]; i++) rn += i % 2 == col;
  MPI_Comm s;
  MPI_Comm_split(ic, col, -rank, &s);
  if (rn == 0) {
    MCHECK(t, s == MPI_COMM_NULL, "split: a color the other group lacks gave a communicator");
    if (s != MPI_COMM_NULL) MPI_Comm_free(&s);
    return;
  }
  int flag = 0, size = -1, r = -1, rsize = -1;
  MPI_Comm_test_inter(s, &flag);
  MPI_Comm_size(s, &size);
  MPI_Comm_rank(s, &r);
  MPI_Comm_remote_size(s, &rsize);
  MCHECK(t, flag && size == ln && r == lr && rsize == rn, "split: inter %d size %d (%d) rank %d (%d) remote %d (%d)",
         flag, size, ln, r, lr, rsize, rn);
  /* Remote rank 0 of the split is the other group's last rank of the color. */
  int last = -1;
  for (int i = 0; i < c->n[other]; i++)
    if (i % 2 == col) last = c->w[other][i];
  int w = -1;
  if (r == 0) MPI_Send(&t->rank, 1, MPI_INT, 0, 2, s);
  if (r == 0) MPI_Recv(&w, 1, MPI_INT, 0, 2, s, MPI_STATUS_IGNORE);
  MCHECK(t, r != 0 || w == last, "split: remote rank 0 is world rank %d (%d due)", w, last);
  MPI_Comm_free(&s);
}

/* Create: each group passes its first half (rounded up). */
static void ic_create(mtest *t, const cut *c, MPI_Comm ic) {
  int rank, me = c->color, other = 1 - me;
  MPI_Comm_rank(ic, &rank);
  MPI_Group lg, half;
  MPI_Comm_group(ic, &lg);
  int range[1][3] = {{0, (c->n[me] + 1) / 2 - 1, 1}};
  MPI_Group_range_incl(lg, 1, range, &half);
  MPI_Comm s;
  MPI_Comm_create(ic, half, &s);
  if (rank >= (c->n[me] + 1) / 2) {
    MCHECK(t, s == MPI_COMM_NULL, "create: a rank outside the group got a communicator");
  } else {
    int size = -1, rsize = -1, r = -1;
    MPI_Comm_size(s, &size);
    MPI_Comm_rank(s, &r);
    MPI_Comm_remote_size(s, &rsize);
    MCHECK(t, size == (c->n[me] + 1) / 2 && rsize == (c->n[other] + 1) / 2 && r == rank,
           "create: size %d remote %d rank %d", size, rsize, r);
    MPI_Comm_free(&s);
  }
  MPI_Group_free(&half);
  MPI_Group_free(&lg);
}

/* ==== collectives ========================================================= */

/* The collectives with roots: the root side is color `from`, rooted at its
 * local rank 0. */
static void ic_rooted(mtest *t, const cut *c, MPI_Comm ic, int from) {
  enum { K = 3 };
  int rank, me = c->color, other = 1 - me, root, rn = c->n[other], ln = c->n[me];
  MPI_Comm_rank(ic, &rank);
  int in_root = me == from;
  root = in_root ? (rank == 0 ? MPI_ROOT : MPI_PROC_NULL) : 0;
  int rootw = c->w[from][0], bad = 0;
  int *buf = calloc((size_t)(K * (t->size + 1) * (t->size + 1)), sizeof *buf);
  int *mine = malloc(K * (size_t)(t->size + 1) * sizeof *mine);
  int *counts = malloc(2 * (size_t)(t->size + 1) * sizeof *counts), *displs = counts + t->size + 1;
  for (int i = 0; i < K * (t->size + 1); i++) mine[i] = val(t->rank, i);
  /* Bcast: the root's K values to the other group. */
  if (root != MPI_PROC_NULL) {
    if (root == MPI_ROOT) memcpy(buf, mine, K * sizeof *buf);
    MPI_Bcast(buf, K, MPI_INT, root, ic);
    for (int i = 0; i < K; i++) bad += buf[i] != val(rootw, i);
  } else {
    MPI_Bcast(buf, K, MPI_INT, root, ic);
  }
  MCHECK(t, bad == 0, "bcast from color %d", from);
  /* Gather: K from each remote rank, in remote rank order, at the root. */
  bad = 0;
  memset(buf, 0, K * (size_t)(t->size + 1) * sizeof *buf);
  MPI_Gather(mine, K, MPI_INT, buf, K, MPI_INT, root, ic);
  if (root == MPI_ROOT)
    for (int r = 0; r < rn; r++)
      for (int i = 0; i < K; i++) bad += buf[r * K + i] != val(c->w[other][r], i);
  MCHECK(t, bad == 0, "gather to color %d", from);
  /* Gatherv: r + 1 from remote rank r, blocks two apart. */
  bad = 0;
  for (int r = 0; r < rn; r++) counts[r] = r + 1, displs[r] = r * (t->size + 2);
  memset(buf, 0, K * (size_t)(t->size + 1) * (t->size + 1) * sizeof *buf);
  MPI_Gatherv(mine, rank + 1, MPI_INT, buf, counts, displs, MPI_INT, root, ic);
  if (root == MPI_ROOT)
    for (int r = 0; r < rn; r++)
      for (int i = 0; i <= r; i++) bad += buf[displs[r] + i] != val(c->w[other][r], i);
  MCHECK(t, bad == 0, "gatherv to color %d", from);
  /* Scatter: block r of the root's to remote rank r. */
  bad = 0;
  int got[K + 2];
  MPI_Scatter(mine, K, MPI_INT, got, K, MPI_INT, root, ic);
  if (!in_root)
    for (int i = 0; i < K; i++) bad += got[i] != val(rootw, rank * K + i);
  MCHECK(t, bad == 0, "scatter from color %d", from);
  /* Scatterv: r + 1 to remote rank r, from displacement r. */
  bad = 0;
  for (int r = 0; r < ln + rn; r++) counts[r] = r + 1, displs[r] = r;
  int *vals = malloc(((size_t)t->size + 2) * sizeof *vals);
  MPI_Scatterv(mine, counts, displs, MPI_INT, vals, rank + 1, MPI_INT, root, ic);
  if (!in_root)
    for (int i = 0; i <= rank; i++) bad += vals[i] != val(rootw, rank + i);
  MCHECK(t, bad == 0, "scatterv from color %d", from);
  free(vals);
  /* Reduce: the sum and the maximum of the other group's values. */
  bad = 0;
  int sum[K], max[K];
  MPI_Reduce(mine, sum, K, MPI_INT, MPI_SUM, root, ic);
  MPI_Reduce(mine, max, K, MPI_INT, MPI_MAX, root, ic);
  if (root == MPI_ROOT)
    for (int i = 0; i < K; i++) {
      int s = 0;
      for (int r = 0; r < rn; r++) s += val(c->w[other][r], i);
      bad += sum[i] != s || max[i] != val(c->w[other][rn - 1], i);
    }
  MCHECK(t, bad == 0, "reduce to color %d", from);
  free(buf);
  free(mine);
  free(counts);
}

/* The all- ones: each group gets the other's. */
static void ic_all(mtest *t, const cut *c, MPI_Comm ic) {
  int rank, me = c->color, other = 1 - me, rn = c->n[other], ln = c->n[me], K = 2;
  MPI_Comm_rank(ic, &rank);
  size_t room = (size_t)(t->size + 2) * (t->size + 2) * 4;
  int *mine = malloc(room * sizeof *mine), *buf = malloc(room * sizeof *buf);
  int *counts = malloc(4 * (size_t)(t->size + 1) * sizeof *counts), *displs = counts + t->size + 1;
  int *scounts = displs + t->size + 1, *sdispls = scounts + t->size + 1;
  for (size_t i = 0; i < room; i++) mine[i] = val(t->rank, (int)i);
  int bad = 0;
  /* Allgather */
  MPI_Allgather(mine, K, MPI_INT, buf, K, MPI_INT, ic);
  for (int r = 0; r < rn; r++)
    for (int i = 0; i < K; i++) bad += buf[r * K + i] != val(c->w[other][r], i);
  MCHECK(t, bad == 0, "allgather");
  /* Allgatherv: remote rank r sends r + 1, placed r * (size + 1) on. */
  bad = 0;
  for (int r = 0; r < rn; r++) counts[r] = r + 1, displs[r] = r * (t->size + 1);
  MPI_Allgatherv(mine, rank + 1, MPI_INT, buf, counts, displs, MPI_INT, ic);
  for (int r = 0; r < rn; r++)
    for (int i = 0; i <= r; i++) bad += buf[displs[r] + i] != val(c->w[other][r], i);
  MCHECK(t, bad == 0, "allgatherv");
  /* Alltoall: block r of mine to remote rank r. */
  bad = 0;
  MPI_Alltoall(mine, K, MPI_INT, buf, K, MPI_INT, ic);
  for (int r = 0; r < rn; r++)
    for (int i = 0; i < K; i++) bad += buf[r * K + i] != val(c->w[other][r], rank * K + i);
  MCHECK(t, bad == 0, "alltoall");
  /* Alltoallv: rank + r + 1 elements to remote rank r, from displacement
   * r * (size + 2); received r + rank + 1 from remote rank r. */
  bad = 0;
  for (int r = 0; r < rn; r++) {
    scounts[r] = rank + r + 1, sdispls[r] = r * (t->size + 2);
    counts[r] = r + rank + 1, displs[r] = r * (t->size + 2);
  }
  MPI_Alltoallv(mine, scounts, sdispls, MPI_INT, buf, counts, displs, MPI_INT, ic);
  for (int r = 0; r < rn; r++)
    for (int i = 0; i < counts[r]; i++) bad += buf[displs[r] + i] != val(c->w[other][r], rank * (t->size + 2) + i);
  MCHECK(t, bad == 0, "alltoallv");
  /* Allreduce: the other group's sums. */
  bad = 0;
  MPI_Allreduce(mine, buf, K, MPI_INT, MPI_SUM, ic);
  for (int i = 0; i < K; i++) {
    int s = 0;
    for (int r = 0; r < rn; r++) s += val(c->w[other][r], i);
    bad += buf[i] != s;
  }
  MCHECK(t, bad == 0, "allreduce");
  /* Reduce_scatter_block: vectors of ln * rn elements; this group's
   * blocks are rn long (the other's ln). */
  bad = 0;
  MPI_Reduce_scatter_block(mine, buf, rn, MPI_INT, MPI_SUM, ic);
  for (int i = 0; i < rn; i++) {
    int s = 0;
    for (int r = 0; r < rn; r++) s += val(c->w[other][r], rank * rn + i);
    bad += buf[i] != s;
  }
  MCHECK(t, bad == 0, "reduce_scatter_block");
  /* Reduce_scatter: 2 * ln * rn elements in both groups; this group's
   * blocks are 2 * rn long, but rank 0's gives one to rank 1's. */
  bad = 0;
  for (int i = 0; i < ln; i++) counts[i] = 2 * rn;
  if (ln > 1) counts[0]--, counts[1]++;
  MPI_Reduce_scatter(mine, buf, counts, MPI_INT, MPI_SUM, ic);
  int off = 0;
  for (int i = 0; i < rank; i++) off += counts[i];
  for (int i = 0; i < counts[rank]; i++) {
    int s = 0;
    for (int r = 0; r < rn; r++) s += val(c->w[other][r], off + i);
    bad += buf[i] != s;
  }
  MCHECK(t, bad == 0, "reduce_scatter");
  /* A barrier, and the error a scan is. */
  MCHECK(t, MPI_Barrier(ic) == MPI_SUCCESS, "barrier");
  MPI_Comm_set_errhandler(ic, MPI_ERRORS_RETURN);
  int rc = MPI_Scan(mine, buf, 1, MPI_INT, MPI_SUM, ic), cls = -1;
  MPI_Error_class(rc, &cls);
  MCHECK(t, cls == MPI_ERR_COMM, "MPI_Scan on an intercommunicator gave class %d", cls);
  MPI_Comm_set_errhandler(ic, MPI_ERRORS_ARE_FATAL);
  free(mine);
  free(buf);
  free(counts);
}

/* Intercommunicators made, used and freed in turn: contexts come back. */
static void ic_many(mtest *t, const cut *c) {
  int bad = 0;
  for (int i = 0; i < 300; i++) {
    MPI_Comm ic = ic_make(c, t, 7), d;
    MPI_Comm_dup(ic, &d);
    int in = -1, rank;
    MPI_Comm_rank(d, &rank);
    if (rank == 0) {
      MPI_Sendrecv(&i, 1, MPI_INT, 0, 1, &in, 1, MPI_INT, 0, 1, d, MPI_STATUS_IGNORE);
      bad += in != i;
    }
    MPI_Comm_free(&d);
    MPI_Comm_free(&ic);
  }
  MCHECK(t, bad == 0, "%d of 300 intercommunicators carried a wrong message", bad);
}

/* Every check, on each of the two cuts. */
static void both_cuts(mtest *t) {
  for (int how = 0; how < 2; how++) {
    cut c;
    cut_make(&c, t, how);
    MPI_Comm ic = ic_make(&c, t, 10 + how);
    ic_queries(t, &c, ic);
    ic_p2p(t, &c, ic, 3);
    ic_merge(t, &c, ic);
    ic_dup(t, &c, ic);
    ic_split(t, &c, ic);
    ic_create(t, &c, ic);
    ic_rooted(t, &c, ic, 0);
    ic_rooted(t, &c, ic, 1);
    ic_all(t, &c, ic);
    if (how == 1) ic_many(t, &c);
    MPI_Comm_free(&ic);
    cut_free(&c);
  }
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {both_cuts, NULL};
  return mtest_main(&argc, &argv, "comm_inter", 2, 0, checks);
}
