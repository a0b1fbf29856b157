/* io.c -- MPI-IO's files: the rank's table, the shared object of an open, opening and closing,
 * errors under a file's handler, and the time each access costs (io.h). */
#include "mpi/io.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mpi/coll.h"
#include "mpi/coll_sched.h"
#include "mpi/dtype.h"
#include "mpi/err.h"
#include "mpi/errh.h"
#include "mp/mp.h"
#include "mpi/core.h"
#include "mpi/state.h"

/* ==== the rank's table ==================================================== */

enum { CREATED = 0x09800000, SLOT_MASK = 0x7fffff };

typedef struct {
  io_file **slot;
  int n;
  MPI_Errhandler null_eh;  /* MPI_FILE_NULL's handler */
} table;

static void release(io_file *f);

static void table_release(void *p) {
  table *tb = p;
  for (int i = 0; i < tb->n; i++)
    if (tb->slot[i]) release(tb->slot[i]);   /* files left open at the rank's end */
  errh_drop(st_get(), tb->null_eh);
  free(tb->slot);
  free(tb);
  io_fs_leave();
}

static table *tab(int create) {
  table *tb = st_part(ST_PART_IO);
  if (tb || !create) return tb;
  tb = calloc(1, sizeof *tb);
  if (!tb) return NULL;
  tb->null_eh = MPI_ERRORS_RETURN;
  st_part_set(ST_PART_IO, tb, table_release);
  io_fs_enter();
  return tb;
}

void io_begin(void) { tab(1); }

io_file *io_file_get(MPI_File fh) {
  if (((unsigned)fh & 0xff800000u) != CREATED) return NULL;
  table *tb = tab(0);
  int i = fh & SLOT_MASK;
  return tb && i < tb->n ? tb->slot[i] : NULL;
}

MPI_Errhandler io_file_null_eh(void) {
  table *tb = tab(0);
  return tb ? tb->null_eh : MPI_ERRORS_RETURN;
}

void io_file_set_null_eh(MPI_Errhandler eh) {
  table *tb = tab(1);
  if (!tb) return;
  errh_set(st_get(), &tb->null_eh, eh);
}

/* ==== errors ============================================================== */

