/* cpuload.c -- the machine's runnable threads, sampled from /proc/loadavg. */
#define _GNU_SOURCE 1
#include "mp/cpuload.h"

#include <fcntl.h>
#include <sched.h>
#include <stdlib.h>
#include <unistd.h>

#include "util/wallclock.h"

int cpuload_cpus(void) {
#if defined(__linux__) && defined(CPU_COUNT)
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    int n = CPU_COUNT(&set);
    if (n >= 1) return n;
  }
#endif
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n >= 1 && n < 1 << 20 ? (int)n : 1;
}

void cpuload_init(cpuload *l) {
  atomic_init(&l->due, 0);
  atomic_init(&l->running, -1);
  atomic_init(&l->base, 0);
  atomic_init(&l->broken, 0);
  atomic_init(&l->hogged, 0);
}

int cpuload_parse(const char *s) {
  /* "0.52 0.58 0.59 2/467 12345": skip three fields, then digits '/' digits. */
  for (int f = 0; f < 3; f++) {
    while (*s == ' ') s++;
    if (!*s) return -1;
    while (*s && *s != ' ') s++;
  }
  while (*s == ' ') s++;
  if (*s < '0' || *s > '9') return -1;
  long v = 0;
  while (*s >= '0' && *s <= '9') {
    v = v * 10 + (*s++ - '0');
    if (v > 1 << 24) return -1;
  }
  if (*s != '/' || s[1] < '0' || s[1] > '9') return -1;
  return (int)v;
}

static int sample(void) {
  int fd = open("/proc/loadavg", O_RDONLY);
  if (fd < 0) return -1;
  char buf[128];
  ssize_t n = read(fd, buf, sizeof buf - 1);
  close(fd);
  if (n <= 0) return -1;
  buf[n] = 0;
  return cpuload_parse(buf);
}

int cpuload_running(cpuload *l, int mine, int *others) {
  long long t = (long long)(wallclock() * 1e9), due = atomic_load_explicit(&l->due, memory_order_relaxed);
  if (t >= due && !atomic_load_explicit(&l->broken, memory_order_relaxed) &&
      atomic_compare_exchange_strong(&l->due, &due, t + (long long)(CPULOAD_PERIOD_S * 1e9))) {
    int r = sample();
    if (r < 0) atomic_store(&l->broken, 1);
    atomic_store_explicit(&l->base, mine, memory_order_relaxed);
    atomic_store_explicit(&l->running, r, memory_order_relaxed);
  }
  int r = atomic_load_explicit(&l->running, memory_order_relaxed);
  if (others) {
    int o = r < 0 ? 0 : r - atomic_load_explicit(&l->base, memory_order_relaxed);
    *others = o > 0 ? o : 0;
  }
  return r;
}

void cpuload_yield(cpuload *l) {
  double t0 = wallclock();
  sched_yield();
  double t1 = wallclock();
  if (t1 - t0 >= CPULOAD_HOG_S)
    atomic_store_explicit(&l->hogged, (long long)((t1 + CPULOAD_HOG_HOLD_S) * 1e9), memory_order_relaxed);
}

int cpuload_hogged(cpuload *l) {
  long long until = atomic_load_explicit(&l->hogged, memory_order_relaxed);
  return until > 0 && (long long)(wallclock() * 1e9) < until;
}

