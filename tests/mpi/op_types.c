/* op_types.c -- every predefined operation on every predefined type, against plain C loops
 * (MPI 3.1 sections 5.9.2 and 5.9.4): MPI_Reduce_local on each pair the standard allows (the
 * result element by element, wrap-around included), MPI_ERR_OP for the pairs it forbids that
 * every library refuses, MINLOC and MAXLOC with ties on every pair type, and the same
 * reductions across the ranks (MPI_Allreduce, MPI_Reduce to each root) against a brute-force
 * reduction over the ranks' values.
 *
 * Plain MPI C: it builds with tilesim's mpi.h and with Open MPI's mpicc, and prints the same
 * "op_types: P passed, F failed" line under both.  Logical operations on MPI_AINT, MPI_OFFSET
 * and MPI_COUNT, which the standard leaves out, are checked as MPICH and Open MPI take them;
 * pairs the standard forbids but Open MPI alone accepts (sums of MPI_BYTE, ...) are checked
 * only under tilesim, and count only when they fail. */
#include <complex.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "mtest.h"

enum { N = 9 };   /* elements per reduction */

/* The operations by index, and which classes they apply to. */
enum { MAX, MIN, SUM, PROD, LAND, BAND, LOR, BOR, LXOR, BXOR, NOPS };
static MPI_Op op_of(int o) {
  static const MPI_Op ops[NOPS] = {MPI_MAX, MPI_MIN, MPI_SUM, MPI_PROD, MPI_LAND,
                                   MPI_BAND, MPI_LOR, MPI_BOR, MPI_LXOR, MPI_BXOR};
  return ops[o];
}
static const char *const op_name[NOPS] = {"MAX", "MIN", "SUM", "PROD", "LAND", "BAND", "LOR", "BOR", "LXOR", "BXOR"};

/* The check of MPI_Reduce_local's answer rc for operation o on name: where
 * the operation applies, success with the expected elements (same); where
 * not, MPI_ERR_OP. */
static void verdict(mtest *t, int o, const char *name, int rc, int applies, int same) {
  if (applies)
    MCHECK(t, same, "%s on %s: rc %d or a wrong element", op_name[o], name, rc);
  else
    MCHECK(t, rc == MPI_ERR_OP, "%s on %s: rc %d, want MPI_ERR_OP", op_name[o], name, rc);
}

/* Classes of MPI 3.1 section 5.9.2 and the operations the standard allows
 * on each (bit o: operation o). */
enum { CINT, FINT, FLOATING, LOGICAL, COMPLEX, BYTE, MULTI };
static const unsigned allowed[] = {
  [CINT] = 0x3ff,                                                        /* all ten */
  [FINT] = 1 << MAX | 1 << MIN | 1 << SUM | 1 << PROD | 1 << BAND | 1 << BOR | 1 << BXOR,
  [FLOATING] = 1 << MAX | 1 << MIN | 1 << SUM | 1 << PROD,
  [LOGICAL] = 1 << LAND | 1 << LOR | 1 << LXOR,
  [COMPLEX] = 1 << SUM | 1 << PROD,
  [BYTE] = 1 << BAND | 1 << BOR | 1 << BXOR,
  [MULTI] = 0x3ff,   /* all ten, as MPICH and Open MPI (the standard leaves out the logical ones) */
};
/* What Open MPI 4.1 accepts beyond the standard and MPICH (measured):
 * every integer operation on MPI_BYTE, logical ones on MPI_INTEGER1/2/8.
 * Those pairs are checked under tilesim only. */
static int lenient(int cls, int o, MPI_Datatype dt) {
  int logical = o == LAND || o == LOR || o == LXOR;
  if (cls == BYTE) return 1;
  if (cls == FINT && logical && dt != MPI_INTEGER && dt != MPI_INTEGER4) return 1;
  return 0;
}

/* The reference results of operation o on a (left) and b (right), for
 * integer types: computed in long long and cut to the type by the caller
 * (wrap-around by conversion, as every MPI library does). */
