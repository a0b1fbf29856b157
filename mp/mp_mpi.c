/* mp_mpi.c -- mp.h over MPI: buffered sends, a pulled mailbox, deadlock
 * detection by rank 0, the end of a run.  mp_mpi.h states the semantics.
 *
 * Reading order: data, errors, the pool of pending sends, the control
 * messages (reports, stop, end, final), polling and waiting, the mp calls,
 * then mpm_run and the end of the run.
 *
 * Two communicators.  `data` carries the program's messages only, so a
 * recv from any source with any tag can never take one of ours; `ctl`
 * carries the backend's: a rank's REPORT to rank 0 (blocked, running or
 * done, with its per-peer counts), rank 0's STOP (deadlock) and END (every
 * rank done), and at the very end each rank's FINAL (its counts and errors)
 * to rank 0 (and, under SimGrid, rank 0's EXPECT back: how many messages
 * each rank must still drain).
 *
 *   rank 1            rank 0 (master, and coordinator)         rank 2
 *   recv ... 2 ms --REPORT blocked-->  all blocked or done?  <--REPORT blocked--
 *                                     sent == arrived on every pair?
 *   <-----------------STOP------------ yes: deadlock --------STOP------------->
 *   recv returns MP_EDEADLOCK                                 MP_EDEADLOCK
 *   main returns --REPORT done----->  all done, balanced    <--REPORT done-----
 *   <-----------------END------------                       ---------END------>
 *   --FINAL-->                        sums, errors                 <--FINAL--
 */
#include "mp/mp_mpi.h"

#include <math.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mp/backend.h"
#include "mp/cpuload.h"
#include "util/xmem.h"
#if defined(__linux__)
#include <sys/prctl.h>
#endif

#if defined(SMPI_H)
#define SIMGRID 1   /* SimGrid's SMPI: blocking receives, explicit compute */
#else
#define SIMGRID 0
#endif

void mpm_config_init(mpm_config *cfg) {
  cfg->c = 0;
  cfg->warn = stderr;
}

/* ==== data ================================================================ */

enum { CT_REPORT = 1, CT_STOP, CT_END, CT_FINAL, CT_EXPECT };   /* ctl tags */
enum { ST_RUNNING, ST_BLOCKED, ST_DONE };                       /* reported states */

/* Waiting: busy polls for BUSY_S while the machine has a processor for
 * every runnable thread (cpuload.h), then polls with sched_yield up to
 * YIELD_S unless a yield lately gave the processor away for long, then (or
 * else) polls with sleeps of an eighth of the wait so far within
 * [SLEEP_MIN_S, SLEEP_MAX_S]; a rank blocked REPORT_S reports it (MPI only). */
#define BUSY_S 50e-6
#define YIELD_S 2e-3
#define SLEEP_MIN_S 20e-6
#define SLEEP_MAX_S 1e-3
#define REPORT_S 2e-3
#define TIMER_SLACK_NS 2000   /* Linux: a sleep of SLEEP_MIN_S is not 50 us longer */

typedef struct msg msg;
struct msg {
  msg *next;
  int src, tag;
  size_t len;
  unsigned char data[];
};

typedef struct {   /* the fixed part of FINAL; then sent_to[n], got_from[n] */
  long long sent, received, bytes, unread, warnings, errors;
  int deadlock, pad;
  char errs[512];
} final_msg;

