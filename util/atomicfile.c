/* atomicfile.c -- a temporary file, then rename(); and no temporary file
 * left behind by a signal.
 *
 * Every live temporary path is kept in a fixed table (no allocation, so
 * that a signal handler can read it).  A slot is claimed with an atomic
 * compare-and-swap (several threads may open files), filled, then marked
 * live; it is emptied before its path is reused.  The handler only reads
 * live slots of its own process (a forked worker inherits the table but
 * not the files), unlinks them, restores the default action and raises the
 * signal again, so the process dies of it as it would have: unlink,
 * getpid, sigaction and raise are async-signal-safe, and a lock-free
 * atomic int is safe to read in a handler. */
#include "util/atomicfile.h"

#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/xmem.h"

enum { SLOTS = 64, SLOT_PATH = 4096 + 32 };
enum { FREE, BUSY, LIVE };

static struct {
  atomic_int state;   /* FREE, BUSY (being filled or emptied), LIVE */
  pid_t pid;          /* the process that made the file */
  char path[SLOT_PATH];
} slot[SLOTS];

/* The signals whose default action ends the process and that a user or the
 * system sends to stop it (SIGPIPE: a reader that went away; SIGXFSZ: the
 * file size limit; SIGABRT: abort(), out of memory). */
static const int fatal[] = {SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGALRM, SIGXCPU, SIGXFSZ, SIGABRT};
enum { NFATAL = sizeof fatal / sizeof *fatal };

static void on_signal(int sig) {
  pid_t me = getpid();
  for (int i = 0; i < SLOTS; i++)
    if (atomic_load(&slot[i].state) == LIVE && slot[i].pid == me) unlink(slot[i].path);
  struct sigaction dfl;
  memset(&dfl, 0, sizeof dfl);
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, NULL);
  raise(sig);   /* pending until the handler returns, then the default: death */
}

/* Our handler for each fatal signal whose action is the default (one a
 * caller ignores, as nohup does SIGHUP, or handles itself, stays so). */
static void install(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int k = 0; k < NFATAL; k++) sigaddset(&sa.sa_mask, fatal[k]);   /* one at a time */
  for (int k = 0; k < NFATAL; k++) {
    struct sigaction old;
    if (sigaction(fatal[k], NULL, &old) == 0 && old.sa_handler == SIG_DFL && !(old.sa_flags & SA_SIGINFO))
      sigaction(fatal[k], &sa, NULL);
  }
}

static pthread_once_t installed = PTHREAD_ONCE_INIT;

/* A free slot, claimed (BUSY); -1 if every one is taken. */
static int claim(void) {
  for (int i = 0; i < SLOTS; i++) {
    int expect = FREE;
    if (atomic_compare_exchange_strong(&slot[i].state, &expect, BUSY)) return i;
  }
  return -1;
}

int atomicfile_open(atomicfile *a, const char *path, const char *mode, char *err, size_t errlen) {
  size_t len = strlen(path) + 16;
  a->f = NULL;
  if (len > SLOT_PATH) {
    snprintf(err, errlen, "%.200s...: a path of %zu bytes is too long", path, len - 16);
    a->path = a->tmp = NULL;
    return -1;
  }
  pthread_once(&installed, install);
  int k = claim();
  if (k < 0) {
    snprintf(err, errlen, "%s: more than %d files written at once", path, SLOTS);
    a->path = a->tmp = NULL;
    return -1;
  }
  a->path = xstrdup(path);
  a->tmp = xmalloc(len);
  snprintf(a->tmp, len, "%s.tmpXXXXXX", path);
  /* Signals wait while the file is made and its slot goes live: a handler
   * sees both or neither. */
  memcpy(slot[k].path, a->tmp, len);
  slot[k].pid = getpid();
  sigset_t all, old;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, &old);
  int fd = mkstemp(slot[k].path);
  memcpy(a->tmp, slot[k].path, len);
  if (fd >= 0) atomic_store(&slot[k].state, LIVE);
  pthread_sigmask(SIG_SETMASK, &old, NULL);
  if (fd >= 0) {
    mode_t um = umask(0);   /* mkstemp makes 0600; give the file the usual mode */
    umask(um);
    fchmod(fd, 0666 & ~um);
    a->f = fdopen(fd, mode);
  }
  if (!a->f) {
    snprintf(err, errlen, "%s: cannot create a temporary file beside it (%s)", path, strerror(errno));
    if (fd >= 0) close(fd), unlink(a->tmp);
    atomic_store(&slot[k].state, FREE);
    free(a->path), free(a->tmp);
    a->path = a->tmp = NULL;
    return -1;
  }
  return 0;
}

int atomicfile_close(atomicfile *a, int ok, char *err, size_t errlen) {
  int bad = !ok || fflush(a->f) != 0 || ferror(a->f);
  int e = errno;
  if (fclose(a->f) != 0 && !bad) bad = 1, e = errno;
  if (!bad && rename(a->tmp, a->path) != 0) bad = 1, e = errno;
  if (bad) {
    if (ok) snprintf(err, errlen, "%s: cannot write (%s)", a->path, strerror(e));
    unlink(a->tmp);
  }
  /* Only now out of the table: renamed or removed, the name is gone. */
  pid_t me = getpid();
  for (int i = 0; i < SLOTS; i++)
    if (atomic_load(&slot[i].state) == LIVE && slot[i].pid == me && strcmp(slot[i].path, a->tmp) == 0) {
      atomic_store(&slot[i].state, FREE);
      break;
    }
  free(a->path);
  free(a->tmp);
  a->f = NULL;
  a->path = a->tmp = NULL;
  return bad ? -1 : 0;
}

int atomicfile_check(const char *path, char *err, size_t errlen) {
  struct stat st;
  if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
    snprintf(err, errlen, "%s: is a folder; name a file", path);
    return -1;
  }
  atomicfile a;
  if (atomicfile_open(&a, path, "w", err, errlen) != 0) return -1;
  atomicfile_close(&a, 0, err, errlen);
  return 0;
}

int atomicfile_live(void) {
  int n = 0;
  for (int i = 0; i < SLOTS; i++) n += atomic_load(&slot[i].state) == LIVE && slot[i].pid == getpid();
  return n;
}
