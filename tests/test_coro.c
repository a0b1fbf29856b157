/* test_coro.c -- coroutines: switching, preserved state, many stacks, the guard page. */
#include <errno.h>
#include <fenv.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "coro.h"

#if defined(__has_include)
#if __has_include(<valgrind/valgrind.h>)
#include <valgrind/valgrind.h>
#define HAVE_VALGRIND 1
#endif
#endif

/* ---- ping-pong between the main context and one coroutine --------------- */

typedef struct {
  coro *main, *self;
  int value;        /* passed back and forth */
  int steps;
} pingpong;

static coro *pp_body(void *ud) {
  pingpong *p = ud;
  for (int i = 0; i < p->steps; i++) {
    p->value = p->value * 2 + 1;
    coro_switch(p->self, p->main);
  }
  p->value = -1;
  return p->main;
}

static void test_pingpong(void) {
  char err[200];
  pingpong p = {coro_main_new(), NULL, 0, 5};
  p.self = coro_new(pp_body, &p, 0, err, sizeof err);
  CHECK(p.self != NULL, "coro_new: %s", err);
  if (!p.self) return;
  int want = 0;
  for (int i = 0; i < 5; i++) {
    coro_switch(p.main, p.self);
    want = want * 2 + 1;
    CHECK(p.value == want, "step %d: value %d, expected %d", i, p.value, want);
    CHECK(!coro_done(p.self), "step %d: finished too early", i);
    p.value = want;
  }
  coro_switch(p.main, p.self);
  CHECK(p.value == -1 && coro_done(p.self), "body did not finish: value %d", p.value);
  coro_free(p.self);
  coro_free(p.main);
}

/* ---- two coroutines switching directly, values live across switches ------ */

typedef struct {
  coro *main, *a, *b;
  int rounds;
  long trail[64];   /* the order in which they ran */
  int n;
} duo;

static volatile int opaque = 3; /* defeats constant folding of the locals below */

static coro *duo_a(void *ud) {
  duo *d = ud;
  /* Many values live across every switch: the compiler keeps them in
   * callee-saved registers, which the switch must preserve. */
  long x0 = opaque, x1 = x0 * 3, x2 = x1 + 7, x3 = x2 * x0, x4 = x3 - 11, x5 = x4 * 5;
  double f0 = opaque * 0.5, f1 = f0 + 1.25, f2 = f1 * 3.0;
  for (int i = 0; i < d->rounds; i++) {
    d->trail[d->n++] = 100 + i;
    coro_switch(d->a, d->b);
    x0 += 1, x1 += 1, x2 += 1, x3 += 1, x4 += 1, x5 += 1;
    f0 += 1.0, f1 += 1.0, f2 += 1.0;
  }
  long r = d->rounds;
  long ok = x0 == 3 + r && x1 == 9 + r && x2 == 16 + r && x3 == 48 + r && x4 == 37 + r &&
            x5 == 185 + r && f0 == 1.5 + (double)r && f1 == 2.75 + (double)r &&
            f2 == 8.25 + (double)r;
  d->trail[d->n++] = ok ? 1 : 0;
  return d->b;
}

static coro *duo_b(void *ud) {
  duo *d = ud;
  for (int i = 0; i < d->rounds; i++) {
    d->trail[d->n++] = 200 + i;
    coro_switch(d->b, d->a);
  }
  d->trail[d->n++] = 2;
  return d->main;
}

static void test_direct(void) {
  char err[200];
  duo d = {.rounds = 10};
  d.main = coro_main_new();
  d.a = coro_new(duo_a, &d, 0, err, sizeof err);
  d.b = coro_new(duo_b, &d, 64 * 1024, err, sizeof err);
  CHECK(d.a && d.b, "coro_new: %s", err);
  if (!d.a || !d.b) return;
  coro_switch(d.main, d.a);
  CHECK(d.n == 2 * d.rounds + 2, "%d steps recorded, expected %d", d.n, 2 * d.rounds + 2);
  for (int i = 0; i < d.rounds; i++) {
    CHECK(d.trail[2 * i] == 100 + i && d.trail[2 * i + 1] == 200 + i,
          "round %d ran %ld then %ld", i, d.trail[2 * i], d.trail[2 * i + 1]);
  }
  CHECK(d.trail[2 * d.rounds] == 1, "callee-saved values were not preserved");
  CHECK(d.trail[2 * d.rounds + 1] == 2, "b did not finish last");
  CHECK(coro_done(d.a) && coro_done(d.b), "both should be done");
  coro_free(d.a);
  coro_free(d.b);
  coro_free(d.main);
}

