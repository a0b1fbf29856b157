/* randprog.c -- random matching programs, for the simulator's and the
 * threads backend's tests. */
#include "tests/randprog.h"

#include <stdio.h>
#include <string.h>

void randprog_make(randprog *p, uint64_t seed, int nranks) {
  rng r;
  rng_seed(&r, seed);
  memset(p, 0, sizeof *p);
  p->seed = seed;
  p->nranks = nranks;
  p->nmsg = rng_int(&r, 1, RANDPROG_MSGS);
  for (int i = 0; i < p->nmsg; i++) {
    randprog_msg *m = &p->msgs[i];
    m->src = rng_int(&r, 0, nranks - 1);
    m->dst = rng_int(&r, 0, nranks - 1);
    m->tag = rng_int(&r, 0, 4);
    m->len = (size_t)rng_int(&r, 16, RANDPROG_LEN);
  }
  for (int k = 0; k < nranks; k++) p->mode[k] = rng_int(&r, 0, 2);
}

static void wrong(randprog *p, int me, const char *what, int i) {
  if (!p->wrong[me]++) snprintf(p->why[me], sizeof p->why[me], "rank %d: %s (message %d)", me, what, i);
}

/* Payload: the message id (bytes 0-3), the send time (8-15), a pattern. */
static void fill(unsigned char *buf, int i, double sent, size_t len) {
  memset(buf, 0, 16);
  memcpy(buf, &i, sizeof i);
  memcpy(buf + 8, &sent, sizeof sent);
  for (size_t j = 16; j < len; j++) buf[j] = (unsigned char)(i * 31 + (int)j);
}

int randprog_draw(randprog *p, uint64_t seed, rng *r) {
  int nranks = rng_int(r, 2, RANDPROG_RANKS);
  randprog_make(p, seed, nranks);
  return nranks;
}

double randprog_cost(rng *r) { return rng_int(r, 0, 8) * 0.125; }

void randprog_main(mp *self, void *ud) {
  randprog *p = ud;
  int me = mp_rank(self);
  rng r;
  rng_seed(&r, p->seed * 1000 + (uint64_t)me);
  unsigned char buf[RANDPROG_LEN], want[RANDPROG_LEN];
  double last = 0;
  for (int i = 0; i < p->nmsg; i++) {
    const randprog_msg *m = &p->msgs[i];
    if (m->src != me && m->dst != me) continue;
    if (rng_int(&r, 0, 2) == 0) {
      double u = rng_int(&r, 0, 12) * 0.25;
      p->units[me] += u;
      if (mp_compute(self, u) != MP_OK) wrong(p, me, "compute failed", i);
    }
    if (m->src == me) {
      fill(buf, i, mp_time(self), m->len);
      if (mp_send(self, m->dst, m->tag, buf, m->len) != MP_OK) wrong(p, me, "send failed", i);
    }
    if (m->dst == me) {
      int mode = p->mode[me], k;
      mp_status st;
      memset(buf, 0, sizeof buf);
      if (mp_recv(self, mode == 1 ? MP_ANY : m->src, mode == 0 ? m->tag : MP_ANY, buf, sizeof buf, &st) !=
          MP_OK) {
        wrong(p, me, "recv failed", i);
        return;
      }
      double sent;
      memcpy(&k, buf, sizeof k);
      memcpy(&sent, buf + 8, sizeof sent);
      if (k < 0 || k >= p->nmsg) {
        wrong(p, me, "a message id out of range", k);
        continue;
      }
      p->delivered[k]++;   /* k's receiver is me: no other rank writes it */
      const randprog_msg *got = &p->msgs[k];
      if (got->dst != me || st.source != got->src || st.tag != got->tag || st.len != got->len)
        wrong(p, me, "the wrong envelope", k);
      if (mode != 1 && k != i) wrong(p, me, "out of order (FIFO per pair)", k);
      fill(want, k, sent, got->len);
      if (memcmp(want, buf, got->len) != 0) wrong(p, me, "corrupted", k);
      if (mp_time(self) < sent) wrong(p, me, "received before it was sent", k);
    }
    if (mp_time(self) < last) wrong(p, me, "the clock went back", i);
    last = mp_time(self);
  }
}

int randprog_failures(const randprog *p, const char **why) {
  int n = 0;
  if (why) *why = "";
  for (int k = 0; k < p->nranks; k++) {
    if (p->wrong[k] && why && !**why) *why = p->why[k];
    n += p->wrong[k];
  }
  for (int i = 0; i < p->nmsg; i++)
    if (p->delivered[i] != 1) {
      if (why && !**why) *why = "a message not delivered exactly once";
      n++;
    }
  return n;
}
