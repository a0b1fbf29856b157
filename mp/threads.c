/* threads.c -- mp.h on POSIX threads: mailboxes, spin-then-sleep waiting,
 * deadlock detection.  threads.h states the semantics.
 *
 * Reading order: the data (messages, mailboxes, ranks, the machine), errors,
 * waking and the deadlock check, the mp calls, then mpt_run.
 *
 * Locks.  Each mailbox has a mutex; the machine has one more, `g`, for the
 * count of sleeping ranks, the live count and the error report.  The order
 * is always a mailbox, then g; nobody holds two mailboxes.
 *
 *   sender                              receiver (rank d)
 *   lock box[d]                         lock box[d]; no match; unlock
 *   append                              spin: arrivals changed? rescan
 *   if d sleeps and it matches:         ... still nothing after spin_ns:
 *     d.sleeping = 0                    lock box[d]; no match:
 *     lock g; sleeping--; unlock g        d.sleeping = 1
 *     signal d                            lock g; sleeping++;
 *   unlock box[d]                         sleeping == live? deadlock; unlock g
 *   arrivals++                  ---->     wait on d's condition variable
 *
 * A rank counts as sleeping from the moment it registers, under its mailbox
 * lock, to the moment a sender hands it a matching message, under the same
 * lock; so `sleeping == live` (under g) means every live rank waits for a
 * message nobody can send any more: a deadlock, never a race. */
#include "threads.h"

#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cpuload.h"
#include "errlog.h"
#include "wallclock.h"
#include "xmem.h"

void mpt_config_init(mpt_config *cfg) {
  cfg->spin_ns = 50000;
  cfg->warn = stderr;
}

/* ==== data ================================================================ */

typedef struct msg msg;
struct msg {
  msg *next;
  int src, tag;
  size_t len;
  unsigned char data[];   /* the payload, copied at mp_send */
};


typedef struct rank rank;
struct rank {
  struct mp base;              /* first: an mp * is a rank * */
  mpt *t;
  pthread_t thread;
  /* The mailbox, under mu. */
  pthread_mutex_t mu;
  pthread_cond_t cv;
  msg *head, *tail;
  atomic_uint arrivals;        /* bumped by every delivery: what a spinning recv watches */
  int sleeping;                /* registered as sleeping in recv (counted in t->sleeping) */
  int wait_src, wait_tag;      /* what it sleeps for */
  int deadlocked;              /* its recv is to return MP_EDEADLOCK */
  double woken_at;             /* wallclock() when a sender woke it */
  /* Owned by the rank's own thread. */
  mpt_rank_stats st;
  /* Pad: ranks' mailboxes on separate cache lines. */
  char pad[64];
};

struct mpt {
  mpt_config cfg;
  int n;
  rank *ranks;
  const mp_proc *procs;
  atomic_int stopped;          /* deadlock: every mp call fails at once */
  atomic_int awake;            /* live - sleeping, for the spinners to read */
  int cpus;                    /* processors this process may use */
  cpuload load;                /* the machine's runnable threads, sampled */
  double t0;                   /* wallclock() at the start */
  /* The start gate: threads wait here until all are created. */
  pthread_mutex_t gate_mu;
  pthread_cond_t gate_cv;
  int gate;                    /* 0: wait, 1: go, -1: do not run main */
  /* Under g. */
  pthread_mutex_t g;
  int live;                    /* ranks whose main has not returned */
  int sleeping;                /* ranks sleeping in recv without a matching message */
  errlog errs;                 /* the errors quoted in mpt_run's message */
  int ran;
  mpt_stats st;                /* errors and warnings under g; the rest after the run */
};

/* ==== errors and warnings ================================================= */

#if defined(__GNUC__)
#define PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define PRINTF(a, b)
#endif

static void add_error_locked(mpt *t, const char *text, int always) {
  t->st.errors++;
  errlog_add(&t->errs, text, always);
}

