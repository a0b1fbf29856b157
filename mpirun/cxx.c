/* cxx.c -- the C++ runtime's per-rank parts (cxx.h). */
#define _GNU_SOURCE
#include "mpirun/cxx.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mp/mp.h"
#include "mpi/init.h"
#include "util/xmem.h"

/* ==== clocks and sleeps =================================================== */

/* Nanoseconds: the rank's simulated clock (from the run's start), or the
 * host's clock outside a rank. */
static int64_t now_ns(clockid_t host, const char *fn) {
  mp *self = mp_self();
  if (self) return (int64_t)(init_clock_read(self, fn) * 1e9 + 0.5);
  struct timespec ts;
  clock_gettime(host, &ts);
  return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* time_point<..., nanoseconds> holds one 64-bit count: returned as one. */
static int64_t system_now(void) { return now_ns(CLOCK_REALTIME, "std::chrono::system_clock::now"); }
static int64_t steady_now(void) { return now_ns(CLOCK_MONOTONIC, "std::chrono::steady_clock::now"); }

/* this_thread::__sleep_for(seconds, nanoseconds): two 64-bit counts. */
static void sleep_for(int64_t s, int64_t ns) {
  mp *self = mp_self();
  if (self) {
    mp_sleep(self, (double)s + (double)ns * 1e-9);
    return;
  }
  struct timespec ts = {(time_t)s, (long)ns};
  while (nanosleep(&ts, &ts) != 0) {
  }
}

static const struct {
  const char *name;
  rlibc_fn fn;
} bound[] = {
    {"_ZNSt6chrono3_V212system_clock3nowEv", (rlibc_fn)system_now},
    {"_ZNSt6chrono3_V212steady_clock3nowEv", (rlibc_fn)steady_now},
    {"_ZNSt11this_thread11__sleep_forENSt6chrono8durationIlSt5ratioILl1ELl1EEEENS1_IlS2_ILl1ELl1000000000EEEE",
     (rlibc_fn)sleep_for},
};

int cxx_bind(const char *name, rlibc_fn *fn) {
  if (name[0] != '_') return 0;
  for (size_t i = 0; i < sizeof bound / sizeof *bound; i++)
    if (strcmp(bound[i].name, name) == 0) {
      *fn = bound[i].fn;
      return 1;
    }
  return 0;
}

/* ==== exceptions in flight ================================================ */

/* libstdc++'s __cxa_eh_globals: the caught exceptions' stack, the count of
 * uncaught ones (and on ARM EABI one more pointer). */
typedef struct {
  void *caught;
  unsigned uncaught;
  void *propagating;
} eh_globals;

static eh_globals *saved;    /* [n]: each rank's while it is in a call of the machine */
static eh_globals *live;     /* the thread's own record */
static int nsaved;

enum { EH_BYTES = sizeof(void *) + sizeof(unsigned) };   /* caught, uncaught */

static void enter(mp *self) {
  int r = mp_rank(self);
  if (r >= nsaved) return;
  memcpy(&saved[r], live, EH_BYTES);
  memset(live, 0, EH_BYTES);   /* the next rank starts clean or brings its own */
}

static void leave(mp *self) {
  int r = mp_rank(self);
  if (r < nsaved) memcpy(live, &saved[r], EH_BYTES);
}

static const mp_hooks hooks = {enter, leave};

const mp_hooks *cxx_ranks_begin(int n, void *(*get_globals)(void)) {
  saved = xcalloc((size_t)n, sizeof *saved);
  nsaved = n;
  live = get_globals();
  return &hooks;
}

void cxx_ranks_end(void) {
  free(saved);
  saved = NULL;
  nsaved = 0;
}
