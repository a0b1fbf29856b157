/* io_api.c -- MPI-IO's file management (MPI 3.1 sections 13.2, 13.3, 13.4.4, 13.5, 13.6,
 * 13.7): open, close, delete, size, preallocation, sync, views, file pointers, queries,
 * atomicity, hints and error handlers (mpi.h; built on io.h, io_view.h, io_model.h).
 *
 * open, close, set_view, set_size, preallocate, sync, set_atomicity, set_info and
 * seek_shared are collective over the file's ranks; set_size, preallocate and sync each make
 * one request of no bytes on the storage model (io_model.h), as open and close do, delete and
 * get_size an independent one.  Hints are accepted and kept (MPI_File_get_info gives back
 * those given); none changes what tilesim does. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mpi/dtype.h"
#include "mpi/errh.h"
#include "mpi/io.h"
#include "mp/mp.h"
#include "mpi/core.h"

/* ==== open, close, delete ================================================= */

int PMPI_File_open(MPI_Comm comm, const char *filename, int amode, MPI_Info info, MPI_File *fh) {
  static const char fn[] = "MPI_File_open";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  int inter = 0;
  PMPI_Comm_test_inter(comm, &inter);
  if (inter) return err_comm_raise(comm, MPI_ERR_COMM, fn, "an intercommunicator (MPI 3.1: an intracommunicator)");
  if (!filename) return io_file_raise(MPI_FILE_NULL, MPI_ERR_ARG, fn, "filename is NULL");
  if (!fh) return io_file_raise(MPI_FILE_NULL, MPI_ERR_ARG, fn, "fh is NULL");
  return io_file_open(comm, filename, amode, info, fh);
}

int PMPI_File_close(MPI_File *fh) {
  static const char fn[] = "MPI_File_close";
  io_file *f;
  if (!fh) return io_file_raise(MPI_FILE_NULL, MPI_ERR_ARG, fn, "fh is NULL");
  int rc = io_file_check(*fh, fn, &f);
  if (rc) return rc;
  if (f->split) return io_file_raise(*fh, MPI_ERR_OTHER, fn, "a split collective call is still active");
  return io_file_close(fh);
}

int PMPI_File_delete(const char *filename, MPI_Info info) {
  static const char fn[] = "MPI_File_delete";
  char host[IO_PATH_MAX], why[160];
  (void)info;
  if (!filename) return io_file_raise(MPI_FILE_NULL, MPI_ERR_ARG, fn, "filename is NULL");
  io_begin();
  io_fs *fs = io_fs_of(filename, host, why, sizeof why);
  if (!fs) return io_file_raise(MPI_FILE_NULL, MPI_ERR_BAD_FILE, fn, "%s", why);
  int err = unlink(host) == 0 ? 0 : errno;
  io_until(io_fs_request(fs, mp_time(mp_self()), 0));
  if (err)
    return io_file_raise(MPI_FILE_NULL, err == ENOENT ? MPI_ERR_NO_SUCH_FILE : err == EACCES ? MPI_ERR_ACCESS
                                                                                                  : MPI_ERR_IO,
                            fn, "%.200s: %s", filename, strerror(err));
  return MPI_SUCCESS;
}

/* ==== size, preallocation, sync =========================================== */

typedef struct {
  MPI_Offset size;
  int grow_only;           /* preallocate: only make it larger */
  int err;                 /* errno of the first rank's ftruncate */
} resize;

static void resize_first(io_file *f, const double *counts, void *ud) {
  resize *z = ud;
  struct stat st;
  (void)counts;
  if (z->grow_only && fstat(f->sh->fd, &st) == 0 && st.st_size >= z->size) return;
  if (ftruncate(f->sh->fd, (off_t)z->size) != 0) z->err = errno;
}

static int resize_call(MPI_File fh, const char *fn, MPI_Offset size, int grow_only) {
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (size < 0) return io_file_raise(fh, MPI_ERR_ARG, fn, "size %lld < 0", (long long)size);
  if (f->amode & MPI_MODE_RDONLY) return io_file_raise(fh, MPI_ERR_READ_ONLY, fn, "the file is open MPI_MODE_RDONLY");
  if (f->amode & MPI_MODE_SEQUENTIAL)
    return io_file_raise(fh, MPI_ERR_UNSUPPORTED_OPERATION, fn, "the file is open MPI_MODE_SEQUENTIAL");
  resize z = {size, grow_only, 0};
  io_until(io_collective(f, fn, 0, NULL, NULL, resize_first, &z));
  if (z.err) return io_file_raise(fh, MPI_ERR_IO, fn, "to %lld bytes: %s", (long long)size, strerror(z.err));
  return MPI_SUCCESS;
}

