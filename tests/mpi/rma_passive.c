/* rma_passive.c -- passive-target synchronisation (MPI 3.1 section 11.5.3)
 * and the request-based operations (11.3.5), checked by themselves on any
 * number of ranks: a counter at rank 0 behind an exclusive lock (every
 * value fetched exactly once); shared locks read at once; a mutex made of
 * MPI_Compare_and_swap guarding a read-modify-write of plain puts and gets;
 * MPI_Win_lock_all with MPI_Win_flush, _flush_all, _flush_local and
 * _flush_local_all; MPI_Win_lock with MPI_MODE_NOCHECK; MPI_Rput, MPI_Rget,
 * MPI_Raccumulate and MPI_Rget_accumulate completed by MPI_Wait, MPI_Waitall
 * and MPI_Test; a flag polled with MPI_Win_sync in a shared window. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

#include "mtest.h"

enum { STEPS = 5 };

/* Each rank takes the counter STEPS times: the values fetched, gathered at
 * rank 0, are 0 .. size * STEPS - 1, each once. */
static void counter(mtest *t) {
  int rank = t->rank, size = t->size;
  long *c, one = 1, got[STEPS];
  MPI_Win win;
  MPI_Win_allocate(rank == 0 ? (MPI_Aint)sizeof(long) : 0, sizeof(long), MPI_INFO_NULL, MPI_COMM_WORLD, &c, &win);
  if (rank == 0) {
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, win);
    *c = 0;
    MPI_Win_unlock(0, win);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  for (int s = 0; s < STEPS; s++) {
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, win);
    MPI_Fetch_and_op(&one, &got[s], MPI_LONG, 0, 0, MPI_SUM, win);
    MPI_Win_unlock(0, win);
  }
  long *all = malloc((size_t)size * STEPS * sizeof *all);
  MPI_Allgather(got, STEPS, MPI_LONG, all, STEPS, MPI_LONG, MPI_COMM_WORLD);
  char *seen = calloc((size_t)size * STEPS, 1);
  int bad = 0;
  for (int i = 0; i < size * STEPS; i++) {
    if (all[i] < 0 || all[i] >= size * STEPS || seen[all[i]])
      bad++;
    else
      seen[all[i]] = 1;
  }
  MCHECK(t, bad == 0, "the counter's values: %d repeated or out of range", bad);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, win);
    MCHECK(t, *c == (long)size * STEPS, "the counter ends at %ld", *c);
    MPI_Win_unlock(0, win);
  }
  free(seen);
  free(all);
  MPI_Win_free(&win);
}

/* A mutex at rank 0: 0 free, else the holder's rank + 1.  Inside it each
 * rank reads a total with MPI_Get, adds its part, writes it back with
 * MPI_Put: no update is lost. */
static void mutex(mtest *t) {
  int rank = t->rank, size = t->size;
  long mem[2] = {0, 0};
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(long), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Win_lock_all(0, win);
  long me = rank + 1, zero = 0, was, total;
  for (int s = 0; s < STEPS; s++) {
    do {
      MPI_Compare_and_swap(&me, &zero, &was, MPI_LONG, 0, 0, win);
      MPI_Win_flush(0, win);
    } while (was != 0);
    MPI_Get(&total, 1, MPI_LONG, 0, 1, 1, MPI_LONG, win);
    MPI_Win_flush(0, win);
    total += rank + 1;
    MPI_Put(&total, 1, MPI_LONG, 0, 1, 1, MPI_LONG, win);
    MPI_Win_flush(0, win);
    MPI_Compare_and_swap(&zero, &me, &was, MPI_LONG, 0, 0, win);   /* release */
    MPI_Win_flush(0, win);
  }
  MPI_Win_unlock_all(win);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) MCHECK(t, mem[1] == (long)STEPS * size * (size + 1) / 2 && mem[0] == 0, "the guarded total %ld", mem[1]);
  MPI_Win_free(&win);
}