struct mpm {
  struct mp base;              /* first: an mp * is an mpm * */
  mpm_config cfg;
  MPI_Comm data, ctl;
  cpuload load;                /* the machine's runnable threads, sampled */
  int cpus;                    /* processors this process may use */
  int n, me;
  int ran;
  double t0;
  /* The mailbox (MPI): messages pulled and not yet received, in order. */
  msg *head, *tail;
  long long *sent_to;          /* [n] messages sent to each rank */
  long long *got_from;         /* [n] pulled (MPI) or received (SimGrid) from each rank */
  long long arrivals;          /* pulled, in all */
  /* Pending sends: the copies MPI may still be reading. */
  MPI_Request *req;
  unsigned char **pbuf;
  int *idx;
  int npend, cappend;
  /* State. */
  int stopped;                 /* STOP came (or rank 0 declared it): calls fail */
  int ended;                   /* END came (or rank 0 declared it) */
  int reported;                /* the state last reported: ST_* */
  long long reported_arrivals; /* arrivals at that report */
  int wait_src, wait_tag;      /* what a blocked recv waits for */
  /* Errors and warnings of this rank (rank 0: of the run). */
  mp_log log;
  mpm_stats st;                /* this rank's; rank 0's becomes the run's */
  /* Rank 0: the coordinator's view. */
  int *cstate, *cwsrc, *cwtag; /* [n] each rank's last reported state, wait */
  long long *S, *A;            /* [n*n]: S[i*n+j] sent i->j as i reported,
                                  A[j*n+i] arrived at j from i as j reported */
  long long unbalanced;        /* pairs with S[i][j] != A[j][i] */
};

static double now(const mpm *m) { return MPI_Wtime() - m->t0; }

/* ==== the pool of pending sends =========================================== */

/* Free the copies MPI is done with. */
static void reap(mpm *m) {
  if (m->npend == 0) return;
  int done = 0;
  MPI_Testsome(m->npend, m->req, &done, m->idx, MPI_STATUSES_IGNORE);
  if (done <= 0 || done == MPI_UNDEFINED) return;
  for (int i = 0; i < done; i++) {
    free(m->pbuf[m->idx[i]]);
    m->pbuf[m->idx[i]] = NULL;
  }
  int k = 0;
  for (int i = 0; i < m->npend; i++)
    if (m->pbuf[i]) m->req[k] = m->req[i], m->pbuf[k] = m->pbuf[i], k++;
  m->npend = k;
}

/* Start sending a copy of buf; it stays in the pool until MPI is done. */
static void isend(mpm *m, MPI_Comm comm, int dst, int tag, const void *buf, size_t len) {
  /* Under SimGrid every MPI_Testsome costs simulated time (smpi/test):
   * the copies are kept to the end instead. */
  if (!SIMGRID && m->npend >= 64) reap(m);
  if (m->npend == m->cappend) {
    m->cappend = m->cappend ? 2 * m->cappend : 64;
    m->req = xreallocarray(m->req, (size_t)m->cappend, sizeof *m->req);
    m->pbuf = xreallocarray(m->pbuf, (size_t)m->cappend, sizeof *m->pbuf);
    m->idx = xreallocarray(m->idx, (size_t)m->cappend, sizeof *m->idx);
  }
  unsigned char *copy = xmalloc(len ? len : 1);
  if (len) memcpy(copy, buf, len);
  m->pbuf[m->npend] = copy;
  MPI_Isend(copy, (int)len, MPI_BYTE, dst, tag, comm, &m->req[m->npend]);
  m->npend++;
}

static void drain_pool(mpm *m) {
  if (m->npend) MPI_Waitall(m->npend, m->req, MPI_STATUSES_IGNORE);
  for (int i = 0; i < m->npend; i++) free(m->pbuf[i]);
  m->npend = 0;
}

/* ==== the coordinator (rank 0) and the control messages =================== */

#if !SIMGRID   /* under SimGrid: blocking receives, no coordinator */

/* Take rank i's report into rank 0's view, and see whether the run is over
 * or deadlocked. */
static void coord_check(mpm *m);

static void coord_apply(mpm *m, int i, int state, int wsrc, int wtag, const long long *sent,
                        const long long *got) {
  int n = m->n;
  for (int j = 0; j < n; j++) {
    long long *s = &m->S[i * n + j], *a = &m->A[j * n + i];
    m->unbalanced -= *s != *a;
    *s = sent[j];
    m->unbalanced += *s != *a;
  }
  for (int j = 0; j < n; j++) {   /* arrived at i from j, against j's sends to i */
    long long *a = &m->A[i * n + j], *s = &m->S[j * n + i];
    m->unbalanced -= *s != *a;
    *a = got[j];
    m->unbalanced += *s != *a;
  }
  m->cstate[i] = state;
  m->cwsrc[i] = wsrc;
  m->cwtag[i] = wtag;
  coord_check(m);
}

