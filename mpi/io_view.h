/* io_view.h -- a file view (MPI 3.1 section 13.3): which bytes of a file a rank sees, as a
 * stream of data, and where each byte of that stream is in the file.
 *
 * Not for programs (mpi.h is theirs).  A view is a displacement, an etype and a filetype: the
 * filetype is laid end to end from the displacement on (tile k at disp + k * extent), and the
 * rank sees the data of those tiles, in type-map order, one after the other.  Offsets in the
 * MPI calls count etypes of that stream; the calls here count its bytes (offset * etype size).
 * The filetype's runs of data within a tile must have non-negative, non-decreasing and
 * non-overlapping displacements (MPI 3.1's rule), its size a whole number of etypes.
 *
 * Data representations: "native" and "internal" (the same here: the bytes as in memory);
 * "external32" and the program's own (MPI_Register_datarep) are refused with
 * MPI_ERR_UNSUPPORTED_DATAREP. */
#ifndef TSMPI_IO_VIEW_H
#define TSMPI_IO_VIEW_H

#include <stddef.h>

#include "mpi/mpi.h"

typedef struct {
  MPI_Offset disp;          /* bytes to the first tile */
  MPI_Datatype etype, ftype;/* held (dtype_hold) */
  MPI_Aint esize;           /* the etype's size */
  MPI_Aint fext;            /* the filetype's extent: one tile to the next */
  MPI_Offset fsize;         /* its bytes of data in a tile */
  size_t nrun;              /* its runs of data in a tile: */
  MPI_Aint *off, *len;      /* at off[k] from the tile's origin, len[k] bytes, */
  MPI_Offset *before;       /* with before[k] bytes of the tile's data before */
  int heap;                 /* off, len, before are malloc'd (else static) */
  char datarep[MPI_MAX_DATAREP_STRING];
} io_view;

/* The view a file opens with: displacement 0, MPI_BYTE, MPI_BYTE, "native". */
void io_view_default(io_view *v);

/* A new view in *v (the old one freed only on success).  MPI_SUCCESS, or an
 * error class and why (len bytes): MPI_ERR_TYPE (an etype or filetype that
 * is not committed), MPI_ERR_ARG (a negative displacement, an etype of no
 * data, a filetype that is not whole etypes or breaks the displacement
 * rule), MPI_ERR_UNSUPPORTED_DATAREP. */
int io_view_set(io_view *v, MPI_Offset disp, MPI_Datatype etype, MPI_Datatype ftype, const char *datarep,
                char *why, size_t len);

void io_view_free(io_view *v);

/* Calls f(ud, off, n, at) for the pieces of the file that hold `bytes` bytes
 * of the view's stream from byte `pos` on, in stream order: n bytes at file
 * offset off, which are the stream's bytes from pos + at; adjacent pieces
 * merged.  Stops early when f returns non-zero, and returns that. */
int io_view_map(const io_view *v, MPI_Offset pos, MPI_Offset bytes,
                int (*f)(void *ud, MPI_Offset off, MPI_Offset n, MPI_Offset at), void *ud);

/* The file offset of the stream's byte pos (MPI_File_get_byte_offset). */
MPI_Offset io_view_byte(const io_view *v, MPI_Offset pos);

/* The stream position of the first stream byte at or past file offset off
 * (where a view's stream ends when the file ends there). */
MPI_Offset io_view_stream(const io_view *v, MPI_Offset off);

#endif
