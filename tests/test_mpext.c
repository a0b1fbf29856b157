/* test_mpext.c -- the calls mp.h offers layers above it (mp_self, mp_user,
 * mp_wait, mp_label, mp_busy, mp_sleep, mp_yield, mp_exit, mp_abort), on the
 * simulator and on threads.
 *
 * On the simulator, times are checked against the model of sim.h with
 * binary-fraction costs (exact); on threads, the same programs must deliver
 * the same messages and end the same way. */
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "mp/mp.h"
#include "sim/sim.h"
#include "mp/threads.h"
#include "tests/simrun.h"

enum { SIM, THREADS };
static const char *const backend[] = {"sim", "threads"};

typedef struct {
  int rc;
  char err[1024];
  sim_stats ss;
  mpt_stats ts;
  double finish[8];
  int done[8];
} result;

/* simrun's machine, ideal, with local messages costing 1/2. */
static sim_config config(int procs) {
  sim_config cfg = simrun_config(SIM_NET_IDEAL, procs);
  cfg.local = 0.5;
  return cfg;
}

/* Run n ranks of fn (each with ud) on backend b; procs processors on the simulator. */
static result run(int b, int n, int procs, mp_main fn, void *ud) {
  result res;
  memset(&res, 0, sizeof res);
  mp_proc pr[8];
  for (int i = 0; i < n; i++) pr[i] = (mp_proc){fn, ud};
  if (b == SIM) {
    sim_config cfg = config(procs);
    sim *s = sim_new(&cfg, n, res.err, sizeof res.err);
    if (!s) abort();
    res.rc = sim_run(s, pr, res.err, sizeof res.err);
    res.ss = *sim_stats_get(s);
    for (int i = 0; i < n; i++) res.finish[i] = sim_rank(s, i)->finish, res.done[i] = sim_rank(s, i)->done;
    sim_free(s);
  } else {
    mpt_config cfg;
    mpt_config_init(&cfg);
    cfg.warn = NULL;
    mpt *t = mpt_new(&cfg, n, res.err, sizeof res.err);
    if (!t) abort();
    res.rc = mpt_run(t, pr, res.err, sizeof res.err);
    res.ts = *mpt_stats_get(t);
    for (int i = 0; i < n; i++) res.done[i] = mpt_rank(t, i)->done;
    mpt_free(t);
  }
  return res;
}

/* ==== mp_self and mp_user ================================================= */

typedef struct {
  atomic_int bad;      /* mp_self or mp_user wrong somewhere */
  atomic_int ran;
} selfcheck;

/* Ranks pass a token around a ring three times; at every step each checks
 * that mp_self is itself and that its user slot still holds its own value
 * (set at the start: every switch between ranks must keep both). */
static void self_main(mp *self, void *ud) {
  selfcheck *c = ud;
  int me = mp_rank(self), n = mp_size(self);
  if (mp_self() != self || mp_user(self) != NULL) atomic_fetch_add(&c->bad, 1);
  int mine = 1000 + me;
  mp_set_user(self, &mine);
  for (int lap = 0; lap < 3; lap++) {
    int tok = 0;
    if (me == 0) mp_send(self, 1 % n, 0, &tok, sizeof tok);
    mp_recv(self, (me + n - 1) % n, 0, &tok, sizeof tok, NULL);
    if (mp_self() != self || mp_user(self) != &mine || *(int *)mp_user(mp_self()) != 1000 + me)
      atomic_fetch_add(&c->bad, 1);
    if (me != 0) mp_send(self, (me + 1) % n, 0, &tok, sizeof tok);
    mp_compute(self, me);   /* the simulator switches on compute too */
    if (mp_self() != self) atomic_fetch_add(&c->bad, 1);
  }
  atomic_fetch_add(&c->ran, 1);
}

static void test_self(int b) {
  CHECK(mp_self() == NULL, "%s: mp_self outside a run is not NULL", backend[b]);
  selfcheck c;
  atomic_init(&c.bad, 0);
  atomic_init(&c.ran, 0);
  result r = run(b, 5, 2, self_main, &c);
  CHECK(r.rc == 0, "%s: self ring: %s", backend[b], r.err);
  CHECK(atomic_load(&c.ran) == 5 && atomic_load(&c.bad) == 0, "%s: mp_self/mp_user wrong %d times (%d ran)",
        backend[b], atomic_load(&c.bad), atomic_load(&c.ran));
  CHECK(mp_self() == NULL, "%s: mp_self after a run is not NULL", backend[b]);
}