static void coord_check(mpm *m) {
  if (m->ended) return;
  int blocked = 0;
  for (int i = 0; i < m->n; i++) {
    if (m->cstate[i] == ST_RUNNING) return;
    blocked += m->cstate[i] == ST_BLOCKED;
  }
  if (m->unbalanced) return;
  if (!blocked) {   /* every rank done, nothing in flight: the end */
    m->ended = 1;
    for (int i = 1; i < m->n; i++) isend(m, m->ctl, i, CT_END, NULL, 0);
    return;
  }
  if (m->stopped) return;
  char buf[512], a[16], b[16];
  size_t len = (size_t)snprintf(buf, sizeof buf, "deadlock after %.6f s:", now(m));
  int shown = 0;
  for (int i = 0; i < m->n && len < sizeof buf; i++) {
    if (m->cstate[i] != ST_BLOCKED) continue;
    if (shown++ == 8) {
      snprintf(buf + len, sizeof buf - len, "; and more");
      break;
    }
    len += (size_t)snprintf(buf + len, sizeof buf - len, "%s rank %d waits in recv(src=%s, tag=%s)",
                            shown > 1 ? ";" : "", i, mp_peer_name(m->cwsrc[i], a, sizeof a),
                            mp_peer_name(m->cwtag[i], b, sizeof b));
  }
  mp_fail_text(&m->log, buf, 1);
  m->st.deadlock = 1;
  m->stopped = 1;
  for (int i = 1; i < m->n; i++) isend(m, m->ctl, i, CT_STOP, NULL, 0);
}

/* Tell rank 0 this rank's state and counts (rank 0 tells itself). */
static void report(mpm *m, int state) {
  m->reported = state;
  m->reported_arrivals = m->arrivals;
  if (m->me == 0) {
    coord_apply(m, 0, state, m->wait_src, m->wait_tag, m->sent_to, m->got_from);
    return;
  }
  size_t len = 16 + 16 * (size_t)m->n;
  unsigned char *b = xmalloc(len);
  int32_t h[4] = {state, m->wait_src, m->wait_tag, 0};
  memcpy(b, h, 16);
  memcpy(b + 16, m->sent_to, 8 * (size_t)m->n);
  memcpy(b + 16 + 8 * (size_t)m->n, m->got_from, 8 * (size_t)m->n);
  isend(m, m->ctl, 0, CT_REPORT, b, len);
  free(b);
}

/* One control message is waiting (st): take it. */
static void take_ctl(mpm *m, const MPI_Status *st) {
  int len;
  MPI_Get_count(st, MPI_BYTE, &len);
  unsigned char *b = xmalloc(len > 0 ? (size_t)len : 1);
  MPI_Recv(b, len, MPI_BYTE, st->MPI_SOURCE, st->MPI_TAG, m->ctl, MPI_STATUS_IGNORE);
  if (st->MPI_TAG == CT_STOP) {
    m->stopped = 1;
  } else if (st->MPI_TAG == CT_END) {
    m->ended = 1;
  } else if (st->MPI_TAG == CT_REPORT && m->me == 0) {
    if ((size_t)len != 16 + 16 * (size_t)m->n) xpanic("mpi: a report of %d bytes", len);
    if (!m->ended) {
      int32_t h[4];
      memcpy(h, b, 16);
      long long *sent = xmallocarray((size_t)m->n, sizeof *sent);
      long long *got = xmallocarray((size_t)m->n, sizeof *got);
      memcpy(sent, b + 16, 8 * (size_t)m->n);
      memcpy(got, b + 16 + 8 * (size_t)m->n, 8 * (size_t)m->n);
      coord_apply(m, st->MPI_SOURCE, h[0], h[1], h[2], sent, got);
      free(sent);
      free(got);
    }
  } else {
    xpanic("mpi: rank %d got control message %d from rank %d", m->me, st->MPI_TAG, st->MPI_SOURCE);
  }
  free(b);
}

/* ==== polling and waiting (MPI) =========================================== */

