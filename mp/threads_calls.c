/* threads_calls.c -- mp.h's calls on POSIX threads: a channel per pair of
 * ranks, spin-then-sleep waiting, deadlock detection.  threads.h states the
 * contract, doc/backends.md the semantics in full.
 *
 * Reading order: a channel's making, choosing a message among the
 * channels, waking and the deadlock check, then the mp calls.  The data
 * (ranks, the machine) are threads_calls.h's, the channels chan.h's;
 * mpt_run is threads.c's.
 *
 * Messages.  Each ordered pair of ranks (s, d) that has ever talked has a
 * channel (chan.h): a queue with one writer (s) and one reader (d), so
 * that a send takes no lock and no read-modify-write operation.
 *
 * Order.  Per pair, a channel is FIFO.  Between senders, mp.h asks for the
 * earliest arrival first: at the least, a message whose sender had heard,
 * directly or through a chain of messages, from the sender of another one
 * after that one was sent must not be taken before it, as a single mailbox
 * in arrival order would have it.  Every message carries the sender's
 * Lamport clock (bumped at every send; a receive takes the maximum of its own and the
 * message's), so a message sent after another, in the happens-before sense
 * of the messages themselves, has the larger stamp.  A receive from any
 * source scans every channel into it for its first match, takes the least
 * (stamp, source), and scans once more (everything that happened before
 * that message is visible by then): if the least is still the same, it is
 * taken, else the new least is checked the same way.  Ranks share nothing
 * else through mp.h, so that is the arrival order a shared mailbox would
 * have had up to the races mp.h leaves to the machine.
 *
 * Sleeping.  A rank that sleeps in recv registers under its own mutex
 * (sleeping = 1, what it waits for, a sequentially consistent store) and
 * looks at its channels once more; a sender publishes (a sequentially
 * consistent store of the record's size) and reads the receiver's
 * `sleeping` (a sequentially consistent load).  One of the two sees the
 * other (in the single order of those operations, one store comes first),
 * so no message is left unseen beside a sleeper; a sender that sees a
 * sleeper takes its mutex and wakes it if the message matches.  Everything
 * the last look reads to find a message is written and read the same way
 * (a new channel's slots and count, a jump to a new chunk), so it cannot
 * read an older value than the sender's store.  No fence: C11 atomics
 * alone say it, which ThreadSanitizer checks (make tsan); on x86 the
 * publishing store is one xchg, as the release store and fence were.
 * The machine's lock `g` holds the count of sleeping ranks and the live
 * count; the order is a rank's mutex, then g.
 *
 *   sender                              receiver (rank d)
 *   write the record; size (seq_cst)    look: nothing; spin on the channels
 *                                       ... still nothing after spin_ns:
 *   d.sleeping?  no: done               lock d.mu; d.sleeping = 1 (seq_cst)
 *     yes: lock d.mu; matches?          look again: found? sleeping = 0, take
 *       d.sleeping = 0                  lock g; sleeping++;
 *       lock g; sleeping--; unlock g      sleeping == live? deadlock; unlock g
 *       signal d; unlock d.mu           wait on d's condition variable
 *
 * A rank counts as sleeping from the moment it registers (and has looked
 * again, under its mutex) to the moment a sender hands it a matching
 * message, under the same mutex; so `sleeping == live` (under g) means every
 * live rank waits for a message nobody can send any more: a deadlock, never
 * a race. */
#include "mp/threads_calls.h"

#include <limits.h>
#include <math.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "util/dlist.h"
#include "util/wallclock.h"
#include "util/xmem.h"

/* ==== making a channel ==================================================== */

/* The channel from r to d, made at r's first send to d: published in d's
 * table by source and appended to its list (under d's mutex: several
 * senders may add theirs at once). */
static chan *chan_get(rank *r, rank *d) {
  int dst = d->base.rank;
  chan *q = r->out[dst];
  if (q) return q;
  q = aligned_alloc(LINE, sizeof *q);
  if (!q) xpanic("threads: out of memory for a channel");
  memset(q, 0, sizeof *q);
  q->wc = q->hc = q->sc = chunk_new();
  q->src = r->base.rank;
  pthread_mutex_lock(&d->mu);
  int k = atomic_load_explicit(&d->nin, memory_order_relaxed);
  d->inlist[k] = q;
  atomic_store_explicit(&d->in[q->src], q, memory_order_seq_cst);
  atomic_store_explicit(&d->nin, k + 1, memory_order_seq_cst);
  pthread_mutex_unlock(&d->mu);
  r->out[dst] = q;
  return q;
}

