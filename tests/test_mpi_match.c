/* test_mpi_match.c -- the MPI layer's matching engine against a brute-force
 * oracle of MPI's matching rules (MPI 3.1 section 3.5), on the simulator
 * and on threads.
 *
 * Random programs of 2 to 4 ranks: each rank first sends its messages
 * (MPI_Send, MPI_Isend, MPI_Issend; tags 0..2 on MPI_COMM_WORLD and on a
 * duplicate), then works through its receives: MPI_Irecv with an MPI_Wait
 * (or a Test loop) later, MPI_Recv, or MPI_Probe (or an Iprobe loop)
 * followed by a receive by the probe's source and tag; each receive's
 * source and tag are the message's or MPI_ANY_SOURCE / MPI_ANY_TAG.  The
 * ranks compute for random times between steps (on the simulator), so
 * messages arrive in every order.  Each message carries its id.
 *
 * THE ORACLE knows nothing of the engine.  MPI's rules, for one receiver:
 * each (source, communicator) stream of messages arrives in the order it
 * was sent, interleaved with the other streams and with the receiver's
 * steps in any way; an arriving message goes to the first posted receive
 * (in posting order) that it matches, else it waits in arrival order; a
 * posted receive takes the first waiting message it matches, else waits;
 * a probe shows the first waiting message it matches (a message a posted
 * receive matches never waits).  The outcome of a run (the message each
 * receive took, each probe's envelope) is correct iff some such
 * interleaving gives it: a depth-first search over (arrivals per stream,
 * step, posted receives, waiting messages), remembering states seen.  The
 * same search over all outcomes first keeps only programs that cannot
 * deadlock whatever the timing (so a hang is always the engine's).
 * Every message is also checked intact, with its source, tag and count.
 *
 * The engine is stricter than MPI in one way the oracle allows: messages
 * of one source on two communicators stay in send order.
 *
 * TILESIM_MATCH=N runs N programs per backend instead of the default. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/mpi.h"
#include "tests/check.h"
#include "mp/mp.h"
#include "tests/mpiharness.h"
#include "util/rng.h"
#include "util/xmem.h"

enum { MR = 4, MM = 18, MSTEP = 3 * MM, MAXLEN = 40, NTAGS = 3 };

/* A polling loop gives up after this many tries (far more than a message
 * due needs: each failed try moves the simulated clock by the poll cost). */
enum { POLLS = 1000000 };

typedef struct {
  int src, dst, comm, tag, mode, len;   /* mode: 0 MPI_Send, 1 MPI_Isend, 2 MPI_Issend */
} gmsg;

enum { S_POST, S_WAIT, S_PROBE };

typedef struct {
  int op;           /* S_POST: receive k posted; S_WAIT: its wait; S_PROBE: a probe, then
                       receive k (posted with the probe's source and tag) */
  int k;
  int blocking;     /* S_POST of an MPI_Recv (its S_WAIT follows at once) */
  int poll;         /* S_WAIT by a Test loop; S_PROBE by an Iprobe loop */
} gstep;

typedef struct {
  int src, tag, comm;   /* MPI_ANY_SOURCE / MPI_ANY_TAG allowed */
} grecv;

typedef struct {
  int nr, nm;
  gmsg m[MM];
  /* per rank */
  int nrecv[MR], nstep[MR];
  grecv recv[MR][MM];
  gstep step[MR][MSTEP];
  uint64_t seed;
  /* the run's outcome, each rank its own part */
  int got[MR][MM];          /* message id each receive took (-1: none) */
  int probed_src[MR][MSTEP], probed_tag[MR][MSTEP], probed_len[MR][MSTEP];
  int bad[MR];              /* messages damaged or mislabelled */
  char why[MR][160];
} prog;

/* ==== the oracle ========================================================== */

/* Streams: (source, communicator) pairs into the receiver, their messages
 * in send order. */
typedef struct {
  const prog *p;
  int d;                    /* the receiver */
  int ns;
  int slen[2 * MR];
  int smsg[2 * MR][MM];
  const int *want;          /* NULL: explore every outcome (deadlock search) */
  const prog *out;          /* with want: the probes' outcome */
  /* states seen: keys in an arena, an open-addressing table of offsets */
  unsigned char *arena;
  size_t used, cap;
  size_t *tab;
  size_t ntab, nkeys;
} oracle;

