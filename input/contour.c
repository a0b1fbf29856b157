/* contour.c -- the contour builder (checking and repairing contours,
 * grouping them into slices), the .contours reader that fills it, and the
 * writer.
 *
 * Everything is validated before any work: each error names the file, the
 * line and the offending value.  What users expect to be repaired is repaired
 * and reported: a repeated closing point, consecutive duplicate points,
 * clockwise contours (every contour is made counter-clockwise seen from +z, so
 * both contours of a pair run the same way and the band does not twist; with
 * several contours on a slice surface/ orients them by nesting instead), and
 * z values that differ by jitter within one slice (snapped to one value). */
#include "input/contour.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "geom/crossing.h"
#include "geom/keyhole.h"
#include "input/slicemerge.h"
#include "util/readfile.h"
#include "util/shown.h"
#include "util/strbuf.h"
#include "util/xmem.h"

/* A contour the reader cannot use (too few points, collinear, crossing
 * itself and no keyhole): named, then refused with the others or dropped. */
typedef struct {
  int line, points;
  char *why;         /* "the contour crosses itself: ..." */
} bad_contour;

/* A contour as read, before repair. */
typedef struct {
  double z;
  int line, have;         /* its place, points read */
  vec2 *pt;
  int *ptline;            /* place of each point, for notes */
  int cap;
} raw;

struct contour_build {
  const contour_places *pl;
  char *err;
  size_t errlen;
  const char *prefix;
  int flags;
  strbuf out;        /* the notes of the contours accepted so far, in order */
  strbuf cur;        /* the current contour's notes, until it is accepted */
  strbuf *to;        /* where note() writes */
  bad_contour *bad;
  int nbad, capbad;
  int ndegen, degen_line;   /* CONTOUR_DROP_DEGENERATE: contours dropped, the first's line */
  long degen_points;
  char *degen_why;          /* the first's reason */
  contour *cs;              /* the contours accepted (a keyhole contour: its loops) */
  int ncs, capcs;
  raw c;                    /* the contour being read */
  int nread;                /* contours ended */
  long points;              /* their points */
};

typedef contour_build reader;   /* the builder, as its helpers below call it */

/* "HEAD: what" in err[0..errlen-1]. */
static int vfail(const contour_places *pl, char *err, size_t errlen, int line, const char *fmt, va_list ap) {
  strbuf b = {0};
  pl->head(pl->ud, &b, line);
  strbuf_raw(&b, ": ", 2);
  strbuf_vadd(&b, fmt, ap);
  snprintf(err, errlen, "%s", b.buf);
  free(b.buf);
  return -1;
}

static int fail(reader *r, int line, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail(r->pl, r->err, r->errlen, line, fmt, ap);
  va_end(ap);
  return -1;
}

static void note(reader *r, int line, const char *fmt, ...) {
  va_list ap;
  strbuf_add(r->to, "%s: ", r->prefix);
  r->pl->head(r->pl->ud, r->to, line);
  strbuf_raw(r->to, ": ", 2);
  va_start(ap, fmt);
  strbuf_vadd(r->to, fmt, ap);
  va_end(ap);
  strbuf_raw(r->to, "\n", 1);
}

const char *contour_place_at(const contour_places *pl, int line, int head, contour_place *p) {
  pl->ref(pl->ud, p->s, sizeof p->s, line, head);
  return p->s;
}

static const char *at(const reader *r, int line, int head, contour_place *p) {
  return contour_place_at(r->pl, line, head, p);
}

/* ---------------------------------------------------------------- files */

static void file_head(void *ud, strbuf *b, int line) {
  if (line > 0) strbuf_add(b, "%s:%d", (const char *)ud, line);
  else strbuf_add(b, "%s", (const char *)ud);
}

static void file_ref(void *ud, char *buf, size_t cap, int line, int head) {
  (void)ud, (void)head;
  snprintf(buf, cap, "line %d", line);
}

contour_places contour_places_file(const char *name) {
  return (contour_places){file_head, file_ref, (void *)name};
}

/* Split a line into whitespace-separated tokens (at most max). */
typedef struct { const char *s; size_t len; } token;

