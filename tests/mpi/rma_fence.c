/* rma_fence.c -- the one-sided operations under MPI_Win_fence (MPI 3.1
 * sections 11.3 and 11.5.1), checked by themselves on any number of ranks
 * against values computed here: MPI_Put and MPI_Get around a ring,
 * contiguous and with derived types on either side (a vector into an
 * indexed type, a struct of an int and a double, a resized type whose
 * elements lie apart); MPI_Accumulate from every rank into every rank
 * (MPI_SUM on ints and doubles of small integers: exact in any order,
 * MPI_MAX, MPI_BOR, MPI_REPLACE, MPI_MINLOC on MPI_2INT, a vector on the
 * target); MPI_Get_accumulate, MPI_Fetch_and_op and MPI_Compare_and_swap
 * with their results; MPI_PROC_NULL and zero-size operations; the
 * assertions MPI_MODE_NOPRECEDE, _NOSTORE, _NOPUT, _NOSUCCEED. */
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "mtest.h"

enum { N = 24 };

static void ring(mtest *t) {
  int rank = t->rank, size = t->size, right = (rank + 1) % size, left = (rank + size - 1) % size;
  int mem[N], src[N], got[N];
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  for (int i = 0; i < N; i++) mem[i] = -1, src[i] = 1000 * rank + i, got[i] = -2;
  MPI_Win_fence(MPI_MODE_NOPRECEDE, win);
  MPI_Put(src, 8, MPI_INT, right, 4, 8, MPI_INT, win);
  MPI_Win_fence(0, win);
  int bad = 0;
  for (int i = 0; i < N; i++) bad += mem[i] != (i >= 4 && i < 12 ? 1000 * left + i - 4 : -1);
  MCHECK(t, bad == 0, "a put from the left neighbour: %d wrong", bad);
  /* Get back what the right neighbour holds, in two pieces. */
  MPI_Get(got, 4, MPI_INT, right, 4, 4, MPI_INT, win);
  MPI_Get(got + 4, 4, MPI_INT, right, 8, 4, MPI_INT, win);
  MPI_Win_fence(MPI_MODE_NOSUCCEED, win);
  bad = 0;
  for (int i = 0; i < 8; i++) bad += got[i] != 1000 * rank + i;
  MCHECK(t, bad == 0, "a get of what this rank put: %d wrong", bad);

  /* Derived types: a vector of every other int at the origin into an
   * indexed type at the target (blocks 2, 1, 3 at 0, 5, 9). */
  MPI_Datatype vec, idx;
  MPI_Type_vector(6, 1, 2, MPI_INT, &vec);
  int bl[3] = {2, 1, 3}, dp[3] = {0, 5, 9};
  MPI_Type_indexed(3, bl, dp, MPI_INT, &idx);
  MPI_Type_commit(&vec);
  MPI_Type_commit(&idx);
  for (int i = 0; i < N; i++) mem[i] = -1;
  MPI_Win_fence(MPI_MODE_NOPRECEDE, win);
  MPI_Put(src, 1, vec, right, 2, 1, idx, win);
  MPI_Type_free(&vec);   /* the operation keeps its types */
  MPI_Type_free(&idx);
  MPI_Win_fence(MPI_MODE_NOSUCCEED, win);
  int want[N];
  for (int i = 0; i < N; i++) want[i] = -1;
  int at[6] = {2, 3, 7, 11, 12, 13};
  for (int k = 0; k < 6; k++) want[at[k]] = 1000 * left + 2 * k;
  bad = 0;
  for (int i = 0; i < N; i++) bad += mem[i] != want[i];
  MCHECK(t, bad == 0, "a vector put into an indexed type: %d wrong", bad);
  MPI_Win_free(&win);
}

typedef struct {
  int i;
  double d;
} pair;

static void structs(mtest *t) {
  int rank = t->rank, size = t->size, right = (rank + 1) % size;
  pair mem[4], src[4], got[4];
  MPI_Datatype pt;
  int bl[2] = {1, 1};
  MPI_Aint dp[2] = {offsetof(pair, i), offsetof(pair, d)};
  MPI_Datatype ty[2] = {MPI_INT, MPI_DOUBLE};
  MPI_Type_create_struct(2, bl, dp, ty, &pt);
  MPI_Type_commit(&pt);
  memset(mem, 0, sizeof mem);
  for (int k = 0; k < 4; k++) src[k].i = rank * 10 + k, src[k].d = rank + k / 4.0;
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(pair), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Win_fence(0, win);
  MPI_Put(src, 3, pt, right, 1, 3, pt, win);
  MPI_Win_fence(0, win);
  MPI_Get(got, 3, pt, right, 1, 3, pt, win);
  MPI_Win_fence(0, win);
  int bad = 0;
  for (int k = 0; k < 3; k++) bad += got[k].i != src[k].i || got[k].d != src[k].d;
  MCHECK(t, bad == 0, "a put and a get of structs: %d wrong", bad);
  MPI_Win_free(&win);
  MPI_Type_free(&pt);
}

