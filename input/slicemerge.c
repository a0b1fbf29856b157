/* slicemerge.c -- duplicates dropped, overlapping contours merged
 * (slicemerge.h). */
#include "input/slicemerge.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "geom/crossing.h"
#include "geom/exact.h"
#include "geom/polyunion.h"
#include "util/xmem.h"

/* ---------------------------------------------------------------- order */

typedef struct {
  int i;          /* index into cs */
  vec2 lo, hi;    /* bounding box */
} boxed;

static _Thread_local const contour *sort_cs;   /* for qsort */

static int by_slice_box(const void *a, const void *b) {
  const boxed *p = a, *q = b;
  const contour *c = &sort_cs[p->i], *d = &sort_cs[q->i];
  if (c->slice != d->slice) return c->slice - d->slice;
  int k = exact_lex(p->lo, q->lo);
  if (k) return k;
  if ((k = exact_lex(p->hi, q->hi))) return k;
  return c->line != d->line ? c->line - d->line : p->i - q->i;
}

static int by_slice_line(const void *a, const void *b) {
  const contour *c = &sort_cs[*(const int *)a], *d = &sort_cs[*(const int *)b];
  if (c->slice != d->slice) return c->slice - d->slice;
  return c->line != d->line ? c->line - d->line : *(const int *)a - *(const int *)b;
}

/* The contour from its least point (counter-clockwise, as stored). */
static void from_least(const vec2 *p, int n, vec2 *out) {
  int k = 0;
  for (int i = 1; i < n; i++)
    if (exact_lex(p[i], p[k]) < 0) k = i;
  for (int i = 0; i < n; i++) out[i] = p[(k + i) % n];
}

/* Without the points that lie between their neighbours on one line (a
 * simple polygon has no spike, so orient 0 means between), from its least
 * point: the region's own sequence.  Returns its length. */
static int reduced(const vec2 *p, int n, vec2 *out) {
  vec2 *t = xmallocarray((size_t)n, sizeof *t);
  int *keep = xmallocarray((size_t)n, sizeof *keep), m = geom_corners(p, n, keep);
  for (int i = 0; i < m; i++) t[i] = p[keep[i]];
  from_least(t, m, out);
  free(keep);
  free(t);
  return m;
}

static int cmp_seq(const vec2 *a, int n, const vec2 *b, int m) {
  if (n != m) return n < m ? -1 : 1;
  for (int i = 0; i < n; i++) {
    int k = exact_lex(a[i], b[i]);
    if (k) return k;
  }
  return 0;
}

/* Which of two copies to keep: fewer points, then the lesser sequence from
 * the least point, then the earlier line.  < 0 when c is kept over d. */
static int keep_order(const contour *c, const contour *d) {
  if (c->n != d->n) return c->n < d->n ? -1 : 1;
  vec2 *a = xmallocarray((size_t)c->n, sizeof *a), *b = xmallocarray((size_t)d->n, sizeof *b);
  from_least(c->pt, c->n, a), from_least(d->pt, d->n, b);
  int k = cmp_seq(a, c->n, b, d->n);
  free(a), free(b);
  return k ? k : c->line - d->line;
}

/* ---------------------------------------------------------------- duplicates */

static void note_line(strbuf *notes, const char *prefix, const contour_places *pl, int line) {
  strbuf_add(notes, "%s: ", prefix);
  pl->head(pl->ud, notes, line);
  strbuf_raw(notes, ": ", 2);
}



