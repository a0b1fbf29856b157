/* calls.c -- the simulator's side of mp.h: scheduling, and the mp calls on
 * the timing model.
 *
 * Reading order: scheduling (who runs next), then the mp calls (compute,
 * send, recv, probe; messages without copies).  The data (ranks, the
 * machine) are calls.h's; messages, mailboxes and channels mailbox.h's;
 * sim_run's main loop and the deadlock report sim.c's.  The timing model
 * itself is specified in sim.h.
 *
 * Scheduling is a conservative sequential discrete-event loop.  Every rank
 * that can act is queued in `q` under the time it will act at; the running
 * rank is always the earliest.  When its clock moves past the next queued
 * time, or it blocks in recv, it switches directly to the earliest queued
 * rank (no trip through a scheduler); only when the queue is empty does
 * control return to sim_run, which then has either finished or found a
 * deadlock.  A rank whose clock moves but stays strictly earliest goes on
 * without a switch: exactly what queueing it and popping it would do.
 *
 *   A token ring on the bus model, messages costing m:
 *
 *   time -->  0            m            2m           3m
 *   rank 0    send--.  recv (blocked, not queued)    .->recv
 *   rank 1    recv  '---->recv send--.               |
 *   rank 2    recv                   '---->recv send-'
 *
 *   Each send queues the blocked receiver at the arrival time; each recv
 *   that finds nothing there switches to the earliest queued rank.
 *
 * A blocked rank is queued only once a matching message is on its way, at
 * that message's arrival time (moved earlier if an earlier matching message
 * is sent later).  Nothing queued and ranks still alive means deadlock. */
#include "sim/calls.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

/* ==== scheduling ========================================================== */

/* The running rank r gives way to the earliest queued rank (or to sim_run
 * when none is queued); returns when r is resumed. */
static void give_way(sim *s, rank *r) {
  double t;
  int id = evq_pop(s->q, &t);
  if (id == r->base.rank) {
    s->gtime = t;
    return;
  }
  s->st.switches++;
  if (s->tick && (++s->ticks & 0xffff) == 0) s->tick(s->tick_ud, s->gtime, s->st.events);
  if (id < 0) {
    coro_switch(r->co, s->main);
  } else {
    XASSERT(t >= s->gtime);
    s->gtime = t;
    coro_switch(r->co, s->ranks[id].co);
  }
  mp_set_self(&r->base);   /* resumed */
}

/* r's clock has moved on.  Go on if it is still strictly the earliest (what
 * queueing and popping it would give), else queue it and give way. */
static inline void moved(sim *s, rank *r) {
  if (r->now < evq_min(s->q)) {
    s->gtime = r->now;
    return;
  }
  evq_set(s->q, r->base.rank, r->now, s->seq++);
  give_way(s, r);
}

/* Reserve r's processor for dur seconds from r's clock on; the start. */
static inline double reserve(sim *s, rank *r, double dur) {
  double start = r->now, *busy = &s->busy[r->proc];
  if (*busy > start) start = *busy;
  *busy = start + dur;
  return start;
}

/* LogGP's overhead: r's processor is busy o from r's clock on (after any
 * wait for it); r's clock moves to its end.  Returns when it began. */
static double overhead(sim *s, rank *r, double o) {
  double t0 = r->now, start = reserve(s, r, o);
  r->st.cpu_wait += start - t0;
  r->st.overhead += o;
  if (s->tr && start > t0) trace_span(s->tr, "cpuwait", r->base.rank, r->proc, t0, start - t0, -1, -1);
  r->now = start + o;
  return start;
}

/* The rank that does not stop calling after the run stopped. */
static void abandon(sim *s, rank *r) {
  mp_fail(&s->log, "rank %d kept calling after the run stopped (%d calls); abandoned it", r->base.rank,
       STOPPED_CALLS_MAX);
  r->state = R_ABANDONED;
  s->live--;
  give_way(s, r);
  xpanic("an abandoned rank was resumed");
}

static int stopped_call(sim *s, rank *r) {
  if (++r->stopped_calls >= STOPPED_CALLS_MAX) abandon(s, r);
  return MP_ESTOPPED;
}

/* ==== the mp calls ======================================================== */

/* A call's start (but a probe's): MP_OK, the call counted and the count of
 * fruitless probes reset; or, the run stopped, stopped_call's answer. */
