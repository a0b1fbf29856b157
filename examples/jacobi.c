/* jacobi.c -- a Jacobi stencil with halo exchange: the heat equation on an
 * NX x NY grid, its rows split among the ranks.
 *
 *   cc jacobi.c $(pkg-config --cflags --libs tilesim) -o jacobi
 *   ./jacobi --procs 8 --machine tc2000 -- 256 256 100
 *
 * Each rank holds a block of rows (the first NY mod P ranks one more) and,
 * around it, a halo row from each neighbour.  A step: send my first and
 * last rows up and down, receive the neighbours' into the halos, then
 * replace every inner point by the mean of its four neighbours.  The top
 * edge is held at 1, the others at 0.  The update is charged to the
 * simulated processor as one unit (--c seconds) per point:
 *
 *     mp_compute(self, rows * NX);
 *
 * so on --net ideal, with NY divisible by P, a step takes exactly
 * m + 8 NX per_byte (the halos) + (NY / P) NX c (the update), and one
 * processor needs NY NX c: the speedup is NY NX c / step.
 *
 * Rank 0 prints the time of the steps and, after gathering every row's sum,
 * the grid's checksum: the sum of the rows' sums in row order, the same bits
 * on any number of ranks and on every backend (each point's update is the
 * same arithmetic whatever the split). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <tilesim/tilesim.h>

typedef struct {
  int nx, ny, steps;
} jacobi_args;

enum { TAG_UP = 1, TAG_DOWN = 2, TAG_SUMS = 3 };

static void jacobi(mp *self, void *ud) {
  const jacobi_args *a = ud;
  int me = mp_rank(self), p = mp_size(self), nx = a->nx;
  /* My rows: [first, first + rows) of the grid's inner rows 1 .. ny. */
  int base = a->ny / p, extra = a->ny % p;
  int rows = base + (me < extra), first = 1 + me * base + (me < extra ? me : extra);
  /* Rows 0 and rows + 1 are the halos (or the grid's edges). */
  size_t w = (size_t)nx + 2, cells = (size_t)(rows + 2) * w;
  double *u = calloc(cells, sizeof *u), *v = calloc(cells, sizeof *v);
  if (!u || !v) mp_abort(self, 1, "jacobi: out of memory");
  if (first == 1)
    for (size_t x = 0; x < w; x++) u[x] = v[x] = 1;   /* the top edge */
  int up = me - 1, down = me + 1;   /* neighbours, if they exist (and hold rows) */
  int has_up = me > 0 && rows > 0, has_down = down < p && rows > 0 && first + rows <= a->ny;
  double t0 = mp_time(self);
  for (int s = 0; s < a->steps; s++) {
    if (has_up) mp_send(self, up, TAG_UP, &u[1 * w + 1], (size_t)nx * sizeof *u);
    if (has_down) mp_send(self, down, TAG_DOWN, &u[(size_t)rows * w + 1], (size_t)nx * sizeof *u);
    if (has_up) mp_recv(self, up, TAG_DOWN, &u[1], (size_t)nx * sizeof *u, NULL);
    if (has_down) mp_recv(self, down, TAG_UP, &u[(size_t)(rows + 1) * w + 1], (size_t)nx * sizeof *u, NULL);
    for (int y = 1; y <= rows; y++)
      for (int x = 1; x <= nx; x++) {
        size_t i = (size_t)y * w + (size_t)x;
        v[i] = 0.25 * (u[i - 1] + u[i + 1] + u[i - w] + u[i + w]);
      }
    mp_compute(self, (double)rows * nx);   /* one unit a point */
    double *t = u;
    u = v, v = t;
  }
  double t = mp_time(self) - t0;
  /* Every row's sum to rank 0, which adds them in row order. */
  double *sums = calloc((size_t)a->ny + 1, sizeof *sums);
  if (!sums) mp_abort(self, 1, "jacobi: out of memory");
  for (int y = 1; y <= rows; y++) {
    double r = 0;
    for (int x = 1; x <= nx; x++) r += u[(size_t)y * w + (size_t)x];
    sums[first - 1 + y - 1] = r;
  }
  if (me != 0) {
    if (rows > 0) mp_send(self, 0, TAG_SUMS, &sums[first - 1], (size_t)rows * sizeof *sums);
  } else {
    for (int r = 1; r < p; r++) {
      int rr = base + (r < extra), rf = 1 + r * base + (r < extra ? r : extra);
      if (rr > 0) mp_recv(self, r, TAG_SUMS, &sums[rf - 1], (size_t)rr * sizeof *sums, NULL);
    }
    double total = 0;
    for (int y = 0; y < a->ny; y++) total += sums[y];
    char b[32];
    printf("jacobi: %d x %d, %d steps on %d ranks: %s s\n", nx, a->ny, a->steps, p, tilesim_fmt_double(t, b, sizeof b));
    printf("jacobi: checksum %s\n", tilesim_fmt_double(total, b, sizeof b));
  }
  free(sums);
  free(u);
  free(v);
}

int main(int argc, char **argv) {
  tilesim_machine *m;
  int status = tilesim_args(&argc, &argv, &m);
  if (!m) return status;
  jacobi_args a = {64, 64, 50};   /* after --: [NX [NY [STEPS]]] */
  if (argc > 1) a.nx = atoi(argv[1]);
  if (argc > 2) a.ny = atoi(argv[2]);
  if (argc > 3) a.steps = atoi(argv[3]);
  if (argc > 4 || a.nx < 1 || a.ny < 1 || a.steps < 0 || a.nx > 1 << 20 || a.ny > 1 << 20) {
    fprintf(stderr, "jacobi: arguments after --: [NX [NY [STEPS]]], NX and NY from 1 to 2^20\n");
    tilesim_machine_free(m);
    return 2;
  }
  return tilesim_exec(m, 0, jacobi, &a);
}
