/* slices.c -- canonical slices and their nesting forests (design note,
 * section 2, steps 2 and 4; IMOD's imodContourNestLevels does the same with
 * scan conversion, here it is exact).
 *
 * Per slice, independently (on the thread pool):
 *   1. every contour starts at its least point; the slice's contours are
 *      sorted by it;
 *   2. no two may cross or touch (crossing_find, exact, O(N log N));
 *   3. depth = the number of contours around it: with no contacts, one
 *      point of a contour is inside another exactly when all of it is;
 *      parent = the deepest of those;
 *   4. odd depth runs clockwise, even counter-clockwise. */
#include "surface/slices.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "geom/crossing.h"
#include "geom/exact.h"
#include "surface/pool.h"
#include "util/xmem.h"

typedef struct {
  slices *sl;
  const char *name;
  char **err;        /* per slice: the refusal, or NULL */
} job;

/* Start p at its least point; returns where that point was. */
static int rotate_least(vec2 *p, int n) {
  int k = 0;
  for (int i = 1; i < n; i++)
    if (exact_lex(p[i], p[k]) < 0) k = i;
  if (k == 0) return 0;
  vec2 *t = xmallocarray((size_t)n, sizeof *t);
  for (int i = 0; i < n; i++) t[i] = p[(i + k) % n];
  memcpy(p, t, (size_t)n * sizeof *p);
  free(t);
  return k;
}

static int by_least(const void *a, const void *b) {
  const slice_contour *p = a, *q = b;
  int c = exact_lex(p->pt[0], q->pt[0]);
  return c ? c : p->line - q->line;
}

static int box_holds(const inside_index *outer, const inside_index *inner) {
  vec2 alo, ahi, blo, bhi;
  inside_box(outer, &alo, &ahi);
  inside_box(inner, &blo, &bhi);
  return alo.x <= blo.x && alo.y <= blo.y && ahi.x >= bhi.x && ahi.y >= bhi.y;
}

static void one_slice(void *ud, int k) {
  job *jb = ud;
  slices *sl = jb->sl;
  slice_contour *c = sl->c + sl->first[k];
  int n = sl->first[k + 1] - sl->first[k];
  qsort(c, (size_t)n, sizeof *c, by_least);

  crossing_poly *poly = xmallocarray((size_t)n, sizeof *poly);
  for (int i = 0; i < n; i++) poly[i] = (crossing_poly){c[i].pt, c[i].n};
  crossing_hit h;
  if (crossing_find(poly, n, &h)) {
    char buf[512];
    const slice_contour *a = &c[h.poly[0]], *b = &c[h.poly[1]];
    int e = sl->scale;   /* in the file's units */
    if (a == b)
      snprintf(buf, sizeof buf, "%s:%d: contour %s itself on slice z=%s (%s %s)", jb->name,
               a->line, crossing_verb(h.kind), ARGS_G(ldexp(sl->z[k], e)), ARGS_G(ldexp(h.at.x, e)), ARGS_G(ldexp(h.at.y, e)));
    else {
      if (a->line > b->line) {
        const slice_contour *t = a;
        a = b, b = t;
      }
      snprintf(buf, sizeof buf, "%s:%d: contour %s the contour at line %d on slice z=%s (%s %s)",
               jb->name, b->line, crossing_verb(h.kind), a->line, ARGS_G(ldexp(sl->z[k], e)), ARGS_G(ldexp(h.at.x, e)),
               ARGS_G(ldexp(h.at.y, e)));
    }
    jb->err[k] = xstrdup(buf);
    free(poly);
    return;
  }
  free(poly);

  for (int i = 0; i < n; i++) c[i].ix = inside_new(c[i].pt, c[i].n);
  for (int i = 0; i < n; i++) {
    c[i].depth = 0;
    for (int j = 0; j < n; j++)
      if (j != i && box_holds(c[j].ix, c[i].ix) && inside_point(c[j].ix, c[i].pt[0]) == INSIDE_IN)
        c[i].depth++;
  }
  for (int i = 0; i < n; i++) {
    c[i].parent = -1;
    for (int j = 0; j < n; j++)
      if (j != i && c[j].depth == c[i].depth - 1 && box_holds(c[j].ix, c[i].ix) &&
          inside_point(c[j].ix, c[i].pt[0]) == INSIDE_IN)
        c[i].parent = sl->first[k] + j;
    XASSERT((c[i].parent < 0) == (c[i].depth == 0));
  }
  for (int i = 0; i < n; i++) {
    c[i].pos = i;
    if (c[i].depth % 2) {   /* a hole: clockwise, still from its least point */
      geom_reverse(c[i].pt, c[i].n);
      c[i].rev = 1;
      inside_free(c[i].ix);
      c[i].ix = inside_new(c[i].pt, c[i].n);
    }
    c[i].area2 = geom_area2(c[i].pt, c[i].n);
  }
}

