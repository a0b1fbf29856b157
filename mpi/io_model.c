/* io_model.c -- the file systems of the run: mounts, host paths, the servers' queues
 * (io_model.h), and the runner's --fs option (settings.h). */
#include "mpi/io_model.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/args.h"
#include "mpi/settings.h"

enum { MOUNTS_MAX = 16 };

struct io_fs {
  char mount[256];         /* "/scratch" */
  char dir[IO_PATH_MAX];/* its files' host directory; "" : the same path */
  int scratch;             /* dir is the default scratch directory (made when used) */
  double latency;          /* seconds a request */
  double bandwidth;        /* bytes a second */
  double free;             /* when the server ends its last request */
};

/* The run's file systems (set before the ranks start) and the servers'
 * state, under one lock (threads share them). */
static io_fs mounts[MOUNTS_MAX];
static int nmounts;
static int users;          /* ranks between their first I/O call and their end */
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

static const double default_latency = 1e-4, default_bandwidth = 1e9;

static void defaults(void) {
  memset(mounts, 0, sizeof mounts);
  snprintf(mounts[0].mount, sizeof mounts[0].mount, "/");
  snprintf(mounts[1].mount, sizeof mounts[1].mount, "/scratch");
  mounts[1].scratch = 1;
  for (int i = 0; i < 2; i++) {
    mounts[i].latency = default_latency;
    mounts[i].bandwidth = default_bandwidth;
  }
  nmounts = 2;
}

void io_fs_reset(void) {
  pthread_mutex_lock(&lock);
  defaults();
  users = 0;
  pthread_mutex_unlock(&lock);
}

static void ensure(void) {
  if (!nmounts) defaults();
}

/* ==== paths =============================================================== */

/* path made absolute (the working directory's if relative) and lexically
 * clean: no "", "." or ".." components.  0, or -1 if too long. */
static int clean(const char *path, char *out, size_t len) {
  char buf[IO_PATH_MAX];
  if (path[0] == '/') {
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) return -1;
  } else {
    char cwd[IO_PATH_MAX];
    if (!getcwd(cwd, sizeof cwd)) return -1;
    if (snprintf(buf, sizeof buf, "%s/%s", cwd, path) >= (int)sizeof buf) return -1;
  }
  size_t n = 0;
  out[0] = '\0';
  for (char *save, *c = strtok_r(buf, "/", &save); c; c = strtok_r(NULL, "/", &save)) {
    if (!strcmp(c, ".")) continue;
    if (!strcmp(c, "..")) {
      while (n > 0 && out[n - 1] != '/') n--;
      if (n > 0) n--;
      out[n] = '\0';
      continue;
    }
    size_t k = strlen(c);
    if (n + 1 + k + 1 > len) return -1;
    out[n++] = '/';
    memcpy(out + n, c, k + 1);
    n += k;
  }
  if (n == 0) snprintf(out, len, "/");
  return 0;
}

/* The length of mount m as a prefix of p on component boundaries, or -1. */
static int prefix(const char *m, const char *p) {
  size_t k = strlen(m);
  if (!strcmp(m, "/")) return 0;
  if (strncmp(m, p, k) || (p[k] != '/' && p[k] != '\0')) return -1;
  return (int)k;
}

/* The default scratch directory, made if missing (caller holds the lock). */
static int scratch_dir(io_fs *fs, char *err, size_t errlen) {
  if (fs->dir[0]) return 0;
  const char *tmp = getenv("TMPDIR");
  if (!tmp || !*tmp) tmp = "/tmp";
  char d[IO_PATH_MAX];
  if (snprintf(d, sizeof d, "%s/tilesim-scratch-%ld", tmp, (long)getuid()) >= (int)sizeof d) {
    snprintf(err, errlen, "%s: $TMPDIR is too long", fs->mount);
    return -1;
  }
  if (mkdir(d, 0700) != 0 && errno != EEXIST) {
    snprintf(err, errlen, "%s: cannot make its directory %s: %s", fs->mount, d, strerror(errno));
    return -1;
  }
  snprintf(fs->dir, sizeof fs->dir, "%s", d);
  return 0;
}

