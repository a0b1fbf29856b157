/* libc.c -- the libc state each rank of an MPI program keeps for itself, and
 * the clocks and sleeps of the simulated machine (libc.h; the loader binds a
 * program's references to libc's names to the functions here).
 *
 * getopt: glibc's own, with the rank's optind, optarg, opterr and optopt.
 * glibc keeps more than those (the place inside a group of options such as
 * -cb, the non-options it has passed over), in one hidden state for the
 * process, which it exposes to no one; so each call starts glibc afresh and
 * replays the rank's earlier calls of this parse silently before making the
 * new one, under a lock (threads call at once).  A parse is cheap to replay
 * (k calls cost k^2/2 glibc calls) and the rank's argv is its own, so every
 * rank parses exactly as a process of its own would, whatever the others do
 * between its calls.  rand and random: glibc's additive generator (TYPE_3, the
 * default) written out, a state per rank, so the sequences are glibc's on
 * any libc.  drand48: POSIX erand48, nrand48 and jrand48 on the rank's own
 * 48 bits, glibc's defaults. */
#define _GNU_SOURCE
#include "mpirun/libc.h"

#include <getopt.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include "mp/mp.h"
#include "mpi/init.h"
#include "util/xmem.h"

/* ==== a rank's libc ======================================================= */

enum { R_DEG = 31, R_SEP = 3 };   /* glibc's TYPE_3: x^31 + x^3 + 1 */

/* An exit handler: atexit's, on_exit's, __cxa_atexit's or a thread-local
 * object's destructor (__cxa_thread_atexit). */
typedef struct {
  int kind;                          /* H_ATEXIT, H_ONEXIT, H_CXA */
  void (*fn)(void);                  /* called as its kind says */
  void *arg, *dso;
} handler;

enum { H_ATEXIT, H_ONEXIT, H_CXA };

typedef struct {
  handler *h;
  int n, cap;
} handlers;

typedef struct {
  int optind, opterr, optopt, opt_used;
  int opt_start, opt_calls, opt_seen;   /* the parse: where it began, calls so far, optind after the last */
  char *optarg;
  int32_t r[R_DEG];                 /* random's state */
  int f, b;                         /* its front and rear positions */
  unsigned short x48[3], old48[3];  /* drand48's */
  char *strtok_at;
  handlers at_exit, tls_dtors;      /* run when the rank ends */
} rank_libc;

static rank_libc *ranks;   /* [n], one per rank of the run */
static int nranks;
static rank_libc outside;  /* calls outside any rank */
static rlibc_exit_fn on_exit_fn;
static rlibc_abort_fn on_abort_fn;

static void seed_random(rank_libc *s, uint32_t seed);

static void init_one(rank_libc *s) {
  memset(s, 0, sizeof *s);
  s->optind = 1;
  s->opterr = 1;
  s->optopt = '?';
  seed_random(s, 1);   /* glibc: as if srandom(1) */
}

void rlibc_setup(int n, rlibc_exit_fn fn, rlibc_abort_fn afn) {
  free(ranks);
  ranks = xmallocarray((size_t)n, sizeof *ranks);
  nranks = n;
  init_one(&outside);
  for (int i = 0; i < n; i++) ranks[i] = outside;
  on_exit_fn = fn;
  on_abort_fn = afn;
}

void rlibc_free(void) {
  for (int i = 0; i < nranks; i++) {
    free(ranks[i].at_exit.h);
    free(ranks[i].tls_dtors.h);
  }
  free(ranks);
  ranks = NULL;
  nranks = 0;
}

static rank_libc *me(void) {
  mp *self = mp_self();
  if (!self || !ranks || mp_rank(self) >= nranks) return &outside;
  return &ranks[mp_rank(self)];
}

/* ==== getopt ============================================================== */

void *rlibc_var(int r, int var) {
  rank_libc *s = r >= 0 && r < nranks ? &ranks[r] : &outside;
  switch (var) {
  case RLIBC_OPTIND: return &s->optind;
  case RLIBC_OPTARG: return &s->optarg;
  case RLIBC_OPTERR: return &s->opterr;
  default: return &s->optopt;
  }
}

/* Which of getopt, getopt_long and getopt_long_only. */
enum { G_SHORT, G_LONG, G_LONG_ONLY };