typedef struct {
  unsigned char pos[2 * MR];
  int pc;
  int probe;                /* the message the last probe showed, -1 */
  int nposted, nwait;
  unsigned char posted[MM]; /* receive indices */
  unsigned char wait[MM];   /* message indices (waiting, in arrival order) */
  int matched[MM];          /* per receive: the message, -1 */
} ostate;

static int fits(const grecv *r, const gmsg *m) {
  return r->comm == m->comm && (r->src < 0 || r->src == m->src) && (r->tag < 0 || r->tag == m->tag);
}

static size_t key_of(const ostate *s, int ns, int nrecv, unsigned char *k) {
  size_t n = 0;
  for (int i = 0; i < ns; i++) k[n++] = s->pos[i];
  k[n++] = (unsigned char)s->pc;
  k[n++] = (unsigned char)(s->probe + 1);
  k[n++] = (unsigned char)s->nposted;
  for (int i = 0; i < s->nposted; i++) k[n++] = s->posted[i];
  k[n++] = (unsigned char)s->nwait;
  for (int i = 0; i < s->nwait; i++) k[n++] = s->wait[i];
  for (int i = 0; i < nrecv; i++) k[n++] = (unsigned char)(s->matched[i] + 1);
  return n;
}

static uint64_t hash_bytes(const unsigned char *k, size_t n) {
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < n; i++) h = (h ^ k[i]) * 1099511628211ull;
  return h;
}

/* 1 if the state was seen before (and remember it). */
static int seen(oracle *o, const ostate *s) {
  unsigned char k[8 * MM];
  size_t n = key_of(s, o->ns, o->p->nrecv[o->d], k);
  if (2 * (o->nkeys + 1) > o->ntab) {
    size_t nt = o->ntab ? 2 * o->ntab : 1024, *t = xcalloc(nt, sizeof *t);
    for (size_t i = 0; i < o->ntab; i++) {
      if (!o->tab[i]) continue;
      size_t off = o->tab[i] - 1, len = o->arena[off];
      size_t h = hash_bytes(o->arena + off + 1, len) & (nt - 1);
      while (t[h]) h = (h + 1) & (nt - 1);
      t[h] = o->tab[i];
    }
    free(o->tab);
    o->tab = t;
    o->ntab = nt;
  }
  size_t h = hash_bytes(k, n) & (o->ntab - 1);
  while (o->tab[h]) {
    size_t off = o->tab[h] - 1;
    if (o->arena[off] == n && memcmp(o->arena + off + 1, k, n) == 0) return 1;
    h = (h + 1) & (o->ntab - 1);
  }
  if (o->used + n + 1 > o->cap) {
    o->cap = 2 * (o->cap + n + 1);
    o->arena = xrealloc(o->arena, o->cap);
  }
  o->arena[o->used] = (unsigned char)n;
  memcpy(o->arena + o->used + 1, k, n);
  o->tab[h] = o->used + 1;
  o->used += n + 1;
  o->nkeys++;
  return 0;
}

/* The arguments receive k is posted with (a probed receive's: the probe's
 * message's source and tag; it takes that message from the waiting ones at
 * once, since any earlier waiting one it fits would have fitted the probe
 * too, so it is never among the posted ones). */
static grecv recv_args(const oracle *o, const ostate *s, int k) {
  grecv r = o->p->recv[o->d][k];
  const gstep *st = &o->p->step[o->d][s->pc];
  if (st->op == S_POST && s->pc > 0 && o->p->step[o->d][s->pc - 1].op == S_PROBE) {
    const gmsg *m = &o->p->m[s->probe];
    r.src = m->src;
    r.tag = m->tag;
  }
  return r;
}

/* Explore from s: with want, 1 if an interleaving gives the outcome; without,
 * 1 if one deadlocks. */