static inline int begin(sim *s, rank *r) {
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  r->probe_spins = 0;
  return MP_OK;
}

/* cpu.h's busy neighbours: the factor 1 + slowdown * k + slowdown_spin * j
 * for r's compute, k the processors other than r's with a rank working at
 * r's clock (not blocked, not finished), j those with a rank blocked no
 * longer than cpu.spin (spinning) and none working; each processor once. */
static double slow_factor(sim *s, const rank *r) {
  unsigned char *seen = s->seen;   /* per processor: 0 idle, 1 spinning, 2 working */
  memset(seen, 0, (size_t)s->cfg.procs);
  for (int i = 0; i < s->n; i++) {
    const rank *o = &s->ranks[i];
    if (o->proc == r->proc || o->state == R_DONE || o->state == R_ABANDONED) continue;
    unsigned char v = o->state != R_BLOCKED ? 2 : r->now - o->since <= s->cfg.cpu.spin ? 1 : 0;
    if (v > seen[o->proc]) seen[o->proc] = v;
  }
  int k = 0, j = 0;
  for (int p = 0; p < s->cfg.procs; p++) k += seen[p] == 2, j += seen[p] == 1;
  return 1 + s->cfg.cpu.slowdown * k + s->cfg.cpu.slowdown_spin * j;
}

/* r computes until end with a progress function: at each arrival before end
 * (and at once for messages already there) the function runs at the
 * arrival, the processor lent to it; the processor time it charges (x)
 * moves the computing's end by as much.  r->now is the computing's start
 * (before any wait for the processor). */
static int busy_progress(sim *s, rank *r, double end) {
  double shown = -INFINITY, at = r->now;   /* messages up to shown were offered; at: last resumed */
  for (;;) {
    msg *m = r->box.head;
    while (m && m->arrival <= shown) m = m->next;
    double next = m ? m->arrival : INFINITY;
    if (next < r->now) next = r->now;
    if (next > end) next = end;
    if (next > r->now) {   /* compute until then, woken earlier by an earlier arrival (sim_send) */
      r->state = R_BUSY;
      r->wake = next;
      evq_set(s->q, r->base.rank, next, s->seq++);
      give_way(s, r);
      r->state = R_READY;
      if (s->stopped) {
        r->now = end;
        return stopped_call(s, r);
      }
      r->now = at = r->wake;
    }
    if (r->now >= end) break;
    double t = r->now, saved = s->busy[r->proc];
    s->busy[r->proc] = t;
    r->in_progress = 1;
    r->base.progress(&r->base, r->base.progress_ud);
    r->in_progress = 0;
    double x = r->now - t;
    s->busy[r->proc] = saved + x;
    end += x;
    shown = t;
    if (s->stopped) {
      r->now = end;
      return stopped_call(s, r);
    }
  }
  r->now = end;
  if (r->now > at) moved(s, r);
  return MP_OK;
}

/* r computes for d seconds (units of them, for the statistics). */
static int charge(sim *s, rank *r, double d, double units) {
  double t0 = r->now;
  if (s->cpu && (s->cfg.cpu.slowdown > 0 || s->cfg.cpu.slowdown_spin > 0)) d *= slow_factor(s, r);
  double start = reserve(s, r, d);
  r->st.units += units;
  r->st.compute += d;
  r->st.cpu_wait += start - t0;
  if (s->tr) {
    if (start > t0) trace_span(s->tr, "cpuwait", r->base.rank, r->proc, t0, start - t0, -1, -1);
    trace_span(s->tr, "compute", r->base.rank, r->proc, start, d, -1, -1);
  }
  if (r->base.progress) return busy_progress(s, r, start + d);
  r->now = start + d;
  if (r->now > t0) moved(s, r);
  return MP_OK;
}

static int sim_compute(mp *self, double units) {
  rank *r = (rank *)self;
  sim *s = r->s;
  int rc = begin(s, r);
  if (rc != MP_OK) return rc;
  return charge(s, r, units * s->cfg.c, units);
}

static int sim_busy(mp *self, double seconds) {
  rank *r = (rank *)self;
  sim *s = r->s;
  int rc = begin(s, r);
  if (rc != MP_OK) return rc;
  return charge(s, r, seconds, 0);
}

