/* test_keyhole.c -- the keyhole repair (geom/keyhole.h) against the loops a
 * keyhole contour is built from: annuli, a rectangle with k holes joined in
 * a chain or a star, an island in a hole, two pieces joined by a channel,
 * channels with extra collinear points on one side, the other or both,
 * from every start point and in both windings; and contours that are no
 * keyhole (a figure eight, a spike, a vertex on an edge, a crossing, a
 * channel across another loop, channels that cross) refused.  Through the
 * reader and the stack (surface/stack.h): a stack of keyhole contours, any
 * start, either winding, gives byte-identical meshes and rows to the same
 * region given as separate contours; the reader's note, lines, refusals,
 * and CONTOUR_NO_KEYHOLES. */
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "tests/check.h"
#include "input/contour.h"
#include "geom/exact.h"
#include "geom/keyhole.h"
#include "surface/mesh.h"
#include "surface/stack.h"
#include "util/xmem.h"

/* ------------------------------------------------ the keyhole generator -- */

enum { MAXL = 12, MAXP = 64, MAXW = 4096 };

/* A tree of loops: loop i > 0 hangs off loop parent[i] by a channel from its
 * point pv[i] to the child's point cv[i], with eo extra points on the way
 * out and eb on the way back (at fractions j / (e + 1): exact for e = 1, 3). */
typedef struct {
  int nl;
  int n[MAXL];
  vec2 p[MAXL][MAXP];
  int parent[MAXL], pv[MAXL], cv[MAXL], eo[MAXL], eb[MAXL];
  double channel;   /* the channels' total length */
  const char *name;
} shape;

static void emit(vec2 *w, int *nw, vec2 q) {
  if (*nw < MAXW) w[(*nw)++] = q;
}

static vec2 along(vec2 a, vec2 b, int j, int e) {
  double t = (double)j / (e + 1);
  return (vec2){a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t};
}

/* Walk loop i from its point `start` once round, each child's loop on the
 * way where it hangs off. */
static void walk(const shape *s, int i, int start, vec2 *w, int *nw) {
  for (int k = 0; k < s->n[i]; k++) {
    int v = (start + k) % s->n[i];
    vec2 a = s->p[i][v];
    emit(w, nw, a);
    for (int c = 1; c < s->nl; c++) {
      if (s->parent[c] != i || s->pv[c] != v) continue;
      vec2 b = s->p[c][s->cv[c]];
      for (int j = 1; j <= s->eo[c]; j++) emit(w, nw, along(a, b, j, s->eo[c]));
      walk(s, c, s->cv[c], w, nw);
      emit(w, nw, b);
      for (int j = 1; j <= s->eb[c]; j++) emit(w, nw, along(b, a, j, s->eb[c]));
      emit(w, nw, a);
    }
  }
}

static void add_loop(shape *s, const vec2 *p, int n, int parent, int pv, int cv) {
  int i = s->nl++;
  s->n[i] = n;
  memcpy(s->p[i], p, (size_t)n * sizeof *p);
  s->parent[i] = parent, s->pv[i] = pv, s->cv[i] = cv, s->eo[i] = s->eb[i] = 0;
  if (parent >= 0) {
    vec2 a = s->p[parent][pv], b = p[cv];
    s->channel += hypot(b.x - a.x, b.y - a.y);
  }
}

/* A circle of n points of radius r, rounded to integers, either way round. */
static void circle(vec2 *p, int n, double r, int cw) {
  for (int k = 0; k < n; k++) {
    double t = 2 * 3.14159265358979323846 * k / n * (cw ? -1 : 1);
    p[k] = (vec2){round(r * cos(t)), round(r * sin(t))};
  }
}

/* A square [x0, x0 + 2h] x [y0, y0 + 2h] with its corners and midpoints,
 * from its bottom midpoint, counter-clockwise or clockwise. */
static void square8(vec2 *p, double x0, double y0, double h, int cw) {
  static const int ccw[8][2] = {{1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}, {0, 0}};
  for (int k = 0; k < 8; k++) {
    int j = cw ? (8 - k) % 8 : k;
    p[k] = (vec2){x0 + h * ccw[j][0], y0 + h * ccw[j][1]};
  }
}

