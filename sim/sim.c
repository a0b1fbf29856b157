/* sim.c -- the discrete-event simulator: ranks as coroutines, the timing model, errors.
 *
 * Reading order: the profiles (the one place for the machine's costs), the
 * data (messages, mailboxes, channels, ranks), scheduling (who runs next),
 * the mp calls (compute, send, recv, probe), then sim_run's main loop and
 * the deadlock report.  The timing model itself is specified in sim.h.
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
#include "sim.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "coro.h"
#include "evq.h"
#include "errlog.h"
#include "trace.h"
#include "wallclock.h"
#include "xmem.h"

/* ==== the profiles ======================================================== */

/* "tc2000": the BBN TC2000 of Johnson, Livadas & Talele (1993), calibrated
 * so that the paper's experiments (sections 6 and 7) show what it reports
 * (doc/model.md, "Calibration: the tc2000 profile").
 *   c = 50 us per node: a node is two triangle areas and a comparison, about
 *       1,000 cycles of the 20 MHz Motorola 88100 with its square root in
 *       software.
 *   m = 275 us per message, on a bus: the paper's message queues were
 *       simulated in the TC2000's shared memory, so a message is a locked
 *       enqueue and dequeue, one at a time, and later ones wait; 275 us puts
 *       the speedup's flattening and decline near 12 processors (section 6).
 *   per_byte = 2.6e-8 s: the butterfly switch's 38 MB/s.
 *   local = 0: master and slave on one processor exchange for free.
 * The LogGP fields, for --net loggp: L = m, no overhead, gap or per-byte gap. */
static void profile_tc2000(sim_config *cfg) {
  *cfg = (sim_config){0};
  cfg->procs = 1;
  cfg->place = NULL;
  cfg->c = 50e-6;          /* seconds per compute unit (a node) */
  cfg->m = 275e-6;         /* seconds per message */
  cfg->per_byte = 2.6e-8;  /* seconds per byte */
  cfg->local = 0;          /* seconds per message on one processor */
  cfg->net = SIM_NET_BUS;
  cfg->L = 275e-6;         /* LogGP latency */
  cfg->o = 0;              /* LogGP overhead */
  cfg->g = 0;              /* LogGP gap */
  cfg->G = 0;              /* LogGP gap per byte */
  cpu_model_init(&cfg->cpu);  /* no processor overheads, wake-ups or slowdown */
  cfg->stack = 0;
  cfg->warn = stderr;
}

/* "unit": whole seconds, for reading a trace by eye. */
static void profile_unit(sim_config *cfg) {
  profile_tc2000(cfg);
  cfg->c = 1;
  cfg->m = 1;
  cfg->per_byte = 0;
  cfg->L = 1;
}

void sim_config_init(sim_config *cfg) { profile_tc2000(cfg); }

int sim_profile(const char *name, sim_config *cfg) {
  if (strcmp(name, "tc2000") == 0)
    profile_tc2000(cfg);
  else if (strcmp(name, "unit") == 0)
    profile_unit(cfg);
  else
    return -1;
  return 0;
}

static const char *const net_names[] = {"ideal", "bus", "loggp", "topology"};

const char *sim_net_name(sim_net net) {
  return (unsigned)net < sizeof net_names / sizeof *net_names ? net_names[net] : "?";
}

int sim_net_parse(const char *name, sim_net *net) {
  for (unsigned i = 0; i < SIM_NET_TOPOLOGY; i++) {
    if (strcmp(name, net_names[i]) == 0) {
      *net = (sim_net)i;
      return 0;
    }
  }
  return -1;
}

/* ==== data ================================================================ */

enum {
  MSG_INLINE = 64,             /* payloads up to this many bytes live in the message */
  STOPPED_CALLS_MAX = 1000000, /* calls after a stop before a rank is abandoned */
  PROBE_SPINS_MAX = 1000000    /* fruitless probes at one clock before we stop */
};

typedef struct msg msg;
struct msg {
  msg *prev, *next;        /* in the receiver's mailbox, by (arrival, seq) */
  double sent;             /* the sender's clock at mp_send */
  double arrival;          /* when it can be received */
  uint64_t seq;            /* send order, machine-wide; the message id in traces */
  int src, tag;
  size_t len;
  unsigned char *data;     /* inl, or a heap block for longer payloads */
  unsigned char inl[MSG_INLINE];
};

