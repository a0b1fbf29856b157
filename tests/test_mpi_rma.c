/* test_mpi_rma.c -- what tilesim's one-sided communication does that the
 * portable programs of tests/mpi cannot check: each operation's and each
 * synchronisation's simulated time against its closed form on the
 * harness's machine (--net ideal, m = 1/4, per_byte = 1/16: exact), a
 * fence, post/start/complete/wait and a contended lock among three ranks,
 * the unified memory model, the hints MPI_Win_set_info keeps, what a
 * deadlock report says of a rank waiting for a lock, an error under
 * MPI_ERRORS_ARE_FATAL in its own words, a loop of flushes of the rank's
 * own memory that waits for another rank (the poll cost moves the clock),
 * and the same results on threads. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/mpi.h"
#include "tests/check.h"
#include "mp/mp.h"
#include "tests/mpiharness.h"

static const char *const bname[] = {"sim", "threads"};

enum { M4 = 4 };   /* 1/m */
static const double m = 0.25, b = 0.0625;

/* fn on n ranks of backend be: the harness's machine, with poll cost poll
 * and no cost between ranks on one processor (a rank's operations on its
 * own memory cost nothing). */
static mpih_result run(int be, int n, double poll, mpih_fn fn, void *ud) {
  mpih_config cfg;
  mpih_config_init(&cfg, be, n);
  cfg.poll_cost = poll;
  cfg.sim.local = 0;
  return mpih_result_of(&cfg, fn, ud);
}

static int has(const char *s, const char *part) { return strstr(s, part) != NULL; }

typedef struct {
  double t[8][16];   /* by rank: times */
  long v[8][8];      /* by rank: values */
} facts;

/* Every rank leaves at the same time (three or more ranks): two rounds of
 * 0-byte messages from every rank to every other, as examples/mpi/level.h
 * does for the examples (which include an MPI library's <mpi.h>). */
static void level(void) {
  int p, r;
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  MPI_Request q[32];
  for (int round = 0; round < 2; round++) {
    int n = 0;
    for (int j = 0; j < p; j++) {
      if (j == r) continue;
      MPI_Irecv(NULL, 0, MPI_BYTE, j, 99, MPI_COMM_WORLD, &q[n++]);
      MPI_Isend(NULL, 0, MPI_BYTE, j, 99, MPI_COMM_WORLD, &q[n++]);
    }
    MPI_Waitall(n, q, MPI_STATUSES_IGNORE);
  }
}

/* ==== one origin, one target ============================================== */

/* Rank 0 on rank 1's window (the target does nothing meanwhile), each step
 * timed by rank 0 alone.  A request carries the origin's data, a reply the
 * target's; the unlock's request follows the operations on the channel. */