static int make_shapes(shape *sh) {
  int ns = 0;
  vec2 a[MAXP], b[MAXP];
  /* Annuli: the channel at angle 0, and at 90 degrees. */
  for (int v = 0; v < 2; v++) {
    shape *s = &sh[ns++];
    memset(s, 0, sizeof *s);
    s->name = v ? "annulus, channel at 90 degrees" : "annulus";
    circle(a, 24, 100, 0), circle(b, 16, 40, 1);
    add_loop(s, a, 24, -1, 0, 0);
    add_loop(s, b, 16, 0, v ? 6 : 0, v ? 12 : 0);
  }
  /* A rectangle with k holes: a star (each from the bottom edge) and a
   * chain (the first from the bottom edge, each next from its left). */
  for (int chain = 0; chain < 2; chain++)
    for (int k = 1; k <= 4; k += 3) {
      shape *s = &sh[ns++];
      memset(s, 0, sizeof *s);
      s->name = chain ? "holes in a chain" : "holes in a star";
      int m = 0;
      for (int x = 0; x <= 4 * k + 2; x++) a[m++] = (vec2){x, 0};
      a[m++] = (vec2){4 * k + 2, 6}, a[m++] = (vec2){0, 6};
      add_loop(s, a, m, -1, 0, 0);
      for (int i = 0; i < k; i++) {
        square8(b, 4 * i + 2, 2, 1, 1);   /* from (4i+3, 2), clockwise: 2 is (4i+2, 3), 6 (4i+4, 3) */
        if (chain && i > 0) add_loop(s, b, 8, i, 6, 2);
        else add_loop(s, b, 8, 0, 4 * i + 3, 0);
      }
    }
  /* An island in a hole: by the hole's top, and from the hole's point
   * where the hole's own channel arrives (two channels at one point). */
  for (int v = 0; v < 2; v++) {
    shape *s = &sh[ns++];
    memset(s, 0, sizeof *s);
    s->name = v ? "island in a hole, channels meeting" : "island in a hole";
    square8(a, 0, 0, 6, 0), add_loop(s, a, 8, -1, 0, 0);
    square8(b, 2, 2, 4, 1), add_loop(s, b, 8, 0, 0, 0);   /* (6,0) to (6,2) */
    square8(a, 5, 5, 1, 0);                              /* 0 (6,5), 4 (6,7) */
    if (v) add_loop(s, a, 8, 1, 0, 0);                   /* (6,2) to (6,5) */
    else add_loop(s, a, 8, 1, 4, 4);                     /* hole's (6,10) to (6,7) */
  }
  /* Two pieces, and three, joined by channels. */
  {
    shape *s = &sh[ns++];
    memset(s, 0, sizeof *s);
    s->name = "pieces joined";
    square8(a, 0, 0, 2, 0), add_loop(s, a, 8, -1, 0, 0);
    square8(b, 6, 0, 2, 0), add_loop(s, b, 8, 0, 3, 5);  /* (4,4) to (6,4) */
    square8(b, 0, 6, 2, 0), add_loop(s, b, 8, 0, 5, 0);  /* (0,4) to (2,6) */
  }
  return ns;
}

/* ------------------------------------------------------- loops compared -- */

/* A loop as a canonical sequence: from its least point, in the direction of
 * its lesser neighbour (so either winding and any start compare equal). */
static void canon(const vec2 *p, int n, vec2 *out) {
  int k = 0;
  for (int i = 1; i < n; i++)
    if (exact_lex(p[i], p[k]) < 0) k = i;
  int dir = exact_lex(p[(k + 1) % n], p[(k + n - 1) % n]) < 0 ? 1 : -1;
  for (int i = 0; i < n; i++) out[i] = p[((k + dir * i) % n + n) % n];
}

static int same_loop(const vec2 *p, int n, const vec2 *q, int m) {
  if (n != m) return 0;
  vec2 a[MAXW], b[MAXW];
  canon(p, n, a), canon(q, m, b);
  return memcmp(a, b, (size_t)n * sizeof *a) == 0;
}

/* The repair of s's walk from every start point, both ways round: its loops
 * are s's loops (each once), and the channels' count and length. */