static int glibc_getopt(int kind, int argc, char *const *argv, const char *shortopts,
                        const struct option *longopts, int *longind) {
  return kind == G_SHORT ? getopt(argc, argv, shortopts)
         : kind == G_LONG ? getopt_long(argc, argv, shortopts, longopts, longind)
                          : getopt_long_only(argc, argv, shortopts, longopts, longind);
}

static pthread_mutex_t getopt_lock = PTHREAD_MUTEX_INITIALIZER;

static int any_getopt(int kind, int argc, char *const *argv, const char *shortopts, const struct option *longopts,
                      int *longind) {
  rank_libc *s = me();
  pthread_mutex_lock(&getopt_lock);
  /* A new parse: the rank's first call, or the program has set optind
   * itself since its last call (0 or 1: from the start, as glibc does). */
  if (!s->opt_used || s->optind != s->opt_seen) {
    s->opt_start = s->optind < 1 ? 1 : s->optind;
    s->opt_calls = 0;
  }
  /* glibc afresh (optind 0, over an argv of the program's name alone: it
   * reads the ordering from shortopts and returns -1 at once), then from
   * the parse's start the rank's calls so far, without messages. */
  char *name[2] = {argc > 0 ? argv[0] : (char *)"", NULL};
  int li;
  optind = 0;
  opterr = 0;
  glibc_getopt(kind, 1, name, shortopts, longopts, &li);
  optind = s->opt_start;
  for (int i = 0; i < s->opt_calls; i++) glibc_getopt(kind, argc, argv, shortopts, longopts, &li);
  opterr = s->opterr;
  optopt = s->optopt;
  int c = glibc_getopt(kind, argc, argv, shortopts, longopts, longind);
  s->optind = s->opt_seen = optind;
  s->optarg = optarg;
  s->optopt = optopt;
  s->opt_used = 1;
  s->opt_calls++;
  pthread_mutex_unlock(&getopt_lock);
  return c;
}

static int r_getopt(int argc, char *const *argv, const char *shortopts) {
  return any_getopt(G_SHORT, argc, argv, shortopts, NULL, NULL);
}

/* glibc's <unistd.h>, in a strict POSIX mode (_POSIX_C_SOURCE without
 * _GNU_SOURCE), binds getopt to the symbol __posix_getopt (which stops at
 * the first operand): a program built so calls this, which tilesim-mpirun
 * exports in glibc's place. */
static int r_posix_getopt(int argc, char *const *argv, const char *shortopts) {
  if (shortopts[0] == '+' || shortopts[0] == '-') return any_getopt(G_SHORT, argc, argv, shortopts, NULL, NULL);
  size_t n = strlen(shortopts);
  char *plus = xmalloc(n + 2);
  plus[0] = '+';
  memcpy(plus + 1, shortopts, n + 1);
  int c = any_getopt(G_SHORT, argc, argv, plus, NULL, NULL);
  free(plus);
  return c;
}

static int r_getopt_long(int argc, char *const *argv, const char *shortopts, const struct option *longopts,
                      int *longind) {
  return any_getopt(G_LONG, argc, argv, shortopts, longopts, longind);
}

static int r_getopt_long_only(int argc, char *const *argv, const char *shortopts, const struct option *longopts,
                           int *longind) {
  return any_getopt(G_LONG_ONLY, argc, argv, shortopts, longopts, longind);
}

/* ==== rand and random: glibc's TYPE_3 generator ==========================
 * srandom(seed): r[0] = seed (1 for 0), r[i] = 16807 r[i-1] mod (2^31 - 1)
 * by Schrage's method; front at 3, rear at 0; 310 outputs discarded.  Each
 * output: r[f] += r[b] (mod 2^32), the result r[f] >> 1, both positions on
 * (glibc stdlib/random_r.c). */

static int32_t next_random(rank_libc *s) {
  uint32_t v = (uint32_t)s->r[s->f] + (uint32_t)s->r[s->b];
  s->r[s->f] = (int32_t)v;
  if (++s->f >= R_DEG) s->f = 0;
  if (++s->b >= R_DEG) s->b = 0;
  return (int32_t)(v >> 1);
}

static void seed_random(rank_libc *s, uint32_t seed) {
  if (seed == 0) seed = 1;
  s->r[0] = (int32_t)seed;
  for (int i = 1; i < R_DEG; i++) {
    int32_t hi = s->r[i - 1] / 127773, lo = s->r[i - 1] % 127773;
    int32_t w = 16807 * lo - 2836 * hi;
    if (w < 0) w += 2147483647;
    s->r[i] = w;
  }
  s->f = R_SEP;
  s->b = 0;
  for (int k = 0; k < 10 * R_DEG; k++) next_random(s);
}

