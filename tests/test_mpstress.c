/* test_mpstress.c -- the threads backend (mp/threads.c, threads_calls.c)
 * under stress: many random matching programs of up to 24 ranks (more threads than this
 * machine has processors), messages of every size class of the channels
 * (inline, at the inline limit, by pointer, across 16 KiB chunks), each
 * rank receiving by source and tag, by source, from any source, or from
 * any source by tag, with probes; some runs beside busy threads that take
 * the processors, some with one send left out (a deadlock the run must
 * report, never hang on).
 *
 * Every message is checked against an oracle kept by the test from the
 * program itself, not from the backend: delivered exactly once, intact,
 * with its envelope; in send order per pair (the first message of its
 * pair not yet taken that the receive's tag allows); and, for receives and
 * probes from any source, never before a matching message sent earlier in
 * happens-before order (vector clocks over the program's own sends,
 * receives and probes: a probe that shows a message is an observation of
 * it, so what the rank does afterwards comes after that message's arrival,
 * and mp.h takes the earliest arrival first).  A probe's message is then
 * received by its source and tag, or from any source with the probe's tag
 * where the step's receive is that, and must be the one received.  The
 * statistics (sent, received, unread, per rank) must equal the program's
 * own counts.  A run with a send left out must end in a deadlock whose
 * report names exactly the ranks left waiting, each with what it waits
 * for, none of which has a matching message sent to it (a deadlock
 * declared beside a deliverable message is a lost wake-up or a missed
 * look), and the messages sent but never taken as unread.
 *
 * Senders send some messages by reference (mp_send_ref), settled a few
 * steps later, their buffers then overwritten and freed; receivers take
 * some through mp_recv_msg and mp_msg_read: the same checks hold.
 *
 * Before the random programs, small fixed programs for bugs found here
 * (each fails on the backend before its fix).
 *
 * TILESIM_STRESS=N runs N random programs instead of the default (for long
 * hunts: thousands, under make tsan or beside busy loops);
 * TILESIM_STRESS_FROM=S starts at seed S (a failure names its seed: the
 * same seed gives the same program, not the same interleaving).  Each
 * program has a watchdog: one that hangs is named and the test fails. */
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "util/args.h"
#include "tests/check.h"
#include "util/rng.h"
#include "mp/threads.h"
#include "util/xmem.h"

enum { SR_RANKS = 24, SR_MSGS = 1200, SR_TAGS = 4, SR_BUF = 40000, SR_SHOWN = 16 };
enum { M_EXACT, M_SRC, M_ANY, M_ANYTAG, M_MODES };   /* a rank's receives: (src, tag), (src, any),
                                                         (any, any), (any, tag) */

typedef struct {
  int src, dst, tag, len;
  int seq;   /* its sender's count of sends, this one included (INT_MAX: never sent) */
} smsg;

typedef struct {
  int nr, nm, skip;   /* skip: the message whose send is left out, or -1 */
  smsg m[SR_MSGS];
  int mode[SR_RANKS];
  int probe[SR_RANKS];          /* 1: the rank probes before some receives */
  uint64_t seed;
  /* Written by the ranks: vc[i] and sent[i] by i's sender (vc before the
   * send, read by its receiver after the receive or a probe that showed
   * it; sent after it, read after the run); taken[i] and delivered[i] by
   * i's receiver; the rest by each rank for itself. */
  uint32_t vc[SR_MSGS][SR_RANKS];
  unsigned char sent[SR_MSGS];
  unsigned char taken[SR_MSGS];
  int delivered[SR_MSGS];
  int bad[SR_RANKS];
  char why[SR_RANKS][200];
  int finished[SR_RANKS];       /* went through every step */
  int deadlocked[SR_RANKS];     /* its recv returned MP_EDEADLOCK ... */
  int wait_src[SR_RANKS], wait_tag[SR_RANKS];   /* ... waiting for this */
  long probes[SR_RANKS];        /* probes that showed a message */
} sprog;

static int msg_len(rng *r) {
  int k = rng_int(r, 0, 99);
  if (k < 60) return rng_int(r, 8, 64);              /* the algorithm's boundaries */
  if (k < 75) return rng_int(r, 65, 900);
  if (k < 90) return rng_int(r, 960, 1030);          /* around the inline limit */
  if (k < 97) return rng_int(r, 1031, 17000);        /* by pointer, up to a chunk */
  return rng_int(r, 17000, SR_BUF);                  /* longer than a chunk */
}