/* Mark in drop[] every contour that repeats another of its slice. */
static int duplicates(contour *cs, int ncs, char *drop, int verbose, const contour_places *pl, const char *prefix,
                      strbuf *notes) {
  contour_place p;
  boxed *bx = xmallocarray((size_t)ncs + 1, sizeof *bx);
  for (int i = 0; i < ncs; i++) {
    vec2 lo = cs[i].pt[0], hi = cs[i].pt[0];
    for (int k = 1; k < cs[i].n; k++) {
      vec2 q = cs[i].pt[k];
      if (q.x < lo.x) lo.x = q.x;
      if (q.y < lo.y) lo.y = q.y;
      if (q.x > hi.x) hi.x = q.x;
      if (q.y > hi.y) hi.y = q.y;
    }
    bx[i] = (boxed){i, lo, hi};
  }
  sort_cs = cs;
  qsort(bx, (size_t)ncs, sizeof *bx, by_slice_box);
  int dropped = 0, first = -1, first_of = -1;
  vec2 **red = xcalloc((size_t)ncs + 1, sizeof *red);
  int *nred = xcalloc((size_t)ncs + 1, sizeof *nred);
  for (int a = 0, b; a < ncs; a = b) {
    /* a run of one slice and one box: the candidates */
    for (b = a + 1; b < ncs && cs[bx[b].i].slice == cs[bx[a].i].slice && exact_lex(bx[b].lo, bx[a].lo) == 0 &&
                    exact_lex(bx[b].hi, bx[a].hi) == 0;
         b++) {}
    if (b - a < 2) continue;
    for (int k = a; k < b; k++) {
      const contour *c = &cs[bx[k].i];
      red[k] = xmallocarray((size_t)c->n, sizeof **red);
      nred[k] = reduced(c->pt, c->n, red[k]);
    }
    for (int k = a; k < b; k++) {
      if (drop[bx[k].i]) continue;
      /* k's copies among the rest: the one kept is the least by keep_order */
      int keep = bx[k].i;
      for (int j = k + 1; j < b; j++)
        if (!drop[bx[j].i] && cmp_seq(red[k], nred[k], red[j], nred[j]) == 0 && keep_order(&cs[bx[j].i], &cs[keep]) < 0)
          keep = bx[j].i;
      for (int j = k; j < b; j++) {
        int i = bx[j].i;
        if (i == keep || drop[i] || cmp_seq(red[k], nred[k], red[j], nred[j]) != 0) continue;
        drop[i] = 1;
        if (dropped++ == 0 || cs[i].line < cs[first].line) first = i, first_of = keep;
        if (verbose && notes) {
          note_line(notes, prefix, pl, cs[i].line);
          strbuf_add(notes, "dropped the contour: it repeats the contour at %s on slice z=%s exactly (the same "
                     "region: another start point, direction or collinear points)\n",
                     contour_place_at(pl, cs[keep].line, cs[i].line, &p), ARGS_G(cs[i].z));
        }
      }
    }
  }
  if (dropped && !verbose && notes) {
    note_line(notes, prefix, pl, cs[first].line);
    const char *of = contour_place_at(pl, cs[first_of].line, cs[first].line, &p);
    if (dropped == 1)
      strbuf_add(notes, "dropped the contour: it repeats the contour at %s on slice z=%s exactly (the same "
                 "region: another start point, direction or collinear points)\n", of, ARGS_G(cs[first].z));
    else
      strbuf_add(notes, "dropped %d contours that repeat another of their slice exactly (the same region: another "
                 "start point, direction or collinear points), this one a copy of %s on slice z=%s; -v "
                 "names each\n", dropped, of, ARGS_G(cs[first].z));
  }
  for (int k = 0; k < ncs; k++) free(red[k]);
  free(red), free(nred), free(bx);
  return dropped;
}

/* ---------------------------------------------------------------- union */

/* "line A, line B and line C" for the members of a group (at most 8, then
 * "and N more"; each as pl names it in a message about `head`). */
static void lines_of(strbuf *b, const contour *cs, const int *idx, const int *mem, int nm, const contour_places *pl,
                     int head) {
  contour_place p;
  for (int k = 0; k < nm; k++) {
    if (k == 8) {
      strbuf_add(b, " and %d more", nm - 8);
      break;
    }
    strbuf_add(b, "%s%s", k == 0 ? "" : k + 1 == nm ? " and " : ", ", contour_place_at(pl, cs[idx[mem[k]]].line, head, &p));
  }
}

typedef struct {
  contour *c;
  int n, cap;
} clist;

static contour *push(clist *l) {
  if (l->n == l->cap) {
    l->cap = l->cap ? 2 * l->cap : 16;
    l->c = xreallocarray(l->c, (size_t)l->cap, sizeof *l->c);
  }
  return &l->c[l->n++];
}

/* What the merges of a stack add up to, for its notes. */
typedef struct {
  int groups, merged, news, holes, slices, pinches;
  int first_line;     /* the first group's lead contour */
  strbuf first;       /* the first group's note (said alone when it is the only one) */
} tally;

