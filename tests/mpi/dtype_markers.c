/* dtype_markers.c -- the lower- and upper-bound markers MPI_LB and MPI_UB (removed by MPI 3.0,
 * kept by MPICH and Open MPI) and the explicit bounds of MPI_Type_create_resized, against the
 * type maps MPI 3.1 section 4.1.7 defines: a type's lower bound is the least displacement of its
 * explicit lb markers if it has any, else the least of all its entries; its upper bound the
 * greatest of its explicit ub markers, else the greatest end of all its entries plus a struct's
 * alignment padding; markers stay explicit ("sticky") in every type built from one.  Each case
 * checks size, bounds and true bounds, and what MPI_Pack writes, element after element one
 * extent apart; then marked types between ranks and their decoding.
 *
 * Plain MPI C: it builds with tilesim's mpi.h and with Open MPI's mpicc, and prints the same
 * "dtype_markers: P passed, F failed" line under both.  Open MPI 4.1, built without
 * --enable-mpi1-compatibility, hides MPI_LB and MPI_UB behind a static assertion in mpi.h; its
 * library has them all the same, and this program names them there. */
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "dtypetest.h"
#include "mtest.h"

#if defined(OPEN_MPI) && !OMPI_ENABLE_MPI1_COMPAT
#undef MPI_LB
#undef MPI_UB
extern struct ompi_predefined_datatype_t ompi_mpi_lb, ompi_mpi_ub;
#define MPI_LB ((MPI_Datatype)(void *)&ompi_mpi_lb)
#define MPI_UB ((MPI_Datatype)(void *)&ompi_mpi_ub)
#endif

/* A struct of n blocks of one element each. */
static MPI_Datatype make_struct(int n, const MPI_Aint *disp, const MPI_Datatype *types) {
  int bl[8] = {1, 1, 1, 1, 1, 1, 1, 1};
  MPI_Datatype dt;
  MPI_Type_create_struct(n, bl, (MPI_Aint *)disp, (MPI_Datatype *)types, &dt);
  MPI_Type_commit(&dt);
  return dt;
}

/* Pack count elements of dt from base (an int array, the elements at
 * byte offset off) and compare with the ints at indices want[n]. */
static void packs(mtest *t, const char *what, const int *base, int off, int count, MPI_Datatype dt, const int *want,
                  int n) {
  int out[64], pos = 0;
  memset(out, 0x55, sizeof out);
  int rc = MPI_Pack((const char *)base + off, count, dt, out, (int)sizeof out, &pos, MPI_COMM_WORLD);
  int bad = rc != MPI_SUCCESS || pos != n * (int)sizeof(int);
  for (int i = 0; i < n && !bad; i++) bad = out[i] != base[want[i]];
  MCHECK(t, !bad, "%s: MPI_Pack rc %d, %d bytes, first ints %d %d %d", what, rc, pos, out[0], out[1], out[2]);
}

static void test_predefined(mtest *t) {
  shape(t, "MPI_LB", MPI_LB, 0, 0, 0, 0, 0);
  shape(t, "MPI_UB", MPI_UB, 0, 0, 0, 0, 0);
  char name[MPI_MAX_OBJECT_NAME];
  int len, ni, na, nd, comb;
  MPI_Type_get_name(MPI_LB, name, &len);
  MCHECK(t, !strcmp(name, "MPI_LB") && len == 6, "MPI_LB's name '%s'", name);
  MPI_Type_get_name(MPI_UB, name, &len);
  MCHECK(t, !strcmp(name, "MPI_UB") && len == 6, "MPI_UB's name '%s'", name);
  MPI_Type_get_envelope(MPI_UB, &ni, &na, &nd, &comb);
  MCHECK(t, comb == MPI_COMBINER_NAMED, "MPI_UB's combiner %d", comb);
}

