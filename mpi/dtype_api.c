/* dtype_api.c -- the MPI functions of datatypes: constructors, commit and free, queries,
 * decoding, MPI_Pack, MPI_Unpack, MPI_Pack_size, MPI_Get_address, MPI_Get_elements (mpi.h;
 * built on dtype.h).
 *
 * Arguments are checked as MPI 3.1 chapter 4 says; an error goes to
 * MPI_COMM_WORLD's error handler (MPI 3.1 section 8.3: calls with no
 * communicator), or to the communicator's for MPI_Pack and MPI_Unpack. */
#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/dtype.h"
#include "mpi/mpi.h"
#include "mpi/core.h"

/* ==== argument checks ===================================================== */

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static int fail(MPI_Comm comm, int cls, const char *fn, const char *fmt, ...) {
  char msg[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return err_comm_raise(comm, cls, fn, "%s", msg);
}

/* A datatype argument that need not be committed (constructors, queries). */
static int type_ok(const char *fn, const char *what, MPI_Datatype dt) {
  char why[96];
  if (dtype_valid(dt, why, sizeof why) == MPI_SUCCESS) return MPI_SUCCESS;
  return fail(MPI_COMM_WORLD, MPI_ERR_TYPE, fn, "invalid %s: %s", what, why);
}

static int count_ok(const char *fn, const char *what, int count) {
  if (count >= 0) return MPI_SUCCESS;
  return fail(MPI_COMM_WORLD, MPI_ERR_COUNT, fn, "negative %s %d", what, count);
}

static int ptr_ok(const char *fn, const char *what, const void *p) {
  if (p) return MPI_SUCCESS;
  return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "%s is NULL", what);
}

/* Each blocklength of n >= 0 (or the one blocklength). */
static int blens_ok(const char *fn, int n, const int *blen) {
  for (int i = 0; i < n; i++)
    if (blen[i] < 0) return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "negative blocklength %d (block %d)", blen[i], i);
  return MPI_SUCCESS;
}

/* The common end of every constructor: build, and say why it failed. */
static int build(const char *fn, int count, const int *blen, const MPI_Aint *disp,
                 const MPI_Datatype *types, MPI_Datatype type, int struct_pad,
                 const dtype_decoding *dec, MPI_Datatype *newtype) {
  char why[96];
  int rc = dtype_build(count, blen, disp, types, type, struct_pad, dec, newtype, why, sizeof why);
  if (rc == MPI_SUCCESS) return rc;
  return fail(MPI_COMM_WORLD, rc, fn, "%s", why);
}

/* Arrays for the blocks of a constructor (freed by the caller). */
static int arrays(const char *fn, int count, int **blen, MPI_Aint **disp, int **ints) {
  size_t n = count > 0 ? (size_t)count : 1;
  *blen = malloc(n * sizeof **blen);
  *disp = malloc(n * sizeof **disp);
  *ints = malloc((2 * n + 3) * sizeof **ints);
  if (*blen && *disp && *ints) return MPI_SUCCESS;
  free(*blen);
  free(*disp);
  free(*ints);
  return fail(MPI_COMM_WORLD, MPI_ERR_NO_MEM, fn, "out of memory for %d blocks", count);
}

/* ==== constructors ======================================================== */

int PMPI_Type_contiguous(int count, MPI_Datatype oldtype, MPI_Datatype *newtype) {
  static const char fn[] = "MPI_Type_contiguous";
  int rc;
  if ((rc = count_ok(fn, "count", count)) || (rc = type_ok(fn, "oldtype", oldtype)) ||
      (rc = ptr_ok(fn, "newtype", newtype)))
    return rc;
  MPI_Aint zero = 0;
  dtype_decoding dec = {MPI_COMBINER_CONTIGUOUS, 1, 0, 1, &count, NULL, &oldtype};
  return build(fn, 1, &count, &zero, NULL, oldtype, 0, &dec, newtype);
}

/* count blocks of blocklength, stride bytes apart. */
static int hvector(const char *fn, int count, int blocklength, MPI_Aint stride, MPI_Datatype oldtype,
                   const dtype_decoding *dec, MPI_Datatype *newtype) {
  int rc, *blen, *ints;
  MPI_Aint *disp;
  if ((rc = count_ok(fn, "count", count)) || (rc = blens_ok(fn, 1, &blocklength)) ||
      (rc = type_ok(fn, "oldtype", oldtype)) || (rc = ptr_ok(fn, "newtype", newtype)) ||
      (rc = arrays(fn, count, &blen, &disp, &ints)))
    return rc;
  for (int i = 0; i < count; i++) {
    blen[i] = blocklength;
    disp[i] = (MPI_Aint)i * stride;
  }
  rc = build(fn, count, blen, disp, NULL, oldtype, 0, dec, newtype);
  free(blen);
  free(disp);
  free(ints);
  return rc;
}

int PMPI_Type_vector(int count, int blocklength, int stride, MPI_Datatype oldtype, MPI_Datatype *newtype) {
  static const char fn[] = "MPI_Type_vector";
  int rc = type_ok(fn, "oldtype", oldtype);
  if (rc) return rc;
  int ints[3] = {count, blocklength, stride};
  dtype_decoding dec = {MPI_COMBINER_VECTOR, 3, 0, 1, ints, NULL, &oldtype};
  return hvector(fn, count, blocklength, (MPI_Aint)stride * dtype_extent(oldtype), oldtype, &dec,
                 newtype);
}

