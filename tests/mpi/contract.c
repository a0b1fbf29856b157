/* contract.c -- the MPI backend (mp/mp_mpi.h) against mp.h's contract,
 * under mpirun -np 4 (any N >= 4 works): ping-pong, any-source and FIFO per
 * pair, tags, probe, truncation, unread messages, bad ranks and arguments,
 * deadlock detection and its report, random matching programs delivering
 * every message exactly once.  Each rank checks what it sees; rank 0 sums
 * the failures and prints "contract_mpi: P passed, F failed".
 * Built by make mpi (or make check, where mpicc is). */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mp/mp_mpi.h"
#include "util/rng.h"
#include "util/xmem.h"

static int passed, failed, me;
static MPI_Comm data, ctl;

#define CHECK(cond, ...)                                                       \
  do {                                                                         \
    if (cond) {                                                                \
      passed++;                                                                \
    } else {                                                                   \
      failed++;                                                                \
      fprintf(stderr, "%s:%d: rank %d: ", __FILE__, __LINE__, me);             \
      fprintf(stderr, __VA_ARGS__);                                            \
      fputc('\n', stderr);                                                     \
    }                                                                          \
  } while (0)

/* One run of main on the first n processes (the others skip it); rank 0's
 * statistics in *st. */
static int run(int n, mp_main main, void *ud, mpm_stats *st, char *err, size_t errlen) {
  err[0] = 0;
  MPI_Barrier(MPI_COMM_WORLD);   /* runs on the same communicators must not overlap */
  if (me >= n) return 0;
  mpm_config cfg;
  mpm_config_init(&cfg);
  cfg.warn = NULL;
  mpm *m = mpm_new(&cfg, data, ctl, n, err, errlen);
  if (!m) return -2;
  int rc = mpm_run(m, main, ud, err, errlen);
  if (st) *st = *mpm_stats_get(m);
  mpm_free(m);
  return rc;
}

/* ==== ping-pong ========================================================== */

static void pingpong_main(mp *self, void *ud) {
  int *bad = ud, r = mp_rank(self);
  if (r > 1) return;
  for (int i = 0; i < 1000; i++) {
    int v = 2 * i + r, got = -1;
    mp_status st;
    if (r == 0) {
      *bad += mp_send(self, 1, 7, &v, sizeof v) != MP_OK;
      *bad += mp_recv(self, 1, 7, &got, sizeof got, &st) != MP_OK || got != 2 * i + 1;
    } else {
      *bad += mp_recv(self, 0, 7, &got, sizeof got, &st) != MP_OK || got != 2 * i;
      *bad += st.source != 0 || st.tag != 7 || st.len != sizeof got;
      *bad += mp_send(self, 0, 7, &v, sizeof v) != MP_OK;
    }
  }
}

static void test_pingpong(void) {
  int bad = 0;
  char err[512];
  mpm_stats st;
  int rc = run(2, pingpong_main, &bad, &st, err, sizeof err);
  CHECK(rc == 0 && bad == 0, "ping-pong: rc %d (%s), %d bad", rc, err, bad);
  if (me == 0) CHECK(st.messages == 2000 && st.received == 2000 && st.unread == 0, "ping-pong counts");
}

/* ==== any-source, FIFO per pair, tags ===================================== */

enum { NMSG = 300 };

static void fifo_main(mp *self, void *ud) {
  int *bad = ud, r = mp_rank(self), n = mp_size(self);
  if (r > 0) {
    for (int i = 0; i < NMSG; i++) {
      int v[2] = {r, i};
      *bad += mp_send(self, 0, 1 + (i & 1), v, sizeof v) != MP_OK;
    }
    return;
  }
  int next[64] = {0}, v[2];
  mp_status st;
  for (int k = 0; k < 50; k++) {   /* rank 1's odd messages (tag 2), in order, past the tag-1 ones */
    *bad += mp_recv(self, 1, 2, v, sizeof v, &st) != MP_OK || v[0] != 1 || v[1] != 2 * k + 1;
  }
  for (int k = 0; k < (n - 1) * NMSG - 50; k++) {
    if (mp_recv(self, MP_ANY, MP_ANY, v, sizeof v, &st) != MP_OK) {
      (*bad)++;
      return;
    }
    int s = v[0];
    if (s < 1 || s >= n || s >= 64 || st.source != s) {
      (*bad)++;
      continue;
    }
    if (s == 1)
      while (next[1] < 100 && (next[1] & 1)) next[1]++;   /* the odd ones below 100 are taken */
    *bad += v[1] != next[s] || st.tag != 1 + (v[1] & 1);
    next[s] = v[1] + 1;
  }
}

static void test_fifo(int n) {
  int bad = 0;
  char err[512];
  mpm_stats st;
  int rc = run(n, fifo_main, &bad, &st, err, sizeof err);
  CHECK(rc == 0 && bad == 0, "any-source / FIFO / tags: rc %d (%s), %d bad", rc, err, bad);
  if (me == 0) CHECK(st.unread == 0 && st.messages == (n - 1) * NMSG, "FIFO counts");
}

/* ==== probe, truncation, unread ========================================== */

