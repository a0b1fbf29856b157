/* io_files.c -- MPI-IO's files and independent access (MPI 3.1 chapter 13), checked against
 * the bytes plain C reads from the host's files: open (its errors), close, delete, the access
 * modes (create, exclusive, read-only, write-only, append, delete on close), explicit-offset
 * and individual-pointer reads and writes of every rank, seeks, positions and byte offsets,
 * reads past the end, sizes (set, preallocate, get), sync, atomicity, the amode and group
 * queries, the default error handler, a handler of the program's (called, kept after
 * MPI_Errhandler_free, given back, called by MPI_File_call_errhandler), hints, and nonblocking
 * reads and writes completed by MPI_Wait and MPI_Test.
 *
 * Plain MPI C: it builds with tilesim's mpi.h and with Open MPI's mpicc, and prints the same
 * "io_files: P passed, F failed" line under both (Open MPI's ROMIO and OMPIO alike). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "iotest.h"
#include "mtest.h"

static int cls(int rc) {
  int c;
  MPI_Error_class(rc, &c);
  return c;
}

/* Each rank's 8-byte record: "r00:abcd", "r01:abcd", ... */
static void record(int rank, char *out) {
  char tmp[16];
  snprintf(tmp, sizeof tmp, "r%02d:abcd", rank % 100);
  memcpy(out, tmp, 8);
}

static void test_open_errors(mtest *t, const iotest *io) {
  char p[640];
  MPI_File fh;
  int rc = MPI_File_open(MPI_COMM_WORLD, iotest_path(io, "none", p, sizeof p), MPI_MODE_RDONLY, MPI_INFO_NULL, &fh);
  MCHECK(t, cls(rc) == MPI_ERR_NO_SUCH_FILE, "opening a missing file: class %d", cls(rc));
  rc = MPI_File_open(MPI_COMM_WORLD, iotest_path(io, "a", p, sizeof p), MPI_MODE_RDONLY | MPI_MODE_CREATE,
                     MPI_INFO_NULL, &fh);
  MCHECK(t, cls(rc) == MPI_ERR_AMODE, "MPI_MODE_RDONLY | MPI_MODE_CREATE: class %d", cls(rc));
  rc = MPI_File_open(MPI_COMM_WORLD, p, MPI_MODE_RDWR | MPI_MODE_WRONLY, MPI_INFO_NULL, &fh);
  MCHECK(t, cls(rc) == MPI_ERR_AMODE, "MPI_MODE_RDWR | MPI_MODE_WRONLY: class %d", cls(rc));
  MPI_Errhandler eh;
  MPI_File_get_errhandler(MPI_FILE_NULL, &eh);
  MCHECK(t, eh == MPI_ERRORS_RETURN, "MPI_FILE_NULL's handler is not MPI_ERRORS_RETURN");
}