int PMPI_Type_create_hvector(int count, int blocklength, MPI_Aint stride, MPI_Datatype oldtype,
                            MPI_Datatype *newtype) {
  int ints[2] = {count, blocklength};
  dtype_decoding dec = {MPI_COMBINER_HVECTOR, 2, 1, 1, ints, &stride, &oldtype};
  return hvector("MPI_Type_create_hvector", count, blocklength, stride, oldtype, &dec, newtype);
}

int PMPI_Type_hvector(int count, int blocklength, MPI_Aint stride, MPI_Datatype oldtype,
                     MPI_Datatype *newtype) {
  int ints[2] = {count, blocklength};
  dtype_decoding dec = {MPI_COMBINER_HVECTOR, 2, 1, 1, ints, &stride, &oldtype};
  return hvector("MPI_Type_hvector", count, blocklength, stride, oldtype, &dec, newtype);
}

/* Blocks of blocklengths[i] (or blocklength when blocklengths is NULL) at
 * displacements in elements (edisp) or bytes (bdisp). */
static int indexed(const char *fn, int combiner, int count, const int *blocklengths, int blocklength,
                   const int *edisp, const MPI_Aint *bdisp, MPI_Datatype oldtype, MPI_Datatype *newtype) {
  int rc, *blen, *ints;
  MPI_Aint *disp;
  int per_block = combiner == MPI_COMBINER_INDEXED || combiner == MPI_COMBINER_HINDEXED;
  if ((rc = count_ok(fn, "count", count)) || (rc = type_ok(fn, "oldtype", oldtype)) ||
      (rc = ptr_ok(fn, "newtype", newtype)))
    return rc;
  if (count > 0 && ((per_block && !blocklengths) || (!edisp && !bdisp)))
    return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "an array argument is NULL");
  if ((rc = blocklengths ? blens_ok(fn, count, blocklengths) : blens_ok(fn, 1, &blocklength)) ||
      (rc = arrays(fn, count, &blen, &disp, &ints)))
    return rc;
  MPI_Aint ext = dtype_extent(oldtype);
  int ni = 0;
  ints[ni++] = count;
  if (!blocklengths) ints[ni++] = blocklength;
  for (int i = 0; i < count; i++) {
    blen[i] = blocklengths ? blocklengths[i] : blocklength;
    disp[i] = edisp ? (MPI_Aint)edisp[i] * ext : bdisp[i];
    if (blocklengths) ints[1 + i] = blocklengths[i];
  }
  if (blocklengths) ni += count;
  if (edisp)
    for (int i = 0; i < count; i++) ints[ni++] = edisp[i];
  dtype_decoding dec = {combiner, ni, edisp ? 0 : count, 1, ints, edisp ? NULL : bdisp, &oldtype};
  rc = build(fn, count, blen, disp, NULL, oldtype, 0, &dec, newtype);
  free(blen);
  free(disp);
  free(ints);
  return rc;
}

int PMPI_Type_indexed(int count, const int array_of_blocklengths[], const int array_of_displacements[],
                     MPI_Datatype oldtype, MPI_Datatype *newtype) {
  return indexed("MPI_Type_indexed", MPI_COMBINER_INDEXED, count, array_of_blocklengths, 0,
                 array_of_displacements, NULL, oldtype, newtype);
}

int PMPI_Type_create_hindexed(int count, const int array_of_blocklengths[],
                             const MPI_Aint array_of_displacements[], MPI_Datatype oldtype,
                             MPI_Datatype *newtype) {
  return indexed("MPI_Type_create_hindexed", MPI_COMBINER_HINDEXED, count, array_of_blocklengths, 0, NULL,
                 array_of_displacements, oldtype, newtype);
}

int PMPI_Type_hindexed(int count, int array_of_blocklengths[], MPI_Aint array_of_displacements[],
                      MPI_Datatype oldtype, MPI_Datatype *newtype) {
  return indexed("MPI_Type_hindexed", MPI_COMBINER_HINDEXED, count, array_of_blocklengths, 0, NULL,
                 array_of_displacements, oldtype, newtype);
}

int PMPI_Type_create_indexed_block(int count, int blocklength, const int array_of_displacements[],
                                  MPI_Datatype oldtype, MPI_Datatype *newtype) {
  return indexed("MPI_Type_create_indexed_block", MPI_COMBINER_INDEXED_BLOCK, count, NULL, blocklength,
                 array_of_displacements, NULL, oldtype, newtype);
}

int PMPI_Type_create_hindexed_block(int count, int blocklength, const MPI_Aint array_of_displacements[],
                                   MPI_Datatype oldtype, MPI_Datatype *newtype) {
  return indexed("MPI_Type_create_hindexed_block", MPI_COMBINER_HINDEXED_BLOCK, count, NULL, blocklength,
                 NULL, array_of_displacements, oldtype, newtype);
}

