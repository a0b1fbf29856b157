/* dtype_maps.c -- derived datatypes against hand-computed type maps (MPI 3.1 chapter 4): each
 * constructor's size, lower bound, extent and true extent, the order MPI_Pack writes its
 * elements in (gaps, negative displacements and strides, out-of-order blocks, structs with
 * padding, resized types, subarrays in C and Fortran order), MPI_Pack/MPI_Unpack round trips
 * at offsets, MPI_Pack_size, MPI_Get_address, decoding (envelope and contents), derived types
 * sent between ranks and received as another type of the same signature, MPI_Type_free before
 * a pending receive completes, MPI_Get_count and MPI_Get_elements, statuses set by
 * MPI_Status_set_elements, names, and argument errors.
 *
 * Plain MPI C: it builds with tilesim's mpi.h and with Open MPI's mpicc, and prints the same
 * "dtype_maps: P passed, F failed" line under both. */
#include <mpi.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "dtypetest.h"
#include "mtest.h"

/* Pack count elements of dt at buf and compare with the ints want[n]. */
static void packs_ints(mtest *t, const char *what, const void *buf, int count, MPI_Datatype dt, const int *want,
                       int n) {
  int out[64], pos = 0;
  memset(out, 0x55, sizeof out);
  int rc = MPI_Pack(buf, count, dt, out, (int)sizeof out, &pos, MPI_COMM_WORLD);
  MCHECK(t, rc == MPI_SUCCESS && pos == n * (int)sizeof(int) && memcmp(out, want, (size_t)n * sizeof(int)) == 0,
         "%s: MPI_Pack rc %d, %d bytes, first ints %d %d %d", what, rc, pos, out[0], out[1], out[2]);
  /* and back: unpack into a zeroed copy, and pack again */
  int back[128], again[64], p2 = 0, p3 = 0;
  memset(back, 0, sizeof back);
  MPI_Aint lb, ext, tlb, text;
  MPI_Type_get_extent(dt, &lb, &ext);
  MPI_Type_get_true_extent(dt, &tlb, &text);
  char *base = (char *)back + 256;   /* room on both sides of the elements */
  (void)lb, (void)ext, (void)tlb, (void)text;
  rc = MPI_Unpack(out, pos, &p2, base, count, dt, MPI_COMM_WORLD);
  if (rc == MPI_SUCCESS) rc = MPI_Pack(base, count, dt, again, (int)sizeof again, &p3, MPI_COMM_WORLD);
  MCHECK(t, rc == MPI_SUCCESS && p2 == pos && p3 == pos && memcmp(again, want, (size_t)n * sizeof(int)) == 0,
         "%s: unpack and pack again: rc %d, %d and %d bytes", what, rc, p2, p3);
}

static void test_contiguous_vector(mtest *t) {
  int a[32];
  for (int i = 0; i < 32; i++) a[i] = i;
  MPI_Datatype c, v, nv, hv;
  MPI_Type_contiguous(3, MPI_INT, &c);
  MPI_Type_commit(&c);
  shape(t, "contiguous(3, int)", c, 12, 0, 12, 0, 12);
  int wc[6] = {0, 1, 2, 3, 4, 5};
  packs_ints(t, "contiguous(3, int) x 2", a, 2, c, wc, 6);

  MPI_Type_vector(3, 2, 4, MPI_INT, &v);   /* ints 0 1, 4 5, 8 9 */
  MPI_Type_commit(&v);
  shape(t, "vector(3, 2, 4, int)", v, 24, 0, 40, 0, 40);
  int wv[12] = {0, 1, 4, 5, 8, 9, 10, 11, 14, 15, 18, 19};   /* two elements, one extent (10 ints) apart */
  packs_ints(t, "vector(3, 2, 4, int) x 2", a, 2, v, wv, 12);

  MPI_Type_vector(3, 1, -2, MPI_INT, &nv);   /* ints at 0, -2, -4 */
  MPI_Type_commit(&nv);
  shape(t, "vector(3, 1, -2, int)", nv, 12, -16, 20, -16, 20);
  int wn[3] = {10, 8, 6};
  packs_ints(t, "vector(3, 1, -2, int) from a[10]", &a[10], 1, nv, wn, 3);

  MPI_Type_create_hvector(2, 3, 20, MPI_INT, &hv);   /* ints 0 1 2, 5 6 7 */
  MPI_Type_commit(&hv);
  shape(t, "hvector(2, 3, 20 bytes, int)", hv, 24, 0, 32, 0, 32);
  int wh[6] = {0, 1, 2, 5, 6, 7};
  packs_ints(t, "hvector(2, 3, 20 bytes, int)", a, 1, hv, wh, 6);
  MPI_Type_free(&c);
  MPI_Type_free(&v);
  MPI_Type_free(&nv);
  MPI_Type_free(&hv);
}