static int passive_times(void *ud) {
  facts *F = ud;
  int r = mpih_init();
  long *mem, buf[16] = {0}, one = 1, old = 0, cmp = 0;
  MPI_Win win;
  MPI_Win_allocate(16 * sizeof(long), sizeof(long), MPI_INFO_NULL, MPI_COMM_WORLD, &mem, &win);
  memset(mem, 0, 16 * sizeof(long));
  MPI_Barrier(MPI_COMM_WORLD);
  if (r == 0) {
    double *t = F->t[0], t0 = MPI_Wtime();
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 1, 0, win);
    t[0] = MPI_Wtime() - t0;                                     /* 2m */
    t0 = MPI_Wtime();
    MPI_Put(buf, 16, MPI_LONG, 1, 0, 16, MPI_LONG, win);
    t[1] = MPI_Wtime() - t0;                                     /* 0 */
    MPI_Win_flush_local(1, win);
    t[2] = MPI_Wtime() - t0;                                     /* 0: the data were copied (+ the poll cost, 0) */
    MPI_Win_flush(1, win);
    t[3] = MPI_Wtime() - t0;                                     /* 2m + 128b */
    t0 = MPI_Wtime();
    MPI_Get(buf, 4, MPI_LONG, 1, 0, 4, MPI_LONG, win);
    MPI_Win_flush_local(1, win);
    t[4] = MPI_Wtime() - t0;                                     /* 2m + 32b */
    t0 = MPI_Wtime();
    MPI_Fetch_and_op(&one, &old, MPI_LONG, 1, 3, MPI_SUM, win);
    MPI_Win_flush(1, win);
    t[5] = MPI_Wtime() - t0;                                     /* 2m + 16b */
    t0 = MPI_Wtime();
    MPI_Compare_and_swap(&one, &cmp, &old, MPI_LONG, 1, 4, win);
    MPI_Win_flush(1, win);
    t[6] = MPI_Wtime() - t0;                                     /* 2m + 24b */
    t0 = MPI_Wtime();
    MPI_Accumulate(buf, 8, MPI_LONG, 1, 8, 8, MPI_LONG, MPI_SUM, win);
    MPI_Win_unlock(1, win);
    t[7] = MPI_Wtime() - t0;                                     /* 2m + 64b */
    t0 = MPI_Wtime();
    MPI_Request q;
    MPI_Win_lock(MPI_LOCK_SHARED, 1, 0, win);
    MPI_Rput(buf, 2, MPI_LONG, 1, 0, 2, MPI_LONG, win, &q);
    MPI_Wait(&q, MPI_STATUS_IGNORE);
    t[8] = MPI_Wtime() - t0;                                     /* 2m: the lock */
    MPI_Rget(buf, 2, MPI_LONG, 1, 0, 2, MPI_LONG, win, &q);
    MPI_Wait(&q, MPI_STATUS_IGNORE);
    t[9] = MPI_Wtime() - t0;                                     /* 2m, then behind the Rput (m + 16b), m + 16b */
    MPI_Win_unlock(1, win);
    t[10] = MPI_Wtime() - t0;                                    /* + 2m */
    F->v[0][0] = old;
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (r == 1) F->v[1][0] = mem[3], F->v[1][1] = mem[4];
  MPI_Win_free(&win);
  MPI_Finalize();
  return 0;
}

static void one_pair(void) {
  facts F = {0};
  mpih_result res = run(MPIH_SIM, 2, 0, passive_times, &F);
  double *t = F.t[0];
  double due[11] = {2 * m, 0, 0, 2 * m + 128 * b, 2 * m + 32 * b, 2 * m + 16 * b, 2 * m + 24 * b, 2 * m + 64 * b,
                    2 * m, 4 * m + 32 * b, 6 * m + 32 * b};
  const char *what[11] = {"lock", "put", "flush_local after a put", "flush after a put of 128 bytes",
                          "get of 32 bytes", "fetch_and_op of 8 bytes", "compare_and_swap of 8 bytes",
                          "accumulate of 64 bytes and unlock", "lock and Rput's wait", "Rget's wait", "unlock"};
  CHECK(res.rc == 0, "passive_times: %s", res.err);
  for (int i = 0; i < 11; i++) CHECK(t[i] == due[i], "%s took %.17g s, the closed form says %.17g", what[i], t[i], due[i]);
  CHECK(F.v[1][0] == 1 && F.v[1][1] == 1 && F.v[0][0] == 0, "the atomics left %ld %ld (fetched %ld)", F.v[1][0],
        F.v[1][1], F.v[0][0]);
  mpih_result_free(&res);
}

/* ==== three ranks from a common start ===================================== */

/* A fence epoch of puts to both neighbours (8 longs each); a post/start/
 * complete/wait epoch of the same puts; three origins at once on rank 0's
 * exclusive lock. */