static int create_struct(const char *fn, int count, const int *blens, const MPI_Aint *disps,
                         const MPI_Datatype *types, MPI_Datatype *newtype) {
  int rc, *blen, *ints;
  MPI_Aint *disp;
  if ((rc = count_ok(fn, "count", count)) || (rc = ptr_ok(fn, "newtype", newtype))) return rc;
  if (count > 0 && (!blens || !disps || !types))
    return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "an array argument is NULL");
  for (int i = 0; i < count; i++) {
    char what[48];
    snprintf(what, sizeof what, "datatype of block %d", i);
    if ((rc = type_ok(fn, what, types[i]))) return rc;
  }
  if ((rc = blens_ok(fn, count, blens)) || (rc = arrays(fn, count, &blen, &disp, &ints))) return rc;
  ints[0] = count;
  for (int i = 0; i < count; i++) ints[1 + i] = blens[i];
  dtype_decoding dec = {MPI_COMBINER_STRUCT, count + 1, count, count, ints, disps, types};
  rc = build(fn, count, blens, disps, types, MPI_DATATYPE_NULL, 1, &dec, newtype);
  free(blen);
  free(disp);
  free(ints);
  return rc;
}

int PMPI_Type_create_struct(int count, const int array_of_blocklengths[],
                           const MPI_Aint array_of_displacements[], const MPI_Datatype array_of_types[],
                           MPI_Datatype *newtype) {
  return create_struct("MPI_Type_create_struct", count, array_of_blocklengths, array_of_displacements,
                       array_of_types, newtype);
}

int PMPI_Type_struct(int count, int array_of_blocklengths[], MPI_Aint array_of_displacements[],
                    MPI_Datatype array_of_types[], MPI_Datatype *newtype) {
  return create_struct("MPI_Type_struct", count, array_of_blocklengths, array_of_displacements,
                       array_of_types, newtype);
}

int PMPI_Type_create_resized(MPI_Datatype oldtype, MPI_Aint lb, MPI_Aint extent, MPI_Datatype *newtype) {
  static const char fn[] = "MPI_Type_create_resized";
  int rc;
  char why[96];
  if ((rc = type_ok(fn, "oldtype", oldtype)) || (rc = ptr_ok(fn, "newtype", newtype))) return rc;
  rc = dtype_resized(oldtype, lb, extent, newtype, why, sizeof why);
  return rc ? fail(MPI_COMM_WORLD, rc, fn, "%s", why) : rc;
}

int PMPI_Type_dup(MPI_Datatype oldtype, MPI_Datatype *newtype) {
  static const char fn[] = "MPI_Type_dup";
  int rc;
  char why[96];
  if ((rc = type_ok(fn, "oldtype", oldtype)) || (rc = ptr_ok(fn, "newtype", newtype))) return rc;
  rc = dtype_dup(oldtype, newtype, why, sizeof why);
  if (rc) return fail(MPI_COMM_WORLD, rc, fn, "%s", why);
  if ((rc = attr_type_copy(oldtype, *newtype, fn))) {
    dtype_free(*newtype);
    *newtype = MPI_DATATYPE_NULL;
  }
  return rc;
}

/* ==== arrays: subarray and darray ======================================== */

/* A part of an ndims-dimensional array of oldtype as a type: in dimension
 * d (dimension 0 varies slowest), the n[d] increasing indices idx[d] of
 * sz[d]; the elements in row-major order, each at its index's offset in
 * the whole array, which is the type's extent (lower bound 0; MPI 3.1
 * sections 4.1.3 and 4.1.4).  Rows of the innermost dimension are cut
 * into blocks of consecutive indices.  Decoded as dec. */
static int array_part(const char *fn, int ndims, const int *sz, int *const *idx, const int *n,
                      MPI_Datatype oldtype, const dtype_decoding *dec, MPI_Datatype *newtype) {
  int in = ndims - 1, runs = 0;
  MPI_Count rows = 1, whole = 1, blocks;
  for (int d = 0; d < ndims; d++) whole *= sz[d];
  for (int d = 0; d < in; d++) rows *= n[d];
  for (int k = 0; k < n[in]; k++) runs += k == 0 || idx[in][k] != idx[in][k - 1] + 1;
  blocks = rows * runs;
  if (blocks > INT_MAX)
    return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "too many blocks (%lld)", (long long)blocks);
  MPI_Aint ext = dtype_extent(oldtype);
  int *blen = malloc((size_t)(blocks ? blocks : 1) * sizeof *blen), *at = calloc((size_t)ndims, sizeof *at);
  MPI_Aint *disp = malloc((size_t)(blocks ? blocks : 1) * sizeof *disp);
  if (!blen || !disp || !at) {
    free(blen), free(disp), free(at);
    return fail(MPI_COMM_WORLD, MPI_ERR_NO_MEM, fn, "out of memory for %lld blocks", (long long)blocks);
  }
  MPI_Count b = 0;
  for (MPI_Count r = 0; r < rows && runs; r++) {
    MPI_Aint row = 0;   /* the offset of the row's index 0, in elements */
    for (int d = 0; d < in; d++) row = (row + idx[d][at[d]]) * sz[d + 1];
    for (int k = 0; k < n[in]; k++) {
      if (k == 0 || idx[in][k] != idx[in][k - 1] + 1) {
        disp[b] = (row + idx[in][k]) * ext;
        blen[b++] = 0;
      }
      blen[b - 1]++;
    }
    for (int d = in - 1; d >= 0; d--) {
      if (++at[d] < n[d]) break;
      at[d] = 0;
    }
  }
  /* The blocks, then their bounds: 0 and the whole array. */
  MPI_Datatype part;
  dtype_decoding none = {MPI_COMBINER_HINDEXED, 0, 0, 0, NULL, NULL, NULL};
  int rc = build(fn, (int)blocks, blen, disp, NULL, oldtype, 0, &none, &part);
  if (rc == MPI_SUCCESS) {
    char why[96];
    rc = dtype_resized(part, 0, (MPI_Aint)whole * ext, newtype, why, sizeof why);
    dtype_free(part);
    if (rc == MPI_SUCCESS) rc = dtype_redecode(*newtype, dec);
    if (rc) rc = fail(MPI_COMM_WORLD, rc, fn, "out of memory");
  }
  free(blen), free(disp), free(at);
  return rc;
}

