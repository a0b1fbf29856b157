/* io_data.c -- MPI-IO's data access (MPI 3.1 section 13.4): reads and writes at explicit
 * offsets, at the individual and at the shared file pointer, independent and collective,
 * ordered, nonblocking, and split collective (mpi.h; built on io.h).
 *
 * Every call moves its data at once, through the view, under the file's shared lock, and
 * charges its time on the storage model: an independent call (and a nonblocking one, whose
 * request is complete when it returns: the time is charged at the call, with no overlap with
 * what the rank does next) is one request; a collective call exchanges every rank's bytes and
 * is one request of their sum when the last rank has come (io.h).  The nonblocking collective
 * calls are charged as independent ones (they may not wait for the other ranks).  A split
 * collective runs whole at its _begin; its _end gives the status.  A read past the end of the
 * file gets what is there: its status counts the bytes read. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mpi/dtype.h"
#include "mpi/io.h"
#include "mpi/core.h"
#include "mpi/pt2pt.h"
#include "mpi/state.h"

enum { RD, WR };
enum { AT, INDIV, SHARED, ORDERED };   /* where an access is */
enum { INDEP, COLL };

/* ==== moving data ========================================================= */

typedef struct {
  int fd, wr;
  char *mem;              /* the packed bytes */
  MPI_Offset done;        /* bytes moved from the start, without a gap */
  int err;                /* errno of a failed call, else 0 */
} mover;

static int piece(void *ud, MPI_Offset off, MPI_Offset n, MPI_Offset at) {
  mover *m = ud;
  MPI_Offset k = 0;
  while (k < n) {
    size_t chunk = n - k > (1 << 30) ? (size_t)1 << 30 : (size_t)(n - k);
    ssize_t r = m->wr ? pwrite(m->fd, m->mem + at + k, chunk, (off_t)(off + k))
                      : pread(m->fd, m->mem + at + k, chunk, (off_t)(off + k));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      m->err = errno;
      return 1;
    }
    if (r == 0) return 1;   /* the end of the file (reads) */
    k += r;
    m->done = at + k;
  }
  return 0;
}

/* count elements of dt at buf to (wr) or from view stream byte pos of f,
 * under the shared lock: the bytes moved (a read stops at the end of the
 * file); *err the errno of a failure, else 0. */
static MPI_Offset move(io_file *f, int wr, MPI_Offset pos, void *buf, int count, MPI_Datatype dt, int *err) {
  MPI_Offset n = (MPI_Offset)dtype_size(dt) * count;
  *err = 0;
  if (n == 0) return 0;
  char *mem = (char *)dtype_contig(buf, count, dt), *tmp = NULL;
  if (!mem) {
    tmp = mem = malloc((size_t)n);
    if (!tmp) {
      *err = ENOMEM;
      return 0;
    }
    if (wr) dtype_pack(buf, count, dt, tmp);
  }
  mover m = {f->sh->fd, wr, mem, 0, 0};
  io_view_map(&f->view, pos, n, piece, &m);
  if (tmp) {
    if (!wr) dtype_unpack(tmp, (size_t)m.done, buf, count, dt);
    free(tmp);
  }
  *err = m.err;
  return m.done;
}

static void status_of(MPI_Status *st, MPI_Offset bytes) {
  if (st == MPI_STATUS_IGNORE) return;
  pt2pt_status_empty(st);
  st->tsmpi_count = bytes;
}

/* ==== one access ========================================================== */

typedef struct {
  int wr, where;
  MPI_Offset bytes;        /* this rank's */
  MPI_Offset esize;
} ordered_ud;

/* An ordered call's one-time part: the shared pointer moves on by every
 * rank's bytes, from where it was (cbase). */
static void ordered_first(io_file *f, const double *counts, void *ud) {
  ordered_ud *o = ud;
  MPI_Offset sum = 0;
  for (int r = 0; r < f->size; r++) sum += (MPI_Offset)counts[r];
  f->sh->cbase = f->sh->shared;
  f->sh->shared += sum / o->esize;
}

static const char *op_word(int wr) { return wr ? "write" : "read"; }