static void check_shape(const shape *s) {
  static vec2 w[MAXW], r[MAXW];
  int nw = 0;
  walk(s, 0, 0, w, &nw);
  CHECK(nw < MAXW, "%s: walk too long", s->name);
  int fails = 0;
  for (int rev = 0; rev < 2; rev++)
    for (int st = 0; st < nw; st++) {
      for (int i = 0; i < nw; i++) r[i] = w[rev ? (st - i + 2 * nw) % nw : (st + i) % nw];
      keyhole_split ks;
      if (!keyhole_repair(r, nw, &ks)) {
        if (fails++ < 3) CHECK(0, "%s (start %d%s): not repaired", s->name, st, rev ? ", reversed" : "");
        continue;
      }
      int ok = ks.nloops == s->nl, used[MAXL] = {0};
      for (int l = 0; l < ks.nloops && ok; l++) {
        int found = 0;
        for (int j = 0; j < s->nl && !found; j++)
          if (!used[j] && same_loop(ks.pt + ks.first[l], ks.first[l + 1] - ks.first[l], s->p[j], s->n[j]))
            used[j] = found = 1;
        ok = found;
      }
      /* Each loop in the walk's direction: its points follow each other in r. */
      for (int l = 0; l < ks.nloops && ok; l++) {
        int f = ks.first[l], m = ks.first[l + 1] - f;
        for (int j = 0; j < m && ok; j++) ok = ks.src[f + j] >= 0 && ks.src[f + j] < nw &&
                                                exact_lex(r[ks.src[f + j]], ks.pt[f + j]) == 0;
      }
      ok = ok && ks.channels == s->nl - 1 && fabs(ks.length - s->channel) <= 1e-12 * s->channel;
      if (!ok && fails++ < 3)
        CHECK(0, "%s (start %d%s): %d loops, %d channels of length %.17g; want %d loops, %d channels of %.17g",
              s->name, st, rev ? ", reversed" : "", ks.nloops, ks.channels, ks.length, s->nl, s->nl - 1, s->channel);
      keyhole_free(&ks);
    }
  CHECK(fails == 0, "%s: %d of %d walks wrong", s->name, fails, 2 * nw);
}

static void generated(void) {
  static shape sh[16];
  int ns = make_shapes(sh);
  static const int extra[][2] = {{0, 0}, {1, 0}, {0, 3}, {1, 1}, {3, 1}};
  for (int i = 0; i < ns; i++)
    for (int e = 0; e < 5; e++) {
      shape s = sh[i];
      for (int c = 1; c < s.nl; c++) s.eo[c] = extra[e][0], s.eb[c] = extra[e][1];
      check_shape(&s);
    }
}

/* -------------------------------------------------------- not keyholes -- */

typedef struct {
  const char *what;
  int n;
  vec2 p[32];
} poly;

static void refused(void) {
  static const poly cases[] = {
      {"a figure eight sharing a point", 6, {{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}}},
      {"a spur crossing the contour", 7, {{0, 0}, {2, 0}, {2, 6}, {2, 0}, {4, 0}, {4, 4}, {0, 4}}},
      {"a spur whose tip touches an edge", 7, {{0, 0}, {4, 0}, {4, 4}, {2, 4}, {2, 0}, {2, 4}, {0, 4}}},
      {"an edge walked over twice one way", 6, {{0, 0}, {3, 0}, {3, 1}, {-1, 1}, {-1, 0}, {1, 0}}},
      {"a vertex on an edge", 5, {{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}}},
      {"a bowtie", 4, {{0, 0}, {1, 1}, {1, 0}, {0, 1}}},
      {"a hole touching its outer boundary", 8, {{0, 0}, {8, 0}, {8, 8}, {0, 8}, {0, 0}, {0, 4}, {4, 4}, {4, 0}}},
      {"a hole whose channel runs on along the outer edge", 9,
       {{0, 0}, {4, 0}, {8, 0}, {8, 8}, {0, 8}, {0, 0}, {4, 0}, {4, 2}, {2, 2}}},
      {"a channel across a hole's edge to an island", 20,
       {{0, 0}, {6, 0}, {6, 5}, {7, 5}, {7, 7}, {5, 7}, {5, 5}, {6, 5}, {6, 0}, {12, 0}, {12, 12}, {0, 12},
        {0, 6}, {2, 6}, {2, 10}, {10, 10}, {10, 2}, {2, 2}, {2, 6}, {0, 6}}},
      {"two channels crossing", 16,
       {{0, 0}, {6, 6}, {6, 8}, {8, 8}, {8, 6}, {6, 6}, {0, 0}, {10, 0}, {4, 6}, {2, 6}, {2, 8}, {4, 8},
        {4, 6}, {10, 0}, {10, 10}, {0, 10}}},
  };
  int n = (int)(sizeof cases / sizeof cases[0]);
  for (int i = 0; i < n; i++) {
    keyhole_split ks;
    int got = keyhole_repair(cases[i].p, cases[i].n, &ks);
    CHECK(!got, "%s: repaired into %d loops", cases[i].what, ks.nloops);
    if (got) keyhole_free(&ks);
  }
}