static void test_struct_markers(mtest *t) {
  int a[64];
  for (int i = 0; i < 64; i++) a[i] = i;
  /* {(lb, -8), (int, 0), (ub, 40)}: lb -8, ub 40; elements 48 bytes apart. */
  MPI_Aint d1[3] = {-8, 0, 40};
  MPI_Datatype t1[3] = {MPI_LB, MPI_INT, MPI_UB}, liu = make_struct(3, d1, t1);
  shape(t, "{lb -8, int 0, ub 40}", liu, 4, -8, 48, 0, 4);
  int w1[3] = {2, 14, 26};   /* from a[2]: ints 0, 12, 24 on */
  packs(t, "{lb -8, int 0, ub 40} x 3", a, 8, 3, liu, w1, 3);

  /* Two lb markers: the least; the ub marker, not the data, ends it. */
  MPI_Aint d2[4] = {8, 0, 2, 20};
  MPI_Datatype t2[4] = {MPI_LB, MPI_INT, MPI_LB, MPI_UB}, two = make_struct(4, d2, t2);
  shape(t, "{lb 8, int 0, lb 2, ub 20}", two, 4, 2, 18, 0, 4);

  /* Two ub markers: the greatest; a char's struct not padded past it. */
  MPI_Aint d3[3] = {0, 4, 20};
  MPI_Datatype t3[3] = {MPI_CHAR, MPI_UB, MPI_UB}, cuu = make_struct(3, d3, t3);
  shape(t, "{char 0, ub 4, ub 20}", cuu, 1, 0, 20, 0, 1);

  /* An explicit ub inside the data: no alignment padding (a double's
   * struct would have extent 8). */
  MPI_Aint d4[2] = {0, 6};
  MPI_Datatype t4[2] = {MPI_DOUBLE, MPI_UB}, du = make_struct(2, d4, t4);
  shape(t, "{double 0, ub 6}", du, 8, 0, 6, 0, 8);

  /* An explicit lb only: the upper bound is the data's end padded so that
   * the extent (from the marker) is a multiple of 8: 8 + 6 -> 16. */
  MPI_Aint d5[2] = {-6, 0};
  MPI_Datatype t5[2] = {MPI_LB, MPI_DOUBLE}, lbonly = make_struct(2, d5, t5);
  shape(t, "{lb -6, double 0}", lbonly, 8, -6, 16, 0, 8);

  /* A marker with a blocklength: the markers of each copy, the least. */
  int bl6[2] = {3, 1};
  MPI_Aint d6[2] = {4, 0};
  MPI_Datatype t6[2] = {MPI_LB, MPI_DOUBLE}, lb3;
  MPI_Type_create_struct(2, bl6, d6, t6, &lb3);
  MPI_Type_commit(&lb3);
  shape(t, "{3 x lb 4, double 0}", lb3, 8, 4, 8, 0, 8);

  /* A struct of one int between markers, packed from a struct array. */
  struct {
    double pad;
    int v;
    int more[3];
  } rec[3] = {{0, 10, {0}}, {0, 11, {0}}, {0, 12, {0}}};
  MPI_Aint d7[3] = {0, 8, (MPI_Aint)sizeof rec[0]};
  MPI_Datatype t7[3] = {MPI_LB, MPI_INT, MPI_UB}, field = make_struct(3, d7, t7);
  int got[3] = {0, 0, 0}, pos = 0;
  MPI_Pack(rec, 3, field, got, (int)sizeof got, &pos, MPI_COMM_WORLD);
  MCHECK(t, pos == 12 && got[0] == 10 && got[1] == 11 && got[2] == 12, "a field of 3 records: %d bytes, %d %d %d", pos,
         got[0], got[1], got[2]);

  MPI_Type_free(&liu);
  MPI_Type_free(&two);
  MPI_Type_free(&cuu);
  MPI_Type_free(&du);
  MPI_Type_free(&lbonly);
  MPI_Type_free(&lb3);
  MPI_Type_free(&field);
}

/* Markers stay explicit in the types built on them. */
static void test_sticky(mtest *t) {
  int a[64];
  for (int i = 0; i < 64; i++) a[i] = i;
  MPI_Aint d1[3] = {-8, 0, 40};
  MPI_Datatype t1[3] = {MPI_LB, MPI_INT, MPI_UB}, liu = make_struct(3, d1, t1), c3, s2, r0, r4, s3, s4, v, hv, ub12,
               s5;
  MPI_Type_contiguous(3, liu, &c3);
  MPI_Type_commit(&c3);
  shape(t, "contiguous(3, {lb -8, int, ub 40})", c3, 12, -8, 144, 0, 100);
  int w3[6] = {2, 14, 26, 38, 50, 62};
  packs(t, "contiguous(3, {lb -8, int, ub 40}) x 2", a, 8, 2, c3, w3, 6);

  /* An int past the marked type's ub does not move its bounds. */
  MPI_Aint d2[2] = {0, 100};
  MPI_Datatype t2[2] = {liu, MPI_INT};
  s2 = make_struct(2, d2, t2);
  shape(t, "{marked at 0, int at 100}", s2, 8, -8, 48, 0, 104);

  /* Resized types' bounds are explicit markers too. */
  MPI_Type_create_resized(MPI_INT, 0, 16, &r0);
  MPI_Type_create_resized(MPI_INT, -4, 16, &r4);
  MPI_Aint d3[2] = {0, 16};
  MPI_Datatype t3[2] = {r0, MPI_CHAR};
  s3 = make_struct(2, d3, t3);
  shape(t, "{resized(int, 0, 16) at 0, char at 16}", s3, 5, 0, 16, 0, 17);
  MPI_Aint d4[2] = {0, -100};
  MPI_Datatype t4[2] = {r4, MPI_INT};
  s4 = make_struct(2, d4, t4);
  shape(t, "{resized(int, -4, 16) at 0, int at -100}", s4, 8, -4, 16, -100, 104);
  int w4[2] = {30, 5};   /* from a[30]: the int at 0, then the one at -100 bytes */
  packs(t, "{resized(int, -4, 16) at 0, int at -100}", a, 120, 1, s4, w4, 2);

  /* A vector of negative stride of a resized type: copies at 0, -32, -64. */
  MPI_Type_vector(3, 1, -2, r4, &v);
  MPI_Type_commit(&v);
  shape(t, "vector(3, 1, -2, resized(int, -4, 16))", v, 12, -68, 80, -64, 68);
  int wv[3] = {20, 12, 4};
  packs(t, "vector(3, 1, -2, resized(int, -4, 16))", a, 80, 1, v, wv, 3);

  /* An hvector of a type with an explicit ub only: the lower bound is the
   * least of all entries, the upper the greatest ub marker. */
  MPI_Aint d5[2] = {0, 12};
  MPI_Datatype t5[2] = {MPI_INT, MPI_UB};
  ub12 = make_struct(2, d5, t5);
  MPI_Type_create_hvector(2, 2, -40, ub12, &hv);
  MPI_Type_commit(&hv);
  shape(t, "hvector(2, 2, -40, {int, ub 12})", hv, 16, -40, 64, -40, 56);
  int wh[4] = {20, 23, 10, 13};
  packs(t, "hvector(2, 2, -40, {int, ub 12})", a, 80, 1, hv, wh, 4);

  /* A struct holding a type with an explicit lb only, and a char below it:
   * the lb stays -6, the upper bound pads the extent from it. */
  MPI_Aint d6[2] = {-6, 0}, d7[2] = {0, -20};
  MPI_Datatype t6[2] = {MPI_LB, MPI_DOUBLE}, lbonly = make_struct(2, d6, t6);
  MPI_Datatype t7[2] = {lbonly, MPI_CHAR};
  s5 = make_struct(2, d7, t7);
  shape(t, "{{lb -6, double} at 0, char at -20}", s5, 9, -6, 16, -20, 28);

  MPI_Type_free(&liu);
  MPI_Type_free(&c3);
  MPI_Type_free(&s2);
  MPI_Type_free(&r0);
  MPI_Type_free(&r4);
  MPI_Type_free(&s3);
  MPI_Type_free(&s4);
  MPI_Type_free(&v);
  MPI_Type_free(&hv);
  MPI_Type_free(&ub12);
  MPI_Type_free(&lbonly);
  MPI_Type_free(&s5);
}

