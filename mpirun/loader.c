/* loader.c -- one dlopen'ed copy of the program per rank (loader.h). */
#define _GNU_SOURCE
#include "loader.h"

#include <dlfcn.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "atomicfile.h"
#include "xmem.h"

struct loader {
  int n;
  void **handle;          /* [n] */
  loader_main_fn *main;   /* [n] */
};

/* The program's bytes, or NULL. */
static unsigned char *slurp(const char *path, size_t *len, char *err, size_t errlen) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    snprintf(err, errlen, "%s: cannot open it", path);
    return NULL;
  }
  size_t cap = 1 << 16, n = 0;
  unsigned char *b = xmalloc(cap);
  for (size_t k; (k = fread(b + n, 1, cap - n, f)) > 0;) {
    n += k;
    if (n == cap) b = xrealloc(b, cap *= 2);
  }
  int bad = ferror(f);
  fclose(f);
  if (bad) {
    snprintf(err, errlen, "%s: cannot read it", path);
    free(b);
    return NULL;
  }
  *len = n;
  return b;
}

/* dlopen's words about the copy at `copy`, with the program's name for it. */
static void why_not(char *err, size_t errlen, int r, const char *path, const char *copy) {
  const char *e = dlerror();
  if (!e) e = "dlopen failed";
  size_t k = strlen(copy);
  if (strncmp(e, copy, k) == 0) e += k + (e[k] == ':' ? 1 : 0);
  while (*e == ' ') e++;
  snprintf(err, errlen, "rank %d: cannot load %s: %s", r, path, e);
}

/* Rank r's main from its loaded copy, or a message. */
static int find_main(loader *l, int r, const char *path, char *err, size_t errlen) {
  if ((*(void **)&l->main[r] = dlsym(l->handle[r], "main"))) return 0;
  snprintf(err, errlen, "%s has no main", path);
  return -1;
}

/* The copies as anonymous memory files (memfd_create: nothing on any disk,
 * nothing to remove), each opened by its /proc/self/fd name while all are
 * open, so that no two copies share a name.  1: loaded; 0: not possible
 * here (no memfd_create, no /proc, too few file descriptors): use files;
 * -1: an error of the program's (a message). */
static int load_memfd(loader *l, const unsigned char *bytes, size_t len, const char *path, char *err,
                      size_t errlen) {
  int n = l->n;
  struct rlimit rl;
  if (getrlimit(RLIMIT_NOFILE, &rl) != 0) return 0;
  if (rl.rlim_cur != RLIM_INFINITY && rl.rlim_cur < (rlim_t)n + 64) {
    if (rl.rlim_max != RLIM_INFINITY && rl.rlim_max < (rlim_t)n + 64) return 0;
    rl.rlim_cur = (rlim_t)n + 64;
    if (setrlimit(RLIMIT_NOFILE, &rl) != 0) return 0;
  }
  int *fd = xmallocarray((size_t)n, sizeof *fd), made = 0, res = 1;
  char name[64];
  for (; made < n && res == 1; made++) {
    int f = memfd_create("tilesim-rank", MFD_CLOEXEC);
    if (f < 0) {
      res = made == 0 ? 0 : -1;
      if (res < 0) snprintf(err, errlen, "rank %d: no memory for its copy of %s", made, path);
      break;
    }
    fd[made] = f;
    size_t off = 0;
    while (off < len) {
      ssize_t w = write(f, bytes + off, len - off);
      if (w <= 0) break;
      off += (size_t)w;
    }
    snprintf(name, sizeof name, "/proc/self/fd/%d", f);
    if (off < len) {
      snprintf(err, errlen, "rank %d: no memory for its copy of %s", made, path);
      res = -1;
    } else if (!(dlerror(), l->handle[made] = dlopen(name, RTLD_NOW | RTLD_LOCAL))) {
      if (made == 0 && access("/proc/self/fd", F_OK) != 0) res = 0;   /* no /proc: files */
      else why_not(err, errlen, made, path, name), res = -1;
    } else if (find_main(l, made, path, err, errlen) != 0) {
      res = -1;
    }
  }
  for (int i = 0; i < made; i++) close(fd[i]);
  free(fd);
  return res;
}

loader *loader_new(const char *path, int n, char *err, size_t errlen) {
  size_t len = 0;
  unsigned char *bytes = slurp(path, &len, err, errlen);
  if (!bytes) return NULL;
  loader *l = xcalloc(1, sizeof *l);
  l->n = n;
  l->handle = xcalloc((size_t)n, sizeof *l->handle);
  l->main = xcalloc((size_t)n, sizeof *l->main);
  int m = load_memfd(l, bytes, len, path, err, errlen);
  if (m != 0) {
    free(bytes);
    if (m > 0) return l;
    loader_free(l);
    return NULL;
  }
  const char *dir = getenv("TMPDIR");
  if (!dir || !*dir) dir = "/tmp";
  char target[4200], why[600];
  int ok = 1;
  for (int r = 0; r < n && ok; r++) {
    snprintf(target, sizeof target, "%s/tilesim-mpirun-%ld-rank%d.so", dir, (long)getpid(), r);
    atomicfile a;
    if (atomicfile_open(&a, target, "wb", why, sizeof why) != 0) {
      snprintf(err, errlen, "rank %d: cannot write its copy of %s: %s ($TMPDIR says where)", r, path, why);
      ok = 0;
      break;
    }
    int wrote = fwrite(bytes, 1, len, a.f) == len && fflush(a.f) == 0;
    if (wrote) {
      dlerror();
      l->handle[r] = dlopen(a.tmp, RTLD_NOW | RTLD_LOCAL);
    }
    atomicfile_close(&a, 0, why, sizeof why);   /* removed: the mapping stays */
    if (!wrote) {
      snprintf(err, errlen, "rank %d: cannot write its copy of %s in %s (full?)", r, path, dir);
      ok = 0;
    } else if (!l->handle[r]) {
      why_not(err, errlen, r, path, a.tmp ? a.tmp : target);
      ok = 0;
    } else if (find_main(l, r, path, err, errlen) != 0) {
      ok = 0;
    }
  }
  free(bytes);
  if (!ok) {
    loader_free(l);
    return NULL;
  }
  return l;
}

loader_main_fn loader_main(const loader *l, int r) { return l->main[r]; }

void loader_free(loader *l) {
  if (!l) return;
  for (int r = 0; r < l->n; r++)
    if (l->handle[r]) dlclose(l->handle[r]);
  free(l->handle);
  free(l->main);
  free(l);
}
