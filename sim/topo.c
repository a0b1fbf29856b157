/* topo.c -- topologies: sizes, link numbering, deterministic routes (topo.h says which). */
#include "sim/topo.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

struct topo {
  topo_kind kind;
  int N;            /* processors */
  int w, h;         /* mesh, torus, line (h = 1), ring (h = 1) */
  int deg;          /* links per processor: 2 on a single row, 4 on a grid; d on a hypercube */
  int d;            /* hypercube dimension */
  int k, n;         /* butterfly: arity and stages */
  int pow[32];      /* butterfly: k^0 .. k^n */
  int nlinks, max_hops;
};

static const char *const kind_names[] = {"none", "bus",   "full",      "line",     "ring",
                                         "mesh", "torus", "hypercube", "butterfly"};
enum { NKINDS = sizeof kind_names / sizeof *kind_names };

/* A whole decimal number in [lo, hi] spanning exactly s[0..len). */
static int whole(const char *s, size_t len, long lo, long hi, int *out) {
  if (len == 0 || len > 9) return -1;
  long v = 0;
  for (size_t i = 0; i < len; i++) {
    if (s[i] < '0' || s[i] > '9') return -1;
    v = v * 10 + (s[i] - '0');
  }
  if (v < lo || v > hi) return -1;
  *out = (int)v;
  return 0;
}

int topo_parse(const char *s, topo_spec *out, char *err, size_t errlen) {
  const char *colon = strchr(s, ':');
  size_t nlen = colon ? (size_t)(colon - s) : strlen(s);
  int kind = -1;
  for (int i = 1; i < NKINDS; i++)
    if (strlen(kind_names[i]) == nlen && strncmp(s, kind_names[i], nlen) == 0) kind = i;
  if (kind < 0) {
    snprintf(err, errlen,
             "unknown topology '%s': full, bus, line, ring, mesh:WxH, torus:WxH, hypercube:d "
             "or butterfly:k",
             s);
    return -1;
  }
  topo_spec sp = {(topo_kind)kind, 0, 0};
  if (colon) {
    const char *v = colon + 1;
    size_t vlen = strlen(v);
    int ok = 0;
    switch (sp.kind) {
    case TOPO_MESH:
    case TOPO_TORUS: {
      const char *x = memchr(v, 'x', vlen);
      ok = x && whole(v, (size_t)(x - v), 1, TOPO_MAX_NODES, &sp.a) == 0 &&
           whole(x + 1, vlen - (size_t)(x + 1 - v), 1, TOPO_MAX_NODES, &sp.b) == 0 &&
           (long)sp.a * sp.b <= TOPO_MAX_NODES;
      if (!ok) {
        snprintf(err, errlen, "topology '%s': %s:WxH takes two whole numbers from 1 up, W*H at most %d", s,
                 kind_names[kind], TOPO_MAX_NODES);
        return -1;
      }
      break;
    }
    case TOPO_HYPERCUBE:
      if (whole(v, vlen, 0, 22, &sp.a) != 0) {
        snprintf(err, errlen, "topology '%s': hypercube:d takes a dimension from 0 to 22", s);
        return -1;
      }
      break;
    case TOPO_BUTTERFLY:
      if (whole(v, vlen, 2, 4096, &sp.a) != 0) {
        snprintf(err, errlen, "topology '%s': butterfly:k takes a switch arity from 2 to 4096", s);
        return -1;
      }
      break;
    default:
      if (whole(v, vlen, 1, TOPO_MAX_NODES, &sp.a) != 0) {
        snprintf(err, errlen, "topology '%s': %s:N takes a number of processors from 1 to %d", s,
                 kind_names[kind], TOPO_MAX_NODES);
        return -1;
      }
    }
  }
  *out = sp;
  return 0;
}

void topo_spec_str(const topo_spec *sp, char *buf, size_t len) {
  const char *name = (unsigned)sp->kind < NKINDS ? kind_names[sp->kind] : "?";
  if (sp->kind == TOPO_NONE || sp->a == 0)
    snprintf(buf, len, "%s", name);
  else if (sp->kind == TOPO_MESH || sp->kind == TOPO_TORUS)
    snprintf(buf, len, "%s:%dx%d", name, sp->a, sp->b);
  else
    snprintf(buf, len, "%s:%d", name, sp->a);
}