/* Pull every data message that has arrived into the mailbox, and take the
 * control messages (REPORT, STOP, END; FINAL is taken at the end). */
static void poll_once(mpm *m) {
  for (;;) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, m->data, &flag, &st);
    if (!flag) break;
    int len;
    MPI_Get_count(&st, MPI_BYTE, &len);
    msg *g = xmalloc(sizeof *g + (size_t)(len > 0 ? len : 0));
    MPI_Recv(g->data, len, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, m->data, MPI_STATUS_IGNORE);
    g->next = NULL;
    g->src = st.MPI_SOURCE;
    g->tag = st.MPI_TAG;
    g->len = (size_t)len;
    if (m->tail)
      m->tail->next = g;
    else
      m->head = g;
    m->tail = g;
    m->got_from[g->src]++;
    m->arrivals++;
  }
  for (;;) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, m->ctl, &flag, &st);
    if (!flag || st.MPI_TAG == CT_FINAL) break;
    take_ctl(m, &st);
  }
  reap(m);
}

/* Between two polls of a wait that began at `since`.
 *   Poll again at once during the first BUSY_S, but only while no more
 *   threads are runnable on the machine than there are processors: this
 *   rank then has a processor nobody else wants.
 *   Else, up to YIELD_S, sched_yield: with more ranks than cores the
 *   processor goes to another rank, likely the one that will send.  But a
 *   yield gives the processor to whatever else is runnable, for a whole
 *   time slice if that is another program's busy thread: once a yield came
 *   back late (cpuload_yield), no yields for a while.
 *   Else sleep an eighth of the wait so far, SLEEP_MIN_S to SLEEP_MAX_S: a
 *   long wait (the master's, mostly) wakes rarely and answers within an
 *   eighth of its length, and never holds a processor another wants. */
static void backoff(mpm *m, double since) {
  double w = now(m) - since;
  if (w < BUSY_S) {
    int running = cpuload_running(&m->load, 1, NULL);
    if (running < 0 || running <= m->cpus) return;
  }
  if (w < YIELD_S && !cpuload_hogged(&m->load)) {
    cpuload_yield(&m->load);
    return;
  }
  double d = w / 8;
  if (d < SLEEP_MIN_S) d = SLEEP_MIN_S;
  if (d > SLEEP_MAX_S) d = SLEEP_MAX_S;
  struct timespec ts = {0, (long)(d * 1e9)};
  nanosleep(&ts, NULL);
}

/* The mailbox's first message from src with tag (MP_ANY: any), or NULL. */
static msg *box_find(const mpm *m, int src, int tag) {
  for (msg *g = m->head; g; g = g->next)
    if ((src < 0 || g->src == src) && (tag < 0 || g->tag == tag)) return g;
  return NULL;
}

/* g out of the mailbox. */
static void box_unlink(mpm *m, const msg *g) {
  msg *prev = NULL;
  for (msg *x = m->head; x != g; prev = x, x = x->next) {
  }
  if (prev)
    prev->next = g->next;
  else
    m->head = g->next;
  if (m->tail == g) m->tail = prev;
}

/* Wait until the mailbox holds a message from src with tag: that message,
 * left there; or NULL and *rc = MP_EDEADLOCK (rank 0 saw every rank
 * blocked, this one among them) or MP_ESTOPPED.  A rank blocked REPORT_S
 * tells rank 0, and again whenever messages have come since. */
static msg *await(mpm *m, int src, int tag, int *rc) {
  double since = -1;
  for (;;) {
    msg *g = box_find(m, src, tag);
    if (g) {
      if (m->reported == ST_BLOCKED) report(m, ST_RUNNING);
      *rc = MP_OK;
      return g;
    }
    if (m->stopped) {
      *rc = m->reported == ST_BLOCKED ? MP_EDEADLOCK : MP_ESTOPPED;
      return NULL;
    }
    if (since < 0) {
      since = now(m);
      m->wait_src = src;
      m->wait_tag = tag;
    } else {
      double w = now(m) - since;
      if (m->reported != ST_BLOCKED && w >= REPORT_S) report(m, ST_BLOCKED);
      else if (m->reported == ST_BLOCKED && m->arrivals != m->reported_arrivals) report(m, ST_BLOCKED);
      if (m->stopped) continue;   /* rank 0 may have just declared it */
      backoff(m, since);
    }
    poll_once(m);
  }
}