static int explore(oracle *o, ostate *s) {
  if (seen(o, s)) return 0;
  const prog *p = o->p;
  int d = o->d;
  if (s->pc == p->nstep[d]) return o->want ? 1 : 0;
  int progress = 0;
  /* The next step, if it can be taken. */
  const gstep *st = &p->step[d][s->pc];
  ostate n = *s;
  if (st->op == S_POST) {
    grecv r = recv_args(o, s, st->k);
    int w = -1;
    for (int i = 0; i < s->nwait && w < 0; i++)
      if (fits(&r, &p->m[s->wait[i]])) w = i;
    int ok = 1;
    if (w >= 0) {
      int msg = s->wait[w];
      if (o->want && o->want[st->k] != msg) ok = 0;
      n.matched[st->k] = msg;
      memmove(&n.wait[w], &n.wait[w + 1], (size_t)(n.nwait - w - 1));
      n.nwait--;
    } else {
      n.posted[n.nposted++] = (unsigned char)st->k;
    }
    n.pc++;
    if (ok) {
      progress = 1;
      if (explore(o, &n)) return 1;
    }
  } else if (st->op == S_WAIT) {
    if (s->matched[st->k] >= 0) {
      n.pc++;
      progress = 1;
      if (explore(o, &n)) return 1;
    }
  } else {   /* S_PROBE */
    grecv r = p->recv[d][st->k];
    for (int i = 0; i < s->nwait; i++) {
      const gmsg *m = &p->m[s->wait[i]];
      if (!fits(&r, m)) continue;
      /* The first waiting message it fits; the outcome's probe must have
       * shown it, and the receive after it taken it. */
      int ok = !o->want || (o->want[st->k] == s->wait[i] && o->out->probed_src[d][s->pc] == m->src &&
                            o->out->probed_tag[d][s->pc] == m->tag && o->out->probed_len[d][s->pc] == m->len);
      progress = 1;
      if (ok) {
        n.probe = s->wait[i];
        n.pc++;
        if (explore(o, &n)) return 1;
      }
      break;
    }
  }
  /* The next message of a stream arrives. */
  for (int j = 0; j < o->ns; j++) {
    if (s->pos[j] == o->slen[j]) continue;
    progress = 1;
    int msg = o->smsg[j][s->pos[j]];
    n = *s;
    n.pos[j]++;
    int k = -1;
    for (int i = 0; i < s->nposted && k < 0; i++)
      if (fits(&p->recv[d][s->posted[i]], &p->m[msg])) k = i;
    int ok = 1;
    if (k >= 0) {
      int rk = s->posted[k];
      /* A probed receive was posted with the probe's source and tag: the
       * same message, so its fit above holds with either. */
      if (o->want && o->want[rk] != msg) ok = 0;
      n.matched[rk] = msg;
      memmove(&n.posted[k], &n.posted[k + 1], (size_t)(n.nposted - k - 1));
      n.nposted--;
    } else {
      n.wait[n.nwait++] = (unsigned char)msg;
    }
    if (ok && explore(o, &n)) return 1;
  }
  return !progress && !o->want;   /* stuck: a deadlock */
}

static void oracle_init(oracle *o, const prog *p, int d) {
  memset(o, 0, sizeof *o);
  o->p = p;
  o->d = d;
  for (int src = 0; src < p->nr; src++)
    for (int c = 0; c < 2; c++) {
      int j = o->ns++;
      for (int i = 0; i < p->nm; i++)
        if (p->m[i].dst == d && p->m[i].src == src && p->m[i].comm == c) o->smsg[j][o->slen[j]++] = i;
    }
}

static void oracle_free(oracle *o) {
  free(o->arena);
  free(o->tab);
}

static void start_state(ostate *s) {
  memset(s, 0, sizeof *s);
  s->probe = -1;
  for (int i = 0; i < MM; i++) s->matched[i] = -1;
}

static int can_deadlock(const prog *p, int d) {
  oracle o;
  oracle_init(&o, p, d);
  ostate s;
  start_state(&s);
  int r = explore(&o, &s);
  oracle_free(&o);
  return r;
}

static int outcome_valid(const prog *p, int d) {
  oracle o;
  oracle_init(&o, p, d);
  o.want = p->got[d];
  o.out = p;
  ostate s;
  start_state(&s);
  int r = explore(&o, &s);
  oracle_free(&o);
  return r;
}

/* ==== programs ============================================================ */

/* Uniform in 0 .. n-1. */
static uint64_t rng_below(rng *r, uint64_t n) { return (uint64_t)rng_int(r, 0, (int)n - 1); }

