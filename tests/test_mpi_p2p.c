/* test_mpi_p2p.c -- what tilesim's point-to-point does that the portable
 * programs of tests/mpi cannot check: the run's end under
 * MPI_ERRORS_ARE_FATAL and MPI_Abort (message, exit code, every rank
 * stopped), errors other MPIs do not catch (MPI_ERR_BUFFER, a freed
 * communicator, calls before MPI_Init and after MPI_Finalize), what a
 * deadlock report says of each rank's MPI call, the simulated times of a
 * ping-pong, a synchronous send, a communicator's context agreement and a
 * polling loop against their closed forms (binary-fraction costs: exact),
 * and each rank's end for the runner.  On the simulator and on threads
 * where it applies. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/coll_sched.h"
#include "mpi/engine.h"
#include "mpi/init.h"
#include "mpi/mpi.h"
#include "tests/check.h"
#include "mp/mp.h"
#include "tests/mpiharness.h"

static const char *const bname[] = {"sim", "threads"};

/* Run fn on n ranks of backend b (the harness's machine: --net ideal,
 * m = 1/4, per_byte = 1/16, c = 1/8, one processor per rank). */
static mpih_result run(int b, int n, mpih_fn fn, void *ud) {
  mpih_config cfg;
  mpih_config_init(&cfg, b, n);
  cfg.poll_cost = 0.0625;
  return mpih_result_of(&cfg, fn, ud);
}

static int has(const char *s, const char *part) { return strstr(s, part) != NULL; }

/* ==== the run's end ======================================================= */

/* Rank 1 sends to rank 7 of 4 under MPI_ERRORS_ARE_FATAL; the others wait
 * for messages that never come. */
