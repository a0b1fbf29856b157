/* reduce.c -- a binomial-tree reduction, or a parallel prefix (scan).
 *
 *   cc reduce.c $(pkg-config --cflags --libs tilesim) -o reduce
 *   ./reduce --procs 16 --topology hypercube:4 --place gray -- scan
 *
 * Rank r holds the value (r + 1)^2.
 *   reduce (the default): in round k = 1, 2, 4, ..., a rank whose bit k is
 *   set sends its partial sum to the rank k below and is done; the others
 *   receive from the rank k above, if there is one, and add.  Rank 0 ends
 *   with the total after ceil(log2 P) rounds.
 *   scan (Hillis and Steele): in round d = 1, 2, 4, ..., every rank sends
 *   its partial sum to the rank d above and adds the one from the rank d
 *   below; after ceil(log2 P) rounds rank r holds the sum of ranks 0..r.
 * Each addition is charged one unit (--c seconds).  On --net ideal, with P
 * a power of two, either takes exactly log2 P (m + 8 per_byte + c): rank 0
 * says when the total is there (reduce), the last rank when its prefix is
 * (scan); with other P some partial sums are ready sooner.  Every rank
 * checks its result against the closed form n(n + 1)(2n + 1) / 6.
 *
 * The argument after -- reaches the ranks through tilesim_argv: a program
 * that needs nothing else can be one call of tilesim_main. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <tilesim/tilesim.h>

enum { TAG_REDUCE = 1, TAG_SCAN = 2 };

/* 1^2 + 2^2 + ... + n^2. */
static int64_t squares(int64_t n) { return n * (n + 1) * (2 * n + 1) / 6; }

static void reduce(mp *self, int me, int p) {
  int64_t part = (int64_t)(me + 1) * (me + 1), in;
  for (int k = 1; k < p; k <<= 1) {
    if (me & k) {
      mp_send(self, me - k, TAG_REDUCE, &part, sizeof part);
      return;
    }
    if (me + k < p) {
      mp_recv(self, me + k, TAG_REDUCE, &in, sizeof in, NULL);
      part += in;
      mp_compute(self, 1);
    }
  }
  if (part != squares(p)) mp_abort(self, 1, "reduce: the total is wrong");
  printf("reduce: %d ranks: total %lld, checked\n", p, (long long)part);
  char b[32];
  printf("reduce: reduction %s s\n", tilesim_fmt_double(mp_time(self), b, sizeof b));
}

static void scan(mp *self, int me, int p) {
  int64_t part = (int64_t)(me + 1) * (me + 1), in;
  for (int d = 1; d < p; d <<= 1) {
    if (me + d < p) mp_send(self, me + d, TAG_SCAN, &part, sizeof part);
    if (me - d >= 0) {
      mp_recv(self, me - d, TAG_SCAN, &in, sizeof in, NULL);
      part += in;
      mp_compute(self, 1);
    }
  }
  if (part != squares(me + 1)) mp_abort(self, 1, "reduce: a rank's prefix sum is wrong");
  if (me == p - 1) {
    printf("reduce: %d ranks: prefixes checked\n", p);
    char b[32];
    printf("reduce: scan %s s\n", tilesim_fmt_double(mp_time(self), b, sizeof b));
  }
}

static void rank_main(mp *self, void *ud) {
  (void)ud;
  int argc;
  char **argv = tilesim_argv(&argc);   /* the program's own arguments, read-only */
  if (argc > 1 && strcmp(argv[1], "scan") == 0) scan(self, mp_rank(self), mp_size(self));
  else reduce(self, mp_rank(self), mp_size(self));
}

int main(int argc, char **argv) {
  for (int i = 1; i < argc; i++)   /* after --: nothing, reduce or scan */
    if (strcmp(argv[i], "--") == 0 &&
        (argc - i > 2 || (argc - i == 2 && strcmp(argv[i + 1], "reduce") != 0 && strcmp(argv[i + 1], "scan") != 0))) {
      fprintf(stderr, "reduce: the argument after -- is reduce or scan\n");
      return 2;
    }
  return tilesim_main(argc, argv, rank_main, NULL);
}
