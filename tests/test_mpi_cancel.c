/* test_mpi_cancel.c -- what tilesim's MPI_Cancel, generalized requests and
 * polling do that the portable programs of tests/mpi cannot check (an MPI
 * may or may not cancel a send; tilesim does as MPICH does): an eager send
 * no receive has matched is taken back, from the receiver's mailbox or
 * its unexpected queue, and a later send with the same envelope is the one
 * received, at its closed-form time; a synchronous send cancelled no
 * longer waits for its ack; a cancelled receive lets its message go to the
 * next receive; a rank that waits on a generalized request nobody
 * completes is named in the deadlock report; a rank that polls (MPI_Test,
 * MPI_Iprobe, MPI_Improbe, MPI_Testany, MPI_Wtime) without its clock
 * moving is stopped with one line naming it, the call and the time, while
 * the same loop with a poll cost ends.  And a request of a kind of its own
 * (core.h: a ring exchange on the collective context, as a nonblocking
 * collective would make one): its progress driven by MPI_Test and
 * MPI_Wait, its status and free called once, its closed-form time, its
 * name in a deadlock report; one advancing while its rank waits for
 * another (MPI's progress).  On the simulator (m = 1/4, 1/16 s a byte,
 * c = 1/8: exact times), and on threads where it applies. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/init.h"
#include "mpi/mpi.h"
#include "mpi/core.h"
#include "tests/check.h"
#include "mp/mp.h"
#include "tests/mpiharness.h"

static const char *const bname[] = {"sim", "threads"};

static mpih_result run(int b, int n, mpih_fn fn, void *ud, double poll_cost) {
  mpih_config cfg;
  mpih_config_init(&cfg, b, n);
  cfg.poll_cost = poll_cost;
  return mpih_result_of(&cfg, fn, ud);
}

static int has(const char *s, const char *part) { return strstr(s, part) != NULL; }

/* ==== cancelled sends ===================================================== */

typedef struct {
  int len;            /* the cancelled message's bytes */
  int ssend;          /* MPI_Issend instead of MPI_Isend */
  int cancelled;      /* rank 0's Test_cancelled */
  double t_wait;      /* rank 0's clock after the cancelled request's Wait */
  double t_recv;      /* rank 1's clock after its receive */
  int got;            /* what rank 1 received */
  int late;           /* rank 1 found the cancelled message after all */
} sc;

/* Rank 0 sends len bytes (tag 5) and cancels at once, computes 8 units
 * (1 s), then sends 4 bytes (value 2) with the same tag: rank 1's receive
 * gets those at 1 + 1/4 + 4/16 = 1.5, or when the cancelled message would
 * have come, 1/4 + len/16, if that is later (it went on the wire: a
 * message never overtakes one sent before it). */
static int cancel_unreceived(void *ud) {
  sc *S = ud;
  int r = mpih_init();
  if (r == 0) {
    char *b = calloc((size_t)S->len + 4, 1);
    MPI_Request q;
    MPI_Status st;
    if (S->ssend)
      MPI_Issend(b, S->len, MPI_BYTE, 1, 5, MPI_COMM_WORLD, &q);
    else
      MPI_Isend(b, S->len, MPI_BYTE, 1, 5, MPI_COMM_WORLD, &q);
    MPI_Cancel(&q);
    MPI_Wait(&q, &st);
    S->t_wait = MPI_Wtime();
    MPI_Test_cancelled(&st, &S->cancelled);
    memset(b, 0xee, (size_t)S->len + 4);   /* the buffer is the program's again */
    mp_compute(mp_self(), 8);
    int v = 2;
    MPI_Send(&v, 1, MPI_INT, 1, 5, MPI_COMM_WORLD);
    free(b);
  } else {
    char *b = calloc((size_t)S->len + 4, 1);
    MPI_Status st;
    MPI_Recv(b, S->len + 4, MPI_BYTE, 0, 5, MPI_COMM_WORLD, &st);
    S->t_recv = MPI_Wtime();
    memcpy(&S->got, b, sizeof S->got);
    MPI_Iprobe(0, 5, MPI_COMM_WORLD, &S->late, MPI_STATUS_IGNORE);
    free(b);
  }
  MPI_Finalize();
  return 0;
}