static int three(void *ud) {
  facts *F = ud;
  int r = mpih_init(), p;
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  long *mem, buf[8] = {1, 2, 3, 4, 5, 6, 7, 8}, one = 1, got = -1;
  MPI_Win win;
  MPI_Win_allocate(33 * sizeof(long), sizeof(long), MPI_INFO_NULL, MPI_COMM_WORLD, &mem, &win);
  int left = (r + p - 1) % p, right = (r + 1) % p;
  level();
  double t0 = MPI_Wtime();
  MPI_Win_fence(0, win);
  F->t[r][0] = MPI_Wtime() - t0;                                 /* ceil(log2 3) m = 2m */
  MPI_Put(buf, 8, MPI_LONG, left, 0, 8, MPI_LONG, win);
  MPI_Put(buf, 8, MPI_LONG, right, 8, 8, MPI_LONG, win);
  MPI_Win_fence(0, win);
  F->t[r][1] = MPI_Wtime() - t0;                                 /* + 2m + 64b + 2m */
  level();
  t0 = MPI_Wtime();
  MPI_Group world, nb;
  MPI_Comm_group(MPI_COMM_WORLD, &world);
  int two[2] = {left, right};
  MPI_Group_incl(world, 2, two, &nb);
  MPI_Win_post(nb, 0, win);
  MPI_Win_start(nb, 0, win);
  MPI_Put(buf, 8, MPI_LONG, left, 16, 8, MPI_LONG, win);
  MPI_Put(buf, 8, MPI_LONG, right, 24, 8, MPI_LONG, win);
  MPI_Win_complete(win);
  F->t[r][2] = MPI_Wtime() - t0;                                 /* the posts (m), then the puts (m + 64b) */
  MPI_Win_wait(win);
  F->t[r][3] = MPI_Wtime() - t0;                                 /* the dones, behind the puts */
  MPI_Group_free(&nb);
  MPI_Group_free(&world);
  level();
  t0 = MPI_Wtime();
  MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, win);
  F->t[r][4] = MPI_Wtime() - t0;
  MPI_Fetch_and_op(&one, &got, MPI_LONG, 0, 32, MPI_SUM, win);
  MPI_Win_unlock(0, win);
  F->t[r][5] = MPI_Wtime() - t0;
  F->v[r][0] = got;
  MPI_Win_free(&win);
  MPI_Finalize();
  return 0;
}

static void three_ranks(void) {
  facts F = {0};
  mpih_result res = run(MPIH_SIM, 3, 0, three, &F);
  CHECK(res.rc == 0, "three: %s", res.err);
  for (int r = 0; r < 3; r++) {
    CHECK(F.t[r][0] == 2 * m && F.t[r][1] == 2 * m + 4 * m + 64 * b, "rank %d: fences at %.17g and %.17g", r, F.t[r][0],
          F.t[r][1]);
    CHECK(F.t[r][2] == 2 * m + 64 * b && F.t[r][3] == 2 * m + 64 * b, "rank %d: complete at %.17g, wait at %.17g", r,
          F.t[r][2], F.t[r][3]);
  }
  /* Rank 0's own request is granted at once (no cost on one processor),
   * and its fetch and release too: the lock is free again when the others'
   * requests come (at m, both: one is taken first, the other queued).  A
   * grant takes m back to its origin, the fetch (8 bytes) and the release
   * follow it, m + 8b, and the next grant leaves at the release; the
   * fetch's reply takes m + 8b more.  f: the first of ranks 1 and 2. */
  double hop = m + 8 * b, g1 = 2 * m, rel1 = g1 + hop, g2 = rel1 + m, rel2 = g2 + hop;
  int f = F.t[1][4] < F.t[2][4] ? 1 : 2, s = 3 - f;
  CHECK(F.t[0][4] == 0 && F.t[f][4] == g1 && F.t[s][4] == g2, "lock granted at %.17g %.17g %.17g (0 %g %g due)",
        F.t[0][4], F.t[f][4], F.t[s][4], g1, g2);
  CHECK(F.t[0][5] == 0 && F.t[f][5] == rel1 + hop && F.t[s][5] == rel2 + hop,
        "unlocked at %.17g %.17g %.17g (0 %g %g due)", F.t[0][5], F.t[f][5], F.t[s][5], rel1 + hop, rel2 + hop);
  CHECK(F.v[0][0] == 0 && F.v[f][0] == 1 && F.v[s][0] == 2, "the counter gave %ld %ld %ld", F.v[0][0], F.v[f][0],
        F.v[s][0]);
  mpih_result_free(&res);
}

/* ==== what tilesim says =================================================== */