static int bad_rank(void *ud) {
  (void)ud;
  int r = mpih_init(), v = 0;
  if (r == 1)
    MPI_Send(&v, 1, MPI_INT, 7, 0, MPI_COMM_WORLD);
  else
    MPI_Recv(&v, 1, MPI_INT, MPI_ANY_SOURCE, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Finalize();
  return 0;
}

static int aborts(void *ud) {
  (void)ud;
  int r = mpih_init(), v = 0;
  if (r == 2) MPI_Abort(MPI_COMM_WORLD, 3);
  MPI_Recv(&v, 1, MPI_INT, MPI_ANY_SOURCE, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Finalize();
  return 0;
}

/* A message longer than the receive, under the default handler. */
static int truncates(void *ud) {
  (void)ud;
  int r = mpih_init(), v[4] = {1, 2, 3, 4};
  if (r == 0)
    MPI_Send(v, 4, MPI_INT, 1, 5, MPI_COMM_WORLD);
  else
    MPI_Recv(v, 2, MPI_INT, 0, 5, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Finalize();
  return 0;
}

static int before_init(void *ud) {
  (void)ud;
  int v = 0;
  MPI_Send(&v, 1, MPI_INT, 0, 0, MPI_COMM_WORLD);
  return 0;
}

static int twice(void *ud) {
  (void)ud;
  MPI_Init(NULL, NULL);
  MPI_Init(NULL, NULL);
  return 0;
}

static void fatal_ends(void) {
  for (int b = 0; b < 2; b++) {
    mpih_result res = run(b, 4, bad_rank, NULL);
    CHECK(res.rc != 0 && has(res.err, "rank 1: MPI_Send: invalid rank 7 (MPI_COMM_WORLD has 4 ranks)"),
          "%s: bad rank: %s", bname[b], res.err);
    CHECK(res.aborted && res.abort_code == 1, "%s: bad rank: aborted %d code %d", bname[b], res.aborted,
          res.abort_code);
    int stopped = 1;
    for (int i = 0; i < 4; i++) stopped &= res.exit[i] == MPIH_NOEXIT;
    CHECK(stopped, "%s: bad rank: a rank went on after the error", bname[b]);
    mpih_result_free(&res);

    res = run(b, 4, aborts, NULL);
    CHECK(res.rc != 0 && has(res.err, "rank 2 called MPI_Abort(MPI_COMM_WORLD, 3)") && res.abort_code == 3,
          "%s: abort: %s (code %d)", bname[b], res.err, res.abort_code);
    mpih_result_free(&res);

    res = run(b, 2, truncates, NULL);
    CHECK(res.rc != 0 && res.abort_code == 1 &&
              has(res.err, "rank 1: MPI_Recv: a 16-byte message from rank 0 (tag 5) is longer than the "
                           "receive buffer (2 elements, 8 bytes): truncated"),
          "%s: truncation: %s", bname[b], res.err);
    mpih_result_free(&res);

    res = run(b, 1, before_init, NULL);
    CHECK(res.rc != 0 && has(res.err, "rank 0: MPI_Send called before MPI_Init"), "%s: before init: %s",
          bname[b], res.err);
    mpih_result_free(&res);

    res = run(b, 1, twice, NULL);
    CHECK(res.rc != 0 && has(res.err, "rank 0: MPI_Init: MPI is initialized already"), "%s: init twice: %s",
          bname[b], res.err);
    mpih_result_free(&res);
  }
}

/* ==== errors returned ===================================================== */

typedef struct {
  int rc[8];
} codes;

static int returned(void *ud) {
  codes *c = ud;
  int r = mpih_init(), v[100] = {0};
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  if (r == 0) {
    c->rc[0] = MPI_Bsend(v, 10, MPI_INT, 0, 1, MPI_COMM_WORLD);   /* no buffer */
    int size = 10 * (int)sizeof(int) + MPI_BSEND_OVERHEAD;
    char *buf = malloc((size_t)size);
    MPI_Buffer_attach(buf, size);
    c->rc[1] = MPI_Bsend(v, 11, MPI_INT, 0, 1, MPI_COMM_WORLD);   /* one int too many */
    c->rc[2] = MPI_Bsend(v, 10, MPI_INT, 0, 1, MPI_COMM_WORLD);   /* fits */
    c->rc[3] = MPI_Recv(v, 10, MPI_INT, 0, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    void *back;
    MPI_Buffer_detach(&back, &size);
    free(buf);
    MPI_Comm dup, gone;
    MPI_Comm_dup(MPI_COMM_SELF, &dup);
    gone = dup;
    MPI_Comm_free(&dup);
    c->rc[4] = MPI_Send(v, 1, MPI_INT, 0, 0, gone);
    c->rc[5] = MPI_Comm_free(&gone);
    MPI_Comm world = MPI_COMM_WORLD;
    c->rc[6] = MPI_Comm_free(&world);
  }
  MPI_Finalize();
  return 0;
}

static void errors_returned(void) {
  for (int b = 0; b < 2; b++) {
    codes c = {0};
    mpih_result res = run(b, 2, returned, &c);
    CHECK(res.rc == 0, "%s: errors returned: %s", bname[b], res.err);
    CHECK(c.rc[0] == MPI_ERR_BUFFER && c.rc[1] == MPI_ERR_BUFFER && c.rc[2] == MPI_SUCCESS && c.rc[3] == MPI_SUCCESS,
          "%s: buffered sends: %d %d %d %d", bname[b], c.rc[0], c.rc[1], c.rc[2], c.rc[3]);
    CHECK(c.rc[4] == MPI_ERR_COMM && c.rc[5] == MPI_ERR_COMM && c.rc[6] == MPI_ERR_COMM,
          "%s: freed and predefined communicators: %d %d %d", bname[b], c.rc[4], c.rc[5], c.rc[6]);
    mpih_result_free(&res);
  }
}

/* ==== deadlock reports ==================================================== */

static int stuck(void *ud) {
  (void)ud;
  int r = mpih_init(), v = 0;
  MPI_Request q[2];
  MPI_Comm dup;
  if (r == 0) {
    MPI_Recv(&v, 1, MPI_INT, 1, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  } else if (r == 1) {
    MPI_Ssend(&v, 1, MPI_INT, 0, 3, MPI_COMM_WORLD);
  } else if (r == 2) {
    MPI_Irecv(&v, 1, MPI_INT, MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_SELF, &q[0]);
    MPI_Issend(&v, 1, MPI_INT, 3, 4, MPI_COMM_WORLD, &q[1]);
    MPI_Waitall(2, q, MPI_STATUSES_IGNORE);
  } else if (r == 3) {
    MPI_Probe(MPI_ANY_SOURCE, 9, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  } else {
    MPI_Comm_dup(MPI_COMM_WORLD, &dup);
  }
  MPI_Finalize();
  return 0;
}

static void deadlock_words(void) {
  for (int b = 0; b < 2; b++) {
    mpih_result res = run(b, 5, stuck, NULL);
    CHECK(res.rc != 0 && res.deadlock, "%s: no deadlock reported: %s", bname[b], res.err);
    CHECK(has(res.err, "rank 0 waits in MPI_Recv(source=1, tag=7, MPI_COMM_WORLD)") &&
              has(res.err, "rank 1 waits in MPI_Ssend(dest=0, tag=3, MPI_COMM_WORLD)") &&
              has(res.err, "rank 2 waits in MPI_Waitall(MPI_Irecv(source=MPI_ANY_SOURCE, tag=MPI_ANY_TAG, "
                           "MPI_COMM_SELF), MPI_Issend(dest=3, tag=4, MPI_COMM_WORLD))") &&
              has(res.err, "rank 3 waits in MPI_Probe(source=MPI_ANY_SOURCE, tag=9, MPI_COMM_WORLD)") &&
              has(res.err, "rank 4 waits in MPI_Comm_dup(MPI_COMM_WORLD)"),
          "%s: the report: %s", bname[b], res.err);
    mpih_result_free(&res);
  }
}

/* ==== simulated time ====================================================== */

typedef struct {
  int len;              /* bytes */
  double t[4];          /* what rank 0 measured */
  long fails;           /* failed tests */
} timing;

/* Ping-pong of len bytes, twice: MPI_Wtime around the second. */
static int pingpong(void *ud) {
  timing *T = ud;
  int r = mpih_init();
  char *buf = calloc((size_t)T->len + 1, 1);
  for (int i = 0; i < 2; i++) {
    double t0 = MPI_Wtime();
    if (r == 0) {
      MPI_Send(buf, T->len, MPI_BYTE, 1, 0, MPI_COMM_WORLD);
      MPI_Recv(buf, T->len, MPI_BYTE, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      T->t[i] = MPI_Wtime() - t0;
    } else {
      MPI_Recv(buf, T->len, MPI_BYTE, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Send(buf, T->len, MPI_BYTE, 0, 0, MPI_COMM_WORLD);
    }
  }
  free(buf);
  MPI_Finalize();
  return 0;
}

/* Rank 0's Ssend at 0; rank 1 computes 16 units (2 s), then receives. */
static int ssend_time(void *ud) {
  timing *T = ud;
  int r = mpih_init(), v[4] = {0};
  if (r == 0) {
    MPI_Ssend(v, 4, MPI_INT, 1, 0, MPI_COMM_WORLD);   /* 16 bytes: arrives at 1/4 + 1 */
    T->t[0] = MPI_Wtime();
    MPI_Ssend(v, 4, MPI_INT, 1, 1, MPI_COMM_WORLD);   /* to a receive posted already */
    T->t[1] = MPI_Wtime();
  } else {
    mp_compute(mp_self(), 16);
    MPI_Recv(v, 4, MPI_INT, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Request q;
    MPI_Irecv(v, 4, MPI_INT, 0, 1, MPI_COMM_WORLD, &q);
    MPI_Wait(&q, MPI_STATUS_IGNORE);
  }
  MPI_Finalize();
  return 0;
}

/* MPI_Comm_dup on 2 ranks: rank 1 sends its 128-byte bitmap of contexts
 * up, rank 0 sends the 4-byte choice down. */
static int dup_time(void *ud) {
  timing *T = ud;
  int r = mpih_init();
  MPI_Comm dup;
  MPI_Comm_dup(MPI_COMM_WORLD, &dup);
  T->t[r] = MPI_Wtime();
  MPI_Comm_free(&dup);
  MPI_Finalize();
  return 0;
}

/* Rank 1 tests for a message rank 0 sends after 8 units (1 s): each
 * failed test costs the poll cost, 1/16 s. */
static int poll_time(void *ud) {
  timing *T = ud;
  int r = mpih_init(), v = 0;
  if (r == 0) {
    mp_compute(mp_self(), 8);
    MPI_Send(&v, 1, MPI_INT, 1, 0, MPI_COMM_WORLD);   /* 4 bytes: arrives at 1 + 1/4 + 1/4 */
  } else {
    MPI_Request q;
    int flag = 0;
    MPI_Irecv(&v, 1, MPI_INT, 0, 0, MPI_COMM_WORLD, &q);
    for (MPI_Test(&q, &flag, MPI_STATUS_IGNORE); !flag; MPI_Test(&q, &flag, MPI_STATUS_IGNORE)) T->fails++;
    T->t[0] = MPI_Wtime();
  }
  MPI_Finalize();
  return 0;
}

static void closed_forms(void) {
  /* m = 1/4, per_byte = 1/16: a message of L bytes takes 1/4 + L/16. */
  for (int len = 0; len <= 4096; len = len ? 4 * len : 1) {
    timing T = {len, {0}, 0};
    mpih_result res = run(MPIH_SIM, 2, pingpong, &T);
    double want = 2 * (0.25 + len * 0.0625);
    CHECK(res.rc == 0 && T.t[1] == want && res.makespan == 2 * want, "ping-pong of %d bytes: %.17g (%.17g due), makespan %.17g",
          len, T.t[1], want, res.makespan);
    CHECK(res.messages == 4, "ping-pong: %lld mp messages (4 due: no others)", res.messages);
    CHECK(res.bytes == 4LL * len, "ping-pong: %lld bytes (%d due: no headers)", res.bytes, 4 * len);
    mpih_result_free(&res);
  }
  timing T = {0, {0}, 0};
  mpih_result res = run(MPIH_SIM, 2, ssend_time, &T);
  /* The first arrives at 1.25, but its receive starts at 2: the ack (0
   * bytes) is sent then and arrives 1/4 later.  The second, sent at 2.25,
   * arrives at 3.5, where the posted receive takes it and acks at once. */
  CHECK(res.rc == 0 && T.t[0] == 2.25 && T.t[1] == 3.75, "ssend: %.17g %.17g (2.25 3.75 due)", T.t[0], T.t[1]);
  mpih_result_free(&res);
  memset(&T, 0, sizeof T);
  res = run(MPIH_SIM, 2, dup_time, &T);
  CHECK(res.rc == 0 && T.t[0] == 0.25 + 128 * 0.0625 && T.t[1] == 0.5 + 132 * 0.0625,
        "comm_dup: %.17g %.17g (%.17g %.17g due)", T.t[0], T.t[1], 0.25 + 128 * 0.0625, 0.5 + 132 * 0.0625);
  mpih_result_free(&res);
  memset(&T, 0, sizeof T);
  res = run(MPIH_SIM, 2, poll_time, &T);
  /* Tests at 0, 1/16, ...: the one at 1.5 finds it, after 24 failed. */
  CHECK(res.rc == 0 && T.t[0] == 1.5 && T.fails == 24, "polling: %.17g after %ld failed tests (1.5, 24 due)", T.t[0],
        T.fails);
  mpih_result_free(&res);
}

/* ==== a window of big sends: one copy each ================================ */

enum { WIN = 4 };

typedef struct {
  int len;        /* bytes a send */
  int late;       /* units rank 1 computes before it posts its receives */
  int same;       /* 1: every send from one buffer (as osu_bw) */
  long wrong;     /* bytes received wrong */
  double done;    /* rank 0's clock when its sends completed */
} window;

static char wbyte(int w, long i) { return (char)(i * 7 + w * 13 + 1); }

/* Rank 0 sends WIN messages of len bytes to rank 1 with MPI_Isend and
 * waits for all, then overwrites its buffers; rank 1 posts as many
 * MPI_Irecv (after `late` units of computing) and waits for all. */
static int big_window(void *ud) {
  window *W = ud;
  int r = mpih_init();
  char *buf[WIN];
  MPI_Request q[WIN];
  for (int w = 0; w < WIN; w++) {
    buf[w] = malloc((size_t)W->len);
    for (long i = 0; i < W->len; i++) buf[w][i] = r == 0 ? wbyte(W->same ? 0 : w, i) : 0;
  }
  if (r == 0) {
    for (int w = 0; w < WIN; w++) MPI_Isend(buf[W->same ? 0 : w], W->len, MPI_BYTE, 1, w, MPI_COMM_WORLD, &q[w]);
    MPI_Waitall(WIN, q, MPI_STATUSES_IGNORE);
    W->done = MPI_Wtime();
    for (int w = 0; w < WIN; w++) memset(buf[w], 0x5a, (size_t)W->len);   /* the program's own again */
  } else if (r == 1) {
    if (W->late) mp_compute(mp_self(), W->late);
    for (int w = 0; w < WIN; w++) MPI_Irecv(buf[w], W->len, MPI_BYTE, 0, w, MPI_COMM_WORLD, &q[w]);
    MPI_Waitall(WIN, q, MPI_STATUSES_IGNORE);
    for (int w = 0; w < WIN; w++)
      for (long i = 0; i < W->len; i++) W->wrong += buf[w][i] != wbyte(W->same ? 0 : w, i);
  }
  for (int w = 0; w < WIN; w++) free(buf[w]);
  MPI_Finalize();
  return 0;
}

/* Blocking sends of len bytes at 0: rank 0 MPI_Send to rank 1's MPI_Recv
 * (how 0), or to it through a derived type (how 1: send_block), or
 * MPI_Bcast from rank 0 to all 4 (how 2); rank 1 late by `late` units. */
static int big_blocking(void *ud) {
  window *W = ud;
  int r = mpih_init(), n = W->len;
  char *b = malloc((size_t)n);
  for (long i = 0; i < n; i++) b[i] = r == 0 ? wbyte(1, i) : 0;
  MPI_Datatype two;
  MPI_Type_contiguous(2, MPI_BYTE, &two);
  MPI_Type_commit(&two);
  if (r == 1 && W->late) mp_compute(mp_self(), W->late);
  if (W->same == 2) {
    MPI_Bcast(b, n, MPI_BYTE, 0, MPI_COMM_WORLD);
  } else if (r == 0) {
    if (W->same == 1)
      MPI_Send(b, n / 2, two, 1, 0, MPI_COMM_WORLD);
    else
      MPI_Send(b, n, MPI_BYTE, 1, 0, MPI_COMM_WORLD);
    W->done = MPI_Wtime();
  } else if (r == 1) {
    MPI_Recv(b, n, MPI_BYTE, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
  if (r != 0 && (W->same == 2 || r == 1))
    for (long i = 0; i < n; i++) W->wrong += b[i] != wbyte(1, i);
  MPI_Type_free(&two);
  free(b);
  MPI_Finalize();
  return 0;
}

/* A send of ENG_YIELD_MIN bytes or more gives way (engine.h): a request's
 * when it completes, a blocking one before it leaves.  So a receiver due at
 * the same simulated time posts first and each payload is copied once,
 * straight into its receive: the simulator pools nothing.  A receiver that posts later in simulated time,
 * and sends below the size, get the pool's copy; every byte arrives, and
 * the sends complete at 0 (eager) in every case. */
static void one_copy(void) {
  static const struct {
    int len, late, same, pooled;
  } cases[] = {
      {ENG_YIELD_MIN, 0, 0, 0},
      {ENG_YIELD_MIN, 0, 1, 0},
      {ENG_YIELD_MIN + 4099, 0, 0, 0},
      {ENG_YIELD_MIN, 16, 0, 1},
      {ENG_YIELD_MIN - 1, 0, 0, 1},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++)
    for (int b = 0; b < 2; b++) {
      window W = {cases[k].len, cases[k].late, cases[k].same, 0, -1};
      mpih_result res = run(b, 2, big_window, &W);
      long long pooled = cases[k].pooled ? (long long)WIN * cases[k].len : 0;
      CHECK(res.rc == 0 && W.wrong == 0 && (b != MPIH_SIM || W.done == 0), "%s: window of %d x %d bytes (late %d%s): rc %d, %ld bytes wrong, "
            "sends done at %g: %s", bname[b], WIN, cases[k].len, cases[k].late, cases[k].same ? ", one buffer" : "",
            res.rc, W.wrong, W.done, res.err);
      if (b == MPIH_SIM)
        CHECK(res.pooled == pooled, "sim: window of %d x %d bytes (late %d%s): %lld bytes pooled (%lld due)", WIN,
              cases[k].len, cases[k].late, cases[k].same ? ", one buffer" : "", res.pooled, pooled);
      mpih_result_free(&res);
    }
  static const struct {
    int len, late, how, ranks, pooled;
  } blocking[] = {
      {ENG_YIELD_MIN, 0, 0, 2, 0},
      {ENG_YIELD_MIN, 0, 1, 2, 0},
      {ENG_YIELD_MIN, 0, 2, 4, 0},
      {ENG_YIELD_MIN, 16, 0, 2, 1},
      {ENG_YIELD_MIN - 2, 0, 0, 2, 1},
  };
  for (size_t k = 0; k < sizeof blocking / sizeof *blocking; k++)
    for (int b = 0; b < 2; b++) {
      window W = {blocking[k].len, blocking[k].late, blocking[k].how, 0, -1};
      mpih_result res = run(b, blocking[k].ranks, big_blocking, &W);
      long long pooled = blocking[k].pooled ? blocking[k].len : 0;
      static const char *const how[] = {"MPI_Send", "MPI_Send of a derived type", "MPI_Bcast"};
      CHECK(res.rc == 0 && W.wrong == 0 && (b != MPIH_SIM || blocking[k].how == 2 || W.done == 0),
            "%s: %s of %d bytes (late %d): rc %d, %ld bytes wrong, sent at %g: %s", bname[b], how[blocking[k].how],
            blocking[k].len, blocking[k].late, res.rc, W.wrong, W.done, res.err);
      if (b == MPIH_SIM)
        CHECK(res.pooled == pooled, "sim: %s of %d bytes (late %d): %lld bytes pooled (%lld due)", how[blocking[k].how],
              blocking[k].len, blocking[k].late, res.pooled, pooled);
      mpih_result_free(&res);
    }
}

/* ==== collectives on the program's own buffers ============================ */

/* A collective on contiguous buffers reads and builds its data where it
 * lies (coll.h: coll_view, coll_place); on a type with gaps it packs into
 * memory of its own and unpacks at the end.  The same collective of the
 * same bytes in both types differs in the collective's memory by exactly
 * the packed copies (coll_sched_mem_given): the algorithms' own buffers
 * are the same. */
enum { CI_RANKS = 8, CI_INTS = 1 << 16 };
typedef struct {
  int op, gaps;
  long wrong;
} collcase;

static int cival(int r, long i) { return (int)(i * 3 + r * 1000 + 1); }

static int coll_bufs(void *ud) {
  collcase *C = ud;
  int r = mpih_init(), p = CI_RANKS, m = CI_INTS / p;
  MPI_Datatype t = MPI_INT, gappy;
  MPI_Type_create_resized(MPI_INT, 0, 2 * sizeof(int), &gappy);   /* an int, then a gap of one */
  MPI_Type_commit(&gappy);
  if (C->gaps) t = gappy;
  int step = C->gaps ? 2 : 1;
  int *a = calloc((size_t)CI_INTS * 2, sizeof(int)), *b = calloc((size_t)CI_INTS * 2, sizeof(int));
  long wrong = 0;
  switch (C->op) {
  case 0:   /* MPI_Bcast from rank 0 */
    for (long i = 0; i < CI_INTS; i++) a[i * step] = r == 0 ? cival(0, i) : 0;
    MPI_Bcast(a, CI_INTS, t, 0, MPI_COMM_WORLD);
    for (long i = 0; i < CI_INTS; i++) wrong += a[i * step] != cival(0, i);
    break;
  case 1:   /* MPI_Allgather, sent as ints, received in t */
    for (long i = 0; i < m; i++) a[i] = cival(r, i);
    MPI_Allgather(a, m, MPI_INT, b, m, t, MPI_COMM_WORLD);
    for (long i = 0; i < CI_INTS; i++) wrong += b[i * step] != cival((int)(i / m), i % m);
    break;
  case 2:   /* MPI_Gather to rank 0, received in t */
    for (long i = 0; i < m; i++) a[i] = cival(r, i);
    MPI_Gather(a, m, MPI_INT, b, m, t, 0, MPI_COMM_WORLD);
    for (long i = 0; r == 0 && i < CI_INTS; i++) wrong += b[i * step] != cival((int)(i / m), i % m);
    break;
  case 3:   /* MPI_Scatter from rank 0, sent and received in t */
    for (long i = 0; r == 0 && i < CI_INTS; i++) a[i * step] = cival((int)(i / m), i % m);
    MPI_Scatter(a, m, t, b, m, t, 0, MPI_COMM_WORLD);
    for (long i = 0; i < m; i++) wrong += b[i * step] != cival(r, i);
    break;
  case 6: {   /* MPI_Alltoallv, sent as ints, received in t; blocks in reverse order at both ends */
    int cnt[CI_RANKS], sd[CI_RANKS], rd[CI_RANKS];
    for (int q = 0; q < p; q++) cnt[q] = m, sd[q] = rd[q] = (p - 1 - q) * m;
    for (int q = 0; q < p; q++)
      for (long i = 0; i < m; i++) a[sd[q] + i] = cival(r, q * m + i);
    MPI_Alltoallv(a, cnt, sd, MPI_INT, b, cnt, rd, t, MPI_COMM_WORLD);
    for (int q = 0; q < p; q++)
      for (long i = 0; i < m; i++) wrong += b[(rd[q] + i) * step] != cival(q, r * m + i);
    break;
  }
  case 7:   /* MPI_Allgatherv, sent as ints, received in t, blocks in rank order */
  case 8:   /* MPI_Gatherv to rank 0, sent as ints, received in t, blocks in reverse order */
  case 9: {   /* MPI_Scatterv from rank 0, sent in t, blocks in reverse order, received in t */
    int cnt[CI_RANKS], at[CI_RANKS];
    for (int q = 0; q < p; q++) cnt[q] = m, at[q] = (C->op == 7 ? q : p - 1 - q) * m;
    if (C->op == 9) {
      for (int q = 0; r == 0 && q < p; q++)
        for (long i = 0; i < m; i++) a[(at[q] + i) * step] = cival(q, i);
      MPI_Scatterv(a, cnt, at, t, b, m, t, 0, MPI_COMM_WORLD);
      for (long i = 0; i < m; i++) wrong += b[i * step] != cival(r, i);
      break;
    }
    for (long i = 0; i < m; i++) a[i] = cival(r, i);
    if (C->op == 7)
      MPI_Allgatherv(a, m, MPI_INT, b, cnt, at, t, MPI_COMM_WORLD);
    else
      MPI_Gatherv(a, m, MPI_INT, b, cnt, at, t, 0, MPI_COMM_WORLD);
    for (int q = 0; q < p && (C->op == 7 || r == 0); q++)
      for (long i = 0; i < m; i++) wrong += b[(at[q] + i) * step] != cival(q, i);
    break;
  }
  case 10: {   /* MPI_Reduce_scatter_block, MPI_SUM of ints in t: rank r's block r of the sums */
    for (long i = 0; i < CI_INTS; i++) a[i * step] = cival(r, i);
    MPI_Reduce_scatter_block(a, b, m, t, MPI_SUM, MPI_COMM_WORLD);
    for (long i = 0; i < m; i++) {
      long want = 0;
      for (int q = 0; q < p; q++) want += cival(q, r * m + i);
      wrong += b[i * step] != (int)want;
    }
    break;
  }
  default:   /* MPI_Allreduce, MPI_Reduce to rank 0 or MPI_Scan: MPI_SUM of ints in t */
    for (long i = 0; i < CI_INTS; i++) a[i * step] = cival(r, i);
    if (C->op == 4)
      MPI_Allreduce(a, b, CI_INTS, t, MPI_SUM, MPI_COMM_WORLD);
    else if (C->op == 5)
      MPI_Reduce(a, b, CI_INTS, t, MPI_SUM, 0, MPI_COMM_WORLD);
    else
      MPI_Scan(a, b, CI_INTS, t, MPI_SUM, MPI_COMM_WORLD);
    for (long i = 0; i < CI_INTS && (C->op != 5 || r == 0); i++) {
      long want = 0;
      for (int q = 0; q < (C->op == 11 ? r + 1 : p); q++) want += cival(q, i);
      wrong += b[i * step] != (int)want;
    }
  }
  C->wrong += wrong;
  free(a);
  free(b);
  MPI_Type_free(&gappy);
  MPI_Finalize();
  return 0;
}

static void coll_in_place(void) {
  static const char *const name[] = {"MPI_Bcast",      "MPI_Allgather", "MPI_Gather",    "MPI_Scatter",
                                     "MPI_Allreduce",  "MPI_Reduce",    "MPI_Alltoallv", "MPI_Allgatherv",
                                     "MPI_Gatherv",    "MPI_Scatterv",  "MPI_Reduce_scatter_block",
                                     "MPI_Scan"};
  /* The packed copies a type with gaps costs: bcast, every rank's buffer;
   * allgather, every rank's receive buffer of all the blocks; gather, the
   * root's; scatter, the root's send buffer and every rank's block;
   * allreduce, every rank's result; reduce, the root's (its input is
   * packed in both types: the algorithms reduce into it); alltoallv and
   * allgatherv, every rank's receive buffer; gatherv, the root's; scatterv,
   * the root's send buffer and every rank's block; reduce_scatter_block,
   * every rank's block of the result; scan, every rank's result. */
  const long long n = (long long)CI_INTS * (long long)sizeof(int), p = CI_RANKS;
  const long long packed[] = {p * n, p * n, n, 2 * n, p * n, n, p * n, p * n, n, 2 * n, n, p * n};
  for (int op = 0; op < 12; op++)
    for (int b = 0; b < 2; b++) {
      long long mem[2];
      for (int gaps = 0; gaps < 2; gaps++) {
        collcase C = {op, gaps, 0};
        long long before = coll_sched_mem_given();
        mpih_result res = run(b, CI_RANKS, coll_bufs, &C);
        mem[gaps] = coll_sched_mem_given() - before;
        CHECK(res.rc == 0 && C.wrong == 0, "%s: %s of %d ints%s on %d ranks: rc %d, %ld wrong: %s", bname[b], name[op],
              CI_INTS, gaps ? " with gaps" : "", CI_RANKS, res.rc, C.wrong, res.err);
        mpih_result_free(&res);
      }
      CHECK(mem[1] - mem[0] == packed[op],
            "%s: %s of %d ints: the collective's memory %lld bytes with gaps, %lld contiguous: %lld more, %lld due",
            bname[b], name[op], CI_INTS, mem[1], mem[0], mem[1] - mem[0], packed[op]);
    }
}

/* ==== the runner's view of a rank ========================================= */

typedef struct {
  int flags[4];
} seen;

static int ends(void *ud) {
  seen *s = ud;
  int r = mp_rank(mp_self());
  if (r == 0) return 0;   /* never MPI */
  MPI_Initialized(&s->flags[0]);
  MPI_Init(NULL, NULL);
  MPI_Initialized(&s->flags[1]);
  if (r == 1) return 0;   /* no MPI_Finalize */
  MPI_Finalize();
  MPI_Finalized(&s->flags[2]);
  MPI_Initialized(&s->flags[3]);
  return 0;
}

static void rank_ends(void) {
  for (int b = 0; b < 2; b++) {
    seen s = {0};
    mpih_result res = run(b, 3, ends, &s);
    CHECK(res.rc == 0 && res.end[0] == INIT_NEVER && res.end[1] == INIT_UNFINALIZED &&
              res.end[2] == INIT_FINALIZED,
          "%s: ends %d %d %d", bname[b], res.end[0], res.end[1], res.end[2]);
    CHECK(s.flags[0] == 0 && s.flags[1] == 1 && s.flags[2] == 1 && s.flags[3] == 1, "%s: flags %d %d %d %d",
          bname[b], s.flags[0], s.flags[1], s.flags[2], s.flags[3]);
    mpih_result_free(&res);
  }
}

int main(void) {
  fatal_ends();
  errors_returned();
  deadlock_words();
  closed_forms();
  one_copy();
  coll_in_place();
  rank_ends();
  return check_done("test_mpi_p2p");
}