int PMPI_File_set_size(MPI_File fh, MPI_Offset size) {
  return resize_call(fh, "MPI_File_set_size", size, 0);
}

int PMPI_File_preallocate(MPI_File fh, MPI_Offset size) {
  return resize_call(fh, "MPI_File_preallocate", size, 1);
}

int PMPI_File_get_size(MPI_File fh, MPI_Offset *size) {
  static const char fn[] = "MPI_File_get_size";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (!size) return io_file_raise(fh, MPI_ERR_ARG, fn, "size is NULL");
  struct stat st;
  if (fstat(f->sh->fd, &st) != 0) return io_file_raise(fh, MPI_ERR_IO, fn, "%s", strerror(errno));
  *size = st.st_size;
  io_until(io_independent(f, 0));
  return MPI_SUCCESS;
}

int PMPI_File_sync(MPI_File fh) {
  static const char fn[] = "MPI_File_sync";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  /* The data are in the host's file since each write; the host's cache
   * is not flushed (a request of the model all the same). */
  io_until(io_collective(f, fn, 0, NULL, NULL, NULL, NULL));
  return MPI_SUCCESS;
}

/* ==== views =============================================================== */

/* The shared file pointer's one-time move (set_view, seek_shared). */
static void seek_shared_first(io_file *f, const double *counts, void *ud) {
  (void)counts;
  f->sh->shared = *(MPI_Offset *)ud;
}

int PMPI_File_set_view(MPI_File fh, MPI_Offset disp, MPI_Datatype etype, MPI_Datatype filetype,
                       const char *datarep, MPI_Info info) {
  static const char fn[] = "MPI_File_set_view";
  io_file *f;
  char why[160];
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (!datarep) return io_file_raise(fh, MPI_ERR_ARG, fn, "datarep is NULL");
  if (f->split) return io_file_raise(fh, MPI_ERR_OTHER, fn, "a split collective call is active");
  if (disp == MPI_DISPLACEMENT_CURRENT) {
    if (!(f->amode & MPI_MODE_SEQUENTIAL))
      return io_file_raise(fh, MPI_ERR_ARG, fn, "MPI_DISPLACEMENT_CURRENT needs MPI_MODE_SEQUENTIAL");
    disp = io_view_byte(&f->view, f->sh->shared * f->view.esize);
  }
  rc = io_view_set(&f->view, disp, etype, filetype, datarep, why, sizeof why);
  if (rc) return io_file_raise(fh, rc, fn, "%s", why);
  /* MPI 3.1 section 13.3: both file pointers go back to 0, the shared one
   * once, before any rank goes on. */
  f->pos = 0;
  MPI_Offset zero = 0;
  io_collective(f, fn, -1, NULL, NULL, seek_shared_first, &zero);
  if (info != MPI_INFO_NULL) return PMPI_File_set_info(fh, info);
  return MPI_SUCCESS;
}

/* A type for the program: predefined ones as they are, others duplicated
 * (the program frees them, MPI 3.1 section 13.3). */
static MPI_Datatype give(MPI_Datatype dt) {
  int ni, na, nd, comb;
  PMPI_Type_get_envelope(dt, &ni, &na, &nd, &comb);
  if (comb == MPI_COMBINER_NAMED) return dt;
  MPI_Datatype d = MPI_DATATYPE_NULL;
  PMPI_Type_dup(dt, &d);
  return d;
}

int PMPI_File_get_view(MPI_File fh, MPI_Offset *disp, MPI_Datatype *etype, MPI_Datatype *filetype, char *datarep) {
  static const char fn[] = "MPI_File_get_view";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (!disp || !etype || !filetype || !datarep) return io_file_raise(fh, MPI_ERR_ARG, fn, "an argument is NULL");
  *disp = f->view.disp;
  *etype = give(f->view.etype);
  *filetype = give(f->view.ftype);
  snprintf(datarep, MPI_MAX_DATAREP_STRING, "%s", f->view.datarep);
  return MPI_SUCCESS;
}