/* ==== choosing a message among the channels ============================== */

/* A message found for a receive: its channel and record. */
typedef struct {
  chan *q;
  rec *x;
} found;

/* The message a recv or probe of r from src with tag takes now, if any.
 * From one source: that channel's first match (FIFO).  From any: the least
 * (stamp, source) among the channels' first matches, confirmed by a second
 * look (the file's head comment says why). */
static found look(rank *r, int src, int tag) {
  found f = {NULL, NULL};
  /* A probe from any source showed a message: it arrived before whatever
   * came into view since, so a look with the same source and tag finds it
   * again (as from one mailbox; a newer message may carry a smaller stamp
   * than one that raced it), until it is taken.  Nothing that happened
   * before it was there unseen (the probe's own look made sure). */
  if (src < 0 && r->pin_x && r->pin_tag == tag) return (found){r->pin_q, r->pin_x};
  if (src >= 0) {
    chan *q = atomic_load_explicit(&r->in[src], memory_order_seq_cst);
    if (q) f.q = q, f.x = chan_find(q, tag);
    return f;
  }
  for (;;) {
    found best = {NULL, NULL};
    int k = atomic_load_explicit(&r->nin, memory_order_seq_cst);
    for (int i = 0; i < k; i++) {
      chan *q = r->inlist[i];
      rec *x = chan_find(q, tag);
      if (x && (!best.x || x->stamp < best.x->stamp || (x->stamp == best.x->stamp && x->src < best.x->src)))
        best.q = q, best.x = x;
    }
    if (!best.x || best.x == f.x) return best;
    f = best;
  }
}

/* Anything new for a recv of r from src (MP_ANY: from anyone) since its
 * last look (which left nin_seen channels)? */
static int news(rank *r, int src, int nin_seen) {
  if (src >= 0) {
    chan *q = atomic_load_explicit(&r->in[src], memory_order_acquire);
    return q && (nin_seen < 0 || chan_news(q));
  }
  int k = atomic_load_explicit(&r->nin, memory_order_acquire);
  if (k != nin_seen) return 1;
  for (int i = 0; i < k; i++)
    if (chan_news(r->inlist[i])) return 1;
  return 0;
}

/* What news() compares with: the channels r knows of (for a source: -1 if
 * that channel does not exist yet, else 0). */
static int news_mark(rank *r, int src) {
  if (src >= 0) return atomic_load_explicit(&r->in[src], memory_order_acquire) ? 0 : -1;
  return atomic_load_explicit(&r->nin, memory_order_acquire);
}

/* ==== waking, and the deadlock check ====================================== */

/* Every live rank sleeps in recv (caller holds g): stop the run, mark the
 * sleepers deadlocked, say who waits for what. */
void mpt_deadlock_locked(mpt *t) {
  mp_deadlock d;
  mp_deadlock_begin(&d, "deadlock after %.6f s:", wallclock() - t->t0);
  for (int i = 0; i < t->n; i++) {
    rank *r = &t->ranks[i];
    /* sleeping and wait_* are written under r->mu and g together (wait_*
     * before sleeping), so reading them under g alone is safe; deadlocked
     * is read by its rank only once the run has stopped. */
    if (!atomic_load_explicit(&r->sleeping, memory_order_relaxed)) continue;
    r->deadlocked = 1;
    /* The label is the sleeper's, set before it went to sleep (under its
     * mutex, which it took after: the store is visible here). */
    mp_deadlock_rank(&d, &r->base, r->wait_src, r->wait_tag);
  }
  t->st.deadlock = 1;
  atomic_store(&t->stopped, 1);
  char *text = mp_deadlock_end(&d);
  mp_fail_text(&t->log, text, 1);   /* always quoted: it is often the consequence of the others */
  free(text);
}

/* After a stop: wake every sleeper so that it sees it (holding no lock). */
void mpt_wake_all(mpt *t) {
  for (int i = 0; i < t->n; i++) {
    rank *r = &t->ranks[i];
    pthread_mutex_lock(&r->mu);
    pthread_cond_broadcast(&r->cv);
    pthread_mutex_unlock(&r->mu);
  }
}

/* A message from src with tag has just been published to d: wake d if it
 * sleeps waiting for it.  This load and the publishing store pair with a
 * sleeper's store of `sleeping` and its last look (the head comment). */