/* The program of a seed: ranks, messages in a global order (each rank
 * walks it: it sends the messages it is the source of and receives once
 * for each it is the destination of, so the program cannot deadlock), the
 * ranks' ways of receiving, and the send left out. */
static void make(sprog *p, uint64_t seed, int deadlock) {
  rng r;
  rng_seed(&r, seed);
  memset(p, 0, sizeof *p);
  p->seed = seed;
  p->nr = rng_int(&r, 2, SR_RANKS);
  p->nm = rng_int(&r, 1, SR_MSGS);
  /* A few ranks talk most (as a master and its slaves do), or all alike. */
  int hot = rng_int(&r, 0, 1) ? rng_int(&r, 1, p->nr) : p->nr;
  for (int i = 0; i < p->nm; i++) {
    smsg *m = &p->m[i];
    m->src = rng_int(&r, 0, rng_int(&r, 0, 3) ? hot - 1 : p->nr - 1);
    m->dst = rng_int(&r, 0, rng_int(&r, 0, 3) ? hot - 1 : p->nr - 1);
    m->tag = rng_int(&r, 0, SR_TAGS - 1);
    m->len = msg_len(&r);
  }
  for (int k = 0; k < p->nr; k++) {
    p->mode[k] = rng_int(&r, 0, M_MODES - 1);
    p->probe[k] = rng_int(&r, 0, 2) == 0;
  }
  p->skip = deadlock ? rng_int(&r, 0, p->nm - 1) : -1;
  int sends[SR_RANKS] = {0};
  for (int i = 0; i < p->nm; i++) p->m[i].seq = i == p->skip ? 0x7fffffff : ++sends[p->m[i].src];
}

static void wrong(sprog *p, int me, int i, const char *what) {
  if (!p->bad[me]++)
    snprintf(p->why[me], sizeof p->why[me], "seed %llu rank %d: %s (message %d)", (unsigned long long)p->seed,
             me, what, i);
}

/* Payload: the message id, then a pattern of (id, position). */
static void fill(unsigned char *buf, int id, int len) {
  memcpy(buf, &id, sizeof id);
  for (int j = (int)sizeof id; j < len; j++) buf[j] = (unsigned char)(id * 131 + j * 7);
}

static int intact(const unsigned char *buf, int id, int len) {
  for (int j = (int)sizeof id; j < len; j++)
    if (buf[j] != (unsigned char)(id * 131 + j * 7)) return 0;
  return 1;
}

static void merge(uint32_t *vc, const uint32_t *other, int nr) {
  for (int j = 0; j < nr; j++)
    if (other[j] > vc[j]) vc[j] = other[j];
}

static int matches(const smsg *m, int src, int tag) {
  return (src < 0 || m->src == src) && (tag < 0 || m->tag == tag);
}

/* The first message from src to me not yet taken that tag allows: the one
 * a receive or probe from src with that tag must find (FIFO per pair; the
 * sender sends in the program's order, so if any message of the pair was
 * sent, this one was). */
static int first_pending(const sprog *p, int me, int src, int tag) {
  for (int i = 0; i < p->nm; i++)
    if (p->m[i].dst == me && matches(&p->m[i], src, tag) && !p->taken[i] && i != p->skip) return i;
  return -1;
}

/* A message to me not yet taken, that tag allows, sent before k in
 * happens-before order (k's sender knew of its send): -1 if none.  A
 * receive or probe from any source that finds k while one is waiting
 * takes a later arrival first. */
static int earlier_than(const sprog *p, int me, int k, int tag) {
  for (int j = 0; j < p->nm; j++) {
    const smsg *o = &p->m[j];
    if (j == k || o->dst != me || p->taken[j] || j == p->skip || (tag >= 0 && o->tag != tag)) continue;
    if ((uint32_t)o->seq <= p->vc[k][o->src]) return j;
  }
  return -1;
}