/* Every rank sends the next 3 elements of {lb 0, int 0, ub 12} (every
 * third int) and receives them as 3 ints; then counts. */
static void test_send(mtest *t) {
  int rank = t->rank, size = t->size, a[9], got[3] = {-1, -1, -1};
  for (int i = 0; i < 9; i++) a[i] = 100 * rank + i;
  MPI_Aint d[3] = {0, 0, 12};
  MPI_Datatype ty[3] = {MPI_LB, MPI_INT, MPI_UB}, every3 = make_struct(3, d, ty);
  int to = (rank + 1) % size, from = (rank - 1 + size) % size;
  MPI_Status st;
  MPI_Sendrecv(a, 3, every3, to, 3, got, 3, MPI_INT, from, 3, MPI_COMM_WORLD, &st);
  MCHECK(t, got[0] == 100 * from && got[1] == 100 * from + 3 && got[2] == 100 * from + 6,
         "every third int from rank %d: %d %d %d", from, got[0], got[1], got[2]);
  int back[9], n;
  for (int i = 0; i < 9; i++) back[i] = -1;
  MPI_Sendrecv(got, 3, MPI_INT, from, 4, back, 3, every3, to, 4, MPI_COMM_WORLD, &st);
  MCHECK(t, back[0] == 100 * rank && back[3] == 100 * rank + 3 && back[6] == 100 * rank + 6 && back[1] == -1 &&
                back[8] == -1,
         "received as every third int: %d %d %d", back[0], back[3], back[6]);
  MPI_Get_count(&st, every3, &n);
  MCHECK(t, n == 3, "MPI_Get_count: %d", n);
  MPI_Get_elements(&st, every3, &n);
  MCHECK(t, n == 3, "MPI_Get_elements: %d", n);

  /* The decoding keeps the markers. */
  int ni, na, nd, comb, ints[4];
  MPI_Aint addr[3];
  MPI_Datatype types[3];
  MPI_Type_get_envelope(every3, &ni, &na, &nd, &comb);
  MCHECK(t, comb == MPI_COMBINER_STRUCT && ni == 4 && na == 3 && nd == 3, "the struct's envelope %d %d %d %d", comb,
         ni, na, nd);
  MPI_Type_get_contents(every3, 4, 3, 3, ints, addr, types);
  MCHECK(t, types[0] == MPI_LB && types[1] == MPI_INT && types[2] == MPI_UB && addr[2] == 12 && ints[0] == 3,
         "the struct's contents: %d blocks, ub at %ld", ints[0], (long)addr[2]);
  MPI_Type_free(&every3);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {test_predefined, test_struct_markers, test_sticky, test_send, NULL};
  return mtest_main(&argc, &argv, "dtype_markers", 1, MTEST_ERRORS_RETURN, checks);
}