static int model_info(void *ud) {
  facts *F = ud;
  MPI_Init(NULL, NULL);
  int mem, *model, flag;
  MPI_Win win;
  MPI_Win_create(&mem, sizeof mem, 1, MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Win_get_attr(win, MPI_WIN_MODEL, &model, &flag);
  F->v[0][0] = flag ? *model : -1;
  MPI_Info in, out;
  MPI_Info_create(&in);
  MPI_Info_set(in, "no_locks", "true");
  MPI_Info_set(in, "accumulate_ops", "same_op");
  MPI_Win_set_info(win, in);
  MPI_Info_free(&in);
  MPI_Win_get_info(win, &out);
  char v[64];
  MPI_Info_get(out, "no_locks", 63, v, &flag);
  F->v[0][1] = flag && !strcmp(v, "true");
  MPI_Info_get(out, "accumulate_ops", 63, v, &flag);
  F->v[0][2] = flag && !strcmp(v, "same_op");
  MPI_Info_free(&out);
  MPI_Win_free(&win);
  MPI_Finalize();
  return 0;
}

/* Rank 0 holds rank 1's lock and waits for a message rank 1 never sends;
 * rank 1 waits for the lock. */
static int stuck(void *ud) {
  (void)ud;
  int r = mpih_init(), mem = 0, v;
  MPI_Win win;
  MPI_Win_create(&mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  if (r == 0) {
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 1, 0, win);
    MPI_Send(&v, 0, MPI_INT, 1, 0, MPI_COMM_WORLD);
    MPI_Recv(&v, 1, MPI_INT, 1, 5, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  } else {
    MPI_Recv(&v, 0, MPI_INT, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 1, 0, win);
  }
  MPI_Finalize();
  return 0;
}

static int fatal(void *ud) {
  (void)ud;
  MPI_Init(NULL, NULL);
  int mem = 0, v = 1;
  MPI_Win win;
  MPI_Win_create(&mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Put(&v, 1, MPI_INT, 1, 0, 1, MPI_INT, win);   /* no epoch: MPI_ERRORS_ARE_FATAL */
  MPI_Finalize();
  return 0;
}

/* Rank 1 polls its own memory under a lock of its own (flushes that wait
 * for nothing) until rank 0 has put a flag there. */
static int polling(void *ud) {
  facts *F = ud;
  int r = mpih_init(), one = 1;
  int *flag;
  MPI_Win win;
  MPI_Win_allocate(sizeof(int), sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &flag, &win);
  *flag = 0;
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Win_lock_all(0, win);
  long tries = 0;
  if (r == 0) {
    MPI_Put(&one, 1, MPI_INT, 1, 0, 1, MPI_INT, win);
    MPI_Win_flush(1, win);
  } else {
    int seen = 0;
    while (!seen) {
      MPI_Fetch_and_op(NULL, &seen, MPI_INT, 1, 0, MPI_NO_OP, win);
      MPI_Win_flush(1, win);
      tries++;
    }
  }
  MPI_Win_unlock_all(win);
  F->v[r][0] = tries;
  MPI_Win_free(&win);
  MPI_Finalize();
  return 0;
}

static void tilesim_words(void) {
  for (int be = 0; be < 2; be++) {
    facts F = {0};
    mpih_result res = run(be, 2, 1e-6, model_info, &F);
    CHECK(res.rc == 0 && F.v[0][0] == MPI_WIN_UNIFIED, "%s: MPI_WIN_MODEL %ld", bname[be], F.v[0][0]);
    CHECK(F.v[0][1] == 1 && F.v[0][2] == 1, "%s: the hints MPI_Win_set_info gave are not kept", bname[be]);
    mpih_result_free(&res);
    res = run(be, 2, 1e-6, stuck, NULL);
    CHECK(res.rc != 0 && res.deadlock && has(res.err, "rank 1 waits in MPI_Win_lock(MPI_LOCK_EXCLUSIVE, rank=1, window") &&
              has(res.err, "rank 0 waits in MPI_Recv(source=1, tag=5, MPI_COMM_WORLD)"),
          "%s: the deadlock report: %s", bname[be], res.err);
    mpih_result_free(&res);
    res = run(be, 2, 1e-6, fatal, NULL);
    CHECK(res.rc != 0 && has(res.err, "MPI_Put: rank 1 is in no access epoch of this rank's"), "%s: the fatal error: %s",
          bname[be], res.err);
    mpih_result_free(&res);
    memset(&F, 0, sizeof F);
    res = run(be, 2, 1e-6, polling, &F);
    CHECK(res.rc == 0 && F.v[1][0] >= 1, "%s: polling a flag: %s (%ld tries)", bname[be], res.rc ? res.err : "",
          F.v[1][0]);
    mpih_result_free(&res);
  }
}

int main(void) {
  one_pair();
  three_ranks();
  tilesim_words();
  return check_done("test_mpi_rma");
}