/* ---------------------------------------------------------------- spurs -- */

/* Zero-width spurs (a spike walked out and back along itself) enclose no
 * area and are dropped like channels: a square with spurs out,
 * in, along an edge's line, with extra points on the way out or back, a
 * spur off a keyhole's outer boundary and one off a channel; from every
 * start point, both ways round: the loops left are the square (and the
 * hole), the spurs' count and length. */
typedef struct {
  const char *what;
  int n;
  vec2 p[24];
  int nloops, spurs, channels;
  double spur_length, area2;   /* the spurs' length; twice the loops' areas, summed */
} spurred;

static double area2(const vec2 *p, int n);

static void spurs(void) {
  static const spurred cases[] = {
      {"a spur out of a square", 7, {{0, 0}, {4, 0}, {4, 2}, {7, 2}, {4, 2}, {4, 4}, {0, 4}}, 1, 1, 0, 3, 32},
      {"a spur into a square", 7, {{0, 0}, {4, 0}, {4, 2}, {1, 2}, {4, 2}, {4, 4}, {0, 4}}, 1, 1, 0, 3, 32},
      {"a spike walked out and back", 4, {{0, 0}, {2, 0}, {1, 0}, {1, 1}}, 1, 1, 0, 1, 1},
      {"a spur with points on the way out", 9,
       {{0, 0}, {4, 0}, {4, 2}, {5, 2}, {6, 2}, {7, 2}, {4, 2}, {4, 4}, {0, 4}}, 1, 1, 0, 3, 32},
      {"a spur with points on the way back", 9,
       {{0, 0}, {4, 0}, {4, 2}, {7, 2}, {6, 2}, {5, 2}, {4, 2}, {4, 4}, {0, 4}}, 1, 1, 0, 3, 32},
      {"two spurs at one point", 9, {{0, 0}, {4, 0}, {4, 2}, {7, 2}, {4, 2}, {7, 6}, {4, 2}, {4, 4}, {0, 4}},
       1, 2, 0, 8, 32},
      {"a triangle's edge walked back", 5, {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {4, 0}}, 1, 1, 0, 4, 16},
      {"a spur back along an edge's line", 6, {{0, 0}, {4, 0}, {6, 0}, {4, 0}, {4, 4}, {0, 4}}, 1, 1, 0, 2, 32},
      {"a spur off a keyhole's outer boundary", 13,
       {{0, 0}, {4, 0}, {4, -2}, {4, 0}, {8, 0}, {8, 8}, {0, 8}, {0, 0}, {2, 2}, {2, 6}, {6, 6}, {6, 2}, {2, 2}},
       2, 1, 1, 2, 160},
      {"a spur off a channel", 13,
       {{0, 0}, {1, 1}, {1, 0.5}, {1, 1}, {2, 2}, {2, 6}, {6, 6}, {6, 2}, {2, 2}, {0, 0}, {8, 0}, {8, 8}, {0, 8}},
       2, 0, 1, 0, 160},
  };
  int n = (int)(sizeof cases / sizeof cases[0]);
  for (int i = 0; i < n; i++) {
    const spurred *c = &cases[i];
    int fails = 0;
    for (int rev = 0; rev < 2; rev++)
      for (int st = 0; st < c->n; st++) {
        vec2 r[24];
        for (int k = 0; k < c->n; k++) r[k] = c->p[rev ? (st - k + 2 * c->n) % c->n : (st + k) % c->n];
        keyhole_split ks;
        if (!keyhole_repair(r, c->n, &ks)) {
          if (fails++ < 2) CHECK(0, "%s (start %d%s): refused", c->what, st, rev ? ", reversed" : "");
          continue;
        }
        int ok = ks.nloops == c->nloops && ks.spurs == c->spurs && ks.channels == c->channels &&
                 ks.spur_length == c->spur_length;
        /* The loops left enclose what the contour does. */
        double area = 0;
        for (int l = 0; l < ks.nloops; l++) area += fabs(area2(ks.pt + ks.first[l], ks.first[l + 1] - ks.first[l]));
        double want = c->area2;
        ok = ok && area == want;
        if (!ok && fails++ < 2)
          CHECK(0, "%s (start %d%s): %d loops, %d spurs (length %g), %d channels, twice the area %g; want %d, %d "
                "(%g), %d, %g", c->what, st, rev ? ", reversed" : "", ks.nloops, ks.spurs, ks.spur_length,
                ks.channels, area, c->nloops, c->spurs, c->spur_length, c->channels, want);
        keyhole_free(&ks);
      }
    CHECK(fails == 0, "%s: %d of %d walks wrong", c->what, fails, 2 * c->n);
  }
}