static long long ref_int(int o, long long a, long long b, int is_unsigned, int bits) {
  unsigned long long mask = bits == 64 ? ~0ull : (1ull << bits) - 1;
  switch (o) {
  case MAX: return a > b ? a : b;
  case MIN: return a < b ? a : b;
  case SUM: return (long long)(((unsigned long long)a + (unsigned long long)b) & mask);
  case PROD: return (long long)(((unsigned long long)a * (unsigned long long)b) & mask);
  case LAND: return (a != 0) && (b != 0);
  case LOR: return (a != 0) || (b != 0);
  case LXOR: return (a != 0) != (b != 0);
  case BAND: return (long long)(((unsigned long long)a & (unsigned long long)b) & mask);
  case BOR: return (long long)(((unsigned long long)a | (unsigned long long)b) & mask);
  default: return (long long)(((unsigned long long)a ^ (unsigned long long)b) & mask);
  }
  (void)is_unsigned;
}

/* Values for element i of rank r's buffer: signs, zeros, and large ones
 * that wrap in small types. */
static long long ival(int r, int i, int is_unsigned, int bits) {
  static const long long v[N] = {0, 1, -1, 7, -100, 100, 12345, -32768, 3};
  long long x = v[i] * (r % 3 + 1) + (i == 0 ? r % 2 : 0);
  if (bits == 64 && (i == 6)) x = v[i];   /* no 64-bit overflow: signed overflow is undefined */
  if (is_unsigned && x < 0) x = -x;
  return x;
}

/* ==== one integer type ==================================================== */

#define INT_TEST(T, U, BITS, UNS)                                                               \
  static void test_##T(mtest *t, MPI_Datatype dt, const char *name, int cls) {                  \
    for (int o = 0; o < NOPS; o++) {                                                            \
      T a[N], b[N], want[N];                                                                    \
      for (int i = 0; i < N; i++) {                                                             \
        a[i] = (T)(U)ival(1, i, UNS, BITS);                                                     \
        b[i] = (T)(U)ival(2, i, UNS, BITS);                                                     \
        want[i] = (T)(U)ref_int(o, (long long)a[i], (long long)b[i], UNS, BITS);                \
      }                                                                                         \
      int rc = MPI_Reduce_local(a, b, N, dt, op_of(o));                                         \
      if (allowed[cls] >> o & 1) {                                                              \
        int bad = rc != MPI_SUCCESS;                                                            \
        for (int i = 0; i < N && !bad; i++) bad = b[i] != want[i];                              \
        MCHECK(t, !bad, "%s on %s: rc %d or a wrong element", op_name[o], name, rc);            \
      } else if (!lenient(cls, o, dt)) {                                                        \
        MCHECK(t, rc == MPI_ERR_OP, "%s on %s: rc %d, want MPI_ERR_OP", op_name[o], name, rc);  \
      } else if (TILESIM) {                                                                     \
        SCHECK(t, rc == MPI_ERR_OP, "%s on %s: rc %d, want MPI_ERR_OP", op_name[o], name, rc);  \
      }                                                                                         \
    }                                                                                           \
  }

typedef signed char schar;
typedef unsigned char uchar;
typedef unsigned short ushort;
typedef unsigned long ulong;
typedef long long llong;
typedef unsigned long long ullong;
INT_TEST(char, uchar, 8, 0)
INT_TEST(schar, uchar, 8, 0)
INT_TEST(uchar, uchar, 8, 1)
INT_TEST(short, ushort, 16, 0)
INT_TEST(ushort, ushort, 16, 1)
INT_TEST(int, unsigned, 32, 0)
INT_TEST(unsigned, unsigned, 32, 1)
INT_TEST(long, ulong, 64, 0)
INT_TEST(ulong, ulong, 64, 1)
INT_TEST(llong, ullong, 64, 0)
INT_TEST(ullong, ullong, 64, 1)
INT_TEST(int8_t, uint8_t, 8, 0)
INT_TEST(int16_t, uint16_t, 16, 0)
INT_TEST(int32_t, uint32_t, 32, 0)
INT_TEST(int64_t, uint64_t, 64, 0)
INT_TEST(uint8_t, uint8_t, 8, 1)
INT_TEST(uint16_t, uint16_t, 16, 1)
INT_TEST(uint32_t, uint32_t, 32, 1)
INT_TEST(uint64_t, uint64_t, 64, 1)