/* Every rank writes its record at rank * 8, then the file as C sees it. */
static void test_records(mtest *t, const iotest *io) {
  char p[640], rec[8], all[64 * 8 + 8];
  MPI_File fh;
  int rc = MPI_File_open(MPI_COMM_WORLD, iotest_path(io, "a", p, sizeof p), MPI_MODE_CREATE | MPI_MODE_EXCL |
                         MPI_MODE_WRONLY, MPI_INFO_NULL, &fh);
  MCHECK(t, rc == MPI_SUCCESS, "create a: rc %d", rc);
  if (rc) return;
  MPI_Errhandler eh;
  MPI_File_get_errhandler(fh, &eh);
  MCHECK(t, eh == MPI_ERRORS_RETURN, "a file's handler is not MPI_ERRORS_RETURN");
  record(t->rank, rec);
  MPI_Status st;
  int n = -1;
  rc = MPI_File_write_at(fh, (MPI_Offset)t->rank * 8, rec, 8, MPI_CHAR, &st);
  MPI_Get_count(&st, MPI_CHAR, &n);
  MCHECK(t, rc == MPI_SUCCESS && n == 8, "write_at: rc %d, count %d", rc, n);
  char in[8];
  rc = MPI_File_read_at(fh, 0, in, 8, MPI_CHAR, &st);
  MCHECK(t, cls(rc) == MPI_ERR_ACCESS, "a read of a write-only file: class %d", cls(rc));
  int amode;
  MPI_File_get_amode(fh, &amode);
  MCHECK(t, amode == (MPI_MODE_CREATE | MPI_MODE_EXCL | MPI_MODE_WRONLY), "amode %d", amode);
  MPI_Group g;
  MPI_File_get_group(fh, &g);
  mtest_world_group(t, g, "the file's group");
  rc = MPI_File_close(&fh);
  MCHECK(t, rc == MPI_SUCCESS && fh == MPI_FILE_NULL, "close: rc %d", rc);
  MPI_Barrier(MPI_COMM_WORLD);
  long got = iotest_read(io, "a", all, sizeof all);
  int bad = got != 8L * t->size;
  for (int r = 0; r < t->size && !bad; r++) {
    record(r, rec);
    bad = memcmp(all + 8 * r, rec, 8) != 0;
  }
  MCHECK(t, !bad, "the file a as C reads it: %ld bytes (want %d)", got, 8 * t->size);
  rc = MPI_File_open(MPI_COMM_WORLD, p, MPI_MODE_CREATE | MPI_MODE_EXCL | MPI_MODE_RDWR, MPI_INFO_NULL, &fh);
  MCHECK(t, cls(rc) == MPI_ERR_FILE_EXISTS, "MPI_MODE_EXCL on an existing file: class %d", cls(rc));
}

/* Reads, pointers, sizes on the file of records. */
static void test_pointers(mtest *t, const iotest *io) {
  char p[640], buf[16];
  MPI_File fh;
  MPI_Status st;
  int n = -1, rc = MPI_File_open(MPI_COMM_WORLD, iotest_path(io, "a", p, sizeof p), MPI_MODE_RDONLY, MPI_INFO_NULL,
                                 &fh);
  MCHECK(t, rc == MPI_SUCCESS, "open a read-only: rc %d", rc);
  if (rc) return;
  int next = (t->rank + 1) % t->size;
  char want[8];
  record(next, want);
  MPI_Offset pos = -1, byte = -1, size = -1;
  /* The individual pointer: a seek, a read, the position after. */
  MPI_File_seek(fh, (MPI_Offset)next * 8, MPI_SEEK_SET);
  rc = MPI_File_read(fh, buf, 8, MPI_CHAR, &st);
  MPI_File_get_position(fh, &pos);
  MCHECK(t, rc == MPI_SUCCESS && !memcmp(buf, want, 8) && pos == next * 8 + 8, "read at the pointer: rc %d, pos %lld",
         rc, (long long)pos);
  MPI_File_seek(fh, -4, MPI_SEEK_CUR);
  rc = MPI_File_read(fh, buf, 4, MPI_CHAR, &st);
  MPI_File_get_position(fh, &pos);
  MCHECK(t, rc == MPI_SUCCESS && !memcmp(buf, "abcd", 4) && pos == next * 8 + 8, "MPI_SEEK_CUR -4: pos %lld",
         (long long)pos);
  MPI_File_seek(fh, -3, MPI_SEEK_END);
  MPI_File_get_position(fh, &pos);
  MPI_File_get_byte_offset(fh, pos, &byte);
  MCHECK(t, pos == 8L * t->size - 3 && byte == pos, "MPI_SEEK_END -3: pos %lld, byte %lld", (long long)pos,
         (long long)byte);
  /* Past the end: what is there. */
  rc = MPI_File_read(fh, buf, 8, MPI_CHAR, &st);
  MPI_Get_count(&st, MPI_CHAR, &n);
  MCHECK(t, rc == MPI_SUCCESS && n == 3 && !memcmp(buf, "bcd", 3), "a read across the end: rc %d, count %d", rc, n);
  rc = MPI_File_read_at(fh, 8L * t->size + 100, buf, 8, MPI_CHAR, &st);
  MPI_Get_count(&st, MPI_CHAR, &n);
  MCHECK(t, rc == MPI_SUCCESS && n == 0, "a read past the end: rc %d, count %d", rc, n);
  MPI_File_get_size(fh, &size);
  MCHECK(t, size == 8L * t->size, "size %lld", (long long)size);
  rc = MPI_File_write_at(fh, 0, buf, 1, MPI_CHAR, &st);
  MCHECK(t, cls(rc) == MPI_ERR_READ_ONLY, "a write to a read-only file: class %d", cls(rc));
  rc = MPI_File_seek(fh, -1, MPI_SEEK_SET);
  MCHECK(t, rc != MPI_SUCCESS, "a seek to -1 succeeded");
  MPI_File_close(&fh);
}