/* What the default reading merged on one slice without --union: the
 * overlapping pieces (groups not nested), said in one note for the slice. */
typedef struct {
  int *mem;           /* their contours, as indices into the slice's idx */
  int n, loops, holes, news, pinches;
  vec2 pinch_at;
} pieces;

static int by_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* The slice's note on its overlapping pieces merged by default (one line,
 * whatever -v says: it names every contour, as far as lines_of does). */
static void note_pieces(strbuf *to, pieces *p, const contour *cs, const int *idx, const contour_places *pl,
                        const char *prefix) {
  qsort(p->mem, (size_t)p->n, sizeof *p->mem, by_int);   /* idx is in line order */
  int nc = p->loops - p->holes;
  int head = cs[idx[p->mem[0]]].line;
  note_line(to, prefix, pl, head);
  strbuf_add(to, "merged %d overlapping contours on slice z=%s into their union (as --union does): the contours at ",
             p->n, ARGS_G(cs[idx[0]].z));
  lines_of(to, cs, idx, p->mem, p->n, pl, head);
  strbuf_add(to, ": %d contour%s", nc, nc == 1 ? "" : "s");
  if (p->holes) strbuf_add(to, " and %d hole%s", p->holes, p->holes == 1 ? "" : "s");
  strbuf_add(to, " (%d new vertices where they cross)", p->news);
  if (p->pinches)
    strbuf_add(to, "; it touches itself at (%s %s)%s, split there (each piece but one off the point by 2^-20 of "
               "its edges)", ARGS_G(p->pinch_at.x), ARGS_G(p->pinch_at.y), p->pinches > 1 ? " and elsewhere" : "");
  strbuf_raw(to, "\n", 1);
}

/* Merge the groups of one slice, cs[idx[0..m-1]] (in line order): every
 * group, their contours marked in drop[], the loops appended to add.  The
 * notes: with `all` (SLICEMERGE_UNION) as --union's; else a nested group (a
 * hole drawn on its outer contour's boundary) counted in t as such, and the
 * overlapping pieces said in one note for the slice.  0, or -1 and err. */
