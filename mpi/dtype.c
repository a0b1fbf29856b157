/* dtype.c -- datatypes: the predefined table, the rank's created types, pack and unpack (dtype.h). */
#include "mpi/dtype.h"

#include <complex.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <wchar.h>

#include "mpi/core.h"

/* ==== the predefined types ================================================ */

/* The pairs of MPI 3.1 section 5.9.4, as the standard defines them (a
 * struct of the value and an int; Fortran's: two of one type). */
typedef struct { float v; int i; } pair_float_int;
typedef struct { double v; int i; } pair_double_int;
typedef struct { long v; int i; } pair_long_int;
typedef struct { int v; int i; } pair_2int;
typedef struct { short v; int i; } pair_short_int;
typedef struct { long double v; int i; } pair_long_double_int;
typedef struct { float v, i; } pair_2real;
typedef struct { double v, i; } pair_2double;
typedef struct { int32_t v, i; } pair_2integer;

#define IDX(h) ((h) & 0xffff)
/* A char's representation: signed on most machines, unsigned on some. */
#define CHAR_REP (CHAR_MIN < 0 ? DTYPE_REP_INT : DTYPE_REP_UINT)

/* Every predefined type: B(handle, C type, class, representation) (the
 * handle as written is the type's name: MPI_LONG_LONG, which MPI_LONG_LONG_INT
 * is a synonym of since MPI 2.1, as MPICH names it),
 * P(handle, pair struct, value's handle, index's handle) and M(handle,
 * sticky lb, sticky ub) for the markers MPI_LB and MPI_UB. */