static void test_indexed(mtest *t) {
  int a[32];
  for (int i = 0; i < 32; i++) a[i] = 100 + i;
  MPI_Datatype x, hx, bx, hbx;
  int bl[3] = {2, 1, 3}, dp[3] = {5, 0, 2};
  MPI_Type_indexed(3, bl, dp, MPI_INT, &x);   /* 5 6, 0, 2 3 4: type-map order, not address order */
  MPI_Type_commit(&x);
  shape(t, "indexed({2,1,3}, {5,0,2}, int)", x, 24, 0, 28, 0, 28);
  int wx[6] = {105, 106, 100, 102, 103, 104};
  packs_ints(t, "indexed out of order", a, 1, x, wx, 6);

  int hbl[2] = {1, 2};
  MPI_Aint hdp[2] = {-8, 12};   /* ints at -2 and 3 4 */
  MPI_Type_create_hindexed(2, hbl, hdp, MPI_INT, &hx);
  MPI_Type_commit(&hx);
  shape(t, "hindexed({1,2}, {-8,12}, int)", hx, 12, -8, 28, -8, 28);
  int whx[3] = {108, 113, 114};
  packs_ints(t, "hindexed with a negative displacement, from a[10]", &a[10], 1, hx, whx, 3);

  int bdp[2] = {3, 0};
  MPI_Type_create_indexed_block(2, 2, bdp, MPI_INT, &bx);   /* 3 4, 0 1 */
  MPI_Type_commit(&bx);
  shape(t, "indexed_block(2, 2, {3,0}, int)", bx, 16, 0, 20, 0, 20);
  int wbx[4] = {103, 104, 100, 101};
  packs_ints(t, "indexed_block", a, 1, bx, wbx, 4);

  MPI_Aint hbdp[3] = {40, 4, 20};
  MPI_Type_create_hindexed_block(3, 1, hbdp, MPI_INT, &hbx);   /* 10, 1, 5 */
  MPI_Type_commit(&hbx);
  shape(t, "hindexed_block(3, 1, {40,4,20}, int)", hbx, 12, 4, 40, 4, 40);
  int whbx[6] = {110, 101, 105, 120, 111, 115};   /* two elements, extent 40 bytes */
  packs_ints(t, "hindexed_block x 2", a, 2, hbx, whbx, 6);
  MPI_Type_free(&x);
  MPI_Type_free(&hx);
  MPI_Type_free(&bx);
  MPI_Type_free(&hbx);
}

struct cdi {
  char c;
  double d;
  int i[2];
};