/* ==== floating point, complex, logical ==================================== */

/* The logical operations on floating point are MPICH 3's (and SMPI's):
 * tilesim takes them, Open MPI refuses them; one check either way. */
#define FLOAT_TEST(T)                                                                           \
  static void test_##T(mtest *t, MPI_Datatype dt, const char *name) {                           \
    for (int o = 0; o < NOPS; o++) {                                                            \
      T a[N], b[N], want[N];                                                                    \
      int logical = o == LAND || o == LOR || o == LXOR;                                         \
      for (int i = 0; i < N; i++) {                                                             \
        a[i] = (T)ival(1, i, 0, 32) / 4;                                                        \
        b[i] = (T)ival(2, i, 0, 32) / 8;                                                        \
        want[i] = o == MAX ? (a[i] > b[i] ? a[i] : b[i]) : o == MIN ? (a[i] < b[i] ? a[i] : b[i]) \
                : o == SUM ? a[i] + b[i] : o == PROD ? a[i] * b[i]                              \
                : (T)ref_int(o, a[i] != 0, b[i] != 0, 1, 8);                                    \
      }                                                                                         \
      int rc = MPI_Reduce_local(a, b, N, dt, op_of(o));                                         \
      int same = rc == MPI_SUCCESS;                                                             \
      for (int i = 0; i < N && same; i++) same = b[i] == want[i];                               \
      verdict(t, o, name, rc, o <= PROD || (logical && TILESIM), same);                         \
    }                                                                                           \
  }
typedef long double ldouble;
FLOAT_TEST(float)
FLOAT_TEST(double)
FLOAT_TEST(ldouble)

#define COMPLEX_TEST(T, R)                                                                      \
  static void test_##R##_complex(mtest *t, MPI_Datatype dt, const char *name) {                 \
    for (int o = 0; o < NOPS; o++) {                                                            \
      T a[N], b[N], want[N];                                                                    \
      for (int i = 0; i < N; i++) {                                                             \
        a[i] = (R)ival(1, i, 0, 32) + (R)i * I;                                                 \
        b[i] = (R)(i - 4) - (R)ival(2, i, 0, 32) / 2 * I;                                       \
        want[i] = o == SUM ? a[i] + b[i] : a[i] * b[i];                                         \
      }                                                                                         \
      int rc = MPI_Reduce_local(a, b, N, dt, op_of(o));                                         \
      int same = rc == MPI_SUCCESS;                                                             \
      for (int i = 0; i < N && same; i++) same = b[i] == want[i];                               \
      verdict(t, o, name, rc, o == SUM || o == PROD, same);                                     \
    }                                                                                           \
  }
COMPLEX_TEST(float _Complex, float)
COMPLEX_TEST(double _Complex, double)
COMPLEX_TEST(long double _Complex, ldouble)

/* _Bool (C's and C++'s) and Fortran's LOGICAL (an int32: any non-zero is
 * true; the results are 1 and 0). */
#define LOGICAL_TEST(T)                                                                         \
  static void test_logical_##T(mtest *t, MPI_Datatype dt, const char *name) {                  \
    for (int o = 0; o < NOPS; o++) {                                                            \
      T a[4], b[4], want[4];                                                                    \
      for (int i = 0; i < 4; i++) {                                                             \
        a[i] = (T)((i & 1) ? (sizeof(T) > 1 ? 5 : 1) : 0);                                      \
        b[i] = (T)((i & 2) ? 1 : 0);                                                            \
        want[i] = (T)ref_int(o < LAND ? LAND : o, a[i], b[i], 1, 8);                            \
      }                                                                                         \
      int rc = MPI_Reduce_local(a, b, 4, dt, op_of(o));                                         \
      int same = rc == MPI_SUCCESS;                                                             \
      for (int i = 0; i < 4 && same; i++) same = b[i] == want[i];                               \
      verdict(t, o, name, rc, o == LAND || o == LOR || o == LXOR, same);                        \
    }                                                                                           \
  }