/* ==== mp_wait ============================================================= */

typedef struct {
  atomic_int bad;
  double t_wait, t_recv;   /* rank 0's clock after mp_wait, after mp_recv */
} waitcheck;

/* Rank 1 sends 4 bytes (tag 5) at t = 0 and, after computing 1 unit, 4
 * bytes (tag 6).  Rank 0 waits for tag 6 first: the wait must show tag 6
 * and leave both messages; a wait for any then shows tag 5 (the earlier
 * arrival); recvs take them in that order. */
static void wait_main(mp *self, void *ud) {
  waitcheck *c = ud;
  if (mp_rank(self) == 1) {
    int a = 15, b = 25;
    mp_send(self, 0, 5, &a, sizeof a);
    mp_compute(self, 1);
    mp_send(self, 0, 6, &b, sizeof b);
    return;
  }
  mp_status st = {-9, -9, 99};
  int rc = mp_wait(self, 1, 6, &st);
  if (rc != MP_OK || st.source != 1 || st.tag != 6 || st.len != 4) atomic_fetch_add(&c->bad, 1);
  c->t_wait = mp_time(self);
  rc = mp_wait(self, MP_ANY, MP_ANY, &st);
  if (rc != MP_OK || st.source != 1 || st.tag != 5 || st.len != 4) atomic_fetch_add(&c->bad, 1);
  if (mp_probe(self, 1, 5, NULL) != 1 || mp_probe(self, 1, 6, NULL) != 1) atomic_fetch_add(&c->bad, 1);
  int x = 0;
  rc = mp_recv(self, MP_ANY, MP_ANY, &x, sizeof x, &st);
  if (rc != MP_OK || st.tag != 5 || x != 15) atomic_fetch_add(&c->bad, 1);
  rc = mp_recv(self, MP_ANY, MP_ANY, &x, sizeof x, &st);
  if (rc != MP_OK || st.tag != 6 || x != 25) atomic_fetch_add(&c->bad, 1);
  c->t_recv = mp_time(self);
}

static void test_wait(int b) {
  waitcheck c = {0};
  atomic_init(&c.bad, 0);
  result r = run(b, 2, 2, wait_main, &c);
  CHECK(r.rc == 0, "%s: wait: %s", backend[b], r.err);
  CHECK(atomic_load(&c.bad) == 0, "%s: mp_wait showed or left the wrong messages (%d)", backend[b],
        atomic_load(&c.bad));
  if (b == SIM) {
    /* Tag 6 leaves rank 1 at c = 0.125 and takes m + 4 per_byte = 0.5
     * (tag 5, sent at 0, arrived at 0.5: no overtaking to wait for). */
    double expect = 0.125 + 0.25 + 4 * 0.0625;
    CHECK(c.t_wait == expect, "sim: mp_wait returned at %.17g, the model says %.17g", c.t_wait, expect);
    CHECK(c.t_recv == expect, "sim: the receives after the wait cost time: %.17g, not %.17g", c.t_recv,
          expect);
    CHECK(r.ss.unread == 0 && r.ss.received == 2, "sim: %lld received, %lld unread", r.ss.received,
          r.ss.unread);
  }
}

/* ==== mp_busy and mp_sleep ================================================ */

typedef struct {
  int sleeper;   /* 1: rank 0 sleeps 1 s; 0: it is busy 1 s */
} napcheck;

/* Two ranks on one processor: rank 0 sleeps (or is busy) 1 s while rank 1
 * computes 8 units (1 s).  Sleeping does not hold the processor: both end
 * at 1; busy does: the second ends at 2. */
static void nap_main(mp *self, void *ud) {
  const napcheck *c = ud;
  if (mp_rank(self) == 0) {
    if (c->sleeper) mp_sleep(self, 1);
    else mp_busy(self, 1);
  } else {
    mp_compute(self, 8);
  }
}