static void probe_main(mp *self, void *ud) {
  int *bad = ud;
  if (mp_rank(self) == 1) {
    unsigned char big[100];
    for (int i = 0; i < 100; i++) big[i] = (unsigned char)i;
    int one = 1;
    *bad += mp_send(self, 0, 5, big, sizeof big) != MP_OK;
    *bad += mp_send(self, 0, 6, &one, sizeof one) != MP_OK;
    *bad += mp_send(self, 0, 9, &one, sizeof one) != MP_OK;   /* never received */
    *bad += mp_send(self, 0, 9, &one, sizeof one) != MP_OK;   /* never received */
    *bad += mp_send(self, 0, 4, NULL, 0) != MP_OK;            /* the go signal */
    return;
  }
  if (mp_rank(self) != 0) return;
  while (mp_probe(self, 1, 4, NULL) == 0) {
  }
  mp_status st;
  *bad += mp_probe(self, MP_ANY, 6, &st) != 1 || st.source != 1 || st.len != 4;
  *bad += mp_probe(self, 1, 7, NULL) != 0;
  unsigned char buf[16] = {0};
  int rc = mp_recv(self, 1, 5, buf, 10, &st);
  int pattern = 1;
  for (int i = 0; i < 10; i++) pattern &= buf[i] == i;
  *bad += rc != MP_ETRUNC || st.len != 100 || !pattern || buf[10] != 0;
  int x = 0;
  *bad += mp_recv(self, MP_ANY, MP_ANY, &x, sizeof x, &st) != MP_OK || st.tag != 6 || x != 1;
  *bad += mp_recv(self, 1, 4, NULL, 0, NULL) != MP_OK;
}

static void test_probe(void) {
  int bad = 0;
  char err[512];
  mpm_stats st;
  int rc = run(2, probe_main, &bad, &st, err, sizeof err);
  CHECK(rc == 0 && bad == 0, "probe / truncation: rc %d (%s), %d bad", rc, err, bad);
  if (me == 0)
    CHECK(st.unread == 2 && st.warnings == 2, "unread %lld (expected 2), warnings %lld (expected 2)",
          st.unread, st.warnings);
}

/* ==== bad arguments ======================================================= */

static void bad_main(mp *self, void *ud) {
  int *rc = ud, x = 0;
  if (mp_rank(self) != 1) return;
  rc[0] = mp_send(self, 2, 0, &x, sizeof x);   /* 2 ranks: no rank 2 */
  rc[1] = mp_send(self, 0, -2, &x, sizeof x);
  rc[2] = mp_send(self, 0, MPM_TAG_MAX + 1, &x, sizeof x);
  rc[3] = mp_recv(self, 5, 0, &x, sizeof x, NULL);
  rc[4] = mp_probe(self, 0, -7, NULL);
  rc[5] = mp_compute(self, -1);
  rc[6] = mp_compute(self, NAN);
  rc[7] = mp_compute(self, 3);
}

static void test_bad(void) {
  int rcs[8] = {0};
  char err[512];
  mpm_stats st;
  int rc = run(2, bad_main, rcs, &st, err, sizeof err);
  if (me == 1)
    CHECK(rc == -1 && rcs[0] == MP_ERANK && rcs[1] == MP_EARG && rcs[2] == MP_EARG && rcs[3] == MP_ERANK &&
              rcs[4] == MP_EARG && rcs[5] == MP_EARG && rcs[6] == MP_EARG && rcs[7] == MP_OK,
          "codes %d %d %d %d %d %d %d %d, rc %d", rcs[0], rcs[1], rcs[2], rcs[3], rcs[4], rcs[5], rcs[6],
          rcs[7], rc);
  if (me == 0)
    CHECK(rc == -1 && strstr(err, "rank 1: mp_send to rank 2, which does not exist (2 ranks)") &&
              strstr(err, "(7 errors in all)") && st.errors == 7 && !st.deadlock,
          "rank 0 reports the run's errors: rc %d: %s", rc, err);
}

/* ==== deadlock ============================================================ */

typedef struct {
  int rc[3];
  int early;
} dead;

static void dead_main(mp *self, void *ud) {
  dead *d = ud;
  int r = mp_rank(self), n = mp_size(self), x = 0;
  if (d->early && r == 0) return;
  if (r == 1) mp_send(self, 2, 8, &x, sizeof x);   /* rank 2 waits for tag 3: unmatched */
  d->rc[0] = mp_recv(self, r == 2 ? MP_ANY : (r + 1) % n, r == 2 ? 3 : MP_ANY, &x, sizeof x, NULL);
  d->rc[1] = mp_send(self, 0, 1, &x, sizeof x);
  d->rc[2] = mp_recv(self, MP_ANY, MP_ANY, &x, sizeof x, NULL);
}