static void causal(sprog *p, int me, int k, int tag, const char *call) {
  int j = earlier_than(p, me, k, tag);
  if (j < 0) return;
  char w[160];
  snprintf(w, sizeof w, "causal order: %s found %d (from %d) before %d (from %d), sent before it", call, k,
           p->m[k].src, j, p->m[j].src);
  wrong(p, me, k, w);
}

/* Sends by reference not yet settled: settled when due (all at the end),
 * their buffers overwritten and freed. */
typedef struct {
  mp_ref *ref;
  unsigned char *buf;
  int due;
} byref;

static void settle(mp *self, byref *br, int *n, int step) {
  for (int k = 0; k < *n;) {
    if (step >= 0 && br[k].due > step) {
      k++;
      continue;
    }
    mp_settle(self, br[k].ref);
    memset(br[k].buf, 0xa5, 8);
    free(br[k].buf);
    br[k] = br[--*n];
  }
}

static void rank_main(mp *self, void *ud) {
  sprog *p = ud;
  int me = mp_rank(self), nr = p->nr, mode = p->mode[me], nbr = 0;
  uint32_t vc[SR_RANKS] = {0};
  unsigned char *buf = xmalloc(SR_BUF);
  byref *br = xmallocarray(SR_MSGS, sizeof *br);
  rng r;
  rng_seed(&r, p->seed * 7919 + (uint64_t)me);
  int i = 0;
  for (; i < p->nm; i++) {
    const smsg *m = &p->m[i];
    settle(self, br, &nbr, i);
    if (m->src == me && i != p->skip) {
      vc[me]++;
      memcpy(p->vc[i], vc, sizeof vc);
      if (rng_int(&r, 0, 2) == 0) {
        unsigned char *b = xmalloc((size_t)m->len);
        fill(b, i, m->len);
        if (mp_send_ref(self, m->dst, m->tag, b, (size_t)m->len, &br[nbr].ref) != MP_OK)
          wrong(p, me, i, "send_ref failed");
        br[nbr].buf = b;
        br[nbr++].due = i + rng_int(&r, 0, 40);
      } else {
        fill(buf, i, m->len);
        if (mp_send(self, m->dst, m->tag, buf, (size_t)m->len) != MP_OK) wrong(p, me, i, "send failed");
      }
      p->sent[i] = 1;
    }
    if (m->dst != me) continue;
    int src = mode == M_EXACT || mode == M_SRC ? m->src : MP_ANY;
    int tag = mode == M_EXACT || mode == M_ANYTAG ? m->tag : MP_ANY;
    int want = -1;   /* the message this step's receive must take, if the probe says */
    mp_status st;
    if (p->probe[me] && rng_int(&r, 0, 1)) {
      /* A probe from anyone, by tag or any: what it shows has arrived. */
      int ptag = rng_int(&r, 0, 1) ? MP_ANY : m->tag;
      int rc = mp_probe(self, MP_ANY, ptag, &st);
      if (rc == 1) {
        int k = st.source >= 0 && st.source < nr && st.tag >= 0 && st.tag < SR_TAGS
                    ? first_pending(p, me, st.source, st.tag)
                    : -1;
        if (k < 0 || (size_t)p->m[k].len != st.len || (ptag >= 0 && st.tag != ptag)) {
          wrong(p, me, k, "a probe showed a message that is not there");
        } else {
          causal(p, me, k, ptag, "a probe");
          merge(vc, p->vc[k], nr);
          p->probes[me]++;
          /* The step's receive from any source with the probe's tag takes
           * it (it arrived before anything that came into view since);
           * else, if the step may take it, take it by source and tag. */
          if (src < 0 && tag == ptag) {
            want = k;
          } else if (matches(&p->m[k], src, tag) && rng_int(&r, 0, 1)) {
            src = st.source;
            tag = st.tag;
            want = k;
          }
        }
      } else if (rc != 0) {
        wrong(p, me, i, "probe failed");
      }
    }
    memset(buf, 0, 8);
    int rc;
    if (rng_int(&r, 0, 2) == 0) {   /* taken, then read */
      mp_msg *h;
      rc = mp_recv_msg(self, src, tag, &h, &st);
      if (rc == MP_OK && mp_msg_read(self, h, buf, SR_BUF) != MP_OK) wrong(p, me, i, "msg_read failed");
    } else {
      rc = mp_recv(self, src, tag, buf, SR_BUF, &st);
    }
    if (rc == MP_EDEADLOCK && p->skip >= 0) {
      p->deadlocked[me] = 1;
      p->wait_src[me] = src;
      p->wait_tag[me] = tag;
      break;
    }
    if (rc != MP_OK) {
      wrong(p, me, i, "recv failed");
      break;
    }
    int k;
    memcpy(&k, buf, sizeof k);
    if (k < 0 || k >= p->nm || p->m[k].dst != me || p->taken[k] || k == p->skip) {
      wrong(p, me, k, "a message that is not mine, or taken twice");
      continue;
    }
    const smsg *g = &p->m[k];
    if (st.source != g->src || st.tag != g->tag || st.len != (size_t)g->len) wrong(p, me, k, "the wrong envelope");
    if (!matches(g, src, tag)) wrong(p, me, k, "a message the receive does not allow");
    if (!intact(buf, k, g->len)) wrong(p, me, k, "corrupted");
    if (first_pending(p, me, g->src, tag) != k) wrong(p, me, k, "out of order (FIFO per pair)");
    if (want >= 0 && k != want) wrong(p, me, k, "not the message the probe showed");
    if (src < 0) causal(p, me, k, tag, "a receive");
    p->taken[k] = 1;
    p->delivered[k]++;
    merge(vc, p->vc[k], nr);
  }
  p->finished[me] = i == p->nm;
  settle(self, br, &nbr, -1);
  free(br);
  free(buf);
}