static int r_rand(void) { return (int)next_random(me()); }
static void r_srand(unsigned seed) { seed_random(me(), seed); }
static long r_random(void) { return (long)next_random(me()); }
static void r_srandom(unsigned seed) { seed_random(me(), seed); }

/* ==== drand48 ============================================================= */

static double r_drand48(void) { return erand48(me()->x48); }
static long r_lrand48(void) { return nrand48(me()->x48); }
static long r_mrand48(void) { return jrand48(me()->x48); }

static void r_srand48(long seed) {
  rank_libc *s = me();
  s->x48[0] = 0x330e;
  s->x48[1] = (unsigned short)(seed & 0xffff);
  s->x48[2] = (unsigned short)((seed >> 16) & 0xffff);
}

static unsigned short *r_seed48(unsigned short seed16v[3]) {
  rank_libc *s = me();
  memcpy(s->old48, s->x48, sizeof s->old48);
  memcpy(s->x48, seed16v, sizeof s->x48);
  return s->old48;
}

/* ==== strtok ============================================================== */

static char *r_strtok(char *restrict str, const char *restrict delim) { return strtok_r(str, delim, &me()->strtok_at); }

/* ==== clocks and sleeps: the simulated machine's ========================== */

/* The rank's clock (simulated on the simulator), as the program's call fn
 * reads it (init_clock_read: the wtime cost, a loop that waits for the
 * clock stopped); 0 outside a rank (the host's clock, then). */
static int now(double *t, const char *fn) {
  mp *self = mp_self();
  if (!self) return 0;
  *t = init_clock_read(self, fn);
  return 1;
}

static time_t r_time(time_t *t) {
  double s;
  time_t v = now(&s, "time") ? (time_t)s : time(NULL);
  if (t) *t = v;
  return v;
}

static int r_gettimeofday(struct timeval *restrict tv, void *restrict tz) {
  double s;
  if (!now(&s, "gettimeofday")) return gettimeofday(tv, tz);
  if (tv) *tv = (struct timeval){.tv_sec = (time_t)s, .tv_usec = (suseconds_t)((s - (double)(time_t)s) * 1e6)};
  return 0;
}

static int r_clock_gettime(clockid_t id, struct timespec *tp) {
  double s;
  if (!now(&s, "clock_gettime")) return clock_gettime(id, tp);
  if (tp) *tp = (struct timespec){.tv_sec = (time_t)s, .tv_nsec = (long)((s - (double)(time_t)s) * 1e9)};
  return 0;
}

static clock_t r_clock(void) {
  double s;
  return now(&s, "clock") ? (clock_t)(s * CLOCKS_PER_SEC) : clock();
}

static void nap(double seconds) {
  mp *self = mp_self();
  if (self) mp_sleep(self, seconds);
}

static unsigned r_sleep(unsigned seconds) {
  if (!mp_self()) return sleep(seconds);
  nap(seconds);
  return 0;
}

static int r_usleep(unsigned us) {
  if (!mp_self()) return usleep(us);
  nap((double)us * 1e-6);
  return 0;
}

static int r_nanosleep(const struct timespec *req, struct timespec *rem) {
  if (!mp_self()) return nanosleep(req, rem);
  if (req) nap((double)req->tv_sec + (double)req->tv_nsec * 1e-9);
  if (rem) rem->tv_sec = 0, rem->tv_nsec = 0;
  return 0;
}

/* ==== exit handlers ======================================================= */

static void add(handlers *hs, int kind, void (*fn)(void), void *arg, void *dso) {
  if (hs->n == hs->cap) hs->h = xreallocarray(hs->h, (size_t)(hs->cap = hs->cap ? 2 * hs->cap : 8), sizeof *hs->h);
  hs->h[hs->n++] = (handler){kind, fn, arg, dso};
}

/* The last registered first, each taken off before it runs (so that one
 * which registers another, or calls exit, sees the rest as libc would);
 * only dso's when dso is not NULL (__cxa_finalize). */
