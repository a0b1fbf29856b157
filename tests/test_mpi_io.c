/* test_mpi_io.c -- what tilesim's MPI-IO does that the portable programs of tests/mpi cannot
 * check: the storage model's simulated times against their closed forms (io_model.h: a file
 * system serves one request at a time, latency + bytes / bandwidth each; a collective call is
 * one request of every rank's bytes once the last rank has come), on a network that costs
 * nothing (--net ideal, m = per_byte = 0) and binary-fraction costs (exact); separate file
 * systems not contending; the mounts' host directories (/scratch among them); the --fs
 * option's refusals; SimGrid's sg_file calls; errors under MPI_ERRORS_ARE_FATAL; a deadlock
 * in a collective file call; the same data on threads. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mpi/io_sg.h"
#include "mpi/mpi.h"
#include "mpi/settings.h"
#include "tests/check.h"
#include "mp/mp.h"
#include "tests/mpiharness.h"

enum { MAXR = 16 };

typedef struct {
  char dir[256];           /* the host directory of /fsa; /fsb's is dir/b */
  int n;                   /* bytes a rank writes */
  double t[MAXR][8];       /* each rank's clock at its steps */
  int ok[MAXR];
} job;

/* Run fn on n ranks of backend b: --net ideal at no cost, one processor a
 * rank. */
static mpih_result run(int b, int n, mpih_fn fn, void *ud) {
  mpih_config cfg;
  mpih_config_init(&cfg, b, n);
  cfg.sim.m = 0;
  cfg.sim.per_byte = 0;
  return mpih_result_of(&cfg, fn, ud);
}

/* The job's directory dir and n bytes a rank; /fsa (dir) and /fsb (dir/b)
 * mounted: latency 1/2 s, 16 bytes a second. */
static void mounts(job *j, const char *dir, int n) {
  char spec[512], err[256];
  snprintf(j->dir, sizeof j->dir, "%s", dir);
  j->n = n;
  io_fs_reset();
  snprintf(spec, sizeof spec, "/fsa,dir=%s,latency=0.5,bandwidth=16", j->dir);
  CHECK(io_fs_option(spec, err, sizeof err) == 0, "--fs %s: %s", spec, err);
  snprintf(spec, sizeof spec, "/fsb,dir=%s/b,latency=0.5,bandwidth=16", j->dir);
  CHECK(io_fs_option(spec, err, sizeof err) == 0, "--fs %s: %s", spec, err);
}

/* Open, an independent write each, a collective write, close. */
static int steps(void *ud) {
  job *j = ud;
  int r = mpih_init(), size;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_File fh;
  char buf[256];
  memset(buf, 'a' + r, sizeof buf);
  int ok = MPI_File_open(MPI_COMM_WORLD, "/fsa/f", MPI_MODE_CREATE | MPI_MODE_RDWR, MPI_INFO_NULL, &fh) == 0;
  j->t[r][0] = MPI_Wtime();
  ok &= MPI_File_write_at(fh, (MPI_Offset)r * j->n, buf, j->n, MPI_CHAR, MPI_STATUS_IGNORE) == 0;
  j->t[r][1] = MPI_Wtime();
  MPI_Barrier(MPI_COMM_WORLD);
  j->t[r][2] = MPI_Wtime();
  ok &= MPI_File_write_at_all(fh, (MPI_Offset)r * j->n, buf, j->n, MPI_CHAR, MPI_STATUS_IGNORE) == 0;
  j->t[r][3] = MPI_Wtime();
  MPI_Request q;
  ok &= MPI_File_iread_at(fh, 0, buf, j->n, MPI_CHAR, &q) == 0;   /* charged at the call */
  j->t[r][4] = MPI_Wtime();
  ok &= MPI_Wait(&q, MPI_STATUS_IGNORE) == 0;
  MPI_Offset sz;
  ok &= MPI_File_get_size(fh, &sz) == 0 && sz == (MPI_Offset)size * j->n;
  j->t[r][5] = MPI_Wtime();
  ok &= MPI_File_close(&fh) == 0;
  j->t[r][6] = MPI_Wtime();
  j->ok[r] = ok;
  MPI_Finalize();
  return 0;
}

