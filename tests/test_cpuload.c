/* test_cpuload.c -- mp/cpuload.h: the /proc/loadavg parser against
 * hand-made lines, the processor count, the sample's bookkeeping (others =
 * running - mine at the sample), and the timed yield's hog flag. */
#include <stdio.h>

#include "tests/check.h"
#include "mp/cpuload.h"
#include "util/wallclock.h"

static void parse(void) {
  static const struct {
    const char *line;
    int want;
  } cases[] = {
      {"0.52 0.58 0.59 2/467 12345\n", 2},
      {"12.00 8.50 3.25 17/1024 99", 17},
      {"0.00 0.00 0.00 0/1 1", 0},
      {"  1.0  2.0  3.0   5/100 7", 5},
      {"0.52 0.58 0.59 2467 12345", -1},   /* no slash */
      {"0.52 0.58 0.59 /467 12345", -1},   /* no running count */
      {"0.52 0.58 0.59 2/ 12345", -1},     /* no thread count */
      {"0.52 0.58", -1},                   /* too short */
      {"", -1},
      {"0.52 0.58 0.59 99999999999/4 1", -1},   /* absurd */
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    int got = cpuload_parse(cases[i].line);
    CHECK(got == cases[i].want, "cpuload_parse(\"%s\") = %d, want %d", cases[i].line, got, cases[i].want);
  }
}

static void sample(void) {
  CHECK(cpuload_cpus() >= 1, "cpuload_cpus() = %d", cpuload_cpus());
  cpuload l;
  cpuload_init(&l);
  int others = -7;
  int r = cpuload_running(&l, 1, &others);
  /* Where /proc/loadavg exists this thread itself is running: >= 1. */
  FILE *f = fopen("/proc/loadavg", "r");
  if (f) {
    fclose(f);
    CHECK(r >= 1, "running = %d with /proc/loadavg readable", r);
    CHECK(others == r - 1 || (others == 0 && r <= 1), "others = %d, running %d, mine 1", others, r);
  } else {
    CHECK(r == -1 && others == 0, "no /proc/loadavg: running %d, others %d", r, others);
  }
  /* Within the period the sample stands: the same count, whatever mine is now.
   * (The period is pushed out first: under valgrind two calls can be more
   * than CPULOAD_PERIOD_S apart, and a new sample then rightly differs.) */
  atomic_store(&l.due, atomic_load(&l.due) + (long long)10e9);
  int o2 = -7, r2 = cpuload_running(&l, 1000, &o2);
  CHECK(r2 == r && o2 == others, "a fresh sample is reused: %d/%d, then %d/%d", r, others, r2, o2);
  /* A yield that comes back at once (nothing else runnable on our
   * processor, mostly) does not set the hog flag; one that is made to look
   * long does: hogged until the hold runs out. */
  CHECK(!cpuload_hogged(&l), "hogged before any yield");
  atomic_store(&l.hogged, (long long)((wallclock() + 1) * 1e9));
  CHECK(cpuload_hogged(&l), "hogged flag set for a second");
  atomic_store(&l.hogged, (long long)((wallclock() - 1) * 1e9));
  CHECK(!cpuload_hogged(&l), "hogged flag expired");
}

int main(void) {
  parse();
  sample();
  return check_done("test_cpuload");
}