#endif /* !SIMGRID */

/* ==== the mp calls ======================================================== */

static int mpm_compute(mp *self, double units) {
  mpm *m = (mpm *)self;
  (void)units;
  if (m->stopped) return MP_ESTOPPED;
#if SIMGRID
  if (units > 0 && m->cfg.c > 0) smpi_execute_benched(units * m->cfg.c);
#endif
  return MP_OK;
}

static int mpm_send(mp *self, int dst, int tag, const void *buf, size_t len) {
  mpm *m = (mpm *)self;
  if (m->stopped) return MP_ESTOPPED;
  if (len > (size_t)INT32_MAX) {
    mp_fail(&m->log, "rank %d: mp_send of %zu bytes: MPI counts stop at %d", m->me, len, (int)INT32_MAX);
    return MP_EARG;
  }
  isend(m, m->data, dst, tag, buf, len);
  m->sent_to[dst]++;
  m->st.messages++;
  m->st.bytes += (long long)len;
  return MP_OK;
}

static int finish_recv(mpm *m, int src, int tag, size_t len, size_t cap, mp_status *st) {
  if (st) *st = (mp_status){src, tag, len};
  m->st.received++;
  if (len > cap) {
    mp_warn(&m->log, "rank %d: mp_recv truncated a %zu-byte message from rank %d (tag %d) to %zu bytes", m->me,
         len, src, tag, cap);
    return MP_ETRUNC;
  }
  return MP_OK;
}

static int mpm_recv(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st) {
  mpm *m = (mpm *)self;
  if (m->stopped) return MP_ESTOPPED;
#if SIMGRID
  /* One blocking receive: the simulated clock moves with the message. */
  MPI_Status ms;
  int icap = cap > (size_t)INT32_MAX ? INT32_MAX : (int)cap;
  int e = MPI_Recv(buf, icap, MPI_BYTE, src < 0 ? MPI_ANY_SOURCE : src, tag < 0 ? MPI_ANY_TAG : tag,
                   m->data, &ms);
  int len = 0;
  MPI_Get_count(&ms, MPI_BYTE, &len);
  if (e != MPI_SUCCESS && e != MPI_ERR_TRUNCATE) xpanic("mpi: rank %d: MPI_Recv failed (%d)", m->me, e);
  m->got_from[ms.MPI_SOURCE]++;
  size_t full = e == MPI_ERR_TRUNCATE && (size_t)len <= cap ? cap + 1 : (size_t)len;
  return finish_recv(m, ms.MPI_SOURCE, ms.MPI_TAG, full, cap, st);
#else
  int rc;
  msg *g = await(m, src, tag, &rc);
  if (!g) return rc;
  box_unlink(m, g);
  size_t k = g->len <= cap ? g->len : cap;
  if (k) memcpy(buf, g->data, k);
  rc = finish_recv(m, g->src, g->tag, g->len, cap, st);
  free(g);
  return rc;
#endif
}

static int mpm_probe(mp *self, int src, int tag, mp_status *st) {
  mpm *m = (mpm *)self;
  if (m->stopped) return MP_ESTOPPED;
#if SIMGRID
  int flag = 0;
  MPI_Status ms;
  MPI_Iprobe(src < 0 ? MPI_ANY_SOURCE : src, tag < 0 ? MPI_ANY_TAG : tag, m->data, &flag, &ms);
  if (flag && st) {
    int len = 0;
    MPI_Get_count(&ms, MPI_BYTE, &len);
    *st = (mp_status){ms.MPI_SOURCE, ms.MPI_TAG, (size_t)len};
  }
  return flag != 0;
#else
  poll_once(m);
  const msg *g = box_find(m, src, tag);
  if (!g) return m->stopped ? MP_ESTOPPED : 0;
  if (st) *st = (mp_status){g->src, g->tag, g->len};
  return 1;
#endif
}

