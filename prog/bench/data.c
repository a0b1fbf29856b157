/* data.c -- finding ./bench's data, in the source tree or installed. */
#include "prog/bench/data.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* The folder of the running program (Linux: /proc/self/exe), or "". */
static void exe_dir(char *buf, size_t len) {
  ssize_t n = readlink("/proc/self/exe", buf, len - 1);
  buf[n > 0 ? n : 0] = 0;
  char *slash = strrchr(buf, '/');
  if (slash) *slash = 0;
  else buf[0] = 0;
}

static int readable(const char *path) { return access(path, R_OK) == 0; }

int bench_data_find(const char *name, const char *dir, char *out, size_t len) {
  static const char tree[] = "tests/data/";
  int in_tree = strncmp(name, tree, sizeof tree - 1) == 0;
  if (readable(name) || strcmp(name, "-") == 0 || (strchr(name, '/') && !in_tree)) {
    snprintf(out, len, "%s", name);
    return 0;
  }
  const char *rel = in_tree ? name + sizeof tree - 1 : name;
  char bin[2048], roots[5][2100];
  int nroots = 0;
  exe_dir(bin, sizeof bin);
  if (dir) snprintf(roots[nroots++], sizeof roots[0], "%s", dir);
  if (bin[0]) {
    snprintf(roots[nroots++], sizeof roots[0], "%s/../share/tilesim", bin);
    snprintf(roots[nroots++], sizeof roots[0], "%s/tests/data", bin);
    snprintf(roots[nroots++], sizeof roots[0], "%s/../../tests/data", bin);
  }
  snprintf(roots[nroots++], sizeof roots[0], "tests/data");
  static const char *const subs[] = {"", "slicerrt/", "rtstruct/"};
  for (int r = 0; r < nroots; r++)
    for (int k = 0; k < (in_tree ? 1 : 3); k++) {
      snprintf(out, len, "%s/%s%s", roots[r], subs[k], rel);
      if (readable(out)) return 0;
    }
  snprintf(out, len,
           "%s: not found%s%s, in %s/../share/tilesim (make install puts the data there) or in "
           "tests/data; --data DIR says where it is",
           name, dir ? " in " : "", dir ? dir : "", bin[0] ? bin : "the program's folder");
  return -1;
}
