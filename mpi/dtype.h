/* dtype.h -- datatypes inside the MPI layer: the predefined types, each rank's created types, and
 * moving count elements of any datatype into and out of a contiguous run of bytes.
 *
 * Not for programs (mpi.h is theirs).  Point-to-point and the collectives
 * move data with these; the MPI_Type_*, MPI_Pack* and MPI_Get_address
 * functions (dtype_api.c) are built on them.
 *
 * THE PACKED FORM.  count elements of a datatype, packed, are the bytes of
 * its type map in order, element after element, with no gaps and no header:
 * count * size bytes.  A message of count elements is a message of exactly
 * that many bytes, and MPI_Pack writes the same bytes.  The pair types
 * (MPI_DOUBLE_INT, ...) pack as their value then their int (12 bytes for
 * MPI_DOUBLE_INT, whose extent is 16).
 *
 * REPRESENTATION.  A type is flattened when it is built: its type map as
 * runs of one predefined type (for reductions and MPI_Get_elements) and as
 * runs of bytes (for packing), adjacent runs merged.  A type of n separate
 * pieces costs about 40 bytes per piece; packing it costs one memcpy per
 * piece, one memcpy in all for contiguous types.
 *
 * HANDLES.  A datatype handle is valid in communication when it is
 * predefined, or created by this rank, committed and not freed.  A created
 * type lives while any handle, any type built from it that can still be
 * decoded (MPI_Type_get_contents), or any holder (dtype_hold) refers to
 * it: point-to-point holds the type of a pending receive, so that
 * MPI_Type_free may come before the receive completes, as MPI allows.
 *
 * Everything here works on the calling rank's types (mp_self); the
 * predefined ones are constants shared by every rank. */
#ifndef TSMPI_DTYPE_H
#define TSMPI_DTYPE_H

#include <stddef.h>

#include "mpi/mpi.h"

/* ==== what point-to-point and the collectives call ======================== */

/* MPI_SUCCESS if dt can be used in communication (predefined and not
 * MPI_DATATYPE_NULL, or created by this rank, committed and not freed);
 * else MPI_ERR_TYPE, and why (len bytes) says which: "MPI_DATATYPE_NULL",
 * "not committed", "not a datatype of this rank (freed?)", "not a
 * datatype", "MPI_INTEGER16 is not supported". */
int dtype_check(MPI_Datatype dt, char *why, size_t len);

/* Bytes of data in one element of dt (MPI_Type_size): dt must have passed
 * dtype_check (or be a created type not yet committed). */
size_t dtype_size(MPI_Datatype dt);

/* The extent and the true lower bound and extent of dt (checked). */
MPI_Aint dtype_extent(MPI_Datatype dt);
MPI_Aint dtype_true_lb(MPI_Datatype dt);
MPI_Aint dtype_true_extent(MPI_Datatype dt);

/* 1 if count elements of dt lie as one run of count * size bytes. */
int dtype_contiguous(MPI_Datatype dt, int count);

/* Where count elements of dt at buf lie as one run of count * size bytes
 * (buf + the type's true lower bound), or NULL if they do not (gaps, or an
 * extent other than the size with count > 1).  count = 0 or a size of 0:
 * buf itself. */
const void *dtype_contig(const void *buf, int count, MPI_Datatype dt);

/* count elements of dt at buf into out: count * size bytes, in type-map
 * order.  out must not overlap the elements. */
void dtype_pack(const void *buf, int count, MPI_Datatype dt, void *out);

/* The first `bytes` bytes of a packed run (at most count * size: a short
 * message fills the first elements, and the last one partly) into count
 * elements of dt at buf, in type-map order. */
void dtype_unpack(const void *in, size_t bytes, void *buf, int count, MPI_Datatype dt);

/* Keep a checked type alive until dtype_release, whatever MPI_Type_free
 * does to its handle meanwhile (predefined types: nothing happens). */
void dtype_hold(MPI_Datatype dt);
void dtype_release(MPI_Datatype dt);

/* Basic elements in the first `bytes` bytes of packed elements of dt
 * (MPI_Get_elements: a pair type counts 2); MPI_UNDEFINED if `bytes` ends
 * inside a basic element. */