#define PREDEF_LIST(B, P, M)                                                                  \
  B(MPI_CHAR, char, DTYPE_CLASS_CINT, CHAR_REP)                                              \
  B(MPI_SIGNED_CHAR, signed char, DTYPE_CLASS_CINT, DTYPE_REP_INT)                           \
  B(MPI_UNSIGNED_CHAR, unsigned char, DTYPE_CLASS_CINT, DTYPE_REP_UINT)                      \
  B(MPI_BYTE, unsigned char, DTYPE_CLASS_BYTE, DTYPE_REP_UINT)                               \
  B(MPI_WCHAR, wchar_t, DTYPE_CLASS_NONE, DTYPE_REP_NONE)                                    \
  B(MPI_SHORT, short, DTYPE_CLASS_CINT, DTYPE_REP_INT)                                       \
  B(MPI_UNSIGNED_SHORT, unsigned short, DTYPE_CLASS_CINT, DTYPE_REP_UINT)                    \
  B(MPI_INT, int, DTYPE_CLASS_CINT, DTYPE_REP_INT)                                           \
  B(MPI_UNSIGNED, unsigned, DTYPE_CLASS_CINT, DTYPE_REP_UINT)                                \
  B(MPI_LONG, long, DTYPE_CLASS_CINT, DTYPE_REP_INT)                                         \
  B(MPI_UNSIGNED_LONG, unsigned long, DTYPE_CLASS_CINT, DTYPE_REP_UINT)                      \
  B(MPI_LONG_LONG, long long, DTYPE_CLASS_CINT, DTYPE_REP_INT)                               \
  B(MPI_UNSIGNED_LONG_LONG, unsigned long long, DTYPE_CLASS_CINT, DTYPE_REP_UINT)            \
  B(MPI_FLOAT, float, DTYPE_CLASS_FLOAT, DTYPE_REP_FLOAT)                                    \
  B(MPI_DOUBLE, double, DTYPE_CLASS_FLOAT, DTYPE_REP_FLOAT)                                  \
  B(MPI_LONG_DOUBLE, long double, DTYPE_CLASS_FLOAT, DTYPE_REP_FLOAT)                        \
  B(MPI_C_BOOL, _Bool, DTYPE_CLASS_LOGICAL, DTYPE_REP_BOOL)                                  \
  B(MPI_INT8_T, int8_t, DTYPE_CLASS_CINT, DTYPE_REP_INT)                                     \
  B(MPI_INT16_T, int16_t, DTYPE_CLASS_CINT, DTYPE_REP_INT)                                   \
  B(MPI_INT32_T, int32_t, DTYPE_CLASS_CINT, DTYPE_REP_INT)                                   \
  B(MPI_INT64_T, int64_t, DTYPE_CLASS_CINT, DTYPE_REP_INT)                                   \
  B(MPI_UINT8_T, uint8_t, DTYPE_CLASS_CINT, DTYPE_REP_UINT)                                  \
  B(MPI_UINT16_T, uint16_t, DTYPE_CLASS_CINT, DTYPE_REP_UINT)                                \
  B(MPI_UINT32_T, uint32_t, DTYPE_CLASS_CINT, DTYPE_REP_UINT)                                \
  B(MPI_UINT64_T, uint64_t, DTYPE_CLASS_CINT, DTYPE_REP_UINT)                                \
  B(MPI_AINT, MPI_Aint, DTYPE_CLASS_MULTI, DTYPE_REP_INT)                                    \
  B(MPI_COUNT, MPI_Count, DTYPE_CLASS_MULTI, DTYPE_REP_INT)                                  \
  B(MPI_OFFSET, MPI_Offset, DTYPE_CLASS_MULTI, DTYPE_REP_INT)                                \
  B(MPI_C_FLOAT_COMPLEX, float _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX)             \
  B(MPI_C_DOUBLE_COMPLEX, double _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX)           \
  B(MPI_C_LONG_DOUBLE_COMPLEX, long double _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX) \
  B(MPI_PACKED, unsigned char, DTYPE_CLASS_NONE, DTYPE_REP_NONE)                             \
  P(MPI_FLOAT_INT, pair_float_int, MPI_FLOAT, MPI_INT)                                       \
  P(MPI_DOUBLE_INT, pair_double_int, MPI_DOUBLE, MPI_INT)                                    \
  P(MPI_LONG_INT, pair_long_int, MPI_LONG, MPI_INT)                                          \
  P(MPI_2INT, pair_2int, MPI_INT, MPI_INT)                                                   \
  P(MPI_SHORT_INT, pair_short_int, MPI_SHORT, MPI_INT)                                       \
  P(MPI_LONG_DOUBLE_INT, pair_long_double_int, MPI_LONG_DOUBLE, MPI_INT)                     \
  B(MPI_CXX_BOOL, _Bool, DTYPE_CLASS_LOGICAL, DTYPE_REP_BOOL)                                \
  B(MPI_CXX_FLOAT_COMPLEX, float _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX)           \
  B(MPI_CXX_DOUBLE_COMPLEX, double _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX)         \
  B(MPI_CXX_LONG_DOUBLE_COMPLEX, long double _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX) \
  B(MPI_CHARACTER, char, DTYPE_CLASS_NONE, DTYPE_REP_NONE)                                   \
  B(MPI_LOGICAL, int32_t, DTYPE_CLASS_LOGICAL, DTYPE_REP_BOOL)                               \
  B(MPI_INTEGER, int32_t, DTYPE_CLASS_FINT, DTYPE_REP_INT)                                   \
  B(MPI_REAL, float, DTYPE_CLASS_FLOAT, DTYPE_REP_FLOAT)                                     \
  B(MPI_DOUBLE_PRECISION, double, DTYPE_CLASS_FLOAT, DTYPE_REP_FLOAT)                        \
  B(MPI_COMPLEX, float _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX)                     \
  B(MPI_DOUBLE_COMPLEX, double _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX)             \
  P(MPI_2REAL, pair_2real, MPI_REAL, MPI_REAL)                                               \
  P(MPI_2DOUBLE_PRECISION, pair_2double, MPI_DOUBLE_PRECISION, MPI_DOUBLE_PRECISION)         \
  P(MPI_2INTEGER, pair_2integer, MPI_INTEGER, MPI_INTEGER)                                   \
  B(MPI_INTEGER1, int8_t, DTYPE_CLASS_FINT, DTYPE_REP_INT)                                   \
  B(MPI_INTEGER2, int16_t, DTYPE_CLASS_FINT, DTYPE_REP_INT)                                  \
  B(MPI_INTEGER4, int32_t, DTYPE_CLASS_FINT, DTYPE_REP_INT)                                  \
  B(MPI_INTEGER8, int64_t, DTYPE_CLASS_FINT, DTYPE_REP_INT)                                  \
  B(MPI_REAL4, float, DTYPE_CLASS_FLOAT, DTYPE_REP_FLOAT)                                    \
  B(MPI_REAL8, double, DTYPE_CLASS_FLOAT, DTYPE_REP_FLOAT)                                   \
  B(MPI_COMPLEX8, float _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX)                    \
  B(MPI_COMPLEX16, double _Complex, DTYPE_CLASS_COMPLEX, DTYPE_REP_COMPLEX)                 \
  M(MPI_LB, 1, 0)                                                                            \
  M(MPI_UB, 0, 1)

/* A pair's parts: the value's and the index's sizes, the index's offset;
 * laid out without a gap between them, a pair is one run of bytes. */
#define VSIZE(st) ((int)sizeof(((st *)0)->v))
#define ISIZE(st) ((int)sizeof(((st *)0)->i))
#define IOFF(st) ((int)offsetof(st, i))
#define PACKED_LIKE(st) (IOFF(st) == VSIZE(st))

