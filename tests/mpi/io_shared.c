/* io_shared.c -- MPI-IO's shared file pointer, ordered and split collective access, and the
 * nonblocking collective calls (MPI 3.1 sections 13.4.4 and 13.4.5), checked against the bytes
 * plain C reads from the host's file: every rank's record written once at the shared pointer
 * (in an order the library picks: each once), read back once each; ordered writes and reads
 * in rank order; seek_shared and get_position_shared; split collectives (begin, end) at
 * explicit offsets, at the individual pointer and ordered; iwrite_shared, iread_shared,
 * iwrite_at_all and iread_all completed by MPI_Waitall.
 *
 * Plain MPI C: it builds with tilesim's mpi.h and with Open MPI's mpicc, and prints the same
 * "io_shared: P passed, F failed" line under both. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "iotest.h"
#include "mtest.h"

/* MPI_File_get_position_shared is checked under tilesim only, and counts
 * only when it fails: Open MPI 4.1's (ROMIO and OMPIO) gives 0 on some
 * ranks after the others moved the pointer. */
#define TSCHECK(t, cond, ...) SCHECK(t, !TILESIM || (cond), __VA_ARGS__)

/* What other ranks wrote becomes visible: MPI 3.1 section 13.6.1's
 * sync-barrier-sync. */
static void settle(MPI_File fh) {
  MPI_File_sync(fh);
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_File_sync(fh);
}

static MPI_File open_new(mtest *t, const iotest *io, const char *name) {
  MPI_File fh = iotest_open(t, io, name);
  if (fh != MPI_FILE_NULL) MPI_File_set_size(fh, 0);
  return fh;
}

/* Rank r's record: 4 ints r, r, r, r (the order they land in is the
 * library's). */
