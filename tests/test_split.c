/* test_split.c -- the diagonal split (the paper's N_i), its closed form and
 * owners, min-diag, and the processor allocation. */
#include <stdlib.h>

#include "tests/check.h"
#include "algo/split.h"

static void check_positions(void) {
  int bad = 0, badown = 0, badbal = 0;
  int N[70];
  for (int len = 1; len <= 700; len++)
    for (int q = 1; q <= 64 && q <= len; q++) {
      split_positions(len, q, N);
      int lo = len, hi = 0;
      for (int i = 0; i <= q; i++)
        if (N[i] != split_n(len, q, i)) bad++;   /* the closed form */
      for (int i = 0; i < q; i++) {
        int run = N[i + 1] - N[i];
        if (run < lo) lo = run;
        if (run > hi) hi = run;
        for (int pos = N[i]; pos < N[i + 1]; pos++)
          if (split_owner(100, 100 + len - 1, q, 100 + pos) != i) badown++;
      }
      if (N[q] != len || hi - lo > 1 || lo < 1) badbal++;   /* contiguous, balanced */
    }
  CHECK(bad == 0, "%d N_i differ from the closed form", bad);
  CHECK(badown == 0, "%d positions with the wrong owner", badown);
  CHECK(badbal == 0, "%d splits not balanced or not covering the diagonal", badbal);
}

static void check_active(void) {
  CHECK(split_active(500, 16, 1) == 16 && split_active(10, 16, 1) == 10, "d = 1");
  CHECK(split_active(500, 16, 80) == 6 && split_active(79, 16, 80) == 1 && split_active(160, 16, 80) == 2,
        "d = 80: %d %d %d", split_active(500, 16, 80), split_active(79, 16, 80), split_active(160, 16, 80));
  int bad = 0;
  for (int len = 1; len < 400; len++)
    for (int d = 1; d < 100; d += 7) {
      int q = split_active(len, 9, d);
      if (q < 1 || q > 9 || (q > 1 && len / q < d)) bad++;   /* everyone gets d nodes */
    }
  CHECK(bad == 0, "%d splits give a slave fewer than d nodes", bad);
}

static void check_alloc(void) {
  /* half: ceil(p/2) below, whatever the sizes (section 4); 3 slaves: 2 and 1. */
  CHECK(split_slaves(ALLOC_HALF, 3, 10, 1000, 5, 5) == 2 && split_slaves(ALLOC_HALF, 4, 1, 1, 5, 5) == 2,
        "half");
  CHECK(split_slaves(ALLOC_HALF, 2, 0, 100, 0, 7) == 1, "half ignores sizes and empty sides");
  /* size: in proportion, at least one each, none to a side without paths. */
  CHECK(split_slaves(ALLOC_SIZE, 10, 300, 700, 5, 5) == 7, "size: 70%% below");
  CHECK(split_slaves(ALLOC_SIZE, 10, 1000, 1, 5, 5) == 1 && split_slaves(ALLOC_SIZE, 10, 1, 1000, 5, 5) == 9,
        "size: at least one each");
  CHECK(split_slaves(ALLOC_SIZE, 6, 100, 100, 0, 4) == 6 && split_slaves(ALLOC_SIZE, 6, 100, 100, 4, 0) == 0,
        "size: all to the side with paths");
}

/* |W| against a brute count of the nodes between two paths. */
static void check_region(void) {
  int m = 6, n = 9, T = m + n;
  int ucol[16], lcol[16];
  /* U from (1,0): right 4, down 6, right 5; L from (5,0): down 6, right 9. */
  int t = 0, c = 0;
  ucol[t++] = c;
  for (int i = 0; i < 4; i++) ucol[t++] = ++c;
  for (int i = 0; i < 6; i++) ucol[t++] = c;
  for (int i = 0; i < 5; i++) ucol[t++] = ++c;
  t = 0, c = 0;
  lcol[t++] = 0;
  for (int i = 0; i < 6; i++) lcol[t++] = 0;
  for (int i = 0; i < 9; i++) lcol[t++] = ++c;
  gpath U = {1, ucol, NULL}, L = {5, lcol, NULL};
  /* Brute: node (r, c) is between them if on or below U and on or above L,
   * and some path for a start in 2..4 can reach it (row 2 .. row 4+m). */
  long long brute = 0;
  for (int r = 0; r <= 2 * m; r++)
    for (int cc = 0; cc <= n; cc++) {
      int k = r + cc, tu = k - 1, tl = k - 5;
      int uc = tu >= 0 && tu <= T ? ucol[tu] : (tu > T ? n : -1);
      int lc = tl >= 0 && tl <= T ? lcol[tl] : (tl < 0 ? 0 : n + 1);
      if (uc < 0 || cc > uc || cc < lc) continue;
      if (r < 2 || r > 4 + m) continue;
      if (k < 2 || k > 4 + T) continue;
      brute++;
    }
  long long got = split_region(m, n, &U, &L);
  /* split_region leaves out cut edges' nodes; here the bounds never pinch
   * to one node on two diagonals in a row inside the region, so none. */
  CHECK(got == brute, "region %lld nodes, brute force %lld", got, brute);
  gpath L2 = {2, lcol, NULL};
  CHECK(split_region(m, n, &U, &L2) == 0, "no paths between mu(1) and mu(2)");
}

int main(void) {
  check_positions();
  check_active();
  check_alloc();
  check_region();
  return check_done("test_split");
}