MPI_Count dtype_elements(MPI_Datatype dt, MPI_Count bytes);

/* The bytes that hold the first n basic elements of packed elements of dt
 * (the inverse of dtype_elements, for MPI_Status_set_elements); -1 if
 * dt has no basic elements and n > 0. */
MPI_Count dtype_elements_bytes(MPI_Datatype dt, MPI_Count n);

/* 1 if a NULL (MPI_BOTTOM) buffer can carry count elements of dt: count is
 * 0, the type has no data, or its data lie at non-zero addresses (a type
 * built from absolute addresses, MPI_Get_address). */
int dtype_bottom_ok(MPI_Datatype dt, int count);

/* ==== for the operations (op.c) =========================================== */

/* The classes of predefined types MPI 3.1 section 5.9.2 names, which say
 * the operations that apply. */
enum {
  DTYPE_CLASS_NONE,     /* no operation applies: MPI_WCHAR, MPI_PACKED, ... */
  DTYPE_CLASS_CINT,     /* C integer (MPI_CHAR too, as MPICH and Open MPI) */
  DTYPE_CLASS_FINT,     /* Fortran integer */
  DTYPE_CLASS_FLOAT,    /* floating point */
  DTYPE_CLASS_LOGICAL,  /* MPI_C_BOOL, MPI_CXX_BOOL, MPI_LOGICAL */
  DTYPE_CLASS_COMPLEX,  /* complex */
  DTYPE_CLASS_BYTE,     /* MPI_BYTE */
  DTYPE_CLASS_MULTI,    /* MPI_AINT, MPI_OFFSET, MPI_COUNT */
  DTYPE_CLASS_PAIR      /* the MINLOC/MAXLOC pairs */
};

/* How a value of a predefined type is stored, for the operations' kernels. */
enum {
  DTYPE_REP_NONE,
  DTYPE_REP_INT,     /* two's complement integer of `size` bytes */
  DTYPE_REP_UINT,    /* unsigned integer of `size` bytes */
  DTYPE_REP_FLOAT,   /* float, double or long double, by size */
  DTYPE_REP_COMPLEX, /* float/double/long double _Complex, by size */
  DTYPE_REP_BOOL,    /* a truth value of `size` bytes (0 false, else true) */
  DTYPE_REP_PAIR     /* value then index: see the pair fields */
};

typedef struct {
  const char *name;     /* "MPI_INT" */
  int size;             /* bytes of data (packed) */
  int extent;           /* its extent (size but for some pairs) */
  int align;            /* its C alignment */
  int cls;              /* DTYPE_CLASS_* */
  int rep;              /* DTYPE_REP_* */
  int pair_value;       /* pairs: the value's predefined index */
  int pair_index;       /* pairs: the index's predefined index */
  int pair_off;         /* pairs: the index's offset in the laid-out pair */
} dtype_predef;

enum { DTYPE_PREDEF_N = 0x3f };   /* predefined indices are 1 .. DTYPE_PREDEF_N - 1 */

/* The predefined types by index (dtype.c's table; unused indices have no
 * name), and the one of index i (1 .. DTYPE_PREDEF_N - 1), or NULL. */
extern const dtype_predef dtype_predefs[DTYPE_PREDEF_N];
static inline const dtype_predef *dtype_predef_get(int i) {
  return i > 0 && i < DTYPE_PREDEF_N && dtype_predefs[i].name ? &dtype_predefs[i] : NULL;
}

/* The index of the one predefined type all of dt's basic entries are (a
 * pair type counts as one), or 0 if they are of several types or dt has
 * none; dt checked.  *per_elem: how many of them one element of dt holds. */
int dtype_elem(MPI_Datatype dt, MPI_Count *per_elem);

/* Calls f(ud, disp, n) for each run of n basic entries of dt's element type
 * (dtype_elem) at byte displacement disp from an element's start, in
 * type-map order; entries of a run are one element-type extent apart. */
void dtype_runs(MPI_Datatype dt, void (*f)(void *ud, MPI_Aint disp, MPI_Count n), void *ud);