/* ------------------------------------------------------ large contours -- */

/* The watchdog: a repair that runs this long has gone quadratic or worse. */
enum { WATCHDOG_S = 60 };

static void on_alarm(int sig) {
  (void)sig;
  static const char msg[] = "test_keyhole: a large contour's repair ran past the watchdog\n";
  ssize_t w = write(2, msg, sizeof msg - 1);
  (void)w;
  _exit(1);
}

static double area2(const vec2 *p, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += p[i].x * p[(i + 1) % n].y - p[i].y * p[(i + 1) % n].x;
  return s;
}

static long peak_kb(void) {
  struct rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;   /* KiB on Linux */
}

/* K nested edges on one line walked to and fro (the polygon runs right
 * along y = 0 over [i, 4K - i], up, over, down to the next): edges the same
 * way overlap, so it is no keyhole, and the repair must say so without
 * first inserting every end into every opposite edge (O(K^2) points a
 * round, O(K^3) in all: 1.3 GB for K = 400).  Run first, so the peak
 * resident size measures it. */
static void nested(void) {
  enum { K = 300 };
  vec2 *p = xmallocarray(3 * K, sizeof *p);
  int n = 0;
  for (int i = 0; i < K; i++) {
    double a = i, b = 4.0 * K - i;
    if (i % 2 == 0) p[n++] = (vec2){a, 0}, p[n++] = (vec2){b, 0}, p[n++] = (vec2){b, 1 + i};
    else p[n++] = (vec2){b, 0}, p[n++] = (vec2){a, 0}, p[n++] = (vec2){a, -1 - i};
  }
  long before = peak_kb();
  keyhole_split ks;
  int got = keyhole_repair(p, n, &ks);
  long grew = peak_kb() - before;
  CHECK(!got, "%d nested edges walked to and fro: repaired into %d loops", K, ks.nloops);
  if (got) keyhole_free(&ks);
  CHECK(grew < 64 * 1024, "%d nested edges walked to and fro: the peak resident size grew by %ld KiB", K, grew);
  free(p);
}

/* A rectangle with K square holes, each joined to the bottom edge by a
 * channel of its own (100,000 points for K = 12,500; MIM-like, but many
 * channels): the loops against the closed forms, K holes of area 4, the
 * outer rectangle, K channels of length 2.  Each channel piece against every
 * loop edge was O(K N). */
static void many_channels(void) {
  enum { K = 50000 };
  vec2 *p = xmallocarray(8 * (size_t)K + 4, sizeof *p);
  int n = 0;
  for (int i = 0; i < K; i++) {
    double x = 4 * i + 2;   /* up the channel, the hole clockwise, down again */
    p[n++] = (vec2){x, 0}, p[n++] = (vec2){x, 2}, p[n++] = (vec2){x - 1, 2}, p[n++] = (vec2){x - 1, 4};
    p[n++] = (vec2){x + 1, 4}, p[n++] = (vec2){x + 1, 2}, p[n++] = (vec2){x, 2}, p[n++] = (vec2){x, 0};
  }
  p[n++] = (vec2){4.0 * K + 2, 0}, p[n++] = (vec2){4.0 * K + 2, 6}, p[n++] = (vec2){0, 6}, p[n++] = (vec2){0, 0};
  keyhole_split ks;
  int got = keyhole_repair(p, n, &ks);
  CHECK(got, "%d holes each by a channel: refused", K);
  if (got) {
    int holes = 0, outer = 0, other = 0;
    for (int l = 0; l < ks.nloops; l++) {
      int f = ks.first[l], m = ks.first[l + 1] - f;
      double a = area2(ks.pt + f, m);
      if (m == 5 && a == -8) holes++;
      else if (m == K + 4 && a == 2 * 6 * (4.0 * K + 2)) outer++;
      else other++;
    }
    CHECK(ks.nloops == K + 1 && holes == K && outer == 1 && other == 0,
          "%d loops: %d holes, %d outer, %d other (want %d holes and the rectangle)", ks.nloops, holes, outer, other, K);
    CHECK(ks.channels == K && ks.length == 2.0 * K, "%d channels of length %.17g (want %d of %d)", ks.channels,
          ks.length, K, 2 * K);
    keyhole_free(&ks);
  }
  free(p);
}

