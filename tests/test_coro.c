/* test_coro.c -- coroutines: switching, preserved state, many stacks, the guard page,
 * sets of stacks that share guard pages and the checks that stand in for them. */
#define _DEFAULT_SOURCE 1 /* sigaltstack, SA_ONSTACK */

#include <errno.h>
#include <fenv.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <signal.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/check.h"
#include "sim/coro.h"

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

/* ---- a set larger than CORO_GUARDED: guard pages shared, checks --------- */

enum { BIG = CORO_GUARDED + 40, SMALL = 16 * 1024, FRAME = 1000 };

/* About FRAME bytes of stack a level, every byte written with fill. */
static long dive(int depth, unsigned char fill) {
  volatile unsigned char buf[FRAME];
  for (size_t i = 0; i < sizeof buf; i++) buf[i] = fill;
  long r = depth > 0 ? dive(depth - 1, fill) : 0;
  return r + buf[(unsigned)depth % sizeof buf];
}

/* bytes of stack in one frame, every byte written (a frame's own gaps,
 * redzones and saved registers, cannot skip what lies below). */
static long flood(size_t bytes) {
  volatile unsigned char buf[bytes];
  for (size_t i = 0; i < bytes; i++) buf[i] = 0xcd;
  return buf[bytes / 2];
}

/* Deeper and deeper until something stops it (the test on `forever`, never
 * false, keeps the compiler from calling it infinite). */
static volatile int forever = 1;
static long runaway(long depth) {
  volatile unsigned char buf[FRAME];
  buf[0] = (unsigned char)depth;
  return forever ? runaway(depth + 1) + buf[0] : 0;
}

typedef struct {
  coro *main, *self;
  int depth;        /* dive this deep (0: not at all; -1: run away; -2:
                       flood 100 KiB in one frame) */
  int finish;       /* then return (1) or switch to main and stay (0) */
  long ran;
} diver;

static coro *diver_body(void *ud) {
  diver *d = ud;
  d->ran++;
  if (d->depth > 0) d->ran += dive(d->depth, 0xab) > 0;
  if (d->depth == -1) d->ran += runaway(0);
  if (d->depth == -2) d->ran += flood(100 * 1024) > 0;
  if (!d->finish) coro_switch(d->self, d->main);
  return d->main;
}

/* Every stack made, the shared guard pages where coro.h says, and none of
 * BIG shallow coroutines found to have overflowed. */
static void test_set(void) {
  char err[200];
  coro_stacks *set = coro_stacks_new(BIG, SMALL, err, sizeof err);
  CHECK(set != NULL, "coro_stacks_new(%d): %s", BIG, err);
  if (!set) return;
  static diver d[BIG];
  coro *main = coro_main_new();
  int made = 0;
  for (; made < BIG; made++) {
    d[made] = (diver){main, NULL, 0, 1, 0};
    d[made].self = coro_new_on(set, diver_body, &d[made], err, sizeof err);
    if (!d[made].self) break;
  }
  CHECK(made == BIG, "made %d coroutines of %d: %s", made, BIG, err);
  CHECK(coro_new_on(set, diver_body, &d[0], err, sizeof err) == NULL && strstr(err, "taken"),
        "a coroutine more than the set holds: %s", err);
  long group = (BIG + CORO_GUARDED - 1) / CORO_GUARDED;
  long ran = 0, overflowed = 0, shared = 0, own = 0;
  for (int i = 0; i < made; i++) {
    coro_switch(main, d[i].self);
    ran += d[i].ran;
    overflowed += coro_overflowed(d[i].self);
    void *lo;
    size_t size;
    coro_stack(d[i].self, &lo, &size);
    unsigned char *g = coro_guard(d[i].self);
    /* Stack i of its group lies i slots of stack and 64 KiB soft zone above
     * the group's guard page. */
    size_t above = (size_t)((unsigned char *)lo - g);
    shared += i % group == 0 ? above == 4096 + 64 * 1024 : above > SMALL;
    if (i % group == 1 && g != coro_guard(d[i - 1].self)) own++;
  }
  CHECK(own == 0, "%ld stacks of a group have a guard page of their own", own);
  CHECK(ran == made && overflowed == 0, "%ld ran, %ld said to have overflowed", ran, overflowed);
  CHECK(coro_stacks_overflowed(set, 0) == -1, "the set is said to have overflowed");
  CHECK(shared == made, "%ld of %d stacks where the layout says", shared, made);
  int fd[2];
  if (pipe(fd) == 0) {
    unsigned char *g = coro_guard(d[1].self);
    ssize_t w = write(fd[1], g, 1);
    CHECK(w == -1 && errno == EFAULT, "the shared guard page is readable (write: %zd)", w);
    close(fd[0]);
    close(fd[1]);
  }
  for (int i = 0; i < made; i++) coro_free(d[i].self);
  coro_stacks_free(set);
  coro_free(main);
}