static void test_struct(mtest *t) {
  /* A C struct described by its members' addresses: the extent rounds up
   * to the strictest alignment (the padding after i). */
  struct cdi s[2] = {{'x', 1.5, {7, 8}}, {'y', -2.25, {9, 10}}};
  int bl[3] = {1, 1, 2};
  MPI_Aint base, disp[3];
  MPI_Datatype ty[3] = {MPI_CHAR, MPI_DOUBLE, MPI_INT}, st;
  MPI_Get_address(&s[0], &base);
  MPI_Get_address(&s[0].c, &disp[0]);
  MPI_Get_address(&s[0].d, &disp[1]);
  MPI_Get_address(&s[0].i, &disp[2]);
  for (int k = 0; k < 3; k++) disp[k] = MPI_Aint_diff(disp[k], base);
  MCHECK(t, disp[0] == (MPI_Aint)offsetof(struct cdi, c) && disp[1] == (MPI_Aint)offsetof(struct cdi, d) &&
                disp[2] == (MPI_Aint)offsetof(struct cdi, i),
         "MPI_Get_address differences %ld %ld %ld", (long)disp[0], (long)disp[1], (long)disp[2]);
  MPI_Type_create_struct(3, bl, disp, ty, &st);
  MPI_Type_commit(&st);
  int end = (int)(offsetof(struct cdi, i) + 2 * sizeof(int));
  shape(t, "struct {char, double, int[2]}", st, 17, 0, (MPI_Aint)sizeof(struct cdi), 0, end);
  char out[64];
  int pos = 0;
  MPI_Pack(s, 2, st, out, (int)sizeof out, &pos, MPI_COMM_WORLD);
  double d0, d1;
  int i0[2], i1[2];
  memcpy(&d0, out + 1, 8);
  memcpy(i0, out + 9, 8);
  memcpy(&d1, out + 18, 8);
  memcpy(i1, out + 26, 8);
  MCHECK(t, pos == 34 && out[0] == 'x' && d0 == 1.5 && i0[0] == 7 && i0[1] == 8 && out[17] == 'y' && d1 == -2.25 &&
                i1[0] == 9 && i1[1] == 10,
         "two packed structs: %d bytes", pos);
  /* Unpack into zeroed structs: the members come back, padding untouched. */
  struct cdi r[2];
  memset(r, 0, sizeof r);
  int p2 = 0;
  MPI_Unpack(out, pos, &p2, r, 2, st, MPI_COMM_WORLD);
  MCHECK(t, r[0].c == 'x' && r[0].d == 1.5 && r[0].i[1] == 8 && r[1].c == 'y' && r[1].d == -2.25 && r[1].i[0] == 9,
         "unpacked structs differ");

  /* {int at 0, char at 4}: 5 bytes of data, extent 8. */
  int bl2[2] = {1, 1};
  MPI_Aint d2[2] = {0, 4};
  MPI_Datatype t2[2] = {MPI_INT, MPI_CHAR}, ic;
  MPI_Type_create_struct(2, bl2, d2, t2, &ic);
  MPI_Type_commit(&ic);
  shape(t, "struct {int, char}", ic, 5, 0, 8, 0, 5);
  MPI_Type_free(&st);
  MPI_Type_free(&ic);
}

static void test_resized_subarray(mtest *t) {
  int a[64];
  for (int i = 0; i < 64; i++) a[i] = i;
  MPI_Datatype r, cr, sub, fsub;
  MPI_Type_create_resized(MPI_INT, -4, 12, &r);   /* an int, then two ints' gap, lb -4 */
  MPI_Type_commit(&r);
  shape(t, "resized(int, -4, 12)", r, 4, -4, 12, 0, 4);
  MPI_Type_contiguous(3, r, &cr);   /* ints 0, 3, 6 */
  MPI_Type_commit(&cr);
  shape(t, "contiguous(3, resized)", cr, 12, -4, 36, 0, 28);
  int wr[3] = {0, 3, 6};
  packs_ints(t, "contiguous(3, resized)", a, 1, cr, wr, 3);

  int sizes[2] = {4, 5}, subs[2] = {2, 3}, starts[2] = {1, 1};
  MPI_Type_create_subarray(2, sizes, subs, starts, MPI_ORDER_C, MPI_INT, &sub);
  MPI_Type_commit(&sub);
  shape(t, "subarray C {4,5} {2,3} {1,1}", sub, 24, 0, 80, 24, 32);
  int ws[6] = {6, 7, 8, 11, 12, 13};
  packs_ints(t, "subarray C order", a, 1, sub, ws, 6);
  MPI_Type_create_subarray(2, sizes, subs, starts, MPI_ORDER_FORTRAN, MPI_INT, &fsub);
  MPI_Type_commit(&fsub);
  shape(t, "subarray Fortran {4,5} {2,3} {1,1}", fsub, 24, 0, 80, 20, 40);
  int wf[6] = {5, 6, 9, 10, 13, 14};
  packs_ints(t, "subarray Fortran order", a, 1, fsub, wf, 6);
  MPI_Type_free(&r);
  MPI_Type_free(&cr);
  MPI_Type_free(&sub);
  MPI_Type_free(&fsub);
}