static int union_slice(contour *cs, const int *idx, int m, int all, char *drop, clist *add, tally *t, int verbose,
                       const contour_places *pl, const char *prefix, strbuf *notes, char *err, size_t errlen) {
  crossing_poly *cp = xmallocarray((size_t)m, sizeof *cp);
  for (int k = 0; k < m; k++) cp[k] = (crossing_poly){cs[idx[k]].pt, cs[idx[k]].n};
  polyunion_result u;
  polyunion_flags(cp, m, POLYUNION_NEST | POLYUNION_SPLIT, &u);
  int slice0 = add->n, rc = 0;
  double z = cs[idx[0]].z;
  pieces pc = {0};
  for (int g = 0; g < u.ngroups && rc == 0; g++) {
    const int *mem = u.members + u.gmember[g];
    int nm = u.gmember[g + 1] - u.gmember[g], nh = 0, lead = idx[mem[0]];
    if (u.gstatus[g] != POLYUNION_OK) {
      strbuf b = {0};
      pl->head(pl->ud, &b, cs[lead].line);
      strbuf_add(&b, ": %sthe region of the contours at ", all ? "--union: " : "");
      lines_of(&b, cs, idx, mem, nm, pl, cs[lead].line);
      strbuf_add(&b, " on slice z=%s: its new vertices, rounded to doubles, make its boundary touch itself near "
                 "(%s %s); it cannot be tiled", ARGS_G(z), ARGS_G(u.gat[g].x), ARGS_G(u.gat[g].y));
      snprintf(err, errlen, "%s", b.buf);
      free(b.buf);
      rc = -1;
      break;
    }
    for (int k = 0; k < nm; k++) drop[idx[mem[k]]] = 1;
    for (int l = u.gfirst[g]; l < u.gfirst[g + 1]; l++) {
      int n = u.first[l + 1] - u.first[l];
      contour *c = push(add);
      c->z = z;
      c->n = n;
      c->pt = xmallocarray((size_t)n, sizeof *c->pt);
      memcpy(c->pt, u.pt + u.first[l], (size_t)n * sizeof *c->pt);
      c->cw = u.hole[l];
      if (c->cw) geom_reverse(c->pt, n);   /* stored counter-clockwise, as the reader's */
      c->line = cs[idx[u.src[l]]].line;
      c->slice = cs[idx[0]].slice;
      nh += u.hole[l];
    }
    int nl = u.gfirst[g + 1] - u.gfirst[g];
    if (!all && !u.nested[g]) {   /* overlapping pieces: the slice's note */
      pc.mem = xreallocarray(pc.mem, (size_t)(pc.n + nm), sizeof *pc.mem);
      memcpy(pc.mem + pc.n, mem, (size_t)nm * sizeof *mem);
      if (u.pinches[g] && !pc.pinches) pc.pinch_at = u.pinch_at[g];
      pc.n += nm, pc.loops += nl, pc.holes += nh, pc.news += u.newpts[g], pc.pinches += u.pinches[g];
      continue;
    }
    if (t->groups == 0) t->first_line = cs[lead].line;
    strbuf *to = verbose ? notes : (t->groups == 0 ? &t->first : NULL);
    if (to) {
      note_line(to, prefix, pl, cs[lead].line);
      if (all) strbuf_add(to, "--union: merged the contours at ");
      else strbuf_add(to, "a hole on its outer contour's boundary: the contours at ");
      lines_of(to, cs, idx, mem, nm, pl, cs[lead].line);
      if (all) strbuf_add(to, " on slice z=%s into their union", ARGS_G(z));
      else strbuf_add(to, " on slice z=%s, one inside another and meeting its boundary, made one region", ARGS_G(z));
      strbuf_add(to, ": %d contour%s", nl - nh, nl - nh == 1 ? "" : "s");
      if (nh) strbuf_add(to, " and %d hole%s", nh, nh == 1 ? "" : "s");
      if (all) strbuf_add(to, " (%d new vertices where they cross)", u.newpts[g]);
      if (u.pinches[g])
        strbuf_add(to, "; it touches itself at (%s %s)%s, split there (each piece but one off the point by "
                   "2^-20 of its edges)", ARGS_G(u.pinch_at[g].x), ARGS_G(u.pinch_at[g].y),
                   u.pinches[g] > 1 ? " and elsewhere" : "");
      strbuf_raw(to, "\n", 1);
    }
    t->groups++, t->merged += nm, t->news += u.newpts[g], t->holes += nh, t->pinches += u.pinches[g];
  }
  if (rc == 0 && pc.n && notes) note_pieces(notes, &pc, cs, idx, pl, prefix);
  free(pc.mem);
  polyunion_free(&u);
  free(cp);
  /* Rounding may have made a loop meet a contour of the slice that met
   * none: checked exactly, as the surface will. */
  if (rc == 0 && add->n > slice0) {
    int k = 0;
    crossing_poly *all_ = xmallocarray((size_t)m + (size_t)(add->n - slice0), sizeof *all_);
    for (int i = 0; i < m; i++)
      if (!drop[idx[i]]) all_[k++] = (crossing_poly){cs[idx[i]].pt, cs[idx[i]].n};
    for (int i = slice0; i < add->n; i++) all_[k++] = (crossing_poly){add->c[i].pt, add->c[i].n};
    crossing_hit h;
    int hit = crossing_find(all_, k, &h);
    free(all_);
    if (hit) {
      strbuf b = {0};
      pl->head(pl->ud, &b, add->c[slice0].line);
      strbuf_add(&b, ": %son slice z=%s the merged region's new vertices, rounded to doubles, make it touch another "
                 "contour near (%s %s); it cannot be tiled", all ? "--union: " : "", ARGS_G(z), ARGS_G(h.at.x),
                 ARGS_G(h.at.y));
      snprintf(err, errlen, "%s", b.buf);
      free(b.buf);
      rc = -1;
    }
  }
  return rc;
}

/* Do contours of this slice cross or touch (the test the surface makes)?
 * Not where no two of their boxes meet. */