/* A coroutine (the second of a group) that overflows into its soft zone
 * and stays suspended: coro_overflowed says so, for it alone, and so does
 * coro_stacks_overflowed for the set. */
static void test_soft(void) {
  char err[200];
  coro_stacks *set = coro_stacks_new(BIG, SMALL, err, sizeof err);
  CHECK(set != NULL, "coro_stacks_new: %s", err);
  if (!set) return;
  coro *main = coro_main_new();
  diver a = {main, NULL, 0, 0, 0}, b = {main, NULL, 24, 0, 0}, c = {main, NULL, 0, 0, 0};
  a.self = coro_new_on(set, diver_body, &a, err, sizeof err);
  b.self = coro_new_on(set, diver_body, &b, err, sizeof err);
  c.self = coro_new_on(set, diver_body, &c, err, sizeof err);
  CHECK(a.self && b.self && c.self, "coro_new_on: %s", err);
  if (a.self && b.self && c.self) {
    coro_switch(main, a.self);
    CHECK(!coro_overflowed(b.self), "b has not run yet and overflowed");
    coro_switch(main, b.self);
    coro_switch(main, c.self);
    CHECK(b.ran == 2, "b dove and came back: %ld", b.ran);
    CHECK(coro_overflowed(b.self), "24 KiB on a 16 KiB stack was not found");
    CHECK(!coro_overflowed(a.self) && !coro_overflowed(c.self), "a neighbour is said to have overflowed");
    long first = coro_stacks_overflowed(set, 0), next = coro_stacks_overflowed(set, 2);
    CHECK(first == 1 && coro_stacks_overflowed(set, 1) == 1 && next == -1,
          "the set's overflows from 0: %ld, then from 2: %ld (want 1, then none)", first, next);
  }
  coro_stacks_free(set);
  coro_free(main);
}

/* In a child: the second coroutine of a group (BIG makes groups of two)
 * dives `depth` levels (-1: runs away), finishing or not; it must die of
 * SIGSEGV on its group's guard page (the fault or the check's).  1 if it
 * did. */
static volatile uintptr_t want_fault;
static void on_segv(int sig, siginfo_t *si, void *uc) {
  (void)sig, (void)uc;
  _exit((uintptr_t)si->si_addr - want_fault < 4096 ? 42 : 43);
}

static int dies_on_guard(int depth, int finish) {
  pid_t pid = fork();
  if (pid < 0) return 0;
  if (pid == 0) {
    static char alt[1 << 16];
    stack_t ss = {.ss_sp = alt, .ss_size = sizeof alt};
    sigaltstack(&ss, NULL);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_sigaction = on_segv;
    sa.sa_flags = SA_SIGINFO | SA_ONSTACK;
    sigaction(SIGSEGV, &sa, NULL);
    sigaction(SIGBUS, &sa, NULL);
    char err[200];
    coro_stacks *set = coro_stacks_new(BIG, SMALL, err, sizeof err);
    if (!set) _exit(2);
    coro *main = coro_main_new();
    diver d[3];
    for (int i = 0; i < 3; i++) {
      d[i] = (diver){main, NULL, i == 1 ? depth : 0, finish, 0};
      d[i].self = coro_new_on(set, diver_body, &d[i], err, sizeof err);
      if (!d[i].self) _exit(3);
    }
    want_fault = (uintptr_t)coro_guard(d[1].self);
    for (int i = 0; i < 3; i++) coro_switch(main, d[i].self);
    _exit(0);   /* it did not die */
  }
  int st;
  if (waitpid(pid, &st, 0) != pid) return 0;
  if (!WIFEXITED(st) || WEXITSTATUS(st) != 42)
    fprintf(stderr, "test_coro: child %s %d\n", WIFEXITED(st) ? "exited" : "killed by", WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st));
  return WIFEXITED(st) && WEXITSTATUS(st) == 42;
}

static void test_checks(void) {
#ifdef HAVE_VALGRIND
  if (RUNNING_ON_VALGRIND) return; /* valgrind (rightly) reports the writes */
#endif
  /* 100 KiB from near the top of a 16 KiB stack: through the soft zone
   * (64 KiB and a page) into the stack below, its canary overwritten, but
   * not as far as the guard page below that stack's soft zone (about 148
   * KiB): the switch away faults, finishing or not. */
  CHECK(dies_on_guard(-2, 0), "an overflow through the canary, then a switch: no fault on the guard");
  CHECK(dies_on_guard(-2, 1), "an overflow through the canary, then the end: no fault on the guard");
  /* Running away: down to the group's guard page. */
  CHECK(dies_on_guard(-1, 0), "a runaway recursion did not fault on the group's guard page");
}

int main(void) {
  printf("coro backend: %s\n", coro_backend());
  test_pingpong();
  test_direct();
  test_fpstate();
  test_many();
  test_guard();
  test_set();
  test_soft();
  test_checks();
  return check_done("test_coro");
}
