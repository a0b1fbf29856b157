/* topo_neighbor.c -- the neighbourhood collectives, blocking and nonblocking, on a Cartesian
 * grid (a periodic dimension and a non-periodic one, so that some neighbours are
 * MPI_PROC_NULL: their blocks must stay as they were), a graph and a distributed graph:
 * MPI_Neighbor_allgather(v) and MPI_Neighbor_alltoall(v,w) (alltoallw with ints to some
 * neighbours and doubles to others), each block against the value its neighbour computes for
 * it, and each MPI_Ineighbor_* against its blocking form.  The neighbour lists have no rank
 * twice (MPI leaves the pairing of a repeated neighbour's messages to their order).  Plain MPI
 * C (mtest.h): the same "topo_neighbor: P passed, F failed" line under Open MPI and tilesim. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "colldata.h"
#include "mtest.h"

/* A topology's neighbours of this rank: sources and destinations. */
typedef struct {
  const char *name;
  MPI_Comm comm;
  int in, out, src[4], dst[4];
} topo;

/* Rank r's value i for neighbour d (alltoall) or for all (allgather: d -1). */
static int v(int r, int d, int i) { return val(r * 64 + d + 1, i); }

static int sentinel(int k, int i) { return -1000 - 17 * k - i; }

/* The neighbours a topology has, as the program set them up. */
static void cart(mtest *t, topo *tp) {
  int d[2] = {0, 0}, me = t->rank;
  MPI_Dims_create(t->size, 2, d);
  int periods[2] = {d[0] >= 3, 0};   /* periodic only where no rank is both neighbours */
  MPI_Cart_create(MPI_COMM_WORLD, 2, d, periods, 0, &tp->comm);
  tp->name = "a Cartesian grid";
  tp->in = tp->out = 4;
  for (int dim = 0; dim < 2; dim++) MPI_Cart_shift(tp->comm, dim, 1, &tp->src[2 * dim], &tp->src[2 * dim + 1]);
  memcpy(tp->dst, tp->src, sizeof tp->src);
  (void)me;
}

/* Up to n ranks of list, each once, in order. */
static int dedup(int *list, int n) {
  int k = 0;
  for (int i = 0; i < n; i++) {
    int seen = 0;
    for (int j = 0; j < k; j++) seen |= list[j] == list[i];
    if (!seen) list[k++] = list[i];
  }
  return k;
}

static void graph(mtest *t, topo *tp) {
  int n = t->size, *index = malloc((size_t)n * sizeof *index), *edges = malloc(2 * (size_t)n * sizeof *edges), ne = 0;
  for (int i = 0; i < n; i++) {
    int nb[2] = {(i + n - 1) % n, (i + 1) % n}, k = n > 1 ? dedup(nb, 2) : 0;
    memcpy(edges + ne, nb, (size_t)k * sizeof *nb);
    ne += k;
    index[i] = ne;
  }
  MPI_Graph_create(MPI_COMM_WORLD, n, index, edges, 0, &tp->comm);
  tp->name = "a graph";
  int lo = t->rank ? index[t->rank - 1] : 0;
  tp->in = tp->out = index[t->rank] - lo;
  memcpy(tp->src, edges + lo, (size_t)tp->in * sizeof *edges);
  memcpy(tp->dst, tp->src, sizeof tp->src);
  free(index);
  free(edges);
}

static void dist(mtest *t, topo *tp) {
  int me = t->rank, n = t->size;
  int s[2] = {(me + n - 1) % n, (me + 2) % n}, d[2] = {(me + 1) % n, (me + 2 * n - 2) % n};
  tp->in = dedup(s, 2);
  tp->out = dedup(d, 2);
  memcpy(tp->src, s, sizeof s);
  memcpy(tp->dst, d, sizeof d);
  int *volatile unw = MPI_UNWEIGHTED;   /* not a constant: GCC's -Wstringop-overread reads one as an array */
  MPI_Dist_graph_create_adjacent(MPI_COMM_WORLD, tp->in, s, unw, tp->out, d, unw, MPI_INFO_NULL, 0, &tp->comm);
  tp->name = "a distributed graph";
}

