/* dtype_external.c -- MPI_Pack_external, MPI_Unpack_external and MPI_Pack_external_size in
 * "external32" (MPI 3.1 sections 4.3 and 13.5.2): the bytes of known values of every basic type
 * against their big-endian encodings in the sizes of the standard's table 13.2, written out
 * here byte by byte; pairs, complex values, derived types with gaps and padding (no padding in
 * external32); round trips into zeroed buffers; positions across several calls; the packed
 * bytes sent between ranks; errors.
 *
 * Plain MPI C: it builds with tilesim's mpi.h and with Open MPI's mpicc, and prints the same
 * "dtype_external: P passed, F failed" line under both.  Where Open MPI 4.1 departs from the
 * table (MPI_Pack_external_size counts 8 bytes for MPI_LONG though it packs 4, and 4 for
 * MPI_WCHAR; its long double is not binary128), the checks run under tilesim only and count
 * only when they fail. */
#include <complex.h>
#include <float.h>
#include <math.h>
#include <mpi.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <wchar.h>

#include "mtest.h"

static const char X32[] = "external32";

/* Pack count elements of dt from buf; compare with want[n]; unpack into
 * back (zeroed, nbytes) and compare with buf's first nbytes. */
static void bytes(mtest *t, const char *what, const void *buf, int count, MPI_Datatype dt, const unsigned char *want,
                  int n, int roundtrip_bytes) {
  unsigned char out[256], back[256];
  MPI_Aint pos = 0, size = -1, in = 0;
  memset(out, 0xa5, sizeof out);
  int rc = MPI_Pack_external(X32, buf, count, dt, out, (MPI_Aint)sizeof out, &pos);
  MPI_Pack_external_size(X32, count, dt, &size);
  int same = rc == MPI_SUCCESS && pos == n && memcmp(out, want, (size_t)n) == 0;
  MCHECK(t, same && size == n, "%s: rc %d, %ld bytes (size %ld, want %d): %02x %02x %02x %02x ...", what, rc,
         (long)pos, (long)size, n, out[0], out[1], out[2], out[3]);
  if (roundtrip_bytes) {
    memset(back, 0, sizeof back);
    rc = MPI_Unpack_external(X32, out, pos, &in, back, count, dt);
    MCHECK(t, rc == MPI_SUCCESS && in == pos && memcmp(back, buf, (size_t)roundtrip_bytes) == 0,
           "%s: unpacked back: rc %d, %ld bytes", what, rc, (long)in);
  }
}