static double mpm_time(const mp *self) { return now((const mpm *)self); }

/* mp_wait: a receive that leaves the message in the mailbox (MPI_Probe
 * under SimGrid). */
static int mpm_wait(mp *self, int src, int tag, mp_status *st) {
  mpm *m = (mpm *)self;
  if (m->stopped) return MP_ESTOPPED;
#if SIMGRID
  MPI_Status ms;
  MPI_Probe(src < 0 ? MPI_ANY_SOURCE : src, tag < 0 ? MPI_ANY_TAG : tag, m->data, &ms);
  int len = 0;
  MPI_Get_count(&ms, MPI_BYTE, &len);
  if (st) *st = (mp_status){ms.MPI_SOURCE, ms.MPI_TAG, (size_t)len};
  return MP_OK;
#else
  int rc;
  const msg *g = await(m, src, tag, &rc);
  if (g && st) *st = (mp_status){g->src, g->tag, g->len};
  return rc;
#endif
}

static int mpm_busy(mp *self, double seconds) {
  mpm *m = (mpm *)self;
  (void)seconds;
  if (m->stopped) return MP_ESTOPPED;
#if SIMGRID
  if (seconds > 0) smpi_execute_benched(seconds);
#endif
  return MP_OK;
}

static int mpm_sleep(mp *self, double seconds) {
  mpm *m = (mpm *)self;
  if (m->stopped) return MP_ESTOPPED;
  struct timespec ts = {(time_t)seconds, (long)((seconds - (double)(time_t)seconds) * 1e9)};
  while (nanosleep(&ts, &ts) != 0) {
  }
  return MP_OK;
}

/* mp_abort: one process cannot stop the others' calls; MPI_Abort ends them
 * all with the code. */
static void mpm_stop(mp *self, int code, const char *why) {
  mpm *m = (mpm *)self;
  fprintf(stderr, "mpi: rank %d: %s\n", m->me, why ? why : "aborted");
  fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, code);
}

/* A call mp.c found a bad argument in. */
static int mpm_reject(mp *self, int code, const char *why) {
  mpm *m = (mpm *)self;
  if (m->stopped) return MP_ESTOPPED;
  mp_fail_text(&m->log, why, 0);
  return code;
}

/* Messages without copies: none here (mp.c copies: mp_send_ref is mp_send,
 * mp_recv_msg is mp_recv into memory of its own, no promises). */
static const mp_ops mpm_ops = {.send = mpm_send, .recv = mpm_recv, .probe = mpm_probe, .compute = mpm_compute,
                               .time = mpm_time, .wait = mpm_wait, .busy = mpm_busy, .sleep_for = mpm_sleep,
                               .stop = mpm_stop, .reject = mpm_reject, .tag_max = MPM_TAG_MAX,
                               .sleep_bounded = 1};

/* ==== the machine ========================================================= */

mpm *mpm_new(const mpm_config *cfg, MPI_Comm data, MPI_Comm ctl, int nranks, char *err,
             size_t errlen) {
  int size, me;
  MPI_Comm_size(data, &size);
  MPI_Comm_rank(data, &me);
  if (nranks < 1 || nranks > size) {
    snprintf(err, errlen, "mpi: %d ranks: the communicator has %d processes", nranks, size);
    return NULL;
  }
  if (me >= nranks) {
    snprintf(err, errlen, "mpi: process %d is not among the %d ranks of the run", me, nranks);
    return NULL;
  }
  if (!(cfg->c >= 0) || isinf(cfg->c)) {
    snprintf(err, errlen, "mpi: c = %g: must be finite and >= 0", cfg->c);
    return NULL;
  }
  mpm *m = xcalloc(1, sizeof *m);
  m->base = (struct mp){.ops = &mpm_ops, .rank = me, .size = nranks};
  m->cfg = *cfg;
  cpuload_init(&m->load);
  m->cpus = cpuload_cpus();
#if defined(__linux__) && defined(PR_SET_TIMERSLACK)
  prctl(PR_SET_TIMERSLACK, (unsigned long)TIMER_SLACK_NS, 0UL, 0UL, 0UL);
#endif
  m->data = data;
  m->ctl = ctl;
  m->n = nranks;
  m->me = me;
  m->sent_to = xcalloc((size_t)nranks, sizeof *m->sent_to);
  m->got_from = xcalloc((size_t)nranks, sizeof *m->got_from);
  m->wait_src = m->wait_tag = MP_ANY;
  m->st.ranks = nranks;
  m->log = (mp_log){.name = "mpi", .warn = cfg->warn, .st = &m->st.run};
  if (me == 0) {
    m->cstate = xcalloc((size_t)nranks, sizeof *m->cstate);
    m->cwsrc = xcalloc((size_t)nranks, sizeof *m->cwsrc);
    m->cwtag = xcalloc((size_t)nranks, sizeof *m->cwtag);
    m->S = xcalloc((size_t)nranks * (size_t)nranks, sizeof *m->S);
    m->A = xcalloc((size_t)nranks * (size_t)nranks, sizeof *m->A);
  }
  return m;
}