/* MPI_Type_get_contents is checked under tilesim only, and counts only
 * when it fails: Open MPI 4.1.4's crashes on these types. */
#define CONTENTS TILESIM

static void test_decoding(mtest *t) {
  MPI_Datatype v, d, got[2];
  MPI_Type_vector(3, 2, 4, MPI_INT, &v);
  int ni, na, nd, comb, ints[4];
  MPI_Aint addr[2];
  MPI_Type_get_envelope(v, &ni, &na, &nd, &comb);
  MCHECK(t, comb == MPI_COMBINER_VECTOR && ni == 3 && na == 0 && nd == 1, "vector's envelope %d %d %d %d", comb, ni,
         na, nd);
  MPI_Type_dup(v, &d);
  MPI_Type_get_envelope(d, &ni, &na, &nd, &comb);
  MCHECK(t, comb == MPI_COMBINER_DUP && nd == 1, "dup's envelope %d", comb);
  MPI_Type_get_envelope(MPI_DOUBLE, &ni, &na, &nd, &comb);
  MCHECK(t, comb == MPI_COMBINER_NAMED, "MPI_DOUBLE's combiner %d", comb);
  if (CONTENTS) {
    MPI_Type_get_contents(v, 4, 2, 2, ints, addr, got);
    SCHECK(t, ints[0] == 3 && ints[1] == 2 && ints[2] == 4 && got[0] == MPI_INT, "vector's contents %d %d %d",
           ints[0], ints[1], ints[2]);
    MPI_Type_get_contents(d, 4, 2, 2, ints, addr, got);
    int s;
    MPI_Type_size(got[0], &s);
    SCHECK(t, s == 24, "dup's contents: a type of %d bytes", s);
    MPI_Type_free(&got[0]);
  }
  MPI_Type_free(&v);
  MPI_Type_free(&d);
}

/* Derived types across ranks: each rank sends rank + 1 a column of a 4 x 5
 * int matrix (a vector) and receives it as 4 contiguous ints; then a
 * receive with a derived type whose handle is freed before it completes. */
static void test_send(mtest *t) {
  int rank = t->rank, size = t->size, m[4][5], col[4];
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 5; j++) m[i][j] = 1000 * rank + 10 * i + j;
  MPI_Datatype column, pair;
  MPI_Type_vector(4, 1, 5, MPI_INT, &column);
  MPI_Type_commit(&column);
  int to = (rank + 1) % size, from = (rank - 1 + size) % size;
  MPI_Sendrecv(&m[0][2], 1, column, to, 5, col, 4, MPI_INT, from, 5, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MCHECK(t, col[0] == 1000 * from + 2 && col[3] == 1000 * from + 32, "column from rank %d: %d .. %d", from, col[0],
         col[3]);

  MPI_Type_vector(2, 1, 3, MPI_INT, &pair);
  MPI_Type_commit(&pair);
  int got[6] = {-1, -1, -1, -1, -1, -1}, send[2] = {rank, -rank};
  MPI_Request req;
  MPI_Irecv(got, 1, pair, from, 6, MPI_COMM_WORLD, &req);
  MPI_Type_free(&pair);   /* MPI 3.1 section 4.1.9: the pending receive goes on */
  MCHECK(t, pair == MPI_DATATYPE_NULL, "MPI_Type_free left the handle");
  MPI_Send(send, 2, MPI_INT, to, 6, MPI_COMM_WORLD);
  MPI_Status st;
  MPI_Wait(&req, &st);
  MCHECK(t, got[0] == from && got[3] == -from && got[1] == -1 && got[2] == -1, "freed type's receive: %d %d %d %d",
         got[0], got[1], got[2], got[3]);
  MPI_Type_free(&column);

  /* Counts: 4 ints received with a {int, double} struct type: one whole
   * element (2 basic ones) and an int. */
  int four[4] = {1, 2, 3, 4};
  char buf[64];
  int bl[2] = {1, 1}, n;
  MPI_Aint dp[2] = {0, 8};
  MPI_Datatype ty[2] = {MPI_INT, MPI_DOUBLE}, id;
  MPI_Type_create_struct(2, bl, dp, ty, &id);
  MPI_Type_commit(&id);
  MPI_Sendrecv(four, 4, MPI_INT, rank, 7, buf, 3, id, rank, 7, MPI_COMM_WORLD, &st);
  MPI_Get_count(&st, id, &n);
  MCHECK(t, n == MPI_UNDEFINED, "MPI_Get_count of 16 bytes as {int, double}: %d", n);
  MPI_Get_elements(&st, id, &n);
  MCHECK(t, n == 3, "MPI_Get_elements of 16 bytes as {int, double}: %d", n);
  MPI_Get_count(&st, MPI_INT, &n);
  MCHECK(t, n == 4, "MPI_Get_count as MPI_INT: %d", n);
  MPI_Type_free(&id);
}