static void large(void) {
  signal(SIGALRM, on_alarm);
  alarm(WATCHDOG_S);
  nested();
  many_channels();
  alarm(0);
}

/* ------------------------------------------- through reader and stack -- */

typedef struct {
  char *buf;
  size_t len, cap;
} text;

static void put(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(text *t, const char *fmt, ...) {
  va_list ap;
  char line[256];
  va_start(ap, fmt);
  int k = vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  if (t->len + (size_t)k + 1 > t->cap) {
    t->cap = 2 * (t->len + (size_t)k + 1);
    t->buf = xrealloc(t->buf, t->cap);
  }
  memcpy(t->buf + t->len, line, (size_t)k + 1);
  t->len += (size_t)k;
}

static void put_contour(text *t, const vec2 *p, int n, double z, int start, int rev) {
  put(t, "C %d %g\n", n, z);
  for (int i = 0; i < n; i++) {
    vec2 q = p[rev ? ((start - i) % n + n) % n : (start + i) % n];
    put(t, "%.17g %.17g\n", q.x, q.y);
  }
}

/* Tile a stack text with flat caps: 0 and *ss, or -1 with the message. */
static int tile_text(const text *t, int flags, stack_surface **ss, char *err, size_t errlen, char *notes,
                     size_t nlen) {
  contour_stack s;
  FILE *f = fmemopen(notes, nlen, "w");
  int rc = contour_parse_flags(t->buf, t->len, "k.contours", flags, &s, f, "tile", err, errlen);
  fclose(f);
  if (rc != 0) return -1;
  stack_options o = {COST_AREA, 1, 0, 1, NULL, NULL, "test", NULL, NULL, MATCH_SINGLE, INFINITY, 0, STACK_BAND_ALIGNED};
  rc = stack_tile(&s, "k.contours", &o, ss, err, errlen);
  contour_stack_free(&s);
  return rc;
}

static int same_rows(const stack_surface *a, const stack_surface *b) {
  if (stack_nrows(a) != stack_nrows(b)) return 0;
  for (int i = 0; i < stack_nrows(a); i++) {
    const stack_row *x = &stack_rows(a)[i], *y = &stack_rows(b)[i];
    if (x->kind != y->kind || x->slice0 != y->slice0 || x->slice1 != y->slice1 || x->depth != y->depth ||
        x->nlo != y->nlo || x->nhi != y->nhi || x->m != y->m || x->n != y->n || x->bridges != y->bridges ||
        memcmp(&x->cost, &y->cost, sizeof x->cost) || memcmp(&x->area, &y->area, sizeof x->area) ||
        memcmp(&x->volume, &y->volume, sizeof x->volume) || x->nodes != y->nodes || x->spans != y->spans)
      return 0;
    for (int k = 0; k < x->nlo; k++)
      if (x->lo[k] != y->lo[k]) return 0;
    for (int k = 0; k < x->nhi; k++)
      if (x->hi[k] != y->hi[k]) return 0;
  }
  return 1;
}

static int same_mesh(const mesh *a, const mesh *b) {
  return a->nv == b->nv && a->nt == b->nt && memcmp(a->v, b->v, (size_t)a->nv * sizeof *a->v) == 0 &&
         memcmp(a->t, b->t, (size_t)a->nt * sizeof *a->t) == 0;
}

/* Each shape on three slices (the middle one shifted and shrunk a little,
 * so that bands are not trivial): once as separate contours, and as keyhole
 * contours from a range of starts, both windings, with extra points on the
 * channels. */
static void stacks(void) {
  static shape sh[16];
  int ns = make_shapes(sh);
  static const int extra[][2] = {{0, 0}, {1, 0}, {0, 3}, {1, 1}};
  static vec2 w[MAXW];
  char err[512], notes[4096];
  for (int i = 0; i < ns; i++) {
    text sep = {0};
    for (int z = 0; z < 3; z++)
      for (int l = 0; l < sh[i].nl; l++) put_contour(&sep, sh[i].p[l], sh[i].n[l], z, 0, l % 2);
    stack_surface *ref = NULL;
    int rc = tile_text(&sep, 0, &ref, err, sizeof err, notes, sizeof notes);
    CHECK(rc == 0, "%s as separate contours: %s", sh[i].name, err);
    int bad = 0, tried = 0;
    for (int e = 0; e < 4 && rc == 0; e++) {
      shape s = sh[i];
      for (int c = 1; c < s.nl; c++) s.eo[c] = extra[e][0], s.eb[c] = extra[e][1];
      int nw = 0;
      walk(&s, 0, 0, w, &nw);
      for (int st = e; st < nw; st += 5)
        for (int rev = 0; rev < 2; rev++) {
          text kh = {0};
          for (int z = 0; z < 3; z++) put_contour(&kh, w, nw, z, (st + 7 * z) % nw, rev ^ (z == 1));
          stack_surface *ss = NULL;
          tried++;
          if (tile_text(&kh, 0, &ss, err, sizeof err, notes, sizeof notes) != 0) {
            if (bad++ < 3) CHECK(0, "%s, start %d%s: %s", s.name, st, rev ? " reversed" : "", err);
          } else if (!same_mesh(stack_mesh(ss), stack_mesh(ref)) || !same_rows(ss, ref)) {
            if (bad++ < 3) CHECK(0, "%s, start %d%s: not the mesh or rows of the separate contours", s.name, st,
                                 rev ? " reversed" : "");
          }
          if (ss) stack_free(ss);
          free(kh.buf);
        }
    }
    CHECK(bad == 0, "%s: %d of %d keyhole stacks differ from the separate contours'", sh[i].name, bad, tried);
    if (ref) stack_free(ref);
    free(sep.buf);
  }
}

/* The reader: the note names the header line; the loops, the lines of their
 * first points; with CONTOUR_NO_KEYHOLES today's refusal. */
static void reader(void) {
  static const char two[] =
      "C 10 0\n0 0\n8 0\n8 8\n0 8\n0 0\n2 2\n2 6\n6 6\n6 2\n2 2\n"   /* lines 1-11 */
      "C 4 1\n0 0\n8 0\n8 8\n0 8\n";
  contour_stack s;
  char err[512], notes[4096];
  FILE *f = fmemopen(notes, sizeof notes, "w");
  int rc = contour_parse(two, strlen(two), "k.contours", &s, f, "tile", err, sizeof err);
  fclose(f);
  CHECK(rc == 0, "keyhole stack refused: %s", err);
  if (rc == 0) {
    CHECK(s.n == 3 && s.nslices == 2, "%d contours on %d slices, want 3 on 2", s.n, s.nslices);
    CHECK(s.n == 3 && s.c[0].n == 4 && s.c[1].n == 4 && s.c[0].line == 2 && s.c[1].line == 7 && s.c[2].line == 12,
          "loops of %d and %d points at lines %d and %d (want 4, 4 at 2, 7)", s.c[0].n, s.c[1].n, s.c[0].line,
          s.c[1].line);
    CHECK(strstr(notes, "tile: k.contours:1: keyhole: the contour split into 2 loops at (0 0), a channel of "
                        "length 2.8284271247461903 dropped\n") != NULL,
          "note: %s", notes);
    contour_stack_free(&s);
  }
  rc = contour_parse_flags(two, strlen(two), "k.contours", CONTOUR_NO_KEYHOLES, &s, NULL, "tile", err, sizeof err);
  CHECK(rc == -1 && strncmp(err, "k.contours:1: the contour crosses itself: the segment from line ", 64) == 0,
        "with CONTOUR_NO_KEYHOLES: %d '%s'", rc, err);
  /* A channel 1e-6 wide is no keyhole: one contour, as it is. */
  static const char narrow[] = "C 10 0\n1e-6 0\n8 0\n8 8\n0 8\n0 0\n2 2\n2 6\n6 6\n6 2\n2.000001 2\n"
                               "C 4 1\n0 0\n8 0\n8 8\n0 8\n";
  rc = contour_parse(narrow, strlen(narrow), "k.contours", &s, NULL, "tile", err, sizeof err);
  CHECK(rc == 0 && s.n == 2 && s.c[0].n == 10, "a narrow channel: %d, %d contours", rc, rc == 0 ? s.n : 0);
  if (rc == 0) contour_stack_free(&s);
}

int main(void) {
  large();
  generated();
  spurs();
  refused();
  stacks();
  reader();
  return check_done("test_keyhole");
}