typedef struct {
  int dst;                 /* -1: empty slot */
  double last;             /* the latest arrival sent on src -> dst */
} chan;

/* R_BUSY: computing with a progress function (mp_set_progress), queued at the
 * computing's end or at the next arrival, whichever is first. */
enum { R_READY, R_BLOCKED, R_DONE, R_ABANDONED, R_BUSY };

typedef struct rank rank;
struct rank {
  struct mp base;          /* first: an mp * is a rank * */
  sim *s;
  coro *co;
  int proc;
  int state;               /* R_* */
  double now;              /* the rank's clock */
  /* blocked in recv: */
  int wait_src, wait_tag;  /* what it waits for (MP_ANY = -1) */
  double wake;             /* the time it is queued to wake at, INFINITY if none */
  double since;            /* when it blocked */
  int deadlocked;          /* woken by the deadlock report */
  msg *head, *tail;        /* mailbox: messages sent to it, sent or arrived */
  chan *chans;             /* last arrival per destination, open addressing */
  int nchan, capchan;
  long stopped_calls;      /* mp calls since the run stopped */
  double call_t0;          /* mp_call_begin: when the outermost call began, */
  long long call_msgs;     /* and the messages sent and received by then */
  long probe_spins;        /* fruitless probes in a row at probe_at */
  double probe_at;
  sim_rank_stats st;
};

struct sim {
  sim_config cfg;
  int n;                   /* ranks */
  int *place;
  rank *ranks;
  double *busy;            /* per processor: busy_until */
  double *nic;             /* per processor: LogGP NIC free time */
  double bus_free;         /* SIM_NET_BUS */
  topo *topo;              /* SIM_NET_TOPOLOGY: the interconnect and its links */
  links *links;
  evq *q;                  /* ranks that can act, by (time, seq) */
  uint64_t seq;            /* the next sequence number (events and messages) */
  double gtime;            /* the time of the latest event started: never decreases */
  coro *main;              /* sim_run's own context */
  coro_stacks *stacks;     /* the ranks' stacks, one set */
  const mp_proc *procs;
  int live;                /* ranks neither done nor abandoned */
  int stopped;             /* deadlock or error: every mp call fails at once */
  int cpu;                 /* the processor-side model (cpu.h) is on */
  unsigned char *seen;     /* per processor, for slow_factor */
  int ran;
  msg *pool;               /* free messages */
  FILE *tcsv, *tjson;
  int count_csv, count_json;   /* sim_trace_count */
  void (*tick)(void *, double, long long);   /* sim_progress */
  void *tick_ud;
  unsigned ticks;
  int limited;                 /* sim_trace_limit */
  unsigned long long trace_limit;
  trace *tr;
  errlog errs;             /* the errors quoted in sim_run's message */
  sim_stats st;
};

/* ==== errors and warnings ================================================= */

static char *vformat(const char *fmt, va_list ap) {
  va_list aq;
  va_copy(aq, ap);
  int n = vsnprintf(NULL, 0, fmt, aq);
  va_end(aq);
  XASSERT(n >= 0);
  char *buf = xmalloc((size_t)n + 1);
  vsnprintf(buf, (size_t)n + 1, fmt, ap);
  return buf;
}

#if defined(__GNUC__)
#define PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define PRINTF(a, b)
#endif

static void add_error(sim *s, char *text, int always) {
  s->st.errors++;
  errlog_add(&s->errs, text, always);
  free(text);
}

/* An error of the run: sim_run will return -1 and quote it. */
static PRINTF(2, 3) void fail(sim *s, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  add_error(s, vformat(fmt, ap), 0);
  va_end(ap);
}

static PRINTF(2, 3) void warn(sim *s, const char *fmt, ...) {
  s->st.warnings++;
  if (!s->cfg.warn) return;
  va_list ap;
  va_start(ap, fmt);
  fputs("sim: warning: ", s->cfg.warn);
  vfprintf(s->cfg.warn, fmt, ap);
  fputc('\n', s->cfg.warn);
  va_end(ap);
}

