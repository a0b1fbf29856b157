/* csvtab.c -- reading the bench's CSV (RFC 4180 quoting, one record a line). */
#include "util/csvtab.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

/* One line's fields: plain, or quoted as RFC 4180 writes them ("...", a
 * quote inside doubled, commas inside kept).  NULL with *why when a quote is
 * not closed or text follows a closing quote. */
static char **split(const char *line, int *n, const char **why) {
  int cap = 8, k = 0;
  char **f = xmallocarray((size_t)cap, sizeof *f);
  char *buf = xmalloc(strlen(line) + 1);
  const char *p = line;
  for (;;) {
    size_t b = 0;
    if (*p == '"') {
      for (p++;; p++) {
        if (!*p) {
          *why = "a quoted field is not closed";
          goto bad;
        }
        if (*p == '"') {
          if (p[1] != '"') break;
          p++;
        }
        buf[b++] = *p;
      }
      p++;
      if (*p && *p != ',') {
        *why = "text after a quoted field's closing quote";
        goto bad;
      }
    } else
      while (*p && *p != ',') buf[b++] = *p++;
    buf[b] = 0;
    if (k == cap) f = xreallocarray(f, (size_t)(cap *= 2), sizeof *f);
    f[k++] = xstrdup(buf);
    if (*p != ',') break;
    p++;
  }
  free(buf);
  *n = k;
  return f;
bad:
  for (int i = 0; i < k; i++) free(f[i]);
  free(f);
  free(buf);
  return NULL;
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
    if (len == sizeof line - 1) {
      snprintf(err, errlen, "%s:%d: a line longer than %zu bytes", path, lineno, sizeof line - 2);
      fclose(f);
      csvtab_free(t);
      return -1;
    }
    int n;
    const char *why = NULL;
    char **fields = split(line, &n, &why);
    if (!fields) {
      snprintf(err, errlen, "%s:%d: %s", path, lineno, why);
      fclose(f);
      csvtab_free(t);
      return -1;
    }
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