static void test_nap(void) {
  for (int sleeper = 0; sleeper < 2; sleeper++) {
    napcheck c = {sleeper};
    result r = run(SIM, 2, 1, nap_main, &c);
    CHECK(r.rc == 0, "sim: nap: %s", r.err);
    double e0 = 1, e1 = sleeper ? 1 : 2;
    CHECK(r.finish[0] == e0 && r.finish[1] == e1, "sim: %s: ranks end at %g and %g, not %g and %g",
          sleeper ? "mp_sleep" : "mp_busy", r.finish[0], r.finish[1], e0, e1);
  }
  /* The statistics identity, with slept. */
  sim_config cfg = config(1);
  sim *s = sim_new(&cfg, 2, NULL, 0);
  napcheck c = {1};
  mp_proc pr[2] = {{nap_main, &c}, {nap_main, &c}};
  char err[256];
  CHECK(sim_run(s, pr, err, sizeof err) == 0, "sim: %s", err);
  const sim_rank_stats *rs = sim_rank(s, 0);
  CHECK(rs->slept == 1 && rs->finish == rs->compute + rs->cpu_wait + rs->overhead + rs->recv_wait + rs->slept,
        "sim: slept %g, finish %g", rs->slept, rs->finish);
  sim_free(s);
}

static void bad_nap_main(mp *self, void *ud) {
  (void)ud;
  if (mp_busy(self, -1) != MP_EARG || mp_sleep(self, NAN) != MP_EARG) abort();
}

static void test_bad_nap(int b) {
  result r = run(b, 1, 1, bad_nap_main, NULL);
  CHECK(r.rc != 0 && strstr(r.err, "mp_busy(-1)") && strstr(r.err, "mp_sleep(nan)"),
        "%s: bad mp_busy/mp_sleep: rc %d, '%s'", backend[b], r.rc, r.err);
}

/* ==== mp_yield ============================================================ */

typedef struct {
  atomic_int next;     /* the order the ranks' steps ran in */
  int at[4];           /* step k's place in it */
  int yield;           /* 0: rank 0 does not yield (the reference order) */
  int rc[2];           /* mp_yield's answers */
  double t[2];         /* rank 0's clock after each yield */
} yieldcheck;

static void step(yieldcheck *c, int k) { c->at[k] = atomic_fetch_add(&c->next, 1); }

/* A progress function that yields: mp_yield does nothing there. */
static void yield_progress(mp *self, void *ud) {
  yieldcheck *c = ud;
  mp_status st;
  while (mp_probe(self, MP_ANY, MP_ANY, &st) == 1) {
    char b;
    mp_recv(self, st.source, st.tag, &b, 1, NULL);
  }
  c->rc[1] = mp_yield(self);
  c->t[1] = mp_time(self);
}

/* Ranks 0 to 2 due at 0 on their own processors.  Rank 0 runs first (step
 * 0), yields, and goes on (step 1); rank 1 takes step 2 at 0; rank 2
 * computes 8 units (1 s), then takes step 3.  With the yield rank 1 acts
 * between rank 0's steps, and rank 2 starts computing there too: 0 2 1 3;
 * without it 0 1 2 3.  Then rank 0 computes while rank 1's message comes
 * and its progress function yields (nothing to do there). */
static void yield_main(mp *self, void *ud) {
  yieldcheck *c = ud;
  int me = mp_rank(self);
  if (me == 0) {
    step(c, 0);
    c->rc[0] = c->yield ? mp_yield(self) : MP_OK;
    c->t[0] = mp_time(self);
    step(c, 1);
    mp_set_progress(self, yield_progress, c);
    mp_compute(self, 16);
    mp_set_progress(self, NULL, NULL);
  } else if (me == 1) {
    step(c, 2);
    mp_send(self, 0, 5, "x", 1);
  } else {
    mp_compute(self, 8);
    step(c, 3);
  }
}

/* One processor: rank 0 computes 16 units (2 s) with yield_progress set;
 * rank 1 sends it a byte at 0 (local: it comes at 1/2), sleeps until then,
 * and computes 8 units, waiting for the processor until 2: it ends at 3.
 * (Were the progress function's yield to give way, rank 1 would compute at
 * 1/2 on a processor lent to rank 0's progress.) */
