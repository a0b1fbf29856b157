/* atomicfile.h -- write a file beside its target and rename it into place
 * when complete, so that a failed run never leaves a partial file (as Redis
 * writes temp-%d.rdb, then rename()); nor does an interrupted one.
 *
 * Signals: the first atomicfile_open installs a handler for SIGHUP, SIGINT,
 * SIGQUIT, SIGTERM, SIGPIPE, SIGALRM, SIGXCPU, SIGXFSZ and SIGABRT (each
 * whose action is still the default: an ignored or handled one is left
 * alone).  It removes every temporary file this process has open, restores
 * the default action and raises the signal again: the process dies of the
 * same signal, leaving only complete files.  Any thread may open files and
 * take the signal; a forked child removes only its own files, never its
 * parent's.  At most 64 files are open at once. */
#ifndef ATOMICFILE_H
#define ATOMICFILE_H

#include <stddef.h>
#include <stdio.h>

typedef struct {
  FILE *f;      /* write here */
  char *path;   /* the target */
  char *tmp;    /* the temporary file beside it */
} atomicfile;

/* Open a temporary file beside path (mode 0666 less the umask).  0, or -1
 * with "PATH: why" in err. */
int atomicfile_open(atomicfile *a, const char *path, const char *mode, char *err, size_t errlen);

/* ok: flush, close and rename into place (0, or -1 with "PATH: why" in err);
 * !ok: close and remove the temporary file (returns -1). */
int atomicfile_close(atomicfile *a, int ok, char *err, size_t errlen);

/* Can path be written, as atomicfile_open and atomicfile_close would write
 * it?  A temporary file is made beside it and removed at once, and a
 * folder in its place is refused: what a program checks before its work,
 * so that a run never ends in "cannot write" after its report.  0, or -1
 * with "PATH: why" in err. */
int atomicfile_check(const char *path, char *err, size_t errlen);

/* How many temporary files this process has open (for tests). */
int atomicfile_live(void);

#endif