/* ==== the end of a run ==================================================== */

#if !SIMGRID
/* What was pulled and never received (MPI): count it, warn, free it. */
static void count_unread(mpm *m) {
  if (!m->head) return;
  long long count = 0;
  for (msg *g = m->head; g; g = g->next) count++;
  mp_warn(&m->log, "rank %d finished with %lld unread message%s (first from rank %d, tag %d)", m->me, count,
       count == 1 ? "" : "s", m->head->src, m->head->tag);
  m->st.unread += count;
  while (m->head) {
    msg *g = m->head;
    m->head = g->next;
    free(g);
  }
  m->tail = NULL;
}

/* Everyone's done (MPI): wait for rank 0's END, answering as done. */
static void wait_end(mpm *m) {
  report(m, ST_DONE);
  double since = now(m);
  while (!m->ended) {
    poll_once(m);
    if (m->arrivals != m->reported_arrivals) report(m, ST_DONE);
    if (!m->ended) backoff(m, since);
  }
}

#else
/* Drain (SimGrid): receive what the others sent to this rank and it never
 * received; `expect` has the counts from each rank, from rank 0. */
static void drain_unread(mpm *m, const long long *expect) {
  long long count = 0;
  int first_src = -1, first_tag = -1;
  for (int s = 0; s < m->n; s++) {
    while (m->got_from[s] < expect[s]) {
      MPI_Status ms;
      MPI_Probe(s, MPI_ANY_TAG, m->data, &ms);
      int len = 0;
      MPI_Get_count(&ms, MPI_BYTE, &len);
      unsigned char *b = xmalloc(len > 0 ? (size_t)len : 1);
      MPI_Recv(b, len, MPI_BYTE, s, ms.MPI_TAG, m->data, MPI_STATUS_IGNORE);
      free(b);
      if (count++ == 0) first_src = s, first_tag = ms.MPI_TAG;
      m->got_from[s]++;
    }
  }
  if (count)
    mp_warn(&m->log, "rank %d finished with %lld unread message%s (first from rank %d, tag %d)", m->me, count,
         count == 1 ? "" : "s", first_src, first_tag);
  m->st.unread += count;
}
#endif

static void pack_final(const mpm *m, unsigned char *b) {
  final_msg f;
  memset(&f, 0, sizeof f);
  f.sent = m->st.messages, f.received = m->st.received, f.bytes = m->st.bytes;
  f.unread = m->st.unread, f.warnings = m->st.warnings, f.errors = m->st.errors;
  f.deadlock = m->st.deadlock;
  snprintf(f.errs, sizeof f.errs, "%s", m->log.errs.text ? m->log.errs.text : "");
  memcpy(b, &f, sizeof f);
  memcpy(b + sizeof f, m->sent_to, 8 * (size_t)m->n);
  memcpy(b + sizeof f + 8 * (size_t)m->n, m->got_from, 8 * (size_t)m->n);
}

/* The end: FINALs to rank 0, which sums them (and, under SimGrid, tells
 * each rank how many messages it must still drain). */