static void lent_main(mp *self, void *ud) {
  yieldcheck *c = ud;
  if (mp_rank(self) == 0) {
    mp_set_progress(self, yield_progress, c);
    mp_compute(self, 16);
    mp_set_progress(self, NULL, NULL);
  } else {
    mp_send(self, 0, 5, "x", 1);
    mp_sleep(self, 0.5);
    mp_compute(self, 8);
  }
}

static void test_yield(int b) {
  if (b == SIM) {
    yieldcheck c;
    memset(&c, 0, sizeof c);
    result r = run(SIM, 2, 1, lent_main, &c);
    CHECK(r.rc == 0 && c.rc[1] == MP_OK && c.t[1] == 0.5 && r.finish[0] == 2 && r.finish[1] == 3,
          "sim: mp_yield in a progress function: rc %d, at %g, ends %g %g (0.5, 2, 3 due): %s", r.rc, c.t[1],
          r.finish[0], r.finish[1], r.err);
  }
  for (int y = 0; y < 2; y++) {
    yieldcheck c;
    memset(&c, 0, sizeof c);
    c.yield = y;
    result r = run(b, 3, 3, yield_main, &c);
    CHECK(r.rc == 0 && c.rc[0] == MP_OK && c.rc[1] == MP_OK, "%s: mp_yield: rc %d (%d, %d): %s", backend[b], r.rc,
          c.rc[0], c.rc[1], r.err);
    if (b != SIM) continue;
    int order = c.at[0] == 0 && c.at[1] == (y ? 2 : 1) && c.at[2] == (y ? 1 : 2) && c.at[3] == 3;
    CHECK(order, "sim: %s: steps ran at %d %d %d %d", y ? "mp_yield" : "no yield", c.at[0], c.at[1], c.at[2],
          c.at[3]);
    /* The clock stays; rank 1's byte (sent at 0) comes at m + 1/16 = 5/16 into rank 0's 2 s of computing,
     * which the progress function's yield leaves as they are. */
    CHECK(c.t[0] == 0 && c.t[1] == 0.3125 && r.finish[0] == 2 && r.finish[2] == 1,
          "sim: mp_yield moved a clock: %g %g, ends %g %g (0, 0.3125, 2, 1 due)", c.t[0], c.t[1], r.finish[0],
          r.finish[2]);
  }
}

/* ==== mp_exit ============================================================= */

typedef struct {
  atomic_int after;   /* code after mp_exit ran */
  atomic_int got;
} exitcheck;

/* Deep in the stack (called through a pointer: gcc 12 takes a recursion
 * that ends in a _Noreturn call for an endless one). */
static void exit_deep(mp *self, exitcheck *c, int depth);
static void (*volatile deeper)(mp *, exitcheck *, int) = exit_deep;
static void exit_deep(mp *self, exitcheck *c, int depth) {
  if (depth > 0) deeper(self, c, depth - 1);
  else mp_exit(self);
  atomic_fetch_add(&c->after, 1);
}

/* Rank 1 sends, computes 2 units, then leaves through mp_exit from deep in
 * its stack; rank 0 receives and goes on. */
static void exit_main(mp *self, void *ud) {
  exitcheck *c = ud;
  int v = 7;
  if (mp_rank(self) == 1) {
    mp_send(self, 0, 1, &v, sizeof v);
    mp_compute(self, 2);
    exit_deep(self, c, 20);
    atomic_fetch_add(&c->after, 1);
    return;
  }
  mp_recv(self, 1, 1, &v, sizeof v, NULL);
  atomic_fetch_add(&c->got, v);
  mp_compute(self, 4);
}

static void test_exit(int b) {
  exitcheck c;
  atomic_init(&c.after, 0);
  atomic_init(&c.got, 0);
  result r = run(b, 2, 2, exit_main, &c);
  CHECK(r.rc == 0, "%s: exit: %s", backend[b], r.err);
  CHECK(atomic_load(&c.after) == 0 && atomic_load(&c.got) == 7 && r.done[0] && r.done[1],
        "%s: mp_exit: %d statements after it ran, got %d, done %d %d", backend[b], atomic_load(&c.after),
        atomic_load(&c.got), r.done[0], r.done[1]);
  if (b == SIM) CHECK(r.finish[1] == 0.25 && r.finish[0] == 0.25 + 4 * 0.0625 + 0.5,
                      "sim: mp_exit: finishes %g and %g", r.finish[1], r.finish[0]);
  /* 0.25: rank 1's 2 units; rank 0: the message's m + 4 per_byte, then 4 units. */
}