static int sim_sleep(mp *self, double seconds) {
  rank *r = (rank *)self;
  sim *s = r->s;
  int rc = begin(s, r);
  if (rc != MP_OK) return rc;
  if (s->tr && seconds > 0) trace_span(s->tr, "sleep", r->base.rank, r->proc, r->now, seconds, -1, -1);
  r->st.slept += seconds;
  double t0 = r->now;
  r->now += seconds;
  if (r->now > t0) moved(s, r);
  return MP_OK;
}

/* mp_yield: the ranks queued at r's time act first (r queued behind them,
 * as moved does when the clock reaches the earliest time).  Not from a
 * progress function: busy_progress has lent it the processor meanwhile. */
static int sim_yield(mp *self) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (s->stopped) return stopped_call(s, r);
  if (r->in_progress || evq_min(s->q) > r->now) return MP_OK;
  evq_set(s->q, r->base.rank, r->now, s->seq++);
  give_way(s, r);
  return s->stopped ? stopped_call(s, r) : MP_OK;
}

/* When len bytes that leave processor a->proc for d's at t arrive, and the
 * network's state charged for them: the machine's model (sim.h) but for
 * the sender's processor costs (the caller's) and the channel's order. */
static inline double wire(sim *s, const rank *a, const rank *d, double t, size_t len, int tag, uint64_t id) {
  const sim_config *c = &s->cfg;
  if (d->proc == a->proc) return t + c->local;
  if (c->net == SIM_NET_BUS) {
    double start = t > s->bus_free ? t : s->bus_free;
    s->bus_free = start + c->m + (double)len * c->per_byte;
    return s->bus_free;
  }
  if (c->net == SIM_NET_IDEAL) return t + c->m + (double)len * c->per_byte;
  if (c->net == SIM_NET_TOPOLOGY)   /* link.h; id names the message in a trace */
    return links_send(s->links, a->proc, d->proc, t, len, s->tr, a->base.rank, d->base.rank, tag, id);
  double *nic = &s->nic[a->proc], inject = t > *nic ? t : *nic;
  *nic = inject + c->g;
  return inject + (len > 1 ? (double)(len - 1) * c->G : 0) + c->L;
}

/* r sends len bytes to d: its processor's costs (cpu.h's send cost, LogGP's
 * o), which move its clock; their total in *o and the start of the first
 * in *t0 (r's clock if none). */
static inline void send_costs(sim *s, rank *r, const rank *d, size_t len, double *t0, double *o) {
  const sim_config *c = &s->cfg;
  *t0 = r->now;
  *o = 0;
  if (d->proc == r->proc) return;
  if (s->cpu && cpu_send_cost(&c->cpu, len) > 0) {   /* cpu.h: the send's processor time */
    *o = cpu_send_cost(&c->cpu, len);
    *t0 = overhead(s, r, *o);
  }
  if (c->net == SIM_NET_LOGGP) {
    double t1 = overhead(s, r, c->o);
    if (*o == 0) *t0 = t1;
    *o += c->o;
  }
}

/* The latest arrival on the channel a -> d so far, moved to arrival if
 * that is later (non-overtaking); the arrival in send order. */
static inline double in_order(rank *a, int dst, double arrival) {
  double *last = chan_last(&a->chans, dst);
  if (arrival < *last) arrival = *last;
  *last = arrival;
  return arrival;
}

/* m (its arrival set, placed) into d's mailbox: a receiver blocked on a
 * matching message wakes when the earliest arrives (cpu.h: later if it has
 * gone to sleep; its first waker r pays o_wake, where remote); a receiver
 * computing with a progress function (R_BUSY) wakes at the arrival. */
static inline void deliver(sim *s, rank *r, rank *d, msg *m, int remote) {
  const sim_config *c = &s->cfg;
  box_insert(m);
  if (d->state == R_BLOCKED && msg_matches(m, d->wait_src, d->wait_tag)) {
    double resume = m->arrival;
    if (s->cpu && remote) {
      resume = cpu_resume(&c->cpu, d->since, m->arrival);
      if (d->wake == INFINITY && cpu_asleep(&c->cpu, d->since, m->arrival) && c->cpu.o_wake > 0)
        overhead(s, r, c->cpu.o_wake);
    }
    if (resume < d->wake) {
      d->wake = resume;
      evq_set(s->q, d->base.rank, resume, s->seq++);
    }
  } else if (d->state == R_BUSY && m->arrival < d->wake) {   /* computing: its progress acts at the arrival */
    d->wake = m->arrival;
    evq_set(s->q, d->base.rank, m->arrival, s->seq++);
  }
}

