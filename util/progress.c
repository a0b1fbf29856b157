/* progress.c -- a self-rewriting line on a terminal, a line every few
 * seconds in a log. */
#include "progress.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "wallclock.h"
#include "xmem.h"

struct progress {
  char prog[32], what[32];
  char note[96];     /* progress_note's last text ("" when it counts steps) */
  int tty;           /* stderr is a terminal */
  double start, last, every;
  long long done, total;
  int lines;         /* log lines written */
  pthread_mutex_t lock;   /* steps may come from several threads */
};

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
  if (now - p->last < p->every && done < total) return;
  if (!p->tty && now - p->start < p->every) return;   /* short runs stay silent in a log */
  p->last = now;
  if (p->tty) {
    fprintf(stderr, "\r%s: %s %lld of %lld", p->prog, p->what, done, total);
  } else {
    fprintf(stderr, "%s: %s %lld of %lld (%.0f%%), %.0f s\n", p->prog, p->what, done, total,
            total > 0 ? 100.0 * (double)done / (double)total : 0.0, now - p->start);
    p->lines++;
  }
  fflush(stderr);
}

void progress_note(progress *p, const char *text) {
  if (!p) return;
  pthread_mutex_lock(&p->lock);
  snprintf(p->note, sizeof p->note, "%s", text);
  double now = wallclock();
  if (now - p->last >= p->every && (p->tty || now - p->start >= p->every)) {
    p->last = now;
    if (p->tty) {
      fprintf(stderr, "\r%s: %s\033[K", p->prog, p->note);
    } else {
      fprintf(stderr, "%s: %s, %.0f s\n", p->prog, p->note, now - p->start);
      p->lines++;
    }
    fflush(stderr);
  }
  pthread_mutex_unlock(&p->lock);
}

void progress_end(progress *p) {
  if (!p) return;
  if (p->tty) fputs("\r\033[K", stderr);
  else if (p->lines && p->note[0])
    fprintf(stderr, "%s: %s, done in %.0f s\n", p->prog, p->note, wallclock() - p->start);
  else if (p->lines)
    fprintf(stderr, "%s: %s %lld of %lld, done in %.0f s\n", p->prog, p->what, p->done, p->total,
            wallclock() - p->start);
  fflush(stderr);
  pthread_mutex_destroy(&p->lock);
  free(p);
}