/* ---- the floating-point rounding mode belongs to each context ------------ */

typedef struct {
  coro *main, *self;
  int seen;
} fpstate;

static coro *fp_body(void *ud) {
  fpstate *f = ud;
  fesetround(FE_UPWARD);
  coro_switch(f->self, f->main);
  f->seen = fegetround();
  fesetround(FE_TONEAREST);
  return f->main;
}

static void test_fpstate(void) {
  char err[200];
  fpstate f = {coro_main_new(), NULL, -1};
  f.self = coro_new(fp_body, &f, 0, err, sizeof err);
  CHECK(f.self != NULL, "coro_new: %s", err);
  if (!f.self) return;
  coro_switch(f.main, f.self);
  CHECK(fegetround() == FE_TONEAREST, "the coroutine's rounding mode leaked into main");
  coro_switch(f.main, f.self);
  CHECK(f.seen == FE_UPWARD, "the coroutine lost its rounding mode (got %d)", f.seen);
  fesetround(FE_TONEAREST);
  coro_free(f.self);
  coro_free(f.main);
}

/* ---- 10,000 coroutines, each suspended once ------------------------------ */

enum { MANY = 10000 };

typedef struct {
  coro *main;
  coro **all;
  long sum;
} crowd;

typedef struct {
  crowd *c;
  int id;
} member;

static coro *member_body(void *ud) {
  member *m = ud;
  volatile char scratch[2048]; /* touch a little stack on each */
  scratch[0] = (char)m->id;
  scratch[sizeof scratch - 1] = (char)(m->id >> 8);
  m->c->sum += m->id;
  coro_switch(m->c->all[m->id], m->c->main);
  m->c->sum += (unsigned char)scratch[0] + 256 * (unsigned char)scratch[sizeof scratch - 1];
  return m->c->main;
}

static void test_many(void) {
  char err[200];
  static member members[MANY];
  crowd c = {coro_main_new(), NULL, 0};
  c.all = calloc(MANY, sizeof *c.all);
  int made = 0;
  for (; made < MANY; made++) {
    members[made] = (member){&c, made};
    c.all[made] = coro_new(member_body, &members[made], 0, err, sizeof err);
    if (!c.all[made]) break;
  }
  CHECK(made == MANY, "made %d coroutines of %d: %s", made, MANY, err);
  for (int i = 0; i < made; i++) coro_switch(c.main, c.all[i]);
  long want = (long)made * (made - 1) / 2;
  CHECK(c.sum == want, "first pass sum %ld, expected %ld", c.sum, want);
  for (int i = made - 1; i >= 0; i--) coro_switch(c.main, c.all[i]);
  long want2 = 0;
  for (int i = 0; i < made; i++) want2 += (i & 0xff) + 256 * ((i >> 8) & 0xff);
  CHECK(c.sum == want + want2, "second pass sum %ld, expected %ld", c.sum, want + want2);
  int done = 0;
  for (int i = 0; i < made; i++) done += coro_done(c.all[i]), coro_free(c.all[i]);
  CHECK(done == made, "%d of %d finished", done, made);
  free(c.all);
  coro_free(c.main);
}

/* ---- the guard page below each stack is not accessible ------------------- */

static void test_guard(void) {
#ifdef HAVE_VALGRIND
  if (RUNNING_ON_VALGRIND) return; /* valgrind (rightly) reports the probe */
#endif
  char err[200];
  coro *co = coro_new(pp_body, NULL, 16 * 1024, err, sizeof err);
  CHECK(co != NULL, "coro_new: %s", err);
  if (!co) return;
  void *lo;
  size_t size;
  coro_stack(co, &lo, &size);
  CHECK(size >= 16 * 1024 && size % 4096 == 0, "stack of %zu bytes", size);
  int fd[2];
  if (pipe(fd) != 0) {
    CHECK(0, "pipe: %s", strerror(errno));
    coro_free(co);
    return;
  }
  /* write() reads the buffer in the kernel: EFAULT instead of a signal. */
  ssize_t below = write(fd[1], (char *)lo - 1, 1);
  int e = errno;
  CHECK(below == -1 && e == EFAULT, "the byte below the stack is readable (write: %zd)", below);
  ssize_t inside = write(fd[1], (char *)lo + size - 1, 1);
  CHECK(inside == 1, "the top byte of the stack is not readable: %s", strerror(errno));
  close(fd[0]);
  close(fd[1]);
  coro_free(co);
}

int main(void) {
  printf("coro backend: %s\n", coro_backend());
  test_pingpong();
  test_direct();
  test_fpstate();
  test_many();
  test_guard();
  return check_done("test_coro");
}