/* The checks of every data call; MPI_SUCCESS or the error raised. */
static int args(MPI_File fh, const char *fn, io_file **fp, int wr, int where, MPI_Offset offset, const void *buf,
                int count, MPI_Datatype dt) {
  io_file *f;
  char why[96];
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  *fp = f;
  if (count < 0) return io_file_raise(fh, MPI_ERR_COUNT, fn, "invalid count %d (must be >= 0)", count);
  if (dtype_check(dt, why, sizeof why) != MPI_SUCCESS)
    return io_file_raise(fh, MPI_ERR_TYPE, fn, "invalid datatype: %s", why);
  if (!buf && count && dtype_size(dt) && !dtype_bottom_ok(dt, count))
    return io_file_raise(fh, MPI_ERR_BUFFER, fn, "buf is NULL");
  if (where == AT && offset < 0) return io_file_raise(fh, MPI_ERR_ARG, fn, "offset %lld < 0", (long long)offset);
  if (wr && (f->amode & MPI_MODE_RDONLY))
    return io_file_raise(fh, MPI_ERR_READ_ONLY, fn, "the file is open MPI_MODE_RDONLY: no writes");
  if (!wr && (f->amode & MPI_MODE_WRONLY))
    return io_file_raise(fh, MPI_ERR_ACCESS, fn, "the file is open MPI_MODE_WRONLY: no reads");
  if ((f->amode & MPI_MODE_SEQUENTIAL) && (where == AT || where == INDIV))
    return io_file_raise(fh, MPI_ERR_UNSUPPORTED_OPERATION, fn,
                         "the file is open MPI_MODE_SEQUENTIAL: only the shared file pointer");
  MPI_Offset n = (MPI_Offset)dtype_size(dt) * count;
  if (n % f->view.esize)
    return io_file_raise(fh, MPI_ERR_IO, fn, "%lld bytes are not a whole number of etypes (%ld bytes each)",
                         (long long)n, (long)f->view.esize);
  return MPI_SUCCESS;
}

/* A read or write of count elements of dt: at etype `offset` (AT), at the
 * individual or the shared file pointer, or ordered; independent or
 * collective. */
static int data_access(MPI_File fh, const char *fn, int wr, int where, int coll, MPI_Offset offset, void *buf,
                  int count, MPI_Datatype dt, MPI_Status *st) {
  io_file *f = NULL;
  int rc = args(fh, fn, &f, wr, where, offset, buf, count, dt);
  if (rc) return rc;
  io_ofile *sh = f->sh;
  MPI_Offset es = f->view.esize, n = (MPI_Offset)dtype_size(dt) * count, pos = 0, got;
  double end = 0;
  int err;
  if (coll == COLL) {
    ordered_ud o = {wr, where, n, es};
    MPI_Offset base = 0, below = 0;
    end = io_collective(f, fn, (double)n, &base, &below, where == ORDERED ? ordered_first : NULL, &o);
    if (where == ORDERED) pos = base * es + below;
  }
  pthread_mutex_lock(&sh->lock);
  if (where == AT) pos = offset * es;
  else if (where == INDIV) pos = f->pos * es;
  else if (where == SHARED) pos = sh->shared * es, sh->shared += n / es;
  got = move(f, wr, pos, buf, count, dt, &err);
  pthread_mutex_unlock(&sh->lock);
  if (where == INDIV) f->pos += got / es;
  if (coll == INDEP) end = io_independent(f, (double)n);
  io_until(end);
  status_of(st, got);
  if (err)
    return io_file_raise(fh, err == ENOSPC ? MPI_ERR_NO_SPACE : err == EDQUOT ? MPI_ERR_QUOTA : MPI_ERR_IO, fn,
                         "%s of %lld bytes at byte %lld of the view: %s", op_word(wr), (long long)n,
                         (long long)pos, strerror(err));
  return MPI_SUCCESS;
}

/* A nonblocking call: the access now, and a request already complete. */
static int iaccess(MPI_File fh, const char *fn, int wr, int where, MPI_Offset offset, void *buf, int count,
                   MPI_Datatype dt, MPI_Request *request) {
  if (!request) {
    io_file *f;
    int rc = io_file_check(fh, fn, &f);
    return rc ? rc : io_file_raise(fh, MPI_ERR_REQUEST, fn, "request is NULL");
  }
  MPI_Status st;
  int rc = data_access(fh, fn, wr, where, INDEP, offset, buf, count, dt, &st);
  if (rc) return rc;
  st_rank *R = st_get();
  st_req *q = st_req_new(R);
  q->kind = RQ_RECV;
  q->state = RS_DONE;
  q->comm = MPI_COMM_NULL;
  q->fn = fn;
  q->st = st;
  *request = st_req_handle(q);
  return MPI_SUCCESS;
}

/* A split collective's begin: the whole call, its result kept for _end. */
static int begin(MPI_File fh, const char *fn, int kind, int wr, int where, MPI_Offset offset, void *buf, int count,
                 MPI_Datatype dt) {
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (f->split) return io_file_raise(fh, MPI_ERR_OTHER, fn, "a split collective call is already active on the file");
  rc = data_access(fh, fn, wr, where, COLL, offset, buf, count, dt, &f->split_st);
  if (rc == MPI_SUCCESS) f->split = kind;
  return rc;
}