/* lock_all, puts to every rank, the flushes, gets back; shared locks. */
static void flushes(mtest *t) {
  int rank = t->rank, size = t->size;
  int *mem = calloc((size_t)size, sizeof *mem), *back = calloc((size_t)size, sizeof *back);
  MPI_Win win;
  MPI_Win_create(mem, (MPI_Aint)size * (MPI_Aint)sizeof(int), sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Win_lock_all(0, win);
  int v = 7 * rank + 1;
  for (int q = 0; q < size; q++) {
    MPI_Put(&v, 1, MPI_INT, q, rank, 1, MPI_INT, win);
    if (q % 2) MPI_Win_flush_local(q, win);   /* v may be reused: not changed here */
  }
  MPI_Win_flush_local_all(win);
  MPI_Win_flush_all(win);
  MPI_Win_unlock_all(win);
  MPI_Barrier(MPI_COMM_WORLD);   /* every rank's puts done */
  MPI_Win_lock_all(MPI_MODE_NOCHECK, win);
  for (int q = 0; q < size; q++) {
    MPI_Get(&back[q], 1, MPI_INT, q, (rank + 1) % size, 1, MPI_INT, win);
    MPI_Win_flush(q, win);
  }
  MPI_Win_unlock_all(win);
  int bad = 0;
  for (int q = 0; q < size; q++) bad += mem[q] != 7 * q + 1 || back[q] != 7 * ((rank + 1) % size) + 1;
  MCHECK(t, bad == 0, "lock_all and flushes: %d wrong", bad);
  MPI_Barrier(MPI_COMM_WORLD);
  /* Shared locks of every rank on rank 0 at once; then an exclusive one of
   * each rank on itself that nobody else asks for (MPI_MODE_NOCHECK). */
  int first = -1;
  MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, win);
  MPI_Get(&first, 1, MPI_INT, 0, 0, 1, MPI_INT, win);
  MPI_Win_unlock(0, win);
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Win_lock(MPI_LOCK_EXCLUSIVE, rank, MPI_MODE_NOCHECK, win);
  int own = -1;
  MPI_Get(&own, 1, MPI_INT, rank, rank, 1, MPI_INT, win);
  MPI_Win_unlock(rank, win);
  MCHECK(t, first == 1 && own == 7 * rank + 1, "gets under a shared lock and a NOCHECK lock: %d %d", first, own);
  MPI_Win_free(&win);
  free(mem);
  free(back);
}

/* Request-based operations to the right neighbour. */
static void requests(mtest *t) {
  int rank = t->rank, size = t->size, right = (rank + 1) % size, left = (rank + size - 1) % size;
  int mem[8] = {0};
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Win_lock_all(0, win);
  int put[2] = {rank, rank + 100}, got[2] = {-1, -1}, acc = 5, old = -1, add = 1;
  MPI_Request q[3];
  MPI_Rput(put, 2, MPI_INT, right, 0, 2, MPI_INT, win, &q[0]);
  MPI_Wait(&q[0], MPI_STATUS_IGNORE);
  put[0] = put[1] = -9;   /* the put's data left when it completed locally */
  MPI_Raccumulate(&acc, 1, MPI_INT, right, 2, 1, MPI_INT, MPI_SUM, win, &q[0]);
  MPI_Rget_accumulate(&add, 1, MPI_INT, &old, 1, MPI_INT, right, 3, 1, MPI_INT, MPI_SUM, win, &q[1]);
  MPI_Waitall(2, q, MPI_STATUSES_IGNORE);
  MPI_Win_flush(right, win);
  MPI_Rget(got, 2, MPI_INT, right, 0, 2, MPI_INT, win, &q[2]);
  int flag = 0;
  while (!flag) MPI_Test(&q[2], &flag, MPI_STATUS_IGNORE);
  MPI_Win_unlock_all(win);
  MCHECK(t, q[0] == MPI_REQUEST_NULL && q[1] == MPI_REQUEST_NULL && q[2] == MPI_REQUEST_NULL, "requests not freed");
  MCHECK(t, got[0] == rank && got[1] == rank + 100, "MPI_Rget after MPI_Rput: %d %d", got[0], got[1]);
  MCHECK(t, old == 0, "MPI_Rget_accumulate's result %d", old);
  MPI_Barrier(MPI_COMM_WORLD);
  MCHECK(t, mem[0] == left && mem[1] == left + 100 && mem[2] == 5 && mem[3] == 1, "what the left neighbour left: %d %d %d %d",
         mem[0], mem[1], mem[2], mem[3]);
  MPI_Win_free(&win);
}

/* A flag in a shared window, set by one rank and polled by the next with
 * MPI_Win_sync (on one node: MPI_COMM_TYPE_SHARED's communicator). */
static void polled(mtest *t) {
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int nr, ns;
  MPI_Comm_rank(node, &nr);
  MPI_Comm_size(node, &ns);
  volatile int *flag;
  MPI_Win win;
  MPI_Win_allocate_shared(sizeof(int), sizeof(int), MPI_INFO_NULL, node, (void *)&flag, &win);
  *flag = 0;
  MPI_Win_lock_all(0, win);
  MPI_Win_sync(win);
  MPI_Barrier(node);
  int ok = 1;
  if (nr > 0) {   /* wait for the one before, then set mine */
    MPI_Aint s;
    int u;
    volatile int *prev;
    MPI_Win_shared_query(win, nr - 1, &s, &u, (void *)&prev);
    while (*prev == 0) MPI_Win_sync(win);
    ok = *prev == nr;
  }
  *flag = nr + 1;
  MPI_Win_sync(win);
  MPI_Win_unlock_all(win);
  MPI_Barrier(node);
  MCHECK(t, ok, "a flag polled with MPI_Win_sync");
  (void)ns;
  MPI_Win_free(&win);
  MPI_Comm_free(&node);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {counter, mutex, flushes, requests, polled, NULL};
  return mtest_main(&argc, &argv, "rma_passive", 1, 0, checks);
}