/* The checks subarray and darray share. */
static int array_args(const char *fn, int ndims, const int **arrays, int narrays, int order, MPI_Datatype oldtype,
                      MPI_Datatype *newtype) {
  int rc;
  if ((rc = type_ok(fn, "oldtype", oldtype)) || (rc = ptr_ok(fn, "newtype", newtype))) return rc;
  if (ndims < 1) return fail(MPI_COMM_WORLD, MPI_ERR_DIMS, fn, "ndims %d < 1", ndims);
  for (int k = 0; k < narrays; k++)
    if (!arrays[k]) return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "an array argument is NULL");
  if (order != MPI_ORDER_C && order != MPI_ORDER_FORTRAN)
    return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "order %d is neither MPI_ORDER_C nor MPI_ORDER_FORTRAN", order);
  return MPI_SUCCESS;
}

/* Room for a part: idx, sz and n of ndims each, then the index lists,
 * total ints from n + ndims on; one block, freed with free(*idx). */
static int array_room(const char *fn, int ndims, MPI_Count total, int ***idx, int **sz, int **n) {
  size_t ptrs = (size_t)ndims * sizeof(int *), ints = 2 * (size_t)ndims + (size_t)total;
  char *m = malloc(ptrs + ints * sizeof(int));
  if (!m) return fail(MPI_COMM_WORLD, MPI_ERR_NO_MEM, fn, "out of memory");
  *idx = (int **)(void *)m;
  *sz = (int *)(void *)(m + ptrs);
  *n = *sz + ndims;
  return MPI_SUCCESS;
}

/* MPI 3.1 section 4.1.3: the subarray of an ndims-dimensional array in C
 * or Fortran order. */
int PMPI_Type_create_subarray(int ndims, const int array_of_sizes[], const int array_of_subsizes[],
                             const int array_of_starts[], int order, MPI_Datatype oldtype,
                             MPI_Datatype *newtype) {
  static const char fn[] = "MPI_Type_create_subarray";
  const int *arrays[3] = {array_of_sizes, array_of_subsizes, array_of_starts};
  int rc = array_args(fn, ndims, arrays, 3, order, oldtype, newtype);
  if (rc) return rc;
  MPI_Count total = 0;
  for (int d = 0; d < ndims; d++) {
    int n = array_of_sizes[d], s = array_of_subsizes[d], b = array_of_starts[d];
    if (n < 1 || s < 1 || s > n || b < 0 || b > n - s)
      return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn,
                  "dimension %d: size %d, subsize %d, start %d (need 1 <= subsize <= size, 0 <= start <= size - subsize)",
                  d, n, s, b);
    total += s;
  }
  int *sz = NULL, *n = NULL, **idx = NULL, *ints = malloc((size_t)(3 * ndims + 2) * sizeof *ints);
  if (!ints) return fail(MPI_COMM_WORLD, MPI_ERR_NO_MEM, fn, "out of memory");
  if ((rc = array_room(fn, ndims, total, &idx, &sz, &n))) {
    free(ints);
    return rc;
  }
  /* Dimension 0 varies slowest: C order as given, Fortran order reversed. */
  int *list = n + ndims;
  for (int d = 0; d < ndims; d++) {
    int e = order == MPI_ORDER_C ? d : ndims - 1 - d;
    sz[d] = array_of_sizes[e];
    n[d] = array_of_subsizes[e];
    idx[d] = list;
    for (int k = 0; k < n[d]; k++) *list++ = array_of_starts[e] + k;
  }
  ints[0] = ndims;
  for (int d = 0; d < ndims; d++) {
    ints[1 + d] = array_of_sizes[d];
    ints[1 + ndims + d] = array_of_subsizes[d];
    ints[1 + 2 * ndims + d] = array_of_starts[d];
  }
  ints[1 + 3 * ndims] = order;
  dtype_decoding dec = {MPI_COMBINER_SUBARRAY, 3 * ndims + 2, 0, 1, ints, NULL, &oldtype};
  rc = array_part(fn, ndims, sz, idx, n, oldtype, &dec, newtype);
  free(idx);
  free(ints);
  return rc;
}