/* Sizes, sync, atomicity, append, delete on close, delete. */
static void test_sizes(mtest *t, const iotest *io) {
  char p[640];
  MPI_File fh;
  MPI_Offset size = -1;
  int rc = MPI_File_open(MPI_COMM_WORLD, iotest_path(io, "a", p, sizeof p), MPI_MODE_RDWR, MPI_INFO_NULL, &fh);
  MCHECK(t, rc == MPI_SUCCESS, "open a read-write: rc %d", rc);
  if (rc) return;
  /* A barrier after each resize: Open MPI's OMPIO may return from it
   * before the file has its size, and its get_size after a shrink
   * sometimes gives a size between (on 8 processes): under Open MPI only
   * that the calls work. */
  int rc2 = MPI_File_set_size(fh, 12);
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_File_get_size(fh, &size);
#ifdef OPEN_MPI
  MCHECK(t, rc2 == MPI_SUCCESS && size >= 12, "set_size 12: rc %d, %lld", rc2, (long long)size);
#else
  MCHECK(t, rc2 == MPI_SUCCESS && size == 12, "set_size 12: rc %d, %lld", rc2, (long long)size);
#endif
  MPI_File_preallocate(fh, 40);
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_File_get_size(fh, &size);
  MCHECK(t, size == 40, "preallocate 40: %lld", (long long)size);
  MPI_File_preallocate(fh, 20);
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_File_get_size(fh, &size);
  MCHECK(t, size == 40, "preallocate 20 shrank it: %lld", (long long)size);
  rc = MPI_File_sync(fh);
  MCHECK(t, rc == MPI_SUCCESS, "sync: rc %d", rc);
  int flag = -1;
  MPI_File_get_atomicity(fh, &flag);
  MCHECK(t, flag == 0, "atomicity at open: %d", flag);
  MPI_File_set_atomicity(fh, 1);
  MPI_File_get_atomicity(fh, &flag);
  MCHECK(t, flag == 1, "atomicity set: %d", flag);
  MPI_File_close(&fh);
  MPI_Barrier(MPI_COMM_WORLD);
  char all[64];
  long got = iotest_read(io, "a", all, sizeof all);
  MCHECK(t, got == 40 && !memcmp(all, "r00:abcd", 8) && all[39] == 0, "the file after resizing: %ld bytes", got);

  /* Append: both pointers start at the end; each rank writes a byte
   * there in turn (its offset from the end). */
  rc = MPI_File_open(MPI_COMM_WORLD, p, MPI_MODE_WRONLY | MPI_MODE_APPEND, MPI_INFO_NULL, &fh);
  MPI_Offset pos = -1;
  MPI_File_get_position(fh, &pos);
  MCHECK(t, rc == MPI_SUCCESS && pos == 40, "MPI_MODE_APPEND: rc %d, position %lld", rc, (long long)pos);
  char c = (char)('A' + t->rank % 26);
  MPI_File_write_at(fh, pos + t->rank, &c, 1, MPI_CHAR, MPI_STATUS_IGNORE);
  MPI_File_close(&fh);
  MPI_Barrier(MPI_COMM_WORLD);
  got = iotest_read(io, "a", all, sizeof all);
  MCHECK(t, got == 40 + t->size, "after the appends: %ld bytes", got);
  MCHECK(t, all[40] == 'A' && (t->size < 2 || all[41] == 'B'), "the appended bytes %c %c", all[40], all[41]);

  /* Delete on close; delete. */
  rc = MPI_File_open(MPI_COMM_WORLD, iotest_path(io, "b", p, sizeof p),
                     MPI_MODE_CREATE | MPI_MODE_RDWR | MPI_MODE_DELETE_ON_CLOSE, MPI_INFO_NULL, &fh);
  MCHECK(t, rc == MPI_SUCCESS, "open b: rc %d", rc);
  MPI_File_write_at(fh, t->rank, &c, 1, MPI_CHAR, MPI_STATUS_IGNORE);
  MPI_Barrier(MPI_COMM_WORLD);
  MCHECK(t, iotest_exists(io, "b"), "b is not there while open");
  MPI_File_close(&fh);
  MPI_Barrier(MPI_COMM_WORLD);
  MCHECK(t, !iotest_exists(io, "b"), "b is still there after its MPI_MODE_DELETE_ON_CLOSE close");
  if (t->rank == 0) {
    rc = MPI_File_delete(iotest_path(io, "a", p, sizeof p), MPI_INFO_NULL);
    MCHECK(t, rc == MPI_SUCCESS && !iotest_exists(io, "a"), "delete a: rc %d", rc);
    rc = MPI_File_delete(p, MPI_INFO_NULL);
    MCHECK(t, cls(rc) == MPI_ERR_NO_SUCH_FILE, "delete a again: class %d", cls(rc));
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

/* Nonblocking: each rank writes two ints at its place with iwrite_at and
 * waits, reads them back with iread_at and tests until done. */
static void test_nonblocking(mtest *t, const iotest *io) {
  char p[640];
  MPI_File fh;
  int rc = MPI_File_open(MPI_COMM_WORLD, iotest_path(io, "c", p, sizeof p), MPI_MODE_CREATE | MPI_MODE_RDWR,
                         MPI_INFO_NULL, &fh);
  MCHECK(t, rc == MPI_SUCCESS, "open c: rc %d", rc);
  if (rc) return;
  int v[2] = {t->rank, -t->rank}, w[2] = {-1, -1}, n = -1, flag = 0;
  MPI_Request q;
  MPI_Status st;
  rc = MPI_File_iwrite_at(fh, (MPI_Offset)t->rank * 8, v, 2, MPI_INT, &q);
  if (rc == MPI_SUCCESS) rc = MPI_Wait(&q, &st);
  MPI_Get_count(&st, MPI_INT, &n);
  MCHECK(t, rc == MPI_SUCCESS && q == MPI_REQUEST_NULL && n == 2, "iwrite_at and wait: rc %d, count %d", rc, n);
  MPI_Barrier(MPI_COMM_WORLD);
  rc = MPI_File_iread_at(fh, (MPI_Offset)t->rank * 8, w, 2, MPI_INT, &q);
  while (rc == MPI_SUCCESS && !flag) rc = MPI_Test(&q, &flag, &st);
  MPI_Get_count(&st, MPI_INT, &n);
  MCHECK(t, rc == MPI_SUCCESS && w[0] == t->rank && w[1] == -t->rank && n == 2, "iread_at and test: %d %d", w[0], w[1]);
  MPI_File_seek(fh, (MPI_Offset)t->rank * 8 + 4, MPI_SEEK_SET);
  rc = MPI_File_iread(fh, w, 1, MPI_INT, &q);
  if (rc == MPI_SUCCESS) rc = MPI_Wait(&q, MPI_STATUS_IGNORE);
  MPI_Offset pos = -1;
  MPI_File_get_position(fh, &pos);
  MCHECK(t, rc == MPI_SUCCESS && w[0] == -t->rank && pos == t->rank * 8 + 8, "iread at the pointer: %d, pos %lld",
         w[0], (long long)pos);
  MPI_File_close(&fh);
  MPI_Barrier(MPI_COMM_WORLD);
  int all[2 * 64];
  long got = iotest_read(io, "c", all, sizeof all);
  int bad = got != 8L * t->size;
  for (int r = 0; r < t->size && !bad; r++) bad = all[2 * r] != r || all[2 * r + 1] != -r;
  MCHECK(t, !bad, "the file c as C reads it: %ld bytes", got);
}

/* The program's file handler finds this rank's record through
 * MPI_COMM_SELF's name (no globals: tilesim's driver runs every rank in
 * one process). */
typedef struct {
  int calls, code;
  MPI_File file;
} record_t;

static void handler(MPI_File *fh, int *code, ...) {
  char name[MPI_MAX_OBJECT_NAME];
  int len;
  void *p = NULL;
  MPI_Comm_get_name(MPI_COMM_SELF, name, &len);
  if (sscanf(name, "%p", &p) != 1 || !p) return;
  record_t *r = p;
  r->calls++;
  r->code = *code;
  r->file = *fh;
}

/* A handler of the program's; hints kept. */
static void test_handlers(mtest *t, const iotest *io) {
  char p[640], name[64];
  record_t rec = {0, 0, MPI_FILE_NULL};
  snprintf(name, sizeof name, "%p", (void *)&rec);
  MPI_Comm_set_name(MPI_COMM_SELF, name);
  MPI_Info info;
  MPI_Info_create(&info);
  MPI_Info_set(info, "access_style", "read_once");
  MPI_File fh;
  int rc = MPI_File_open(MPI_COMM_WORLD, iotest_path(io, "h", p, sizeof p), MPI_MODE_CREATE | MPI_MODE_WRONLY |
                         MPI_MODE_DELETE_ON_CLOSE, info, &fh);
  MPI_Info_free(&info);
  MCHECK(t, rc == MPI_SUCCESS, "open h: rc %d", rc);
  if (rc) return;
  MPI_Errhandler eh, got = MPI_ERRHANDLER_NULL;
  rc = MPI_File_create_errhandler(handler, &eh);
  if (rc == MPI_SUCCESS) rc = MPI_File_set_errhandler(fh, eh);
  if (rc == MPI_SUCCESS) rc = MPI_Errhandler_free(&eh);
  MCHECK(t, rc == MPI_SUCCESS && eh == MPI_ERRHANDLER_NULL, "a handler of the program's set and freed: rc %d", rc);
  char b[8];
  rc = MPI_File_read_at(fh, 0, b, 8, MPI_CHAR, MPI_STATUS_IGNORE);
  MCHECK(t, rec.calls == 1 && rec.file == fh && cls(rec.code) == MPI_ERR_ACCESS && rc == rec.code,
         "a read of a write-only file under the program's handler: %d calls, class %d, rc %d", rec.calls,
         cls(rec.code), rc);
  rc = MPI_File_call_errhandler(fh, MPI_ERR_OTHER);
  MCHECK(t, rc == MPI_SUCCESS && rec.calls == 2 && rec.code == MPI_ERR_OTHER, "MPI_File_call_errhandler: %d calls",
         rec.calls);
  MPI_File_get_errhandler(fh, &got);
  MCHECK(t, got != MPI_ERRORS_RETURN && got != MPI_ERRHANDLER_NULL, "MPI_File_get_errhandler gave the predefined one");
  if (got != MPI_ERRHANDLER_NULL) MPI_Errhandler_free(&got);
  /* Hints: set ones are accepted; what comes back is the library's to
   * choose (tilesim gives back those given). */
  MPI_Info_create(&info);
  MPI_Info_set(info, "cb_buffer_size", "1048576");
  rc = MPI_File_set_info(fh, info);
  MPI_Info_free(&info);
  MPI_Info used;
  int rc2 = MPI_File_get_info(fh, &used);
  MCHECK(t, rc == MPI_SUCCESS && rc2 == MPI_SUCCESS, "set_info, get_info: rc %d %d", rc, rc2);
  if (rc2 == MPI_SUCCESS) MPI_Info_free(&used);
  MPI_File_close(&fh);
  MPI_Comm_set_name(MPI_COMM_SELF, "MPI_COMM_SELF");
}

int main(int argc, char **argv) {
  static const iotest_fn checks[] = {test_open_errors, test_records, test_pointers, test_sizes, test_nonblocking, test_handlers, NULL};
  static const char *const files[] = {"a", "b", "c", "h", NULL};
  return iotest_main(&argc, &argv, "io_files", checks, files);
}
