/* dtype_darray.c -- MPI_Type_create_darray against MPI 3.1 section 4.1.4's distributions,
 * computed here element by element: in a dimension of g elements on p processes with
 * distribution argument b, element i belongs to grid coordinate i / b (block; b by default
 * ceil(g / p)), (i / b) mod p (cyclic; b by default 1) or 0 (none), and the processes form a
 * row-major grid.  For every process of each distribution (block, cyclic of several
 * arguments, none; one to three dimensions; C and Fortran order; an oldtype with a gap), the
 * type must hold exactly that process's elements, in the array's storage order, with lower
 * bound 0 and the whole array as extent: what MPI_Pack writes is checked against the owned
 * elements, and the processes' parts together must cover the array once.  Then the ranks
 * send their parts to rank 0, which receives each with that rank's darray type into the
 * whole array; decoding; argument errors.
 *
 * Plain MPI C: it builds with tilesim's mpi.h and with Open MPI's mpicc, and prints the same
 * "dtype_darray: P passed, F failed" line under both. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

enum { MAXD = 3, MAXN = 4096 };

typedef struct {
  const char *name;
  int ndims, gsizes[MAXD], distribs[MAXD], dargs[MAXD], psizes[MAXD], order;
} layout;

/* The grid coordinate owning index i of dimension d. */
static int owner(const layout *l, int d, int i) {
  int g = l->gsizes[d], p = l->psizes[d], b = l->dargs[d];
  switch (l->distribs[d]) {
  case MPI_DISTRIBUTE_BLOCK:
    if (b == MPI_DISTRIBUTE_DFLT_DARG) b = (g + p - 1) / p;
    return i / b;
  case MPI_DISTRIBUTE_CYCLIC:
    if (b == MPI_DISTRIBUTE_DFLT_DARG) b = 1;
    return i / b % p;
  default:
    return 0;
  }
}

/* The process (row-major in the grid) owning the element of linear index
 * k in storage order. */
static int owner_of(const layout *l, int k) {
  int idx[MAXD], rank = 0;
  for (int s = 0; s < l->ndims; s++) {   /* fastest-varying dimension first */
    int d = l->order == MPI_ORDER_C ? l->ndims - 1 - s : s;
    idx[d] = k % l->gsizes[d];
    k /= l->gsizes[d];
  }
  for (int d = 0; d < l->ndims; d++) rank = rank * l->psizes[d] + owner(l, d, idx[d]);
  return rank;
}

static int elements(const layout *l) {
  int n = 1;
  for (int d = 0; d < l->ndims; d++) n *= l->gsizes[d];
  return n;
}

static int processes(const layout *l) {
  int n = 1;
  for (int d = 0; d < l->ndims; d++) n *= l->psizes[d];
  return n;
}

static int make(const layout *l, int rank, MPI_Datatype old, MPI_Datatype *dt) {
  int rc = MPI_Type_create_darray(processes(l), rank, l->ndims, (int *)l->gsizes, (int *)l->distribs,
                                  (int *)l->dargs, (int *)l->psizes, l->order, old, dt);
  if (rc == MPI_SUCCESS) MPI_Type_commit(dt);
  return rc;
}

/* Every process's type of layout l on ints: extent, size, the elements
 * MPI_Pack writes; the parts cover the array once. */