/* MPI 3.1 section 4.1.4: the part of an ndims-dimensional array that
 * process rank of size owns under HPF's distributions, the processes a
 * grid of psizes in row-major order.  In a dimension of g elements on p
 * processes, coordinate c owns: MPI_DISTRIBUTE_BLOCK, the indices
 * [c b, (c + 1) b) below g (b the darg, by default ceil(g / p), and b p >=
 * g); MPI_DISTRIBUTE_CYCLIC, the indices i with (i / b) mod p = c (b the
 * darg, by default 1); MPI_DISTRIBUTE_NONE, all (p must be 1: MPI 3.1's
 * definition, MPICH and Open MPI disagree on more).  C or Fortran order, as
 * for subarray. */
int PMPI_Type_create_darray(int size, int rank, int ndims, const int array_of_gsizes[],
                           const int array_of_distribs[], const int array_of_dargs[],
                           const int array_of_psizes[], int order, MPI_Datatype oldtype,
                           MPI_Datatype *newtype) {
  static const char fn[] = "MPI_Type_create_darray";
  const int *arrays[4] = {array_of_gsizes, array_of_distribs, array_of_dargs, array_of_psizes};
  int rc = array_args(fn, ndims, arrays, 4, order, oldtype, newtype);
  if (rc) return rc;
  if (size < 1) return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "size %d < 1", size);
  if (rank < 0 || rank >= size)
    return fail(MPI_COMM_WORLD, MPI_ERR_RANK, fn, "rank %d is not in 0..%d", rank, size - 1);
  MPI_Count procs = 1, total = 0;
  for (int d = 0; d < ndims; d++) {
    int g = array_of_gsizes[d], dist = array_of_distribs[d], b = array_of_dargs[d], p = array_of_psizes[d];
    if (g < 1 || p < 1)
      return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "dimension %d: gsize %d, psize %d (need both >= 1)", d, g, p);
    if (dist != MPI_DISTRIBUTE_BLOCK && dist != MPI_DISTRIBUTE_CYCLIC && dist != MPI_DISTRIBUTE_NONE)
      return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "dimension %d: distribution %d is not MPI_DISTRIBUTE_BLOCK, "
                  "_CYCLIC or _NONE", d, dist);
    if (dist != MPI_DISTRIBUTE_NONE && b != MPI_DISTRIBUTE_DFLT_DARG && b < 1)
      return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "dimension %d: darg %d (need >= 1 or MPI_DISTRIBUTE_DFLT_DARG)",
                  d, b);
    if (dist == MPI_DISTRIBUTE_BLOCK && b != MPI_DISTRIBUTE_DFLT_DARG && (MPI_Count)b * p < g)
      return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "dimension %d: %d blocks of %d cover %lld of %d elements", d, p,
                  b, (long long)b * p, g);
    if (dist == MPI_DISTRIBUTE_NONE && p != 1)
      return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "dimension %d is MPI_DISTRIBUTE_NONE on a grid dimension of %d "
                  "processes (need 1)", d, p);
    procs *= p;
    total += g;
  }
  if (procs != size)
    return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "the process grid has %lld processes, size is %d", (long long)procs,
                size);
  int *sz = NULL, *n = NULL, **idx = NULL, *ints = malloc((size_t)(4 * ndims + 4) * sizeof *ints);
  int *coord = malloc((size_t)ndims * sizeof *coord);
  if (!ints || !coord) {
    free(ints), free(coord);
    return fail(MPI_COMM_WORLD, MPI_ERR_NO_MEM, fn, "out of memory");
  }
  if ((rc = array_room(fn, ndims, total, &idx, &sz, &n))) {
    free(ints), free(coord);
    return rc;
  }
  /* The process's coordinates, row-major whatever the order. */
  for (int d = ndims - 1, r = rank; d >= 0; d--) {
    coord[d] = r % array_of_psizes[d];
    r /= array_of_psizes[d];
  }
  int *list = n + ndims;
  for (int d = 0; d < ndims; d++) {
    int e = order == MPI_ORDER_C ? d : ndims - 1 - d;
    int g = array_of_gsizes[e], p = array_of_psizes[e], c = coord[e], b = array_of_dargs[e];
    if (array_of_distribs[e] == MPI_DISTRIBUTE_NONE) b = g;
    else if (b == MPI_DISTRIBUTE_DFLT_DARG) b = array_of_distribs[e] == MPI_DISTRIBUTE_BLOCK ? (g + p - 1) / p : 1;
    sz[d] = g;
    idx[d] = list;
    n[d] = 0;
    for (int i = 0; i < g; i++)
      if ((i / b) % p == c) list[n[d]++] = i;
    list += n[d];
  }
  ints[0] = size;
  ints[1] = rank;
  ints[2] = ndims;
  for (int d = 0; d < ndims; d++) {
    ints[3 + d] = array_of_gsizes[d];
    ints[3 + ndims + d] = array_of_distribs[d];
    ints[3 + 2 * ndims + d] = array_of_dargs[d];
    ints[3 + 3 * ndims + d] = array_of_psizes[d];
  }
  ints[3 + 4 * ndims] = order;
  dtype_decoding dec = {MPI_COMBINER_DARRAY, 4 * ndims + 4, 0, 1, ints, NULL, &oldtype};
  rc = array_part(fn, ndims, sz, idx, n, oldtype, &dec, newtype);
  free(idx);
  free(ints), free(coord);
  return rc;
}