static void make_prog(prog *p, uint64_t seed) {
  rng r;
  rng_seed(&r, seed);
  memset(p, 0, sizeof *p);
  p->seed = seed;
  p->nr = 2 + (int)rng_below(&r, MR - 1);
  p->nm = 4 + (int)rng_below(&r, (uint64_t)(MM - 4));
  for (int i = 0; i < p->nm; i++) {
    gmsg *m = &p->m[i];
    m->src = (int)rng_below(&r, (uint64_t)p->nr);
    m->dst = (int)rng_below(&r, (uint64_t)p->nr);
    m->comm = (int)rng_below(&r, 4) == 0;
    m->tag = (int)rng_below(&r, NTAGS);
    m->mode = (int)rng_below(&r, 3);
    m->len = 1 + (int)rng_below(&r, rng_below(&r, 4) ? 3 : MAXLEN);
  }
  for (int d = 0; d < p->nr; d++) {
    /* A receive per incoming message, wildcarded at random, in random order. */
    int ks[MM], n = 0;
    for (int i = 0; i < p->nm; i++) {
      if (p->m[i].dst != d) continue;
      grecv *g = &p->recv[d][n];
      g->comm = p->m[i].comm;
      g->src = rng_below(&r, 3) == 0 ? MPI_ANY_SOURCE : p->m[i].src;
      g->tag = rng_below(&r, 3) == 0 ? MPI_ANY_TAG : p->m[i].tag;
      ks[n] = n;
      n++;
    }
    p->nrecv[d] = n;
    for (int i = n - 1; i > 0; i--) {
      int j = (int)rng_below(&r, (uint64_t)i + 1), t = ks[i];
      ks[i] = ks[j];
      ks[j] = t;
    }
    int pend[MM], np = 0, ns = 0;
    for (int i = 0; i < n; i++) {
      int k = ks[i], how = (int)rng_below(&r, 5);
      if (how <= 1) {   /* MPI_Irecv, waited for later */
        p->step[d][ns++] = (gstep){S_POST, k, 0, 0};
        pend[np++] = k;
      } else if (how <= 3) {   /* MPI_Recv */
        p->step[d][ns++] = (gstep){S_POST, k, 1, 0};
        p->step[d][ns++] = (gstep){S_WAIT, k, 1, 0};
      } else {   /* a probe, then a receive by its source and tag */
        p->step[d][ns++] = (gstep){S_PROBE, k, 0, (int)rng_below(&r, 2)};
        p->step[d][ns++] = (gstep){S_POST, k, 1, 0};
        p->step[d][ns++] = (gstep){S_WAIT, k, 1, 0};
      }
      while (np && rng_below(&r, 5) < 2) {
        int j = (int)rng_below(&r, (uint64_t)np);
        p->step[d][ns++] = (gstep){S_WAIT, pend[j], 0, (int)rng_below(&r, 3) == 0};
        pend[j] = pend[--np];
      }
    }
    while (np) {
      int j = (int)rng_below(&r, (uint64_t)np);
      p->step[d][ns++] = (gstep){S_WAIT, pend[j], 0, (int)rng_below(&r, 3) == 0};
      pend[j] = pend[--np];
    }
    p->nstep[d] = ns;
  }
}

/* ==== running one ========================================================= */

typedef struct {
  prog *p;
  int sim;
} job;

static void note(prog *p, int d, const char *what, int k) {
  if (!p->bad[d]++) snprintf(p->why[d], sizeof p->why[d], "%s (receive %d)", what, k);
}

