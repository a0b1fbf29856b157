/* test_spans.c -- the spans a tiling uses twice, against
 * the band's own triangles: an edge between the two contours in more than
 * two triangles is exactly a repeated span.  On the sliver case, on
 * small contours far off big ones (fans), and on random pairs; beside
 * surface/unpinch's run-counting test of the same property. */
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/gen.h"
#include "util/rng.h"
#include "algo/tiling.h"
#include "surface/unpinch.h"
#include "util/xmem.h"

static int cmp_int2(const void *a, const void *b) {
  const int *x = a, *y = b;
  if (x[0] != y[0]) return x[0] < y[0] ? -1 : 1;
  return (x[1] > y[1]) - (x[1] < y[1]);
}

/* The spans (P index, Q index) whose edge lies in more than two of the
 * band's triangles, sorted; returns their number. */
static int ref_spans(const tiling *t, int np, int (*out)[2]) {
  int steps = t->m + t->n, ne = 0;
  int (*tile)[3] = xmallocarray((size_t)steps, sizeof *tile);
  unsigned char *on = xmalloc((size_t)steps);
  tiling_tiles(t, tile, on);
  /* every triangle's two edges between the contours, as (P index, Q index) */
  int (*e)[2] = xmallocarray(2 * (size_t)steps, sizeof *e);
  for (int k = 0; k < steps; k++)
    for (int s = 0; s < 2; s++) {
      int x = tile[k][s], y = tile[k][2];   /* an end of the contour edge, the apex */
      e[ne][0] = on[k] ? y : x, e[ne][1] = on[k] ? x : y;
      ne++;
    }
  qsort(e, (size_t)ne, sizeof *e, cmp_int2);
  int n = 0;
  for (int k = 0; k < ne;) {
    int j = k;
    while (j < ne && e[j][0] == e[k][0] && e[j][1] == e[k][1]) j++;
    if (j - k > 2) out[n][0] = e[k][0], out[n][1] = e[k][1], n++;
    k = j;
  }
  (void)np;
  free(tile), free(on), free(e);
  return n;
}

static int check_one(const vec2 *P, int np, const vec2 *Q, int nq, cost_kind kind, const char *what) {
  tiling t;
  tiling_solve(P, np, 0, Q, nq, 1, kind, -1, &t);
  int (*ref)[2] = xmallocarray((size_t)(np + nq), sizeof *ref), (*got)[2] = xmallocarray((size_t)(np + nq), sizeof *got);
  int nr = ref_spans(&t, np, ref), ng = tiling_repeated_spans(&t, got, np + nq);
  int counted = tiling_repeated_spans(&t, NULL, 0);
  qsort(got, (size_t)(ng < np + nq ? ng : np + nq), sizeof *got, cmp_int2);
  int ok = ng == nr && counted == ng && memcmp(ref, got, sizeof *ref * (size_t)nr) == 0 &&
           unpinch_repeats(&t) == (ng > 0);
  if (!ok)
    CHECK(0, "%s: %d spans used twice (counted %d), the triangles say %d, unpinch %d", what, ng, counted, nr,
          unpinch_repeats(&t));
  tiling_free(&t);
  free(ref), free(got);
  return ng;
}

int main(void) {
  rng g;
  rng_seed(&g, 8080);
  vec2 P[400], Q[400];

  /* The sliver: 50 points (1e8+i, 1e8+i) and (1e8, 1e8+1e-8), under
   * a 20-gon of radius 100 one unit up, off to one side: the span-cost
   * optimum fans the sliver from one polygon point, and the span at both ends
   * of the fan is used twice. */
  for (int i = 0; i < 50; i++) P[i] = (vec2){1e8 + i, 1e8 + i};
  P[50] = (vec2){1e8, 1e8 + 1e-8};
  CHECK(geom_orientation(P, 51) > 0, "the sliver runs counter-clockwise");
  gen_regular(Q, 20, 1e8 + 100, 1e8 + 100, 100, 0.1);
  int n = check_one(P, 51, Q, 20, COST_SPAN, "sliver");
  CHECK(n == 1, "the sliver's band uses %d spans twice, want 1", n);
  tiling t;
  tiling_solve(P, 51, 0, Q, 20, 1, COST_SPAN, -1, &t);
  int sp[1][2] = {{-1, -1}};
  tiling_repeated_spans(&t, sp, 1);
  CHECK(sp[0][0] == 49, "the span from sliver point %d (want 49, the far end) to polygon point %d", sp[0][0], sp[0][1]);
  tiling_free(&t);

  /* Small contours far off big ones: fans; and random pairs: mostly none. */
  int with = 0, without = 0;
  for (int trial = 0; trial < 3000; trial++) {
    int np = rng_int(&g, 3, trial % 3 ? 40 : 8), nq = rng_int(&g, 3, trial % 3 ? 40 : 8);
    double off = trial % 2 ? 0 : 30 + 200 * rng_uniform(&g);
    gen_star(&g, P, np, 0, 0, 10, 0.5);
    gen_star(&g, Q, nq, off, rng_uniform(&g) * off, trial % 4 == 0 ? 0.5 : 6, 0.5);
    char what[64];
    snprintf(what, sizeof what, "trial %d (%dx%d, offset %.0f)", trial, np, nq, off);
    int k = check_one(P, np, Q, nq, trial % 5 ? COST_AREA : COST_SPAN, what);
    with += k > 0, without += k == 0;
  }
  CHECK(with > 100 && without > 100, "both drawn: %d pairs with a span used twice, %d without", with, without);
  return check_done("test_spans");
}