static int cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static void closed_forms(const char *dir) {
  for (int p = 1; p <= 8; p *= 2) {
    job j = {0};
    mounts(&j, dir, 32);   /* 2 s of bandwidth */
    mpih_result res = run(MPIH_SIM, p, steps, &j);
    CHECK(res.rc == 0, "%d ranks: %s", p, res.err);
    /* open: one request, 1/2 s, from 0 */
    int bad = 0;
    for (int r = 0; r < p; r++) bad += !j.ok[r] || j.t[r][0] != 0.5;
    CHECK(bad == 0, "%d ranks: open ends at %.17g (0.5 due), %d wrong", p, j.t[0][0], bad);
    /* independent writes at 1/2: served one after the other, 2.5 s each */
    double ends[MAXR];
    for (int r = 0; r < p; r++) ends[r] = j.t[r][1];
    qsort(ends, (size_t)p, sizeof *ends, cmp);
    bad = 0;
    for (int k = 0; k < p; k++) bad += ends[k] != 0.5 + 2.5 * (k + 1);
    CHECK(bad == 0, "%d ranks: independent writes end at %.17g .. %.17g (0.5 + 2.5 k due)", p, ends[0], ends[p - 1]);
    /* the collective: one request of every rank's bytes: 0.5 + 2 p */
    double t2 = j.t[0][2], want = t2 + 0.5 + 2.0 * p;
    bad = 0;
    for (int r = 0; r < p; r++) bad += j.t[r][2] != 0.5 + 2.5 * p || j.t[r][3] != want;
    CHECK(bad == 0, "%d ranks: the barrier at %.17g, write_at_all ends at %.17g (%.17g due)", p, t2, j.t[0][3], want);
    /* iread_at (2.5 s each, in turn), then get_size (0.5 each, in turn),
     * then close (0.5 once every rank has come) */
    for (int r = 0; r < p; r++) ends[r] = j.t[r][4];
    qsort(ends, (size_t)p, sizeof *ends, cmp);
    bad = 0;
    for (int k = 0; k < p; k++) bad += ends[k] != want + 2.5 * (k + 1);
    double after = want + 2.5 * p + 0.5 * p, maxsize = 0;
    for (int r = 0; r < p; r++) maxsize = j.t[r][5] > maxsize ? j.t[r][5] : maxsize;
    for (int r = 0; r < p; r++) bad += j.t[r][6] != maxsize + 0.5;
    CHECK(bad == 0 && maxsize == after, "%d ranks: iread_at, get_size and close: %.17g %.17g %.17g (%.17g, %.17g due)",
          p, ends[0], maxsize, j.t[0][6], want + 2.5, after + 0.5);
    CHECK(res.makespan == after + 0.5, "%d ranks: makespan %.17g (%.17g due)", p, res.makespan, after + 0.5);
    mpih_result_free(&res);
  }
}

/* Rank 0 writes to /fsa, rank 1 to /fsb, at once: no contention. */
static int two_fs(void *ud) {
  job *j = ud;
  int r = mpih_init();
  MPI_File fh;
  char buf[64] = {0};
  int ok = MPI_File_open(MPI_COMM_SELF, r ? "/fsb/g" : "/fsa/g", MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL,
                         &fh) == 0;
  ok &= MPI_File_write(fh, buf, 48, MPI_CHAR, MPI_STATUS_IGNORE) == 0;
  j->t[r][0] = MPI_Wtime();
  ok &= MPI_File_close(&fh) == 0;
  if (r == 0) ok &= MPI_File_delete("/fsa/g", MPI_INFO_NULL) == 0;
  j->t[r][1] = MPI_Wtime();
  j->ok[r] = ok;
  MPI_Finalize();
  return 0;
}

static void separate(const char *dir) {
  job j = {0};
  mounts(&j, dir, 0);
  char b[300], g[320];
  snprintf(b, sizeof b, "%s/b", dir);
  mkdir(b, 0700);
  mpih_result res = run(MPIH_SIM, 2, two_fs, &j);
  /* open 0.5, 48 bytes 0.5 + 3: 4 s on each; close 0.5; rank 0's delete 0.5 */
  CHECK(res.rc == 0 && j.ok[0] && j.ok[1] && j.t[0][0] == 4 && j.t[1][0] == 4 && j.t[0][1] == 5 && j.t[1][1] == 4.5,
        "two file systems: %.17g %.17g, %.17g %.17g (4 4 5 4.5 due)", j.t[0][0], j.t[1][0], j.t[0][1], j.t[1][1]);
  struct stat st;
  snprintf(g, sizeof g, "%s/b/g", dir);
  CHECK(stat(g, &st) == 0 && st.st_size == 48, "/fsb/g is not the host's %s of 48 bytes", g);
  snprintf(g, sizeof g, "%s/g", dir);
  CHECK(stat(g, &st) != 0, "/fsa/g (the host's %s) was not deleted", g);
  remove(b);
  snprintf(g, sizeof g, "%s/b/g", dir);
  remove(g);
  rmdir(b);
  mpih_result_free(&res);
}