static void test_integers(mtest *t) {
  signed char c[2] = {-3, 100};
  const unsigned char wc[] = {0xfd, 0x64};
  bytes(t, "MPI_SIGNED_CHAR", c, 2, MPI_SIGNED_CHAR, wc, 2, 2);
  short s[2] = {0x1234, -2};
  const unsigned char ws[] = {0x12, 0x34, 0xff, 0xfe};
  bytes(t, "MPI_SHORT", s, 2, MPI_SHORT, ws, 4, 4);
  int i[3] = {0x01020304, -2, 0};
  const unsigned char wi[] = {1, 2, 3, 4, 0xff, 0xff, 0xff, 0xfe, 0, 0, 0, 0};
  bytes(t, "MPI_INT", i, 3, MPI_INT, wi, 12, 12);
  unsigned u[1] = {0xdeadbeefu};
  const unsigned char wu[] = {0xde, 0xad, 0xbe, 0xef};
  bytes(t, "MPI_UNSIGNED", u, 1, MPI_UNSIGNED, wu, 4, 4);
  long long ll[1] = {-0x0102030405060708LL};
  const unsigned char wll[] = {0xfe, 0xfd, 0xfc, 0xfb, 0xfa, 0xf9, 0xf8, 0xf8};
  bytes(t, "MPI_LONG_LONG", ll, 1, MPI_LONG_LONG, wll, 8, 8);
  uint16_t u16[1] = {0xabcd};
  const unsigned char w16[] = {0xab, 0xcd};
  bytes(t, "MPI_UINT16_T", u16, 1, MPI_UINT16_T, w16, 2, 2);
  int64_t i64[1] = {0x1122334455667788LL};
  const unsigned char w64[] = {0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88};
  bytes(t, "MPI_INT64_T", i64, 1, MPI_INT64_T, w64, 8, 8);
  MPI_Aint a[1] = {-256};
  const unsigned char wa[] = {0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x00};
  bytes(t, "MPI_AINT", a, 1, MPI_AINT, wa, 8, 8);
  MPI_Offset o[1] = {0x100000000LL};
  const unsigned char wo[] = {0, 0, 0, 1, 0, 0, 0, 0};
  bytes(t, "MPI_OFFSET", o, 1, MPI_OFFSET, wo, 8, 8);
  _Bool b[2] = {1, 0};
  const unsigned char wb[] = {1, 0};
  bytes(t, "MPI_C_BOOL", b, 2, MPI_C_BOOL, wb, 2, 2);
  unsigned char y[3] = {0, 0x80, 0xff};
  bytes(t, "MPI_BYTE", y, 3, MPI_BYTE, y, 3, 3);
  char ch[3] = {'a', 'b', 'c'};
  const unsigned char wch[] = {'a', 'b', 'c'};
  bytes(t, "MPI_CHAR", ch, 3, MPI_CHAR, wch, 3, 3);

  /* MPI_LONG is 4 bytes in external32: the low 32 bits, sign-extended back. */
  long l[2] = {-2, 0x7fffffffL};
  unsigned char out[16];
  MPI_Aint pos = 0, in = 0, size = 0;
  long back[2] = {0, 0};
  int rc = MPI_Pack_external(X32, l, 2, MPI_LONG, out, 16, &pos);
  if (rc == MPI_SUCCESS) rc = MPI_Unpack_external(X32, out, pos, &in, back, 2, MPI_LONG);
  MCHECK(t, rc == MPI_SUCCESS && pos == 8 && out[0] == 0xff && out[3] == 0xfe && out[4] == 0x7f && out[7] == 0xff &&
                back[0] == -2 && back[1] == 0x7fffffffL,
         "MPI_LONG in 4 bytes: rc %d, %ld bytes, back %ld %ld", rc, (long)pos, back[0], back[1]);
  if (TILESIM) {
    MPI_Pack_external_size(X32, 3, MPI_LONG, &size);
    SCHECK(t, size == 12, "MPI_Pack_external_size of 3 MPI_LONG: %ld", (long)size);
    wchar_t w[2] = {0x263a, 'x'};
    const unsigned char ww[] = {0x26, 0x3a, 0, 'x'};
    unsigned char wout[8];
    wchar_t wback[2] = {0, 0};
    pos = in = 0;
    rc = MPI_Pack_external(X32, w, 2, MPI_WCHAR, wout, 8, &pos);
    if (rc == MPI_SUCCESS) rc = MPI_Unpack_external(X32, wout, pos, &in, wback, 2, MPI_WCHAR);
    SCHECK(t, rc == MPI_SUCCESS && pos == 4 && !memcmp(wout, ww, 4) && wback[0] == 0x263a && wback[1] == 'x',
           "MPI_WCHAR in 2 bytes: rc %d, %ld bytes", rc, (long)pos);
  }
}