static PRINTF(2, 3) void fail(mpt *t, const char *fmt, ...) {
  char buf[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  pthread_mutex_lock(&t->g);
  add_error_locked(t, buf, 0);
  pthread_mutex_unlock(&t->g);
}

static PRINTF(2, 3) void warn(mpt *t, const char *fmt, ...) {
  char buf[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  pthread_mutex_lock(&t->g);
  t->st.warnings++;
  if (t->cfg.warn) fprintf(t->cfg.warn, "threads: warning: %s\n", buf);
  pthread_mutex_unlock(&t->g);
}

/* ==== waking, and the deadlock check ====================================== */

static inline int matches(const msg *m, int src, int tag) {
  return (src < 0 || m->src == src) && (tag < 0 || m->tag == tag);
}

/* The first message in r's mailbox matching src and tag, unlinked; or NULL.
 * Caller holds r->mu. */
static msg *box_take(rank *r, int src, int tag) {
  msg *prev = NULL;
  for (msg *m = r->head; m; prev = m, m = m->next) {
    if (!matches(m, src, tag)) continue;
    if (prev)
      prev->next = m->next;
    else
      r->head = m->next;
    if (r->tail == m) r->tail = prev;
    return m;
  }
  return NULL;
}

static const char *peer_name(int v, char *buf, size_t len) {
  if (v < 0) return "any";
  snprintf(buf, len, "%d", v);
  return buf;
}

/* Every live rank sleeps in recv (caller holds g): stop the run, mark the
 * sleepers deadlocked, say who waits for what. */
static void declare_deadlock_locked(mpt *t) {
  enum { SHOWN = 16 };
  size_t cap = 64 + SHOWN * 64, len = 0;
  char *buf = xmalloc(cap), a[16], b[16];
  len += (size_t)snprintf(buf, cap, "deadlock after %.6f s:", wallclock() - t->t0);
  int blocked = 0;
  for (int i = 0; i < t->n; i++) {
    rank *r = &t->ranks[i];
    /* sleeping and wait_* are written under r->mu and g together (wait_*
     * before sleeping), so reading them under g alone is safe; deadlocked
     * is read by its rank only once the run has stopped. */
    if (!r->sleeping) continue;
    r->deadlocked = 1;
    if (blocked++ < SHOWN)
      len += (size_t)snprintf(buf + len, cap - len, "%s rank %d waits in recv(src=%s, tag=%s)",
                              blocked > 1 ? ";" : "", i, peer_name(r->wait_src, a, sizeof a),
                              peer_name(r->wait_tag, b, sizeof b));
  }
  if (blocked > SHOWN) snprintf(buf + len, cap - len, "; and %d more ranks", blocked - SHOWN);
  t->st.deadlock = 1;
  atomic_store(&t->stopped, 1);
  add_error_locked(t, buf, 1);   /* always quoted: it is often the consequence of the others */
  free(buf);
}

/* After a stop: wake every sleeper so that it sees it (holding no lock). */
static void wake_all(mpt *t) {
  for (int i = 0; i < t->n; i++) {
    rank *r = &t->ranks[i];
    pthread_mutex_lock(&r->mu);
    pthread_cond_broadcast(&r->cv);
    pthread_mutex_unlock(&r->mu);
  }
}

/* ==== the mp calls ======================================================== */

static inline void cpu_relax(void) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  __builtin_ia32_pause();
#elif defined(__GNUC__) && defined(__aarch64__)
  __asm__ __volatile__("yield");
#endif
}

/* Lock a mailbox.  Its critical sections are a few loads and stores (an
 * append, a take), so a thread that finds it held tries again for a moment
 * before pthread_mutex_lock, which would put it to sleep in the kernel and
 * make the holder's unlock a system call too: on the algorithm's exchanges
 * (two neighbours sending into a mailbox while its owner takes from it) that
 * cost microseconds a message. */
static void box_lock(rank *r) {
  for (int i = 0; i < 256; i++) {
    if (pthread_mutex_trylock(&r->mu) == 0) return;
    cpu_relax();
  }
  pthread_mutex_lock(&r->mu);
}

static int stopped(const mpt *t) { return atomic_load_explicit(&t->stopped, memory_order_acquire); }

static int mpt_compute(mp *self, double units) {
  rank *r = (rank *)self;
  if (stopped(r->t)) return MP_ESTOPPED;
  if (!(units >= 0) || isinf(units)) {
    fail(r->t, "rank %d: mp_compute(%g): units must be finite and >= 0", r->base.rank, units);
    return MP_EARG;
  }
  return MP_OK;
}

static int mpt_send(mp *self, int dst, int tag, const void *buf, size_t len) {
  rank *r = (rank *)self;
  mpt *t = r->t;
  if (stopped(t)) return MP_ESTOPPED;
  if (dst < 0 || dst >= t->n) {
    fail(t, "rank %d: mp_send to rank %d, which does not exist (%d ranks)", r->base.rank, dst, t->n);
    return MP_ERANK;
  }
  if (tag < 0) {
    fail(t, "rank %d: mp_send to rank %d with tag %d: tags are >= 0", r->base.rank, dst, tag);
    return MP_EARG;
  }
  if (len && !buf) {
    fail(t, "rank %d: mp_send of %zu bytes from a NULL buffer", r->base.rank, len);
    return MP_EARG;
  }
  msg *m = xmalloc(sizeof *m + len);
  m->next = NULL;
  m->src = r->base.rank;
  m->tag = tag;
  m->len = len;
  if (len) memcpy(m->data, buf, len);
  rank *d = &t->ranks[dst];
  box_lock(d);
  if (d->tail)
    d->tail->next = m;
  else
    d->head = m;
  d->tail = m;
  if (d->sleeping && matches(m, d->wait_src, d->wait_tag)) {
    pthread_mutex_lock(&t->g);
    d->sleeping = 0;
    t->sleeping--;
    atomic_fetch_add_explicit(&t->awake, 1, memory_order_relaxed);
    pthread_mutex_unlock(&t->g);
    d->woken_at = wallclock();
    pthread_cond_signal(&d->cv);
  }
  pthread_mutex_unlock(&d->mu);
  /* After the unlock: a receiver spinning on the counter then finds the
   * mailbox free instead of waiting for this sender to leave it. */
  atomic_fetch_add_explicit(&d->arrivals, 1, memory_order_release);
  r->st.sent++;
  r->st.bytes_sent += (long long)len;
  return MP_OK;
}

/* Check recv's and probe's source and tag. */
static int check_match_args(rank *r, const char *call, int src, int tag) {
  mpt *t = r->t;
  if (src < MP_ANY || src >= t->n) {
    fail(t, "rank %d: %s from rank %d, which does not exist (%d ranks)", r->base.rank, call, src, t->n);
    return MP_ERANK;
  }
  if (tag < MP_ANY) {
    fail(t, "rank %d: %s with tag %d: tags are >= 0 or MP_ANY", r->base.rank, call, tag);
    return MP_EARG;
  }
  return MP_OK;
}

/* Copy m out to the caller, free it. */
static int deliver(rank *r, msg *m, void *buf, size_t cap, mp_status *st) {
  size_t n = m->len <= cap ? m->len : cap;
  if (n) memcpy(buf, m->data, n);
  if (st) *st = (mp_status){m->src, m->tag, m->len};
  r->st.received++;
  r->st.bytes_received += (long long)m->len;
  int rc = MP_OK;
  if (m->len > cap) {
    warn(r->t, "rank %d: mp_recv truncated a %zu-byte message from rank %d (tag %d) to %zu bytes",
         r->base.rank, m->len, m->src, m->tag, cap);
    rc = MP_ETRUNC;
  }
  free(m);
  return rc;
}

/* How a waiting rank waits, now (cpuload.h says what else runs). */
enum { W_SLEEP, W_PAUSE, W_YIELD };

static int how_to_wait(mpt *t) {
  int awake = atomic_load_explicit(&t->awake, memory_order_relaxed), others;
  cpuload_running(&t->load, awake, &others);
  if (awake <= t->cpus - others) return W_PAUSE;   /* a processor of its own */
  if (others == 0 && !cpuload_hogged(&t->load))
    return W_YIELD;                                /* only our own threads want it */
  return W_SLEEP;                                  /* other programs want it */
}

/* Watch r's arrival counter until it moves from `seen`, the run stops or
 * spin_ns pass; 1 if it moved.  How, decided again now and then:
 *   pause  while no more of this machine's threads are awake (computing or
 *          spinning) than there are processors other programs leave idle:
 *          the sender runs on another core and the message is seen within a
 *          cache-line transfer;
 *   yield  while more are awake than there are processors but nothing else
 *          runs on the machine (sixteen ranks on two cores): sched_yield
 *          hands the processor to another of our threads, likely the one
 *          that will send (unless a yield lately took long: then a thread
 *          that does not give the processor back got it, cpuload_yield);
 *   sleep  at once while other programs want the processors: a spinner or
 *          yielder would take the processor from a thread that works,
 *          perhaps the one it waits for, for a whole time slice; the sender
 *          wakes a sleeper instead. */
static int spin(rank *r, unsigned seen) {
  mpt *t = r->t;
  if (t->cfg.spin_ns <= 0) return 0;
  double now = wallclock(), until = now + (double)t->cfg.spin_ns * 1e-9;
  int how = how_to_wait(t);
  for (long i = 1; how != W_SLEEP; i++) {
    if (atomic_load_explicit(&r->arrivals, memory_order_acquire) != seen) return 1;
    if (how == W_YIELD)
      cpuload_yield(&t->load);
    else
      cpu_relax();
    if ((i & 31) == 0 || how == W_YIELD) {   /* now and then: the clock, the run, the room */
      now = wallclock();
      if (now >= until || stopped(t)) return 0;
      how = how_to_wait(t);
    }
  }
  return 0;
}

static int mpt_recv(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st) {
  rank *r = (rank *)self;
  mpt *t = r->t;
  if (stopped(t)) return MP_ESTOPPED;
  int rc = check_match_args(r, "mp_recv", src, tag);
  if (rc != MP_OK) return rc;
  if (cap && !buf) {
    fail(t, "rank %d: mp_recv into a NULL buffer of %zu bytes", r->base.rank, cap);
    return MP_EARG;
  }
  double w0 = -1;
  for (;;) {
    /* Look. */
    box_lock(r);
    msg *m = box_take(r, src, tag);
    unsigned seen = atomic_load_explicit(&r->arrivals, memory_order_relaxed);
    pthread_mutex_unlock(&r->mu);
    if (m) {
      if (w0 >= 0) r->st.recv_wait += wallclock() - w0;
      return deliver(r, m, buf, cap, st);
    }
    if (w0 < 0) w0 = wallclock();
    /* Spin. */
    if (spin(r, seen)) continue;
    /* Sleep. */
    box_lock(r);
    m = box_take(r, src, tag);
    if (m) {
      pthread_mutex_unlock(&r->mu);
      r->st.recv_wait += wallclock() - w0;
      return deliver(r, m, buf, cap, st);
    }
    if (stopped(t)) {
      pthread_mutex_unlock(&r->mu);
      r->st.recv_wait += wallclock() - w0;
      return MP_ESTOPPED;
    }
    r->st.sleeps++;
    r->wait_src = src;
    r->wait_tag = tag;
    pthread_mutex_lock(&t->g);
    r->sleeping = 1;
    t->sleeping++;
    atomic_fetch_sub_explicit(&t->awake, 1, memory_order_relaxed);
    int dead = t->sleeping == t->live;
    if (dead) declare_deadlock_locked(t);
    pthread_mutex_unlock(&t->g);
    if (dead) {
      pthread_mutex_unlock(&r->mu);
      wake_all(t);
      pthread_mutex_lock(&r->mu);
    }
    r->woken_at = -1;
    while (r->sleeping && !stopped(t)) pthread_cond_wait(&r->cv, &r->mu);
    if (r->woken_at >= 0) {
      r->st.wakes++;
      r->st.wake_s += wallclock() - r->woken_at;
    }
    int was_dead = r->deadlocked;
    r->deadlocked = 0;
    pthread_mutex_unlock(&r->mu);
    if (was_dead) {
      r->st.recv_wait += wallclock() - w0;
      return MP_EDEADLOCK;
    }
    /* Woken with a matching message (or by a stop that was not a deadlock
     * of ours): look again. */
  }
}

static int mpt_probe(mp *self, int src, int tag, mp_status *st) {
  rank *r = (rank *)self;
  if (stopped(r->t)) return MP_ESTOPPED;
  int rc = check_match_args(r, "mp_probe", src, tag);
  if (rc != MP_OK) return rc;
  int found = 0;
  box_lock(r);
  for (msg *m = r->head; m; m = m->next) {
    if (!matches(m, src, tag)) continue;
    if (st) *st = (mp_status){m->src, m->tag, m->len};
    found = 1;
    break;
  }
  pthread_mutex_unlock(&r->mu);
  return found;
}

static double mpt_time(const mp *self) { return wallclock() - ((const rank *)self)->t->t0; }

static const mp_ops mpt_ops = {mpt_send, mpt_recv, mpt_probe, mpt_compute, mpt_time};

/* ==== the machine ========================================================= */

mpt *mpt_new(const mpt_config *cfg, int nranks, char *err, size_t errlen) {
  if (nranks < 1) {
    snprintf(err, errlen, "threads: %d ranks: need at least 1", nranks);
    return NULL;
  }
  if (cfg->spin_ns < 0) {
    snprintf(err, errlen, "threads: spin time %ld ns: must be >= 0", cfg->spin_ns);
    return NULL;
  }
  mpt *t = xcalloc(1, sizeof *t);
  t->cfg = *cfg;
  t->n = nranks;
  t->ranks = xcalloc((size_t)nranks, sizeof *t->ranks);
  for (int i = 0; i < nranks; i++) {
    rank *r = &t->ranks[i];
    r->base = (struct mp){&mpt_ops, i, nranks};
    r->t = t;
    pthread_mutex_init(&r->mu, NULL);
    pthread_cond_init(&r->cv, NULL);
    atomic_init(&r->arrivals, 0);
  }
  atomic_init(&t->stopped, 0);
  atomic_init(&t->awake, 0);
  t->cpus = cpuload_cpus();
  cpuload_init(&t->load);
  pthread_mutex_init(&t->g, NULL);
  pthread_mutex_init(&t->gate_mu, NULL);
  pthread_cond_init(&t->gate_cv, NULL);
  t->st.ranks = nranks;
  return t;
}

/* Every rank runs this on its own thread. */
static void *rank_main(void *ud) {
  rank *r = ud;
  mpt *t = r->t;
  pthread_mutex_lock(&t->gate_mu);
  while (t->gate == 0) pthread_cond_wait(&t->gate_cv, &t->gate_mu);
  int go = t->gate > 0;
  pthread_mutex_unlock(&t->gate_mu);
  if (!go) return NULL;
  t->procs[r->base.rank].main(&r->base, t->procs[r->base.rank].ud);
  r->st.done = 1;
  r->st.finish = wallclock() - t->t0;
  pthread_mutex_lock(&t->g);
  t->live--;
  atomic_fetch_sub_explicit(&t->awake, 1, memory_order_relaxed);
  int dead = t->live > 0 && t->sleeping == t->live && !stopped(t);
  if (dead) declare_deadlock_locked(t);
  pthread_mutex_unlock(&t->g);
  if (dead) wake_all(t);
  return NULL;
}

/* Count and report what was sent and never received; free it. */
static void sweep_unread(mpt *t) {
  for (int i = 0; i < t->n; i++) {
    rank *r = &t->ranks[i];
    if (!r->head) continue;
    long long count = 0;
    for (msg *m = r->head; m; m = m->next) count++;
    r->st.unread = count;
    t->st.unread += count;
    warn(t, "rank %d finished with %lld unread message%s (first from rank %d, tag %d)", i, count,
         count == 1 ? "" : "s", r->head->src, r->head->tag);
    while (r->head) {
      msg *m = r->head;
      r->head = m->next;
      free(m);
    }
    r->tail = NULL;
  }
}

int mpt_run(mpt *t, const mp_proc *procs, char *err, size_t errlen) {
  if (t->ran) {
    snprintf(err, errlen, "mpt_run: this machine has run already");
    return -1;
  }
  t->ran = 1;
  for (int i = 0; i < t->n; i++) {
    if (!procs[i].main) {
      snprintf(err, errlen, "mpt_run: rank %d has no main function", i);
      return -1;
    }
  }
  t->procs = procs;
  t->live = t->n;
  atomic_store(&t->awake, t->n);
  int made = 0;
  for (; made < t->n; made++) {
    int e = pthread_create(&t->ranks[made].thread, NULL, rank_main, &t->ranks[made]);
    if (e != 0) {
      char buf[160];
      snprintf(buf, sizeof buf, "mpt_run: cannot start the thread of rank %d of %d (%s)", made, t->n,
               strerror(e));
      pthread_mutex_lock(&t->g);
      add_error_locked(t, buf, 1);
      pthread_mutex_unlock(&t->g);
      break;
    }
  }
  /* Open the gate: all at once, or, if a thread is missing, nobody runs. */
  t->t0 = wallclock();
  pthread_mutex_lock(&t->gate_mu);
  t->gate = made == t->n ? 1 : -1;
  pthread_cond_broadcast(&t->gate_cv);
  pthread_mutex_unlock(&t->gate_mu);
  for (int i = 0; i < made; i++) pthread_join(t->ranks[i].thread, NULL);
  t->st.wall_s = wallclock() - t->t0;
  if (made == t->n) sweep_unread(t);
  for (int i = 0; i < t->n; i++) {
    const mpt_rank_stats *rs = &t->ranks[i].st;
    t->st.messages += rs->sent;
    t->st.received += rs->received;
    t->st.bytes += rs->bytes_sent;
    t->st.sleeps += rs->sleeps;
    t->st.wakes += rs->wakes;
    t->st.wake_s += rs->wake_s;
  }
  return errlog_report(&t->errs, t->st.errors, err, errlen);
}

const mpt_rank_stats *mpt_rank(const mpt *t, int i) {
  XASSERT(i >= 0 && i < t->n);
  return &t->ranks[i].st;
}

const mpt_stats *mpt_stats_get(const mpt *t) { return &t->st; }

void mpt_free(mpt *t) {
  if (!t) return;
  for (int i = 0; i < t->n; i++) {
    rank *r = &t->ranks[i];
    while (r->head) {
      msg *m = r->head;
      r->head = m->next;
      free(m);
    }
    pthread_mutex_destroy(&r->mu);
    pthread_cond_destroy(&r->cv);
  }
  pthread_mutex_destroy(&t->g);
  pthread_mutex_destroy(&t->gate_mu);
  pthread_cond_destroy(&t->gate_cv);
  free(t->ranks);
  errlog_free(&t->errs);
  free(t);
}
