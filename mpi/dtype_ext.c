/* dtype_ext.c -- the external32 representation (dtype_ext.h) and MPI_Pack_external,
 * MPI_Unpack_external, MPI_Pack_external_size (MPI 3.1 section 4.3; errors to MPI_COMM_WORLD's
 * handler, as for every call with no communicator). */
#include "mpi/dtype_ext.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <wchar.h>

#include "mpi/dtype.h"
#include "mpi/core.h"

/* ==== one basic value ===================================================== */

/* How a scalar is stored: native bytes ns, external bytes xs. */
enum { SINT, UINT, FLT, RAW };
typedef struct {
  int kind, ns, xs;
} scalar;

/* The scalars of predefined type i (one, or two: complex parts, a pair's
 * value and index) and their offsets in the native value. */
static int parts(int i, scalar s[2], int off[2]) {
  const dtype_predef *p = dtype_predef_get(i);
  off[0] = 0;
  switch (p->rep) {
  case DTYPE_REP_INT:
    s[0] = (scalar){SINT, p->size, i == (MPI_LONG & 0xffff) ? 4 : p->size};
    return 1;
  case DTYPE_REP_UINT:
  case DTYPE_REP_BOOL:
    s[0] = (scalar){UINT, p->size, i == (MPI_UNSIGNED_LONG & 0xffff) ? 4 : p->size};
    return 1;
  case DTYPE_REP_FLOAT:
    s[0] = (scalar){FLT, p->size, p->size};
    return 1;
  case DTYPE_REP_COMPLEX:
    s[0] = s[1] = (scalar){FLT, p->size / 2, p->size / 2};
    off[1] = p->size / 2;
    return 2;
  case DTYPE_REP_PAIR: {
    scalar v[2], x[2];
    int o[2];
    parts(p->pair_value, v, o);
    parts(p->pair_index, x, o);
    s[0] = v[0];
    s[1] = x[0];
    off[1] = p->pair_off;
    return 2;
  }
  default:
    if (i == (MPI_WCHAR & 0xffff)) s[0] = (scalar){UINT, (int)sizeof(wchar_t), 2};
    else s[0] = (scalar){RAW, p->size, p->size};
    return 1;
  }
}

static int xsize(int i) {
  scalar s[2];
  int off[2], n = parts(i, s, off);
  return s[0].xs + (n > 1 ? s[1].xs : 0);
}

/* Unsigned big-endian integers of n bytes. */
static void put_be(unsigned char *o, uint64_t v, int n) {
  for (int k = n - 1; k >= 0; k--, v >>= 8) o[k] = (unsigned char)v;
}
static uint64_t get_be(const unsigned char *in, int n) {
  uint64_t v = 0;
  for (int k = 0; k < n; k++) v = v << 8 | in[k];
  return v;
}

/* A native integer of n bytes (n <= 8), as the low bits of a uint64_t,
 * sign-extended if signed. */
static uint64_t get_native(const void *p, int n, int is_signed) {
  switch (n) {
  case 1: { uint8_t u; memcpy(&u, p, 1); return is_signed ? (uint64_t)(int64_t)(int8_t)u : u; }
  case 2: { uint16_t u; memcpy(&u, p, 2); return is_signed ? (uint64_t)(int64_t)(int16_t)u : u; }
  case 4: { uint32_t u; memcpy(&u, p, 4); return is_signed ? (uint64_t)(int64_t)(int32_t)u : u; }
  default: { uint64_t u; memcpy(&u, p, 8); return u; }
  }
}
static void put_native(void *p, uint64_t v, int n) {
  switch (n) {
  case 1: { uint8_t u = (uint8_t)v; memcpy(p, &u, 1); break; }
  case 2: { uint16_t u = (uint16_t)v; memcpy(p, &u, 2); break; }
  case 4: { uint32_t u = (uint32_t)v; memcpy(p, &u, 4); break; }
  default: memcpy(p, &v, 8);
  }
}

/* A long double as IEEE 754 binary128 (sign, 15-bit exponent of bias
 * 16383, 112-bit fraction), from its value: exact for every format of at
 * most 113 significant bits. */