static void finish(mpm *m) {
  int n = m->n;
  size_t flen = sizeof(final_msg) + 16 * (size_t)n;
  unsigned char *b = xmalloc(flen);
#if !SIMGRID
  count_unread(m);
#endif
  if (m->me != 0) {
    pack_final(m, b);
    isend(m, m->ctl, 0, CT_FINAL, b, flen);
#if SIMGRID
    long long *expect = xmallocarray((size_t)n, sizeof *expect);
    MPI_Recv(expect, 8 * n, MPI_BYTE, 0, CT_EXPECT, m->ctl, MPI_STATUS_IGNORE);
    drain_unread(m, expect);
    free(expect);
#endif
    free(b);
    return;
  }
  /* Rank 0: every FINAL (REPORTs still on their way come first and are
   * dropped: the run is over). */
  long long *sent = xcalloc((size_t)n * (size_t)n, sizeof *sent);   /* sent[i*n+j]: i -> j */
  mpm_stats tot = m->st;
  memcpy(sent, m->sent_to, 8 * (size_t)n);
  for (int got = 1; got < n;) {
    MPI_Status ms;
    MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, m->ctl, &ms);
    int len;
    MPI_Get_count(&ms, MPI_BYTE, &len);
    if (ms.MPI_TAG != CT_FINAL) {
      unsigned char *skip = xmalloc(len > 0 ? (size_t)len : 1);
      MPI_Recv(skip, len, MPI_BYTE, ms.MPI_SOURCE, ms.MPI_TAG, m->ctl, MPI_STATUS_IGNORE);
      free(skip);
      continue;
    }
    if ((size_t)len != flen) xpanic("mpi: a final message of %d bytes", len);
    MPI_Recv(b, len, MPI_BYTE, ms.MPI_SOURCE, CT_FINAL, m->ctl, MPI_STATUS_IGNORE);
    final_msg f;
    memcpy(&f, b, sizeof f);
    memcpy(sent + (size_t)ms.MPI_SOURCE * (size_t)n, b + sizeof f, 8 * (size_t)n);
    tot.messages += f.sent, tot.received += f.received, tot.bytes += f.bytes;
    tot.unread += f.unread, tot.warnings += f.warnings, tot.errors += f.errors;
    tot.deadlock |= f.deadlock;
    if (f.errs[0]) errlog_add(&m->log.errs, f.errs, 0);   /* the first few; the count says the rest */
    got++;
  }
#if SIMGRID
  /* Each rank must have received what the others sent it. */
  long long *expect = xmallocarray((size_t)n, sizeof *expect);
  for (int i = 0; i < n; i++) {
    for (int s = 0; s < n; s++) expect[s] = sent[(size_t)s * (size_t)n + (size_t)i];
    if (i == 0)
      drain_unread(m, expect);
    else
      MPI_Send(expect, 8 * n, MPI_BYTE, i, CT_EXPECT, m->ctl);
  }
  free(expect);
  tot.unread = tot.messages - tot.received;
#endif
  m->st = tot;
  free(sent);
  free(b);
}

int mpm_run(mpm *m, mp_main main, void *ud, char *err, size_t errlen) {
  if (m->ran) {
    snprintf(err, errlen, "mpm_run: this machine has run already");
    return -1;
  }
  m->ran = 1;
  m->t0 = MPI_Wtime();
  mp_enter(&m->base, main, ud);
#if !SIMGRID
  wait_end(m);
#endif
  finish(m);
  drain_pool(m);
  m->st.wall_s = now(m);
  return mp_log_report(&m->log, err, errlen);
}

const mpm_stats *mpm_stats_get(const mpm *m) { return &m->st; }

void mpm_free(mpm *m) {
  if (!m) return;
  while (m->head) {
    msg *g = m->head;
    m->head = g->next;
    free(g);
  }
  for (int i = 0; i < m->npend; i++) free(m->pbuf[i]);
  free(m->req), free(m->pbuf), free(m->idx);
  free(m->sent_to), free(m->got_from);
  free(m->cstate), free(m->cwsrc), free(m->cwtag), free(m->S), free(m->A);
  mp_log_free(&m->log);
  free(m);
}