int PMPI_File_get_type_extent(MPI_File fh, MPI_Datatype datatype, MPI_Aint *extent) {
  static const char fn[] = "MPI_File_get_type_extent";
  io_file *f;
  char why[96];
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (dtype_valid(datatype, why, sizeof why) != MPI_SUCCESS)
    return io_file_raise(fh, MPI_ERR_TYPE, fn, "invalid datatype: %s", why);
  if (!extent) return io_file_raise(fh, MPI_ERR_ARG, fn, "extent is NULL");
  *extent = dtype_extent(datatype);   /* native: as in memory */
  return MPI_SUCCESS;
}

/* ==== file pointers ======================================================= */

/* The etype offset a seek reaches from cur (the pointer's) and the end of
 * the file as the view sees it. */
static int seek_to(MPI_File fh, const char *fn, io_file *f, MPI_Offset cur, MPI_Offset offset, int whence,
                   MPI_Offset *to) {
  MPI_Offset base = 0;
  if (whence == MPI_SEEK_SET) {
    base = 0;
  } else if (whence == MPI_SEEK_CUR) {
    base = cur;
  } else if (whence == MPI_SEEK_END) {
    struct stat st;
    if (fstat(f->sh->fd, &st) != 0) return io_file_raise(fh, MPI_ERR_IO, fn, "%s", strerror(errno));
    base = io_view_stream(&f->view, st.st_size) / f->view.esize;
  } else {
    return io_file_raise(fh, MPI_ERR_ARG, fn, "whence %d is none of MPI_SEEK_SET, _CUR, _END", whence);
  }
  if (base + offset < 0)
    return io_file_raise(fh, MPI_ERR_ARG, fn, "the pointer would go to %lld etypes, before the view's start",
                         (long long)(base + offset));
  *to = base + offset;
  return MPI_SUCCESS;
}

int PMPI_File_seek(MPI_File fh, MPI_Offset offset, int whence) {
  static const char fn[] = "MPI_File_seek";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (f->amode & MPI_MODE_SEQUENTIAL)
    return io_file_raise(fh, MPI_ERR_UNSUPPORTED_OPERATION, fn, "the file is open MPI_MODE_SEQUENTIAL");
  return seek_to(fh, fn, f, f->pos, offset, whence, &f->pos);
}

int PMPI_File_get_position(MPI_File fh, MPI_Offset *offset) {
  static const char fn[] = "MPI_File_get_position";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (!offset) return io_file_raise(fh, MPI_ERR_ARG, fn, "offset is NULL");
  *offset = f->pos;
  return MPI_SUCCESS;
}

int PMPI_File_seek_shared(MPI_File fh, MPI_Offset offset, int whence) {
  static const char fn[] = "MPI_File_seek_shared";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  pthread_mutex_lock(&f->sh->lock);
  MPI_Offset cur = f->sh->shared, to = 0;
  pthread_mutex_unlock(&f->sh->lock);
  if ((rc = seek_to(fh, fn, f, cur, offset, whence, &to))) return rc;
  /* Collective: the pointer moves once, before any rank goes on. */
  io_collective(f, fn, -1, NULL, NULL, seek_shared_first, &to);
  return MPI_SUCCESS;
}

int PMPI_File_get_position_shared(MPI_File fh, MPI_Offset *offset) {
  static const char fn[] = "MPI_File_get_position_shared";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (!offset) return io_file_raise(fh, MPI_ERR_ARG, fn, "offset is NULL");
  pthread_mutex_lock(&f->sh->lock);
  *offset = f->sh->shared;
  pthread_mutex_unlock(&f->sh->lock);
  return MPI_SUCCESS;
}

int PMPI_File_get_byte_offset(MPI_File fh, MPI_Offset offset, MPI_Offset *disp) {
  static const char fn[] = "MPI_File_get_byte_offset";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (!disp) return io_file_raise(fh, MPI_ERR_ARG, fn, "disp is NULL");
  if (offset < 0) return io_file_raise(fh, MPI_ERR_ARG, fn, "offset %lld < 0", (long long)offset);
  *disp = io_view_byte(&f->view, offset * f->view.esize);
  return MPI_SUCCESS;
}

/* ==== queries, atomicity, hints =========================================== */

int PMPI_File_get_amode(MPI_File fh, int *amode) {
  io_file *f;
  int rc = io_file_check(fh, "MPI_File_get_amode", &f);
  if (rc) return rc;
  if (!amode) return io_file_raise(fh, MPI_ERR_ARG, "MPI_File_get_amode", "amode is NULL");
  *amode = f->amode;
  return MPI_SUCCESS;
}