static void ld_to_quad(long double x, unsigned char o[16]) {
  uint64_t hi = signbit(x) ? (uint64_t)1 << 63 : 0, lo = 0;
  long double a = fabsl(x);
  if (isnan(x)) {
    hi |= (uint64_t)0x7fff << 48 | (uint64_t)1 << 47;
  } else if (isinf(x)) {
    hi |= (uint64_t)0x7fff << 48;
  } else if (a != 0) {
    int e;
    long double m = frexpl(a, &e), f;   /* a = m 2^e, m in [0.5, 1) */
    int E = e - 1 + 16383;
    if (E >= 1) {
      f = ldexpl(m, 49) - ldexpl(1, 48);   /* the fraction's top 48 bits and the rest */
    } else {
      E = 0;   /* subnormal: a = f 2^-16494 */
      f = ldexpl(a, 16494 - 64);
    }
    uint64_t top = (uint64_t)f;
    hi |= (uint64_t)E << 48 | top;
    lo = (uint64_t)ldexpl(f - (long double)top, 64);
  }
  put_be(o, hi, 8);
  put_be(o + 8, lo, 8);
}

static long double quad_to_ld(const unsigned char in[16]) {
  uint64_t hi = get_be(in, 8), lo = get_be(in + 8, 8);
  int E = (int)(hi >> 48 & 0x7fff);
  uint64_t top = hi & (((uint64_t)1 << 48) - 1);
  long double v;
  if (E == 0x7fff) {
    v = top || lo ? NAN : INFINITY;
  } else {
    /* (2^48 [normal] + top) 2^64 + lo, rounded once, then scaled. */
    long double m = ldexpl((long double)(top + (E ? (uint64_t)1 << 48 : 0)), 64) + (long double)lo;
    v = ldexpl(m, (E ? E : 1) - 16383 - 112);
  }
  return hi >> 63 ? -v : v;
}

static void put_scalar(unsigned char *o, const char *p, scalar s) {
  switch (s.kind) {
  case SINT:
  case UINT:
    put_be(o, get_native(p, s.ns, s.kind == SINT), s.xs);
    break;
  case FLT:
    if (s.ns == 4) {
      uint32_t u;
      memcpy(&u, p, 4);
      put_be(o, u, 4);
    } else if (s.ns == 8) {
      uint64_t u;
      memcpy(&u, p, 8);
      put_be(o, u, 8);
    } else {
      long double x;
      memcpy(&x, p, sizeof x);
      ld_to_quad(x, o);
    }
    break;
  default:
    memcpy(o, p, (size_t)s.ns);
  }
}

static void get_scalar(const unsigned char *in, char *p, scalar s) {
  switch (s.kind) {
  case SINT:
  case UINT: {
    uint64_t v = get_be(in, s.xs);
    if (s.kind == SINT && s.xs < 8 && v >> (8 * s.xs - 1)) v |= ~(uint64_t)0 << 8 * s.xs;   /* sign-extend */
    put_native(p, v, s.ns);
    break;
  }
  case FLT:
    if (s.ns == 4) {
      uint32_t u = (uint32_t)get_be(in, 4);
      memcpy(p, &u, 4);
    } else if (s.ns == 8) {
      uint64_t u = get_be(in, 8);
      memcpy(p, &u, 8);
    } else {
      long double x = quad_to_ld(in);
      memcpy(p, &x, sizeof x);
    }
    break;
  default:
    memcpy(p, in, (size_t)s.ns);
  }
}

/* ==== whole types ========================================================= */

typedef struct {
  char *buf;                   /* the element's start */
  unsigned char *ext;          /* the external bytes, moving on */
  int unpack;
  MPI_Count size;              /* dtype_ext32_size's sum */
} walk;

static void size_run(void *ud, MPI_Aint disp, MPI_Count n, int type) {
  (void)disp;
  ((walk *)ud)->size += n * xsize(type);
}

static void move_run(void *ud, MPI_Aint disp, MPI_Count n, int type) {
  walk *w = ud;
  scalar s[2];
  int off[2], np = parts(type, s, off);
  MPI_Aint pext = dtype_predef_get(type)->extent;
  for (MPI_Count j = 0; j < n; j++) {
    char *p = (char *)((uintptr_t)w->buf + (uintptr_t)(disp + j * pext));
    for (int k = 0; k < np; k++) {
      if (w->unpack) get_scalar(w->ext, p + off[k], s[k]);
      else put_scalar(w->ext, p + off[k], s[k]);
      w->ext += s[k].xs;
    }
  }
}