/* Busy threads beside the run, taking processors from it. */
static atomic_int noise_stop;

static void *noise_main(void *ud) {
  (void)ud;
  volatile unsigned long x = 0;
  while (!atomic_load_explicit(&noise_stop, memory_order_relaxed)) x++;
  return NULL;
}

/* The watchdog: a program that runs this long has hung. */
enum { WATCHDOG_S = 120 };
static volatile sig_atomic_t current_seed;

static void on_alarm(int sig) {
  (void)sig;
  char msg[96] = "test_mpstress: a random program hung (seed ";
  size_t n = strlen(msg);
  char d[24];
  int nd = 0;
  unsigned long s = (unsigned long)current_seed;
  do d[nd++] = (char)('0' + s % 10); while ((s /= 10) && nd < 20);
  while (nd) msg[n++] = d[--nd];
  memcpy(msg + n, ")\n", 2);
  ssize_t w = write(2, msg, n + 2);
  (void)w;
  _exit(1);
}

static sprog prog;

/* The deadlock report the backend must give for the ranks left waiting:
 * each of the first SR_SHOWN as "rank K waits in recv(src=S, tag=T)". */
static void expected_report(const sprog *p, char *out, size_t cap) {
  size_t len = 0;
  int blocked = 0;
  out[0] = 0;
  for (int k = 0; k < p->nr; k++) {
    if (!p->deadlocked[k]) continue;
    if (blocked++ >= SR_SHOWN) continue;
    char s[16] = "any", t[16] = "any";
    if (p->wait_src[k] >= 0) snprintf(s, sizeof s, "%d", p->wait_src[k]);
    if (p->wait_tag[k] >= 0) snprintf(t, sizeof t, "%d", p->wait_tag[k]);
    len += (size_t)snprintf(out + len, cap - len, "%s rank %d waits in recv(src=%s, tag=%s)",
                            blocked > 1 ? ";" : "", k, s, t);
  }
  if (blocked > SR_SHOWN) snprintf(out + len, cap - len, "; and %d more ranks", blocked - SR_SHOWN);
}

