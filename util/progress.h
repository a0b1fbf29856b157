/* progress.h -- how far a long run has got, on stderr, in a form both a
 * person and a log can use.
 *
 * On a terminal: one line that rewrites itself ("tile: pair 12 of 91, 4 s"),
 * its time moving every second, cleared at the end.  Otherwise (stderr is
 * a file or a pipe, a log): a whole line every few seconds, "tile: pair 12
 * of 91 (13%), 5 s", and a last line "tile: pair 91 of 91, done in 48 s" if
 * any line was written; a run shorter than the interval writes nothing.
 * The lines keep coming while no step ends (a thread of the progress's
 * own repeats the last count with the time so far), so a long single step
 * shows too.  The interval is 5 s; the environment variable
 * TILESIM_PROGRESS_S sets another (0: a line at every step and no
 * repeats, as the tests use it). */
#ifndef PROGRESS_H
#define PROGRESS_H

typedef struct progress progress;

/* Progress of `what` ("pair", "run") for program prog ("tile"); NULL if
 * quiet (no progress at all: then the calls below do nothing). */
progress *progress_new(const char *prog, const char *what, int quiet);

/* done of total steps are complete (any thread may call it); 0 of total at
 * the start makes the repeated lines count from there. */
void progress_step(progress *p, long long done, long long total);

/* For a run whose end is not known: text says how far it has got
 * ("simulated 12.5 s, 3.1 M calls"), shown at the same pace as the steps
 * (a terminal's line, or a log line every few seconds with the time). */
void progress_note(progress *p, const char *text);

/* Stop the thread that repeats the lines, and start it again: around a
 * fork(), which must not copy a process in which that thread may hold a
 * lock (the allocator's: the child would wait for it for ever).  Lines
 * still come from the steps meanwhile.  NULL is fine. */
void progress_hold(progress *p);
void progress_resume(progress *p);

/* The run is over: clear the terminal line, or write the last log line;
 * free p (NULL is fine). */
void progress_end(progress *p);

#endif