io_fs *io_fs_of(const char *path, char *host, char *err, size_t errlen) {
  char abs[IO_PATH_MAX];
  if (!*path) {
    snprintf(err, errlen, "an empty file name");
    return NULL;
  }
  if (strlen(path) >= IO_PATH_MAX || clean(path, abs, sizeof abs) != 0) {
    snprintf(err, errlen, "the file name is too long (%zu bytes)", strlen(path));
    return NULL;
  }
  pthread_mutex_lock(&lock);
  ensure();
  io_fs *best = NULL;
  int blen = -1;
  for (int i = 0; i < nmounts; i++) {
    int k = prefix(mounts[i].mount, abs);
    if (k > blen) best = &mounts[i], blen = k;
  }
  int rc = best->scratch ? scratch_dir(best, err, errlen) : 0;
  pthread_mutex_unlock(&lock);
  if (rc) return NULL;
  int n = best->dir[0] ? snprintf(host, IO_PATH_MAX, "%s%s", best->dir, abs + blen)
                       : snprintf(host, IO_PATH_MAX, "%s", path);
  if (n >= IO_PATH_MAX) {
    snprintf(err, errlen, "the file's host path is too long");
    return NULL;
  }
  return best;
}

/* ==== the servers ========================================================= */

void io_fs_enter(void) {
  pthread_mutex_lock(&lock);
  ensure();
  users++;
  pthread_mutex_unlock(&lock);
}

void io_fs_leave(void) {
  pthread_mutex_lock(&lock);
  if (users > 0 && --users == 0)
    for (int i = 0; i < nmounts; i++) mounts[i].free = 0;
  pthread_mutex_unlock(&lock);
}

double io_fs_request(io_fs *fs, double t, double bytes) {
  pthread_mutex_lock(&lock);
  double start = fs->free > t ? fs->free : t;
  double end = start + fs->latency + (bytes > 0 ? bytes / fs->bandwidth : 0);
  fs->free = end;
  pthread_mutex_unlock(&lock);
  return end;
}

const char *io_fs_mount(const io_fs *fs) { return fs->mount; }
double io_fs_latency(const io_fs *fs) { return fs->latency; }
double io_fs_bandwidth(const io_fs *fs) { return fs->bandwidth; }

/* ==== --fs ================================================================ */

int io_fs_option(const char *spec, char *err, size_t errlen) {
  char buf[IO_PATH_MAX + 256], mount[IO_PATH_MAX];
  if (snprintf(buf, sizeof buf, "%s", spec) >= (int)sizeof buf) {
    snprintf(err, errlen, "--fs: the value is too long");
    return -1;
  }
  char *save, *m = strtok_r(buf, ",", &save);
  if (!m || m[0] != '/' || clean(m, mount, sizeof mount) != 0 || strlen(mount) >= sizeof mounts[0].mount) {
    snprintf(err, errlen, "--fs takes MOUNT[,dir=DIR][,latency=S][,bandwidth=B/S], MOUNT an absolute path (%.60s)",
             spec);
    return -1;
  }
  io_fs fs = {.latency = default_latency, .bandwidth = default_bandwidth};
  memcpy(fs.mount, mount, strlen(mount) + 1);
  pthread_mutex_lock(&lock);
  ensure();
  int at = nmounts;
  for (int i = 0; i < nmounts; i++)
    if (!strcmp(mounts[i].mount, mount)) at = i, fs = mounts[i];
  pthread_mutex_unlock(&lock);
  for (char *kv = strtok_r(NULL, ",", &save); kv; kv = strtok_r(NULL, ",", &save)) {
    if (!strncmp(kv, "dir=", 4)) {
      if (!strcmp(mount, "/")) {
        snprintf(err, errlen, "--fs: / is the host's own file system: it takes no dir=");
        return -1;
      }
      if (!kv[4] || snprintf(fs.dir, sizeof fs.dir, "%s", kv + 4) >= (int)sizeof fs.dir) {
        snprintf(err, errlen, "--fs %s: dir= takes a directory of the host", mount);
        return -1;
      }
      fs.scratch = 0;
    } else if (!strncmp(kv, "latency=", 8)) {
      if (args_real("--fs latency", kv + 8, "seconds", 0, 1e3, &fs.latency, err, errlen) != 0) return -1;
    } else if (!strncmp(kv, "bandwidth=", 10)) {
      if (args_real("--fs bandwidth", kv + 10, "bytes a second", 1, 1e15, &fs.bandwidth, err, errlen) != 0)
        return -1;
    } else {
      snprintf(err, errlen, "--fs %s: '%.40s' is none of dir=, latency=, bandwidth=", mount, kv);
      return -1;
    }
  }
  pthread_mutex_lock(&lock);
  int rc = 0;
  if (at == nmounts && nmounts == MOUNTS_MAX) {
    snprintf(err, errlen, "--fs: at most %d file systems", MOUNTS_MAX);
    rc = -1;
  } else {
    fs.free = 0;
    mounts[at] = fs;
    if (at == nmounts) nmounts++;
  }
  pthread_mutex_unlock(&lock);
  return rc;
}
