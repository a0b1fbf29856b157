/* bw.c -- a bandwidth window, as osu_bw measures one (written for tilesim's
 * benchmark, tests/bench_mpi.sh; no code of the OSU suite): rank 0 posts
 * WINDOW nonblocking sends of SIZE bytes to rank 1, which has posted as many
 * receives; both wait for all, rank 1 answers with 4 bytes; ITERS times.
 * Every buffer's first and last 8 bytes change each iteration; rank 1 adds
 * what it received there into a checksum, which must be the sum rank 0
 * sent (the program says "wrong" and exits 1 if not).  Rank 0 prints the
 * time and the bandwidth (simulated under tilesim-mpirun and smpirun).
 *   bw [SIZE [WINDOW [ITERS]]]     (default 4194304 64 10) */
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "mpibench.h"
#include <string.h>

/* What rank 0 writes at both ends of buffer w in iteration it. */
static uint64_t mark(long it, int w, int end) { return (uint64_t)(it + 1) * 1000003u + (uint64_t)w * 7919u + (uint64_t)end; }

int main(int argc, char **argv) {
  mpibench b;
  mpibench_init(&b, &argc, &argv);
  int r = b.r, p = b.p;
  long size = mpibench_arg(&b, 1, 4194304), iters = mpibench_arg(&b, 3, 10);
  int window = (int)mpibench_arg(&b, 2, 64);
  mpibench_refuse(&b, p < 2 || size < 16 || window < 1 || iters < 1, "bw", "2 ranks or more, SIZE >= 16, WINDOW and ITERS >= 1");
  char **buf = malloc((size_t)window * sizeof *buf);
  MPI_Request *req = malloc((size_t)window * sizeof *req);
  for (int w = 0; w < window; w++) {
    buf[w] = malloc((size_t)size);
    memset(buf[w], r == 0 ? 'a' + w % 26 : 0, (size_t)size);
  }
  uint64_t sum = 0;
  int ack = 0;
  double t0 = MPI_Wtime();
  for (long it = 0; it < iters; it++) {
    if (r == 0) {
      for (int w = 0; w < window; w++) {
        uint64_t a = mark(it, w, 0), b = mark(it, w, 1);
        memcpy(buf[w], &a, 8);
        memcpy(buf[w] + size - 8, &b, 8);
        sum += a + b;
        MPI_Isend(buf[w], (int)size, MPI_BYTE, 1, 7, MPI_COMM_WORLD, &req[w]);
      }
      MPI_Waitall(window, req, MPI_STATUSES_IGNORE);
      MPI_Recv(&ack, 1, MPI_INT, 1, 8, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    } else if (r == 1) {
      for (int w = 0; w < window; w++) MPI_Irecv(buf[w], (int)size, MPI_BYTE, 0, 7, MPI_COMM_WORLD, &req[w]);
      MPI_Waitall(window, req, MPI_STATUSES_IGNORE);
      for (int w = 0; w < window; w++) {
        uint64_t a, b;
        memcpy(&a, buf[w], 8);
        memcpy(&b, buf[w] + size - 8, 8);
        sum += a + b;
      }
      MPI_Send(&ack, 1, MPI_INT, 0, 8, MPI_COMM_WORLD);
    }
  }
  double t = MPI_Wtime() - t0;
  uint64_t sent = r == 0 ? sum : 0, got = r == 1 ? sum : 0;
  MPI_Bcast(&sent, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  MPI_Bcast(&got, 1, MPI_UINT64_T, 1, MPI_COMM_WORLD);
  int status = 0;
  if (r == 0) {
    if (got != sent) {
      printf("bw: wrong: received %llu, sent %llu\n", (unsigned long long)got, (unsigned long long)sent);
      status = 1;
    } else {
      printf("bw: %ld bytes, window %d, %ld iterations: checksum %llu, %.17g s, %.6g MB/s\n", size, window, iters,
             (unsigned long long)got, t, t > 0 ? (double)size * window * iters / t / 1e6 : 0.0);
    }
  }
  for (int w = 0; w < window; w++) free(buf[w]);
  free(buf);
  free(req);
  MPI_Finalize();
  return status;
}