/* One program; 1 if it went as expected. */
static int one(uint64_t seed, int deadlock, int noise, long spin_ns) {
  sprog *p = &prog;
  make(p, seed, deadlock);
  pthread_t nt[2];
  int nnoise = 0;
  atomic_store(&noise_stop, 0);
  for (int k = 0; k < noise; k++)
    if (pthread_create(&nt[k], NULL, noise_main, NULL) == 0) nnoise++;
  mpt_config cfg;
  mpt_config_init(&cfg);
  cfg.warn = NULL;
  cfg.spin_ns = spin_ns;
  char err[2048];
  mpt *t = mpt_new(&cfg, p->nr, err, sizeof err);
  XASSERT(t);
  mp_proc procs[SR_RANKS];
  for (int k = 0; k < p->nr; k++) procs[k] = (mp_proc){rank_main, p};
  err[0] = 0;
  int rc = mpt_run(t, procs, err, sizeof err);
  atomic_store(&noise_stop, 1);
  for (int k = 0; k < nnoise; k++) pthread_join(nt[k], NULL);
  const mpt_stats *st = mpt_stats_get(t);
  int bad = 0;
  const char *why = "";
  for (int k = 0; k < p->nr; k++)
    if (p->bad[k]) {
      if (!bad) why = p->why[k];
      bad += p->bad[k];
    }
  /* The program's own counts, per rank and in all. */
  long long sent = 0, taken = 0, twice = 0, stats = 0;
  for (int k = 0; k < p->nr; k++) {
    long long ks = 0, kt = 0, kb = 0, kr = 0, ku = 0;
    for (int i = 0; i < p->nm; i++) {
      const smsg *m = &p->m[i];
      if (m->src == k && p->sent[i]) ks++, kb += m->len;
      if (m->dst == k && p->delivered[i]) kt++, kr += m->len;
      if (m->dst == k && p->sent[i] && !p->delivered[i]) ku++;
    }
    const mpt_rank_stats *rs = mpt_rank(t, k);
    if (rs->sent != ks || rs->bytes_sent != kb || rs->received != kt || rs->bytes_received != kr ||
        rs->unread != ku || !rs->done)
      stats++;
  }
  for (int i = 0; i < p->nm; i++) {
    sent += p->sent[i];
    taken += p->delivered[i];
    twice += p->delivered[i] > p->sent[i];   /* delivered twice, or never sent */
  }
  int ok = !bad && !stats && !twice && st->messages == sent && st->received == taken &&
           st->unread == sent - taken;
  int finished = 0, dead = 0;
  for (int k = 0; k < p->nr; k++) finished += p->finished[k], dead += p->deadlocked[k];
  if (p->skip < 0) {
    if (!ok || rc != 0 || sent != p->nm || taken != p->nm || finished != p->nr || st->deadlock) {
      CHECK(0, "seed %llu (%d ranks, %d messages, noise %d, spin %ld): rc %d (%s), %d wrong (%s), %lld of %d "
               "delivered (%lld twice), %d of %d ranks finished, %lld ranks' statistics differ, %lld sent, %lld received, "
               "%lld unread",
            (unsigned long long)seed, p->nr, p->nm, noise, spin_ns, rc, err, bad, why, taken, p->nm, twice, finished,
            p->nr, stats, st->messages, st->received, st->unread);
      ok = 0;
    }
  } else {
    /* The receiver of the missing message waits for ever: every rank
     * finishes or is left waiting, the run reports a deadlock naming those
     * left waiting, and none of them waits for a message that was sent. */
    int dst = p->m[p->skip].dst, deliverable = -1;
    for (int i = 0; i < p->nm && deliverable < 0; i++) {
      const smsg *m = &p->m[i];
      if (p->sent[i] && !p->delivered[i] && p->deadlocked[m->dst] &&
          matches(m, p->wait_src[m->dst], p->wait_tag[m->dst]))
        deliverable = i;
    }
    char want[SR_SHOWN * 64 + 64];
    expected_report(p, want, sizeof want);
    const char *rep = strstr(err, "deadlock after ");
    rep = rep ? strstr(rep, " s:") : NULL;
    int named = rep && strncmp(rep + 3, want, strlen(want)) == 0 &&
                (rep[3 + strlen(want)] == 0 || rep[3 + strlen(want)] == ';');
    if (!ok || rc != -1 || !st->deadlock || !p->deadlocked[dst] || finished + dead != p->nr || !named ||
        deliverable >= 0) {
      CHECK(0, "seed %llu (%d ranks, %d messages, message %d to rank %d left out, noise %d, spin %ld): rc %d "
               "(%s), expected the report%s, %d wrong (%s), %lld ranks' statistics differ, %d finished and %d "
               "waiting of %d ranks, message %d deliverable, %lld sent, %lld received (%lld taken), %lld unread",
            (unsigned long long)seed, p->nr, p->nm, p->skip, dst, noise, spin_ns, rc, err, want, bad, why, stats,
            finished, dead, p->nr, deliverable, st->messages, st->received, taken, st->unread);
      ok = 0;
    }
  }
  mpt_free(t);
  return ok;
}