static void check_layout(mtest *t, const layout *l) {
  static int a[MAXN], out[MAXN], seen[MAXN];
  int n = elements(l), np = processes(l), bad = 0;
  for (int k = 0; k < n; k++) a[k] = 1000 + k, seen[k] = 0;
  for (int r = 0; r < np; r++) {
    MPI_Datatype dt;
    if (make(l, r, MPI_INT, &dt) != MPI_SUCCESS) {
      MCHECK(t, 0, "%s: process %d: MPI_Type_create_darray failed", l->name, r);
      return;
    }
    int size, pos = 0, mine = 0;
    MPI_Aint lb, ext;
    MPI_Type_size(dt, &size);
    MPI_Type_get_extent(dt, &lb, &ext);
    for (int k = 0; k < n; k++) mine += owner_of(l, k) == r;
    if (lb != 0 || ext != (MPI_Aint)(n * sizeof(int)) || size != mine * (int)sizeof(int)) {
      MCHECK(t, 0, "%s: process %d: lb %ld extent %ld size %d; want 0 %ld %d", l->name, r, (long)lb, (long)ext, size,
             (long)(n * sizeof(int)), mine * (int)sizeof(int));
      bad++;
    } else {
      MPI_Pack(a, 1, dt, out, (int)sizeof out, &pos, MPI_COMM_WORLD);
      int j = 0;
      for (int k = 0; k < n; k++) {
        if (owner_of(l, k) != r) continue;
        if (out[j++] != a[k]) bad++;
        seen[k]++;
      }
    }
    MPI_Type_free(&dt);
  }
  for (int k = 0; k < n; k++) bad += seen[k] != 1;
  MCHECK(t, bad == 0, "%s: %d elements misplaced", l->name, bad);
}

static const layout layouts[] = {
  {"block 10 on 3", 1, {10}, {MPI_DISTRIBUTE_BLOCK}, {MPI_DISTRIBUTE_DFLT_DARG}, {3}, MPI_ORDER_C},
  {"block(5) 9 on 2", 1, {9}, {MPI_DISTRIBUTE_BLOCK}, {5}, {2}, MPI_ORDER_C},
  {"block(4) 9 on 4 (the last process empty)", 1, {9}, {MPI_DISTRIBUTE_BLOCK}, {4}, {4}, MPI_ORDER_FORTRAN},
  {"cyclic 10 on 4", 1, {10}, {MPI_DISTRIBUTE_CYCLIC}, {MPI_DISTRIBUTE_DFLT_DARG}, {4}, MPI_ORDER_C},
  {"cyclic(3) 11 on 2", 1, {11}, {MPI_DISTRIBUTE_CYCLIC}, {3}, {2}, MPI_ORDER_C},
  {"none 7 on 1", 1, {7}, {MPI_DISTRIBUTE_NONE}, {MPI_DISTRIBUTE_DFLT_DARG}, {1}, MPI_ORDER_C},
  {"C 6x5 block x cyclic(2) on 2x3", 2, {6, 5}, {MPI_DISTRIBUTE_BLOCK, MPI_DISTRIBUTE_CYCLIC},
   {MPI_DISTRIBUTE_DFLT_DARG, 2}, {2, 3}, MPI_ORDER_C},
  {"Fortran 6x5 block x cyclic(2) on 2x3", 2, {6, 5}, {MPI_DISTRIBUTE_BLOCK, MPI_DISTRIBUTE_CYCLIC},
   {MPI_DISTRIBUTE_DFLT_DARG, 2}, {2, 3}, MPI_ORDER_FORTRAN},
  {"C 5x7 cyclic x none on 4x1", 2, {5, 7}, {MPI_DISTRIBUTE_CYCLIC, MPI_DISTRIBUTE_NONE},
   {MPI_DISTRIBUTE_DFLT_DARG, MPI_DISTRIBUTE_DFLT_DARG}, {4, 1}, MPI_ORDER_C},
  {"C 4x6x5 none x block x cyclic(2) on 1x2x2", 3, {4, 6, 5},
   {MPI_DISTRIBUTE_NONE, MPI_DISTRIBUTE_BLOCK, MPI_DISTRIBUTE_CYCLIC}, {MPI_DISTRIBUTE_DFLT_DARG, 3, 2}, {1, 2, 2},
   MPI_ORDER_C},
  {"Fortran 3x8x5 cyclic(2) x block x cyclic on 2x3x2", 3, {3, 8, 5},
   {MPI_DISTRIBUTE_CYCLIC, MPI_DISTRIBUTE_BLOCK, MPI_DISTRIBUTE_CYCLIC},
   {2, MPI_DISTRIBUTE_DFLT_DARG, MPI_DISTRIBUTE_DFLT_DARG}, {2, 3, 2}, MPI_ORDER_FORTRAN},
  {"C 18x4 block x block on 6x3 (row blocks of 3)", 2, {18, 4}, {MPI_DISTRIBUTE_BLOCK, MPI_DISTRIBUTE_BLOCK},
   {MPI_DISTRIBUTE_DFLT_DARG, MPI_DISTRIBUTE_DFLT_DARG}, {6, 3}, MPI_ORDER_C},
};