/* ==== commit, free, names ================================================= */

int PMPI_Type_commit(MPI_Datatype *datatype) {
  static const char fn[] = "MPI_Type_commit";
  int rc;
  if ((rc = ptr_ok(fn, "datatype", datatype)) || (rc = type_ok(fn, "datatype", *datatype))) return rc;
  return dtype_commit(*datatype);
}

int PMPI_Type_free(MPI_Datatype *datatype) {
  static const char fn[] = "MPI_Type_free";
  int rc;
  if ((rc = ptr_ok(fn, "datatype", datatype)) || (rc = type_ok(fn, "datatype", *datatype))) return rc;
  if (((unsigned)*datatype & 0x800000u) && (rc = attr_type_delete(*datatype, fn))) return rc;
  if (dtype_free(*datatype) != MPI_SUCCESS)
    return fail(MPI_COMM_WORLD, MPI_ERR_TYPE, fn, "%s is predefined and cannot be freed",
                dtype_name(*datatype));
  *datatype = MPI_DATATYPE_NULL;
  return MPI_SUCCESS;
}

int PMPI_Type_get_name(MPI_Datatype datatype, char *type_name, int *resultlen) {
  static const char fn[] = "MPI_Type_get_name";
  int rc;
  if ((rc = type_ok(fn, "datatype", datatype)) || (rc = ptr_ok(fn, "type_name", type_name)) ||
      (rc = ptr_ok(fn, "resultlen", resultlen)))
    return rc;
  const char *s = dtype_name(datatype);
  snprintf(type_name, MPI_MAX_OBJECT_NAME, "%s", s);
  *resultlen = (int)strlen(type_name);
  return MPI_SUCCESS;
}

int PMPI_Type_set_name(MPI_Datatype datatype, const char *type_name) {
  static const char fn[] = "MPI_Type_set_name";
  int rc;
  if ((rc = type_ok(fn, "datatype", datatype)) || (rc = ptr_ok(fn, "type_name", type_name))) return rc;
  rc = dtype_set_name(datatype, type_name);
  return rc ? fail(MPI_COMM_WORLD, rc, fn, "out of memory") : rc;
}

/* ==== queries ============================================================= */

int PMPI_Type_size_x(MPI_Datatype datatype, MPI_Count *size) {
  static const char fn[] = "MPI_Type_size_x";
  int rc;
  if ((rc = type_ok(fn, "datatype", datatype)) || (rc = ptr_ok(fn, "size", size))) return rc;
  *size = (MPI_Count)dtype_size(datatype);
  return MPI_SUCCESS;
}

int PMPI_Type_size(MPI_Datatype datatype, int *size) {
  static const char fn[] = "MPI_Type_size";
  int rc;
  if ((rc = type_ok(fn, "datatype", datatype)) || (rc = ptr_ok(fn, "size", size))) return rc;
  size_t s = dtype_size(datatype);
  *size = s > INT_MAX ? MPI_UNDEFINED : (int)s;
  return MPI_SUCCESS;
}

/* lb and extent (truly: the data's) of a type, for the queries. */
static int extent_of(const char *fn, MPI_Datatype dt, int truly, MPI_Aint *lb, MPI_Aint *extent) {
  int rc;
  if ((rc = type_ok(fn, "datatype", dt))) return rc;
  if (!lb || !extent) return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "an output argument is NULL");
  MPI_Aint l, u, tl, tu;
  dtype_bounds(dt, &l, &u, &tl, &tu);
  *lb = truly ? tl : l;
  *extent = truly ? tu - tl : u - l;
  return MPI_SUCCESS;
}

int PMPI_Type_get_extent(MPI_Datatype datatype, MPI_Aint *lb, MPI_Aint *extent) {
  return extent_of("MPI_Type_get_extent", datatype, 0, lb, extent);
}

int PMPI_Type_get_true_extent(MPI_Datatype datatype, MPI_Aint *true_lb, MPI_Aint *true_extent) {
  return extent_of("MPI_Type_get_true_extent", datatype, 1, true_lb, true_extent);
}

/* The _x forms: the same in MPI_Count. */
static int extent_x(const char *fn, MPI_Datatype dt, int truly, MPI_Count *lb, MPI_Count *extent) {
  MPI_Aint l, e;
  int rc = extent_of(fn, dt, truly, &l, &e);
  if (rc) return rc;
  if (!lb || !extent) return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "an output argument is NULL");
  *lb = l;
  *extent = e;
  return MPI_SUCCESS;
}

int PMPI_Type_get_extent_x(MPI_Datatype datatype, MPI_Count *lb, MPI_Count *extent) {
  return extent_x("MPI_Type_get_extent_x", datatype, 0, lb, extent);
}

int PMPI_Type_get_true_extent_x(MPI_Datatype datatype, MPI_Count *true_lb, MPI_Count *true_extent) {
  return extent_x("MPI_Type_get_true_extent_x", datatype, 1, true_lb, true_extent);
}

int PMPI_Type_extent(MPI_Datatype datatype, MPI_Aint *extent) {
  MPI_Aint lb;
  return extent_of("MPI_Type_extent", datatype, 0, &lb, extent);
}