/* ==== messages, mailboxes, channels ======================================= */

static msg *msg_new(sim *s, size_t len) {
  msg *m = s->pool;
  if (m)
    s->pool = m->next;
  else
    m = xmalloc(sizeof *m);
  m->data = len <= MSG_INLINE ? m->inl : xmalloc(len);
  return m;
}

static void msg_free(sim *s, msg *m) {
  if (m->data != m->inl) free(m->data);
  m->next = s->pool;
  s->pool = m;
}

/* Insert m into d's mailbox by (arrival, seq); its seq is the largest yet. */
static void box_insert(rank *d, msg *m) {
  msg *p = d->tail;
  while (p && p->arrival > m->arrival) p = p->prev;
  m->prev = p;
  m->next = p ? p->next : d->head;
  if (m->next)
    m->next->prev = m;
  else
    d->tail = m;
  if (p)
    p->next = m;
  else
    d->head = m;
}

static void box_unlink(rank *r, msg *m) {
  if (m->prev)
    m->prev->next = m->next;
  else
    r->head = m->next;
  if (m->next)
    m->next->prev = m->prev;
  else
    r->tail = m->prev;
}

static inline int matches(const msg *m, int src, int tag) {
  return (src < 0 || m->src == src) && (tag < 0 || m->tag == tag);
}

/* The earliest (arrival, seq) message matching src and tag, or NULL. */
static msg *box_find(const rank *r, int src, int tag) {
  for (msg *m = r->head; m; m = m->next)
    if (matches(m, src, tag)) return m;
  return NULL;
}

static inline unsigned chan_hash(int dst, int cap) {
  return ((unsigned)dst * 2654435761u) & (unsigned)(cap - 1);
}

static void chan_grow(rank *r) {
  int cap = r->capchan ? 2 * r->capchan : 4;
  chan *old = r->chans, *t = xmallocarray((size_t)cap, sizeof *t);
  for (int i = 0; i < cap; i++) t[i].dst = -1;
  for (int i = 0; i < r->capchan; i++) {
    if (old[i].dst < 0) continue;
    unsigned h = chan_hash(old[i].dst, cap);
    while (t[h].dst >= 0) h = (h + 1) & (unsigned)(cap - 1);
    t[h] = old[i];
  }
  free(old);
  r->chans = t;
  r->capchan = cap;
}

/* The latest arrival on the channel r -> dst (-infinity if none yet). */
static double *chan_last(rank *r, int dst) {
  if (2 * (r->nchan + 1) > r->capchan) chan_grow(r);
  unsigned h = chan_hash(dst, r->capchan);
  while (r->chans[h].dst >= 0) {
    if (r->chans[h].dst == dst) return &r->chans[h].last;
    h = (h + 1) & (unsigned)(r->capchan - 1);
  }
  r->chans[h].dst = dst;
  r->chans[h].last = -INFINITY;
  r->nchan++;
  return &r->chans[h].last;
}

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
  fail(s, "rank %d kept calling after the run stopped (%d calls); abandoned it", r->base.rank,
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
    msg *m = r->head;
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
    r->base.progress(&r->base, r->base.progress_ud);
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
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  r->probe_spins = 0;
  if (!(units >= 0) || isinf(units)) {
    fail(s, "rank %d: mp_compute(%g): units must be finite and >= 0", r->base.rank, units);
    return MP_EARG;
  }
  return charge(s, r, units * s->cfg.c, units);
}

static int sim_busy(mp *self, double seconds) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  r->probe_spins = 0;
  if (!(seconds >= 0) || isinf(seconds)) {
    fail(s, "rank %d: mp_busy(%g): seconds must be finite and >= 0", r->base.rank, seconds);
    return MP_EARG;
  }
  return charge(s, r, seconds, 0);
}

