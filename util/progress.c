/* progress.c -- a self-rewriting line on a terminal, a line every few
 * seconds in a log; a ticker thread keeps them coming while no step ends. */
#include "util/progress.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "util/wallclock.h"
#include "util/xmem.h"

struct progress {
  char prog[32], what[32];
  char note[96];     /* progress_note's last text ("" when it counts steps) */
  int tty;           /* stderr is a terminal */
  double start, last, every;
  long long done, total;
  int lines;         /* log lines written */
  pthread_mutex_t lock;   /* steps may come from several threads */
  pthread_cond_t wake;    /* progress_end wakes the ticker */
  pthread_t ticker;
  int ticking, stop;
};

/* One line of where the run is, now (the lock held). */
static void show(progress *p, double now) {
  p->last = now;
  char at[160];
  if (p->note[0]) snprintf(at, sizeof at, "%s", p->note);
  else if (p->total > 0 && p->tty) snprintf(at, sizeof at, "%s %lld of %lld", p->what, p->done, p->total);
  else if (p->total > 0)
    snprintf(at, sizeof at, "%s %lld of %lld (%.0f%%)", p->what, p->done, p->total,
             100.0 * (double)p->done / (double)p->total);
  else snprintf(at, sizeof at, "running");
  if (p->tty) {
    fprintf(stderr, "\r%s: %s, %.0f s\033[K", p->prog, at, now - p->start);
  } else {
    fprintf(stderr, "%s: %s, %.0f s\n", p->prog, at, now - p->start);
    p->lines++;
  }
  fflush(stderr);
}

/* Due: the interval has passed since the last line (and, in a log, since
 * the start: short runs stay silent). */
static int due(const progress *p, double now) {
  return now - p->last >= p->every && (p->tty || now - p->start >= p->every);
}

/* While no step ends and no note comes (a long single run, a slow start),
 * the same line again, its time moving on: every second on a terminal,
 * every interval in a log (after the first interval: short runs stay
 * silent). */
static void *tick(void *arg) {
  progress *p = arg;
  double every = p->tty ? 1 : p->every;
  pthread_mutex_lock(&p->lock);
  while (!p->stop) {
    double next = p->last + every, now = wallclock();
    if (!p->tty && next < p->start + p->every) next = p->start + p->every;
    if (now < next) {
      struct timespec ts;
      clock_gettime(CLOCK_REALTIME, &ts);
      double at = (double)ts.tv_sec + ts.tv_nsec * 1e-9 + (next - now) + 0.001;
      ts.tv_sec = (time_t)at;
      ts.tv_nsec = (long)((at - (double)ts.tv_sec) * 1e9);
      if (ts.tv_nsec > 999999999) ts.tv_nsec = 999999999;
      pthread_cond_timedwait(&p->wake, &p->lock, &ts);
      continue;
    }
    show(p, now);
  }
  pthread_mutex_unlock(&p->lock);
  return NULL;
}

progress *progress_new(const char *prog, const char *what, int quiet) {
  if (quiet) return NULL;
  progress *p = xcalloc(1, sizeof *p);
  snprintf(p->prog, sizeof p->prog, "%s", prog);
  snprintf(p->what, sizeof p->what, "%s", what);
  p->tty = isatty(2);
  p->every = p->tty ? 0.1 : 5;
  const char *env = getenv("TILESIM_PROGRESS_S");
  if (env && !p->tty) {
    char *end;
    double v = strtod(env, &end);
    if (end != env && !*end && v >= 0) p->every = v;
  }
  p->start = p->last = wallclock();
  pthread_mutex_init(&p->lock, NULL);
  pthread_cond_init(&p->wake, NULL);
  /* The ticker: on a terminal the line's time moves every second; in a
   * log a line every interval (none when a line comes at every step). */
  if (p->every > 0) p->ticking = pthread_create(&p->ticker, NULL, tick, p) == 0;
  return p;
}

static void step(progress *p, long long done, long long total);

void progress_step(progress *p, long long done, long long total) {
  if (!p) return;
  pthread_mutex_lock(&p->lock);
  step(p, done, total);
  pthread_mutex_unlock(&p->lock);
}

static void step(progress *p, long long done, long long total) {
  if (done < p->done) return;   /* (threads: a later count already shown) */
  p->done = done, p->total = total;
  if (!p->tty && done >= total) return;   /* progress_end says it */
  double now = wallclock();
  if (!due(p, now) && !(p->tty && done >= total && now - p->last >= p->every)) return;
  show(p, now);
}

void progress_note(progress *p, const char *text) {
  if (!p) return;
  pthread_mutex_lock(&p->lock);
  snprintf(p->note, sizeof p->note, "%s", text);
  double now = wallclock();
  if (due(p, now)) show(p, now);
  pthread_mutex_unlock(&p->lock);
}

void progress_hold(progress *p) {
  if (!p || !p->ticking) return;
  pthread_mutex_lock(&p->lock);
  p->stop = 1;
  pthread_cond_signal(&p->wake);
  pthread_mutex_unlock(&p->lock);
  pthread_join(p->ticker, NULL);
  p->ticking = 0;
}

void progress_resume(progress *p) {
  if (!p || p->ticking || p->every <= 0) return;
  p->stop = 0;
  p->ticking = pthread_create(&p->ticker, NULL, tick, p) == 0;
}

void progress_end(progress *p) {
  if (!p) return;
  progress_hold(p);
  if (p->tty) fputs("\r\033[K", stderr);
  else if (p->lines && p->note[0])
    fprintf(stderr, "%s: %s, done in %.0f s\n", p->prog, p->note, wallclock() - p->start);
  else if (p->lines && p->total > 0)
    fprintf(stderr, "%s: %s %lld of %lld, done in %.0f s\n", p->prog, p->what, p->done, p->total,
            wallclock() - p->start);
  else if (p->lines)   /* no count to give: "running" lines before */
    fprintf(stderr, "%s: done in %.0f s\n", p->prog, wallclock() - p->start);
  fflush(stderr);
  pthread_cond_destroy(&p->wake);
  pthread_mutex_destroy(&p->lock);
  free(p);
}
