/* test_atomicfile.c -- util/atomicfile: complete files or none.  A closed
 * file is in place with its bytes and no temporary file beside it; a
 * discarded one leaves nothing (and an older target as it was); a process
 * killed by a signal removes its temporary files and dies of that signal
 * (checked in forked children, by the wait status and the folder's
 * listing); a forked child's death leaves its parent's files alone; eight
 * threads opening and closing at once never share a slot; at most 64 open. */
#include <dirent.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "util/atomicfile.h"
#include "tests/check.h"

static char dir[64];

/* Files in dir whose name starts with prefix. */
static int count(const char *prefix) {
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));) n += strncmp(e->d_name, prefix, strlen(prefix)) == 0;
  if (d) closedir(d);
  return n;
}

static void path_of(char *buf, size_t len, const char *name) { snprintf(buf, len, "%s/%s", dir, name); }

static int contents_are(const char *name, const char *want) {
  char p[128], got[64] = "";
  path_of(p, sizeof p, name);
  FILE *f = fopen(p, "r");
  if (!f) return 0;
  size_t n = fread(got, 1, sizeof got - 1, f);
  fclose(f);
  got[n] = 0;
  return strcmp(got, want) == 0;
}

static void basics(void) {
  char p[128], err[300];
  atomicfile a;
  path_of(p, sizeof p, "a.txt");
  CHECK(atomicfile_open(&a, p, "w", err, sizeof err) == 0, "open: %s", err);
  CHECK(atomicfile_live() == 1 && count("a.txt.tmp") == 1 && count("a.txt") == 1, "one temporary file, no target");
  fputs("hello", a.f);
  CHECK(atomicfile_close(&a, 1, err, sizeof err) == 0, "close: %s", err);
  CHECK(atomicfile_live() == 0 && count("a.txt.tmp") == 0 && contents_are("a.txt", "hello"), "renamed into place");
  CHECK(atomicfile_open(&a, p, "w", err, sizeof err) == 0, "open: %s", err);
  fputs("partial", a.f);
  CHECK(atomicfile_close(&a, 0, err, sizeof err) == -1, "a discarded file reports -1");
  CHECK(atomicfile_live() == 0 && count("a.txt.tmp") == 0 && contents_are("a.txt", "hello"), "discarded: the old target stays");
  /* No folder to put it in. */
  path_of(p, sizeof p, "nodir/x.txt");
  CHECK(atomicfile_open(&a, p, "w", err, sizeof err) == -1 && strstr(err, "cannot create a temporary file"),
        "no folder: %s", err);
  CHECK(atomicfile_live() == 0, "a failed open holds no slot");
  /* Checked before the work: no folder, a folder in the file's place, a
   * target that exists (kept as it is), a new one (not made). */
  CHECK(atomicfile_check(p, err, sizeof err) == -1 && strstr(err, "nodir/x.txt: cannot create a temporary file"),
        "check, no folder: %s", err);
  char d[128];
  path_of(d, sizeof d, "");
  CHECK(atomicfile_check(d, err, sizeof err) == -1 && strstr(err, "is a folder"), "check, a folder: %s", err);
  path_of(p, sizeof p, "a.txt");
  CHECK(atomicfile_check(p, err, sizeof err) == 0 && contents_are("a.txt", "hello") && count("a.txt") == 1,
        "check, an existing file: %s", err);
  path_of(p, sizeof p, "new.txt");
  CHECK(atomicfile_check(p, err, sizeof err) == 0 && count("new.txt") == 0 && atomicfile_live() == 0,
        "check, a new file: nothing made, no slot held (%s)", err);
  /* At most 64 at once, and a slot comes back when closed. */
  static atomicfile many[65];
  int opened = 0;
  for (int i = 0; i < 65; i++) {
    path_of(p, sizeof p, "m.txt");
    if (atomicfile_open(&many[i], p, "w", err, sizeof err) == 0) opened++;
  }
  CHECK(opened == 64 && strstr(err, "more than 64 files written at once"), "%d opened: %s", opened, err);
  for (int i = 0; i < 64; i++) atomicfile_close(&many[i], 0, err, sizeof err);
  CHECK(atomicfile_live() == 0 && count("m.txt") == 0, "all 64 discarded");
}

/* A child opens two files, writes, and sends itself sig: it must die of
 * sig with no temporary file left; its parent's open file must survive. */