int PMPI_Type_lb(MPI_Datatype datatype, MPI_Aint *displacement) {
  MPI_Aint ext;
  return extent_of("MPI_Type_lb", datatype, 0, displacement, &ext);
}

int PMPI_Type_ub(MPI_Datatype datatype, MPI_Aint *displacement) {
  MPI_Aint lb, ext;
  int rc = extent_of("MPI_Type_ub", datatype, 0, &lb, &ext);
  if (rc == MPI_SUCCESS && (rc = ptr_ok("MPI_Type_ub", "displacement", displacement)) == 0) *displacement = lb + ext;
  return rc;
}

int PMPI_Type_get_envelope(MPI_Datatype datatype, int *num_integers, int *num_addresses, int *num_datatypes,
                          int *combiner) {
  static const char fn[] = "MPI_Type_get_envelope";
  int rc;
  if ((rc = type_ok(fn, "datatype", datatype))) return rc;
  if (!num_integers || !num_addresses || !num_datatypes || !combiner)
    return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "an output argument is NULL");
  dtype_envelope(datatype, num_integers, num_addresses, num_datatypes, combiner);
  return MPI_SUCCESS;
}

int PMPI_Type_get_contents(MPI_Datatype datatype, int max_integers, int max_addresses, int max_datatypes,
                          int array_of_integers[], MPI_Aint array_of_addresses[],
                          MPI_Datatype array_of_datatypes[]) {
  static const char fn[] = "MPI_Type_get_contents";
  int rc = type_ok(fn, "datatype", datatype);
  if (rc) return rc;
  int ni, na, nd, comb;
  dtype_envelope(datatype, &ni, &na, &nd, &comb);
  if (comb == MPI_COMBINER_NAMED)
    return fail(MPI_COMM_WORLD, MPI_ERR_TYPE, fn, "%s is predefined (MPI_COMBINER_NAMED)", dtype_name(datatype));
  if (max_integers < ni || max_addresses < na || max_datatypes < nd)
    return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "the arrays hold %d, %d and %d; the type needs %d, %d and %d",
                max_integers, max_addresses, max_datatypes, ni, na, nd);
  if ((ni && !array_of_integers) || (na && !array_of_addresses) || (nd && !array_of_datatypes))
    return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "an array argument is NULL");
  return dtype_contents(datatype, max_integers, max_addresses, max_datatypes, array_of_integers,
                        array_of_addresses, array_of_datatypes);
}

/* MPI 3.1 section 17.2.5: the Fortran types of a class and size. */
int PMPI_Type_match_size(int typeclass, int size, MPI_Datatype *datatype) {
  static const char fn[] = "MPI_Type_match_size";
  int rc = ptr_ok(fn, "datatype", datatype);
  if (rc) return rc;
  MPI_Datatype t = MPI_DATATYPE_NULL;
  if (typeclass == MPI_TYPECLASS_INTEGER)
    t = size == 1 ? MPI_INTEGER1 : size == 2 ? MPI_INTEGER2 : size == 4 ? MPI_INTEGER4 : size == 8 ? MPI_INTEGER8 : t;
  else if (typeclass == MPI_TYPECLASS_REAL)
    t = size == 4 ? MPI_REAL4 : size == 8 ? MPI_REAL8 : t;
  else if (typeclass == MPI_TYPECLASS_COMPLEX)
    t = size == 8 ? MPI_COMPLEX8 : size == 16 ? MPI_COMPLEX16 : t;
  else
    return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "typeclass %d is not MPI_TYPECLASS_INTEGER, _REAL or _COMPLEX",
                typeclass);
  if (t == MPI_DATATYPE_NULL) return fail(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "no type of class %d has %d bytes", typeclass, size);
  *datatype = t;
  return MPI_SUCCESS;
}

/* ==== addresses =========================================================== */

int PMPI_Get_address(const void *location, MPI_Aint *address) {
  int rc = ptr_ok("MPI_Get_address", "address", address);
  if (rc == MPI_SUCCESS) *address = (MPI_Aint)(uintptr_t)location;
  return rc;
}

int PMPI_Address(void *location, MPI_Aint *address) {
  int rc = ptr_ok("MPI_Address", "address", address);
  if (rc == MPI_SUCCESS) *address = (MPI_Aint)(uintptr_t)location;
  return rc;
}

MPI_Aint PMPI_Aint_add(MPI_Aint base, MPI_Aint disp) {
  return (MPI_Aint)((uintptr_t)base + (uintptr_t)disp);
}

MPI_Aint PMPI_Aint_diff(MPI_Aint addr1, MPI_Aint addr2) {
  return (MPI_Aint)((uintptr_t)addr1 - (uintptr_t)addr2);
}

/* ==== pack, unpack, elements ============================================== */

/* A committed type for a data-moving call on comm. */
static int commtype_ok(MPI_Comm comm, const char *fn, MPI_Datatype dt) {
  char why[96];
  if (dtype_check(dt, why, sizeof why) == MPI_SUCCESS) return MPI_SUCCESS;
  return fail(comm, MPI_ERR_TYPE, fn, "invalid datatype: %s", why);
}