int io_file_raise(MPI_File fh, int cls, const char *fn, const char *fmt, ...) {
  io_file *f = io_file_get(fh);
  MPI_Errhandler eh = f ? f->eh : io_file_null_eh();
  char msg[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return err_raise_on(st_need(fn), eh, f ? fh : MPI_FILE_NULL, cls, fn, "%s", msg);
}

int io_file_check(MPI_File fh, const char *fn, io_file **f) {
  *f = io_file_get(fh);
  if (*f) return MPI_SUCCESS;
  return io_file_raise(MPI_FILE_NULL, MPI_ERR_FILE, fn, "%s",
                       fh == MPI_FILE_NULL ? "MPI_FILE_NULL is not an open file"
                                              : "not a file of this rank (closed?)");
}

/* ==== time ================================================================ */

void io_until(double end) {
  mp *self = mp_self();
  double now = mp_time(self);
  if (end > now && mp_sleep(self, end - now) != MP_OK) st_stopped(st_get());
}

double io_independent(io_file *f, double bytes) {
  return io_fs_request(f->sh->fs, mp_time(mp_self()), bytes);
}

/* Every rank's pair of doubles (mine) to every rank of comm, under call
 * fn's name (what a deadlock report and the trace say): MPICH's allgather
 * for so few bytes, recursive doubling on a power of two ranks, Bruck's
 * otherwise.  Returns the pairs by rank, scratch of the collectives
 * (coll_cg_free it). */
static double *exchange(MPI_Comm comm, const char *fn, const double mine[2]) {
  coll_sched *s = coll_start(fn, comm, COLL_ALLGATHER, -1, NULL);   /* blocking: steps run as added */
  const coll_cg *g = coll_sched_group(s);
  size_t p = (size_t)g->size, *counts = coll_sched_mem(s, 2 * p * sizeof *counts), *displs = counts + p;
  double *all = coll_cg_alloc(g, 2 * p * sizeof *all);
  for (size_t r = 0; r < p; r++) counts[r] = 2 * sizeof *all, displs[r] = r * 2 * sizeof *all;
  all[2 * g->rank] = mine[0];
  all[2 * g->rank + 1] = mine[1];
  if (p > 1) {
    if (coll_is_pof2(g->size)) coll_allgatherv_recursive_doubling(s, all, counts, displs);
    else coll_allgatherv_brucks(s, all, counts, displs);
  }
  coll_finish(s);
  return all;
}

double io_collective(io_file *f, const char *fn, double bytes, MPI_Offset *base, MPI_Offset *below,
                     void (*first)(io_file *f, const double *counts, void *ud), void *ud) {
  double mine[2] = {mp_time(mp_self()), bytes}, *all = exchange(f->comm, fn, mine);
  double come = 0, sum = 0;
  for (int r = 0; r < f->size; r++) {
    if (all[2 * r] > come) come = all[2 * r];
    sum += all[2 * r + 1];
    all[r] = all[2 * r + 1];   /* the counts, in place (r <= 2 r + 1) */
    if (below && r == 0) *below = 0;
    if (below && r < f->rank) *below += (MPI_Offset)all[r];
  }
  f->cseq++;
  io_ofile *sh = f->sh;
  pthread_mutex_lock(&sh->lock);
  if (sh->cseq != f->cseq) {   /* the first past the exchange */
    if (first) first(f, all, ud);
    sh->cend = bytes < 0 ? come : io_fs_request(sh->fs, come, sum);
    sh->cseq = f->cseq;
  }
  double end = sh->cend;
  if (base) *base = sh->cbase;
  pthread_mutex_unlock(&sh->lock);
  coll_cg_free(all);
  return end;
}

/* ==== open and close ====================================================== */

static int amode_ok(int amode, const char **why) {
  int rw = !!(amode & MPI_MODE_RDONLY) + !!(amode & MPI_MODE_WRONLY) + !!(amode & MPI_MODE_RDWR);
  int known = MPI_MODE_CREATE | MPI_MODE_RDONLY | MPI_MODE_WRONLY | MPI_MODE_RDWR | MPI_MODE_DELETE_ON_CLOSE |
              MPI_MODE_UNIQUE_OPEN | MPI_MODE_EXCL | MPI_MODE_APPEND | MPI_MODE_SEQUENTIAL;
  *why = NULL;
  if (amode & ~known) *why = "an unknown MPI_MODE_ bit";
  else if (rw != 1) *why = "not exactly one of MPI_MODE_RDONLY, MPI_MODE_WRONLY and MPI_MODE_RDWR";
  else if ((amode & MPI_MODE_RDONLY) && (amode & (MPI_MODE_CREATE | MPI_MODE_EXCL)))
    *why = "MPI_MODE_RDONLY with MPI_MODE_CREATE or MPI_MODE_EXCL";
  else if ((amode & MPI_MODE_RDWR) && (amode & MPI_MODE_SEQUENTIAL)) *why = "MPI_MODE_RDWR with MPI_MODE_SEQUENTIAL";
  return *why == NULL;
}

/* errno after open(2) or unlink(2) as an MPI error class. */
static int errno_class(int e) {
  switch (e) {
  case ENOENT: case ENOTDIR: return MPI_ERR_NO_SUCH_FILE;
  case EEXIST: return MPI_ERR_FILE_EXISTS;
  case EACCES: case EPERM: return MPI_ERR_ACCESS;
  case EROFS: return MPI_ERR_READ_ONLY;
  case ENOSPC: return MPI_ERR_NO_SPACE;
  case EDQUOT: return MPI_ERR_QUOTA;
  case ENAMETOOLONG: case EISDIR: return MPI_ERR_BAD_FILE;
  case EBUSY: case ETXTBSY: return MPI_ERR_FILE_IN_USE;
  default: return MPI_ERR_IO;
  }
}

/* What rank 0 of the open tells the others. */
typedef struct {
  int cls;                 /* MPI_SUCCESS or the error */
  char why[200];
  io_ofile *sh;         /* the shared object: one process, one address */
  double end;              /* the open's request's end */
} opened;

/* Rank 0's part: the file opened and its shared object made. */
static void open_first(const char *path, int amode, double come, opened *o) {
  char host[IO_PATH_MAX];
  io_fs *fs = io_fs_of(path, host, o->why, sizeof o->why);
  if (!fs) {
    o->cls = MPI_ERR_BAD_FILE;
    return;
  }
  int flags = (amode & MPI_MODE_RDONLY ? O_RDONLY : amode & MPI_MODE_WRONLY ? O_WRONLY : O_RDWR) |
              (amode & MPI_MODE_CREATE ? O_CREAT : 0) | (amode & MPI_MODE_EXCL ? O_EXCL : 0) | O_CLOEXEC;
  int fd = open(host, flags, 0666);
  if (fd < 0) {
    int e = errno;
    o->cls = errno_class(e);
    if (strcmp(path, host))
      snprintf(o->why, sizeof o->why, "%.80s (the host's %.80s): %s", path, host, strerror(e));
    else
      snprintf(o->why, sizeof o->why, "%.160s: %s", path, strerror(e));
    return;
  }
  io_ofile *sh = calloc(1, sizeof *sh);
  if (!sh) {
    close(fd);
    o->cls = MPI_ERR_NO_MEM;
    snprintf(o->why, sizeof o->why, "out of memory");
    return;
  }
  pthread_mutex_init(&sh->lock, NULL);
  sh->fd = fd;
  sh->fs = fs;
  snprintf(sh->host, sizeof sh->host, "%s", host);
  sh->delete_on_close = !!(amode & MPI_MODE_DELETE_ON_CLOSE);
  if (amode & MPI_MODE_APPEND) {
    struct stat stt;
    if (fstat(fd, &stt) == 0) sh->shared = stt.st_size;
  }
  o->sh = sh;
  o->cls = MPI_SUCCESS;
  o->end = io_fs_request(fs, come, 0);
}

static void drop_shared(io_ofile *sh) {
  pthread_mutex_lock(&sh->lock);
  int last = --sh->refs == 0;
  pthread_mutex_unlock(&sh->lock);
  if (!last) return;
  close(sh->fd);
  if (sh->delete_on_close) unlink(sh->host);
  pthread_mutex_destroy(&sh->lock);
  free(sh);
}

static void release(io_file *f) {
  errh_drop(st_get(), f->eh);
  drop_shared(f->sh);
  io_view_free(&f->view);
  if (f->hints != MPI_INFO_NULL) PMPI_Info_free(&f->hints);
  free(f);
}

int io_file_open(MPI_Comm comm, const char *path, int amode, MPI_Info info, MPI_File *fh) {
  static const char fn[] = "MPI_File_open";
  table *tb = tab(1);
  if (!tb) return err_comm_raise(comm, MPI_ERR_NO_MEM, fn, "out of memory");
  const char *bad;
  int size, rank, rc;
  PMPI_Comm_size(comm, &size);
  PMPI_Comm_rank(comm, &rank);
  /* Every rank's amode and arrival, then rank 0's open. */
  double mine[2] = {mp_time(mp_self()), amode}, *all;
  MPI_Comm dup;
  if ((rc = PMPI_Comm_dup(comm, &dup)) != MPI_SUCCESS) return rc;
  all = exchange(dup, fn, mine);
  double come = 0;
  int same = 1;
  for (int r = 0; r < size; r++) {
    if (all[2 * r] > come) come = all[2 * r];
    same &= all[2 * r + 1] == amode;
  }
  coll_cg_free(all);
  opened o = {0};
  if (!same) {   /* the checks every rank makes alike */
    o.cls = MPI_ERR_NOT_SAME;
    snprintf(o.why, sizeof o.why, "the ranks of the communicator gave different amodes");
  } else if (!amode_ok(amode, &bad)) {
    o.cls = MPI_ERR_AMODE;
    snprintf(o.why, sizeof o.why, "amode 0x%x: %s", (unsigned)amode, bad);
  } else {
    if (rank == 0) open_first(path, amode, come, &o);
    PMPI_Bcast(&o, (int)sizeof o, MPI_BYTE, 0, dup);
  }
  if (o.cls != MPI_SUCCESS) {
    PMPI_Comm_free(&dup);
    return io_file_raise(MPI_FILE_NULL, o.cls, fn, "%s", o.why);
  }
  pthread_mutex_lock(&o.sh->lock);
  o.sh->refs++;
  pthread_mutex_unlock(&o.sh->lock);
  int slot = 0;
  while (slot < tb->n && tb->slot[slot]) slot++;
  io_file *f = calloc(1, sizeof *f);
  if (f && slot == tb->n && slot <= SLOT_MASK) {
    io_file **s = realloc(tb->slot, ((size_t)tb->n + 1) * sizeof *s);
    if (s) tb->slot = s, tb->slot[tb->n++] = NULL;
  }
  if (!f || slot >= tb->n) {
    free(f);
    drop_shared(o.sh);
    PMPI_Comm_free(&dup);
    return io_file_raise(MPI_FILE_NULL, MPI_ERR_NO_MEM, fn, "out of memory for a file");
  }
  f->sh = o.sh;
  f->comm = dup;
  f->rank = rank;
  f->size = size;
  f->amode = amode;
  f->eh = MPI_ERRORS_RETURN;
  f->hints = MPI_INFO_NULL;
  f->pos = o.sh->shared;   /* 0, or the end of the file (MPI_MODE_APPEND) */
  io_view_default(&f->view);
  if (info != MPI_INFO_NULL) PMPI_Info_dup(info, &f->hints);
  tb->slot[slot] = f;
  *fh = (MPI_File)(CREATED | slot);
  io_until(o.end);
  return MPI_SUCCESS;
}

static void no_first(io_file *f, const double *counts, void *ud) {
  (void)f, (void)counts, (void)ud;
}

int io_file_close(MPI_File *fh) {
  io_file *f = io_file_get(*fh);
  double end = io_collective(f, "MPI_File_close", 0, NULL, NULL, no_first, NULL);
  table *tb = tab(0);
  tb->slot[*fh & SLOT_MASK] = NULL;
  MPI_Comm c = f->comm;
  release(f);
  PMPI_Comm_free(&c);
  *fh = MPI_FILE_NULL;
  io_until(end);
  return MPI_SUCCESS;
}
