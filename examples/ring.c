/* ring.c -- a token passed around a ring of ranks: the smallest useful
 * tilesim program, and a start for your own.
 *
 *   cc ring.c $(pkg-config --cflags --libs tilesim) -o ring
 *   ./ring --procs 16 --topology torus:4x4 -- 1000 64
 *
 * Rank 0 starts a token of B bytes (default 8); every rank passes it to the
 * next, rank n-1 back to 0; L laps (default 10).  Rank 0 checks the token
 * that comes back and prints two lines: what ran, then the time per lap
 * and the messages per second (simulated time on the simulator).  On
 * --net ideal one lap takes n hops of m + B per_byte each. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <tilesim/tilesim.h>

typedef struct {
  int laps;
  int bytes;
} ring_args;

/* One rank: receive from the left, send to the right, `laps` times.  Its
 * state lives on its stack; the arguments are shared and read-only. */
static void ring(mp *self, void *ud) {
  const ring_args *a = ud;
  int me = mp_rank(self), n = mp_size(self);
  int left = (me + n - 1) % n, right = (me + 1) % n;
  char *token = calloc(1, (size_t)a->bytes + 1);
  if (!token) mp_abort(self, 1, "ring: out of memory for the token");
  double t0 = mp_time(self);
  for (int lap = 0; lap < a->laps; lap++) {
    if (me == 0) {
      token[0] = (char)lap;
      mp_send(self, right, lap, token, (size_t)a->bytes);
      mp_recv(self, left, lap, token, (size_t)a->bytes, NULL);
      if (token[0] != (char)lap) mp_abort(self, 1, "ring: the token came back changed");
    } else {
      mp_recv(self, left, lap, token, (size_t)a->bytes, NULL);
      mp_send(self, right, lap, token, (size_t)a->bytes);
    }
  }
  if (me == 0) {
    double t = mp_time(self) - t0;
    printf("ring: %d ranks, %d laps of %d bytes: the token came back every lap\n", n, a->laps, a->bytes);
    char b[32];
    printf("ring: %s s a lap, %.6g messages a second\n", tilesim_fmt_double(t / a->laps, b, sizeof b),
           t > 0 ? (double)n * a->laps / t : 0.0);
  }
  free(token);
}

int main(int argc, char **argv) {
  tilesim_machine *m;
  int status = tilesim_args(&argc, &argv, &m);   /* the machine's options out of argv */
  if (!m) return status;                          /* --help, or bad usage */
  ring_args a = {10, 8};                          /* the program's own: [LAPS [BYTES]] */
  if (argc > 1) a.laps = atoi(argv[1]);
  if (argc > 2) a.bytes = atoi(argv[2]);
  if (argc > 3 || a.laps < 1 || a.bytes < 1) {
    fprintf(stderr, "ring: arguments after --: [LAPS [BYTES]], both at least 1\n");
    tilesim_machine_free(m);
    return 2;
  }
  return tilesim_exec(m, 0, ring, &a);
}