static int tokens(const char *line, size_t len, token *t, int max) {
  int n = 0;
  size_t i = 0;
  while (i < len) {
    while (i < len && (line[i] == ' ' || line[i] == '\t')) i++;
    if (i >= len) break;
    size_t j = i;
    while (j < len && line[j] != ' ' && line[j] != '\t') j++;
    if (n < max) t[n].s = line + i, t[n].len = j - i;
    n++;
    i = j;
  }
  return n;
}

/* 0 and *v if the token is a whole finite number; 1 if it is a number but not
 * finite; -1 if it is not a number. */
static int number(token t, double *v) {
  char buf[64], *end;
  if (t.len == 0 || t.len >= sizeof buf) return -1;
  memcpy(buf, t.s, t.len);
  buf[t.len] = 0;
  errno = 0;
  *v = strtod(buf, &end);
  if (end != buf + t.len) return -1;
  if (!isfinite(*v)) return 1;
  return 0;
}

static void raw_push(raw *c, vec2 p, int line) {
  if (c->have == c->cap) {
    c->cap = c->cap ? 2 * c->cap : 64;
    c->pt = xreallocarray(c->pt, (size_t)c->cap, sizeof *c->pt);
    c->ptline = xreallocarray(c->ptline, (size_t)c->cap, sizeof *c->ptline);
  }
  c->pt[c->have] = p;
  c->ptline[c->have++] = line;
}

/* A bad contour: kept with its reason, to be named with the others. */
static int bad(reader *r, const raw *c, int points, const char *fmt, ...) {
  va_list ap;
  strbuf why = {0};
  va_start(ap, fmt);
  strbuf_vadd(&why, fmt, ap);
  va_end(ap);
  if (r->nbad == r->capbad) {
    r->capbad = r->capbad ? 2 * r->capbad : 8;
    r->bad = xreallocarray(r->bad, (size_t)r->capbad, sizeof *r->bad);
  }
  r->bad[r->nbad++] = (bad_contour){c->line, points, why.buf};
  return 1;
}

/* Does the polygon p[0..k-1] enclose no area to speak of: twice its area at
 * most 2^-40 of its bounding box's diagonal squared?  Points written to two
 * decimals that lay on a line no longer do exactly (0.45 is no double), and
 * the thread they make is no region (a real contour 10 mm long is 1e-11 mm
 * wide before it counts). */
static int no_area(const vec2 *p, int k) {
  double lx = p[0].x, hx = p[0].x, ly = p[0].y, hy = p[0].y;
  for (int i = 1; i < k; i++) lx = fmin(lx, p[i].x), hx = fmax(hx, p[i].x), ly = fmin(ly, p[i].y), hy = fmax(hy, p[i].y);
  double w = hx - lx, h = hy - ly;
  if (!isfinite(w) || !isfinite(h)) return 0;
  int e = geom_scale_exp(fmax(w, h));   /* about p[0], at the extent's scale: no overflow */
  double a = 0, x1 = geom_ldexp(p[1].x - p[0].x, -e), y1 = geom_ldexp(p[1].y - p[0].y, -e);
  for (int i = 2; i < k; i++) {
    double x2 = geom_ldexp(p[i].x - p[0].x, -e), y2 = geom_ldexp(p[i].y - p[0].y, -e);
    a += x1 * y2 - x2 * y1, x1 = x2, y1 = y2;
  }
  w = geom_ldexp(w, -e), h = geom_ldexp(h, -e);
  return fabs(a) <= 0x1p-40 * (w * w + h * h);
}

/* A degenerate contour (fewer than 3 distinct points, all collinear, or
 * simple with no area to speak of) under CONTOUR_DROP_DEGENERATE: dropped, its own repair
 * notes with it, and counted (one note for the stack, -v one each).
 * Returns 1. */
static int degenerate(reader *r, const raw *c, int points, int k) {
  strbuf why = {0};
  if (k < 3) strbuf_add(&why, "%d distinct point%s", k, k == 1 ? "" : "s");
  else if (geom_collinear(c->pt, k)) strbuf_add(&why, "all %d points collinear", k);
  else strbuf_add(&why, "%d points all but collinear (twice its area %.3g)", k, fabs(geom_area2(c->pt, k)));
  strbuf_add(&why, ", no area (z=%s)", ARGS_G(c->z));
  if (r->flags & CONTOUR_VERBOSE) {
    r->to = &r->out;
    note(r, c->line, "dropped a degenerate contour: %s", why.buf);
  }
  if (r->ndegen++ == 0) {
    r->degen_line = c->line;
    r->degen_why = why.buf;
  } else {
    free(why.buf);
  }
  r->degen_points += points;
  return 1;
}