typedef _Bool cbool;
LOGICAL_TEST(cbool)
LOGICAL_TEST(int32_t)

/* ==== MINLOC and MAXLOC =================================================== */

#define PAIR_TEST(NAME, V, IX)                                                                  \
  static void test_pair_##NAME(mtest *t, MPI_Datatype dt, const char *name) {                   \
    struct { V v; IX i; } a[6], b[6], want[2][6];                                               \
    static const int av[6] = {1, 5, 5, -2, 7, 0}, ai[6] = {0, 3, 9, 4, 1, 2};                   \
    static const int bv[6] = {2, 5, 5, -3, 7, 0}, bi[6] = {5, 4, 2, 8, 1, 2};                   \
    for (int m = 0; m < 2; m++)                                                                 \
      for (int k = 0; k < 6; k++) {                                                             \
        int pick_a = m == 0 ? av[k] < bv[k] : av[k] > bv[k];                                    \
        int tie = av[k] == bv[k];                                                               \
        want[m][k].v = (V)(pick_a ? av[k] : bv[k]);                                             \
        want[m][k].i = (IX)(tie ? (ai[k] < bi[k] ? ai[k] : bi[k]) : pick_a ? ai[k] : bi[k]);    \
      }                                                                                         \
    for (int m = 0; m < 2; m++) {                                                               \
      for (int k = 0; k < 6; k++) {                                                             \
        a[k].v = (V)av[k], a[k].i = (IX)ai[k];                                                  \
        b[k].v = (V)bv[k], b[k].i = (IX)bi[k];                                                  \
      }                                                                                         \
      int rc = MPI_Reduce_local(a, b, 6, dt, m == 0 ? MPI_MINLOC : MPI_MAXLOC);                 \
      int bad = rc != MPI_SUCCESS;                                                              \
      for (int k = 0; k < 6 && !bad; k++) bad = b[k].v != want[m][k].v || b[k].i != want[m][k].i; \
      MCHECK(t, !bad, "%s on %s: rc %d or a wrong pair", m ? "MAXLOC" : "MINLOC", name, rc);    \
    }                                                                                           \
    for (int o = 0; o < NOPS; o++) {                                                            \
      int rc = MPI_Reduce_local(a, b, 6, dt, op_of(o));                                         \
      MCHECK(t, rc == MPI_ERR_OP, "%s on %s: rc %d, want MPI_ERR_OP", op_name[o], name, rc);    \
    }                                                                                           \
  }
PAIR_TEST(float_int, float, int)
PAIR_TEST(double_int, double, int)
PAIR_TEST(long_int, long, int)
PAIR_TEST(2int, int, int)
PAIR_TEST(short_int, short, int)
PAIR_TEST(long_double_int, long double, int)
PAIR_TEST(2real, float, float)
PAIR_TEST(2double, double, double)
PAIR_TEST(2integer, int32_t, int32_t)

/* Types no operation applies to; MINLOC on a plain type; the RMA-only
 * operations in a reduction. */