static void test_shared(mtest *t, const iotest *io) {
  int size = t->size, rank = t->rank;
  MPI_File fh = open_new(t, io, "shared");
  if (fh == MPI_FILE_NULL) return;
  MPI_File_set_view(fh, 0, MPI_INT, MPI_INT, "native", MPI_INFO_NULL);
  int rec[4] = {rank, rank, rank, rank}, got[4] = {-1, -1, -1, -1};
  int rc = MPI_File_write_shared(fh, rec, 4, MPI_INT, MPI_STATUS_IGNORE);
  MCHECK(t, rc == MPI_SUCCESS, "write_shared: rc %d", rc);
  settle(fh);
  MPI_Offset pos = -1;
  MPI_File_get_position_shared(fh, &pos);
  TSCHECK(t, pos == 4L * size, "the shared pointer after every rank's record: %lld", (long long)pos);
  int *all = malloc(sizeof(int) * 4 * (size_t)size + 16), *seen = calloc((size_t)size, sizeof *seen);
  long n = iotest_read(io, "shared", all, sizeof(int) * 4 * (size_t)size + 16);
  int bad = n != 16L * size;
  for (int k = 0; k < size && !bad; k++) {
    int r = all[4 * k];
    bad = r < 0 || r >= size || seen[r]++ || all[4 * k + 1] != r || all[4 * k + 2] != r || all[4 * k + 3] != r;
  }
  MCHECK(t, !bad, "the file of records as C reads it: %ld bytes, each rank's record once", n);
  /* Back to the start, and each rank reads one record: every record once. */
  rc = MPI_File_seek_shared(fh, 0, MPI_SEEK_SET);
  MPI_File_get_position_shared(fh, &pos);
  MPI_Barrier(MPI_COMM_WORLD);   /* no rank reads before every rank looked */
  MCHECK(t, rc == MPI_SUCCESS, "seek_shared 0: rc %d", rc);
  TSCHECK(t, pos == 0, "the shared pointer after seek_shared 0: %lld", (long long)pos);
  rc = MPI_File_read_shared(fh, got, 4, MPI_INT, MPI_STATUS_IGNORE);
  MCHECK(t, rc == MPI_SUCCESS && got[0] == got[3] && got[0] >= 0 && got[0] < size, "read_shared: %d", got[0]);
  MPI_Gather(&got[0], 1, MPI_INT, all, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (rank == 0) {
    memset(seen, 0, sizeof *seen * (size_t)size);
    bad = 0;
    for (int k = 0; k < size && !bad; k++) bad = all[k] < 0 || all[k] >= size || seen[all[k]]++;
    MCHECK(t, !bad, "the records read at the shared pointer are not each rank's once");
  }
  free(all);
  free(seen);
  MPI_File_close(&fh);
}

/* Rank r writes r + 1 ints of r in rank order; reads them back so. */
static void test_ordered(mtest *t, const iotest *io) {
  int size = t->size, rank = t->rank, mine[64], back[64];
  MPI_File fh = open_new(t, io, "ordered");
  if (fh == MPI_FILE_NULL) return;
  MPI_File_set_view(fh, 0, MPI_INT, MPI_INT, "native", MPI_INFO_NULL);
  for (int i = 0; i <= rank; i++) mine[i] = 100 + rank, back[i] = -1;
  MPI_Status st;
  int n = -1, rc = MPI_File_write_ordered(fh, mine, rank + 1, MPI_INT, &st);
  MPI_Get_count(&st, MPI_INT, &n);
  MCHECK(t, rc == MPI_SUCCESS && n == rank + 1, "write_ordered: rc %d, count %d", rc, n);
  MPI_Offset pos = -1, total = (MPI_Offset)size * (size + 1) / 2;
  MPI_File_get_position_shared(fh, &pos);
  TSCHECK(t, pos == total, "the shared pointer after write_ordered: %lld (want %lld)", (long long)pos, (long long)total);
  MPI_File_seek_shared(fh, 0, MPI_SEEK_SET);
  rc = MPI_File_read_ordered(fh, back, rank + 1, MPI_INT, &st);
  MCHECK(t, rc == MPI_SUCCESS && !memcmp(back, mine, sizeof(int) * (size_t)(rank + 1)), "read_ordered: %d .. %d",
         back[0], back[rank]);
  /* The split form, after the others: rank r's int at total + r. */
  int one = 1000 + rank;
  rc = MPI_File_write_ordered_begin(fh, &one, 1, MPI_INT);
  if (rc == MPI_SUCCESS) rc = MPI_File_write_ordered_end(fh, &one, &st);
  MPI_Get_count(&st, MPI_INT, &n);
  MCHECK(t, rc == MPI_SUCCESS && n == 1, "write_ordered_begin/end: rc %d, count %d", rc, n);
  MPI_File_close(&fh);
  MPI_Barrier(MPI_COMM_WORLD);
  int *all = malloc(sizeof(int) * (size_t)(total + size) + 8), k = 0, bad;
  long got = iotest_read(io, "ordered", all, sizeof(int) * (size_t)(total + size) + 8);
  bad = got != (long)sizeof(int) * (total + size);
  for (int r = 0; r < size && !bad; r++)
    for (int i = 0; i <= r && !bad; i++) bad = all[k++] != 100 + r;
  for (int r = 0; r < size && !bad; r++) bad = all[k++] != 1000 + r;
  MCHECK(t, !bad, "the ordered file as C reads it: %ld bytes", got);
  free(all);
}

/* Split collectives at explicit offsets and at the individual pointer;
 * nonblocking collective and shared calls. */
static void test_split_nonblocking(mtest *t, const iotest *io) {
  int size = t->size, rank = t->rank;
  MPI_File fh = open_new(t, io, "split");
  if (fh == MPI_FILE_NULL) return;
  int v[2] = {rank, 2 * rank}, w[2] = {-1, -1}, n = -1;
  MPI_Status st;
  int rc = MPI_File_write_at_all_begin(fh, (MPI_Offset)rank * 8, v, 2, MPI_INT);
  if (rc == MPI_SUCCESS) rc = MPI_File_write_at_all_end(fh, v, &st);
  MPI_Get_count(&st, MPI_INT, &n);
  MCHECK(t, rc == MPI_SUCCESS && n == 2, "write_at_all_begin/end: rc %d, count %d", rc, n);
  settle(fh);
  MPI_File_seek(fh, (MPI_Offset)rank * 8, MPI_SEEK_SET);
  rc = MPI_File_read_all_begin(fh, w, 2, MPI_INT);
  if (rc == MPI_SUCCESS) rc = MPI_File_read_all_end(fh, w, &st);
  MCHECK(t, rc == MPI_SUCCESS && w[0] == rank && w[1] == 2 * rank, "read_all_begin/end: %d %d", w[0], w[1]);
  rc = MPI_File_read_at_all_begin(fh, (MPI_Offset)((rank + 1) % size) * 8, w, 2, MPI_INT);
  if (rc == MPI_SUCCESS) rc = MPI_File_read_at_all_end(fh, w, &st);
  int next = (rank + 1) % size;
  MCHECK(t, rc == MPI_SUCCESS && w[0] == next && w[1] == 2 * next, "read_at_all_begin/end: %d %d", w[0], w[1]);
  /* Nonblocking: an int each after the pairs, at explicit offsets, then
   * one at the shared pointer (set there first). */
  MPI_Request q[2];
  int x = 50 + rank, y = 70 + rank, rx = -1;
  MPI_Offset end = 8L * size;
  rc = MPI_File_iwrite_at_all(fh, end + 4L * rank, &x, 1, MPI_INT, &q[0]);
  MPI_Waitall(1, q, MPI_STATUSES_IGNORE);
  settle(fh);
  MPI_File_seek(fh, end + 4L * ((rank + 1) % size), MPI_SEEK_SET);
  rc |= MPI_File_iread_all(fh, &rx, 1, MPI_INT, &q[0]);
  MPI_Waitall(1, q, MPI_STATUSES_IGNORE);
  MCHECK(t, rc == MPI_SUCCESS && rx == 50 + next, "iwrite_at_all then iread_all: %d", rx);
  MPI_File_seek_shared(fh, end + 4L * size, MPI_SEEK_SET);
  rc = MPI_File_iwrite_shared(fh, &y, 1, MPI_INT, &q[0]);
  MPI_Wait(&q[0], MPI_STATUS_IGNORE);
  settle(fh);
  MPI_Offset pos = -1;
  MPI_File_get_position_shared(fh, &pos);
  MCHECK(t, rc == MPI_SUCCESS, "iwrite_shared: rc %d", rc);
  TSCHECK(t, pos == end + 4L * size + 4L * size, "iwrite_shared: shared pointer %lld", (long long)pos);
  MPI_File_seek_shared(fh, end + 4L * size, MPI_SEEK_SET);
  rx = -1;
  rc = MPI_File_iread_shared(fh, &rx, 1, MPI_INT, &q[1]);
  MPI_Wait(&q[1], &st);
  MPI_Get_count(&st, MPI_INT, &n);
  MCHECK(t, rc == MPI_SUCCESS && n == 1 && rx >= 70 && rx < 70 + size, "iread_shared: %d", rx);
  MPI_File_close(&fh);
  MPI_Barrier(MPI_COMM_WORLD);
  int *all = malloc(sizeof(int) * 4 * (size_t)size + 8), *seen = calloc((size_t)size, sizeof *seen), bad;
  long got = iotest_read(io, "split", all, sizeof(int) * 4 * (size_t)size + 8);
  bad = got != 16L * size;
  for (int r = 0; r < size && !bad; r++)
    bad = all[2 * r] != r || all[2 * r + 1] != 2 * r || all[2 * size + r] != 50 + r;
  for (int r = 0; r < size && !bad; r++) {
    int y2 = all[3 * size + r] - 70;
    bad = y2 < 0 || y2 >= size || seen[y2]++;
  }
  MCHECK(t, !bad, "the split file as C reads it: %ld bytes", got);
  free(all);
  free(seen);
}

int main(int argc, char **argv) {
  static const iotest_fn checks[] = {test_shared, test_ordered, test_split_nonblocking, NULL};
  static const char *const files[] = {"shared", "ordered", "split", NULL};
  return iotest_main(&argc, &argv, "io_shared", checks, files);
}