/* ==== fixed programs for the bugs found ================================== */

/* A probe is an observation (fixed in threads.c: a probe that shows a
 * message advances the prober's clock to its stamp).  Rank 1 sends many
 * messages to rank 2 (its clock runs ahead), then one to rank 0.  Rank 0
 * probes until that one is there, then sends one to itself, then receives
 * from any source: the message from rank 1 arrived before the one to
 * itself was even sent, so it comes first.  Without the fix, rank 0's
 * clock was still 0 and the message to itself (stamp 1) went first. */
typedef struct {
  int first_src, bad[3];   /* each rank's own (no race between them) */
} probeclock;

static void probeclock_main(mp *self, void *ud) {
  probeclock *c = ud;
  int me = mp_rank(self), x = 0, *bad = &c->bad[me];
  mp_status st;
  if (me == 1) {
    for (int i = 0; i < 50; i++) *bad += mp_send(self, 2, 0, &i, sizeof i) != MP_OK;
    *bad += mp_send(self, 0, 5, &x, sizeof x) != MP_OK;
  } else if (me == 2) {
    for (int i = 0; i < 50; i++) *bad += mp_recv(self, 1, 0, &x, sizeof x, NULL) != MP_OK;
  } else {
    int rc;
    while ((rc = mp_probe(self, 1, MP_ANY, &st)) == 0) sched_yield();
    *bad += rc != 1;
    *bad += mp_send(self, 0, 6, &x, sizeof x) != MP_OK;
    *bad += mp_recv(self, MP_ANY, MP_ANY, &x, sizeof x, &st) != MP_OK;
    c->first_src = st.source;
    *bad += mp_recv(self, MP_ANY, MP_ANY, &x, sizeof x, &st) != MP_OK;
  }
}

static void test_probe_clock(void) {
  for (long spin = 0; spin <= 100000; spin += 100000) {
    probeclock c = {-1, {0, 0, 0}};
    mpt_config cfg;
    mpt_config_init(&cfg);
    cfg.warn = NULL;
    cfg.spin_ns = spin;
    char err[512] = "";
    mpt *t = mpt_new(&cfg, 3, err, sizeof err);
    XASSERT(t);
    mp_proc procs[3] = {{probeclock_main, &c}, {probeclock_main, &c}, {probeclock_main, &c}};
    int rc = mpt_run(t, procs, err, sizeof err);
    int bad = c.bad[0] + c.bad[1] + c.bad[2];
    CHECK(rc == 0 && bad == 0, "probe clock (spin %ld): rc %d (%s), %d bad", spin, rc, err, bad);
    CHECK(c.first_src == 1,
          "probe clock (spin %ld): a receive from any source took the message rank 0 sent itself after a probe "
          "had shown rank 1's (source %d first)",
          spin, c.first_src);
    mpt_free(t);
  }
}

/* A probe from any source pins what it showed (fixed in threads.c: a
 * receive from any source with the probe's tag takes it).  Rank 1 sends
 * many messages to rank 2 (its clock runs ahead), then one to rank 0.
 * Rank 0 probes from any source until it is there, then lets rank 3 go (by
 * a flag outside mp.h: no message, so rank 3's clock stays 0); rank 3 sends
 * rank 0 a message (stamp 1); rank 0 probes rank 3 until it is there, then
 * receives from any source: rank 1's came first (the probe from any source
 * showed it while rank 3's was not even sent), whatever the stamps say.
 * Without the fix the smaller stamp, rank 3's, was taken. */
typedef struct {
  atomic_int go;
  int first_src, bad[4];
} probepin;

