/* loader.c -- one dlopen'ed copy of the program per rank (loader.h). */
#define _GNU_SOURCE
#include "loader.h"

#include <dlfcn.h>
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

loader *loader_new(const char *path, int n, char *err, size_t errlen) {
  size_t len = 0;
  unsigned char *bytes = slurp(path, &len, err, errlen);
  if (!bytes) return NULL;
  loader *l = xcalloc(1, sizeof *l);
  l->n = n;
  l->handle = xcalloc((size_t)n, sizeof *l->handle);
  l->main = xcalloc((size_t)n, sizeof *l->main);
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
      const char *e = dlerror();
      snprintf(err, errlen, "rank %d: cannot load %s: %s", r, path, e ? e : "dlopen failed");
      ok = 0;
    } else if (!(*(void **)&l->main[r] = dlsym(l->handle[r], "main"))) {
      snprintf(err, errlen, "%s has no main", path);
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