static inline void count_sent(sim *s, rank *r, int tag, size_t len) {
  r->st.sent++;
  r->st.bytes_sent += (long long)len;
  if (tag >= 0 && tag < SIM_TAGS) r->st.sent_tag[tag]++;
  s->st.messages++;
  s->st.bytes += (long long)len;
}

/* mp_send, or with ref mp_send_ref (*ref: the message, by reference). */
static int send_msg(mp *self, int dst, int tag, const void *buf, size_t len, mp_ref **ref) {
  rank *r = (rank *)self;
  sim *s = r->s;
  int rc = begin(s, r);
  if (rc != MP_OK) return rc;
  rank *d = &s->ranks[dst];
  double before = r->now, t0, o;
  send_costs(s, r, d, len, &t0, &o);
  double arrival = in_order(r, dst, wire(s, r, d, r->now, len, tag, s->seq));

  msg *m = ref ? msg_new_ref(&s->msgs, &d->box, buf, len) : msg_new(&s->msgs, &d->box, len);
  m->sent = t0;
  m->arrival = arrival;
  m->seq = s->seq++;
  m->src = r->base.rank;
  m->tag = tag;
  if (ref)
    *ref = (mp_ref *)m;
  else
    box_place(&s->msgs, m, buf);
  count_sent(s, r, tag, len);
  if (s->tr) trace_send(s->tr, r->base.rank, r->proc, t0, o, dst, tag, len, m->seq, arrival);
  deliver(s, r, d, m, d->proc != r->proc);
  if (r->now > before) moved(s, r);
  return MP_OK;
}

/* mp_transfer: wire's charge without a message.  The transfer counts as a
 * message sent by src and received by dst in the statistics. */
static double sim_transfer(mp *self, int src, int dst, size_t len, double at) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (begin(s, r) != MP_OK) return at;
  rank *a = &s->ranks[src], *d = &s->ranks[dst];
  double before = r->now, t = at;
  if (a == r && at == r->now) {
    double t0, o;
    send_costs(s, r, d, len, &t0, &o);
    t = r->now;
  }
  double arrival = in_order(a, dst, wire(s, a, d, t, len, 0, s->seq++));
  count_sent(s, a, -1, len);
  d->st.received++;
  d->st.bytes_received += (long long)len;
  s->st.received++;
  if (r->now > before) moved(s, r);
  return arrival;
}

/* mp_notify: a 0-byte message whose arrival the caller chose. */
static int sim_notify(mp *self, int dst, int tag, double at) {
  rank *r = (rank *)self;
  sim *s = r->s;
  int rc = begin(s, r);
  if (rc != MP_OK) return rc;
  rank *d = &s->ranks[dst];
  msg *m = msg_new(&s->msgs, &d->box, 0);
  m->sent = r->now;
  m->arrival = at > r->now ? at : r->now;
  m->seq = s->seq++;
  m->src = r->base.rank;
  m->tag = tag;
  box_place(&s->msgs, m, "");   /* no bytes */
  count_sent(s, r, tag, 0);
  deliver(s, r, d, m, 0);
  return MP_OK;
}

static int sim_send(mp *self, int dst, int tag, const void *buf, size_t len) {
  return send_msg(self, dst, tag, buf, len, NULL);
}

static int sim_send_ref(mp *self, int dst, int tag, const void *buf, size_t len, mp_ref **ref) {
  return send_msg(self, dst, tag, buf, len, ref);
}

static void sim_settle(mp *self, mp_ref *ref) { msg_settle(&((rank *)self)->s->msgs, (msg *)ref, !((rank *)self)->s->stopped); }

static int sim_withdraw(mp *self, mp_ref *ref) { return msg_withdraw(&((rank *)self)->s->msgs, (msg *)ref); }

/* Promises (mailbox.h): only of a message from a rank, into a buffer. */
static mp_promise *sim_promise(mp *self, int src, int tag, int mask, void *buf, size_t cap) {
  rank *r = (rank *)self;
  if (src < 0 || src >= r->s->n || !buf || !cap) return NULL;
  return (mp_promise *)promise_add(&r->s->msgs, &r->box, src, tag, mask, buf, cap);
}

static int sim_promise_drop(mp *self, mp_promise *p, int keep) {
  rank *r = (rank *)self;
  return promise_drop(&r->s->msgs, &r->box, (promise *)p, keep);
}