int PMPI_File_get_group(MPI_File fh, MPI_Group *group) {
  io_file *f;
  int rc = io_file_check(fh, "MPI_File_get_group", &f);
  if (rc) return rc;
  if (!group) return io_file_raise(fh, MPI_ERR_ARG, "MPI_File_get_group", "group is NULL");
  return PMPI_Comm_group(f->comm, group);
}

static void atomic_first(io_file *f, const double *counts, void *ud) {
  (void)counts;
  f->sh->atomic = *(int *)ud;
}

int PMPI_File_set_atomicity(MPI_File fh, int flag) {
  static const char fn[] = "MPI_File_set_atomicity";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  int on = flag != 0;
  io_collective(f, fn, -1, NULL, NULL, atomic_first, &on);
  return MPI_SUCCESS;
}

int PMPI_File_get_atomicity(MPI_File fh, int *flag) {
  io_file *f;
  int rc = io_file_check(fh, "MPI_File_get_atomicity", &f);
  if (rc) return rc;
  if (!flag) return io_file_raise(fh, MPI_ERR_ARG, "MPI_File_get_atomicity", "flag is NULL");
  pthread_mutex_lock(&f->sh->lock);
  *flag = f->sh->atomic;
  pthread_mutex_unlock(&f->sh->lock);
  return MPI_SUCCESS;
}

int PMPI_File_set_info(MPI_File fh, MPI_Info info) {
  static const char fn[] = "MPI_File_set_info";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (info == MPI_INFO_NULL) return MPI_SUCCESS;
  /* The hints given are kept, later ones over earlier ones. */
  int n = 0;
  if ((rc = PMPI_Info_get_nkeys(info, &n))) return io_file_raise(fh, rc, fn, "invalid info");
  if (f->hints == MPI_INFO_NULL) PMPI_Info_create(&f->hints);
  for (int i = 0; i < n; i++) {
    char key[MPI_MAX_INFO_KEY + 1], val[MPI_MAX_INFO_VAL + 1];
    int flag = 0;
    PMPI_Info_get_nthkey(info, i, key);
    PMPI_Info_get(info, key, MPI_MAX_INFO_VAL, val, &flag);
    if (flag) PMPI_Info_set(f->hints, key, val);
  }
  return MPI_SUCCESS;
}

int PMPI_File_get_info(MPI_File fh, MPI_Info *info_used) {
  static const char fn[] = "MPI_File_get_info";
  io_file *f;
  int rc = io_file_check(fh, fn, &f);
  if (rc) return rc;
  if (!info_used) return io_file_raise(fh, MPI_ERR_ARG, fn, "info_used is NULL");
  if (f->hints == MPI_INFO_NULL) return PMPI_Info_create(info_used);
  return PMPI_Info_dup(f->hints, info_used);
}

/* ==== error handlers ====================================================== */

int PMPI_File_set_errhandler(MPI_File file, MPI_Errhandler errhandler) {
  static const char fn[] = "MPI_File_set_errhandler";
  char why[96];
  io_file *f = NULL;
  if (file != MPI_FILE_NULL) {
    int rc = io_file_check(file, fn, &f);
    if (rc) return rc;
  }
  if (errh_check(st_need(fn), errhandler, ERRH_FILE, why)) return io_file_raise(file, MPI_ERR_ARG, fn, "%s", why);
  if (!f) {
    io_file_set_null_eh(errhandler);
    return MPI_SUCCESS;
  }
  errh_set(st_get(), &f->eh, errhandler);
  return MPI_SUCCESS;
}

int PMPI_File_get_errhandler(MPI_File file, MPI_Errhandler *errhandler) {
  static const char fn[] = "MPI_File_get_errhandler";
  if (!errhandler) return io_file_raise(file, MPI_ERR_ARG, fn, "errhandler is NULL");
  /* The handle given is the program's to free, as MPI_Comm_get_errhandler's. */
  if (file == MPI_FILE_NULL) {
    *errhandler = io_file_null_eh();
  } else {
    io_file *f;
    int rc = io_file_check(file, fn, &f);
    if (rc) return rc;
    *errhandler = f->eh;
  }
  errh_hold(st_get(), *errhandler);
  return MPI_SUCCESS;
}

int PMPI_File_call_errhandler(MPI_File fh, int errorcode) {
  if (fh != MPI_FILE_NULL && !io_file_get(fh))
    return io_file_raise(MPI_FILE_NULL, MPI_ERR_FILE, "MPI_File_call_errhandler", "not a file of this rank");
  io_file_raise(fh, errorcode, "MPI_File_call_errhandler", "error code %d", errorcode);
  return MPI_SUCCESS;
}
