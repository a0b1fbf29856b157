/* dtype_ext.h -- the "external32" data representation (MPI 3.1 section 13.5.2): every basic
 * value big-endian in the standard's size, back to back; what MPI_Pack_external writes, and
 * what a file view in external32 holds.
 *
 * Not for programs (mpi.h is theirs).  Sizes are table 13.2's, as MPICH has them: MPI_LONG and
 * MPI_UNSIGNED_LONG take 4 bytes, MPI_WCHAR 2, MPI_LONG_DOUBLE 16 (IEEE 754 binary128), the
 * address and count types 8; a pair is its value then its index (MPI_DOUBLE_INT: 12 bytes).
 * Integers wider here than there keep their low bytes (a long beyond 32 bits is cut, as in
 * MPICH and Open MPI) and come back sign- or zero-extended; floating point is IEEE 754, a long
 * double rounded to nearest where it has fewer bits than binary128 (x86's 80-bit format: every
 * value exactly, and back).  MPI_BYTE, MPI_PACKED and MPI_CHARACTER are bytes as they are. */
#ifndef TSMPI_DTYPE_EXT_H
#define TSMPI_DTYPE_EXT_H

#include "mpi/mpi.h"

/* Bytes of one element of dt (checked) in external32. */
MPI_Count dtype_ext32_size(MPI_Datatype dt);

/* count elements of dt at buf into out, external32: count *
 * dtype_ext32_size(dt) bytes.  out must not overlap the elements. */
void dtype_ext32_pack(const void *buf, MPI_Count count, MPI_Datatype dt, void *out);

/* count elements of dt in external32 at in into their places at buf. */
void dtype_ext32_unpack(const void *in, void *buf, MPI_Count count, MPI_Datatype dt);

#endif