/* A contour that crosses, touches or runs back over itself: the first
 * offending pair of segments the sweep finds (geom/crossing.h,
 * exact, O(n log n)), each named by the lines of its two points. */
static int refuse_crossing(reader *r, const raw *c, int k, int points, const crossing_hit *hp) {
  crossing_hit h = *hp;
  int a = h.seg[0], b = h.seg[1];
  contour_place p[4];
  return bad(r, c, points,
             "the contour crosses itself: the segment from %s to %s %s the segment "
             "from %s to %s (%s %s)",
             at(r, c->ptline[a], c->line, &p[0]), at(r, c->ptline[(a + 1) % k], c->line, &p[1]),
             crossing_verb(h.kind), at(r, c->ptline[b], c->line, &p[2]),
             at(r, c->ptline[(b + 1) % k], c->line, &p[3]), ARGS_G(h.at.x), ARGS_G(h.at.y));
}

/* pt[0..k-1] (owned from here on) as a contour of the stack. */
static void take(reader *r, vec2 *pt, int k, double z, int line) {
  if (r->ncs == r->capcs) {
    r->capcs = r->capcs ? 2 * r->capcs : 16;
    r->cs = xreallocarray(r->cs, (size_t)r->capcs, sizeof *r->cs);
  }
  contour *out = &r->cs[r->ncs++];
  out->cw = geom_orientation(pt, k) < 0;
  if (out->cw) geom_reverse(pt, k);
  out->slice = 0;
  out->z = z;
  out->n = k;
  out->pt = pt;
  out->line = line;
}

/* A keyhole contour (geom/keyhole.h) becomes its loops, each named by the
 * line of its first point in the file; a note says what was dropped. */
static void split_keyhole(reader *r, const raw *c, const keyhole_split *ks) {
  for (int l = 0; l < ks->nloops; l++) {
    int f = ks->first[l], m = ks->first[l + 1] - f, line = c->ptline[ks->src[f]];
    for (int j = 1; j < m; j++)
      if (c->ptline[ks->src[f + j]] < line) line = c->ptline[ks->src[f + j]];
    vec2 *pt = xmallocarray((size_t)m, sizeof *pt);
    memcpy(pt, ks->pt + f, (size_t)m * sizeof *pt);
    take(r, pt, m, c->z, line);
  }
  if (ks->channels == 1)
    note(r, c->line, "keyhole: the contour split into %d loops at (%s %s), a channel of length %s dropped",
         ks->nloops, ARGS_G(ks->at.x), ARGS_G(ks->at.y), ARGS_G(ks->length));
  else if (ks->channels > 1)
    note(r, c->line, "keyhole: the contour split into %d loops at (%s %s) and elsewhere, %d channels of total "
         "length %s dropped", ks->nloops, ARGS_G(ks->at.x), ARGS_G(ks->at.y), ks->channels, ARGS_G(ks->length));
  if (ks->spurs == 1)
    note(r, c->line, "dropped a zero-width spur (walked out and back along itself) of length %s at (%s %s)",
         ARGS_G(ks->spur_length), ARGS_G(ks->spur_at.x), ARGS_G(ks->spur_at.y));
  else if (ks->spurs > 1)
    note(r, c->line, "dropped %d zero-width spurs (walked out and back along themselves) of total length %s, "
         "the first at (%s %s)", ks->spurs, ARGS_G(ks->spur_length), ARGS_G(ks->spur_at.x), ARGS_G(ks->spur_at.y));
}

/* Repairs of one kind in one contour: each in full with CONTOUR_VERBOSE,
 * else one line at the contour's header that counts them and names the
 * first (a single one is named in full either way). */
typedef struct {
  int count, line;
  vec2 p;
} tally;

static void tally_add(reader *r, tally *t, int line, vec2 p, const char *one) {
  if (r->flags & CONTOUR_VERBOSE) note(r, line, one, ARGS_G(p.x), ARGS_G(p.y));
  if (t->count++ == 0) t->line = line, t->p = p;
}

static void tally_note(reader *r, const tally *t, int header, const char *one, const char *many) {
  contour_place p;
  if (t->count == 0 || (r->flags & CONTOUR_VERBOSE)) return;
  if (t->count == 1) note(r, t->line, one, ARGS_G(t->p.x), ARGS_G(t->p.y));
  else note(r, header, many, t->count, at(r, t->line, header, &p), ARGS_G(t->p.x), ARGS_G(t->p.y));
}