static void killed(int sig) {
  char p[128], q[128], err[300];
  atomicfile mine;
  path_of(p, sizeof p, "parent.txt");
  CHECK(atomicfile_open(&mine, p, "w", err, sizeof err) == 0, "open: %s", err);
  fputs("parent", mine.f);
  fflush(mine.f);
  pid_t pid = fork();
  if (pid == 0) {
    atomicfile a, b;
    path_of(p, sizeof p, "c1.txt");
    path_of(q, sizeof q, "c2.txt");
    if (atomicfile_open(&a, p, "w", err, sizeof err) != 0 || atomicfile_open(&b, q, "wb", err, sizeof err) != 0)
      _exit(3);
    fputs("half", a.f);
    fflush(a.f);
    raise(sig);
    _exit(4);   /* not reached: the signal ends the process */
  }
  int st;
  waitpid(pid, &st, 0);
  CHECK(WIFSIGNALED(st) && WTERMSIG(st) == sig, "signal %d: the child ended with status %#x", sig, st);
  CHECK(count("c1.txt") == 0 && count("c2.txt") == 0, "signal %d: the child left its files", sig);
  CHECK(count("parent.txt.tmp") == 1 && atomicfile_live() == 1, "signal %d: the parent's file went", sig);
  CHECK(atomicfile_close(&mine, 1, err, sizeof err) == 0 && contents_are("parent.txt", "parent"),
        "signal %d: the parent's file: %s", sig, err);
}

/* An ignored signal stays ignored (nohup's SIGHUP): the program goes on. */
static void ignored(void) {
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGHUP, SIG_IGN);
    char p[128], err[300];
    atomicfile a;
    path_of(p, sizeof p, "nohup.txt");
    if (atomicfile_open(&a, p, "w", err, sizeof err) != 0) _exit(3);
    raise(SIGHUP);
    fputs("done", a.f);
    _exit(atomicfile_close(&a, 1, err, sizeof err) == 0 ? 0 : 5);
  }
  int st;
  waitpid(pid, &st, 0);
  CHECK(WIFEXITED(st) && WEXITSTATUS(st) == 0 && contents_are("nohup.txt", "done"),
        "an ignored SIGHUP: status %#x", st);
}

typedef struct {
  int id, bad;
} worker;

static void *churn(void *ud) {
  worker *w = ud;
  char p[128], err[300];
  for (int i = 0; i < 200; i++) {
    atomicfile a;
    snprintf(p, sizeof p, "%s/t%d.txt", dir, w->id);
    if (atomicfile_open(&a, p, "w", err, sizeof err) != 0) {
      w->bad++;
      continue;
    }
    fprintf(a.f, "%d %d", w->id, i);
    if (atomicfile_close(&a, 1, err, sizeof err) != 0) w->bad++;
  }
  return NULL;
}

static void threads(void) {
  pthread_t t[8];
  worker w[8];
  for (int i = 0; i < 8; i++) {
    w[i] = (worker){i, 0};
    pthread_create(&t[i], NULL, churn, &w[i]);
  }
  int bad = 0;
  for (int i = 0; i < 8; i++) pthread_join(t[i], NULL), bad += w[i].bad;
  CHECK(bad == 0, "%d opens or closes failed on eight threads", bad);
  CHECK(atomicfile_live() == 0, "%d slots still held", atomicfile_live());
  char want[32];
  int right = 0;
  for (int i = 0; i < 8; i++) {
    char name[32];
    snprintf(name, sizeof name, "t%d.txt", i);
    snprintf(want, sizeof want, "%d 199", i);
    right += contents_are(name, want);
  }
  CHECK(right == 8 && count("t") == 8, "each thread's last file in place, nothing else (%d right)", right);
}

int main(void) {
  /* As a program started normally, whatever started the test: nohup leaves
   * SIGHUP ignored, and atomicfile keeps an ignored signal ignored. */
  for (int s = 1; s < 32; s++)
    if (s != SIGKILL && s != SIGSTOP) signal(s, SIG_DFL);
  snprintf(dir, sizeof dir, "/tmp/tilesim-atomic.XXXXXX");
  if (!mkdtemp(dir)) return 1;
  basics();
  static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGQUIT, SIGXFSZ, SIGALRM};
  for (size_t i = 0; i < sizeof sigs / sizeof *sigs; i++) killed(sigs[i]);
  ignored();
  threads();
  if (check_rmtree(dir) != 0) return 1;
  return check_done("test_atomicfile");
}