int slices_scale_exp(const contour_stack *s) {
  double m = 0;
  for (int i = 0; i < s->n; i++) {
    m = fmax(m, fabs(s->c[i].z));
    for (int k = 0; k < s->c[i].n; k++) m = fmax(m, fmax(fabs(s->c[i].pt[k].x), fabs(s->c[i].pt[k].y)));
  }
  return geom_scale_exp(m);
}

int slices_build(const contour_stack *s, const char *name, int threads, slices *out, char *err,
                 size_t errlen) {
  return slices_build_at(s, name, 0, threads, out, err, errlen);
}

int slices_build_at(const contour_stack *s, const char *name, int scale, int threads, slices *out,
                    char *err, size_t errlen) {
  slices *sl = out;
  memset(sl, 0, sizeof *sl);
  sl->scale = scale;
  int ns = s->nslices;
  sl->nslices = ns;
  sl->ncontours = s->n;
  sl->z = xcalloc((size_t)ns, sizeof *sl->z);
  sl->first = xcalloc((size_t)ns + 1, sizeof *sl->first);
  sl->c = xcalloc((size_t)s->n, sizeof *sl->c);
  for (int i = 0; i < s->n; i++) {
    XASSERT(s->c[i].slice >= 0 && s->c[i].slice < ns);
    sl->first[s->c[i].slice + 1]++;
    sl->z[s->c[i].slice] = geom_ldexp(s->c[i].z, -scale);
  }
  for (int k = 0; k < ns; k++) sl->first[k + 1] += sl->first[k];
  int *fill = xmallocarray((size_t)ns, sizeof *fill);
  memcpy(fill, sl->first, (size_t)ns * sizeof *fill);
  for (int i = 0; i < s->n; i++) {
    const contour *f = &s->c[i];
    slice_contour *c = &sl->c[fill[f->slice]++];
    c->n = f->n;
    c->pt = xmallocarray((size_t)f->n, sizeof *c->pt);
    for (int k = 0; k < f->n; k++) c->pt[k] = (vec2){geom_ldexp(f->pt[k].x, -scale), geom_ldexp(f->pt[k].y, -scale)};
    c->from = rotate_least(c->pt, c->n);
    c->src = i;
    c->line = f->line;
    c->slice = f->slice;
    c->filecw = f->cw;
  }
  free(fill);

  job jb = {sl, name, xcalloc((size_t)ns, sizeof(char *))};
  pool_run(threads, ns, NULL, one_slice, &jb);

  /* Every slice with contours that meet: one line each (its first
   * contact, as many lines as err holds), and the way out. */
  int rc = 0, nbad = 0, shown = 0;
  size_t at = 0;
  for (int k = 0; k < ns; k++) nbad += jb.err[k] != NULL;
  for (int k = 0; k < ns && nbad; k++) {
    if (!jb.err[k]) continue;
    size_t l = strlen(jb.err[k]);
    if (rc == 0 || at + l + 300 < errlen) {
      at += (size_t)snprintf(err + at, errlen - at, "%s%s", rc ? "\n" : "", jb.err[k]);
      if (at >= errlen) at = errlen - 1;
      shown++;
    }
    rc = -1;
  }
  if (nbad > 1)
    snprintf(err + at, errlen - at, "\n%s: contours cross or touch on %d slices (%s named above)", name, nbad,
             shown == nbad ? "each" : "the first ones");
  for (int k = 0; k < ns; k++) free(jb.err[k]);
  free(jb.err);
  if (rc == 0) {
    for (int i = 0; i < sl->ncontours; i++) {
      slice_contour *c = &sl->c[i];
      c->base = sl->nverts;
      sl->nverts += c->n;
      if (c->filecw != c->depth % 2) sl->reoriented++;
    }
  }
  if (rc != 0) slices_free(sl);
  return rc;
}

void slices_free(slices *sl) {
  for (int i = 0; i < sl->ncontours; i++) {
    free(sl->c[i].pt);
    inside_free(sl->c[i].ix);
  }
  free(sl->c);
  free(sl->z);
  free(sl->first);
  memset(sl, 0, sizeof *sl);
}