/* ==== mp_abort and mp_label =============================================== */

typedef struct {
  atomic_int stopped;   /* ranks whose blocked recv returned MP_ESTOPPED */
  atomic_int after;
} abortcheck;

/* Rank 2 computes, then aborts with code 3; ranks 0 and 1 wait for messages
 * that never come, and must be let go with MP_ESTOPPED. */
static void abort_main(mp *self, void *ud) {
  abortcheck *c = ud;
  if (mp_rank(self) == 2) {
    mp_compute(self, 1);
    mp_abort(self, 3, "rank 2 gave up");
    atomic_fetch_add(&c->after, 1);
  }
  int v;
  int rc = mp_recv(self, MP_ANY, 9, &v, sizeof v, NULL);
  if (rc == MP_ESTOPPED) atomic_fetch_add(&c->stopped, 1);
  if (mp_send(self, 0, 1, &v, sizeof v) != MP_ESTOPPED) atomic_fetch_add(&c->after, 100);
}

static void test_abort(int b) {
  abortcheck c;
  atomic_init(&c.stopped, 0);
  atomic_init(&c.after, 0);
  result r = run(b, 3, 3, abort_main, &c);
  int aborted = b == SIM ? r.ss.aborted : r.ts.aborted, code = b == SIM ? r.ss.abort_code : r.ts.abort_code;
  CHECK(r.rc != 0 && strstr(r.err, "rank 2 gave up") && aborted && code == 3,
        "%s: abort: rc %d, aborted %d code %d, '%s'", backend[b], r.rc, aborted, code, r.err);
  CHECK(atomic_load(&c.stopped) == 2 && atomic_load(&c.after) == 0, "%s: abort: %d ranks stopped, after %d",
        backend[b], atomic_load(&c.stopped), atomic_load(&c.after));
  CHECK(!strstr(r.err, "deadlock"), "%s: an abort is not a deadlock: '%s'", backend[b], r.err);
}

static void describe(void *ud, char *buf, size_t len) {
  snprintf(buf, len, "MPI_Recv(source=%d, tag=7, MPI_COMM_WORLD)", *(int *)ud);
}

/* Ranks 0 and 1 wait for each other: rank 0 with a label, rank 1 without. */
static void label_main(mp *self, void *ud) {
  (void)ud;
  int peer = 1 - mp_rank(self), v;
  if (mp_rank(self) == 0) mp_label(self, describe, &peer);
  mp_recv(self, peer, 7, &v, sizeof v, NULL);
}

static void test_label(int b) {
  result r = run(b, 2, 2, label_main, NULL);
  CHECK(r.rc != 0 && strstr(r.err, "rank 0 waits in MPI_Recv(source=1, tag=7, MPI_COMM_WORLD)") &&
            strstr(r.err, "rank 1 waits in recv(src=0, tag=7)"),
        "%s: the deadlock report does not use the label: '%s'", backend[b], r.err);
}

/* ==== mp_set_hooks ======================================================== */

static atomic_int entered, left;

/* Charges half a second before every call, as a runtime charges the
 * computing a program did between its calls. */
static void hook_enter(mp *self) {
  atomic_fetch_add(&entered, 1);
  mp_charge(self, 0.5);
}

static void hook_leave(mp *self) {
  (void)self;
  atomic_fetch_add(&left, 1);
}

typedef struct {
  double t[2];   /* rank 0's clock after its compute, and as mp_time reads it */
} hookcheck;

/* Rank 0: compute 1 unit, read the clock, send; rank 1: receive. */
static void hook_main(mp *self, void *ud) {
  hookcheck *c = ud;
  int v = 1;
  if (mp_rank(self) == 0) {
    mp_compute(self, 1);
    c->t[0] = mp_time(self);
    mp_send(self, 1, 0, &v, sizeof v);
  } else {
    mp_recv(self, 0, 0, &v, sizeof v, NULL);
  }
}

