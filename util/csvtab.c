/* csvtab.c -- reading the bench's CSV. */
#include "csvtab.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "xmem.h"

static char **split(char *line, int *n) {
  int cap = 8, k = 0;
  char **f = xmallocarray((size_t)cap, sizeof *f);
  char *p = line;
  for (;;) {
    char *c = strchr(p, ',');
    if (k == cap) f = xreallocarray(f, (size_t)(cap *= 2), sizeof *f);
    if (c) *c = 0;
    f[k++] = xstrdup(p);
    if (!c) break;
    p = c + 1;
  }
  *n = k;
  return f;
}

int csvtab_read(const char *path, csvtab *t, char *err, size_t errlen) {
  memset(t, 0, sizeof *t);
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(err, errlen, "%s: cannot open (%s)", path, strerror(errno));
    return -1;
  }
  char line[8192];
  int lineno = 0, cap = 0;
  while (fgets(line, sizeof line, f)) {
    lineno++;
    size_t len = strlen(line);
    while (len && (line[len - 1] == '\n' || line[len - 1] == '\r')) line[--len] = 0;
    if (len == 0) continue;
    int n;
    char **fields = split(line, &n);
    if (!t->head) {
      t->head = fields;
      t->ncol = n;
      continue;
    }
    if (n != t->ncol) {
      snprintf(err, errlen, "%s:%d: %d fields, the header has %d", path, lineno, n, t->ncol);
      for (int i = 0; i < n; i++) free(fields[i]);
      free(fields);
      fclose(f);
      csvtab_free(t);
      return -1;
    }
    if (t->nrow == cap) t->cell = xreallocarray(t->cell, (size_t)(cap = cap ? 2 * cap : 64), sizeof *t->cell);
    t->cell[t->nrow++] = fields;
  }
  fclose(f);
  if (!t->head) {
    snprintf(err, errlen, "%s:1: empty, no header row", path);
    return -1;
  }
  return 0;
}

int csvtab_col(const csvtab *t, const char *name) {
  for (int i = 0; i < t->ncol; i++)
    if (strcmp(t->head[i], name) == 0) return i;
  return -1;
}

void csvtab_free(csvtab *t) {
  for (int r = 0; r < t->nrow; r++) {
    for (int c = 0; c < t->ncol; c++) free(t->cell[r][c]);
    free(t->cell[r]);
  }
  for (int c = 0; c < t->ncol; c++) free(t->head[c]);
  free(t->cell);
  free(t->head);
  memset(t, 0, sizeof *t);
}
