/* randprog.h -- random matching send/receive programs for any mp.h backend:
 * a global order of messages; each rank walks it, doing its sends and its
 * receives (deadlock-free by construction, since sends never block), and
 * checks every message: delivered once, to the right rank, intact, in FIFO
 * order per pair, never before it was sent, clocks never going back. */
#ifndef RANDPROG_H
#define RANDPROG_H

#include <stddef.h>
#include <stdint.h>

#include "mp/mp.h"
#include "util/rng.h"

enum { RANDPROG_MSGS = 300, RANDPROG_RANKS = 12, RANDPROG_LEN = 120 };

typedef struct {
  int src, dst, tag;
  size_t len;
} randprog_msg;

/* Each field a rank writes is its own (per-rank, or per message written only
 * by its receiver), so the ranks may be threads. */
typedef struct {
  int nmsg, nranks;
  randprog_msg msgs[RANDPROG_MSGS];   /* the global order */
  int mode[RANDPROG_RANKS];           /* 0: recv(src, tag), 1: (any, any), 2: (src, any) */
  uint64_t seed;                      /* for the ranks' compute draws */
  int delivered[RANDPROG_MSGS];       /* times each message was received */
  int wrong[RANDPROG_RANKS];          /* content, envelope, order or clock errors */
  char why[RANDPROG_RANKS][160];      /* each rank's first error */
  double units[RANDPROG_RANKS];       /* units each rank charged with mp_compute */
} randprog;

/* A random program for nranks ranks (2 .. RANDPROG_RANKS); every draw is its
 * own statement, so every compiler makes the same program from the seed. */
void randprog_make(randprog *p, uint64_t seed, int nranks);

/* randprog_make for a number of ranks drawn from r (2 .. RANDPROG_RANKS):
 * that number. */
int randprog_draw(randprog *p, uint64_t seed, rng *r);

/* A cost drawn from r: a multiple of 1/8 from 0 to 1 (exact in binary). */
double randprog_cost(rng *r);

/* The ranks' main (ud: the randprog).  Each rank now and then charges a
 * random compute (0 .. 3 units in quarters). */
void randprog_main(mp *self, void *ud);

/* Errors seen by the ranks plus messages not delivered exactly once; the
 * first error's text in *why (may be NULL). */
int randprog_failures(const randprog *p, const char **why);

#endif