int dtype_room_ok(MPI_Comm comm, const char *fn, int packing, const void *position, long pos, long size,
                  MPI_Count n, const void *buf) {
  if (!position) return fail(comm, MPI_ERR_ARG, fn, "position is NULL");
  if (pos < 0 || size < 0 || pos > size || n > size - pos)
    return fail(comm, MPI_ERR_TRUNCATE, fn, "%lld bytes %s at position %ld of a %ld-byte buffer", (long long)n,
                packing ? "do not fit" : "are not there", pos, size);
  if (n > 0 && !buf) return fail(comm, MPI_ERR_BUFFER, fn, "%s is NULL", packing ? "outbuf" : "inbuf");
  return MPI_SUCCESS;
}

int PMPI_Pack(const void *inbuf, int incount, MPI_Datatype datatype, void *outbuf, int outsize, int *position,
             MPI_Comm comm) {
  static const char fn[] = "MPI_Pack";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = err_comm_check_count(comm, fn, incount)) ||
      (rc = commtype_ok(comm, fn, datatype)) || (rc = err_comm_check_buf(comm, fn, inbuf, incount, datatype)))
    return rc;
  MPI_Count n = (MPI_Count)dtype_size(datatype) * incount;
  if ((rc = dtype_room_ok(comm, fn, 1, position, position ? *position : 0, outsize, n, outbuf))) return rc;
  if (n > 0) dtype_pack(inbuf, incount, datatype, (char *)outbuf + *position);
  *position += (int)n;
  return MPI_SUCCESS;
}

int PMPI_Unpack(const void *inbuf, int insize, int *position, void *outbuf, int outcount, MPI_Datatype datatype,
               MPI_Comm comm) {
  static const char fn[] = "MPI_Unpack";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = err_comm_check_count(comm, fn, outcount)) ||
      (rc = commtype_ok(comm, fn, datatype)) || (rc = err_comm_check_buf(comm, fn, outbuf, outcount, datatype)))
    return rc;
  MPI_Count n = (MPI_Count)dtype_size(datatype) * outcount;
  if ((rc = dtype_room_ok(comm, fn, 0, position, position ? *position : 0, insize, n, inbuf))) return rc;
  if (n > 0) dtype_unpack((const char *)inbuf + *position, (size_t)n, outbuf, outcount, datatype);
  *position += (int)n;
  return MPI_SUCCESS;
}

int PMPI_Pack_size(int incount, MPI_Datatype datatype, MPI_Comm comm, int *size) {
  static const char fn[] = "MPI_Pack_size";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = err_comm_check_count(comm, fn, incount)) ||
      (rc = commtype_ok(comm, fn, datatype)))
    return rc;
  if (!size) return fail(comm, MPI_ERR_ARG, fn, "size is NULL");
  MPI_Count n = (MPI_Count)dtype_size(datatype) * incount;
  if (n > INT_MAX) return fail(comm, MPI_ERR_SIZE, fn, "%lld bytes do not fit an int", (long long)n);
  *size = (int)n;
  return MPI_SUCCESS;
}

int PMPI_Get_elements_x(const MPI_Status *status, MPI_Datatype datatype, MPI_Count *count) {
  static const char fn[] = "MPI_Get_elements_x";
  int rc;
  if ((rc = ptr_ok(fn, "status", status)) || (rc = ptr_ok(fn, "count", count)) ||
      (rc = commtype_ok(MPI_COMM_WORLD, fn, datatype)))
    return rc;
  *count = dtype_elements(datatype, status->tsmpi_count);
  return MPI_SUCCESS;
}

int PMPI_Get_elements(const MPI_Status *status, MPI_Datatype datatype, int *count) {
  MPI_Count n;
  int rc = MPI_Get_elements_x(status, datatype, &n);
  if (rc == MPI_SUCCESS) {
    if (!count) return fail(MPI_COMM_WORLD, MPI_ERR_ARG, "MPI_Get_elements", "count is NULL");
    *count = n > INT_MAX ? MPI_UNDEFINED : (int)n;
  }
  return rc;
}

/* MPI 3.1 section 12.3: status as if count basic elements of datatype had
 * arrived (MPI_Get_elements then says count, MPI_Get_count the whole
 * elements or MPI_UNDEFINED). */
int PMPI_Status_set_elements_x(MPI_Status *status, MPI_Datatype datatype, MPI_Count count) {
  static const char fn[] = "MPI_Status_set_elements_x";
  int rc;
  if ((rc = ptr_ok(fn, "status", status)) || (rc = commtype_ok(MPI_COMM_WORLD, fn, datatype))) return rc;
  MPI_Count bytes = count < 0 ? -1 : dtype_elements_bytes(datatype, count);
  if (bytes < 0)
    return fail(MPI_COMM_WORLD, MPI_ERR_COUNT, fn, "count %lld of %s, which has %s", (long long)count,
                *dtype_name(datatype) ? dtype_name(datatype) : "a derived type",
                count < 0 ? "no negative counts" : "no basic elements");
  status->tsmpi_count = bytes;
  return MPI_SUCCESS;
}

int PMPI_Status_set_elements(MPI_Status *status, MPI_Datatype datatype, int count) {
  return MPI_Status_set_elements_x(status, datatype, count);
}