topo *topo_new(const topo_spec *sp, int procs, char *err, size_t errlen) {
  if (procs < 1 || procs > TOPO_MAX_NODES) {
    snprintf(err, errlen, "topology: %d processors: need 1 to %d", procs, TOPO_MAX_NODES);
    return NULL;
  }
  topo t = {0};
  t.kind = sp->kind;
  long N = 0;
  switch (sp->kind) {
  case TOPO_BUS:
  case TOPO_FULL:
  case TOPO_LINE:
  case TOPO_RING:
    N = sp->a ? sp->a : procs;
    t.w = (int)N, t.h = 1;
    break;
  case TOPO_MESH:
  case TOPO_TORUS:
    if (sp->a) {
      t.w = sp->a, t.h = sp->b;
    } else {
      int w = 1;
      while ((long)w * w < procs) w++;
      t.w = w, t.h = (procs + w - 1) / w;
    }
    N = (long)t.w * t.h;
    break;
  case TOPO_HYPERCUBE:
    if (sp->a || procs == 1) {
      t.d = sp->a;
    } else {
      while ((1L << t.d) < procs) t.d++;
    }
    N = 1L << t.d;
    break;
  case TOPO_BUTTERFLY:
    t.k = sp->a ? sp->a : 2;
    N = 1;
    t.pow[0] = 1;
    while (N < procs) {
      N *= t.k;
      t.pow[++t.n] = (int)(N <= TOPO_MAX_NODES ? N : 0);
    }
    break;
  default:
    snprintf(err, errlen, "topology: no topology given");
    return NULL;
  }
  char name[64];
  topo_spec_str(sp, name, sizeof name);
  if (N > TOPO_MAX_NODES) {
    snprintf(err, errlen, "topology %s: %ld processors, more than %d", name, N, TOPO_MAX_NODES);
    return NULL;
  }
  if (N < procs) {
    snprintf(err, errlen, "topology %s has %ld processor%s; the run needs %d", name, N, N == 1 ? "" : "s", procs);
    return NULL;
  }
  t.N = (int)N;
  switch (t.kind) {
  case TOPO_BUS:
    t.nlinks = 1, t.max_hops = 1;
    break;
  case TOPO_FULL:
    t.nlinks = 2 * t.N, t.max_hops = 2;
    break;
  case TOPO_LINE:
  case TOPO_RING:
  case TOPO_MESH:
  case TOPO_TORUS:
    t.deg = t.h > 1 ? 4 : 2;
    t.nlinks = t.N * t.deg;
    t.max_hops = t.kind == TOPO_TORUS || t.kind == TOPO_RING ? t.w / 2 + t.h / 2
                                                              : t.w - 1 + t.h - 1;
    break;
  case TOPO_HYPERCUBE:
    t.deg = t.d;
    t.nlinks = t.N * t.d, t.max_hops = t.d;
    break;
  case TOPO_BUTTERFLY:
    t.nlinks = (t.n + 1) * t.N, t.max_hops = t.n + 1;
    break;
  default:
    break;
  }
  if (t.max_hops < 1) t.max_hops = 1;
  topo *p = xmalloc(sizeof *p);
  *p = t;
  return p;
}

void topo_free(topo *t) { free(t); }

topo_kind topo_kind_of(const topo *t) { return t->kind; }
int topo_nodes(const topo *t) { return t->N; }
int topo_nlinks(const topo *t) { return t->nlinks; }
int topo_max_hops(const topo *t) { return t->max_hops; }

/* Ports of a grid processor: the link id is processor * deg + port. */
enum { XPLUS, XMINUS, YPLUS, YMINUS };

/* One dimension of a grid route from coordinate a to b of a dimension of n
 * (wrapping on a torus or ring): the links, processor at * deg + port, where
 * the processor is base + a * stride.  Appends to links[h..]; the new h. */
static int walk(int deg, int base, int stride, int a, int b, int n, int plus, int minus, int wrap,
                int *links, int h) {
  if (a == b) return h;
  int up, steps;
  if (wrap) {
    int f = b - a < 0 ? b - a + n : b - a;   /* steps going up */
    up = 2 * f <= n;                         /* half way round goes up */
    steps = up ? f : n - f;
  } else {
    up = b > a;
    steps = up ? b - a : a - b;
  }
  if (up) {
    for (int i = 0; i < steps; i++) {
      links[h++] = (base + a * stride) * deg + plus;
      a = a + 1 == n ? 0 : a + 1;
    }
  } else {
    for (int i = 0; i < steps; i++) {
      links[h++] = (base + a * stride) * deg + minus;
      a = (a == 0 ? n : a) - 1;
    }
  }
  return h;
}