static void accumulates(mtest *t) {
  int rank = t->rank, size = t->size;
  int im[N];
  double dm[N];
  MPI_Win iw, dw;
  MPI_Win_create(im, sizeof im, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &iw);
  MPI_Win_create(dm, sizeof dm, sizeof(double), MPI_INFO_NULL, MPI_COMM_WORLD, &dw);
  for (int i = 0; i < N; i++) im[i] = i, dm[i] = i;
  MPI_Win_fence(0, iw);
  MPI_Win_fence(0, dw);
  int isrc[N];
  double dsrc[N];
  for (int i = 0; i < N; i++) isrc[i] = rank + 1, dsrc[i] = (rank + 1) * 2;
  for (int q = 0; q < size; q++) {
    MPI_Accumulate(isrc, 4, MPI_INT, q, 0, 4, MPI_INT, MPI_SUM, iw);         /* [0, 4): + sum(r+1) */
    MPI_Accumulate(isrc, 4, MPI_INT, q, 4, 4, MPI_INT, MPI_MAX, iw);         /* [4, 8): max(i, size) */
    MPI_Accumulate(dsrc, 4, MPI_DOUBLE, q, 8, 4, MPI_DOUBLE, MPI_SUM, dw);   /* [8, 12): + sum 2(r+1) */
  }
  int bits = 1 << rank % 20;
  MPI_Accumulate(&bits, 1, MPI_INT, 0, 9, 1, MPI_INT, MPI_BOR, iw);
  MPI_Win_fence(0, iw);
  MPI_Win_fence(0, dw);
  int s = size * (size + 1) / 2, bad = 0, orbits = 0;
  for (int r = 0; r < size; r++) orbits |= 1 << r % 20;
  for (int i = 0; i < 4; i++) bad += im[i] != i + s;
  for (int i = 4; i < 8; i++) bad += im[i] != (i > size ? i : size);
  for (int i = 8; i < 12; i++) bad += dm[i] != i + 2.0 * s;
  if (rank == 0) bad += im[9] != (9 | orbits);
  MCHECK(t, bad == 0, "accumulates from every rank: %d wrong", bad);

  /* MPI_REPLACE and MPI_MINLOC on pairs; a vector target. */
  int pairs[2 * 4];
  MPI_Win pw;
  MPI_Win_create(pairs, sizeof pairs, 2 * sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &pw);
  for (int k = 0; k < 4; k++) pairs[2 * k] = 1000, pairs[2 * k + 1] = -1;
  MPI_Win_fence(0, pw);
  int mine[2] = {100 - (rank % 3), rank};   /* the least value: rank % 3 == 2's, the least such rank */
  for (int q = 0; q < size; q++) MPI_Accumulate(mine, 1, MPI_2INT, q, 1, 1, MPI_2INT, MPI_MINLOC, pw);
  MPI_Win_fence(0, pw);
  int lv = 1000, li = -1;
  for (int r = 0; r < size; r++)
    if (100 - r % 3 < lv) lv = 100 - r % 3, li = r;
  MCHECK(t, pairs[2] == lv && pairs[3] == li, "MPI_MINLOC gave (%d, %d), not (%d, %d)", pairs[2], pairs[3], lv, li);
  MPI_Win_free(&pw);

  MPI_Datatype every3;
  MPI_Type_vector(4, 1, 3, MPI_INT, &every3);
  MPI_Type_commit(&every3);
  for (int i = 0; i < N; i++) im[i] = 0;
  MPI_Win_fence(0, iw);
  int four[4] = {1, 2, 3, 4};
  MPI_Accumulate(four, 4, MPI_INT, (rank + 1) % size, 12, 1, every3, MPI_SUM, iw);
  MPI_Win_fence(0, iw);
  bad = 0;
  for (int i = 0; i < N; i++) {
    int w = i >= 12 && (i - 12) % 3 == 0 && i - 12 < 12 ? (i - 12) / 3 + 1 : 0;
    bad += im[i] != w;
  }
  MCHECK(t, bad == 0, "an accumulate into a vector: %d wrong", bad);
  MPI_Win_fence(0, iw);   /* the next epoch's accumulates after this rank's loads */
  MPI_Accumulate(four, 4, MPI_INT, (rank + 1) % size, 0, 4, MPI_INT, MPI_REPLACE, iw);
  MPI_Win_fence(0, iw);
  MCHECK(t, im[0] == 1 && im[3] == 4, "MPI_REPLACE: %d %d", im[0], im[3]);
  MPI_Type_free(&every3);
  MPI_Win_free(&iw);
  MPI_Win_free(&dw);
}

