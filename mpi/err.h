/* err.h -- errors of the MPI layer's calls: the communicator's error
 * handler (MPI_ERRORS_ARE_FATAL, MPI_ERRORS_RETURN, or the program's: errh.h),
 * the argument checks every call makes, error classes and their strings.
 *
 * A call's errors are reported with MPI's class as the error code (codes
 * and classes are one: MPI_Error_class(c) is c) and, under
 * MPI_ERRORS_ARE_FATAL, a message that names the rank, the call and the
 * argument, e.g. "rank 2: MPI_Send: invalid rank 7 (MPI_COMM_WORLD has 4
 * ranks)", with which the run ends (exit status 1). */
#ifndef TSMPI_ERR_H
#define TSMPI_ERR_H

#include "mpi/state.h"

/* An error of call fn in R under c's handler (c NULL: MPI_COMM_WORLD's):
 * returns cls under MPI_ERRORS_RETURN, and after calling the program's
 * handler with c's handle and cls; ends the run under
 * MPI_ERRORS_ARE_FATAL (never returns then). */
#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
int err_raise(st_rank *R, const st_comm *c, int cls, const char *fn, const char *fmt, ...);

/* The same under handler eh of the object whose handle is `handle` (a
 * window's, a file's: the program's handler function gets the handle and
 * cls, then cls is returned; MPI_ERRORS_RETURN returns cls;
 * MPI_ERRORS_ARE_FATAL ends the run). */
#if defined(__GNUC__)
__attribute__((format(printf, 6, 7)))
#endif
int err_raise_on(st_rank *R, MPI_Errhandler eh, int handle, int cls, const char *fn, const char *fmt, ...);

/* The predefined class cls's text (0 <= cls <= MPI_ERR_LASTCODE):
 * "MPI_ERR_COMM: invalid communicator". */
const char *err_class_text(int cls);

/* The checks, each MPI_SUCCESS or err_raise's result:
 *   err_check_comm   comm is R's (*out: it)                 MPI_ERR_COMM
 *   err_check_count  count >= 0                             MPI_ERR_COUNT
 *   err_check_type   dt usable (committed, not freed)       MPI_ERR_TYPE
 *   err_check_tag    0 <= tag <= MPI_TAG_UB, or MPI_ANY_TAG
 *                    with any_ok                            MPI_ERR_TAG
 *   err_check_peer   0 <= r < size, MPI_PROC_NULL, or
 *                    MPI_ANY_SOURCE with any_ok             MPI_ERR_RANK
 *   err_check_buf    buf not NULL when count elements of dt
 *                    have bytes                             MPI_ERR_BUFFER */
int err_check_comm(st_rank *R, MPI_Comm comm, const char *fn, st_comm **out);
int err_check_count(st_rank *R, const st_comm *c, const char *fn, int count);
int err_check_type(st_rank *R, const st_comm *c, const char *fn, MPI_Datatype dt);
int err_check_tag(st_rank *R, const st_comm *c, const char *fn, int tag, int any_ok);
int err_check_peer(st_rank *R, const st_comm *c, const char *fn, int r, int any_ok);
int err_check_buf(st_rank *R, const st_comm *c, const char *fn, const void *buf, int count,
                  MPI_Datatype dt);

/* A communicator handle in words for a message: "MPI_COMM_NULL",
 * "communicator handle 0x1800005 (not one of this rank's)" (buf: 64 bytes). */
const char *err_comm_words(MPI_Comm comm, char *buf);

#endif