static void wake_if_waiting(mpt *t, rank *d, int src, int tag) {
  if (!atomic_load_explicit(&d->sleeping, memory_order_seq_cst)) return;
  pthread_mutex_lock(&d->mu);
  if (atomic_load_explicit(&d->sleeping, memory_order_relaxed) && (d->wait_src < 0 || d->wait_src == src) &&
      tag_ok(d->wait_tag, tag)) {
    pthread_mutex_lock(&t->g);
    atomic_store_explicit(&d->sleeping, 0, memory_order_relaxed);
    t->sleeping--;
    atomic_fetch_add_explicit(&t->awake, 1, memory_order_relaxed);
    pthread_mutex_unlock(&t->g);
    d->woken_at = wallclock();
    pthread_cond_signal(&d->cv);
  }
  pthread_mutex_unlock(&d->mu);
}

/* ==== the mp calls ======================================================== */

static inline void cpu_relax(void) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  __builtin_ia32_pause();
#elif defined(__GNUC__) && defined(__aarch64__)
  __asm__ __volatile__("yield");
#endif
}

static int mpt_probe(mp *self, int src, int tag, mp_status *st);

/* Computing is the program's own here: a progress function (mp_set_progress)
 * runs at each charge if a message is there. */
static int progress_now(rank *r) {
  mp_status st;
  if (r->base.progress && mpt_probe(&r->base, MP_ANY, MP_ANY, &st) == 1)
    r->base.progress(&r->base, r->base.progress_ud);
  return MP_OK;
}

/* mp_compute and mp_busy: nothing to charge but the progress function. */
static int mpt_compute(mp *self, double amount) {
  rank *r = (rank *)self;
  (void)amount;
  if (stopped(r->t)) return MP_ESTOPPED;
  return progress_now(r);
}

/* k off its sender's list: the sender lets go of it. */
static void unlist(rank *r, ticket *k) {
  DLIST_UNLINK_HEAD(r->refs, k);
}

/* k back on its sender's list. */
static void relist(rank *r, ticket *k) {
  k->prev = NULL;
  k->next = r->refs;
  if (r->refs) r->refs->prev = k;
  r->refs = k;
}

/* mp_send, or with ref mp_send_ref (*ref: the record's ticket). */
static int send_msg(mp *self, int dst, int tag, const void *buf, size_t len, mp_ref **ref) {
  rank *r = (rank *)self;
  mpt *t = r->t;
  if (stopped(t)) return MP_ESTOPPED;
  rank *d = &t->ranks[dst];
  if (ref) {
    ticket *k;
    chan_put_ref(chan_get(r, d), r->base.rank, tag, ++r->clock, buf, len, &k);
    relist(r, k);   /* the sender's until it lets go (mpt_free: a stopped run) */
    *ref = (mp_ref *)k;
  } else {
    chan_put(chan_get(r, d), r->base.rank, tag, ++r->clock, buf, len);
  }
  wake_if_waiting(t, d, r->base.rank, tag);
  r->st.sent++;
  r->st.bytes_sent += (long long)len;
  return MP_OK;
}

static int mpt_send(mp *self, int dst, int tag, const void *buf, size_t len) {
  return send_msg(self, dst, tag, buf, len, NULL);
}

static int mpt_send_ref(mp *self, int dst, int tag, const void *buf, size_t len, mp_ref **ref) {
  return send_msg(self, dst, tag, buf, len, ref);
}

static void mpt_settle(mp *self, mp_ref *ref) {
  unlist((rank *)self, (ticket *)ref);
  ticket_settle((ticket *)ref);
}

static int mpt_withdraw(mp *self, mp_ref *ref) {
  rank *r = (rank *)self;
  ticket *k = (ticket *)ref;
  unlist(r, k);   /* first: a withdrawn ticket may be freed at once */
  if (ticket_withdraw(k)) return 1;
  relist(r, k);
  return 0;
}

/* Copy the message f out to the caller and take it. */
static int deliver(rank *r, found f, void *buf, size_t cap, mp_status *st) {
  rec *x = f.x;
  if (x == r->pin_x) r->pin_x = NULL;   /* taken: no longer pinned (its chunk may go) */
  size_t len = (size_t)x->len, n = len <= cap ? len : cap;
  int src = (int)x->src, tag = x->tag;
  if (x->flags & REC_REF) {
    ticket_read(rec_ticket(x), rec_data(x) + sizeof(ticket *), buf, n);   /* seen: not withdrawn */
  } else if (n) {
    const unsigned char *p = rec_data(x);
    if (x->flags & REC_BIG) memcpy(&p, rec_data(x), sizeof p);
    memcpy(buf, p, n);
  }
  if (x->stamp > r->clock) r->clock = x->stamp;
  chan_take(f.q, x);
  if (st) *st = (mp_status){src, tag, len};
  r->st.received++;
  r->st.bytes_received += (long long)len;
  if (len > cap) {
    mpt_warn(r->t, "rank %d: mp_recv truncated a %zu-byte message from rank %d (tag %d) to %zu bytes",
         r->base.rank, len, src, tag, cap);
    return MP_ETRUNC;
  }
  return MP_OK;
}

