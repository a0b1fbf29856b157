/* info.h -- info objects (MPI 3.1 chapter 9), MPI_INFO_ENV, and the hints a
 * communicator keeps (MPI_Comm_set_info, MPI_Comm_get_info,
 * MPI_Comm_dup_with_info, MPI_Comm_split_type's info).
 *
 * An info object is an ordered list of (key, value) strings: keys of 1 to
 * MPI_MAX_INFO_KEY (255) characters, values of 1 to MPI_MAX_INFO_VAL
 * (1024), kept in the order first set (MPI_Info_get_nthkey), as MPICH.
 * MPI_INFO_ENV holds what MPI_Init saw: "command" and "argv" (when the
 * program passed its argv), "maxprocs" (the number of ranks) and
 * "thread_level"; it cannot be changed or freed.  It is made when first
 * used (a rank that never asks spends nothing on it), from the argc and
 * argv MPI_Init kept.
 *
 * HINTS.  A communicator keeps the hints tilesim knows, MPI 4.0's
 * assertions mpi_assert_no_any_tag, mpi_assert_no_any_source,
 * mpi_assert_exact_length and mpi_assert_allow_overtaking ("true" or
 * "false"), and ignores the others, as MPICH does; they change nothing in
 * how tilesim runs (a program that breaks one is not told).
 * MPI_Comm_get_info gives back those that were set. */
#ifndef TSMPI_INFO_H
#define TSMPI_INFO_H

#include "mpi/state.h"

/* A communicator's hints word from info (MPI_INFO_NULL: none): `given`
 * bits in the low byte, their values ("true") in the next; *hints keeps
 * its other bits (a merge).  MPI_SUCCESS, or MPI_ERR_INFO raised on c for
 * fn (an invalid info handle). */
int info_hints(st_rank *R, const st_comm *c, const char *fn, MPI_Info info, unsigned *hints);

/* The value of key in info object h (a window's hints): 1 and up to len
 * bytes of it in value (NUL-terminated), 0 if h has no such key, -1 if h
 * is not a valid info object (MPI_INFO_NULL: 0). */
int info_value(st_rank *R, MPI_Info h, const char *key, char *value, size_t len);

/* Free every info object of the rank (its end). */
void info_release_all(st_rank *R);

#endif