/* The message a recv of r from src with tag takes, once it has arrived:
 * r blocks until then.  NULL and *rc = MP_EDEADLOCK or MP_ESTOPPED if the
 * run stopped meanwhile. */
static msg *arrived(sim *s, rank *r, int src, int tag, int *rc) {
  msg *m = box_find(&r->box, src, tag);
  if (!m || m->arrival > r->now) {
    /* Block: queued at the first matching arrival if one is on its way,
     * else not queued until a matching send queues it.  Woken for a
     * message its sender has withdrawn since (mp_withdraw), it blocks on. */
    double since = r->now;
    r->state = R_BLOCKED;
    r->wait_src = src;
    r->wait_tag = tag;
    r->since = since;
    for (;;) {
      r->wake = INFINITY;
      if (m) {
        r->wake = s->cpu && s->ranks[m->src].proc != r->proc ? cpu_resume(&s->cfg.cpu, since, m->arrival)
                                                              : m->arrival;
        evq_set(s->q, r->base.rank, r->wake, s->seq++);
      }
      give_way(s, r);
      if (s->stopped) break;
      XASSERT(r->wake == s->gtime);
      m = box_find(&r->box, src, tag);
      if (m && m->arrival <= s->gtime) break;
    }
    r->state = R_READY;
    double t = s->stopped ? (s->gtime > since ? s->gtime : since) : r->wake;
    r->now = t;
    r->st.recv_wait += t - since;
    if (s->tr && t > since) trace_span(s->tr, "wait", r->base.rank, r->proc, since, t - since, src, tag);
    if (s->stopped) {
      *rc = r->deadlocked ? MP_EDEADLOCK : MP_ESTOPPED;
      return NULL;
    }
  }
  return m;
}

/* A receive's or mp_wait's start: the call counted, and the message it
 * takes once it has arrived (r blocks until then); NULL and *rc if the run
 * has stopped or stops meanwhile. */
static inline msg *receive(sim *s, rank *r, int src, int tag, int *rc) {
  if ((*rc = begin(s, r)) != MP_OK) return NULL;
  return arrived(s, r, src, tag, rc);
}

/* mp_recv into buf (cap bytes), or, with hold, mp_recv_msg: *hold holds
 * the message, unless fit and it fits (mp_recv_msg_into: its tag t has
 * (t & mask) == (want & mask), its length at most cap), when it is read into
 * buf as mp_recv reads it. */
static inline int recv_msg(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st, mp_msg **hold, int fit,
                           int mask, int want) {
  rank *r = (rank *)self;
  sim *s = r->s;
  int rc;
  msg *m = receive(s, r, src, tag, &rc);
  if (!m) return rc;

  double before = r->now, t0 = r->now, o = 0;
  if (s->cfg.net == SIM_NET_LOGGP && s->ranks[m->src].proc != r->proc) {
    o = s->cfg.o;
    t0 = overhead(s, r, o);
  }
  if (s->cpu && s->ranks[m->src].proc != r->proc && cpu_recv_cost(&s->cfg.cpu, m->len) > 0) {
    double orc = cpu_recv_cost(&s->cfg.cpu, m->len), t1 = overhead(s, r, orc);   /* cpu.h */
    if (o == 0) t0 = t1;
    o += orc;
  }
  if (st) *st = (mp_status){m->src, m->tag, m->len};
  r->st.received++;
  r->st.bytes_received += (long long)m->len;
  s->st.received++;
  if (s->tr) trace_recv(s->tr, r->base.rank, r->proc, t0, o, m->src, m->tag, m->len, m->seq);
  rc = MP_OK;
  if (hold && !(fit && ((m->tag ^ want) & mask) == 0 && m->len <= cap)) {
    msg_hold(&s->msgs, m);
    *hold = (mp_msg *)m;
  } else {
    if (m->len > cap) {
      mp_warn(&s->log, "rank %d: mp_recv truncated a %zu-byte message from rank %d (tag %d) to %zu bytes",
           r->base.rank, m->len, m->src, m->tag, cap);
      rc = MP_ETRUNC;
    }
    msg_read(&s->msgs, m, buf, m->len <= cap ? m->len : cap);
  }
  if (r->now > before) moved(s, r);
  return rc;
}