static int end(MPI_File fh, const char *fn, int kind, MPI_Status *st) {
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (f->split != kind)
    return io_file_raise(fh, MPI_ERR_OTHER, fn, "%s", f->split ? "the active split collective is another one"
                                                                  : "no split collective call is active on the file");
  f->split = 0;
  if (st != MPI_STATUS_IGNORE) *st = f->split_st;
  return MPI_SUCCESS;
}

/* ==== the calls =========================================================== */

#define CB(x) ((void *)(uintptr_t)(x))   /* a const buffer where a write takes it */

int PMPI_File_read(MPI_File fh, void *buf, int count, MPI_Datatype datatype, MPI_Status *status) {
  return data_access(fh, "MPI_File_read", RD, INDIV, INDEP, 0, buf, count, datatype, status);
}
int PMPI_File_read_all(MPI_File fh, void *buf, int count, MPI_Datatype datatype, MPI_Status *status) {
  return data_access(fh, "MPI_File_read_all", RD, INDIV, COLL, 0, buf, count, datatype, status);
}
int PMPI_File_read_at(MPI_File fh, MPI_Offset offset, void *buf, int count, MPI_Datatype datatype,
                      MPI_Status *status) {
  return data_access(fh, "MPI_File_read_at", RD, AT, INDEP, offset, buf, count, datatype, status);
}
int PMPI_File_read_at_all(MPI_File fh, MPI_Offset offset, void *buf, int count, MPI_Datatype datatype,
                          MPI_Status *status) {
  return data_access(fh, "MPI_File_read_at_all", RD, AT, COLL, offset, buf, count, datatype, status);
}
int PMPI_File_read_shared(MPI_File fh, void *buf, int count, MPI_Datatype datatype, MPI_Status *status) {
  return data_access(fh, "MPI_File_read_shared", RD, SHARED, INDEP, 0, buf, count, datatype, status);
}
int PMPI_File_read_ordered(MPI_File fh, void *buf, int count, MPI_Datatype datatype, MPI_Status *status) {
  return data_access(fh, "MPI_File_read_ordered", RD, ORDERED, COLL, 0, buf, count, datatype, status);
}
int PMPI_File_write(MPI_File fh, const void *buf, int count, MPI_Datatype datatype, MPI_Status *status) {
  return data_access(fh, "MPI_File_write", WR, INDIV, INDEP, 0, CB(buf), count, datatype, status);
}
int PMPI_File_write_all(MPI_File fh, const void *buf, int count, MPI_Datatype datatype, MPI_Status *status) {
  return data_access(fh, "MPI_File_write_all", WR, INDIV, COLL, 0, CB(buf), count, datatype, status);
}
int PMPI_File_write_at(MPI_File fh, MPI_Offset offset, const void *buf, int count, MPI_Datatype datatype,
                       MPI_Status *status) {
  return data_access(fh, "MPI_File_write_at", WR, AT, INDEP, offset, CB(buf), count, datatype, status);
}
int PMPI_File_write_at_all(MPI_File fh, MPI_Offset offset, const void *buf, int count, MPI_Datatype datatype,
                           MPI_Status *status) {
  return data_access(fh, "MPI_File_write_at_all", WR, AT, COLL, offset, CB(buf), count, datatype, status);
}
int PMPI_File_write_shared(MPI_File fh, const void *buf, int count, MPI_Datatype datatype, MPI_Status *status) {
  return data_access(fh, "MPI_File_write_shared", WR, SHARED, INDEP, 0, CB(buf), count, datatype, status);
}
int PMPI_File_write_ordered(MPI_File fh, const void *buf, int count, MPI_Datatype datatype, MPI_Status *status) {
  return data_access(fh, "MPI_File_write_ordered", WR, ORDERED, COLL, 0, CB(buf), count, datatype, status);
}