/* Repair and check one contour; on success append it (or, a keyhole
 * contour, its loops) to *cs.  A contour that cannot be used is kept in
 * r->bad (returns 1) and the reading goes on. */
static int finish(reader *r, raw *c) {
  int n = c->have, k = 0, rc = 0;
  tally dup = {0}, closing = {0};
  static const char dup_one[] = "dropped a duplicate of the point before (%s %s)";
  static const char close_one[] = "dropped the repeated closing point (%s %s)";
  r->cur.len = 0;
  r->to = &r->cur;
  /* Consecutive duplicates, then a repeated closing point. */
  for (int i = 0; i < n; i++) {
    if (k > 0 && c->pt[i].x == c->pt[k - 1].x && c->pt[i].y == c->pt[k - 1].y) {
      tally_add(r, &dup, c->ptline[i], c->pt[i], dup_one);
      continue;
    }
    c->pt[k] = c->pt[i];
    c->ptline[k++] = c->ptline[i];
  }
  tally_note(r, &dup, c->line, dup_one, "dropped %d duplicates of the point before (the first at %s: %s %s)");
  while (k > 1 && c->pt[k - 1].x == c->pt[0].x && c->pt[k - 1].y == c->pt[0].y) {
    tally_add(r, &closing, c->ptline[k - 1], c->pt[k - 1], close_one);
    k--;
  }
  tally_note(r, &closing, c->line, close_one,
             "dropped %d repeated closing points (the last at %s: %s %s)");
  crossing_hit h;
  keyhole_split ks;
  int simple = -1;   /* not yet known */
  if ((k < 3 || geom_collinear(c->pt, k) ||
       ((simple = !crossing_find(&(crossing_poly){c->pt, k}, 1, &h)) && no_area(c->pt, k))) &&
      (r->flags & CONTOUR_DROP_DEGENERATE))
    rc = degenerate(r, c, n, k);
  else if (k < 3)
    rc = bad(r, c, n, "contour has %d distinct point%s, needs at least 3 (z=%s)", k, k == 1 ? "" : "s", ARGS_G(c->z));
  else if (geom_collinear(c->pt, k))
    rc = bad(r, c, n, "all %d points of the contour are collinear (z=%s)", k, ARGS_G(c->z));
  else if (simple == 1 || (simple < 0 && !crossing_find(&(crossing_poly){c->pt, k}, 1, &h))) {
    take(r, xreallocarray(c->pt, (size_t)k, sizeof *c->pt), k, c->z, c->line);
    c->pt = NULL;
  } else if ((r->flags & CONTOUR_NO_KEYHOLES) || !keyhole_repair(c->pt, k, &ks)) {
    rc = refuse_crossing(r, c, k, n, &h);
  } else {
    split_keyhole(r, c, &ks);
    keyhole_free(&ks);
  }
  r->to = &r->out;
  if (rc == 0 && r->cur.len) strbuf_raw(&r->out, r->cur.buf, r->cur.len);
  free(c->pt);
  free(c->ptline);
  memset(c, 0, sizeof *c);
  return rc;
}

static int by_z(const void *a, const void *b) {
  const contour *p = *(const contour *const *)a, *q = *(const contour *const *)b;
  if (p->z != q->z) return p->z < q->z ? -1 : 1;
  return p->line - q->line;
}

static int by_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/* Slices.  Sorted by z, the contours split into slices where the gap to the
 * next z is at least a tenth of the slice spacing S; S is the median of the
 * gaps that are at least 1% of the largest (so jitter of a few contours does
 * not pull it down).  The contours of a slice take one z, the lower median of
 * theirs (an input value, whatever the file order), and the snapping is
 * reported.  The gaps are taken with z scaled by the power of two 2^-e that
 * brings the largest |z| into [1/2, 1) (exact: subnormal z are scaled up), so
 * the grouping is the same for a stack scaled by any 2^k and no gap, its
 * hundredth or tenth underflows or overflows.  Returns the
 * number of slices. */