static void test_floats(mtest *t) {
  float f[2] = {1.5f, -0.0f};
  const unsigned char wf[] = {0x3f, 0xc0, 0, 0, 0x80, 0, 0, 0};
  bytes(t, "MPI_FLOAT", f, 2, MPI_FLOAT, wf, 8, 8);
  double d[2] = {-2.25, 1.0 / 3};
  const unsigned char wd[] = {0xc0, 0x02, 0, 0, 0, 0, 0, 0, 0x3f, 0xd5, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55};
  bytes(t, "MPI_DOUBLE", d, 2, MPI_DOUBLE, wd, 16, 16);
  float _Complex z[1] = {1.5f - 2.0f * _Complex_I};
  const unsigned char wz[] = {0x3f, 0xc0, 0, 0, 0xc0, 0, 0, 0};
  bytes(t, "MPI_C_FLOAT_COMPLEX", z, 1, MPI_C_FLOAT_COMPLEX, wz, 8, 8);
  double _Complex dz[1] = {-2.25 + 1.5 * _Complex_I};
  const unsigned char wdz[] = {0xc0, 0x02, 0, 0, 0, 0, 0, 0, 0x3f, 0xf8, 0, 0, 0, 0, 0, 0};
  bytes(t, "MPI_C_DOUBLE_COMPLEX", dz, 1, MPI_C_DOUBLE_COMPLEX, wdz, 16, 16);
  if (TILESIM) {
    /* binary128: 1.5 is 3fff 8000 0..., -2^-16400 a subnormal; the
     * smallest long double, the largest and an infinity come back. */
    long double ld[5] = {1.5L, -0x1p-16400L, LDBL_TRUE_MIN, LDBL_MAX, -HUGE_VALL}, back[5] = {0, 0, 0, 0, 0};
    unsigned char out[80];
    MPI_Aint pos = 0, in = 0;
    int rc = MPI_Pack_external(X32, ld, 5, MPI_LONG_DOUBLE, out, 80, &pos);
    if (rc == MPI_SUCCESS) rc = MPI_Unpack_external(X32, out, pos, &in, back, 5, MPI_LONG_DOUBLE);
    const unsigned char w0[16] = {0x3f, 0xff, 0x80};
    /* 2^-16400 = 2^94 2^-16494: bit 94 of the fraction, bit 30 of its top 48 */
    const unsigned char w1[16] = {0x80, 0, 0, 0, 0x40};
    int same = rc == MPI_SUCCESS && pos == 80 && !memcmp(out, w0, 16) && !memcmp(out + 16, w1, 16);
    for (int k = 0; k < 5; k++) same = same && back[k] == ld[k];
    SCHECK(t, same, "MPI_LONG_DOUBLE as binary128: rc %d, %ld bytes, %02x %02x %02x", rc, (long)pos, out[0], out[1],
           out[2]);
  }
}

struct di {
  double d;
  int i;
};
struct cdi {
  char c;
  double d;
  int i[2];
};

