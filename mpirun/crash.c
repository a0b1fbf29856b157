/* crash.c -- a crashing rank named on stderr (crash.h).  Only write(2) and
 * _exit(2) in the handler: it may run in the middle of malloc or stdio. */
#define _GNU_SOURCE
#include "mpirun/crash.h"

#include <signal.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

#include "mp/mp.h"

static const char *name = "tilesim-mpirun";
static char altstack[1 << 16];

/* A small append-only buffer for the handler. */
typedef struct {
  char b[512];
  size_t n;
} line;

static void put(line *l, const char *s) {
  while (*s && l->n < sizeof l->b - 1) l->b[l->n++] = *s++;
}

static void put_num(line *l, unsigned long long v) {
  char d[24];
  int k = 0;
  do d[k++] = (char)('0' + v % 10); while ((v /= 10) > 0);
  while (k > 0 && l->n < sizeof l->b - 1) l->b[l->n++] = d[--k];
}

static const char *sig_name(int sig, const char **what) {
  switch (sig) {
  case SIGSEGV: *what = "segmentation fault"; return "SIGSEGV";
  case SIGBUS: *what = "bus error"; return "SIGBUS";
  case SIGFPE: *what = "arithmetic exception"; return "SIGFPE";
  case SIGILL: *what = "illegal instruction"; return "SIGILL";
  case SIGABRT: *what = "abort"; return "SIGABRT";
  default: *what = "signal"; return "a signal";
  }
}

static void on_crash(int sig, siginfo_t *si, void *uc) {
  (void)uc;
  const char *what, *sname = sig_name(sig, &what);
  mp *self = mp_self();
  line l = {{0}, 0};
  put(&l, name);
  put(&l, ": ");
  if (self) {
    put(&l, "rank ");
    put_num(&l, (unsigned long long)mp_rank(self));
    put(&l, " crashed: ");
  } else {
    put(&l, "crashed outside any rank: ");
  }
  put(&l, sname);
  put(&l, " (");
  void *slo = NULL, *sguard = NULL;   /* its stack, and its group's guard page (coro.h) */
  size_t ssize = 0;
  if (self) mp_stack(self, &slo, &ssize, &sguard);
  uintptr_t a = (uintptr_t)si->si_addr, lo = (uintptr_t)slo, guard = (uintptr_t)sguard;
  if ((sig == SIGSEGV || sig == SIGBUS) && lo && a < lo && (a + (1u << 20) >= lo || (guard && a >= guard))) {
    put(&l, "a stack overflow: its stack is ");
    put_num(&l, ssize >> 10);
    put(&l, " KiB; --stack sets it");
  } else {
    put(&l, what);
  }
  put(&l, ")\n");
  ssize_t w = write(2, l.b, l.n);
  (void)w;
  _exit(128 + sig);
}

void crash_install(const char *prog) {
  if (prog) name = prog;
  stack_t ss;
  memset(&ss, 0, sizeof ss);
  ss.ss_sp = altstack;
  ss.ss_size = sizeof altstack;
  sigaltstack(&ss, NULL);
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_sigaction = on_crash;
  sa.sa_flags = SA_SIGINFO | SA_ONSTACK;
  sigemptyset(&sa.sa_mask);
  static const int sigs[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
  for (size_t i = 0; i < sizeof sigs / sizeof *sigs; i++) sigaction(sigs[i], &sa, NULL);
}
