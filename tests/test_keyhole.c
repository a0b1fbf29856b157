/* test_keyhole.c -- the keyhole repair (algo/keyhole.h) against the loops a
 * keyhole contour is built from: annuli, a rectangle with k holes joined in
 * a chain or a star, an island in a hole, two pieces joined by a channel,
 * channels with extra collinear points on one side, the other or both,
 * from every start point and in both windings; and contours that are no
 * keyhole (a figure eight, a spike, a vertex on an edge, a crossing, a
 * channel across another loop, channels that cross) refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "exact.h"
#include "keyhole.h"
#include "xmem.h"

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
      {"a spike walked out and back", 4, {{0, 0}, {2, 0}, {1, 0}, {1, 1}}},
      {"a spike off a keyhole's outer boundary", 13,
       {{0, 0}, {4, 0}, {4, -2}, {4, 0}, {8, 0}, {8, 8}, {0, 8}, {0, 0}, {2, 2}, {2, 6}, {6, 6}, {6, 2}, {2, 2}}},
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

int main(void) {
  generated();
  refused();
  return check_done("test_keyhole");
}