int topo_route(const topo *t, int s, int d, int *links) {
  int h = 0;
  switch (t->kind) {
  case TOPO_BUS:
    links[0] = 0;
    return 1;
  case TOPO_FULL:
    links[0] = s;
    links[1] = t->N + d;
    return 2;
  case TOPO_LINE:
  case TOPO_RING:
  case TOPO_MESH:
  case TOPO_TORUS: {
    int wrap = t->kind == TOPO_RING || t->kind == TOPO_TORUS, w = t->w;
    int sx = s % w, sy = s / w, dx = d % w, dy = d / w;
    h = walk(t->deg, sy * w, 1, sx, dx, w, XPLUS, XMINUS, wrap, links, h);   /* X first */
    return walk(t->deg, dx, w, sy, dy, t->h, YPLUS, YMINUS, wrap, links, h);  /* then Y */
  }
  case TOPO_HYPERCUBE: {
    int cur = s, diff = s ^ d;
    for (int b = 0; b < t->d; b++)
      if (diff >> b & 1) {
        links[h++] = cur * t->d + b;
        cur ^= 1 << b;
      }
    return h;
  }
  case TOPO_BUTTERFLY:
    for (int l = 0; l <= t->n; l++) {
      int hi = t->pow[t->n - l];
      links[h++] = l * t->N + d / hi * hi + s % hi;
    }
    return h;
  default:
    xpanic("topo_route: no topology");
  }
}

int topo_link_exists(const topo *t, int l) {
  if (l < 0 || l >= t->nlinks) return 0;
  if (t->kind != TOPO_LINE && t->kind != TOPO_RING && t->kind != TOPO_MESH &&
      t->kind != TOPO_TORUS)
    return 1;
  int node = l / t->deg, port = l % t->deg, x = node % t->w, y = node / t->w;
  int wrap = t->kind == TOPO_RING || t->kind == TOPO_TORUS;
  switch (port) {
  case XPLUS: return wrap ? t->w > 1 : x < t->w - 1;
  case XMINUS: return wrap ? t->w > 2 : x > 0;   /* a 2-ring goes up only */
  case YPLUS: return wrap ? t->h > 1 : y < t->h - 1;
  default: return wrap ? t->h > 2 : y > 0;
  }
}

/* The processor at the far end of grid link l. */
static int grid_next(const topo *t, int l) {
  int node = l / t->deg, port = l % t->deg, x = node % t->w, y = node / t->w;
  switch (port) {
  case XPLUS: x = (x + 1) % t->w; break;
  case XMINUS: x = (x + t->w - 1) % t->w; break;
  case YPLUS: y = (y + 1) % t->h; break;
  default: y = (y + t->h - 1) % t->h; break;
  }
  return x + y * t->w;
}

void topo_link_name(const topo *t, int l, char *buf, size_t len) {
  switch (t->kind) {
  case TOPO_BUS:
    snprintf(buf, len, "bus");
    break;
  case TOPO_FULL:
    if (l < t->N) snprintf(buf, len, "%d>sw", l);
    else snprintf(buf, len, "sw>%d", l - t->N);
    break;
  case TOPO_HYPERCUBE:
    snprintf(buf, len, "%d>%d", l / t->d, (l / t->d) ^ (1 << (l % t->d)));
    break;
  case TOPO_BUTTERFLY: {
    int level = l / t->N, w = l % t->N;
    if (level == 0) snprintf(buf, len, "in %d", w);
    else if (level == t->n) snprintf(buf, len, "out %d", w);
    else snprintf(buf, len, "L%d w%d", level, w);
    break;
  }
  default:
    snprintf(buf, len, "%d>%d", l / t->deg, grid_next(t, l));
  }
}

int topo_grid(const topo *t, int *w, int *h) {
  int grid = t->kind == TOPO_LINE || t->kind == TOPO_RING || t->kind == TOPO_MESH ||
             t->kind == TOPO_TORUS;
  *w = grid ? t->w : t->N;
  *h = grid ? t->h : 1;
  return grid;
}
