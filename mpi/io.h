/* io.h -- MPI-IO's files inside the MPI layer: a rank's open files, the object the ranks that
 * opened a file together share, errors under a file's handler, and what each kind of access
 * costs on the storage model (io_model.h).  The MPI_File_* functions (io_api.c, io_data.c)
 * are built on these.
 *
 * Not for programs (mpi.h is theirs).
 *
 * ONE PROCESS.  tilesim's ranks share one process: the ranks that open a file together
 * (MPI_File_open over a communicator) share one host file descriptor and one object with the
 * shared file pointer and the results of their collective calls; the first of them to get there
 * opens the file, and the last to close it closes it.  Every access holds the shared object's
 * lock while it moves data, so each call's data move is atomic with respect to the others'
 * (both atomicity modes allow it; on the simulator the ranks take turns anyway, in simulated
 * time).  Data go to the host's file at the call: a program's files hold what they would.
 *
 * HANDLES.  MPI_File handles are 0x09800000 | slot, the rank's own; MPI_FILE_NULL is
 * 0x09000000.  An error of a call on a file goes to the file's handler (MPI_ERRORS_RETURN
 * when opened, as MPI 3.1 section 13.7 says), of MPI_File_open and MPI_File_delete to
 * MPI_FILE_NULL's (the same default). */
#ifndef TSMPI_IO_H
#define TSMPI_IO_H

#include <pthread.h>

#include "mpi/io_model.h"
#include "mpi/io_view.h"
#include "mpi/mpi.h"

/* What the ranks of one open share. */
typedef struct {
  pthread_mutex_t lock;    /* every data move and every field below */
  int refs;                /* ranks that have it open */
  int fd;
  io_fs *fs;
  char host[IO_PATH_MAX];
  int delete_on_close;
  int atomic;              /* MPI_File_set_atomicity's mode (the same on every rank) */
  MPI_Offset shared;       /* the shared file pointer, in etypes */
  unsigned long cseq;      /* the last collective call settled (io_collective) */
  double cend;             /* its end */
  MPI_Offset cbase;        /* its shared file pointer (ordered calls) */
} io_ofile;

/* A rank's open file. */
typedef struct {
  io_ofile *sh;
  MPI_Comm comm;           /* the file's own duplicate of the communicator */
  int rank, size;          /* in it */
  int amode;
  io_view view;
  MPI_Offset pos;          /* the individual file pointer, in etypes */
  MPI_Errhandler eh;
  MPI_Info hints;          /* the hints given (a copy), or MPI_INFO_NULL */
  unsigned long cseq;      /* collective calls made on it */
  int split;               /* a split collective begun: its kind (io_data.c), else 0 */
  int split_rc;            /* its result and status */
  MPI_Status split_st;
} io_file;

/* The rank's file of handle fh, or NULL (MPI_FILE_NULL, closed, not a file). */
io_file *io_file_get(MPI_File fh);

/* An error of call fn under fh's handler (MPI_FILE_NULL: the handler of
 * calls with no file): the class returned, or the run ended (fatal). */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
int io_file_raise(MPI_File fh, int cls, const char *fn, const char *fmt, ...);

/* fh valid for fn: its file in *f, or the error raised (MPI_ERR_FILE under
 * MPI_FILE_NULL's handler). */
int io_file_check(MPI_File fh, const char *fn, io_file **f);

/* Open and close (MPI_File_open, MPI_File_close: collective). */
int io_file_open(MPI_Comm comm, const char *path, int amode, MPI_Info info, MPI_File *fh);
int io_file_close(MPI_File *fh);

/* The rank uses MPI-IO from now on (its table made, the file systems'
 * users counted: io_model.h); every call that reaches a file system does
 * it first. */
void io_begin(void);

/* The handler of MPI_FILE_NULL (MPI_File_set/get_errhandler on it). */
MPI_Errhandler io_file_null_eh(void);
void io_file_set_null_eh(MPI_Errhandler eh);

/* ==== time ================================================================ */

/* An independent request of `bytes` bytes on f's file system coming now:
 * its end. */
double io_independent(io_file *f, double bytes);

/* A collective call's exchange (call fn, for a deadlock report): every rank
 * of the file gives its bytes and the time it came; the call is one request of their sum coming when the
 * last came, made by the first rank to get past the exchange, which also
 * runs first(f, counts, ud) under the shared lock before it (the one-time
 * part of the call: a resize, the shared pointer's move; counts[r] rank r's
 * bytes).  Returns the request's end (the same on every rank); *base (if
 * not NULL) gets the shared object's cbase as first left it, *below (if not
 * NULL) the bytes of the ranks below this one.  bytes < 0 on every rank: no
 * request (a call that only agrees on something: its end is the exchange's). */
double io_collective(io_file *f, const char *fn, double bytes, MPI_Offset *base, MPI_Offset *below,
                     void (*first)(io_file *f, const double *counts, void *ud), void *ud);

/* The rank's clock moves on to `end` if it is before (mp_sleep: the
 * processor is free meanwhile). */
void io_until(double end);

#endif
