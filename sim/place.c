/* place.c -- placements of a run's processors on a topology (place.h). */
#include "sim/place.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/rng.h"
#include "util/xmem.h"

/* A whole number 0..TOPO_MAX_NODES-1 spanning all of s. */
static int node_id(const char *s, int *out) {
  if (!*s) return -1;
  long v = 0;
  for (const char *p = s; *p; p++) {
    if (*p < '0' || *p > '9' || v >= TOPO_MAX_NODES) return -1;
    v = v * 10 + (*p - '0');
  }
  if (v >= TOPO_MAX_NODES) return -1;
  *out = (int)v;
  return 0;
}

/* The file's processors into *ids (and the line of each into *lines), *n
 * of them; the caller frees both.  0, or -1 and "PATH:LINE: why". */
typedef struct {
  int *ids, *lines, nids;
} listing;

static int read_file(const char *path, listing *p, char *err, size_t errlen) {
  p->ids = p->lines = NULL;
  p->nids = 0;
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(err, errlen, "%s: %s", path, strerror(errno));
    return -1;
  }
  int cap = 0, ln = 0, bad = 0;
  char line[256];
  unsigned char *seen = NULL;   /* by processor id, grown as needed */
  int seencap = 0;
  while (!bad && fgets(line, sizeof line, f)) {
    ln++;
    size_t len = strlen(line);
    if (len == sizeof line - 1 && line[len - 1] != '\n' && !feof(f)) {
      snprintf(err, errlen, "%s:%d: line too long", path, ln);
      bad = 1;
      break;
    }
    while (len && (line[len - 1] == '\n' || line[len - 1] == '\r')) line[--len] = 0;
    if (len == 0 || line[0] == '#') continue;
    int id;
    if (node_id(line, &id) != 0) {
      snprintf(err, errlen, "%s:%d: '%s' is not a processor number (a whole number, one per line)",
               path, ln, line);
      bad = 1;
      break;
    }
    if (id >= seencap) {
      int ncap = seencap ? seencap : 64;
      while (ncap <= id) ncap *= 2;
      seen = xrealloc(seen, (size_t)ncap);
      memset(seen + seencap, 0, (size_t)(ncap - seencap));
      seencap = ncap;
    }
    if (seen[id]) {
      int first = 0;
      for (int i = 0; i < p->nids; i++)
        if (p->ids[i] == id) first = p->lines[i];
      snprintf(err, errlen, "%s:%d: processor %d is placed twice (line %d too)", path, ln, id,
               first);
      bad = 1;
      break;
    }
    seen[id] = 1;
    if (p->nids == cap) {
      cap = cap ? 2 * cap : 64;
      p->ids = xreallocarray(p->ids, (size_t)cap, sizeof *p->ids);
      p->lines = xreallocarray(p->lines, (size_t)cap, sizeof *p->lines);
    }
    p->ids[p->nids] = id;
    p->lines[p->nids++] = ln;
  }
  if (!bad && ferror(f)) {
    snprintf(err, errlen, "%s: %s", path, strerror(errno));
    bad = 1;
  }
  if (!bad && p->nids == 0) {
    snprintf(err, errlen, "%s: no processors listed (one whole number a line)", path);
    bad = 1;
  }
  fclose(f);
  free(seen);
  if (bad) {
    free(p->ids), free(p->lines);
    p->ids = p->lines = NULL;
  }
  return bad ? -1 : 0;
}

int place_parse(const char *s, place_spec *out, char *err, size_t errlen) {
  place_spec p;
  memset(&p, 0, sizeof p);
  if (strcmp(s, "linear") == 0) {
    p.kind = PLACE_LINEAR;
  } else if (strcmp(s, "snake") == 0) {
    p.kind = PLACE_SNAKE;
  } else if (strcmp(s, "gray") == 0) {
    p.kind = PLACE_GRAY;
  } else if (strncmp(s, "random:", 7) == 0) {
    const char *v = s + 7;
    char *end;
    errno = 0;
    p.seed = strtoull(v, &end, 10);
    if (!*v || *end || errno || *v < '0' || *v > '9') {
      snprintf(err, errlen, "placement '%s': random:SEED takes a whole number", s);
      return -1;
    }
    p.kind = PLACE_RANDOM;
  } else if (strncmp(s, "file:", 5) == 0 && s[5]) {
    if (strlen(s + 5) >= sizeof p.path) {
      snprintf(err, errlen, "placement file name longer than %d bytes", PLACE_PATH_MAX - 1);
      return -1;
    }
    p.kind = PLACE_FILE;
    snprintf(p.path, sizeof p.path, "%s", s + 5);
    listing l;
    if (read_file(p.path, &l, err, errlen) != 0) return -1;
    free(l.ids), free(l.lines);
  } else {
    snprintf(err, errlen, "unknown placement '%s': linear, snake, gray, random:SEED or file:PATH",
             s);
    return -1;
  }
  *out = p;
  return 0;
}

void place_spec_str(const place_spec *p, char *buf, size_t len) {
  switch (p->kind) {
  case PLACE_SNAKE: snprintf(buf, len, "snake"); break;
  case PLACE_GRAY: snprintf(buf, len, "gray"); break;
  case PLACE_RANDOM: snprintf(buf, len, "random:%llu", p->seed); break;
  case PLACE_FILE: snprintf(buf, len, "file:%s", p->path); break;
  default: snprintf(buf, len, "linear"); break;
  }
}

int place_map(const place_spec *p, const topo *t, int n, int *map, char *err, size_t errlen) {
  int N = topo_nodes(t);
  if (n > N) {
    snprintf(err, errlen, "placement: %d processors on a machine of %d", n, N);
    return -1;
  }
  switch (p->kind) {
  case PLACE_LINEAR:
    for (int v = 0; v < n; v++) map[v] = v;
    break;
  case PLACE_SNAKE: {
    int w, h;
    topo_grid(t, &w, &h);
    for (int v = 0; v < n; v++) {
      int y = v / w, x = v % w;
      map[v] = y * w + (y % 2 ? w - 1 - x : x);
    }
    break;
  }
  case PLACE_GRAY:
    for (int v = 0, i = 0; v < n; i++) {
      int g = i ^ (i >> 1);
      if (g < N) map[v++] = g;
    }
    break;
  case PLACE_RANDOM: {
    int *perm = xmallocarray((size_t)N, sizeof *perm);
    for (int i = 0; i < N; i++) perm[i] = i;
    rng g;
    rng_seed(&g, p->seed);
    for (int i = N - 1; i > 0; i--) {   /* Fisher-Yates */
      int j = rng_int(&g, 0, i), x = perm[i];
      perm[i] = perm[j], perm[j] = x;
    }
    memcpy(map, perm, (size_t)n * sizeof *map);
    free(perm);
    break;
  }
  case PLACE_FILE: {
    listing l;
    if (read_file(p->path, &l, err, errlen) != 0) return -1;
    int bad = 0;
    if (l.nids < n) {
      snprintf(err, errlen, "%s: %d processors listed, the run needs %d", p->path, l.nids, n);
      bad = 1;
    }
    for (int v = 0; !bad && v < n; v++) {
      if (l.ids[v] >= N) {
        snprintf(err, errlen, "%s:%d: processor %d: the machine has %d (0..%d)", p->path,
                 l.lines[v], l.ids[v], N, N - 1);
        bad = 1;
      }
      map[v] = l.ids[v];
    }
    free(l.ids), free(l.lines);
    if (bad) return -1;
    break;
  }
  }
  return 0;
}