static void run(handlers *hs, int status, void *dso) {
  for (;;) {
    int i = hs->n - 1;
    while (i >= 0 && dso && hs->h[i].dso != dso) i--;
    if (i < 0) break;
    handler h = hs->h[i];
    memmove(&hs->h[i], &hs->h[i + 1], (size_t)(hs->n - i - 1) * sizeof *hs->h);
    hs->n--;
    if (h.kind == H_ATEXIT) h.fn();
    else if (h.kind == H_ONEXIT) ((void (*)(int, void *))h.fn)(status, h.arg);
    else ((void (*)(void *))h.fn)(h.arg);
  }
}

void rlibc_run_exit(int r, int status) {
  rank_libc *s = r >= 0 && r < nranks ? &ranks[r] : &outside;
  run(&s->tls_dtors, status, NULL);
  run(&s->at_exit, status, NULL);
}

static int r_atexit(void (*fn)(void)) {
  add(&me()->at_exit, H_ATEXIT, fn, NULL, NULL);
  return 0;
}

static int r_on_exit(void (*fn)(int, void *), void *arg) {
  add(&me()->at_exit, H_ONEXIT, (void (*)(void))fn, arg, NULL);
  return 0;
}

static int r_cxa_atexit(void (*fn)(void *), void *arg, void *dso) {
  add(&me()->at_exit, H_CXA, (void (*)(void))fn, arg, dso);
  return 0;
}

static void r_cxa_finalize(void *dso) { run(&me()->at_exit, 0, dso); }

static int r_cxa_thread_atexit(void (*fn)(void *), void *obj, void *dso) {
  add(&me()->tls_dtors, H_CXA, (void (*)(void))fn, obj, dso);
  return 0;
}

/* ==== ending ============================================================== */

static _Noreturn void end_rank(int status, int run_handlers) {
  mp *self = mp_self();
  if (!self) {
    if (run_handlers) exit(status);
    _exit(status);
  }
  fflush(stdout);
  if (on_exit_fn) on_exit_fn(self, status, run_handlers);   /* the runner's: may stop the run */
  fflush(stdout);
  mp_exit(self);
}

static void r_exit(int status) { end_rank(status, 1); }
static void r__exit(int status) { end_rank(status, 0); }

static void r_abort(void) {
  mp *self = mp_self();
  if (!self) abort();
  char why[80];
  snprintf(why, sizeof why, "rank %d called abort()", mp_rank(self));
  fflush(stdout);
  if (on_abort_fn) on_abort_fn(self);
  mp_abort(self, 134, why);
}

static pid_t r_getpid(void) {
  mp *self = mp_self();
  return self ? (pid_t)(100000 + mp_rank(self)) : getpid();
}

/* ==== the names bound here ================================================ */

#define F(name, fn) {name, (rlibc_fn)(fn), -1}
#define V(name, var) {name, NULL, var}
static const struct {
  const char *name;
  rlibc_fn fn;
  int var;
} bound[] = {
    F("getopt", r_getopt), F("getopt_long", r_getopt_long), F("getopt_long_only", r_getopt_long_only),
    F("__posix_getopt", r_posix_getopt), V("optind", RLIBC_OPTIND), V("optarg", RLIBC_OPTARG),
    V("opterr", RLIBC_OPTERR), V("optopt", RLIBC_OPTOPT),
    F("rand", r_rand), F("srand", r_srand), F("random", r_random), F("srandom", r_srandom), F("drand48", r_drand48),
    F("lrand48", r_lrand48), F("mrand48", r_mrand48), F("srand48", r_srand48), F("seed48", r_seed48),
    F("strtok", r_strtok),
    F("time", r_time), F("gettimeofday", r_gettimeofday), F("clock_gettime", r_clock_gettime), F("clock", r_clock),
    F("sleep", r_sleep), F("usleep", r_usleep), F("nanosleep", r_nanosleep),
    F("atexit", r_atexit), F("on_exit", r_on_exit), F("__cxa_atexit", r_cxa_atexit),
    F("__cxa_finalize", r_cxa_finalize), F("__cxa_thread_atexit", r_cxa_thread_atexit),
    F("__cxa_thread_atexit_impl", r_cxa_thread_atexit),
    F("exit", r_exit), F("_exit", r__exit), F("_Exit", r__exit), F("abort", r_abort), F("getpid", r_getpid),
};
#undef F
#undef V

int rlibc_bind(const char *name, rlibc_fn *fn, int *var) {
  for (size_t i = 0; i < sizeof bound / sizeof *bound; i++)
    if (strcmp(bound[i].name, name) == 0) {
      *fn = bound[i].fn;
      *var = bound[i].var;
      return 1;
    }
  return 0;
}