/* Fetching atomics: every rank adds to rank 0's counter once per round
 * (the values fetched are distinct: their sum is known), swaps its rank in
 * where the value is its left neighbour's, reads with MPI_NO_OP. */
static void fetching(mtest *t) {
  int rank = t->rank, size = t->size;
  long mem[4] = {0, 0, 0, 0};
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(long), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Win_fence(0, win);
  long one = 1, old = -1;
  MPI_Fetch_and_op(&one, &old, MPI_LONG, 0, 0, MPI_SUM, win);
  MPI_Win_fence(0, win);
  long sum = 0, all = 0;
  MPI_Allreduce(&old, &sum, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&one, &all, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  MCHECK(t, sum == all * (all - 1) / 2 && (rank != 0 || mem[0] == size), "fetch-and-add: the old values sum to %ld",
         sum);
  /* Compare-and-swap: only the one whose compare value is there wins. */
  long cmp = 0, mine = rank + 1, res = -1;
  MPI_Win_fence(0, win);
  MPI_Compare_and_swap(&mine, &cmp, &res, MPI_LONG, 0, 1, win);
  MPI_Win_fence(0, win);
  long won = res == 0, winners = 0;
  MPI_Allreduce(&won, &winners, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  long held = -1;
  MPI_Fetch_and_op(NULL, &held, MPI_LONG, 0, 1, MPI_NO_OP, win);
  MPI_Win_fence(0, win);
  MPI_Win_fence(0, win);   /* the read of every rank before the next epoch's writes */
  MCHECK(t, winners == 1 && held >= 1 && held <= size && (!won || held == rank + 1),
         "compare-and-swap: %ld winners, %ld held", winners, held);
  /* Get_accumulate: a vector of 3 longs, the result and the new value. */
  long add[3] = {rank, rank, rank}, out[3] = {-1, -1, -1};
  MPI_Get_accumulate(add, 3, MPI_LONG, out, 3, MPI_LONG, (rank + 1) % size, 1, 3, MPI_LONG, MPI_REPLACE, win);
  MPI_Win_fence(0, win);
  int left = (rank + size - 1) % size;
  MCHECK(t, mem[1] == left && mem[2] == left && mem[3] == left, "MPI_Get_accumulate with MPI_REPLACE: %ld %ld %ld",
         mem[1], mem[2], mem[3]);
  MCHECK(t, out[1] == 0 && out[2] == 0, "MPI_Get_accumulate's result %ld %ld %ld", out[0], out[1], out[2]);
  MPI_Win_free(&win);
}

/* MPI_PROC_NULL and empty operations do nothing and succeed. */
static void nothing(mtest *t) {
  int mem[2] = {5, 6}, v[2] = {1, 2}, r = -1;
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Win_fence(0, win);
  int rc = MPI_Put(v, 2, MPI_INT, MPI_PROC_NULL, 0, 2, MPI_INT, win);
  rc |= MPI_Get(v, 2, MPI_INT, MPI_PROC_NULL, 0, 2, MPI_INT, win);
  rc |= MPI_Accumulate(v, 2, MPI_INT, MPI_PROC_NULL, 0, 2, MPI_INT, MPI_SUM, win);
  rc |= MPI_Fetch_and_op(v, &r, MPI_INT, MPI_PROC_NULL, 0, MPI_SUM, win);
  rc |= MPI_Put(v, 0, MPI_INT, 0, 0, 0, MPI_INT, win);
  MPI_Win_fence(0, win);
  MCHECK(t, rc == MPI_SUCCESS && mem[0] == 5 && mem[1] == 6 && v[0] == 1 && r == -1,
         "operations to MPI_PROC_NULL or of nothing did something");
  MPI_Win_free(&win);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {ring, structs, accumulates, fetching, nothing, NULL};
  return mtest_main(&argc, &argv, "rma_fence", 1, 0, checks);
}