static void test_refusals(mtest *t) {
  wchar_t w[2] = {1, 2}, w2[2] = {3, 4};
  int bad = 0;
  for (int o = 0; o < NOPS; o++) bad += MPI_Reduce_local(w, w2, 2, MPI_WCHAR, op_of(o)) != MPI_ERR_OP;
  MCHECK(t, bad == 0, "%d operations accepted MPI_WCHAR", bad);
  char p[2] = {1, 2}, p2[2] = {3, 4};
  bad = 0;
  for (int o = 0; o < NOPS; o++) bad += MPI_Reduce_local(p, p2, 2, MPI_PACKED, op_of(o)) != MPI_ERR_OP;
  MCHECK(t, bad == 0, "%d operations accepted MPI_PACKED", bad);
  double d[2] = {1, 2}, d2[2] = {3, 4};
  MCHECK(t, MPI_Reduce_local(d, d2, 2, MPI_DOUBLE, MPI_MINLOC) == MPI_ERR_OP, "MINLOC accepted MPI_DOUBLE");
  MCHECK(t, MPI_Reduce_local(d, d2, 2, MPI_DOUBLE, MPI_REPLACE) == MPI_ERR_OP, "MPI_Reduce_local accepted MPI_REPLACE");
  MCHECK(t, MPI_Reduce_local(d, d2, 2, MPI_DOUBLE, MPI_NO_OP) == MPI_ERR_OP, "MPI_Reduce_local accepted MPI_NO_OP");
  MCHECK(t, MPI_Reduce_local(d, d2, 2, MPI_DOUBLE, MPI_OP_NULL) == MPI_ERR_OP, "MPI_Reduce_local accepted MPI_OP_NULL");
  MCHECK(t, d2[0] == 3 && d2[1] == 4, "a refused reduction changed its buffer: %g %g", d2[0], d2[1]);
  if (TILESIM) {
    /* The standard's groups: tilesim refuses what Open MPI also takes. */
    unsigned char y[2] = {1, 2}, y2[2] = {3, 4};
    SCHECK(t, MPI_Reduce_local(y, y2, 2, MPI_BYTE, MPI_SUM) == MPI_ERR_OP, "MPI_SUM accepted MPI_BYTE");
    SCHECK(t, MPI_Reduce_local(y, y2, 2, MPI_CHARACTER, MPI_MAX) == MPI_ERR_OP, "MPI_MAX accepted MPI_CHARACTER");
  }
}

/* ==== across the ranks ==================================================== */

/* MPI_Allreduce and MPI_Reduce (to every root in turn) of every rank's
 * values, for a few type and operation pairs, against the brute-force
 * reduction of the values every rank can compute. */
static void test_collective(mtest *t) {
  long long want[N];
  int size = t->size, rank = t->rank;
  for (int o = 0; o < NOPS; o++) {
    if (o == LAND || o == LOR || o == LXOR) continue;
    for (int i = 0; i < N; i++) {
      want[i] = (int)(unsigned)ival(0, i, 0, 32);
      for (int r = 1; r < size; r++) want[i] = (int)(unsigned)ref_int(o, want[i], (int)(unsigned)ival(r, i, 0, 32), 0, 32);
    }
    int in[N], out[N];
    for (int i = 0; i < N; i++) in[i] = (int)(unsigned)ival(rank, i, 0, 32);
    int rc = MPI_Allreduce(in, out, N, MPI_INT, op_of(o), MPI_COMM_WORLD), bad = rc != MPI_SUCCESS;
    for (int i = 0; i < N && !bad; i++) bad = out[i] != (int)want[i];
    MCHECK(t, !bad, "MPI_Allreduce %s on %d ranks: rc %d or a wrong element", op_name[o], size, rc);
    bad = 0;
    for (int root = 0; root < size; root++) {
      memset(out, 0, sizeof out);
      rc = MPI_Reduce(in, out, N, MPI_INT, op_of(o), root, MPI_COMM_WORLD);
      if (rc != MPI_SUCCESS) bad++;
      for (int i = 0; i < N && rank == root; i++) bad += out[i] != (int)want[i];
    }
    MCHECK(t, bad == 0, "MPI_Reduce %s on %d ranks: %d wrong", op_name[o], size, bad);
  }
  /* Logical operations on the address and count types across the ranks
   * (MPICH's allred test): rank r's value is r % 3 (0 on ranks 0, 3, ...). */
  static const MPI_Op lops[3] = {MPI_LAND, MPI_LOR, MPI_LXOR};
  static const MPI_Datatype mtypes[3] = {MPI_AINT, MPI_OFFSET, MPI_COUNT};
  for (int k = 0; k < 3; k++) {
    int bad = 0, nonzero = 0;
    for (int r = 0; r < size; r++) nonzero += r % 3 != 0;
    long long lwant[3] = {nonzero == size, nonzero > 0, nonzero % 2};
    for (int o = 0; o < 3; o++) {
      MPI_Aint a = rank % 3, ra = -1;
      MPI_Offset f = rank % 3, rf = -1;
      MPI_Count c = rank % 3, rc2 = -1;
      void *in = k == 0 ? (void *)&a : k == 1 ? (void *)&f : (void *)&c;
      void *out = k == 0 ? (void *)&ra : k == 1 ? (void *)&rf : (void *)&rc2;
      int rc = MPI_Allreduce(in, out, 1, mtypes[k], lops[o], MPI_COMM_WORLD);
      long long got = k == 0 ? (long long)ra : k == 1 ? (long long)rf : (long long)rc2;
      bad += rc != MPI_SUCCESS || got != lwant[o];
    }
    MCHECK(t, bad == 0, "logical MPI_Allreduce on %s over %d ranks: %d wrong",
           k == 0 ? "MPI_AINT" : k == 1 ? "MPI_OFFSET" : "MPI_COUNT", size, bad);
  }
  /* MAXLOC of (value, rank) pairs: the largest value, the lowest rank among
   * equals. */
  struct { double v; int i; } p = {(double)(rank % 3), rank}, q;
  MPI_Allreduce(&p, &q, 1, MPI_DOUBLE_INT, MPI_MAXLOC, MPI_COMM_WORLD);
  int wv = size > 2 ? 2 : size - 1;
  MCHECK(t, q.v == wv && q.i == wv, "MAXLOC of rank %% 3: (%g, %d), want (%d, %d)", q.v, q.i, wv, wv);
  MPI_Allreduce(&p, &q, 1, MPI_DOUBLE_INT, MPI_MINLOC, MPI_COMM_WORLD);
  MCHECK(t, q.v == 0 && q.i == 0, "MINLOC of rank %% 3: (%g, %d)", q.v, q.i);
}