static int group_slices(reader *r, contour *cs, int n) {
  contour **o = xmallocarray((size_t)n, sizeof *o);
  double *gap = xmallocarray((size_t)n, sizeof *gap), zmax = 0;
  for (int i = 0; i < n; i++) o[i] = &cs[i], zmax = fmax(zmax, fabs(cs[i].z));
  int e = geom_scale_exp(zmax);
  qsort(o, (size_t)n, sizeof *o, by_z);
  int ng = 0;
  double big = 0;
  for (int i = 1; i < n; i++)
    if (o[i]->z > o[i - 1]->z) {
      double g = ldexp(o[i]->z, -e) - ldexp(o[i - 1]->z, -e);
      if (g > big) big = g;
      gap[ng++] = g;
    }
  int nk = 0;
  for (int i = 0; i < ng; i++)
    if (gap[i] >= big / 100) gap[nk++] = gap[i];
  qsort(gap, (size_t)nk, sizeof *gap, by_double);
  double spacing = nk ? gap[nk / 2] : 0, tol = spacing / 10;
  int nslices = 0, snapped = 0, first = 0;
  double worst = 0;
  for (int i = 0, j; i < n; i = j) {
    for (j = i + 1; j < n && (o[j]->z == o[j - 1]->z || ldexp(o[j]->z, -e) - ldexp(o[j - 1]->z, -e) < tol); j++) {}
    double z = o[i + (j - i - 1) / 2]->z;
    for (int k = i; k < j; k++) {
      if (o[k]->z != z) {
        double d = fabs(ldexp(o[k]->z, -e) - ldexp(z, -e));
        if (!snapped || o[k]->line < first) first = o[k]->line;
        if (d > worst) worst = d;
        snapped++;
        o[k]->z = z;
      }
      o[k]->slice = nslices;
    }
    nslices++;
  }
  if (snapped)
    note(r, first,
         "snapped the z of %d contour%s to their slice's (at most %.3g away; slices are about "
         "%.3g apart)", snapped, snapped == 1 ? "" : "s", ldexp(worst, e), ldexp(spacing, e));
  free(gap);
  free(o);
  return nslices;
}

/* The bad contours, in file order: refused, each named on a line of its
 * own and then one summary (as many lines as err holds; the summary says
 * how many were left out), or with CONTOUR_SKIP_BAD dropped with a note
 * each and one that counts them.  0 when the reading goes on. */
static int bad_contours(reader *r, int nread, long points) {
  long badpts = 0;
  for (int i = 0; i < r->nbad; i++) badpts += r->bad[i].points;
  if (r->flags & CONTOUR_SKIP_BAD) {
    for (int i = 0; i < r->nbad; i++) note(r, r->bad[i].line, "dropped, it cannot be tiled: %s", r->bad[i].why);
    note(r, 0, "--skip-bad dropped %d bad contour%s of %d (%ld of %ld points); the rest are tiled", r->nbad,
         r->nbad == 1 ? "" : "s", nread, badpts, points);
    return 0;
  }
  if (r->nbad == 1)
    return fail(r, r->bad[0].line, "%s; --skip-bad drops such a contour and tiles the rest", r->bad[0].why);
  char sum[300];
  strbuf b = {0}, whole = {0};
  r->pl->head(r->pl->ud, &whole, 0);
  int shown_ = 0;
  for (; shown_ < r->nbad; shown_++) {
    size_t mark = b.len;
    r->pl->head(r->pl->ud, &b, r->bad[shown_].line);
    strbuf_add(&b, ": %s\n", r->bad[shown_].why);
    snprintf(sum, sizeof sum, "%d of %d contours cannot be tiled (%ld of %ld points)%s", r->nbad, nread,
             badpts, points, shown_ + 1 < r->nbad ? ", the first 1000000000 named above" : "");
    if (b.len + whole.len + strlen(sum) + 80 >= r->errlen) {
      b.len = mark;
      break;
    }
  }
  if (shown_ == r->nbad)
    snprintf(sum, sizeof sum, "%d of %d contours cannot be tiled (%ld of %ld points), each named above", r->nbad,
             nread, badpts, points);
  else
    snprintf(sum, sizeof sum, "%d of %d contours cannot be tiled (%ld of %ld points), the first %d named above",
             r->nbad, nread, badpts, points, shown_);
  strbuf_add(&b, "%s: %s; --skip-bad drops them and tiles the rest", whole.buf, sum);
  snprintf(r->err, r->errlen, "%s", b.buf);
  free(b.buf);
  free(whole.buf);
  return -1;
}

