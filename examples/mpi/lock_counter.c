/* lock_counter.c -- a shared counter behind a lock: rank 0 holds a long in
 * its window, and every other rank takes it STEPS times with
 * MPI_Win_lock(MPI_LOCK_EXCLUSIVE), MPI_Fetch_and_op(MPI_SUM, 1) and
 * MPI_Win_unlock.  Plain MPI: it runs under any MPI library; under
 * tilesim-mpirun it prints the simulated time.
 *
 *   tilesim-mpicc lock_counter.c -o lock_counter
 *   tilesim-mpirun -np P --net ideal --m M --per-byte B ./lock_counter [STEPS]
 *
 * THE CLOSED FORM (P >= 3 ranks, so two or more origins; --net ideal,
 * every other cost 0).  From a common start S (as in halo_fence.c), the
 * K = (P - 1) STEPS increments end, for the last origin, at
 *
 *     T = 2 M + 8 B + K (2 M + 8 B)
 *
 * The lock requests reach rank 0 at S + M (a request carries no data); the
 * lock goes to one origin, the others queue in the order they came.  The
 * holder's grant takes M back to it, its fetch-and-op (8 bytes) and its
 * release leave at once and arrive M + 8 B later, one after the other on
 * their channel: the lock passes every 2 M + 8 B, and the origins that wait
 * are always back in the queue by then.  The last holder's reply (8 bytes)
 * takes M + 8 B more.  (One origin alone, P = 2, waits for its own replies:
 * STEPS (4 M + 16 B).)  tests/cli_rma.sh checks T exactly.  Rank 0 prints
 * "lock_counter: counter C" (it must be K, and every value 0 .. K - 1
 * fetched once); each origin "lock_counter: rank R: T s". */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

#include "level.h"


int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int p, r;
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  int steps = argc > 1 ? atoi(argv[1]) : 10, k = (p - 1) * steps, bad = 0;
  long *counter, one = 1;
  MPI_Win win;
  MPI_Win_allocate(r == 0 ? (MPI_Aint)sizeof(long) : 0, sizeof(long), MPI_INFO_NULL, MPI_COMM_WORLD, &counter,
                   &win);
  if (r == 0) *counter = 0;
  long *got = malloc(((size_t)steps + 1) * sizeof *got);
  MPI_Barrier(MPI_COMM_WORLD);
  level(MPI_COMM_WORLD);
  double start = MPI_Wtime();
  if (r > 0) {
    for (int s = 0; s < steps; s++) {
      MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, win);
      MPI_Fetch_and_op(&one, &got[s], MPI_LONG, 0, 0, MPI_SUM, win);
      MPI_Win_unlock(0, win);
    }
    printf("lock_counter: rank %d: %.17g s\n", r, MPI_Wtime() - start);
  }
  /* Every value fetched once: rank 0 counts them. */
  long *all = r == 0 ? calloc((size_t)p * (size_t)steps + 1, sizeof *all) : NULL;
  MPI_Gather(got, steps, MPI_LONG, all, steps, MPI_LONG, 0, MPI_COMM_WORLD);
  MPI_Barrier(MPI_COMM_WORLD);
  if (r == 0) {
    char *seen = calloc((size_t)k + 1, 1);
    for (int i = steps; i < p * steps; i++) {
      if (all[i] < 0 || all[i] >= k || seen[all[i]]) bad = 1;
      else seen[all[i]] = 1;
    }
    printf("lock_counter: counter %ld%s\n", *counter, *counter == k && !bad ? "" : " (wrong)");
    bad |= *counter != k;
    free(seen);
  }
  free(all);
  free(got);
  MPI_Win_free(&win);
  MPI_Finalize();
  return bad;
}