/* The message to cancel is in rank 1's unexpected queue when rank 0
 * cancels it: rank 1 received tag 6 (sent after it) first. */
static int cancel_unexpected(void *ud) {
  sc *S = ud;
  int r = mpih_init(), v = 1, w = 0;
  if (r == 0) {
    MPI_Request q;
    MPI_Status st;
    MPI_Isend(&v, 1, MPI_INT, 1, 5, MPI_COMM_WORLD, &q);
    MPI_Send(&v, 1, MPI_INT, 1, 6, MPI_COMM_WORLD);
    mp_compute(mp_self(), 8);   /* rank 1 has both by then (0.5) */
    MPI_Cancel(&q);
    MPI_Wait(&q, &st);
    MPI_Test_cancelled(&st, &S->cancelled);
    MPI_Send(&S->cancelled, 1, MPI_INT, 1, 7, MPI_COMM_WORLD);
  } else {
    MPI_Recv(&w, 1, MPI_INT, 0, 6, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Recv(&w, 1, MPI_INT, 0, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Iprobe(0, 5, MPI_COMM_WORLD, &S->late, MPI_STATUS_IGNORE);
  }
  MPI_Finalize();
  return 0;
}

/* A receive cancelled: the message it would have taken goes to the next
 * receive posted. */
static int cancel_receive(void *ud) {
  sc *S = ud;
  int r = mpih_init(), v = 9, w = 0;
  if (r == 0) {
    mp_compute(mp_self(), 8);
    MPI_Send(&v, 1, MPI_INT, 1, 5, MPI_COMM_WORLD);
  } else {
    MPI_Request q;
    MPI_Status st;
    MPI_Irecv(&w, 1, MPI_INT, 0, 5, MPI_COMM_WORLD, &q);
    MPI_Cancel(&q);
    MPI_Wait(&q, &st);
    MPI_Test_cancelled(&st, &S->cancelled);
    MPI_Recv(&S->got, 1, MPI_INT, 0, MPI_ANY_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    S->t_recv = MPI_Wtime();
    S->late = w;   /* the cancelled receive's buffer: untouched */
  }
  MPI_Finalize();
  return 0;
}

static void cancels(void) {
  static const int lens[3] = {8, 200, 200000};
  for (int k = 0; k < 3; k++) {
    for (int ss = 0; ss < 2; ss++) {
      sc S = {.len = lens[k], .ssend = ss};
      mpih_result res = run(MPIH_SIM, 2, cancel_unreceived, &S, 1e-6);
      double due = 0.25 + lens[k] * 0.0625 > 1.5 ? 0.25 + lens[k] * 0.0625 : 1.5;
      CHECK(res.rc == 0 && S.cancelled == 1 && S.t_wait == 0 && S.got == 2 && S.t_recv == due && !S.late,
            "%s of %d bytes cancelled: %d at %.17g; received %d at %.17g (2 at %.17g due), late %d: %s",
            ss ? "Issend" : "Isend", lens[k], S.cancelled, S.t_wait, S.got, S.t_recv, due, S.late, res.err);
      CHECK(res.messages == 2 && res.unread == 0, "a cancelled send's message: %lld sent (2 due), %lld unread",
            res.messages, res.unread);
      mpih_result_free(&res);
    }
  }
  for (int b = 0; b < 2; b++) {
    sc S = {0};
    mpih_result res = run(b, 2, cancel_unexpected, &S, 1e-6);
    CHECK(res.rc == 0 && (b == MPIH_THREADS || S.cancelled == 1) && S.late == !S.cancelled,
          "%s: cancel of an unexpected message: cancelled %d, still there %d: %s", bname[b], S.cancelled, S.late,
          res.err);
    mpih_result_free(&res);
    memset(&S, 0, sizeof S);
    res = run(b, 2, cancel_receive, &S, 1e-6);
    CHECK(res.rc == 0 && S.cancelled == 1 && S.got == 9 && S.late == 0, "%s: a cancelled receive: %d %d %d: %s",
          bname[b], S.cancelled, S.got, S.late, res.err);
    if (b == MPIH_SIM) CHECK(S.t_recv == 1.5, "a cancelled receive: the next at %.17g (1.5 due)", S.t_recv);
    mpih_result_free(&res);
  }
}

/* ==== generalized requests nobody completes =============================== */

static int noop_query(void *extra, MPI_Status *st) {
  (void)extra, (void)st;
  return MPI_SUCCESS;
}
static int noop_free(void *extra) { return (void)extra, MPI_SUCCESS; }
static int noop_cancel(void *extra, int complete) { return (void)extra, (void)complete, MPI_SUCCESS; }

static int greq_stuck(void *ud) {
  (void)ud;
  MPI_Init(NULL, NULL);
  MPI_Request q;
  MPI_Grequest_start(noop_query, noop_free, noop_cancel, NULL, &q);
  MPI_Wait(&q, MPI_STATUS_IGNORE);
  MPI_Finalize();
  return 0;
}

static void greq_deadlock(void) {
  for (int b = 0; b < 2; b++) {
    mpih_result res = run(b, 2, greq_stuck, NULL, 1e-6);
    CHECK(res.rc != 0 && res.deadlock && has(res.err, "rank 0 waits in MPI_Wait(MPI_Grequest_start)") &&
              has(res.err, "rank 1 waits in MPI_Wait(MPI_Grequest_start)"),
          "%s: a Wait on a generalized request nobody completes: %s", bname[b], res.err);
    mpih_result_free(&res);
  }
}

/* ==== ranks that poll for ever ============================================ */

enum { P_TEST, P_IPROBE, P_IMPROBE, P_TESTANY, P_WTIME, P_KINDS };
static const char *const pname[P_KINDS] = {"MPI_Test", "MPI_Iprobe", "MPI_Improbe", "MPI_Testany", "MPI_Wtime"};

typedef struct {
  int kind;
  long polls;
} spin;

/* Rank 1 polls for a message nobody sends (MPI_Wtime: for 1 s to pass),
 * up to 10^6 times; rank 0 computes 2 units (1/4 s) and waits in a
 * barrier. */
static int polls(void *ud) {
  spin *S = ud;
  int r = mpih_init(), v, flag = 0;
  if (r == 1) {
    MPI_Request q;
    MPI_Message m;
    MPI_Irecv(&v, 1, MPI_INT, 0, 99, MPI_COMM_WORLD, &q);
    double t0 = mp_time(mp_self());   /* (not MPI_Wtime: it polls too) */
    for (S->polls = 0; S->polls < 1000000 && !flag; S->polls++) {
      int idx;
      switch (S->kind) {
      case P_TEST: MPI_Test(&q, &flag, MPI_STATUS_IGNORE); break;
      case P_IPROBE: MPI_Iprobe(0, 98, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE); break;
      case P_IMPROBE: MPI_Improbe(MPI_ANY_SOURCE, 98, MPI_COMM_WORLD, &flag, &m, MPI_STATUS_IGNORE); break;
      case P_TESTANY: MPI_Testany(1, &q, &idx, &flag, MPI_STATUS_IGNORE); break;
      default: flag = MPI_Wtime() - t0 >= 1; break;
      }
      if (S->kind != P_WTIME && mp_time(mp_self()) - t0 >= 1) break;   /* with a poll cost: 1 s */
    }
    MPI_Cancel(&q);
    MPI_Wait(&q, MPI_STATUS_IGNORE);
  } else {
    mp_compute(mp_self(), 2);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}

static void spinning(void) {
  for (int k = 0; k < P_KINDS; k++) {
    spin S = {k, 0};
    mpih_result res = run(MPIH_SIM, 2, polls, &S, 0);
    char want[160];
    snprintf(want, sizeof want, "rank 1: %s called 100000 times at t=0 s without the rank's clock moving", pname[k]);
    CHECK(res.rc != 0 && res.aborted && res.abort_code == 1 && has(res.err, want) && has(res.err, "poll forever") &&
              S.polls < 100000 + 10,
          "%s spinning: %s (polls %ld)", pname[k], res.err, S.polls);
    mpih_result_free(&res);
    /* The same loop with a cost per poll (and per MPI_Wtime): 1 s passes. */
    memset(&S, 0, sizeof S);
    S.kind = k;
    mpih_config cfg;
    mpih_config_init(&cfg, MPIH_SIM, 2);
    cfg.poll_cost = 0.0625;
    if (k == P_WTIME) init_set_wtime_cost(0.0625);
    mpih_run_fn(&cfg, polls, &S, &res);
    init_set_wtime_cost(0);
    long due = k == P_WTIME ? 17 : 15;   /* the 17th Wtime reads 1 s; the 15th poll ends at 1 s */
    CHECK(res.rc == 0 && S.polls == due, "%s with a poll cost: %s (%ld polls, %ld due)", pname[k], res.err, S.polls,
          due);
    mpih_result_free(&res);
  }
}

/* ==== a request of a kind of its own ====================================== */

typedef struct {
  MPI_Request r[2];   /* receive from the left, send to the right */
  int v, w;           /* sent, received */
  int progress, statuses, frees;
  int never;          /* a kind that never completes */
} xchg;

static int x_progress(void *state) {
  xchg *x = state;
  x->progress++;
  int a = coll_p2p_done(&x->r[0], MPI_STATUS_IGNORE), b = coll_p2p_done(&x->r[1], MPI_STATUS_IGNORE);
  return a && b && !x->never;
}

static int x_status(void *state, MPI_Status *st) {
  xchg *x = state;
  x->statuses++;
  st->MPI_SOURCE = 7;
  st->MPI_TAG = x->w;
  return MPI_SUCCESS;
}

static int x_free(void *state) {
  ((xchg *)state)->frees++;
  return MPI_SUCCESS;
}

static const req_kind xchg_kind = {"MPI_Ixchg", x_progress, NULL, x_status, x_free, NULL};

typedef struct {
  int wait;           /* MPI_Wait, else MPI_Test until done */
  int never;
  xchg x[4];
  double t[4];        /* each rank's clock when done */
  long fails[4];
} kindrun;

static int kinds(void *ud) {
  kindrun *K = ud;
  int r = mpih_init(), n;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  xchg *x = &K->x[r];
  x->v = 100 + r;
  x->never = K->never;
  coll_p2p_irecv(&x->w, 1, MPI_INT, (r + n - 1) % n, 3, MPI_COMM_WORLD, &x->r[0]);
  coll_p2p_isend(&x->v, 1, MPI_INT, (r + 1) % n, 3, MPI_COMM_WORLD, &x->r[1]);
  MPI_Request q;
  MPI_Status st;
  req_start(&xchg_kind, x, &q);
  if (K->wait) {
    MPI_Wait(&q, &st);
  } else {
    int flag = 0;
    for (MPI_Test(&q, &flag, &st); !flag; MPI_Test(&q, &flag, &st)) K->fails[r]++;
  }
  K->t[r] = MPI_Wtime();
  if (st.MPI_SOURCE != 7 || st.MPI_TAG != x->w || q != MPI_REQUEST_NULL) x->statuses = -100;
  MPI_Finalize();
  return 0;
}

static void kind_requests(void) {
  for (int w = 0; w < 2; w++) {
    kindrun K = {0};
    K.wait = w;
    mpih_result res = run(MPIH_SIM, 4, kinds, &K, 0.0625);
    int bad = 0;
    for (int r = 0; r < 4; r++)
      bad += K.x[r].w != 100 + (r + 3) % 4 || K.x[r].statuses != 1 || K.x[r].frees != 1 || K.t[r] != 0.5 ||
             K.fails[r] != (w ? 0 : 8);
    /* The message arrives at 1/4 + 4/16 = 1/2; tests at 0, 1/16, ...: the
     * one at 1/2 finds it, after 8 failed. */
    CHECK(res.rc == 0 && bad == 0, "a kind of its own (%s): %d ranks wrong (rank 0: got %d, statuses %d, frees %d, "
                                   "done at %.17g after %ld failed tests): %s",
          w ? "MPI_Wait" : "MPI_Test", bad, K.x[0].w, K.x[0].statuses, K.x[0].frees, K.t[0], K.fails[0], res.err);
    mpih_result_free(&res);
  }
  for (int b = 0; b < 2; b++) {
    kindrun K = {0};
    K.wait = K.never = 1;
    mpih_result res = run(b, 2, kinds, &K, 0.0625);
    CHECK(res.rc != 0 && res.deadlock && has(res.err, "rank 1 waits in MPI_Wait(MPI_Ixchg)"),
          "%s: a kind that never completes: %s", bname[b], res.err);
    mpih_result_free(&res);
  }
}

/* MPI's progress: a request of a kind advances while its rank waits for
 * another.  Rank 0's relay forwards rank 1's message (tag 10) back to it
 * (tag 11) once it comes; rank 0 waits only for rank 1's answer (tag 12),
 * which rank 1 sends once the relay's message is there: 1/2 s a hop, done
 * at 1.5. */
typedef struct {
  MPI_Request in, out, answer;
  int v, stage;
} relay;

static int relay_progress(void *state) {
  relay *x = state;
  if (x->stage == 0 && coll_p2p_done(&x->in, MPI_STATUS_IGNORE)) {
    coll_p2p_isend(&x->v, 1, MPI_INT, 1, 11, MPI_COMM_WORLD, &x->out);
    x->stage = 1;
  }
  return x->stage == 1 && coll_p2p_done(&x->out, MPI_STATUS_IGNORE);
}

static int answer_progress(void *state) { return coll_p2p_done(&((relay *)state)->answer, MPI_STATUS_IGNORE); }

static const req_kind relay_kind = {"MPI_Irelay", relay_progress, NULL, NULL, NULL, NULL};
static const req_kind answer_kind = {"MPI_Ianswer", answer_progress, NULL, NULL, NULL, NULL};

typedef struct {
  double t;
  int v, w;
} relayrun;

static int relays(void *ud) {
  relayrun *K = ud;
  int r = mpih_init(), v = 5;
  if (r == 0) {
    relay x = {.stage = 0};
    MPI_Request a, b;
    coll_p2p_irecv(&x.v, 1, MPI_INT, 1, 10, MPI_COMM_WORLD, &x.in);
    req_start(&relay_kind, &x, &b);
    coll_p2p_irecv(&K->w, 1, MPI_INT, 1, 12, MPI_COMM_WORLD, &x.answer);
    req_start(&answer_kind, &x, &a);
    MPI_Wait(&a, MPI_STATUS_IGNORE);
    K->t = MPI_Wtime();
    MPI_Wait(&b, MPI_STATUS_IGNORE);
  } else if (r == 1) {
    coll_p2p_send(&v, 1, MPI_INT, 0, 10, MPI_COMM_WORLD);
    coll_p2p_recv(&K->v, 1, MPI_INT, 0, 11, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    K->v++;
    coll_p2p_send(&K->v, 1, MPI_INT, 0, 12, MPI_COMM_WORLD);
  }
  MPI_Finalize();
  return 0;
}

static void progress_of_all(void) {
  for (int b = 0; b < 2; b++) {
    relayrun K = {0};
    mpih_result res = run(b, 2, relays, &K, 0.0625);
    CHECK(res.rc == 0 && K.v == 6 && K.w == 6 && (b == MPIH_THREADS || K.t == 1.5),
          "%s: a kind advancing while its rank waits for another: %d %d at %.17g (6 6 at 1.5 due): %s", bname[b], K.v,
          K.w, K.t, res.err);
    mpih_result_free(&res);
  }
}

int main(void) {
  kind_requests();
  progress_of_all();
  cancels();
  greq_deadlock();
  spinning();
  return check_done("test_mpi_cancel");
}