static void test_pack_api(mtest *t) {
  int size, rc, pos;
  MPI_Pack_size(5, MPI_DOUBLE, MPI_COMM_WORLD, &size);
  MCHECK(t, size >= 40, "MPI_Pack_size of 5 doubles: %d", size);
  /* Two packs one after the other, unpacked in turn. */
  double d[3] = {1.25, -3.5, 8};
  short s[2] = {-7, 9};
  char buf[128];
  pos = 0;
  rc = MPI_Pack(d, 3, MPI_DOUBLE, buf, (int)sizeof buf, &pos, MPI_COMM_WORLD);
  if (!rc) rc = MPI_Pack(s, 2, MPI_SHORT, buf, (int)sizeof buf, &pos, MPI_COMM_WORLD);
  double d2[3] = {0, 0, 0};
  short s2[2] = {0, 0};
  int in = 0;
  if (!rc) rc = MPI_Unpack(buf, pos, &in, d2, 3, MPI_DOUBLE, MPI_COMM_WORLD);
  if (!rc) rc = MPI_Unpack(buf, pos, &in, s2, 2, MPI_SHORT, MPI_COMM_WORLD);
  MCHECK(t, rc == MPI_SUCCESS && in == pos && d2[1] == -3.5 && d2[2] == 8 && s2[0] == -7 && s2[1] == 9,
         "two packs and unpacks: rc %d, %d of %d bytes", rc, in, pos);
  /* Too little room, too little data. */
  pos = 0;
  rc = MPI_Pack(d, 3, MPI_DOUBLE, buf, 16, &pos, MPI_COMM_WORLD);
  MCHECK(t, rc != MPI_SUCCESS, "MPI_Pack of 24 bytes into 16 succeeded");
  in = 0;
  rc = MPI_Unpack(buf, 8, &in, d2, 3, MPI_DOUBLE, MPI_COMM_WORLD);
  MCHECK(t, rc != MPI_SUCCESS, "MPI_Unpack of 24 bytes from 8 succeeded");
}

/* A status made by MPI_Status_set_elements (as a generalized request's
 * query function makes one). */