/* The rank's recorded neighbours against the topology's own answer. */
static void neighbours_are(mtest *t, const topo *tp) {
  int status, ok = 1;
  MPI_Topo_test(tp->comm, &status);
  if (status == MPI_DIST_GRAPH) {
    int in, out, w, s[4], d[4], *volatile unw = MPI_UNWEIGHTED;
    MPI_Dist_graph_neighbors_count(tp->comm, &in, &out, &w);
    MPI_Dist_graph_neighbors(tp->comm, 4, s, unw, 4, d, unw);
    ok = in == tp->in && out == tp->out && !memcmp(s, tp->src, (size_t)in * sizeof *s) &&
         !memcmp(d, tp->dst, (size_t)out * sizeof *d);
  }
  MCHECK(t, ok, "%s: its neighbours", tp->name);
}

/* ==== the collectives ===================================================== */

static void allgathers(mtest *t, const topo *tp, int count, int vee) {
  int me = t->rank, bad = 0, cnt[4], disp[4], total = 0;
  for (int k = 0; k < tp->in; k++) {
    int s = tp->src[k];
    cnt[k] = vee ? (s == MPI_PROC_NULL ? 2 : count + s % 3) : count;
    disp[k] = total + (vee ? 1 : 0);
    total = disp[k] + cnt[k];
  }
  int mine = vee ? count + me % 3 : count;
  int *snd = xmalloc_or_abort((size_t)mine * sizeof(int) + 4);
  int *a = xmalloc_or_abort((size_t)total * sizeof(int) + 4), *b = xmalloc_or_abort((size_t)total * sizeof(int) + 4);
  for (int i = 0; i < mine; i++) snd[i] = v(me, -1, i);
  for (int i = 0; i < total; i++) a[i] = b[i] = sentinel(0, i);
  MPI_Request r;
  if (vee) {
    MPI_Neighbor_allgatherv(snd, mine, MPI_INT, b, cnt, disp, MPI_INT, tp->comm);
    MPI_Ineighbor_allgatherv(snd, mine, MPI_INT, a, cnt, disp, MPI_INT, tp->comm, &r);
  } else {
    MPI_Neighbor_allgather(snd, count, MPI_INT, b, count, MPI_INT, tp->comm);
    MPI_Ineighbor_allgather(snd, count, MPI_INT, a, count, MPI_INT, tp->comm, &r);
  }
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  for (int k = 0; k < tp->in; k++) {
    int s = tp->src[k];
    for (int i = 0; i < cnt[k]; i++) bad += b[disp[k] + i] != (s == MPI_PROC_NULL ? sentinel(0, disp[k] + i) : v(s, -1, i));
  }
  MCHECK(t, !bad, "neighbor_allgather%s of %d on %s: %d elements wrong", vee ? "v" : "", count, tp->name, bad);
  MCHECK(t, !memcmp(a, b, (size_t)total * sizeof(int)), "ineighbor_allgather%s of %d on %s: not the blocking result",
         vee ? "v" : "", count, tp->name);
  free(snd), free(a), free(b);
}

/* alltoall (kind 0), alltoallv (1), alltoallw (2: doubles to and from the
 * neighbours whose rank has this rank's parity). */