static void test_hooks(int b) {
  static const mp_hooks h = {hook_enter, hook_leave};
  hookcheck c = {{0, 0}};
  atomic_store(&entered, 0);
  atomic_store(&left, 0);
  mp_set_hooks(&h);
  result r = run(b, 2, 2, hook_main, &c);
  mp_set_hooks(NULL);
  /* Rank 0: compute, time, send; rank 1: recv: 4 calls, each between the hooks. */
  CHECK(r.rc == 0 && atomic_load(&entered) == 4 && atomic_load(&left) == 4, "%s: hooks: %d entered, %d left (%s)",
        backend[b], atomic_load(&entered), atomic_load(&left), r.err);
  if (b == SIM) {
    /* 0.5 charged before the compute (0.125), 0.5 more before the time is read. */
    CHECK(c.t[0] == 1.125, "sim: with the hooks' charges the clock reads %.17g, not 1.125", c.t[0]);
    /* The message: sent at 1.625 (after a charge), m + 4 per_byte = 0.5; the
     * receive's charge (0.5, at 0) is before it waits. */
    CHECK(r.finish[1] == 2.125, "sim: hooks: rank 1 ends at %.17g, not 2.125", r.finish[1]);
  }
}

/* ==== mp_call_begin and mp_call_end ====================================== */

/* Rank 0: a call that computes 1 unit and sends (shown), one with another
 * nested in it (the outer shown), one that does nothing (not shown); rank 1:
 * a call that receives (shown, from 0 to the arrival). */
static void calls_main(mp *self, void *ud) {
  (void)ud;
  int v = 1;
  if (mp_rank(self) == 0) {
    mp_call_begin(self, "MPI_Outer");
    mp_compute(self, 1);
    mp_send(self, 1, 0, &v, sizeof v);
    mp_call_end(self);
    mp_call_begin(self, "MPI_Two");
    mp_call_begin(self, "MPI_Inner");
    mp_compute(self, 2);
    mp_call_end(self);
    mp_call_end(self);
    mp_call_begin(self, "MPI_Nothing");
    mp_call_end(self);
  } else {
    mp_call_begin(self, "MPI_Recv");
    mp_recv(self, 0, 0, &v, sizeof v, NULL);
    mp_call_end(self);
  }
}

static void test_calls(void) {
  sim_config cfg = config(2);
  char err[256], *text = NULL;
  size_t len = 0;
  FILE *csv = open_memstream(&text, &len);
  sim *s = sim_new(&cfg, 2, err, sizeof err);
  sim_trace(s, csv, NULL);
  mp_proc pr[2] = {{calls_main, NULL}, {calls_main, NULL}};
  CHECK(sim_run(s, pr, err, sizeof err) == 0, "calls: %s", err);
  sim_free(s);
  fclose(csv);
  /* c = 1/8: the outer call 0 to 1/8; the message arrives at 1/8 + m + 4/16 = 5/8. */
  CHECK(strstr(text, "\n0.000000000,0,0,MPI_Outer,,,,0.125000000,,\n") != NULL, "the outer call's slice:\n%s", text);
  CHECK(strstr(text, "\n0.125000000,0,0,MPI_Two,,,,0.250000000,,\n") != NULL && !strstr(text, "MPI_Inner") &&
            !strstr(text, "MPI_Nothing"),
        "nested and empty calls:\n%s", text);
  CHECK(strstr(text, "\n0.000000000,1,1,MPI_Recv,,,,0.625000000,,\n") != NULL, "the receive's call:\n%s", text);
  /* The count mode counts the same bytes. */
  s = sim_new(&cfg, 2, err, sizeof err);
  sim_trace_count(s, 1, 1);
  CHECK(sim_run(s, pr, err, sizeof err) == 0, "calls, counted: %s", err);
  unsigned long long nc, nj;
  sim_trace_size(s, &nc, &nj);
  sim_free(s);
  CHECK(nc == len, "calls: counted %llu bytes of CSV, written %zu", nc, len);
  free(text);
  /* Threads: calls are not traced, and cost nothing. */
  result r = run(THREADS, 2, 2, calls_main, NULL);
  CHECK(r.rc == 0, "threads: calls: %s", r.err);
}

int main(void) {
  for (int b = 0; b < 2; b++) {
    test_self(b);
    test_wait(b);
    test_bad_nap(b);
    test_exit(b);
    test_abort(b);
    test_label(b);
    test_hooks(b);
    test_yield(b);
  }
  test_nap();
  test_calls();
  return check_done("test_mpext");
}
