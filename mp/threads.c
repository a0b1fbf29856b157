/* threads.c -- the threads backend's machine (threads.h): making it,
 * running its ranks (a thread each), the unread messages, the statistics;
 * its ranks' calls are threads_calls.c's. */
#include "mp/threads.h"

#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "mp/threads_calls.h"
#include "util/wallclock.h"
#include "util/xmem.h"

void mpt_config_init(mpt_config *cfg) {
  cfg->spin_ns = 1000000;
  cfg->warn = stderr;
}

/* ==== errors and warnings ================================================= */

/* The run's log (backend.h) is the machine's, under g. */
void mpt_fail_text(mpt *t, const char *text, int always) {
  pthread_mutex_lock(&t->g);
  mp_fail_text(&t->log, text, always);
  pthread_mutex_unlock(&t->g);
}

void mpt_warn(mpt *t, const char *fmt, ...) {
  char buf[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  pthread_mutex_lock(&t->g);
  mp_warn(&t->log, "%s", buf);
  pthread_mutex_unlock(&t->g);
}

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
  mpt *t = aligned_alloc(LINE, (sizeof *t + LINE - 1) / LINE * LINE);
  rank *ranks = aligned_alloc(LINE, (size_t)nranks * sizeof *ranks);
  if (!t || !ranks) xpanic("threads: out of memory for %d ranks", nranks);
  memset(t, 0, sizeof *t);
  memset(ranks, 0, (size_t)nranks * sizeof *ranks);
  t->cfg = *cfg;
  t->n = nranks;
  t->ranks = ranks;
  for (int i = 0; i < nranks; i++) {
    rank *r = &t->ranks[i];
    r->base = (struct mp){.ops = &mpt_ops, .rank = i, .size = nranks};
    r->t = t;
    r->out = xcalloc((size_t)nranks, sizeof *r->out);
    r->in = xcalloc((size_t)nranks, sizeof *r->in);
    for (int s = 0; s < nranks; s++) atomic_init(&r->in[s], NULL);
    r->inlist = xcalloc((size_t)nranks, sizeof *r->inlist);
    atomic_init(&r->nin, 0);
    atomic_init(&r->sleeping, 0);
    pthread_mutex_init(&r->mu, NULL);
    pthread_cond_init(&r->cv, NULL);
  }
  atomic_init(&t->stopped, 0);
  atomic_init(&t->awake, 0);
  t->cpus = cpuload_cpus();
  cpuload_init(&t->load);
  pthread_mutex_init(&t->g, NULL);
  pthread_mutex_init(&t->gate_mu, NULL);
  pthread_cond_init(&t->gate_cv, NULL);
  t->st.ranks = nranks;
  t->log = (mp_log){.name = "threads", .warn = cfg->warn, .st = &t->st.run};
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
  mp_enter(&r->base, t->procs[r->base.rank].main, t->procs[r->base.rank].ud);
  r->st.done = 1;
  r->st.finish = wallclock() - t->t0;
  pthread_mutex_lock(&t->g);
  t->live--;
  atomic_fetch_sub_explicit(&t->awake, 1, memory_order_relaxed);
  int dead = t->live > 0 && t->sleeping == t->live && !stopped(t);
  if (dead) mpt_deadlock_locked(t);
  pthread_mutex_unlock(&t->g);
  if (dead) mpt_wake_all(t);
  return NULL;
}

/* Count and report what was sent and never received (every thread has
 * ended: everything published is visible).  The first is the earliest
 * arrival, as a receive from any source would have taken it. */
static void sweep_unread(mpt *t) {
  for (int i = 0; i < t->n; i++) {
    rank *r = &t->ranks[i];
    long long count = 0;
    const rec *first = NULL;
    int k = atomic_load(&r->nin);
    for (int j = 0; j < k; j++) {
      chan *q = r->inlist[j];
      chunk *c = q->hc;
      for (size_t off = q->hoff;;) {
        const rec *x = rec_at(c, off);
        uint32_t sz = atomic_load(&x->size);
        if (sz == 0) break;
        if (sz == REC_JUMP) {
          c = c->next, off = 0;
          continue;
        }
        off += sz;
        if (x->flags & REC_TAKEN) continue;
        if ((x->flags & REC_REF) && atomic_load(&rec_ticket((rec *)x)->state) == T_GONE) continue;
        count++;
        if (!first || x->stamp < first->stamp || (x->stamp == first->stamp && x->src < first->src)) first = x;
      }
    }
    if (!count) continue;
    r->st.unread = count;
    t->st.unread += count;
    mpt_warn(t, "rank %d finished with %lld unread message%s (first from rank %d, tag %d)", i, count,
         count == 1 ? "" : "s", (int)first->src, first->tag);
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
      mpt_fail_text(t, buf, 1);
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
  return mp_log_report(&t->log, err, errlen);
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
    /* A run that stopped may leave sends by reference unsettled: the
     * sender's hold goes here, the record's with its channel. */
    for (ticket *k = r->refs, *next; k; k = next) {
      next = k->next;
      ticket_drop(k);
    }
    int k = atomic_load(&r->nin);
    for (int j = 0; j < k; j++) chan_free(r->inlist[j]);
    free(r->out);
    free(r->in);
    free(r->inlist);
    pthread_mutex_destroy(&r->mu);
    pthread_cond_destroy(&r->cv);
  }
  pthread_mutex_destroy(&t->g);
  pthread_mutex_destroy(&t->gate_mu);
  pthread_cond_destroy(&t->gate_cv);
  free(t->ranks);
  mp_log_free(&t->log);
  free(t);
}