static void test_pairs_and_derived(mtest *t) {
  struct di p[1] = {{2.0, 7}};
  const unsigned char wp[] = {0x40, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 7};
  bytes(t, "MPI_DOUBLE_INT", p, 1, MPI_DOUBLE_INT, wp, 12, 12);
  struct {
    short v;
    int i;
  } si[1] = {{-1, 258}};
  const unsigned char wsi[] = {0xff, 0xff, 0, 0, 1, 2};
  unsigned char out[64];
  MPI_Aint pos = 0;
  MPI_Pack_external(X32, si, 1, MPI_SHORT_INT, out, 64, &pos);
  MCHECK(t, pos == 6 && !memcmp(out, wsi, 6), "MPI_SHORT_INT: %ld bytes", (long)pos);

  /* A vector of ints with gaps: only the data, big-endian. */
  int a[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  MPI_Datatype v;
  MPI_Type_vector(2, 1, 3, MPI_INT, &v);   /* ints 0, 3 */
  MPI_Type_commit(&v);
  const unsigned char wv[] = {0, 0, 0, 1, 0, 0, 0, 4, 0, 0, 0, 5, 0, 0, 0, 8};   /* two elements, extent 16 bytes */
  bytes(t, "vector(2, 1, 3, int) x 2", a, 2, v, wv, 16, 0);

  /* A C struct with padding: 1 + 8 + 8 bytes an element, no padding. */
  struct cdi s[2] = {{'x', 1.0, {1, -1}}, {'y', -2.0, {256, 3}}}, r[2];
  int bl[3] = {1, 1, 2};
  MPI_Aint disp[3] = {offsetof(struct cdi, c), offsetof(struct cdi, d), offsetof(struct cdi, i)};
  MPI_Datatype ty[3] = {MPI_CHAR, MPI_DOUBLE, MPI_INT}, st;
  MPI_Type_create_struct(3, bl, disp, ty, &st);
  MPI_Type_commit(&st);
  const unsigned char ws[34] = {'x', 0x3f, 0xf0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0xff, 0xff, 0xff, 0xff,
                                'y', 0xc0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 3};
  bytes(t, "struct {char, double, int[2]} x 2", s, 2, st, ws, 34, 0);
  memset(r, 0, sizeof r);
  pos = 0;
  MPI_Aint in = 0;
  MPI_Pack_external(X32, s, 2, st, out, 64, &pos);
  int rc = MPI_Unpack_external(X32, out, pos, &in, r, 2, st);
  MCHECK(t, rc == MPI_SUCCESS && r[0].c == 'x' && r[0].d == 1.0 && r[0].i[1] == -1 && r[1].c == 'y' &&
                r[1].d == -2.0 && r[1].i[0] == 256 && r[1].i[1] == 3,
         "structs unpacked from external32: rc %d", rc);

  /* Two packs one after the other; the second unpacked alone. */
  pos = 0;
  double d3[3] = {0.5, 4, -8};
  rc = MPI_Pack_external(X32, a, 3, MPI_INT, out, 64, &pos);
  if (rc == MPI_SUCCESS) rc = MPI_Pack_external(X32, d3, 3, MPI_DOUBLE, out, 64, &pos);
  double d2[3] = {0, 0, 0};
  in = 12;
  if (rc == MPI_SUCCESS) rc = MPI_Unpack_external(X32, out, pos, &in, d2, 3, MPI_DOUBLE);
  MCHECK(t, rc == MPI_SUCCESS && pos == 36 && in == 36 && d2[0] == 0.5 && d2[2] == -8,
         "two packs, the second unpacked from 12: rc %d, %ld and %ld", rc, (long)pos, (long)in);
  MPI_Type_free(&v);
  MPI_Type_free(&st);
}

static void test_errors(mtest *t) {
  int a[4] = {1, 2, 3, 4};
  unsigned char out[16];
  MPI_Aint pos = 0, in = 0;
  MCHECK(t, MPI_Pack_external(X32, a, 4, MPI_INT, out, 8, &pos) != MPI_SUCCESS, "16 bytes packed into 8");
  MCHECK(t, MPI_Unpack_external(X32, out, 8, &in, a, 4, MPI_INT) != MPI_SUCCESS, "16 bytes unpacked from 8");
  if (TILESIM) {
    MPI_Aint size;
    SCHECK(t, MPI_Pack_external_size("native", 1, MPI_INT, &size) == MPI_ERR_ARG, "datarep \"native\" accepted");
    pos = 0;
    SCHECK(t, MPI_Pack_external("external64", a, 1, MPI_INT, out, 16, &pos) == MPI_ERR_ARG && pos == 0,
           "datarep \"external64\" accepted");
  }
}

/* Each rank packs its values in external32 and sends the bytes to the
 * next, which unpacks them. */
static void test_send(mtest *t) {
  int rank = t->rank, size = t->size, to = (rank + 1) % size, from = (rank - 1 + size) % size;
  double v[2] = {rank + 0.25, -rank};
  int n[2] = {rank, 1000 * rank};
  unsigned char out[64], in[64];
  MPI_Aint pos = 0, at = 0;
  MPI_Pack_external(X32, v, 2, MPI_DOUBLE, out, 64, &pos);
  MPI_Pack_external(X32, n, 2, MPI_INT, out, 64, &pos);
  MPI_Sendrecv(out, (int)pos, MPI_BYTE, to, 1, in, 64, MPI_BYTE, from, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  double gv[2];
  int gn[2];
  MPI_Unpack_external(X32, in, 24, &at, gv, 2, MPI_DOUBLE);
  MPI_Unpack_external(X32, in, 24, &at, gn, 2, MPI_INT);
  MCHECK(t, in[0] == (from >= 2 ? 0x40 : 0x3f) && gv[0] == from + 0.25 && gv[1] == -from && gn[0] == from &&
                gn[1] == 1000 * from && at == 24,
         "external32 from rank %d: %g %g %d %d", from, gv[0], gv[1], gn[0], gn[1]);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {mtest_rank0,  test_integers,    test_floats, test_pairs_and_derived,
                                    test_errors,  mtest_every_rank, test_send,   NULL};
  return mtest_main(&argc, &argv, "dtype_external", 1, MTEST_ERRORS_RETURN, checks);
}