static int sim_sleep(mp *self, double seconds) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  r->probe_spins = 0;
  if (!(seconds >= 0) || isinf(seconds)) {
    fail(s, "rank %d: mp_sleep(%g): seconds must be finite and >= 0", r->base.rank, seconds);
    return MP_EARG;
  }
  if (s->tr && seconds > 0) trace_span(s->tr, "sleep", r->base.rank, r->proc, r->now, seconds, -1, -1);
  r->st.slept += seconds;
  double t0 = r->now;
  r->now += seconds;
  if (r->now > t0) moved(s, r);
  return MP_OK;
}

static int sim_send(mp *self, int dst, int tag, const void *buf, size_t len) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  r->probe_spins = 0;
  if (dst < 0 || dst >= s->n) {
    fail(s, "rank %d: mp_send to rank %d, which does not exist (%d ranks)", r->base.rank, dst,
         s->n);
    return MP_ERANK;
  }
  if (tag < 0) {
    fail(s, "rank %d: mp_send to rank %d with tag %d: tags are >= 0", r->base.rank, dst, tag);
    return MP_EARG;
  }
  if (len && !buf) {
    fail(s, "rank %d: mp_send of %zu bytes from a NULL buffer", r->base.rank, len);
    return MP_EARG;
  }
  const sim_config *c = &s->cfg;
  rank *d = &s->ranks[dst];
  double before = r->now, t0 = r->now, o = 0, arrival;
  int remote = d->proc != r->proc;
  if (remote && s->cpu && cpu_send_cost(&c->cpu, len) > 0) {   /* cpu.h: the send's processor time */
    o = cpu_send_cost(&c->cpu, len);
    t0 = overhead(s, r, o);
  }
  if (!remote) {
    arrival = t0 + c->local;
  } else if (c->net == SIM_NET_BUS) {
    double start = r->now > s->bus_free ? r->now : s->bus_free;
    s->bus_free = start + c->m + (double)len * c->per_byte;
    arrival = s->bus_free;
  } else if (c->net == SIM_NET_IDEAL) {
    arrival = r->now + c->m + (double)len * c->per_byte;
  } else if (c->net == SIM_NET_TOPOLOGY) {   /* link.h; s->seq is the message's id */
    arrival = links_send(s->links, r->proc, d->proc, r->now, len, s->tr, r->base.rank, dst, tag, s->seq);
  } else {
    double t1 = overhead(s, r, c->o);
    if (o == 0) t0 = t1;
    o += c->o;
    double *nic = &s->nic[r->proc], inject = r->now > *nic ? r->now : *nic;
    *nic = inject + c->g;
    arrival = inject + (len > 1 ? (double)(len - 1) * c->G : 0) + c->L;
  }
  double *last = chan_last(r, dst);
  if (arrival < *last) arrival = *last; /* non-overtaking */
  *last = arrival;

  msg *m = msg_new(s, len);
  m->sent = t0;
  m->arrival = arrival;
  m->seq = s->seq++;
  m->src = r->base.rank;
  m->tag = tag;
  m->len = len;
  if (len) memcpy(m->data, buf, len);
  box_insert(d, m);

  r->st.sent++;
  r->st.bytes_sent += (long long)len;
  if (tag < SIM_TAGS) r->st.sent_tag[tag]++;
  s->st.messages++;
  s->st.bytes += (long long)len;
  if (s->tr) trace_send(s->tr, r->base.rank, r->proc, t0, o, dst, tag, len, m->seq, arrival);

  /* A receiver blocked on a matching message wakes when the earliest arrives
   * (cpu.h: later if it has gone to sleep; its first waker pays o_wake). */
  if (d->state == R_BLOCKED && matches(m, d->wait_src, d->wait_tag)) {
    double resume = arrival;
    if (s->cpu && remote) {
      resume = cpu_resume(&c->cpu, d->since, arrival);
      if (d->wake == INFINITY && cpu_asleep(&c->cpu, d->since, arrival) && c->cpu.o_wake > 0)
        overhead(s, r, c->cpu.o_wake);
    }
    if (resume < d->wake) {
      d->wake = resume;
      evq_set(s->q, dst, resume, s->seq++);
    }
  } else if (d->state == R_BUSY && arrival < d->wake) {   /* computing: its progress acts at the arrival */
    d->wake = arrival;
    evq_set(s->q, dst, arrival, s->seq++);
  }
  if (r->now > before) moved(s, r);
  return MP_OK;
}

