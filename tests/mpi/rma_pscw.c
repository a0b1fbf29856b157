/* rma_pscw.c -- general active-target synchronisation (MPI 3.1 section
 * 11.5.2), checked by itself on any number of ranks: MPI_Win_post,
 * MPI_Win_start, MPI_Win_complete, MPI_Win_wait and MPI_Win_test between
 * neighbours of a ring (puts and gets both ways, several epochs in a row);
 * an access epoch begun before the target's exposure (MPI_Win_start does not
 * wait for the post: even ranks start first, odd ones post first); every
 * rank accumulating into rank 0 in one epoch, rank 0 waiting with
 * MPI_Win_test; empty groups. */
#include <mpi.h>
#include <stdio.h>

#include "mtest.h"

/* The group of the given ranks of MPI_COMM_WORLD (duplicates dropped). */
static MPI_Group group_of(int n, const int *ranks) {
  MPI_Group world, g;
  int uniq[4], m = 0;
  for (int i = 0; i < n; i++) {
    int dup = 0;
    for (int j = 0; j < m; j++) dup |= uniq[j] == ranks[i];
    if (!dup) uniq[m++] = ranks[i];
  }
  MPI_Comm_group(MPI_COMM_WORLD, &world);
  MPI_Group_incl(world, m, uniq, &g);
  MPI_Group_free(&world);
  return g;
}

static void ring(mtest *t) {
  int rank = t->rank, size = t->size, right = (rank + 1) % size, left = (rank + size - 1) % size;
  int mem[8], out[2], in[2];
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  int nb[2] = {left, right};
  MPI_Group g = group_of(2, nb);
  int bad = 0;
  for (int e = 0; e < 3; e++) {
    for (int i = 0; i < 8; i++) mem[i] = 100 * e + 10 * rank + i;
    out[0] = out[1] = 1000 * e + rank;
    in[0] = in[1] = -1;
    MPI_Win_post(g, 0, win);
    MPI_Win_start(g, 0, win);
    MPI_Put(&out[0], 1, MPI_INT, right, 6, 1, MPI_INT, win);   /* my right neighbour's slot for its left */
    MPI_Put(&out[1], 1, MPI_INT, left, 7, 1, MPI_INT, win);    /* my left neighbour's slot for its right */
    MPI_Get(&in[0], 1, MPI_INT, left, 0, 1, MPI_INT, win);
    MPI_Get(&in[1], 1, MPI_INT, right, 1, 1, MPI_INT, win);
    MPI_Win_complete(win);
    MPI_Win_wait(win);
    bad += mem[6] != 1000 * e + left || mem[7] != 1000 * e + right;
    bad += in[0] != 100 * e + 10 * left || in[1] != 100 * e + 10 * right + 1;
  }
  MCHECK(t, bad == 0, "three epochs around the ring: %d wrong", bad);
  MPI_Group_free(&g);
  MPI_Win_free(&win);
}

/* Even ranks start an access epoch before they post; odd ones post first:
 * only correct if MPI_Win_start waits for nothing. */
static void ordering(mtest *t) {
  int rank = t->rank, size = t->size;
  if (size % 2) return;   /* pairs of ranks */
  int mem = -1, v = rank, peer = rank ^ 1;
  MPI_Win win;
  MPI_Win_create(&mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Group g = group_of(1, &peer);
  if (rank % 2 == 0) {
    MPI_Win_start(g, 0, win);
    MPI_Win_post(g, 0, win);
  } else {
    MPI_Win_post(g, 0, win);
    MPI_Win_start(g, 0, win);
  }
  MPI_Put(&v, 1, MPI_INT, peer, 0, 1, MPI_INT, win);
  MPI_Win_complete(win);
  MPI_Win_wait(win);
  MCHECK(t, mem == peer, "start before post: got %d, not %d", mem, peer);
  MPI_Group_free(&g);
  MPI_Win_free(&win);
}

/* Every rank adds into rank 0 in one access epoch; rank 0 tests until it
 * is done.  The count of tries depends on timing: checked once. */
static void gather_test(mtest *t) {
  int rank = t->rank, size = t->size, zero = 0;
  long mem[2] = {0, 0};
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(long), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  if (rank == 0) {
    MPI_Group world;
    MPI_Comm_group(MPI_COMM_WORLD, &world);
    MPI_Win_post(world, 0, win);
    MPI_Group_free(&world);
  }
  MPI_Group g = group_of(1, &zero);
  MPI_Win_start(g, 0, win);
  long v[2] = {rank + 1, 1};
  MPI_Accumulate(v, 2, MPI_LONG, 0, 0, 2, MPI_LONG, MPI_SUM, win);
  MPI_Win_complete(win);
  if (rank == 0) {
    int flag = 0;
    while (!flag) MPI_Win_test(win, &flag);
    MCHECK(t, mem[0] == (long)size * (size + 1) / 2 && mem[1] == size, "the sums at rank 0: %ld %ld", mem[0], mem[1]);
  }
  MPI_Group_free(&g);
  MPI_Win_free(&win);
}

/* Epochs with nobody in them end at once. */
static void empty(mtest *t) {
  int mem = 0;
  MPI_Win win;
  MPI_Win_create(&mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  int rc = MPI_Win_post(MPI_GROUP_EMPTY, 0, win);
  rc |= MPI_Win_start(MPI_GROUP_EMPTY, 0, win);
  rc |= MPI_Win_complete(win);
  int flag = 0;
  rc |= MPI_Win_test(win, &flag);
  MCHECK(t, rc == MPI_SUCCESS && flag, "empty groups: %d, flag %d", rc, flag);
  MPI_Win_free(&win);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {ring, ordering, gather_test, empty, NULL};
  return mtest_main(&argc, &argv, "rma_pscw", 1, 0, checks);
}