MPI_Count dtype_ext32_size(MPI_Datatype dt) {
  walk w = {0};
  dtype_walk(dt, size_run, &w);
  return w.size;
}

static void move(const void *buf, MPI_Count count, MPI_Datatype dt, void *ext, int unpack) {
  walk w = {NULL, ext, unpack, 0};
  MPI_Aint extent = dtype_extent(dt);
  for (MPI_Count i = 0; i < count; i++) {
    w.buf = (char *)((uintptr_t)buf + (uintptr_t)(i * extent));
    dtype_walk(dt, move_run, &w);
  }
}

void dtype_ext32_pack(const void *buf, MPI_Count count, MPI_Datatype dt, void *out) {
  move(buf, count, dt, out, 0);
}

void dtype_ext32_unpack(const void *in, void *buf, MPI_Count count, MPI_Datatype dt) {
  move(buf, count, dt, (void *)in, 1);
}

/* ==== the MPI functions =================================================== */

/* The common checks: datarep, count, type. */
static int ext_args(const char *fn, const char *datarep, int count, MPI_Datatype dt) {
  MPI_Comm w = MPI_COMM_WORLD;
  char why[96];
  int rc;
  if (!datarep) return err_comm_raise(w, MPI_ERR_ARG, fn, "datarep is NULL");
  if (strcmp(datarep, "external32"))
    return err_comm_raise(w, MPI_ERR_ARG, fn, "datarep \"%.40s\": only \"external32\" is defined", datarep);
  if ((rc = err_comm_check_count(w, fn, count))) return rc;
  if (dtype_check(dt, why, sizeof why) != MPI_SUCCESS)
    return err_comm_raise(w, MPI_ERR_TYPE, fn, "invalid datatype: %s", why);
  return MPI_SUCCESS;
}

int PMPI_Pack_external_size(const char *datarep, int incount, MPI_Datatype datatype, MPI_Aint *size) {
  static const char fn[] = "MPI_Pack_external_size";
  int rc = ext_args(fn, datarep, incount, datatype);
  if (rc) return rc;
  if (!size) return err_comm_raise(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "size is NULL");
  *size = (MPI_Aint)(dtype_ext32_size(datatype) * incount);
  return MPI_SUCCESS;
}

int PMPI_Pack_external(const char datarep[], const void *inbuf, int incount, MPI_Datatype datatype,
                      void *outbuf, MPI_Aint outsize, MPI_Aint *position) {
  static const char fn[] = "MPI_Pack_external";
  MPI_Comm w = MPI_COMM_WORLD;
  int rc = ext_args(fn, datarep, incount, datatype);
  if (rc || (rc = err_comm_check_buf(w, fn, inbuf, incount, datatype))) return rc;
  MPI_Count n = dtype_ext32_size(datatype) * incount;
  if ((rc = dtype_room_ok(w, fn, 1, position, position ? (long)*position : 0, (long)outsize, n, outbuf))) return rc;
  if (n > 0) dtype_ext32_pack(inbuf, incount, datatype, (char *)outbuf + *position);
  *position += (MPI_Aint)n;
  return MPI_SUCCESS;
}

int PMPI_Unpack_external(const char datarep[], const void *inbuf, MPI_Aint insize, MPI_Aint *position,
                        void *outbuf, int outcount, MPI_Datatype datatype) {
  static const char fn[] = "MPI_Unpack_external";
  MPI_Comm w = MPI_COMM_WORLD;
  int rc = ext_args(fn, datarep, outcount, datatype);
  if (rc || (rc = err_comm_check_buf(w, fn, outbuf, outcount, datatype))) return rc;
  MPI_Count n = dtype_ext32_size(datatype) * outcount;
  if ((rc = dtype_room_ok(w, fn, 0, position, position ? (long)*position : 0, (long)insize, n, inbuf))) return rc;
  if (n > 0) dtype_ext32_unpack((const char *)inbuf + *position, outbuf, outcount, datatype);
  *position += (MPI_Aint)n;
  return MPI_SUCCESS;
}