/* How a waiting rank waits, now (cpuload.h says what else runs). */
enum { W_SLEEP, W_PAUSE, W_YIELD, W_SHORT };
#define SHORT_SPIN_S 20e-6   /* W_SHORT: how long, at most */
#define YIELD_SPIN_S 50e-6   /* W_YIELD: how long, at most */
#define CROWDED_SPIN_S 50e-6 /* any wait, at most, while the run has more ranks than
                                processors: ranks that spin or yield long there starve
                                the ones that work (5 ranks on 2 cores took 2 to 4 times
                                as long with 1 ms) */

static int how_to_wait(mpt *t) {
  int awake = atomic_load_explicit(&t->awake, memory_order_relaxed), others;
  cpuload_running(&t->load, awake, &others);
  /* On a machine of 8 or more processors a runnable thread or two of
   * others' is noise (a kernel thread; a rank of ours that has just
   * registered as sleeping but is still runnable): it must not make 16
   * ranks on 16 cores sleep and wake at every exchange. */
  if (others <= t->cpus / 8) others = 0;
  if (awake <= t->cpus - others) return W_PAUSE;   /* a processor of its own */
  if (others == 0 && !cpuload_hogged(&t->load))
    return W_YIELD;                                /* only our own threads want it */
  if (t->n <= t->cpus + 1) return W_SHORT;         /* ours fit (but a master that mostly
                                                      waits), beside other programs */
  return W_SLEEP;                                  /* ours and others crowd the cores */
}

/* Watch r's channels from src (MP_ANY: all) until something new is there,
 * the run stops or spin_ns pass; 1 if something came.  How, decided again
 * now and then:
 *   pause  while no more of this machine's threads are awake (computing or
 *          spinning) than there are processors other programs leave idle:
 *          the sender runs on another core and the message is seen within a
 *          cache-line transfer;
 *   yield  while more are awake than there are processors but nothing else
 *          runs on the machine (sixteen ranks on two cores): sched_yield
 *          hands the processor to another of our threads, likely the one
 *          that will send (unless a yield lately took long: then a thread
 *          that does not give the processor back got it, cpuload_yield);
 *          for at most YIELD_SPIN_S;
 *   short  pause for at most SHORT_SPIN_S while other programs want the
 *          processors but this run's ranks alone would fit on them (all but
 *          one: a master that mostly waits):
 *          while the scheduler has both ends of an exchange on processors,
 *          the message comes within the spin (two slaves trade a boundary
 *          every few microseconds) and the pair runs at full speed for the
 *          rest of their time slices; a partner that lost its processor is
 *          not waited for long (the waiter then sleeps, and a busy loop
 *          gets the processor);
 *   sleep  at once while this run's threads and other programs' together
 *          crowd the processors: a spinner or yielder would take the
 *          processor from a thread that works, perhaps the one it waits
 *          for, for a whole time slice; the sender wakes a sleeper instead. */
static int spin(rank *r, int src, int mark) {
  mpt *t = r->t;
  if (t->cfg.spin_ns <= 0) return 0;
  double lim = (double)t->cfg.spin_ns * 1e-9;
  if (t->n > t->cpus && lim > CROWDED_SPIN_S) lim = CROWDED_SPIN_S;
  double now = wallclock(), until = now + lim;
  int how = how_to_wait(t);
  if (how == W_SHORT || how == W_YIELD) {
    double u = now + (how == W_SHORT ? SHORT_SPIN_S : YIELD_SPIN_S);
    if (u < until) until = u;
  }
  for (long i = 1; how != W_SLEEP; i++) {
    if (news(r, src, mark)) return 1;
    if (how == W_YIELD)
      cpuload_yield(&t->load);
    else
      cpu_relax();
    if ((i & 31) == 0 || how == W_YIELD) {   /* now and then: the clock, the run, the room */
      now = wallclock();
      if (now >= until || stopped(t)) return 0;
      int h = how_to_wait(t);
      if (h == W_SHORT && how != W_SHORT && now + SHORT_SPIN_S < until) until = now + SHORT_SPIN_S;
      if (h == W_YIELD && how != W_YIELD && now + YIELD_SPIN_S < until) until = now + YIELD_SPIN_S;
      how = how == W_SHORT && h != W_SLEEP ? W_SHORT : h;   /* a short spin stays short */
    }
  }
  return 0;
}

