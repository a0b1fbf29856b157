/* halo_fence.c -- a halo exchange with MPI_Put and MPI_Win_fence: every rank
 * of a ring holds N doubles with a ghost cell of W doubles on each side, and
 * each step puts its W edge values into its neighbours' ghost cells, closes
 * the epoch with a fence and checks what it got.  Plain MPI: it runs under
 * any MPI library; under tilesim-mpirun it prints the simulated time.
 *
 *   tilesim-mpicc halo_fence.c -o halo_fence
 *   tilesim-mpirun -np P --net ideal --m M --per-byte B ./halo_fence [W [STEPS]]
 *
 * THE CLOSED FORM (P >= 3 ranks, --net ideal, every other cost 0).  From a
 * common start S (two rounds in which every rank sends 0 bytes to every
 * other: on --net ideal every rank leaves the second at the same time), the
 * program's first fence and STEPS steps take
 *
 *     T = ceil(log2 P) M + STEPS ((2 + ceil(log2 P)) M + 8 W B)
 *
 * A put of 8W bytes arrives M + 8W B after it is issued and its
 * acknowledgement M later; a fence waits for the acknowledgements of the
 * rank's puts, then runs MPI_Barrier's algorithm (dissemination: ceil(log2 P)
 * rounds of 0-byte messages, M each) on the window's ranks.  tests/cli_rma.sh
 * checks T exactly for several P and W (binary-fraction costs).  Every rank
 * prints "halo_fence: rank R: T s" and "halo_fence: rank R: wrong" if its
 * ghost cells do not hold its neighbours' edges. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

#include "level.h"


int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int p, r;
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  int w = argc > 1 ? atoi(argv[1]) : 4, steps = argc > 2 ? atoi(argv[2]) : 10, n = 4 * w + 4;
  int left = (r + p - 1) % p, right = (r + 1) % p, wrong = 0;
  /* The window: two left ghosts, the rank's own n values, two right ghosts
   * (w doubles each).  Step s puts into the ghosts of parity s % 2, so that
   * a rank reads step s's while its neighbours put step s + 1's (one fence
   * ends an epoch and begins the next). */
  double *u;
  MPI_Win win;
  MPI_Win_allocate((MPI_Aint)(n + 4 * w) * (MPI_Aint)sizeof(double), sizeof(double), MPI_INFO_NULL,
                   MPI_COMM_WORLD, &u, &win);
  for (int i = 0; i < n + 4 * w; i++) u[i] = -1;
  double *own = u + 2 * w;
  level(MPI_COMM_WORLD);
  double start = MPI_Wtime();
  MPI_Win_fence(MPI_MODE_NOPRECEDE, win);
  for (int s = 0; s < steps; s++) {
    /* This step's values (no rank puts into them), then the edges out:
     * the left edge into the left neighbour's right ghost, the right edge
     * into the right neighbour's left ghost. */
    int g = s % 2;
    for (int i = 0; i < n; i++) own[i] = 1000.0 * s + 10.0 * r + i;
    MPI_Put(&own[0], w, MPI_DOUBLE, left, 2 * w + n + g * w, w, MPI_DOUBLE, win);
    MPI_Put(&own[n - w], w, MPI_DOUBLE, right, g * w, w, MPI_DOUBLE, win);
    MPI_Win_fence(0, win);
    for (int i = 0; i < w; i++) {
      wrong += u[g * w + i] != 1000.0 * s + 10.0 * left + (n - w + i);
      wrong += u[2 * w + n + g * w + i] != 1000.0 * s + 10.0 * right + i;
    }
  }
  double t = MPI_Wtime() - start;
  printf("halo_fence: rank %d: %.17g s\n", r, t);
  if (wrong) printf("halo_fence: rank %d: wrong\n", r);
  MPI_Win_free(&win);
  MPI_Finalize();
  return wrong != 0;
}