/* Check recv's and probe's source and tag. */
static int check_match_args(sim *s, rank *r, const char *call, int src, int tag) {
  if (src < MP_ANY || src >= s->n) {
    fail(s, "rank %d: %s from rank %d, which does not exist (%d ranks)", r->base.rank, call, src,
         s->n);
    return MP_ERANK;
  }
  if (tag < MP_ANY) {
    fail(s, "rank %d: %s with tag %d: tags are >= 0 or MP_ANY", r->base.rank, call, tag);
    return MP_EARG;
  }
  return MP_OK;
}

/* The message a recv of r from src with tag takes, once it has arrived:
 * r blocks until then.  NULL and *rc = MP_EDEADLOCK or MP_ESTOPPED if the
 * run stopped meanwhile. */
static msg *arrived(sim *s, rank *r, int src, int tag, int *rc) {
  msg *m = box_find(r, src, tag);
  if (!m || m->arrival > r->now) {
    /* Block: queued at the first matching arrival if one is on its way,
     * else not queued until a matching send queues it. */
    double since = r->now;
    r->state = R_BLOCKED;
    r->wait_src = src;
    r->wait_tag = tag;
    r->wake = INFINITY;
    r->since = since;
    if (m) {
      r->wake = s->cpu && s->ranks[m->src].proc != r->proc ? cpu_resume(&s->cfg.cpu, since, m->arrival)
                                                            : m->arrival;
      evq_set(s->q, r->base.rank, r->wake, s->seq++);
    }
    give_way(s, r);
    r->state = R_READY;
    double t = s->stopped ? (s->gtime > since ? s->gtime : since) : r->wake;
    r->now = t;
    r->st.recv_wait += t - since;
    if (s->tr && t > since) trace_span(s->tr, "wait", r->base.rank, r->proc, since, t - since, src, tag);
    if (s->stopped) {
      *rc = r->deadlocked ? MP_EDEADLOCK : MP_ESTOPPED;
      return NULL;
    }
    XASSERT(t == s->gtime);
    m = box_find(r, src, tag);
    XASSERT(m && m->arrival <= r->now);
  }
  return m;
}

static int sim_recv(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  r->probe_spins = 0;
  int rc = check_match_args(s, r, "mp_recv", src, tag);
  if (rc != MP_OK) return rc;
  if (cap && !buf) {
    fail(s, "rank %d: mp_recv into a NULL buffer of %zu bytes", r->base.rank, cap);
    return MP_EARG;
  }
  msg *m = arrived(s, r, src, tag, &rc);
  if (!m) return rc;
  box_unlink(r, m);

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
  size_t n = m->len <= cap ? m->len : cap;
  if (n) memcpy(buf, m->data, n);
  if (st) *st = (mp_status){m->src, m->tag, m->len};
  r->st.received++;
  r->st.bytes_received += (long long)m->len;
  s->st.received++;
  if (s->tr) trace_recv(s->tr, r->base.rank, r->proc, t0, o, m->src, m->tag, m->len, m->seq);
  rc = MP_OK;
  if (m->len > cap) {
    warn(s, "rank %d: mp_recv truncated a %zu-byte message from rank %d (tag %d) to %zu bytes",
         r->base.rank, m->len, m->src, m->tag, cap);
    rc = MP_ETRUNC;
  }
  msg_free(s, m);
  if (r->now > before) moved(s, r);
  return rc;
}