static int rank_prog(void *ud) {
  job *j = ud;
  prog *p = j->p;
  int d = mpih_init();
  MPI_Comm comm[2] = {MPI_COMM_WORLD, MPI_COMM_NULL};
  MPI_Comm_dup(MPI_COMM_WORLD, &comm[1]);
  rng r;
  rng_seed(&r, p->seed * 31 + (uint64_t)d);
  mp *self = mp_self();
  /* Sends: payload [id, id, ...] of len ints. */
  MPI_Request sreq[MM];
  int nsreq = 0, data[MM][MAXLEN];
  for (int i = 0; i < p->nm; i++) {
    const gmsg *m = &p->m[i];
    if (m->src != d) continue;
    for (int x = 0; x < m->len; x++) data[i][x] = i;
    if (m->mode == 0)
      MPI_Send(data[i], m->len, MPI_INT, m->dst, m->tag, comm[m->comm]);
    else if (m->mode == 1)
      MPI_Isend(data[i], m->len, MPI_INT, m->dst, m->tag, comm[m->comm], &sreq[nsreq++]);
    else
      MPI_Issend(data[i], m->len, MPI_INT, m->dst, m->tag, comm[m->comm], &sreq[nsreq++]);
    if (j->sim && rng_below(&r, 2)) mp_compute(self, (double)rng_below(&r, 8));
  }
  MPI_Request rreq[MM];
  int buf[MM][MAXLEN + 1];
  int psrc = -1, ptag = -1;
  for (int k = 0; k < MM; k++) p->got[d][k] = -1;
  for (int s = 0; s < p->nstep[d]; s++) {
    const gstep *st = &p->step[d][s];
    const grecv *g = &p->recv[d][st->k];
    MPI_Status status;
    if (st->op == S_PROBE) {
      if (st->poll) {
        int flag = 0;
        for (long tries = 0; !flag && tries < POLLS; tries++)
          MPI_Iprobe(g->src, g->tag, comm[g->comm], &flag, &status);
        if (!flag) {   /* a correct engine cannot starve a safe program */
          note(p, d, "an Iprobe loop that never found its message", st->k);
          break;
        }
      } else {
        MPI_Probe(g->src, g->tag, comm[g->comm], &status);
      }
      int count = -1;
      MPI_Get_count(&status, MPI_INT, &count);
      p->probed_src[d][s] = psrc = status.MPI_SOURCE;
      p->probed_tag[d][s] = ptag = status.MPI_TAG;
      p->probed_len[d][s] = count;
    } else if (st->op == S_POST) {
      int src = g->src, tag = g->tag;
      if (s > 0 && p->step[d][s - 1].op == S_PROBE) src = psrc, tag = ptag;
      memset(buf[st->k], 0xff, sizeof buf[st->k]);
      if (st->blocking) {
        MPI_Recv(buf[st->k], MAXLEN + 1, MPI_INT, src, tag, comm[g->comm], &status);
        s++;   /* its S_WAIT */
      } else {
        MPI_Irecv(buf[st->k], MAXLEN + 1, MPI_INT, src, tag, comm[g->comm], &rreq[st->k]);
      }
    } else {
      if (st->poll) {
        int flag = 0;
        for (long tries = 0; !flag && tries < POLLS; tries++) MPI_Test(&rreq[st->k], &flag, &status);
        if (!flag) {
          note(p, d, "a Test loop whose receive never completed", st->k);
          break;
        }
      } else {
        MPI_Wait(&rreq[st->k], &status);
      }
    }
    if (st->op == S_POST ? st->blocking : st->op == S_WAIT) {
      /* Receive k is done: its message, checked against its own label. */
      int k = st->k, id = buf[k][0], count = -1;
      MPI_Get_count(&status, MPI_INT, &count);
      p->got[d][k] = id;
      if (id < 0 || id >= p->nm) {
        note(p, d, "a message with no valid id", k);
        continue;
      }
      const gmsg *m = &p->m[id];
      int intact = count == m->len;
      for (int x = 0; x < m->len && intact; x++) intact = buf[k][x] == id;
      if (!intact || m->dst != d || status.MPI_SOURCE != m->src || status.MPI_TAG != m->tag ||
          !fits(g, m))
        note(p, d, "a message damaged, mislabelled, or not one the receive fits", k);
    }
    if (j->sim && rng_below(&r, 2)) mp_compute(self, (double)rng_below(&r, 8));
  }
  MPI_Waitall(nsreq, sreq, MPI_STATUSES_IGNORE);
  MPI_Comm_free(&comm[1]);
  MPI_Finalize();
  return 0;
}

/* One program on one backend: 0, or 1 with what went wrong said. */
static int run_one(prog *p, int backend) {
  mpih_config cfg;
  mpih_config_init(&cfg, backend, p->nr);
  cfg.poll_cost = 0.0625;   /* a fraction of the steps' computing (units of 0.125 s) */
  job j = {p, backend == MPIH_SIM};
  mpih_result res;
  memset(p->bad, 0, sizeof p->bad);
  mpih_run_fn(&cfg, rank_prog, &j, &res);
  int fail = 0;
  const char *b = backend == MPIH_SIM ? "sim" : "threads";
  if (res.rc != 0) {
    printf("program %llu (%s): the run failed: %s\n", (unsigned long long)p->seed, b, res.err);
    fail = 1;
  }
  for (int d = 0; d < p->nr && !fail; d++) {
    if (res.exit[d] != 0 || res.end[d] != 1) {
      printf("program %llu (%s): rank %d ended badly (%d, %d)\n", (unsigned long long)p->seed, b, d,
             res.exit[d], res.end[d]);
      fail = 1;
    } else if (p->bad[d]) {
      printf("program %llu (%s): rank %d: %s\n", (unsigned long long)p->seed, b, d, p->why[d]);
      fail = 1;
    } else if (!outcome_valid(p, d)) {
      printf("program %llu (%s): rank %d's matching is one no MPI execution gives:", (unsigned long long)p->seed,
             b, d);
      for (int k = 0; k < p->nrecv[d]; k++) printf(" r%d<-m%d", k, p->got[d][k]);
      printf("\n");
      fail = 1;
    }
  }
  mpih_result_free(&res);
  return fail;
}