#define DESC_B(h, ctype, cls, rep) \
  [IDX(h)] = {#h, (int)sizeof(ctype), (int)sizeof(ctype), (int)_Alignof(ctype), cls, rep, 0, 0, 0},
#define DESC_P(h, st, vh, ih)                                                                  \
  [IDX(h)] = {#h, VSIZE(st) + ISIZE(st), (int)sizeof(st), (int)_Alignof(st), DTYPE_CLASS_PAIR, \
              DTYPE_REP_PAIR, IDX(vh), IDX(ih), IOFF(st)},
#define DESC_M(h, l, u) [IDX(h)] = {#h, 0, 0, 1, DTYPE_CLASS_NONE, DTYPE_REP_NONE, 0, 0, 0},
const dtype_predef dtype_predefs[DTYPE_PREDEF_N] = {PREDEF_LIST(DESC_B, DESC_P, DESC_M)};

/* ==== type objects ======================================================== */

typedef struct {
  MPI_Aint disp;   /* of the first entry, from the element's start */
  MPI_Count n;     /* entries, one predefined extent apart */
  int type;        /* predefined index */
} run;

typedef struct {
  MPI_Aint disp, len;   /* bytes of data at disp */
} seg;

typedef struct dt {
  int refs;              /* created types: handles, holds and decoding parents */
  int committed;
  int predef;            /* the predefined index, or 0 */
  int slb, sub;          /* explicit (sticky) lb and ub markers: MPI_LB, MPI_UB, resized */
  int align;             /* the strictest alignment of its basic types */
  int contig;            /* one run of bytes, size == extent (or no data) */
  int elem;              /* the one predefined type of its entries, or 0 */
  MPI_Count per_elem;    /* entries of elem per element */
  MPI_Count size;        /* bytes of data */
  MPI_Count nbasic;      /* basic entries (a pair counts 2) */
  MPI_Aint lb, ub, tlb, tub;
  size_t nrun, nseg;
  const run *runs;   /* static for the predefined objects, malloc'd for created ones */
  const seg *segs;
  int combiner, ni, na, nd;   /* decoding (MPI_Type_get_contents) */
  int *ints;
  MPI_Aint *aints;
  MPI_Datatype *types;
  char *name;
} dt;

/* The predefined objects, constants shared by every rank: one run of one
 * entry; a pair's bytes in one piece or two. */
#define RUN_B(h, ctype, cls, rep) [IDX(h)] = {0, 1, IDX(h)},
#define RUN_P(h, st, vh, ih) [IDX(h)] = {0, 1, IDX(h)},
#define NONE_M(h, l, u)
static const run pre_run[DTYPE_PREDEF_N] = {PREDEF_LIST(RUN_B, RUN_P, NONE_M)};

#define SEG_B(h, ctype, cls, rep) [IDX(h)] = {{0, (MPI_Aint)sizeof(ctype)}, {0, 0}},
#define SEG_P(h, st, vh, ih) \
  [IDX(h)] = {{0, PACKED_LIKE(st) ? VSIZE(st) + ISIZE(st) : VSIZE(st)}, {IOFF(st), ISIZE(st)}},
static const seg pre_seg[DTYPE_PREDEF_N][2] = {PREDEF_LIST(SEG_B, SEG_P, NONE_M)};

#define OBJ_B(h, ctype, cls, rep)                                                          \
  [IDX(h)] = {.committed = 1, .predef = IDX(h), .align = (int)_Alignof(ctype), .contig = 1, \
              .elem = IDX(h), .per_elem = 1, .size = sizeof(ctype), .nbasic = 1,           \
              .ub = sizeof(ctype), .tub = sizeof(ctype), .nrun = 1, .nseg = 1,             \
              .runs = &pre_run[IDX(h)], .segs = pre_seg[IDX(h)],                           \
              .combiner = MPI_COMBINER_NAMED},
#define OBJ_P(h, st, vh, ih)                                                               \
  [IDX(h)] = {.committed = 1, .predef = IDX(h), .align = (int)_Alignof(st),                \
              .contig = PACKED_LIKE(st) && VSIZE(st) + ISIZE(st) == (int)sizeof(st),       \
              .elem = IDX(h), .per_elem = 1, .size = VSIZE(st) + ISIZE(st), .nbasic = 2,   \
              .ub = sizeof(st), .tub = IOFF(st) + ISIZE(st), .nrun = 1,                    \
              .nseg = PACKED_LIKE(st) ? 1 : 2, .runs = &pre_run[IDX(h)],                   \
              .segs = pre_seg[IDX(h)], .combiner = MPI_COMBINER_NAMED},
/* A marker: no data, lower and upper bound 0, one of them sticky. */
#define OBJ_M(h, l, u)                                                                     \
  [IDX(h)] = {.committed = 1, .predef = IDX(h), .slb = l, .sub = u, .align = 1, .contig = 1, \
              .combiner = MPI_COMBINER_NAMED},
static const dt pre_obj[DTYPE_PREDEF_N] = {PREDEF_LIST(OBJ_B, OBJ_P, OBJ_M)};

/* ==== the rank's table ==================================================== */

enum { CREATED = 0x03800000, SLOT_MASK = 0x7fffff };

typedef struct {
  dt **slot;
  int n, cap;
  int *spare;   /* freed slots, reused last in first out */
  int nspare;
  char *pname[DTYPE_PREDEF_N];   /* names this rank gave predefined types */
} table;

static void table_release(void *p) {
  table *tb = p;
  for (int i = 0; i < tb->n; i++) {
    dt *t = tb->slot[i];
    if (!t) continue;
    free((void *)t->runs);
    free((void *)t->segs);
    free(t->ints);
    free(t->aints);
    free(t->types);
    free(t->name);
    free(t);
  }
  for (int i = 0; i < DTYPE_PREDEF_N; i++) free(tb->pname[i]);
  free(tb->slot);
  free(tb->spare);
  free(tb);
}

static table *tab(int create) {
  table *tb = st_part(ST_PART_DTYPE);
  if (tb || !create) return tb;
  tb = calloc(1, sizeof *tb);
  if (!tb) return NULL;
  st_part_set(ST_PART_DTYPE, tb, table_release);
  return tb;
}

/* The object of handle h, or NULL. */
static dt *obj(MPI_Datatype h) {
  if ((h & 0xff000000) != 0x03000000) return NULL;
  if (!(h & 0x800000)) {
    int i = h & 0xffff;
    return (h & 0x7f0000) == 0 && i > 0 && i < DTYPE_PREDEF_N && dtype_predefs[i].name ? (dt *)&pre_obj[i] : NULL;
  }
  table *tb = tab(0);
  int i = h & SLOT_MASK;
  if (!tb || i >= tb->n) return NULL;
  return tb->slot[i];
}

static void unref(MPI_Datatype h);

static void destroy(table *tb, int i) {
  dt *t = tb->slot[i];
  tb->slot[i] = NULL;
  if (tb->nspare < tb->cap) tb->spare[tb->nspare++] = i;
  for (int k = 0; k < t->nd; k++) unref(t->types[k]);
  free((void *)t->runs);
  free((void *)t->segs);
  free(t->ints);
  free(t->aints);
  free(t->types);
  free(t->name);
  free(t);
}

static void unref(MPI_Datatype h) {
  dt *t = obj(h);
  if (!t || t->predef) return;
  if (--t->refs == 0) destroy(tab(0), h & SLOT_MASK);
}

static void ref(MPI_Datatype h) {
  dt *t = obj(h);
  if (t && !t->predef) t->refs++;
}

/* A slot for t: its handle, or MPI_DATATYPE_NULL when memory ran out. */
static MPI_Datatype enter(dt *t) {
  table *tb = tab(1);
  if (!tb) return MPI_DATATYPE_NULL;
  int i;
  if (tb->nspare) {
    i = tb->spare[--tb->nspare];
  } else {
    if (tb->n == tb->cap) {
      int cap = tb->cap ? 2 * tb->cap : 16;
      if (cap > SLOT_MASK + 1) return MPI_DATATYPE_NULL;
      dt **s = realloc(tb->slot, (size_t)cap * sizeof *s);
      if (!s) return MPI_DATATYPE_NULL;
      tb->slot = s;
      int *sp = realloc(tb->spare, (size_t)cap * sizeof *sp);
      if (!sp) return MPI_DATATYPE_NULL;
      tb->spare = sp;
      tb->cap = cap;
    }
    i = tb->n++;
  }
  tb->slot[i] = t;
  t->refs = 1;
  return CREATED | i;
}

/* ==== checks and queries ================================================== */

int dtype_valid(MPI_Datatype h, char *why, size_t len) {
  const char *w = NULL;
  if (h == MPI_DATATYPE_NULL) w = "MPI_DATATYPE_NULL";
  else if ((h & 0xff000000) != 0x03000000) w = "not a datatype";
  else if (!obj(h)) w = h & 0x800000 ? "not a datatype of this rank (freed?)" : "not a datatype";
  if (!w) return MPI_SUCCESS;
  if (why && len) snprintf(why, len, "%s", w);
  return MPI_ERR_TYPE;
}

int dtype_check(MPI_Datatype h, char *why, size_t len) {
  int rc = dtype_valid(h, why, len);
  if (rc != MPI_SUCCESS) return rc;
  if (!obj(h)->committed) {
    if (why && len) snprintf(why, len, "not committed");
    return MPI_ERR_TYPE;
  }
  return MPI_SUCCESS;
}

size_t dtype_size(MPI_Datatype h) { return (size_t)obj(h)->size; }
MPI_Aint dtype_extent(MPI_Datatype h) { const dt *t = obj(h); return t->ub - t->lb; }
MPI_Aint dtype_true_lb(MPI_Datatype h) { return obj(h)->tlb; }
MPI_Aint dtype_true_extent(MPI_Datatype h) { const dt *t = obj(h); return t->tub - t->tlb; }

void dtype_bounds(MPI_Datatype h, MPI_Aint *lb, MPI_Aint *ub, MPI_Aint *tlb, MPI_Aint *tub) {
  const dt *t = obj(h);
  if (lb) *lb = t->lb;
  if (ub) *ub = t->ub;
  if (tlb) *tlb = t->tlb;
  if (tub) *tub = t->tub;
}

/* The address disp bytes from p, without pointer arithmetic on NULL
 * (MPI_BOTTOM with absolute displacements). */
static char *at(const void *p, MPI_Aint disp) {
  return (char *)((uintptr_t)p + (uintptr_t)disp);
}

int dtype_contiguous(MPI_Datatype h, int count) {
  const dt *t = obj(h);
  return count == 0 || t->size == 0 || t->contig || (count == 1 && t->nseg == 1);
}

const void *dtype_contig(const void *buf, int count, MPI_Datatype h) {
  const dt *t = obj(h);
  if (!dtype_contiguous(h, count)) return NULL;
  return count == 0 || t->size == 0 ? buf : at(buf, t->segs[0].disp);
}

void dtype_pack(const void *buf, int count, MPI_Datatype h, void *out) {
  const dt *t = obj(h);
  if (dtype_contiguous(h, count)) {
    if (t->size && count) memcpy(out, dtype_contig(buf, count, h), (size_t)(t->size * count));
    return;
  }
  char *o = out;
  MPI_Aint ext = t->ub - t->lb;
  for (int i = 0; i < count; i++) {
    const char *b = at(buf, (MPI_Aint)i * ext);
    for (size_t k = 0; k < t->nseg; k++) {
      memcpy(o, at(b, t->segs[k].disp), (size_t)t->segs[k].len);
      o += t->segs[k].len;
    }
  }
}

void dtype_unpack(const void *in, size_t bytes, void *buf, int count, MPI_Datatype h) {
  const dt *t = obj(h);
  size_t all = (size_t)(t->size * count);
  if (bytes > all) bytes = all;
  if (dtype_contiguous(h, count)) {
    if (bytes) memcpy((void *)dtype_contig(buf, count, h), in, bytes);
    return;
  }
  const char *p = in;
  MPI_Aint ext = t->ub - t->lb;
  for (int i = 0; i < count && bytes; i++) {
    char *b = at(buf, (MPI_Aint)i * ext);
    for (size_t k = 0; k < t->nseg && bytes; k++) {
      size_t n = (size_t)t->segs[k].len < bytes ? (size_t)t->segs[k].len : bytes;
      memcpy(at(b, t->segs[k].disp), p, n);
      p += n;
      bytes -= n;
    }
  }
}

void dtype_hold(MPI_Datatype h) { ref(h); }
void dtype_release(MPI_Datatype h) { unref(h); }

MPI_Count dtype_elements(MPI_Datatype h, MPI_Count bytes) {
  const dt *t = obj(h);
  if (t->size == 0) return 0;
  MPI_Count n = bytes / t->size * t->nbasic, rest = bytes % t->size;
  for (size_t k = 0; k < t->nrun && rest > 0; k++) {
    const dtype_predef *p = &dtype_predefs[t->runs[k].type];
    for (MPI_Count j = 0; j < t->runs[k].n && rest > 0; j++) {
      if (p->rep == DTYPE_REP_PAIR) {
        int vs = dtype_predefs[p->pair_value].size;
        if (rest < vs) return MPI_UNDEFINED;
        rest -= vs;
        n++;
        if (rest == 0) break;
        if (rest < p->size - vs) return MPI_UNDEFINED;
        rest -= p->size - vs;
        n++;
      } else {
        if (rest < p->size) return MPI_UNDEFINED;
        rest -= p->size;
        n++;
      }
    }
  }
  return n;
}

MPI_Count dtype_elements_bytes(MPI_Datatype h, MPI_Count n) {
  const dt *t = obj(h);
  if (t->nbasic == 0) return n > 0 ? -1 : 0;
  MPI_Count bytes = n / t->nbasic * t->size, rest = n % t->nbasic;
  for (size_t k = 0; k < t->nrun && rest > 0; k++) {
    const dtype_predef *p = &dtype_predefs[t->runs[k].type];
    int two = p->rep == DTYPE_REP_PAIR;
    MPI_Count whole = rest / (two ? 2 : 1) < t->runs[k].n ? rest / (two ? 2 : 1) : t->runs[k].n;
    bytes += whole * p->size;
    rest -= whole * (two ? 2 : 1);
    if (rest > 0 && whole < t->runs[k].n && two) {   /* the value of one more pair */
      bytes += dtype_predefs[p->pair_value].size;
      rest = 0;
    }
  }
  return bytes;
}

int dtype_bottom_ok(MPI_Datatype h, int count) {
  const dt *t = obj(h);
  return count == 0 || t->size == 0 || t->tlb != 0;
}

int dtype_elem(MPI_Datatype h, MPI_Count *per_elem) {
  const dt *t = obj(h);
  if (per_elem) *per_elem = t->per_elem;
  return t->elem;
}

void dtype_runs(MPI_Datatype h, void (*f)(void *ud, MPI_Aint disp, MPI_Count n), void *ud) {
  const dt *t = obj(h);
  for (size_t k = 0; k < t->nrun; k++) f(ud, t->runs[k].disp, t->runs[k].n);
}

void dtype_walk(MPI_Datatype h, void (*f)(void *ud, MPI_Aint disp, MPI_Count n, int type), void *ud) {
  const dt *t = obj(h);
  for (size_t k = 0; k < t->nrun; k++) f(ud, t->runs[k].disp, t->runs[k].n, t->runs[k].type);
}

size_t dtype_segments(MPI_Datatype h, void (*f)(void *ud, MPI_Aint disp, MPI_Aint len), void *ud) {
  const dt *t = obj(h);
  for (size_t k = 0; k < t->nseg && f; k++) f(ud, t->segs[k].disp, t->segs[k].len);
  return t->nseg;
}

/* ==== building ============================================================ */

typedef struct {
  run *r;
  size_t nr, cr;
  seg *s;
  size_t ns, cs;
  int oom;
} builder;

static int grow(void **p, size_t *cap, size_t need, size_t size) {
  if (need <= *cap) return 1;
  size_t c = *cap ? *cap : 8;
  while (c < need) c *= 2;
  void *q = realloc(*p, c * size);
  if (!q) return 0;
  *p = q;
  *cap = c;
  return 1;
}

static void add_run(builder *b, MPI_Aint disp, MPI_Count n, int type) {
  if (n == 0 || b->oom) return;
  if (b->nr) {
    run *l = &b->r[b->nr - 1];
    if (l->type == type && l->disp + l->n * dtype_predefs[type].extent == disp) {
      l->n += n;
      return;
    }
  }
  if (!grow((void **)&b->r, &b->cr, b->nr + 1, sizeof *b->r)) {
    b->oom = 1;
    return;
  }
  b->r[b->nr++] = (run){disp, n, type};
}

static void add_seg(builder *b, MPI_Aint disp, MPI_Aint len) {
  if (len == 0 || b->oom) return;
  if (b->ns) {
    seg *l = &b->s[b->ns - 1];
    if (l->disp + l->len == disp) {
      l->len += len;
      return;
    }
  }
  if (!grow((void **)&b->s, &b->cs, b->ns + 1, sizeof *b->s)) {
    b->oom = 1;
    return;
  }
  b->s[b->ns++] = (seg){disp, len};
}

/* reps elements of t, the first at disp, one extent apart. */
static void add_type(builder *b, const dt *t, MPI_Aint disp, MPI_Count reps) {
  MPI_Aint ext = t->ub - t->lb;
  if (t->size == 0 || reps == 0) return;
  if (t->nrun == 1 && t->runs[0].n * dtype_predefs[t->runs[0].type].extent == ext)
    add_run(b, disp + t->runs[0].disp, t->runs[0].n * reps, t->runs[0].type);
  else
    for (MPI_Count j = 0; j < reps && !b->oom; j++)
      for (size_t k = 0; k < t->nrun; k++) add_run(b, disp + j * ext + t->runs[k].disp, t->runs[k].n, t->runs[k].type);
  if (t->contig)
    add_seg(b, disp + t->segs[0].disp, (MPI_Aint)(t->size * reps));
  else
    for (MPI_Count j = 0; j < reps && !b->oom; j++)
      for (size_t k = 0; k < t->nseg; k++) add_seg(b, disp + j * ext + t->segs[k].disp, t->segs[k].len);
}

static MPI_Aint amin(MPI_Aint a, MPI_Aint b) { return a < b ? a : b; }
static MPI_Aint amax(MPI_Aint a, MPI_Aint b) { return a > b ? a : b; }

static int copy_decoding(dt *t, const dtype_decoding *dec) {
  int *ints = dec->ni ? malloc((size_t)dec->ni * sizeof *ints) : NULL;
  MPI_Aint *aints = dec->na ? malloc((size_t)dec->na * sizeof *aints) : NULL;
  MPI_Datatype *types = dec->nd ? malloc((size_t)dec->nd * sizeof *types) : NULL;
  if ((dec->ni && !ints) || (dec->na && !aints) || (dec->nd && !types)) {
    free(ints);
    free(aints);
    free(types);
    return 0;
  }
  if (dec->ni) memcpy(ints, dec->ints, (size_t)dec->ni * sizeof *ints);
  if (dec->na) memcpy(aints, dec->aints, (size_t)dec->na * sizeof *aints);
  if (dec->nd) memcpy(types, dec->types, (size_t)dec->nd * sizeof *types);
  for (int k = 0; k < dec->nd; k++) ref(dec->types[k]);
  t->combiner = dec->combiner;
  t->ni = dec->ni;
  t->na = dec->na;
  t->nd = dec->nd;
  t->ints = ints;
  t->aints = aints;
  t->types = types;
  return 1;
}

static void drop(dt *t) {
  free((void *)t->runs);
  free((void *)t->segs);
  free(t->ints);
  free(t->aints);
  free(t->types);
  free(t->name);
  free(t);
}

/* Derive what follows from the runs, segments and bounds. */
static void finish(dt *t) {
  t->size = 0;
  t->nbasic = 0;
  t->elem = t->nrun ? t->runs[0].type : 0;
  t->per_elem = 0;
  for (size_t k = 0; k < t->nrun; k++) {
    const dtype_predef *p = &dtype_predefs[t->runs[k].type];
    t->size += t->runs[k].n * p->size;
    t->nbasic += t->runs[k].n * (p->rep == DTYPE_REP_PAIR ? 2 : 1);
    if (t->runs[k].type != t->elem) t->elem = 0;
    t->per_elem += t->runs[k].n;
  }
  if (!t->elem) t->per_elem = 0;
  t->contig = t->size == 0 || (t->nseg == 1 && t->size == t->ub - t->lb);
}

int dtype_build(int count, const int *blen, const MPI_Aint *disp, const MPI_Datatype *types,
                MPI_Datatype type, int struct_pad, const dtype_decoding *dec,
                MPI_Datatype *newtype, char *why, size_t len) {
  builder b = {0};
  dt *t = calloc(1, sizeof *t);
  if (!t) goto oom;
  /* MPI 3.1 section 4.1.7: the lower bound is the least displacement of
   * the explicit lb markers (sticky) if the type map has any, else the
   * least of all entries; the upper bound likewise. */
  int any = 0, anydata = 0;
  MPI_Aint slb = 0, sub = 0;
  t->align = 1;
  for (int i = 0; i < count; i++) {
    const dt *c = obj(types ? types[i] : type);
    if (blen[i] == 0) continue;
    MPI_Aint ext = c->ub - c->lb, last = (MPI_Aint)(blen[i] - 1) * ext;
    MPI_Aint lo = disp[i] + amin(0, last), hi = disp[i] + amax(0, last);
    if (!any) {
      t->lb = lo + c->lb;
      t->ub = hi + c->ub;
    } else {
      t->lb = amin(t->lb, lo + c->lb);
      t->ub = amax(t->ub, hi + c->ub);
    }
    any = 1;
    if (c->slb) {
      slb = t->slb ? amin(slb, lo + c->lb) : lo + c->lb;
      t->slb = 1;
    }
    if (c->sub) {
      sub = t->sub ? amax(sub, hi + c->ub) : hi + c->ub;
      t->sub = 1;
    }
    if (c->size > 0) {
      if (!anydata) {
        t->tlb = lo + c->tlb;
        t->tub = hi + c->tub;
      } else {
        t->tlb = amin(t->tlb, lo + c->tlb);
        t->tub = amax(t->tub, hi + c->tub);
      }
      anydata = 1;
    }
    if (c->align > t->align) t->align = c->align;
    add_type(&b, c, disp[i], blen[i]);
  }
  if (b.oom) goto oom;
  if (t->slb) t->lb = slb;
  if (t->sub) t->ub = sub;
  /* The struct's epsilon: with no explicit upper bound, the extent rounded
   * up to the strictest alignment. */
  if (struct_pad && !t->sub && any) {
    MPI_Aint ext = t->ub - t->lb, r = ext % t->align;
    if (r) t->ub += t->align - (r < 0 ? r + t->align : r);
  }
  t->runs = b.r;
  t->nrun = b.nr;
  t->segs = b.s;
  t->nseg = b.ns;
  b.r = NULL;
  b.s = NULL;
  finish(t);
  if (!copy_decoding(t, dec)) goto oom;
  *newtype = enter(t);
  if (*newtype == MPI_DATATYPE_NULL) {
    for (int k = 0; k < t->nd; k++) unref(t->types[k]);
    t->nd = 0;
    goto oom;
  }
  return MPI_SUCCESS;
oom:
  free(b.r);
  free(b.s);
  if (t) drop(t);
  if (why && len) snprintf(why, len, "out of memory");
  return MPI_ERR_NO_MEM;
}

/* A copy of c's maps into a new object (decoding and name left empty). */
static dt *clone(const dt *c) {
  dt *t = calloc(1, sizeof *t);
  if (!t) return NULL;
  *t = *c;
  t->predef = 0;
  t->refs = 0;
  t->ints = NULL;
  t->aints = NULL;
  t->types = NULL;
  t->name = NULL;
  t->ni = t->na = t->nd = 0;
  run *r = c->nrun ? malloc(c->nrun * sizeof *r) : NULL;
  seg *s = c->nseg ? malloc(c->nseg * sizeof *s) : NULL;
  t->runs = r;
  t->segs = s;
  if ((c->nrun && !r) || (c->nseg && !s)) {
    drop(t);
    return NULL;
  }
  if (c->nrun) memcpy(r, c->runs, c->nrun * sizeof *r);
  if (c->nseg) memcpy(s, c->segs, c->nseg * sizeof *s);
  return t;
}

static int entered(dt *t, MPI_Datatype *newtype, char *why, size_t len) {
  *newtype = enter(t);
  if (*newtype != MPI_DATATYPE_NULL) return MPI_SUCCESS;
  for (int k = 0; k < t->nd; k++) unref(t->types[k]);
  t->nd = 0;
  drop(t);
  if (why && len) snprintf(why, len, "out of memory");
  return MPI_ERR_NO_MEM;
}

int dtype_resized(MPI_Datatype h, MPI_Aint lb, MPI_Aint extent, MPI_Datatype *newtype,
                  char *why, size_t len) {
  const dt *c = obj(h);
  dt *t = clone(c);
  MPI_Aint aints[2] = {lb, extent};
  dtype_decoding dec = {MPI_COMBINER_RESIZED, 0, 2, 1, NULL, aints, &h};
  if (!t || !copy_decoding(t, &dec)) {
    if (t) drop(t);
    if (why && len) snprintf(why, len, "out of memory");
    return MPI_ERR_NO_MEM;
  }
  t->committed = 0;
  t->lb = lb;
  t->ub = lb + extent;
  t->slb = t->sub = 1;
  finish(t);
  return entered(t, newtype, why, len);
}

int dtype_dup(MPI_Datatype h, MPI_Datatype *newtype, char *why, size_t len) {
  const dt *c = obj(h);
  dt *t = clone(c);
  dtype_decoding dec = {MPI_COMBINER_DUP, 0, 0, 1, NULL, NULL, &h};
  if (!t || !copy_decoding(t, &dec)) {
    if (t) drop(t);
    if (why && len) snprintf(why, len, "out of memory");
    return MPI_ERR_NO_MEM;
  }
  t->committed = c->committed;
  return entered(t, newtype, why, len);
}

int dtype_commit(MPI_Datatype h) {
  dt *t = obj(h);
  if (!t->predef) t->committed = 1;
  return MPI_SUCCESS;
}

int dtype_free(MPI_Datatype h) {
  dt *t = obj(h);
  if (!t || t->predef) return MPI_ERR_TYPE;
  unref(h);
  return MPI_SUCCESS;
}

/* ==== names and decoding ================================================== */

int dtype_redecode(MPI_Datatype h, const dtype_decoding *dec) {
  dt *t = obj(h);
  for (int k = 0; k < t->nd; k++) unref(t->types[k]);
  free(t->ints);
  free(t->aints);
  free(t->types);
  t->ints = NULL;
  t->aints = NULL;
  t->types = NULL;
  t->ni = t->na = t->nd = 0;
  return copy_decoding(t, dec) ? MPI_SUCCESS : MPI_ERR_NO_MEM;
}

const char *dtype_name(MPI_Datatype h) {
  const dt *t = obj(h);
  const table *tb = t->predef ? tab(0) : NULL;
  if (tb && tb->pname[t->predef]) return tb->pname[t->predef];
  if (t->name) return t->name;
  return t->predef ? dtype_predefs[t->predef].name : "";
}

int dtype_set_name(MPI_Datatype h, const char *name) {
  dt *t = obj(h);
  table *tb = t->predef ? tab(1) : NULL;
  if (t->predef && !tb) return MPI_ERR_NO_MEM;
  size_t n = strlen(name);
  if (n >= MPI_MAX_OBJECT_NAME) n = MPI_MAX_OBJECT_NAME - 1;
  char *s = malloc(n + 1);
  if (!s) return MPI_ERR_NO_MEM;
  memcpy(s, name, n);
  s[n] = '\0';
  char **slot = t->predef ? &tb->pname[t->predef] : &t->name;
  free(*slot);
  *slot = s;
  return MPI_SUCCESS;
}

void dtype_envelope(MPI_Datatype h, int *ni, int *na, int *nd, int *combiner) {
  const dt *t = obj(h);
  *ni = t->ni;
  *na = t->na;
  *nd = t->nd;
  *combiner = t->combiner;
}

int dtype_contents(MPI_Datatype h, int ni, int na, int nd, int *ints, MPI_Aint *aints,
                   MPI_Datatype *types) {
  const dt *t = obj(h);
  if (t->predef || ni < t->ni || na < t->na || nd < t->nd) return MPI_ERR_ARG;
  if (t->ni) memcpy(ints, t->ints, (size_t)t->ni * sizeof *ints);
  if (t->na) memcpy(aints, t->aints, (size_t)t->na * sizeof *aints);
  for (int k = 0; k < t->nd; k++) {
    types[k] = t->types[k];
    ref(t->types[k]);
  }
  return MPI_SUCCESS;
}