/* Calls f(ud, disp, n, type) for every run of dt's type map, whatever its
 * types: n basic entries of the predefined type of index `type` (a pair
 * counting as one), the first at byte displacement disp from an element's
 * start, one predefined extent apart; in type-map order. */
void dtype_walk(MPI_Datatype dt, void (*f)(void *ud, MPI_Aint disp, MPI_Count n, int type), void *ud);

/* Calls f(ud, disp, len) for every run of bytes of dt's data (what packing
 * copies, adjacent runs merged), in type-map order: len bytes at byte
 * displacement disp from an element's start.  Returns how many. */
size_t dtype_segments(MPI_Datatype dt, void (*f)(void *ud, MPI_Aint disp, MPI_Aint len), void *ud);

/* ==== the rank's table (for the MPI functions in dtype_api.c) ============= */

/* A created type's handle from its parts: count blocks, block i being
 * blen[i] elements of types[i] (all of `type` when types is NULL) at byte
 * displacement disp[i]; struct_pad: round the extent up to the strictest
 * alignment (MPI_Type_create_struct's epsilon).  The type's decoding
 * (combiner, integers, addresses, types) is recorded for
 * MPI_Type_get_contents.  MPI_SUCCESS, or an error class with why filled. */
typedef struct {
  int combiner;
  int ni, na, nd;
  const int *ints;
  const MPI_Aint *aints;
  const MPI_Datatype *types;
} dtype_decoding;
int dtype_build(int count, const int *blen, const MPI_Aint *disp, const MPI_Datatype *types,
                MPI_Datatype type, int struct_pad, const dtype_decoding *dec,
                MPI_Datatype *newtype, char *why, size_t len);

/* A copy of dt with lower bound lb and extent extent (MPI_Type_create_resized). */
int dtype_resized(MPI_Datatype dt, MPI_Aint lb, MPI_Aint extent, MPI_Datatype *newtype,
                  char *why, size_t len);

/* Replace a created type's decoding (MPI_Type_create_subarray's, built as
 * blocks then resized). */
int dtype_redecode(MPI_Datatype dt, const dtype_decoding *dec);

/* A duplicate of dt (MPI_Type_dup): same type map, committed if dt is. */
int dtype_dup(MPI_Datatype dt, MPI_Datatype *newtype, char *why, size_t len);

/* Is h a datatype handle at all (predefined or this rank's), committed or
 * not?  MPI_SUCCESS, or MPI_ERR_TYPE with why. */
int dtype_valid(MPI_Datatype h, char *why, size_t len);

int dtype_commit(MPI_Datatype dt);   /* dt valid */
int dtype_free(MPI_Datatype dt);     /* dt valid and created: MPI_SUCCESS; else MPI_ERR_TYPE */

/* lb and ub as MPI_Type_get_extent says them (ub - lb: the extent). */
void dtype_bounds(MPI_Datatype dt, MPI_Aint *lb, MPI_Aint *ub, MPI_Aint *true_lb,
                  MPI_Aint *true_ub);

/* The type's name (MPI_Type_get_name): the one this rank set, or a
 * predefined type's MPI name, or "".  A predefined type's name set is the
 * rank's own. */
const char *dtype_name(MPI_Datatype dt);
int dtype_set_name(MPI_Datatype dt, const char *name);

/* Its decoding: the combiner, the numbers of integers, addresses and types
 * (MPI_Type_get_envelope), and the arrays (get_contents: the types returned
 * as new handles to the same types, which the caller frees). */
void dtype_envelope(MPI_Datatype dt, int *ni, int *na, int *nd, int *combiner);
int dtype_contents(MPI_Datatype dt, int ni, int na, int nd, int *ints, MPI_Aint *aints,
                   MPI_Datatype *types);

/* The packed buffer's checks of MPI_Pack, MPI_Unpack and their external
 * forms, raised on comm for call fn: position not NULL (pos: its value),
 * n bytes at pos within the buffer's size (packing: they fit; unpacking:
 * they are there), buf (the packed side's) not NULL when n > 0. */
int dtype_room_ok(MPI_Comm comm, const char *fn, int packing, const void *position, long pos, long size,
                  MPI_Count n, const void *buf);

#endif