int contour_stack_pairs(const contour_stack *s, const char *name, char *err, size_t errlen) {
  contour_places pl = contour_places_file(name);
  return contour_stack_pairs_at(s, &pl, err, errlen);
}

int contour_stack_pairs_at(const contour_stack *s, const contour_places *pl, char *err, size_t errlen) {
  reader rd;
  memset(&rd, 0, sizeof rd);
  rd.pl = pl, rd.err = err, rd.errlen = errlen;
  contour_place p;
  const contour *cs = s->c, *bad = NULL;
  int n = s->n;
  /* Two contours on one slice: report the later one in file order, naming
   * the first contour on that slice. */
  for (int i = 0; i < n; i++)
    for (int j = 0; j < i && !bad; j++)
      if (cs[j].slice == cs[i].slice) bad = &cs[i];
  if (bad) {
    int first = 0;
    while (cs[first].slice != bad->slice) first++;
    return fail(&rd, bad->line,
                "slice z=%s already has a contour (%s); this program tiles each "
                "contour with the next and needs one contour per slice (%s)",
                ARGS_G(bad->z), at(&rd, cs[first].line, bad->line, &p), ARGS_G(bad->z));
  }
  for (int i = 2; i < n; i++)
    if ((cs[i].z > cs[i - 1].z) != (cs[1].z > cs[0].z))
      return fail(&rd, cs[i].line,
                  "z goes back: contours must come in increasing or decreasing z (%s after %s)",
                  ARGS_G(cs[i].z), ARGS_G(cs[i - 1].z));
  return 0;
}

static void free_contours(contour *cs, int n) {
  for (int i = 0; i < n; i++) free(cs[i].pt);
  free(cs);
}

/* ---------------------------------------------------------------- the builder */

contour_build *contour_build_open(const contour_places *pl, int flags, const char *prefix) {
  reader *r = xcalloc(1, sizeof *r);
  r->pl = pl, r->prefix = prefix ? prefix : "tilesim", r->flags = flags;
  r->to = &r->out;
  return r;
}

void contour_build_begin(contour_build *r, double z, int line) {
  r->c.z = z;
  r->c.line = line;
  r->c.have = 0;
}

void contour_build_point(contour_build *r, vec2 p, int line) { raw_push(&r->c, p, line); }

void contour_build_end(contour_build *r) {
  r->nread++;
  r->points += r->c.have;
  finish(r, &r->c);
}

void contour_build_free(contour_build *r) {
  free(r->c.pt);
  free(r->c.ptline);
  free_contours(r->cs, r->ncs);
  free(r->out.buf);
  free(r->cur.buf);
  for (int i = 0; i < r->nbad; i++) free(r->bad[i].why);
  free(r->bad);
  free(r->degen_why);
  free(r);
}

/* Notes are held back and shown only if the stack is accepted: a rejected
 * stack gets its error and nothing else. */