/* An oldtype with a gap and a lower bound below 0: the darray places
 * element k at k extents, with the oldtype's own layout inside. */
static void test_gapped_oldtype(mtest *t) {
  MPI_Datatype r, dt;
  MPI_Type_create_resized(MPI_INT, -4, 12, &r);   /* an int at 0 of each 12 bytes, lb -4 */
  layout l = {"cyclic(2) 10 on 3, resized int", 1, {10}, {MPI_DISTRIBUTE_CYCLIC}, {2}, {3}, MPI_ORDER_C};
  int a[40], out[10], pos = 0;
  for (int i = 0; i < 40; i++) a[i] = i;
  make(&l, 1, r, &dt);   /* elements 2 3, 8 9 */
  MPI_Aint lb, ext, tlb, text;
  MPI_Type_get_extent(dt, &lb, &ext);
  MPI_Type_get_true_extent(dt, &tlb, &text);
  MPI_Pack(a + 1, 1, dt, out, (int)sizeof out, &pos, MPI_COMM_WORLD);   /* element 0's int is a[1] */
  MCHECK(t, lb == 0 && ext == 120 && tlb == 24 && text == 88 && pos == 16 && out[0] == 7 && out[1] == 10 &&
                out[2] == 25 && out[3] == 28,
         "%s: lb %ld extent %ld true %ld %ld, %d bytes: %d %d %d %d", l.name, (long)lb, (long)ext, (long)tlb,
         (long)text, pos, out[0], out[1], out[2], out[3]);
  MPI_Type_free(&dt);
  MPI_Type_free(&r);
}

/* The ranks of MPI_COMM_WORLD own a block-cyclic 2-D array (a grid of
 * size x 1 or 2 x size/2); each sends its part as plain ints to rank 0,
 * which receives it with that rank's darray type into the whole array. */