/* Wait until a message from src with tag is there: *f, and MP_OK; or
 * MP_EDEADLOCK or MP_ESTOPPED. */
static int arrived(rank *r, int src, int tag, found *out) {
  mpt *t = r->t;
  double w0 = -1;
  for (;;) {
    /* Look. */
    int mark = news_mark(r, src);
    found f = look(r, src, tag);
    if (f.x) {
      if (w0 >= 0) r->st.recv_wait += wallclock() - w0;
      *out = f;
      return MP_OK;
    }
    if (w0 < 0) w0 = wallclock();
    /* Spin. */
    if (spin(r, src, mark)) continue;
    /* Sleep: register, then look once more (wake_if_waiting says why). */
    pthread_mutex_lock(&r->mu);
    r->wait_src = src;
    r->wait_tag = tag;
    atomic_store_explicit(&r->sleeping, 1, memory_order_seq_cst);
    f = look(r, src, tag);
    if (f.x || stopped(t)) {
      atomic_store_explicit(&r->sleeping, 0, memory_order_relaxed);
      pthread_mutex_unlock(&r->mu);
      r->st.recv_wait += wallclock() - w0;
      *out = f;
      return f.x ? MP_OK : MP_ESTOPPED;
    }
    r->st.sleeps++;
    pthread_mutex_lock(&t->g);
    t->sleeping++;
    atomic_fetch_sub_explicit(&t->awake, 1, memory_order_relaxed);
    int dead = t->sleeping == t->live && !stopped(t);   /* a stop (an abort) is no deadlock */
    if (dead) mpt_deadlock_locked(t);
    pthread_mutex_unlock(&t->g);
    if (dead) {
      pthread_mutex_unlock(&r->mu);
      mpt_wake_all(t);
      pthread_mutex_lock(&r->mu);
    }
    r->woken_at = -1;
    while (atomic_load_explicit(&r->sleeping, memory_order_relaxed) && !stopped(t))
      pthread_cond_wait(&r->cv, &r->mu);
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

static int mpt_recv(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st) {
  rank *r = (rank *)self;
  mpt *t = r->t;
  if (stopped(t)) return MP_ESTOPPED;
  found f;
  int rc = arrived(r, src, tag, &f);
  return rc == MP_OK ? deliver(r, f, buf, cap, st) : rc;
}

/* A message taken by mp_recv_msg: its payload in the sender's buffer (a
 * ticket's), in a copy (REC_BIG's), or here; a send by reference keeps its
 * ticket, by which its sender may still withdraw it. */
typedef struct {
  size_t len;
  ticket *t;
  unsigned char *big;
  unsigned char inl[];
} held;

static int mpt_recv_msg(mp *self, int src, int tag, mp_msg **msg, mp_status *st) {
  rank *r = (rank *)self;
  if (stopped(r->t)) return MP_ESTOPPED;
  int rc;
  found f;
  if ((rc = arrived(r, src, tag, &f)) != MP_OK) return rc;
  rec *x = f.x;
  size_t len = (size_t)x->len;
  int inl = !(x->flags & REC_BIG) && !((x->flags & REC_REF) && rec_ticket(x)->buf);
  held *h = xmalloc(sizeof *h + (inl ? len : 0));
  h->len = len;
  h->t = NULL;
  h->big = NULL;
  if (x->flags & REC_REF) {   /* the record's hold on the ticket passes to h */
    h->t = rec_ticket(x);
    if (inl && len) memcpy(h->inl, rec_data(x) + sizeof h->t, len);
    int seen = T_SEEN;
    atomic_compare_exchange_strong(&h->t->state, &seen, T_REF);   /* withdrawable again */
    x->flags &= ~(uint32_t)REC_REF;
  } else if (x->flags & REC_BIG) {   /* the copy passes to h */
    memcpy(&h->big, rec_data(x), sizeof h->big);
    x->flags &= ~(uint32_t)REC_BIG;
  } else if (len) {
    memcpy(h->inl, rec_data(x), len);
  }
  if (x == r->pin_x) r->pin_x = NULL;
  if (x->stamp > r->clock) r->clock = x->stamp;
  if (st) *st = (mp_status){(int)x->src, x->tag, len};
  chan_take(f.q, x);
  r->st.received++;
  r->st.bytes_received += (long long)len;
  *msg = (mp_msg *)h;
  return MP_OK;
}

static int mpt_msg_read(mp *self, mp_msg *msg, void *buf, size_t cap) {
  (void)self;
  held *h = (held *)msg;
  size_t n = h->len <= cap ? h->len : cap;
  int rc = h->len > cap && buf ? MP_ETRUNC : MP_OK;
  if (h->t) {
    if (ticket_read(h->t, h->inl, buf, n) < 0) rc = MP_EGONE;
    ticket_drop(h->t);
  } else if (n) {
    memcpy(buf, h->big ? h->big : h->inl, n);
  }
  free(h->big);
  free(h);
  return rc;
}

static int mpt_msg_gone(mp *self, const mp_msg *msg) {
  (void)self;
  const held *h = (const held *)msg;
  return h->t && atomic_load(&h->t->state) == T_GONE;
}

/* A message is shown, not taken (a probe that found one, mp_wait): it has
 * arrived, so whatever this rank sends from now on comes after it, and its
 * clock moves past the message's stamp as a receive's does (else a message
 * it then sends to itself, or one sent on in its name, could be taken from
 * any source before this one); from any source, it is pinned (look() says
 * why). */
static void show(rank *r, found f, int src, int tag, mp_status *st) {
  if (f.x->stamp > r->clock) r->clock = f.x->stamp;
  if (src < 0) r->pin_q = f.q, r->pin_x = f.x, r->pin_tag = tag;
  if (st) *st = (mp_status){(int)f.x->src, f.x->tag, (size_t)f.x->len};
}

static int mpt_wait(mp *self, int src, int tag, mp_status *st) {
  rank *r = (rank *)self;
  if (stopped(r->t)) return MP_ESTOPPED;
  found f;
  int rc = arrived(r, src, tag, &f);
  if (rc == MP_OK) show(r, f, src, tag, st);
  return rc;
}

static int mpt_probe(mp *self, int src, int tag, mp_status *st) {
  rank *r = (rank *)self;
  if (stopped(r->t)) return MP_ESTOPPED;
  found f = look(r, src, tag);
  if (!f.x) return 0;
  show(r, f, src, tag, st);
  return 1;
}

static double mpt_time(const mp *self) { return wallclock() - ((const rank *)self)->t->t0; }

static int mpt_sleep(mp *self, double seconds) {
  rank *r = (rank *)self;
  if (stopped(r->t)) return MP_ESTOPPED;
  struct timespec ts = {(time_t)seconds, (long)((seconds - (double)(time_t)seconds) * 1e9)};
  while (nanosleep(&ts, &ts) != 0 && !stopped(r->t)) {
  }
  return MP_OK;
}

/* mp_abort: the first to abort gives the run's exit code. */
static void mpt_stop(mp *self, int code, const char *why) {
  rank *r = (rank *)self;
  mpt *t = r->t;
  pthread_mutex_lock(&t->g);
  if (!t->st.aborted) {
    t->st.aborted = 1;
    t->st.abort_code = code;
  }
  mp_fail_text(&t->log, why ? why : "aborted", 0);
  atomic_store(&t->stopped, 1);
  pthread_mutex_unlock(&t->g);
  mpt_wake_all(t);
}

/* A call mp.c found a bad argument in. */
static int mpt_reject(mp *self, int code, const char *why) {
  mpt *t = ((rank *)self)->t;
  if (stopped(t)) return MP_ESTOPPED;
  mpt_fail_text(t, why, 0);
  return code;
}

/* Promises: none here (the receiver takes a message when it comes, often
 * before its sender settles it; where not, the settle copies it out). */
const mp_ops mpt_ops = {.send = mpt_send, .recv = mpt_recv, .probe = mpt_probe, .compute = mpt_compute,
                               .time = mpt_time, .wait = mpt_wait, .busy = mpt_compute,
                               .sleep_for = mpt_sleep, .stop = mpt_stop, .send_ref = mpt_send_ref,
                               .settle = mpt_settle, .withdraw = mpt_withdraw, .recv_msg = mpt_recv_msg,
                               .msg_read = mpt_msg_read, .msg_gone = mpt_msg_gone, .reject = mpt_reject,
                               .tag_max = INT_MAX, .sleep_bounded = 1};