int contour_build_close(contour_build *r, contour_stack *out, FILE *notes, char *err, size_t errlen) {
  int rc = -1, flags = r->flags, nread = r->nread;
  r->err = err, r->errlen = errlen;
  memset(out, 0, sizeof *out);
  if (r->nbad && bad_contours(r, nread, r->points) != 0) goto done;
  if (r->ndegen == 1 && !(flags & CONTOUR_VERBOSE))
    note(r, r->degen_line, "dropped a degenerate contour: %s", r->degen_why);
  else if (r->ndegen > 1 && !(flags & CONTOUR_VERBOSE))
    note(r, r->degen_line, "dropped %d degenerate contours of %d (%ld points: single points, two points or all "
         "collinear, no area), this one the first: %s; -v names each", r->ndegen, nread, r->degen_points,
         r->degen_why);
  if (r->ncs == 0 && nread > 0 && r->nbad == 0) {
    fail(r, 0, "no contours left to tile: all %d are degenerate (a point, two points or all collinear: no area)",
         nread);
    goto done;
  }
  if (r->ncs == 0 && nread > 0) {
    fail(r, 0, "no contours left to tile: all %d are bad%s and --skip-bad dropped them", nread,
         r->ndegen ? " or degenerate" : "");
    goto done;
  }
  if (r->ncs == 0) {
    fail(r, 0, "no contours");
    goto done;
  }
  if (r->ncs < 2 && !(flags & CONTOUR_ONE_SLICE)) {
    fail(r, r->cs[0].line, "only one contour; tiling needs at least 2 (z=%s)", ARGS_G(r->cs[0].z));
    goto done;
  }
  int nslices = group_slices(r, r->cs, r->ncs);
  /* Exact duplicates on a slice dropped, overlapping contours merged
   * (slicemerge.h; --union says so as its own notes). */
  if (slicemerge(&r->cs, &r->ncs,
                 (flags & CONTOUR_UNION ? SLICEMERGE_UNION : 0) | (flags & CONTOUR_VERBOSE ? SLICEMERGE_VERBOSE : 0),
                 r->pl, r->prefix, &r->out, err, errlen) != 0)
    goto done;
  if (nslices < 2 && !(flags & CONTOUR_ONE_SLICE)) {
    fail(r, r->cs[0].line, "all %d contours lie on one slice; tiling needs at least 2 (z=%s)",
         r->ncs, ARGS_G(r->cs[0].z));
    goto done;
  }
  /* With several contours on a slice, surface/ orients them by nesting and
   * reports what it changed. */
  int reversed = 0;   /* of the contours kept */
  for (int i = 0; i < r->ncs; i++) reversed += r->cs[i].cw;
  if (reversed && nslices == r->ncs)
    note(r, 0, "%d of %d contours ran clockwise; reversed to counter-clockwise", reversed, r->ncs);
  out->n = r->ncs;
  out->c = r->cs;
  out->nslices = nslices;
  r->cs = NULL, r->ncs = 0;
  if ((flags & CONTOUR_PAIRS) && contour_stack_pairs_at(out, r->pl, err, errlen) != 0) {
    contour_stack_free(out);
    goto done;
  }
  rc = 0;
done:
  if (rc == 0 && notes && r->out.len) fwrite(r->out.buf, 1, r->out.len, notes);
  contour_build_free(r);
  return rc;
}

/* ---------------------------------------------------------------- the text */

int contour_parse(const char *text, size_t len, const char *name,
                  contour_stack *out, FILE *notes, const char *prefix,
                  char *err, size_t errlen) {
  return contour_parse_flags(text, len, name, 0, out, notes, prefix, err, errlen);
}

/* A refusal of the text itself: "NAME:LINE: what". */
static int text_fail(const contour_places *pl, char *err, size_t errlen, int line, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail(pl, err, errlen, line, fmt, ap);
  va_end(ap);
  return -1;
}