static void test_gather(mtest *t) {
  int size = t->size, rank = t->rank;
  layout l = {"world", 2, {7, 6}, {MPI_DISTRIBUTE_CYCLIC, MPI_DISTRIBUTE_BLOCK}, {2, MPI_DISTRIBUTE_DFLT_DARG},
              {size, 1}, MPI_ORDER_FORTRAN};
  if (size % 2 == 0 && size <= 6) l.psizes[0] = 2, l.psizes[1] = size / 2;
  int n = elements(&l), whole[42], mine[42] = {0}, cnt = 0;
  for (int k = 0; k < n; k++)
    if (owner_of(&l, k) == rank) mine[cnt++] = 100 * rank + k;
  MPI_Request req;
  MPI_Isend(mine, cnt, MPI_INT, 0, 9, MPI_COMM_WORLD, &req);
  if (rank == 0) {
    for (int k = 0; k < n; k++) whole[k] = -1;
    for (int r = 0; r < size; r++) {
      MPI_Datatype dt;
      make(&l, r, MPI_INT, &dt);
      MPI_Recv(whole, 1, dt, r, 9, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Type_free(&dt);
    }
    int bad = 0;
    for (int k = 0; k < n; k++) bad += whole[k] != 100 * owner_of(&l, k) + k;
    MCHECK(t, bad == 0, "the array gathered from %d ranks' darrays: %d elements wrong", size, bad);
  }
  MPI_Wait(&req, MPI_STATUS_IGNORE);
}

static void test_decoding(mtest *t) {
  const layout *l = &layouts[10];
  MPI_Datatype dt;
  make(l, 5, MPI_INT, &dt);
  int ni, na, nd, comb;
  MPI_Type_get_envelope(dt, &ni, &na, &nd, &comb);
  MCHECK(t, comb == MPI_COMBINER_DARRAY && ni == 4 * 3 + 4 && na == 0 && nd == 1, "darray's envelope %d %d %d %d",
         comb, ni, na, nd);
  int ints[16];
  MPI_Aint none[1];
  MPI_Datatype old[1];
  MPI_Type_get_contents(dt, 16, 0, 1, ints, none, old);
  MCHECK(t, ints[0] == 12 && ints[1] == 5 && ints[2] == 3 && ints[3] == 3 && ints[6] == MPI_DISTRIBUTE_CYCLIC &&
                ints[9] == 2 && ints[10] == MPI_DISTRIBUTE_DFLT_DARG && ints[14] == 2 &&
                ints[15] == MPI_ORDER_FORTRAN && old[0] == MPI_INT,
         "darray's contents: %d %d %d ... order %d", ints[0], ints[1], ints[2], ints[15]);
  MPI_Type_free(&dt);
}

static void test_errors(mtest *t) {
  MPI_Datatype dt;
  int g[2] = {10, 4}, dist[2] = {MPI_DISTRIBUTE_BLOCK, MPI_DISTRIBUTE_BLOCK}, darg[2] = {2, MPI_DISTRIBUTE_DFLT_DARG},
      ps[2] = {3, 1};
  MCHECK(t, MPI_Type_create_darray(3, 0, 2, g, dist, darg, ps, MPI_ORDER_C, MPI_INT, &dt) != MPI_SUCCESS,
         "3 blocks of 2 for 10 elements accepted");
  darg[0] = MPI_DISTRIBUTE_DFLT_DARG;
  MCHECK(t, MPI_Type_create_darray(4, 0, 2, g, dist, darg, ps, MPI_ORDER_C, MPI_INT, &dt) != MPI_SUCCESS,
         "a grid of 3 processes for size 4 accepted");
  MCHECK(t, MPI_Type_create_darray(3, 3, 2, g, dist, darg, ps, MPI_ORDER_C, MPI_INT, &dt) != MPI_SUCCESS,
         "rank 3 of 3 accepted");
  MCHECK(t, MPI_Type_create_darray(3, 0, 2, g, dist, darg, ps, 99, MPI_INT, &dt) != MPI_SUCCESS, "order 99 accepted");
  if (TILESIM) {
    /* Open MPI divides by a zero darg and treats none on 2 processes as
     * block: tilesim refuses both. */
    int cyc[1] = {MPI_DISTRIBUTE_CYCLIC}, zero[1] = {0}, one[1] = {10}, two[1] = {2}, none[1] = {MPI_DISTRIBUTE_NONE};
    SCHECK(t, MPI_Type_create_darray(1, 0, 1, one, cyc, zero, ps + 1, MPI_ORDER_C, MPI_INT, &dt) == MPI_ERR_ARG,
           "a cyclic darg of 0 accepted");
    SCHECK(t, MPI_Type_create_darray(2, 0, 1, one, none, darg + 1, two, MPI_ORDER_C, MPI_INT, &dt) == MPI_ERR_ARG,
           "MPI_DISTRIBUTE_NONE on 2 processes accepted");
  }
}

/* Every distribution of the table. */
static void test_layouts(mtest *t) {
  for (size_t i = 0; i < sizeof layouts / sizeof layouts[0]; i++) check_layout(t, &layouts[i]);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {mtest_rank0,  test_layouts, test_gapped_oldtype, test_decoding, test_errors,
                                    mtest_every_rank, test_gather, NULL};
  return mtest_main(&argc, &argv, "dtype_darray", 1, MTEST_ERRORS_RETURN, checks);
}