static void test_deadlock(void) {
  for (int early = 0; early <= 1; early++) {
    dead d;
    memset(&d, 0, sizeof d);
    d.early = early;
    char err[1024];
    mpm_stats st;
    int rc = run(4, dead_main, &d, &st, err, sizeof err);
    if (me < 4 && !(early && me == 0))
      CHECK(d.rc[0] == MP_EDEADLOCK && d.rc[1] == MP_ESTOPPED && d.rc[2] == MP_ESTOPPED,
            "deadlock (early %d): codes %d %d %d", early, d.rc[0], d.rc[1], d.rc[2]);
    if (me == 0)
      CHECK(rc == -1 && st.deadlock && strstr(err, "deadlock after") &&
                strstr(err, "rank 1 waits in recv(src=2, tag=any)") &&
                strstr(err, "rank 2 waits in recv(src=any, tag=3)") &&
                strstr(err, "rank 3 waits in recv(src=0, tag=any)") &&
                (early || strstr(err, "rank 0 waits in recv(src=1, tag=any)")) && st.unread == 1,
            "deadlock report (early %d): rc %d, unread %lld: %s", early, rc, st.unread, err);
  }
}

/* ==== random matching programs ============================================ */

enum { RMAX = 200, RLEN = 100 };

typedef struct {
  int nmsg, src[RMAX], dst[RMAX], tag[RMAX], len[RMAX], mode[8];
  int delivered[RMAX];
  int bad;
} rprog;

static void fill(unsigned char *b, int id, int len) {
  memcpy(b, &id, sizeof id);
  for (int j = (int)sizeof id; j < len; j++) b[j] = (unsigned char)(id * 31 + j);
}

static void random_main(mp *self, void *ud) {
  rprog *p = ud;
  int r = mp_rank(self);
  unsigned char buf[RLEN], want[RLEN];
  for (int i = 0; i < p->nmsg; i++) {
    if (p->src[i] == r) {
      fill(buf, i, p->len[i]);
      p->bad += mp_send(self, p->dst[i], p->tag[i], buf, (size_t)p->len[i]) != MP_OK;
    }
    if (p->dst[i] != r) continue;
    int mode = p->mode[r], k = -1;
    mp_status st;
    if (mp_recv(self, mode == 1 ? MP_ANY : p->src[i], mode == 0 ? p->tag[i] : MP_ANY, buf, sizeof buf, &st) !=
        MP_OK) {
      p->bad++;
      return;
    }
    memcpy(&k, buf, sizeof k);
    if (k < 0 || k >= p->nmsg || p->dst[k] != r) {
      p->bad++;
      continue;
    }
    p->delivered[k]++;
    p->bad += st.source != p->src[k] || st.tag != p->tag[k] || (int)st.len != p->len[k];
    p->bad += mode != 1 && k != i;
    fill(want, k, p->len[k]);
    p->bad += memcmp(want, buf, (size_t)p->len[k]) != 0;
  }
}

static void test_random(int nprocs) {
  int bad_runs = 0;
  for (unsigned seed = 1; seed <= 12; seed++) {
    rng g;
    rng_seed(&g, seed);   /* the same program on every process */
    int n = rng_int(&g, 2, nprocs < 8 ? nprocs : 8);
    static rprog p;
    memset(&p, 0, sizeof p);
    p.nmsg = rng_int(&g, 1, RMAX);
    for (int i = 0; i < p.nmsg; i++) {
      p.src[i] = rng_int(&g, 0, n - 1), p.dst[i] = rng_int(&g, 0, n - 1);
      p.tag[i] = rng_int(&g, 0, 4), p.len[i] = rng_int(&g, 4, RLEN);
    }
    for (int k = 0; k < n; k++) p.mode[k] = rng_int(&g, 0, 2);
    char err[512];
    int rc = run(n, random_main, &p, NULL, err, sizeof err);
    int undelivered = 0;
    for (int i = 0; i < p.nmsg; i++) undelivered += p.dst[i] == me && p.delivered[i] != 1;
    if ((rc != 0 || p.bad || undelivered) && bad_runs++ < 3)
      CHECK(0, "random seed %u (%d ranks, %d messages): rc %d (%s), %d bad, %d undelivered", seed, n, p.nmsg,
            rc, err, p.bad, undelivered);
  }
  CHECK(bad_runs == 0, "%d random programs failed here", bad_runs);
}

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int n;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  MPI_Comm_dup(MPI_COMM_WORLD, &data);
  MPI_Comm_dup(MPI_COMM_WORLD, &ctl);
  MPI_Comm_set_errhandler(data, MPI_ERRORS_RETURN);
  if (n < 4) {
    if (me == 0) fprintf(stderr, "contract_mpi: needs mpirun -np 4 or more (%d)\n", n);
    MPI_Finalize();
    return 2;
  }
  test_pingpong();
  test_fifo(n);
  test_probe();
  test_bad();
  test_deadlock();
  test_random(n);
  int mine[2] = {passed, failed}, all[2] = {0, 0};
  MPI_Reduce(mine, all, 2, MPI_INT, MPI_SUM, 0, MPI_COMM_WORLD);
  if (me == 0) {
    printf("contract_mpi: %d passed, %d failed\n", all[0], all[1]);
    fflush(stdout);
  }
  MPI_Comm_free(&ctl);
  MPI_Comm_free(&data);
  MPI_Finalize();
  return me == 0 && all[1] ? 1 : 0;
}