static int sim_probe(mp *self, int src, int tag, mp_status *st) {
  rank *r = (rank *)self;
  sim *s = r->s;
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  int rc = check_match_args(s, r, "mp_probe", src, tag);
  if (rc != MP_OK) return rc;
  msg *m = box_find(r, src, tag);
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
    fail(s,
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
  sim *s = r->s;
  if (s->stopped) return stopped_call(s, r);
  s->st.events++;
  r->probe_spins = 0;
  int rc = check_match_args(s, r, "mp_wait", src, tag);
  if (rc != MP_OK) return rc;
  msg *m = arrived(s, r, src, tag, &rc);
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
  fail(s, "%s", why ? why : "aborted");
  s->stopped = 1;
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

static const mp_ops sim_ops = {sim_send, sim_recv, sim_probe, sim_compute, sim_time,
                               sim_wait, sim_busy,  sim_sleep, sim_stop,  sim_call};

/* ==== the machine ========================================================= */

sim *sim_new(const sim_config *cfg, int nranks, char *err, size_t errlen) {
  if (nranks < 1) {
    snprintf(err, errlen, "sim: %d ranks: need at least 1", nranks);
    return NULL;
  }
  if (cfg->procs < 1) {
    snprintf(err, errlen, "sim: %d processors: need at least 1", cfg->procs);
    return NULL;
  }
  const struct {
    const char *name;
    double v;
  } costs[] = {{"c", cfg->c},          {"m", cfg->m}, {"per_byte", cfg->per_byte},
               {"local", cfg->local},  {"L", cfg->L}, {"o", cfg->o},
               {"g", cfg->g},          {"G", cfg->G}, {"hop_latency", cfg->hop_latency}};
  for (size_t i = 0; i < sizeof costs / sizeof *costs; i++) {
    if (!(costs[i].v >= 0) || isinf(costs[i].v)) {
      snprintf(err, errlen, "sim: cost %s = %g: must be finite and >= 0", costs[i].name,
               costs[i].v);
      return NULL;
    }
  }
  if (cpu_model_check(&cfg->cpu, err, errlen) != 0) return NULL;
  if ((unsigned)cfg->net > SIM_NET_TOPOLOGY ||
      (cfg->net == SIM_NET_TOPOLOGY && cfg->topo.kind == TOPO_NONE)) {
    snprintf(err, errlen, "sim: unknown network model %d", (int)cfg->net);
    return NULL;
  }
  /* A topology: its processors (at least procs), its links. */
  topo *tp = NULL;
  int procs = cfg->procs;
  if (cfg->topo.kind != TOPO_NONE) {
    char terr[200];
    if (!(tp = topo_new(&cfg->topo, cfg->procs, terr, sizeof terr))) {
      snprintf(err, errlen, "sim: %s", terr);
      return NULL;
    }
    procs = topo_nodes(tp);
  }
  if (cfg->place) {
    for (int r = 0; r < nranks; r++) {
      if (cfg->place[r] < 0 || cfg->place[r] >= procs) {
        snprintf(err, errlen, "sim: place[%d] = %d: processors are 0..%d", r, cfg->place[r],
                 procs - 1);
        topo_free(tp);
        return NULL;
      }
    }
  }
  sim *s = xcalloc(1, sizeof *s);
  s->cfg = *cfg;
  s->cfg.procs = procs;
  if (tp) {
    s->cfg.net = SIM_NET_TOPOLOGY;
    s->topo = tp;
    s->links = links_new(tp, cfg->m, cfg->hop_latency, cfg->per_byte, cfg->store_forward);
  }
  s->n = nranks;
  s->place = xmallocarray((size_t)nranks, sizeof *s->place);
  for (int r = 0; r < nranks; r++) s->place[r] = cfg->place ? cfg->place[r] : r % cfg->procs;
  s->cfg.place = s->place;
  s->cpu = cpu_model_on(&cfg->cpu);
  s->seen = xcalloc((size_t)cfg->procs, 1);
  s->ranks = xcalloc((size_t)nranks, sizeof *s->ranks);
  for (int r = 0; r < nranks; r++) {
    rank *k = &s->ranks[r];
    k->base = (struct mp){.ops = &sim_ops, .rank = r, .size = nranks};
    k->s = s;
    k->proc = s->place[r];
    k->st.proc = k->proc;
    k->wake = INFINITY;
  }
  s->busy = xcalloc((size_t)procs, sizeof *s->busy);
  s->nic = xcalloc((size_t)procs, sizeof *s->nic);
  s->q = evq_new(nranks);
  s->st.ranks = nranks;
  s->st.procs = procs;
  return s;
}

links *sim_links(sim *s) { return s->links; }

void sim_trace(sim *s, FILE *csv, FILE *json) {
  s->tcsv = csv;
  s->tjson = json;
}

void sim_trace_count(sim *s, int csv, int json) {
  s->count_csv = csv;
  s->count_json = json;
}

void sim_progress(sim *s, void (*tick)(void *ud, double t, long long events), void *ud) {
  s->tick = tick;
  s->tick_ud = ud;
}

void sim_trace_limit(sim *s, unsigned long long limit) {
  s->limited = 1;
  s->trace_limit = limit;
}

int sim_trace_over(const sim *s) { return trace_over(s->tr); }

void sim_trace_size(const sim *s, unsigned long long *csv, unsigned long long *json) {
  trace_size(s->tr, csv, json);
}

/* Every rank runs this on its own stack. */
static coro *rank_main(void *ud) {
  rank *r = ud;
  sim *s = r->s;
  mp_enter(&r->base, s->procs[r->base.rank].main, s->procs[r->base.rank].ud);
  r->state = R_DONE;
  r->st.done = 1;
  r->st.finish = r->now;
  if (r->now > s->st.makespan) s->st.makespan = r->now;
  if (s->tr) trace_finish(s->tr, r->base.rank, r->proc, r->now);
  s->live--;
  s->st.switches++;
  double t;
  int id = evq_pop(s->q, &t);
  if (id < 0) return s->main;
  XASSERT(t >= s->gtime);
  s->gtime = t;
  return s->ranks[id].co;
}

static const char *peer_name(int v, char *buf, size_t len) {
  if (v < 0) return "any";
  snprintf(buf, len, "%d", v);
  return buf;
}

/* Every live rank waits in recv and nothing is on its way: say who waits for
 * what, and stop the run. */
static void report_deadlock(sim *s) {
  enum { SHOWN = 16 };
  size_t cap = 64 + SHOWN * 64, len = 0;
  char *buf = xmalloc(cap), a[16], b[16], what[160];
  len += (size_t)snprintf(buf, cap, "deadlock at t=%.9g:", s->gtime);
  int blocked = 0;
  for (int i = 0; i < s->n; i++) {
    rank *r = &s->ranks[i];
    if (r->state != R_BLOCKED) continue;
    r->deadlocked = 1;
    if (blocked++ >= SHOWN) continue;
    const char *label = mp_label_text(&r->base, what, sizeof what);
    if (label) {
      if (cap - len < 200) buf = xrealloc(buf, cap *= 2);
      len += (size_t)snprintf(buf + len, cap - len, "%s rank %d waits in %s", blocked > 1 ? ";" : "",
                              i, label);
    } else {
      len += (size_t)snprintf(buf + len, cap - len, "%s rank %d waits in recv(src=%s, tag=%s)",
                              blocked > 1 ? ";" : "", i, peer_name(r->wait_src, a, sizeof a),
                              peer_name(r->wait_tag, b, sizeof b));
    }
  }
  if (blocked > SHOWN)
    snprintf(buf + len, cap - len, "; and %d more ranks", blocked - SHOWN);
  s->st.deadlock = 1;
  s->stopped = 1;
  add_error(s, buf, 1); /* always quoted: it is often the consequence of the others */
}

/* Count and report what was sent and never received; free it. */
static void sweep_unread(sim *s) {
  for (int i = 0; i < s->n; i++) {
    rank *r = &s->ranks[i];
    if (!r->head) continue;
    long long count = 0;
    for (msg *m = r->head; m; m = m->next) count++;
    r->st.unread = count;
    s->st.unread += count;
    warn(s, "rank %d finished with %lld unread message%s (first from rank %d, tag %d)", i, count,
         count == 1 ? "" : "s", r->head->src, r->head->tag);
    while (r->head) {
      msg *m = r->head;
      r->head = m->next;
      msg_free(s, m);
    }
    r->tail = NULL;
  }
}

int sim_run(sim *s, const mp_proc *procs, char *err, size_t errlen) {
  if (s->ran) {
    snprintf(err, errlen, "sim_run: this machine has run already");
    return -1;
  }
  s->ran = 1;
  for (int i = 0; i < s->n; i++) {
    if (!procs[i].main) {
      snprintf(err, errlen, "sim_run: rank %d has no main function", i);
      return -1;
    }
  }
  double w0 = wallclock();
  mp *outer = mp_self();   /* restored whenever a rank gives way to sim_run */
  s->procs = procs;
  s->tr = s->count_csv || s->count_json ? trace_new_count(s->count_csv, s->count_json)
          : s->limited                    ? trace_new_limited(s->tcsv, s->tjson, s->trace_limit)
                                          : trace_new(s->tcsv, s->tjson);
  s->main = coro_main_new();
  char cerr[256];
  int made = 0;
  s->stacks = coro_stacks_new(s->n, s->cfg.stack, cerr, sizeof cerr);
  if (!s->stacks) fail(s, "sim_run: %s", cerr);
  for (; s->stacks && made < s->n; made++) {
    rank *r = &s->ranks[made];
    r->co = coro_new_on(s->stacks, rank_main, r, cerr, sizeof cerr);
    if (!r->co) {
      fail(s, "sim_run: rank %d: %s", made, cerr);
      break;
    }
    coro_stack(r->co, &r->base.stack_lo, &r->base.stack_size);
    r->base.stack_guard = coro_guard(r->co);
  }
  if (made == s->n) {
    if (s->tr) trace_begin(s->tr, s->n, s->place, s->cfg.procs);
    for (int i = 0; i < s->n; i++) s->ranks[i].base.traced = s->tr != NULL;
    for (int i = 0; i < s->n; i++) evq_set(s->q, i, 0.0, s->seq++);
    s->live = s->n;
    for (;;) {
      double t;
      int id = evq_pop(s->q, &t);
      if (id >= 0) {
        XASSERT(t >= s->gtime);
        s->gtime = t;
        s->st.switches++;
        coro_switch(s->main, s->ranks[id].co);
        mp_set_self(outer);
        continue;
      }
      if (s->live == 0) break;
      /* Nothing can act and ranks are alive: all of them wait in recv. */
      if (!s->stopped) report_deadlock(s);
      int woken = 0;
      for (int i = 0; i < s->n; i++) {
        if (s->ranks[i].state != R_BLOCKED) continue;
        evq_set(s->q, i, s->gtime, s->seq++);
        woken++;
      }
      XASSERT(woken > 0);
    }
    sweep_unread(s);
    if (s->tr && trace_end(s->tr, cerr, sizeof cerr) != 0) fail(s, "sim_run: %s", cerr);
  }
  /* Ranks whose stacks share guard pages (coro.h) may have overflowed
   * where only a check sees it: the run fails naming them. */
  for (long i = coro_stacks_overflowed(s->stacks, 0); i >= 0; i = coro_stacks_overflowed(s->stacks, i + 1))
    fail(s, "rank %ld overflowed its stack of %zu KiB (--stack sets it)", i, s->ranks[i].base.stack_size >> 10);
  for (int i = 0; i < made; i++) {
    coro_free(s->ranks[i].co);
    s->ranks[i].co = NULL;
  }
  coro_stacks_free(s->stacks);
  s->stacks = NULL;
  coro_free(s->main);
  s->main = NULL;
  s->st.wall_s = wallclock() - w0;
  return errlog_report(&s->errs, s->st.errors, err, errlen);
}

const sim_rank_stats *sim_rank(const sim *s, int i) {
  XASSERT(i >= 0 && i < s->n);
  return &s->ranks[i].st;
}

const sim_stats *sim_stats_get(const sim *s) { return &s->st; }

void sim_free(sim *s) {
  if (!s) return;
  for (int i = 0; i < s->n; i++) {
    rank *r = &s->ranks[i];
    coro_free(r->co);
    while (r->head) {
      msg *m = r->head;
      r->head = m->next;
      msg_free(s, m);
    }
    free(r->chans);
  }
  while (s->pool) {
    msg *m = s->pool;
    s->pool = m->next;
    free(m);
  }
  coro_stacks_free(s->stacks);
  coro_free(s->main);
  trace_free(s->tr);
  evq_free(s->q);
  free(s->ranks);
  free(s->place);
  free(s->busy);
  free(s->nic);
  links_free(s->links);
  topo_free(s->topo);
  free(s->seen);
  errlog_free(&s->errs);
  free(s);
}