/* ==== the oracle's own checks ============================================= */

/* Hand-made receivers whose answers are known: the oracle must accept the
 * right outcome and refuse the wrong ones (else it could pass anything). */
static void oracle_selftest(void) {
  prog p = {0};
  p.nr = 2;
  p.nm = 2;
  /* Rank 0 sends m0 (tag 7) then m1 (tag 5) to rank 1 on one communicator. */
  p.m[0] = (gmsg){0, 1, 0, 7, 0, 1};
  p.m[1] = (gmsg){0, 1, 0, 5, 0, 1};
  /* Rank 1: r0 = (0, 5) posted, then r1 = (any, any): r0 <- m1 always. */
  p.nrecv[1] = 2;
  p.recv[1][0] = (grecv){0, 5, 0};
  p.recv[1][1] = (grecv){MPI_ANY_SOURCE, MPI_ANY_TAG, 0};
  p.nstep[1] = 4;
  p.step[1][0] = (gstep){S_POST, 0, 0, 0};
  p.step[1][1] = (gstep){S_POST, 1, 0, 0};
  p.step[1][2] = (gstep){S_WAIT, 0, 0, 0};
  p.step[1][3] = (gstep){S_WAIT, 1, 0, 0};
  p.got[1][0] = 1, p.got[1][1] = 0;
  CHECK(outcome_valid(&p, 1), "oracle refused the one right outcome");
  p.got[1][0] = 0, p.got[1][1] = 1;
  CHECK(!outcome_valid(&p, 1), "oracle accepted an impossible outcome");
  CHECK(!can_deadlock(&p, 1), "oracle found a deadlock in a safe program");
  /* Two receives (any, 5) then (0, 5) of two tag-5 messages: posting order. */
  p.m[0].tag = 5;
  p.recv[1][0] = (grecv){MPI_ANY_SOURCE, 5, 0};
  p.recv[1][1] = (grecv){0, 5, 0};
  p.got[1][0] = 0, p.got[1][1] = 1;
  CHECK(outcome_valid(&p, 1), "oracle refused posting order");
  p.got[1][0] = 1, p.got[1][1] = 0;
  CHECK(!outcome_valid(&p, 1), "oracle accepted overtaking");
  /* (any, any) first and then (0, 7) with m0 tag 5, m1 tag 7: the first
   * takes m0, and the second m1; but (0, 7) first and then (any, 5) with
   * m0 tag 7 ... a deadlock case: (any, any) then (0, 5), messages tag 5
   * from rank 0 and tag 9 from rank 0, posted while both wait: (any, any)
   * takes the tag-5 one, (0, 5) never matches. */
  p.m[0] = (gmsg){0, 1, 0, 5, 0, 1};
  p.m[1] = (gmsg){0, 1, 0, 9, 0, 1};
  p.recv[1][0] = (grecv){MPI_ANY_SOURCE, MPI_ANY_TAG, 0};
  p.recv[1][1] = (grecv){0, 5, 0};
  CHECK(can_deadlock(&p, 1), "oracle missed a deadlock");
}

int main(void) {
  oracle_selftest();
  long n = getenv("TILESIM_MATCH") ? atol(getenv("TILESIM_MATCH")) : 600;
  for (int backend = 0; backend < 2; backend++) {
    long ran = 0, skipped = 0, failed = 0;
    for (uint64_t seed = 1; ran < (backend == MPIH_SIM ? n : n / 3); seed++) {
      prog *p = xmalloc(sizeof *p);
      make_prog(p, seed);
      int unsafe = 0;
      for (int d = 0; d < p->nr && !unsafe; d++) unsafe = can_deadlock(p, d);
      if (unsafe) {
        skipped++;
      } else {
        ran++;
        failed += run_one(p, backend);
      }
      free(p);
    }
    CHECK(failed == 0, "%s: %ld of %ld random programs matched wrongly", backend ? "threads" : "sim", failed, ran);
    printf("test_mpi_match: %s: %ld programs (%ld that could deadlock skipped)\n", backend ? "threads" : "sim",
           ran, skipped);
  }
  return check_done("test_mpi_match");
}