static int meet(const contour *cs, const int *idx, int m) {
  vec2 *lo = xmallocarray((size_t)m, sizeof *lo), *hi = xmallocarray((size_t)m, sizeof *hi);
  int any = 0;
  for (int k = 0; k < m; k++) {
    const contour *c = &cs[idx[k]];
    lo[k] = hi[k] = c->pt[0];
    for (int j = 1; j < c->n; j++) {
      vec2 q = c->pt[j];
      if (q.x < lo[k].x) lo[k].x = q.x;
      if (q.y < lo[k].y) lo[k].y = q.y;
      if (q.x > hi[k].x) hi[k].x = q.x;
      if (q.y > hi[k].y) hi[k].y = q.y;
    }
    for (int j = 0; j < k && !any; j++)
      any = lo[j].x <= hi[k].x && lo[k].x <= hi[j].x && lo[j].y <= hi[k].y && lo[k].y <= hi[j].y;
  }
  free(lo), free(hi);
  if (!any) return 0;
  crossing_poly *cp = xmallocarray((size_t)m, sizeof *cp);
  for (int k = 0; k < m; k++) cp[k] = (crossing_poly){cs[idx[k]].pt, cs[idx[k]].n};
  crossing_hit h;
  int hit = crossing_find(cp, m, &h);
  free(cp);
  return hit;
}

/* ---------------------------------------------------------------- the whole */

int slicemerge(contour **csp, int *ncsp, int flags, const contour_places *pl, const char *prefix, strbuf *notes,
               char *err, size_t errlen) {
  contour *cs = *csp;
  int ncs = *ncsp, verbose = (flags & SLICEMERGE_VERBOSE) != 0, rc = 0;
  char *drop = xcalloc((size_t)ncs + 1, 1);
  int ndup = duplicates(cs, ncs, drop, verbose, pl, prefix, notes);
  clist add = {0};
  {
    /* Each slice whose contours meet: every group merged (with --union or
     * without, the same contours); only the notes differ. */
    int all = (flags & SLICEMERGE_UNION) != 0;
    int *idx = xmallocarray((size_t)ncs + 1, sizeof *idx), m = 0;
    for (int i = 0; i < ncs; i++)
      if (!drop[i]) idx[m++] = i;
    sort_cs = cs;
    qsort(idx, (size_t)m, sizeof *idx, by_slice_line);
    tally t = {0};
    for (int a = 0, b; a < m && rc == 0; a = b) {
      for (b = a + 1; b < m && cs[idx[b]].slice == cs[idx[a]].slice; b++) {}
      int before = t.groups;
      if (b - a >= 2 && meet(cs, idx + a, b - a))
        rc = union_slice(cs, idx + a, b - a, all, drop, &add, &t, verbose, pl, prefix, notes, err, errlen);
      t.slices += t.groups > before;
    }
    if (rc == 0 && !verbose && notes && t.groups == 1) strbuf_raw(notes, t.first.buf, t.first.len);
    else if (rc == 0 && !verbose && notes && t.groups > 1) {
      note_line(notes, prefix, pl, t.first_line);
      if (all)
        strbuf_add(notes, "--union: merged %d overlapping contours in %d groups on %d slices into their unions: %d "
                   "contours, %d of them holes (%d new vertices where they cross", t.merged, t.groups, t.slices, add.n,
                   t.holes, t.news);
      else
        strbuf_add(notes, "holes on their outer contours' boundaries: %d contours in %d groups on %d slices made "
                   "their regions: %d contours, %d of them holes", t.merged, t.groups, t.slices, add.n, t.holes);
      if (t.pinches) strbuf_add(notes, "%s%d points where a region touches itself, split", all ? "; " : " (", t.pinches);
      strbuf_add(notes, "%s; -v names each group\n", all || t.pinches ? ")" : "");
    }
    free(t.first.buf);
    free(idx);
  }
  if (rc != 0) {
    for (int i = 0; i < add.n; i++) free(add.c[i].pt);
    free(add.c);
    free(drop);
    return -1;
  }
  if (ndup || add.n) {
    int k = 0;
    for (int i = 0; i < ncs; i++) {
      if (drop[i]) {
        free(cs[i].pt);
        continue;
      }
      cs[k++] = cs[i];
    }
    if (add.n) {
      cs = xreallocarray(cs, (size_t)(k + add.n), sizeof *cs);
      memcpy(cs + k, add.c, (size_t)add.n * sizeof *cs);
      k += add.n;
    }
    *csp = cs;
    *ncsp = k;
  }
  free(add.c);
  free(drop);
  return 0;
}