int contour_parse_flags(const char *text, size_t len, const char *name, int flags,
                        contour_stack *out, FILE *notes, const char *prefix,
                        char *err, size_t errlen) {
  contour_places pl = contour_places_file(name);
  contour_build *b = contour_build_open(&pl, flags, prefix);
  int line = 0, last_want = 0, last_line = 0, nread = 0;
  int open = 0, cur_line = 0, want = 0, have = 0;   /* reading the points of the contour at cur_line */
  char vb[200];

  memset(out, 0, sizeof *out);
  if (len == 0) {
    text_fail(&pl, err, errlen, 1, "empty file, no contours");
    goto fail;
  }
  size_t pos = 0;
  while (pos < len) {
    size_t end = pos;
    while (end < len && text[end] != '\n') end++;
    size_t ll = end;
    line++;
    if (ll - pos > CONTOUR_MAX_LINE) {
      text_fail(&pl, err, errlen, line, "line longer than %d bytes (%zu bytes)", CONTOUR_MAX_LINE, ll - pos);
      goto fail;
    }
    if (ll > pos && text[ll - 1] == '\r') ll--;
    for (size_t i = pos; i < ll; i++) {
      unsigned char ch = (unsigned char)text[i];
      if ((ch < 32 && ch != '\t') || ch == 127) {
        text_fail(&pl, err, errlen, line, "binary data, not a contour file (byte 0x%02x)", ch);
        goto fail;
      }
    }
    const char *s = text + pos;
    size_t sl = ll - pos;
    pos = end + 1;
    token t[4];
    int nt = tokens(s, sl, t, 4);
    if (nt == 0 || t[0].s[0] == '#') continue;

    int is_header = t[0].len == 1 && t[0].s[0] == 'C';
    if (open && is_header) {
      text_fail(&pl, err, errlen, line, "the contour at line %d announced %d points but has %d (next header: %s)",
                cur_line, want, have, shown_bytes(s, sl, vb, sizeof vb));
      goto fail;
    }
    if (!open && !is_header) {
      if (nread > 0)
        text_fail(&pl, err, errlen, line, "more point lines than the %d announced at line %d (%s)", last_want,
                  last_line, shown_bytes(s, sl, vb, sizeof vb));
      else
        text_fail(&pl, err, errlen, line, "expected a header 'C <points> <z>' (%s)", shown_bytes(s, sl, vb, sizeof vb));
      goto fail;
    }
    if (is_header) {
      double nv, z;
      if (nt != 3) {
        text_fail(&pl, err, errlen, line, "garbled header, expected 'C <points> <z>' (%s)",
                  shown_bytes(s, sl, vb, sizeof vb));
        goto fail;
      }
      if (number(t[1], &nv) != 0 || nv != floor(nv) || nv < 1) {
        text_fail(&pl, err, errlen, line, "bad point count in header, expected a positive integer (%s)",
                  shown_bytes(t[1].s, t[1].len, vb, sizeof vb));
        goto fail;
      }
      if (nv > CONTOUR_MAX_POINTS) {
        text_fail(&pl, err, errlen, line, "point count too large, at most %d (%s)", CONTOUR_MAX_POINTS,
                  shown_bytes(t[1].s, t[1].len, vb, sizeof vb));
        goto fail;
      }
      int k = number(t[2], &z);
      if (k != 0) {
        text_fail(&pl, err, errlen, line, k > 0 ? "z is not finite (%s)" : "z is not a number (%s)",
                  shown_bytes(t[2].s, t[2].len, vb, sizeof vb));
        goto fail;
      }
      contour_build_begin(b, z, line);
      cur_line = line;
      want = (int)nv;
      have = 0;
      open = 1;
      continue;
    }
    /* A point line. */
    if (nt != 2) {
      text_fail(&pl, err, errlen, line, "expected a point 'x y' (%s)", shown_bytes(s, sl, vb, sizeof vb));
      goto fail;
    }
    vec2 p;
    for (int i = 0; i < 2; i++) {
      double v;
      int k = number(t[i], &v);
      if (k != 0) {
        text_fail(&pl, err, errlen, line, k > 0 ? "%c is not finite (%s)" : "%c is not a number (%s)",
                  i ? 'y' : 'x', shown_bytes(t[i].s, t[i].len, vb, sizeof vb));
        goto fail;
      }
      if (i) p.y = v;
      else p.x = v;
    }
    contour_build_point(b, p, line);
    if (++have == want) {
      last_want = want;
      last_line = cur_line;
      nread++;
      contour_build_end(b);
      open = 0;
    }
  }
  if (open) {
    text_fail(&pl, err, errlen, line, "the contour at line %d announced %d points but has %d (end of file)",
              cur_line, want, have);
    goto fail;
  }
  if (nread == 0) {
    text_fail(&pl, err, errlen, line, "no contours in the file (only comments or blank lines)");
    goto fail;
  }
  return contour_build_close(b, out, notes, err, errlen);
fail:
  contour_build_free(b);
  return -1;
}

int contour_read(const char *path, contour_stack *out, FILE *notes,
                 const char *prefix, char *err, size_t errlen) {
  return contour_read_flags(path, 0, out, notes, prefix, err, errlen);
}

int contour_read_flags(const char *path, int flags, contour_stack *out, FILE *notes,
                       const char *prefix, char *err, size_t errlen) {
  size_t len;
  char *buf = readfile(path, &len, err, errlen);
  memset(out, 0, sizeof *out);
  if (!buf) return -1;
  int rc = contour_parse_flags(buf, len, readfile_name(path), flags, out, notes, prefix, err, errlen);
  free(buf);
  return rc;
}

int contour_write(FILE *f, const contour_stack *s) {
  for (int i = 0; i < s->n; i++) {
    const contour *c = &s->c[i];
    fprintf(f, "C %d %.17g\n", c->n, c->z);
    for (int j = 0; j < c->n; j++) fprintf(f, "%.17g %.17g\n", c->pt[j].x, c->pt[j].y);
  }
  return ferror(f) ? -1 : 0;
}

void contour_stack_free(contour_stack *s) {
  free_contours(s->c, s->n);
  s->c = NULL;
  s->n = 0;
  s->nslices = 0;
}