static void test_status(mtest *t) {
  MPI_Status st;
  int n;
  MPI_Count x;
  MPI_Status_set_elements(&st, MPI_INT, 5);
  MPI_Get_count(&st, MPI_INT, &n);
  MCHECK(t, n == 5, "MPI_Get_count after MPI_Status_set_elements(5 MPI_INT): %d", n);
  MPI_Get_count(&st, MPI_BYTE, &n);
  MCHECK(t, n == 20, "MPI_Get_count as MPI_BYTE: %d", n);
  /* {int, double}: 3 basic elements are one element and an int. */
  int bl[2] = {1, 1};
  MPI_Aint dp[2] = {0, 8};
  MPI_Datatype ty[2] = {MPI_INT, MPI_DOUBLE}, id;
  MPI_Type_create_struct(2, bl, dp, ty, &id);
  MPI_Type_commit(&id);
  MPI_Status_set_elements(&st, id, 3);
  MPI_Get_elements(&st, id, &n);
  MCHECK(t, n == 3, "MPI_Get_elements after setting 3 of {int, double}: %d", n);
  MPI_Get_count(&st, id, &n);
  MCHECK(t, n == MPI_UNDEFINED, "MPI_Get_count after setting 3 of {int, double}: %d", n);
  MPI_Get_count(&st, MPI_BYTE, &n);
  MCHECK(t, n == 16, "3 basic elements of {int, double} in bytes: %d", n);
  MPI_Status_set_elements_x(&st, MPI_SHORT, 7);
  MPI_Get_elements_x(&st, MPI_SHORT, &x);
  MPI_Get_count(&st, MPI_CHAR, &n);
  MCHECK(t, x == 7 && n == 14, "7 MPI_SHORT set: %lld elements, %d chars", (long long)x, n);
  MPI_Type_free(&id);
}

/* Names: predefined ones, set on a predefined type (each rank its own, as
 * each process its own) and on a derived one. */
static void test_names(mtest *t) {
  char name[MPI_MAX_OBJECT_NAME], mine[32];
  int len;
  MPI_Type_get_name(MPI_DOUBLE, name, &len);
  MCHECK(t, !strcmp(name, "MPI_DOUBLE") && len == 10, "MPI_DOUBLE's name '%s' (%d)", name, len);
  snprintf(mine, sizeof mine, "int of rank %d", t->rank);
  MPI_Type_set_name(MPI_INT, mine);
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Type_get_name(MPI_INT, name, &len);
  MCHECK(t, !strcmp(name, mine), "MPI_INT renamed '%s', reads '%s'", mine, name);
  MPI_Type_set_name(MPI_INT, "MPI_INT");
  MPI_Datatype c;
  MPI_Type_contiguous(2, MPI_INT, &c);
  MPI_Type_get_name(c, name, &len);
  MCHECK(t, len == 0 && name[0] == 0, "a new type's name '%s'", name);
  MPI_Type_set_name(c, "pair of ints");
  MPI_Type_get_name(c, name, &len);
  MCHECK(t, !strcmp(name, "pair of ints") && len == 12, "a derived type's name '%s'", name);
  MPI_Type_free(&c);
}

static void test_errors(mtest *t) {
  MPI_Datatype v = MPI_DATATYPE_NULL, u;
  int x[4] = {0, 0, 0, 0};
  MCHECK(t, MPI_Type_vector(-1, 1, 1, MPI_INT, &v) != MPI_SUCCESS, "vector of count -1 succeeded");
  MCHECK(t, MPI_Type_contiguous(2, MPI_DATATYPE_NULL, &v) == MPI_ERR_TYPE, "contiguous of MPI_DATATYPE_NULL");
  MPI_Datatype f = MPI_INT;
  MCHECK(t, MPI_Type_free(&f) == MPI_ERR_TYPE, "MPI_Type_free(MPI_INT) succeeded");
  MPI_Type_contiguous(2, MPI_INT, &u);   /* not committed */
  MCHECK(t, MPI_Send(x, 1, u, MPI_PROC_NULL, 0, MPI_COMM_WORLD) == MPI_ERR_TYPE, "a send with an uncommitted type");
  int pos = 0;
  char b[16];
  MCHECK(t, MPI_Pack(x, 1, u, b, 16, &pos, MPI_COMM_WORLD) == MPI_ERR_TYPE, "a pack with an uncommitted type");
  MPI_Type_free(&u);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {test_contiguous_vector, test_indexed, test_struct, test_resized_subarray, test_decoding, test_pack_api, test_errors, test_status, test_names, test_send, NULL};
  return mtest_main(&argc, &argv, "dtype_maps", 1, MTEST_ERRORS_RETURN, checks);
}