static void probepin_main(mp *self, void *ud) {
  probepin *c = ud;
  int me = mp_rank(self), x = 0, rc, *bad = &c->bad[me];
  mp_status st;
  if (me == 1) {
    for (int i = 0; i < 50; i++) *bad += mp_send(self, 2, 0, &i, sizeof i) != MP_OK;
    *bad += mp_send(self, 0, 5, &x, sizeof x) != MP_OK;
  } else if (me == 2) {
    for (int i = 0; i < 50; i++) *bad += mp_recv(self, 1, 0, &x, sizeof x, NULL) != MP_OK;
  } else if (me == 3) {
    while (!atomic_load(&c->go)) sched_yield();
    *bad += mp_send(self, 0, 5, &x, sizeof x) != MP_OK;
  } else {
    while ((rc = mp_probe(self, MP_ANY, 5, &st)) == 0) sched_yield();
    *bad += rc != 1 || st.source != 1;
    atomic_store(&c->go, 1);
    while ((rc = mp_probe(self, 3, 5, &st)) == 0) sched_yield();
    *bad += rc != 1;
    *bad += mp_recv(self, MP_ANY, 5, &x, sizeof x, &st) != MP_OK;
    c->first_src = st.source;
    *bad += mp_recv(self, MP_ANY, 5, &x, sizeof x, &st) != MP_OK;
  }
}

static void test_probe_pin(void) {
  for (long spin = 0; spin <= 100000; spin += 100000) {
    probepin c;
    memset(&c, 0, sizeof c);
    atomic_init(&c.go, 0);
    c.first_src = -1;
    mpt_config cfg;
    mpt_config_init(&cfg);
    cfg.warn = NULL;
    cfg.spin_ns = spin;
    char err[512] = "";
    mpt *t = mpt_new(&cfg, 4, err, sizeof err);
    XASSERT(t);
    mp_proc procs[4];
    for (int k = 0; k < 4; k++) procs[k] = (mp_proc){probepin_main, &c};
    int rc = mpt_run(t, procs, err, sizeof err);
    int bad = c.bad[0] + c.bad[1] + c.bad[2] + c.bad[3];
    CHECK(rc == 0 && bad == 0, "probe pin (spin %ld): rc %d (%s), %d bad", spin, rc, err, bad);
    CHECK(c.first_src == 1,
          "probe pin (spin %ld): after a probe from any source showed rank 1's message, a receive from any "
          "source with its tag took one that came later (source %d)",
          spin, c.first_src);
    mpt_free(t);
  }
}

/* ==== main ================================================================ */

static long env_long(const char *name, long lo, long hi, long dflt) {
  const char *v = getenv(name);
  if (!v) return dflt;
  long x;
  char err[200];
  if (args_long(name, v, lo, hi, &x, err, sizeof err) != 0) {
    fprintf(stderr, "test_mpstress: %s\n", err);
    exit(2);
  }
  return x;
}

int main(void) {
  long n = env_long("TILESIM_STRESS", 1, 100000000, 300);
  long from = env_long("TILESIM_STRESS_FROM", 1, 1000000000, 1);
  signal(SIGALRM, on_alarm);
  alarm(WATCHDOG_S);
  test_probe_clock();
  test_probe_pin();
  long failed = 0, probes = 0, deadlocks = 0, noisy = 0;
  for (long s = from; s < from + n; s++) {
    /* Which programs deadlock, run beside busy threads, and how long a
     * receive spins: from the seed, independently of one another. */
    rng r;
    rng_seed(&r, (uint64_t)s * 0x9e3779b97f4a7c15ull + 1);
    int deadlock = rng_int(&r, 0, 5) == 0, noise = rng_int(&r, 0, 4) == 0 ? rng_int(&r, 1, 2) : 0;
    static const long spins[] = {0, 2000, 50000, 1000000};
    long spin = spins[rng_int(&r, 0, 3)];
    current_seed = (sig_atomic_t)s;
    alarm(WATCHDOG_S);
    failed += !one((uint64_t)s, deadlock, noise, spin);
    for (int k = 0; k < prog.nr; k++) probes += prog.probes[k];
    deadlocks += deadlock;
    noisy += noise > 0;
  }
  alarm(0);
  CHECK(failed == 0, "%ld of %ld random programs failed", failed, n);
  CHECK(probes > 0 && (n < 20 || (deadlocks > 0 && noisy > 0)), "%ld probes showed a message; %ld deadlocks, "
        "%ld beside busy threads", probes, deadlocks, noisy);
  printf("test_mpstress: %ld random programs (seeds %ld..%ld), %ld with a send left out, %ld beside busy "
         "threads, %ld probes that showed a message\n",
         n, from, from + n - 1, deadlocks, noisy, probes);
  return check_done("test_mpstress");
}