static void alltoalls(mtest *t, const topo *tp, int count, int kind) {
  int me = t->rank, bad = 0, sc[4], rc[4], sd[4], rd[4], stot = 0, rtot = 0;
  MPI_Aint sdb[4], rdb[4];
  MPI_Datatype st[4], rt[4];
  for (int l = 0; l < tp->out; l++) {   /* 8 bytes of room an element */
    int d = tp->dst[l];
    sc[l] = kind == 0 ? count : count + (d < 0 ? 0 : (me + d) % 3);
    st[l] = kind == 2 && d >= 0 && (me + d) % 2 == 0 ? MPI_DOUBLE : MPI_INT;
    sd[l] = stot / 4;
    sdb[l] = stot;
    stot += (kind == 0 ? count : sc[l]) * 8;
  }
  for (int k = 0; k < tp->in; k++) {
    int s = tp->src[k];
    rc[k] = kind == 0 ? count : count + (s < 0 ? 0 : (me + s) % 3);
    rt[k] = kind == 2 && s >= 0 && (me + s) % 2 == 0 ? MPI_DOUBLE : MPI_INT;
    rd[k] = rtot / 4;
    rdb[k] = rtot;
    rtot += (kind == 0 ? count : rc[k]) * 8;
  }
  if (kind == 0) {   /* alltoall: blocks back to back */
    for (int l = 0; l < tp->out; l++) sd[l] = l * count, sdb[l] = (MPI_Aint)l * count * 4;
    for (int k = 0; k < tp->in; k++) rd[k] = k * count, rdb[k] = (MPI_Aint)k * count * 4;
  }
  char *snd = xmalloc_or_abort((size_t)stot + 8), *a = xmalloc_or_abort((size_t)rtot + 8), *b = xmalloc_or_abort((size_t)rtot + 8);
  for (int l = 0; l < tp->out; l++)
    for (int i = 0; i < sc[l]; i++) {
      if (st[l] == MPI_DOUBLE) ((double *)(void *)(snd + sdb[l]))[i] = (double)v(me, tp->dst[l], i);
      else ((int *)(void *)(snd + sdb[l]))[i] = v(me, tp->dst[l], i);
    }
  for (int i = 0; i < rtot / 4; i++) ((int *)(void *)a)[i] = ((int *)(void *)b)[i] = sentinel(1, i);
  MPI_Request r;
  if (kind == 0) {
    MPI_Neighbor_alltoall(snd, count, MPI_INT, b, count, MPI_INT, tp->comm);
    MPI_Ineighbor_alltoall(snd, count, MPI_INT, a, count, MPI_INT, tp->comm, &r);
  } else if (kind == 1) {
    MPI_Neighbor_alltoallv(snd, sc, sd, MPI_INT, b, rc, rd, MPI_INT, tp->comm);
    MPI_Ineighbor_alltoallv(snd, sc, sd, MPI_INT, a, rc, rd, MPI_INT, tp->comm, &r);
  } else {
    MPI_Neighbor_alltoallw(snd, sc, sdb, st, b, rc, rdb, rt, tp->comm);
    MPI_Ineighbor_alltoallw(snd, sc, sdb, st, a, rc, rdb, rt, tp->comm, &r);
  }
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  for (int k = 0; k < tp->in; k++) {
    int s = tp->src[k];
    for (int i = 0; i < rc[k]; i++) {
      if (s == MPI_PROC_NULL) {
        bad += rt[k] == MPI_INT && ((int *)(void *)(b + rdb[k]))[i] != sentinel(1, (int)(rdb[k] / 4) + i);
      } else if (rt[k] == MPI_DOUBLE) {
        bad += ((double *)(void *)(b + rdb[k]))[i] != (double)v(s, me, i);
      } else {
        bad += ((int *)(void *)(b + rdb[k]))[i] != v(s, me, i);
      }
    }
  }
  static const char *const names[] = {"alltoall", "alltoallv", "alltoallw"};
  MCHECK(t, !bad, "neighbor_%s of %d on %s: %d elements wrong", names[kind], count, tp->name, bad);
  MCHECK(t, !memcmp(a, b, (size_t)rtot), "ineighbor_%s of %d on %s: not the blocking result", names[kind], count,
         tp->name);
  free(snd), free(a), free(b);
}

/* The neighbourhood collectives on each kind of topology, at three counts. */
static void each_topology(mtest *t) {
  void (*make[3])(mtest *, topo *) = {cart, graph, dist};
  for (int m = 0; m < 3; m++) {
    topo tp;
    memset(&tp, 0, sizeof tp);
    make[m](t, &tp);
    neighbours_are(t, &tp);
    for (int c = 0; c < 3; c++) {
      int count = c == 0 ? 1 : c == 1 ? 7 : 3000;
      allgathers(t, &tp, count, 0);
      allgathers(t, &tp, count, 1);
      for (int kind = 0; kind < 3; kind++) alltoalls(t, &tp, count, kind);
    }
    MPI_Comm_free(&tp.comm);
  }
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {each_topology, NULL};
  return mtest_main(&argc, &argv, "topo_neighbor", 1, 0, checks);
}