/* The same steps on threads: the data, not the times. */
static void threads(const char *dir) {
  job j = {0};
  mounts(&j, dir, 8);
  io_fs_option("/fsa,latency=0,bandwidth=1e15", (char[64]){0}, 64);
  char f[300], data[64];
  snprintf(f, sizeof f, "%s/f", dir);
  remove(f);
  mpih_result res = run(MPIH_THREADS, 4, steps, &j);
  int bad = res.rc != 0;
  for (int r = 0; r < 4; r++) bad += !j.ok[r];
  FILE *in = fopen(f, "rb");
  size_t n = in ? fread(data, 1, sizeof data, in) : 0;
  if (in) fclose(in);
  for (int r = 0; r < 4 && n == 32; r++)
    for (int k = 0; k < 8; k++) bad += data[8 * r + k] != 'a' + r;
  CHECK(bad == 0 && n == 32, "threads: rc %d, %zu bytes in the file: %s", res.rc, n, res.err);
  remove(f);
  mpih_result_free(&res);
}

/* A missing file under MPI_ERRORS_ARE_FATAL on MPI_FILE_NULL: the run
 * ends in the call's words. */
static int fatal_open(void *ud) {
  (void)ud;
  MPI_Init(NULL, NULL);
  MPI_File fh;
  MPI_File_set_errhandler(MPI_FILE_NULL, MPI_ERRORS_ARE_FATAL);
  MPI_File_open(MPI_COMM_WORLD, "/fsa/missing", MPI_MODE_RDONLY, MPI_INFO_NULL, &fh);
  MPI_Finalize();
  return 0;
}

static void fatal(const char *dir) {
  job j = {0};
  mounts(&j, dir, 0);
  mpih_result res = run(MPIH_SIM, 2, fatal_open, &j);
  CHECK(res.rc != 0 && res.aborted && strstr(res.err, "MPI_File_open") && strstr(res.err, "/fsa/missing"),
        "a fatal open of a missing file: rc %d, \"%s\"", res.rc, res.err);
  mpih_result_free(&res);
}

/* Rank 0 in a collective write, rank 1 waiting for a message: the
 * deadlock report names the file call. */
static int stuck(void *ud) {
  (void)ud;
  int r = mpih_init(), v = 0;
  MPI_File fh;
  MPI_File_open(MPI_COMM_WORLD, "/fsa/stuck", MPI_MODE_CREATE | MPI_MODE_WRONLY | MPI_MODE_DELETE_ON_CLOSE,
                MPI_INFO_NULL, &fh);
  if (r == 0) MPI_File_write_all(fh, &v, 1, MPI_INT, MPI_STATUS_IGNORE);
  else MPI_Recv(&v, 1, MPI_INT, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_File_close(&fh);
  MPI_Finalize();
  return 0;
}

static void deadlock(const char *dir) {
  job j = {0};
  mounts(&j, dir, 0);
  mpih_result res = run(MPIH_SIM, 2, stuck, &j);
  CHECK(res.rc != 0 && res.deadlock && strstr(res.err, "MPI_File_write_all") && strstr(res.err, "MPI_Recv"),
        "a deadlock in a collective write: rc %d, \"%s\"", res.rc, res.err);
  mpih_result_free(&res);
  char f[300];
  snprintf(f, sizeof f, "%s/stuck", dir);
  remove(f);
}

/* --fs's refusals; /scratch's directory; sg_file. */
static void options(const char *dir) {
  char err[256];
  static const char *const bad[] = {"scratch", "/x,latency=-1", "/x,bandwidth=0", "/x,speed=3", "/,dir=/tmp",
                                    "/x,latency=abc", ""};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    err[0] = 0;
    CHECK(io_fs_option(bad[i], err, sizeof err) == -1 && strstr(err, "--fs"), "--fs '%s' accepted (%s)", bad[i],
          err);
  }
  io_fs_reset();
  char spec[300];
  snprintf(spec, sizeof spec, "/scratch,dir=%s", dir);
  CHECK(io_fs_option(spec, err, sizeof err) == 0, "--fs %s: %s", spec, err);
  char host[300];
  snprintf(host, sizeof host, "%s/s.txt", dir);
  FILE *f = fopen(host, "w");
  if (f) fclose(f);
  io_sg_file *sg = sg_file_open("/scratch/./x/../s.txt", NULL);
  CHECK(sg && !strcmp(sg_file_get_name(sg), "/scratch/./x/../s.txt") && sg_file_get_size(sg) == 0,
        "sg_file_open of /scratch/s.txt");
  sg_file_unlink(sg);
  struct stat st;
  CHECK(stat(host, &st) != 0, "sg_file_unlink left %s", host);
  io_fs_reset();
}

int main(void) {
  const char *tmp = getenv("TMPDIR");
  char d[256];
  snprintf(d, sizeof d, "%s/test_mpi_io.XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (!mkdtemp(d)) {
    CHECK(0, "mkdtemp %s", d);
    return check_done("test_mpi_io");
  }
  closed_forms(d);
  separate(d);
  threads(d);
  fatal(d);
  deadlock(d);
  options(d);
  char f[300];
  snprintf(f, sizeof f, "%s/f", d);
  remove(f);
  rmdir(d);
  io_fs_reset();
  return check_done("test_mpi_io");
}