/* Nonblocking. */
int PMPI_File_iread(MPI_File fh, void *buf, int count, MPI_Datatype datatype, MPI_Request *request) {
  return iaccess(fh, "MPI_File_iread", RD, INDIV, 0, buf, count, datatype, request);
}
int PMPI_File_iread_all(MPI_File fh, void *buf, int count, MPI_Datatype datatype, MPI_Request *request) {
  return iaccess(fh, "MPI_File_iread_all", RD, INDIV, 0, buf, count, datatype, request);
}
int PMPI_File_iread_at(MPI_File fh, MPI_Offset offset, void *buf, int count, MPI_Datatype datatype,
                       MPI_Request *request) {
  return iaccess(fh, "MPI_File_iread_at", RD, AT, offset, buf, count, datatype, request);
}
int PMPI_File_iread_at_all(MPI_File fh, MPI_Offset offset, void *buf, int count, MPI_Datatype datatype,
                           MPI_Request *request) {
  return iaccess(fh, "MPI_File_iread_at_all", RD, AT, offset, buf, count, datatype, request);
}
int PMPI_File_iread_shared(MPI_File fh, void *buf, int count, MPI_Datatype datatype, MPI_Request *request) {
  return iaccess(fh, "MPI_File_iread_shared", RD, SHARED, 0, buf, count, datatype, request);
}
int PMPI_File_iwrite(MPI_File fh, const void *buf, int count, MPI_Datatype datatype, MPI_Request *request) {
  return iaccess(fh, "MPI_File_iwrite", WR, INDIV, 0, CB(buf), count, datatype, request);
}
int PMPI_File_iwrite_all(MPI_File fh, const void *buf, int count, MPI_Datatype datatype, MPI_Request *request) {
  return iaccess(fh, "MPI_File_iwrite_all", WR, INDIV, 0, CB(buf), count, datatype, request);
}
int PMPI_File_iwrite_at(MPI_File fh, MPI_Offset offset, const void *buf, int count, MPI_Datatype datatype,
                        MPI_Request *request) {
  return iaccess(fh, "MPI_File_iwrite_at", WR, AT, offset, CB(buf), count, datatype, request);
}
int PMPI_File_iwrite_at_all(MPI_File fh, MPI_Offset offset, const void *buf, int count, MPI_Datatype datatype,
                            MPI_Request *request) {
  return iaccess(fh, "MPI_File_iwrite_at_all", WR, AT, offset, CB(buf), count, datatype, request);
}
int PMPI_File_iwrite_shared(MPI_File fh, const void *buf, int count, MPI_Datatype datatype, MPI_Request *request) {
  return iaccess(fh, "MPI_File_iwrite_shared", WR, SHARED, 0, CB(buf), count, datatype, request);
}

/* Split collectives. */
enum { S_READ_ALL = 1, S_READ_AT_ALL, S_READ_ORDERED, S_WRITE_ALL, S_WRITE_AT_ALL, S_WRITE_ORDERED };

int PMPI_File_read_all_begin(MPI_File fh, void *buf, int count, MPI_Datatype datatype) {
  return begin(fh, "MPI_File_read_all_begin", S_READ_ALL, RD, INDIV, 0, buf, count, datatype);
}
int PMPI_File_read_all_end(MPI_File fh, void *buf, MPI_Status *status) {
  (void)buf;
  return end(fh, "MPI_File_read_all_end", S_READ_ALL, status);
}
int PMPI_File_read_at_all_begin(MPI_File fh, MPI_Offset offset, void *buf, int count, MPI_Datatype datatype) {
  return begin(fh, "MPI_File_read_at_all_begin", S_READ_AT_ALL, RD, AT, offset, buf, count, datatype);
}
int PMPI_File_read_at_all_end(MPI_File fh, void *buf, MPI_Status *status) {
  (void)buf;
  return end(fh, "MPI_File_read_at_all_end", S_READ_AT_ALL, status);
}
int PMPI_File_read_ordered_begin(MPI_File fh, void *buf, int count, MPI_Datatype datatype) {
  return begin(fh, "MPI_File_read_ordered_begin", S_READ_ORDERED, RD, ORDERED, 0, buf, count, datatype);
}
int PMPI_File_read_ordered_end(MPI_File fh, void *buf, MPI_Status *status) {
  (void)buf;
  return end(fh, "MPI_File_read_ordered_end", S_READ_ORDERED, status);
}
int PMPI_File_write_all_begin(MPI_File fh, const void *buf, int count, MPI_Datatype datatype) {
  return begin(fh, "MPI_File_write_all_begin", S_WRITE_ALL, WR, INDIV, 0, CB(buf), count, datatype);
}
int PMPI_File_write_all_end(MPI_File fh, const void *buf, MPI_Status *status) {
  (void)buf;
  return end(fh, "MPI_File_write_all_end", S_WRITE_ALL, status);
}
int PMPI_File_write_at_all_begin(MPI_File fh, MPI_Offset offset, const void *buf, int count,
                                 MPI_Datatype datatype) {
  return begin(fh, "MPI_File_write_at_all_begin", S_WRITE_AT_ALL, WR, AT, offset, CB(buf), count, datatype);
}
int PMPI_File_write_at_all_end(MPI_File fh, const void *buf, MPI_Status *status) {
  (void)buf;
  return end(fh, "MPI_File_write_at_all_end", S_WRITE_AT_ALL, status);
}
int PMPI_File_write_ordered_begin(MPI_File fh, const void *buf, int count, MPI_Datatype datatype) {
  return begin(fh, "MPI_File_write_ordered_begin", S_WRITE_ORDERED, WR, ORDERED, 0, CB(buf), count, datatype);
}
int PMPI_File_write_ordered_end(MPI_File fh, const void *buf, MPI_Status *status) {
  (void)buf;
  return end(fh, "MPI_File_write_ordered_end", S_WRITE_ORDERED, status);
}