static int sim_recv(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st) {
  return recv_msg(self, src, tag, buf, cap, st, NULL, 0, 0, 0);
}

static int sim_recv_msg(mp *self, int src, int tag, mp_msg **hold, mp_status *st) {
  return recv_msg(self, src, tag, NULL, 0, st, hold, 0, 0, 0);
}

static int sim_recv_msg_into(mp *self, int src, int tag, int mask, int want, void *buf, size_t cap, mp_msg **hold,
                             mp_status *st) {
  return recv_msg(self, src, tag, buf, cap, st, hold, 1, mask, want);
}

static int sim_msg_read(mp *self, mp_msg *hold, void *buf, size_t cap) {
  sim *s = ((rank *)self)->s;
  msg *m = (msg *)hold;
  if (m->state == M_GONE) {
    msg_take(&s->msgs, m, NULL, 0);
    return MP_EGONE;
  }
  int rc = m->len > cap && buf ? MP_ETRUNC : MP_OK;
  msg_take(&s->msgs, m, buf, m->len <= cap ? m->len : cap);
  return rc;
}

static int sim_msg_gone(mp *self, const mp_msg *hold) { return (void)self, ((const msg *)hold)->state == M_GONE; }

static int sim_probe(mp *self, int src, int tag, mp_status *st) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  msg *m = box_find(&r->box, src, tag);
  if (m && m->arrival <= r->now) {
    r->probe_spins = 0;
    if (st) *st = (mp_status){m->src, m->tag, m->len};
    return 1;
  }
  if (r->probe_at != r->now) {
    r->probe_at = r->now;
    r->probe_spins = 0;
  }
  if (++r->probe_spins >= PROBE_SPINS_MAX) {
    mp_fail(&s->log,
         "rank %d called mp_probe %d times at t=%.9g without its clock moving: nothing "
         "new can arrive (compute between probes, or recv); run stopped",
         r->base.rank, PROBE_SPINS_MAX, r->now);
    s->stopped = 1;
    return MP_ESTOPPED;
  }
  return 0;
}

static int sim_wait(mp *self, int src, int tag, mp_status *st) {
  rank *r = (rank *)self;
  int rc;
  msg *m = receive(r->s, r, src, tag, &rc);
  if (!m) return rc;
  if (st) *st = (mp_status){m->src, m->tag, m->len};
  return MP_OK;
}

static double sim_time(const mp *self) { return ((const rank *)self)->now; }

/* mp_abort: the first abort in simulated time gives the run's exit code. */
static void sim_stop(mp *self, int code, const char *why) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (!s->st.aborted) {
    s->st.aborted = 1;
    s->st.abort_code = code;
  }
  mp_fail(&s->log, "%s", why ? why : "aborted");
  s->stopped = 1;
}

/* A call mp.c found a bad argument in: counted as an event, the run's error. */
static int sim_reject(mp *self, int code, const char *why) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  mp_fail_text(&s->log, why, 0);
  return code;
}

/* A layer's call (mp_call_begin/end), traced as a slice when it took time
 * or moved messages. */
static void sim_call(mp *self, const char *name, int begin) {
  rank *r = (rank *)self;
  sim *s = r->s;
  long long msgs = r->st.sent + r->st.received;
  if (begin) {
    r->call_t0 = r->now;
    r->call_msgs = msgs;
  } else if (s->tr && (r->now > r->call_t0 || msgs != r->call_msgs)) {
    trace_span(s->tr, name, r->base.rank, r->proc, r->call_t0, r->now - r->call_t0, -1, -1);
  }
}

const mp_ops sim_ops = {.send = sim_send, .recv = sim_recv, .probe = sim_probe, .compute = sim_compute,
                               .time = sim_time, .wait = sim_wait, .busy = sim_busy, .sleep_for = sim_sleep,
                               .yield = sim_yield,
                               .stop = sim_stop, .call = sim_call, .send_ref = sim_send_ref,
                               .settle = sim_settle, .withdraw = sim_withdraw, .recv_msg = sim_recv_msg,
                               .recv_msg_into = sim_recv_msg_into,
                               .msg_read = sim_msg_read, .msg_gone = sim_msg_gone, .promise = sim_promise,
                               .promise_drop = sim_promise_drop, .transfer = sim_transfer,
                               .notify = sim_notify, .reject = sim_reject, .tag_max = INT_MAX,
                               .sleep_bounded = 0};
