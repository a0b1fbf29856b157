/* op.c -- reduction operations: the predefined kernels, user operations, applying them (op.h). */
#include "mpi/op.h"

#include <complex.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/dtype.h"
#include "mpi/core.h"

/* ==== kernels =============================================================
 * kernel(in, inout, n, stride, ioff): n elements stride bytes apart;
 * inout = in op inout.  Values are loaded and stored with memcpy: packed
 * pairs and user buffers need not be aligned. */

typedef void kernel(const char *in, char *io, size_t n, size_t stride, size_t ioff);

#define KERNEL(name, T, EXPR)                                                  \
  static void name(const char *in, char *io, size_t n, size_t stride, size_t ioff) { \
    (void)ioff;                                                                \
    for (size_t k = 0; k < n; k++, in += stride, io += stride) {               \
      T a, b;                                                                  \
      memcpy(&a, in, sizeof a);                                                \
      memcpy(&b, io, sizeof b);                                                \
      b = (T)(EXPR);                                                           \
      memcpy(io, &b, sizeof b);                                                \
    }                                                                          \
  }

/* Integers of type T (U: the unsigned type of its size): sums and products
 * wrap around, computed in unsigned long long (no overflow, no promotion to
 * int), then cut to U. */
#define WRAP(U, x) ((U)(unsigned long long)(x))
#define INT_KERNELS(p, T, U)                                                          \
  KERNEL(p##_max, T, a > b ? a : b)                                                   \
  KERNEL(p##_min, T, a < b ? a : b)                                                   \
  KERNEL(p##_sum, T, WRAP(U, (unsigned long long)(U)a + (unsigned long long)(U)b))    \
  KERNEL(p##_prod, T, WRAP(U, (unsigned long long)(U)a * (unsigned long long)(U)b))   \
  KERNEL(p##_land, T, (a != 0) && (b != 0))                                           \
  KERNEL(p##_lor, T, (a != 0) || (b != 0))                                            \
  KERNEL(p##_lxor, T, (a != 0) != (b != 0))                                           \
  KERNEL(p##_band, T, (U)((U)a & (U)b))                                               \
  KERNEL(p##_bor, T, (U)((U)a | (U)b))                                                \
  KERNEL(p##_bxor, T, (U)((U)a ^ (U)b))

INT_KERNELS(i8, int8_t, uint8_t)
INT_KERNELS(i16, int16_t, uint16_t)
INT_KERNELS(i32, int32_t, uint32_t)
INT_KERNELS(i64, int64_t, uint64_t)
INT_KERNELS(u8, uint8_t, uint8_t)
INT_KERNELS(u16, uint16_t, uint16_t)
INT_KERNELS(u32, uint32_t, uint32_t)
INT_KERNELS(u64, uint64_t, uint64_t)

#define FLOAT_KERNELS(p, T)                 \
  KERNEL(p##_max, T, a > b ? a : b)         \
  KERNEL(p##_min, T, a < b ? a : b)         \
  KERNEL(p##_sum, T, a + b)                 \
  KERNEL(p##_prod, T, a * b)                \
  KERNEL(p##_land, T, (a != 0) && (b != 0)) \
  KERNEL(p##_lor, T, (a != 0) || (b != 0))  \
  KERNEL(p##_lxor, T, (a != 0) != (b != 0))

FLOAT_KERNELS(f32, float)
FLOAT_KERNELS(f64, double)
FLOAT_KERNELS(fld, long double)

#define COMPLEX_KERNELS(p, T)  \
  KERNEL(p##_sum, T, a + b)    \
  KERNEL(p##_prod, T, a * b)

COMPLEX_KERNELS(c32, float _Complex)
COMPLEX_KERNELS(c64, double _Complex)
COMPLEX_KERNELS(cld, long double _Complex)

/* MINLOC and MAXLOC (MPI 3.1 section 5.9.4): the smaller (larger) value
 * with its index; on equal values the smaller index.  The index lies ioff
 * bytes into the pair. */
#define PAIR_KERNEL(name, V, I, CMP)                                               \
  static void name(const char *in, char *io, size_t n, size_t stride, size_t ioff) { \
    for (size_t k = 0; k < n; k++, in += stride, io += stride) {                   \
      V u, v;                                                                      \
      I i, j;                                                                      \
      memcpy(&u, in, sizeof u);                                                    \
      memcpy(&i, in + ioff, sizeof i);                                             \
      memcpy(&v, io, sizeof v);                                                    \
      memcpy(&j, io + ioff, sizeof j);                                             \
      if (u CMP v) {                                                               \
        v = u;                                                                     \
        j = i;                                                                     \
      } else if (u == v && i < j) {                                                \
        j = i;                                                                     \
      }                                                                            \
      memcpy(io, &v, sizeof v);                                                    \
      memcpy(io + ioff, &j, sizeof j);                                             \
    }                                                                              \
  }
#define PAIR_KERNELS(p, V, I) PAIR_KERNEL(p##_minloc, V, I, <) PAIR_KERNEL(p##_maxloc, V, I, >)

PAIR_KERNELS(float_int, float, int)
PAIR_KERNELS(double_int, double, int)
PAIR_KERNELS(long_int, long, int)
PAIR_KERNELS(int_int, int, int)
PAIR_KERNELS(short_int, short, int)
PAIR_KERNELS(ldouble_int, long double, int)
PAIR_KERNELS(real_real, float, float)
PAIR_KERNELS(dp_dp, double, double)
PAIR_KERNELS(integer_integer, int32_t, int32_t)

/* The predefined operations by index (MPI_MAX is 1, ... MPI_NO_OP 14). */
enum { OP_MAX = 1, OP_MIN, OP_SUM, OP_PROD, OP_LAND, OP_BAND, OP_LOR, OP_BOR, OP_LXOR, OP_BXOR,
       OP_MINLOC, OP_MAXLOC, OP_REPLACE, OP_NO_OP, OP_N };

static const char *const op_names[OP_N] = {
  NULL, "MPI_MAX", "MPI_MIN", "MPI_SUM", "MPI_PROD", "MPI_LAND", "MPI_BAND", "MPI_LOR", "MPI_BOR",
  "MPI_LXOR", "MPI_BXOR", "MPI_MINLOC", "MPI_MAXLOC", "MPI_REPLACE", "MPI_NO_OP"};

/* Which classes (dtype.h) each operation applies to: MPI 3.1 section
 * 5.9.2's table, and the logical ones on MPI_AINT, MPI_OFFSET and
 * MPI_COUNT too, as MPICH and Open MPI (the standard leaves them out), and
 * on floating point, as MPICH 3 and SMPI (its test suite checks it; MPICH 4
 * and Open MPI refuse): 1 where both operands' truth (non-zero) gives
 * true, else 0. */
#define C(x) (1u << DTYPE_CLASS_##x)
static const unsigned op_classes[OP_N] = {
  [OP_MAX] = C(CINT) | C(FINT) | C(FLOAT) | C(MULTI),
  [OP_MIN] = C(CINT) | C(FINT) | C(FLOAT) | C(MULTI),
  [OP_SUM] = C(CINT) | C(FINT) | C(FLOAT) | C(COMPLEX) | C(MULTI),
  [OP_PROD] = C(CINT) | C(FINT) | C(FLOAT) | C(COMPLEX) | C(MULTI),
  [OP_LAND] = C(CINT) | C(LOGICAL) | C(MULTI) | C(FLOAT),
  [OP_LOR] = C(CINT) | C(LOGICAL) | C(MULTI) | C(FLOAT),
  [OP_LXOR] = C(CINT) | C(LOGICAL) | C(MULTI) | C(FLOAT),
  [OP_BAND] = C(CINT) | C(FINT) | C(BYTE) | C(MULTI),
  [OP_BOR] = C(CINT) | C(FINT) | C(BYTE) | C(MULTI),
  [OP_BXOR] = C(CINT) | C(FINT) | C(BYTE) | C(MULTI),
  [OP_MINLOC] = C(PAIR),
  [OP_MAXLOC] = C(PAIR),
};
#undef C

/* The ten integer kernels of one integer kind, by operation. */
#define INT_ROW(p) {NULL, p##_max, p##_min, p##_sum, p##_prod, p##_land, p##_band, p##_lor, p##_bor, p##_lxor, p##_bxor}
static kernel *const int_k[2][4][OP_BXOR + 1] = {
  {INT_ROW(i8), INT_ROW(i16), INT_ROW(i32), INT_ROW(i64)},
  {INT_ROW(u8), INT_ROW(u16), INT_ROW(u32), INT_ROW(u64)},
};

static int log2size(int size) {
  return size == 1 ? 0 : size == 2 ? 1 : size == 4 ? 2 : size == 8 ? 3 : -1;
}

/* The kernel of predefined operation o on predefined type i, or NULL. */
static kernel *pick(int o, int i) {
  const dtype_predef *p = dtype_predef_get(i);
  if (!p || o <= 0 || o >= OP_N || !(op_classes[o] & (1u << p->cls))) return NULL;
  switch (p->rep) {
  case DTYPE_REP_INT:
  case DTYPE_REP_UINT:
  case DTYPE_REP_BOOL: {
    int l = log2size(p->size);
    if (l < 0 || o > OP_BXOR) return NULL;
    return int_k[p->rep != DTYPE_REP_INT][l][o];
  }
  case DTYPE_REP_FLOAT: {
    /* by operation: MAX MIN SUM PROD LAND BAND LOR BOR LXOR */
    kernel *k32[] = {NULL, f32_max, f32_min, f32_sum, f32_prod, f32_land, NULL, f32_lor, NULL, f32_lxor};
    kernel *k64[] = {NULL, f64_max, f64_min, f64_sum, f64_prod, f64_land, NULL, f64_lor, NULL, f64_lxor};
    kernel *kld[] = {NULL, fld_max, fld_min, fld_sum, fld_prod, fld_land, NULL, fld_lor, NULL, fld_lxor};
    if (o > OP_LXOR) return NULL;
    if (p->size == (int)sizeof(float)) return k32[o];
    if (p->size == (int)sizeof(double)) return k64[o];
    if (p->size == (int)sizeof(long double)) return kld[o];
    return NULL;
  }
  case DTYPE_REP_COMPLEX:
    if (o != OP_SUM && o != OP_PROD) return NULL;
    if (p->size == (int)sizeof(float _Complex)) return o == OP_SUM ? c32_sum : c32_prod;
    if (p->size == (int)sizeof(double _Complex)) return o == OP_SUM ? c64_sum : c64_prod;
    if (p->size == (int)sizeof(long double _Complex)) return o == OP_SUM ? cld_sum : cld_prod;
    return NULL;
  case DTYPE_REP_PAIR: {
    int min = o == OP_MINLOC;
    switch (i) {
    case MPI_FLOAT_INT & 0xffff: return min ? float_int_minloc : float_int_maxloc;
    case MPI_DOUBLE_INT & 0xffff: return min ? double_int_minloc : double_int_maxloc;
    case MPI_LONG_INT & 0xffff: return min ? long_int_minloc : long_int_maxloc;
    case MPI_2INT & 0xffff: return min ? int_int_minloc : int_int_maxloc;
    case MPI_SHORT_INT & 0xffff: return min ? short_int_minloc : short_int_maxloc;
    case MPI_LONG_DOUBLE_INT & 0xffff: return min ? ldouble_int_minloc : ldouble_int_maxloc;
    case MPI_2REAL & 0xffff: return min ? real_real_minloc : real_real_maxloc;
    case MPI_2DOUBLE_PRECISION & 0xffff: return min ? dp_dp_minloc : dp_dp_maxloc;
    case MPI_2INTEGER & 0xffff: return min ? integer_integer_minloc : integer_integer_maxloc;
    default: return NULL;
    }
  }
  default:
    return NULL;
  }
}

/* ==== the rank's user operations ========================================== */

enum { CREATED = 0x04800000, SLOT_MASK = 0x7fffff };

typedef struct {
  MPI_User_function *fn;
  int commute;
  int used;
  int holds;    /* op_hold's, not released yet */
  int freed;    /* MPI_Op_free'd while held: gone when the last hold goes */
} user_op;

typedef struct {
  user_op *slot;
  int n, cap;
} table;

static void table_release(void *p) {
  table *tb = p;
  free(tb->slot);
  free(tb);
}

static table *tab(int create) {
  table *tb = st_part(ST_PART_OP);
  if (tb || !create) return tb;
  tb = calloc(1, sizeof *tb);
  if (!tb) return NULL;
  st_part_set(ST_PART_OP, tb, table_release);
  return tb;
}

/* The predefined index of op (1 .. OP_N - 1), or 0. */
static int predefined(MPI_Op op) {
  int i = op & 0xffffff;
  return (op & 0xff000000) == 0x04000000 && i > 0 && i < OP_N ? i : 0;
}

static user_op *user(MPI_Op op) {
  if ((op & 0xff800000) != CREATED) return NULL;
  table *tb = tab(0);
  int i = op & SLOT_MASK;
  return tb && i < tb->n && tb->slot[i].used ? &tb->slot[i] : NULL;
}

int op_valid(MPI_Op op, char *why, size_t len) {
  const char *w = NULL;
  if (op == MPI_OP_NULL) w = "MPI_OP_NULL";
  else if ((op & 0xff000000) != 0x04000000) w = "not an operation";
  else if (!predefined(op) && (!user(op) || user(op)->freed))
    w = op & 0x800000 ? "not an operation of this rank (freed?)" : "not an operation";
  if (!w) return MPI_SUCCESS;
  if (why && len) snprintf(why, len, "%s", w);
  return MPI_ERR_OP;
}

int op_is_predefined(MPI_Op op) { return predefined(op) != 0; }

int op_commutative(MPI_Op op) {
  const user_op *u = user(op);
  return u ? u->commute : 1;
}

const char *op_name(MPI_Op op) {
  int o = predefined(op);
  return o ? op_names[o] : "a user operation";
}

int op_check(MPI_Op op, MPI_Datatype dt, char *why, size_t len) {
  int o = predefined(op);
  if (!o) return MPI_SUCCESS;
  MPI_Count per;
  int e = dtype_elem(dt, &per);
  const char *tn = dtype_name(dt);
  if (dtype_size(dt) == 0) return MPI_SUCCESS;   /* nothing to combine */
  if (!e) {
    if (why && len) snprintf(why, len, "%s does not apply to a type of several basic types", op_names[o]);
    return MPI_ERR_OP;
  }
  if (pick(o, e)) return MPI_SUCCESS;
  if (why && len) {
    const char *en = dtype_predef_get(e)->name;
    if (o == OP_REPLACE || o == OP_NO_OP)
      snprintf(why, len, "%s is only for MPI_Accumulate", op_names[o]);
    else if (e == (dt & 0xffff) && !(dt & 0x800000))
      snprintf(why, len, "%s does not apply to %s", op_names[o], en);
    else
      snprintf(why, len, "%s does not apply to %s (a type of %s)", op_names[o], *tn ? tn : "a derived type", en);
  }
  return MPI_ERR_OP;
}

/* ==== applying ============================================================ */

static void predefined_packed(int o, MPI_Datatype dt, const void *in, void *inout, int count) {
  MPI_Count per;
  int e = dtype_elem(dt, &per);
  const dtype_predef *p = dtype_predef_get(e);
  if (!p || count == 0) return;
  size_t ioff = p->rep == DTYPE_REP_PAIR ? (size_t)dtype_predef_get(p->pair_value)->size : 0;
  pick(o, e)(in, inout, (size_t)(per * count), (size_t)p->size, ioff);
}

typedef struct {
  kernel *k;
  const char *in;
  char *io;
  size_t stride, ioff;
} runs_ud;

static void one_run(void *ud, MPI_Aint disp, MPI_Count n) {
  runs_ud *r = ud;
  r->k(r->in + disp, r->io + disp, (size_t)n, r->stride, r->ioff);
}

static void predefined_laid_out(int o, MPI_Datatype dt, const void *in, void *inout, int count) {
  int e = dtype_elem(dt, NULL);
  const dtype_predef *p = dtype_predef_get(e);
  if (!p) return;
  MPI_Aint ext = dtype_extent(dt);
  runs_ud r = {pick(o, e), NULL, NULL, (size_t)p->extent, p->rep == DTYPE_REP_PAIR ? (size_t)p->pair_off : 0};
  for (int i = 0; i < count; i++) {
    r.in = (const char *)((uintptr_t)in + (uintptr_t)((MPI_Aint)i * ext));
    r.io = (char *)((uintptr_t)inout + (uintptr_t)((MPI_Aint)i * ext));
    dtype_runs(dt, one_run, &r);
  }
}

void op_reduce(MPI_Op op, MPI_Datatype dt, const void *in, void *inout, int count) {
  int o = predefined(op);
  if (o) {
    predefined_laid_out(o, dt, in, inout, count);
    return;
  }
  user_op *u = user(op);
  MPI_Datatype d = dt;
  int n = count;
  u->fn((void *)in, inout, &n, &d);
}

void op_reduce_packed(MPI_Op op, MPI_Datatype dt, const void *in, void *inout, int count) {
  int o = predefined(op);
  if (o) {
    predefined_packed(o, dt, in, inout, count);
    return;
  }
  if (count == 0) return;
  /* A user function sees the elements laid out: packed elements of a
   * contiguous type are, others are unpacked into scratch and back. */
  if (dtype_contiguous(dt, count)) {
    uintptr_t shift = (uintptr_t)dtype_true_lb(dt);
    op_reduce(op, dt, (const void *)((uintptr_t)in - shift), (void *)((uintptr_t)inout - shift), count);
    return;
  }
  MPI_Aint ext = dtype_extent(dt), tlb = dtype_true_lb(dt);
  size_t span = (size_t)((MPI_Aint)(count - 1) * (ext < 0 ? -ext : ext) + dtype_true_extent(dt));
  char *a = malloc(span ? span : 1), *b = malloc(span ? span : 1);
  if (!a || !b) {
    fprintf(stderr, "tilesim: out of memory (%zu bytes) for a user reduction\n", 2 * span);
    abort();
  }
  /* The scratch's start is the lowest byte the elements touch. */
  MPI_Aint low = tlb + (ext < 0 ? (MPI_Aint)(count - 1) * ext : 0);
  char *abase = (char *)((uintptr_t)a - (uintptr_t)low), *bbase = (char *)((uintptr_t)b - (uintptr_t)low);
  size_t bytes = dtype_size(dt) * (size_t)count;
  dtype_unpack(in, bytes, abase, count, dt);
  dtype_unpack(inout, bytes, bbase, count, dt);
  op_reduce(op, dt, abase, bbase, count);
  dtype_pack(bbase, count, dt, inout);
  free(a);
  free(b);
}

/* ==== creating and freeing ================================================ */

int op_create(MPI_User_function *fn, int commute, MPI_Op *op) {
  table *tb = tab(1);
  if (!tb) return MPI_ERR_NO_MEM;
  int i;
  for (i = 0; i < tb->n && tb->slot[i].used; i++)
    ;
  if (i == tb->n) {
    if (tb->n == tb->cap) {
      int cap = tb->cap ? 2 * tb->cap : 8;
      if (cap > SLOT_MASK + 1) return MPI_ERR_NO_MEM;
      user_op *s = realloc(tb->slot, (size_t)cap * sizeof *s);
      if (!s) return MPI_ERR_NO_MEM;
      tb->slot = s;
      tb->cap = cap;
    }
    tb->n++;
  }
  tb->slot[i] = (user_op){fn, commute != 0, 1, 0, 0};
  *op = CREATED | i;
  return MPI_SUCCESS;
}

int op_free(MPI_Op op) {
  user_op *u = user(op);
  if (!u || u->freed) return MPI_ERR_OP;
  if (u->holds)
    u->freed = 1;
  else
    u->used = 0;
  return MPI_SUCCESS;
}

void op_hold(MPI_Op op) {
  user_op *u = user(op);
  if (u) u->holds++;
}

void op_release(MPI_Op op) {
  user_op *u = user(op);
  if (!u || u->holds <= 0) return;
  if (--u->holds == 0 && u->freed) u->used = u->freed = 0;
}