/* Every predefined type with each operation that applies to it. */
static void test_types(mtest *t) {
  test_char(t, MPI_CHAR, "MPI_CHAR", CINT);
  test_schar(t, MPI_SIGNED_CHAR, "MPI_SIGNED_CHAR", CINT);
  test_uchar(t, MPI_UNSIGNED_CHAR, "MPI_UNSIGNED_CHAR", CINT);
  test_uchar(t, MPI_BYTE, "MPI_BYTE", BYTE);
  test_short(t, MPI_SHORT, "MPI_SHORT", CINT);
  test_ushort(t, MPI_UNSIGNED_SHORT, "MPI_UNSIGNED_SHORT", CINT);
  test_int(t, MPI_INT, "MPI_INT", CINT);
  test_unsigned(t, MPI_UNSIGNED, "MPI_UNSIGNED", CINT);
  test_long(t, MPI_LONG, "MPI_LONG", CINT);
  test_ulong(t, MPI_UNSIGNED_LONG, "MPI_UNSIGNED_LONG", CINT);
  test_llong(t, MPI_LONG_LONG_INT, "MPI_LONG_LONG_INT", CINT);
  test_llong(t, MPI_LONG_LONG, "MPI_LONG_LONG", CINT);
  test_ullong(t, MPI_UNSIGNED_LONG_LONG, "MPI_UNSIGNED_LONG_LONG", CINT);
  test_int8_t(t, MPI_INT8_T, "MPI_INT8_T", CINT);
  test_int16_t(t, MPI_INT16_T, "MPI_INT16_T", CINT);
  test_int32_t(t, MPI_INT32_T, "MPI_INT32_T", CINT);
  test_int64_t(t, MPI_INT64_T, "MPI_INT64_T", CINT);
  test_uint8_t(t, MPI_UINT8_T, "MPI_UINT8_T", CINT);
  test_uint16_t(t, MPI_UINT16_T, "MPI_UINT16_T", CINT);
  test_uint32_t(t, MPI_UINT32_T, "MPI_UINT32_T", CINT);
  test_uint64_t(t, MPI_UINT64_T, "MPI_UINT64_T", CINT);
  test_int32_t(t, MPI_INTEGER, "MPI_INTEGER", FINT);
  test_int8_t(t, MPI_INTEGER1, "MPI_INTEGER1", FINT);
  test_int16_t(t, MPI_INTEGER2, "MPI_INTEGER2", FINT);
  test_int32_t(t, MPI_INTEGER4, "MPI_INTEGER4", FINT);
  test_int64_t(t, MPI_INTEGER8, "MPI_INTEGER8", FINT);
  if (sizeof(MPI_Aint) == 8) test_int64_t(t, MPI_AINT, "MPI_AINT", MULTI);
  if (sizeof(MPI_Offset) == 8) test_int64_t(t, MPI_OFFSET, "MPI_OFFSET", MULTI);
  if (sizeof(MPI_Count) == 8) test_int64_t(t, MPI_COUNT, "MPI_COUNT", MULTI);
  test_float(t, MPI_FLOAT, "MPI_FLOAT");
  test_double(t, MPI_DOUBLE, "MPI_DOUBLE");
  test_ldouble(t, MPI_LONG_DOUBLE, "MPI_LONG_DOUBLE");
  test_float(t, MPI_REAL, "MPI_REAL");
  test_double(t, MPI_DOUBLE_PRECISION, "MPI_DOUBLE_PRECISION");
  test_float(t, MPI_REAL4, "MPI_REAL4");
  test_double(t, MPI_REAL8, "MPI_REAL8");
  test_float_complex(t, MPI_C_FLOAT_COMPLEX, "MPI_C_FLOAT_COMPLEX");
  test_float_complex(t, MPI_C_COMPLEX, "MPI_C_COMPLEX");
  test_double_complex(t, MPI_C_DOUBLE_COMPLEX, "MPI_C_DOUBLE_COMPLEX");
  test_ldouble_complex(t, MPI_C_LONG_DOUBLE_COMPLEX, "MPI_C_LONG_DOUBLE_COMPLEX");
  test_float_complex(t, MPI_CXX_FLOAT_COMPLEX, "MPI_CXX_FLOAT_COMPLEX");
  test_double_complex(t, MPI_CXX_DOUBLE_COMPLEX, "MPI_CXX_DOUBLE_COMPLEX");
  test_ldouble_complex(t, MPI_CXX_LONG_DOUBLE_COMPLEX, "MPI_CXX_LONG_DOUBLE_COMPLEX");
  test_float_complex(t, MPI_COMPLEX, "MPI_COMPLEX");
  test_double_complex(t, MPI_DOUBLE_COMPLEX, "MPI_DOUBLE_COMPLEX");
  test_float_complex(t, MPI_COMPLEX8, "MPI_COMPLEX8");
  test_double_complex(t, MPI_COMPLEX16, "MPI_COMPLEX16");
  test_logical_cbool(t, MPI_C_BOOL, "MPI_C_BOOL");
  test_logical_cbool(t, MPI_CXX_BOOL, "MPI_CXX_BOOL");
  test_logical_int32_t(t, MPI_LOGICAL, "MPI_LOGICAL");
  test_pair_float_int(t, MPI_FLOAT_INT, "MPI_FLOAT_INT");
  test_pair_double_int(t, MPI_DOUBLE_INT, "MPI_DOUBLE_INT");
  test_pair_long_int(t, MPI_LONG_INT, "MPI_LONG_INT");
  test_pair_2int(t, MPI_2INT, "MPI_2INT");
  test_pair_short_int(t, MPI_SHORT_INT, "MPI_SHORT_INT");
  test_pair_long_double_int(t, MPI_LONG_DOUBLE_INT, "MPI_LONG_DOUBLE_INT");
  test_pair_2real(t, MPI_2REAL, "MPI_2REAL");
  test_pair_2double(t, MPI_2DOUBLE_PRECISION, "MPI_2DOUBLE_PRECISION");
  test_pair_2integer(t, MPI_2INTEGER, "MPI_2INTEGER");
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {mtest_rank0, test_types, test_refusals, mtest_every_rank, test_collective, NULL};
  return mtest_main(&argc, &argv, "op_types", 1, MTEST_ERRORS_RETURN, checks);
}
