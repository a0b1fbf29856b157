/* pipeline.c -- ./tile's work on one input, in memory, with invariants that
 * abort: the robustness tests' and the fuzz targets' oracle. */
#include "tests/pipeline.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "input/contour.h"
#include "surface/mesh.h"
#include "input/rtstruct.h"
#include "tests/rtwriter.h"
#include "surface/stack.h"
#include "algo/tiling.h"
#include "util/xmem.h"

#define NAME "fuzz.dcm"

#define INVARIANT(cond, ...)                                                   \
  do {                                                                         \
    if (!(cond)) {                                                             \
      fprintf(stderr, "pipeline: %s:%d: ", __FILE__, __LINE__);                \
      fprintf(stderr, __VA_ARGS__);                                            \
      fputc('\n', stderr);                                                     \
      abort();                                                                 \
    }                                                                          \
  } while (0)

/* A refusal: one line, or (bad contours, slices with crossings) a line per
 * contour and a summary; every line names the input first. */
static void one_line(const char *err, const char *name) {
  INVARIANT(err[0] != 0, "a refusal without a message");
  for (const char *p = err; *p;) {
    INVARIANT(strncmp(p, name, strlen(name)) == 0 && p[strlen(name)] == ':',
              "a refusal line that does not name the input first: %s", err);
    const char *e = strchr(p, '\n');
    if (!e) break;
    INVARIANT(e[1] != 0, "a refusal ending in an empty line: %s", err);
    p = e + 1;
  }
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static void same_stacks(const contour_stack *a, const contour_stack *b) {
  INVARIANT(a->n == b->n, "stacks of %d and %d contours", a->n, b->n);
  for (int i = 0; i < a->n; i++) {
    INVARIANT(a->c[i].n == b->c[i].n && same_bits(a->c[i].z, b->c[i].z), "contour %d differs", i);
    for (int j = 0; j < a->c[i].n; j++)
      INVARIANT(same_bits(a->c[i].pt[j].x, b->c[i].pt[j].x) && same_bits(a->c[i].pt[j].y, b->c[i].pt[j].y),
                "contour %d point %d differs", i, j);
  }
}

static int cmp(const void *a, const void *b) {
  unsigned long long x = *(const unsigned long long *)a, y = *(const unsigned long long *)b;
  return x < y ? -1 : x > y;
}

/* Tile the stack when it is small enough; the mesh must be closed: every
 * edge used as often in one direction as in the other. */
/* Every directed edge of the mesh as often as its reverse: closed. */
static int closed_mesh(const mesh *me) {
  size_t ne = (size_t)me->nt * 3;
  unsigned long long *e = xmallocarray(ne ? ne : 1, sizeof *e), *r = xmallocarray(ne ? ne : 1, sizeof *r);
  for (int t = 0; t < me->nt; t++)
    for (int k = 0; k < 3; k++) {
      unsigned long long a = (unsigned long long)me->t[t][k], b = (unsigned long long)me->t[t][(k + 1) % 3];
      e[3 * (size_t)t + (size_t)k] = a * (unsigned long long)me->nv + b;
      r[3 * (size_t)t + (size_t)k] = b * (unsigned long long)me->nv + a;
    }
  qsort(e, ne, sizeof *e, cmp);
  qsort(r, ne, sizeof *r, cmp);
  int ok = memcmp(e, r, ne * sizeof *e) == 0;
  free(e);
  free(r);
  return ok;
}

/* The whole stack as ./tile makes it with the default options (aligned
 * bands, caps; a thin slab for one slice): refused in lines that name the
 * input, or a closed mesh. */
static void surface(const contour_stack *s, double max_pair) {
  double pts = 0;
  for (int i = 0; i < s->n; i++) pts += s->c[i].n;
  if (pts * pts > 4 * max_pair) return;
  stack_options o = {COST_AREA, 1, 0, 1, NULL, NULL, "fuzz", NULL, NULL, MATCH_SINGLE, INFINITY, 0.5,
                     STACK_BAND_ALIGNED};
  stack_surface *ss = NULL;
  static char err[1 << 14];
  if (stack_tile(s, NAME, &o, &ss, err, sizeof err) != 0) {
    one_line(err, NAME);
    return;
  }
  INVARIANT(closed_mesh(stack_mesh(ss)), "the surface of %d contours is not closed", s->n);
  stack_free(ss);
}

static void tile(const contour_stack *s, double max_pair) {
  for (int i = 0; i + 1 < s->n; i++)
    if ((double)s->c[i].n * s->c[i + 1].n > max_pair) return;
  mesh me;
  mesh_init(&me, s);
  for (int i = 0; i + 1 < s->n; i++) {
    tiling t;
    double area, volume;
    tiling_solve(s->c[i].pt, s->c[i].n, s->c[i].z, s->c[i + 1].pt, s->c[i + 1].n, s->c[i + 1].z,
                 COST_AREA, -1, &t);
    mesh_add_band(&me, s, i, &t, &area, &volume);
    tiling_free(&t);
  }
  mesh_add_caps(&me, s);
  INVARIANT(closed_mesh(&me), "the mesh of %d contours is not closed", s->n);
  mesh_free(&me);
}

/* The stack read with --skip-bad, --union and -v and degenerate
 * contours dropped: refused in lines that name the input, or a stack whose
 * slices' contours meet nowhere, which writes and reads back as itself, and
 * whose surface (small stacks) is closed. */
static void merged(const char *buf, size_t len, double max_pair) {
  contour_stack s, t;
  static char err[1 << 14];
  char *notes = NULL;
  size_t nl = 0;
  FILE *nf = open_memstream(&notes, &nl);
  int rc = contour_parse_flags(buf, len, NAME, CONTOUR_SKIP_BAD | CONTOUR_UNION | CONTOUR_VERBOSE | CONTOUR_DROP_DEGENERATE,
                               &s, nf, "fuzz", err, sizeof err);
  fclose(nf);
  if (rc != 0) {
    one_line(err, NAME);
    INVARIANT(nl == 0, "notes for a refused stack: %s", notes);
    free(notes);
    return;
  }
  for (const char *p = notes; p && *p; p = strchr(p, '\n') + 1)
    INVARIANT(strncmp(p, "fuzz: " NAME, strlen("fuzz: " NAME)) == 0 && strchr(p, '\n'), "a note: %s", p);
  free(notes);
  char *text = NULL;
  size_t tl = 0;
  FILE *f = open_memstream(&text, &tl);
  INVARIANT(contour_write(f, &s) == 0, "contour_write failed");
  fclose(f);
  INVARIANT(contour_parse(text, tl, NAME, &t, NULL, "fuzz", err, sizeof err) == 0,
            "a merged stack does not read back: %s", err);
  INVARIANT(t.n == s.n, "a merged stack of %d contours reads back as %d", s.n, t.n);
  if (contour_stack_pairs(&s, NAME, err, sizeof err) == 0) tile(&s, max_pair);
  surface(&s, max_pair);
  free(text);
  contour_stack_free(&s);
  contour_stack_free(&t);
}

int pipeline_contours(const char *buf, size_t len, double max_pair) {
  contour_stack s, t;
  char err[1 << 14];
  merged(buf, len, max_pair);
  if (contour_parse(buf, len, NAME, &s, NULL, "fuzz", err, sizeof err) != 0) {
    one_line(err, NAME);
    return 1;
  }
  char *text = NULL;
  size_t tl = 0;
  FILE *f = open_memstream(&text, &tl);
  INVARIANT(contour_write(f, &s) == 0, "contour_write failed");
  fclose(f);
  INVARIANT(contour_parse(text, tl, NAME, &t, NULL, "fuzz", err, sizeof err) == 0,
            "a written stack does not read back: %s", err);
  same_stacks(&s, &t);
  /* Tiled as ./tile tiles it: each contour with the next. */
  if (contour_stack_pairs(&s, NAME, err, sizeof err) == 0) tile(&s, max_pair);
  else one_line(err, NAME);
  free(text);
  contour_stack_free(&s);
  contour_stack_free(&t);
  return 0;
}

/* Re-encode what was read with the test writer (implicit VR, undefined
 * lengths) and read it again: the same ROIs and the same contours. */
static void reencode(const rtstruct *s) {
  rtw_roi *roi = xcalloc((size_t)s->nroi + 1, sizeof *roi);
  rtw_contour **cs = xcalloc((size_t)s->nroi + 1, sizeof *cs);
  for (int i = 0; i < s->nroi; i++) {
    const rtstruct_roi *r = &s->roi[i];
    roi[i].number = r->number;
    roi[i].name = r->name;
    roi[i].type = r->type[0] ? r->type : NULL;
    if (r->error) {
      roi[i].no_contours = 1;
      continue;
    }
    cs[i] = xcalloc((size_t)r->nc + 1, sizeof **cs);
    for (int k = 0; k < r->nc; k++) cs[i][k] = (rtw_contour){NULL, r->c[k].n, r->c[k].p, NULL, -1};
    roi[i].nc = r->nc;
    roi[i].c = cs[i];
  }
  rtw_opts o = {0, 1, 0, 0, NULL, NULL, 0};
  size_t len;
  unsigned char *b = rtw_write(&o, roi, s->nroi, &len);
  rtstruct t;
  char err[1024];
  INVARIANT(rtstruct_parse(b, len, NAME, &t, err, sizeof err) == 0, "a re-encoded set does not read: %s", err);
  INVARIANT(t.nroi == s->nroi, "%d ROIs, re-encoded %d", s->nroi, t.nroi);
  for (int i = 0; i < s->nroi; i++) {
    const rtstruct_roi *a = &s->roi[i], *c = &t.roi[i];
    INVARIANT(a->number == c->number && strcmp(a->name, c->name) == 0 && strcmp(a->type, c->type) == 0,
              "ROI %d: number, name or type differ after re-encoding", a->number);
    if (a->error) continue;
    INVARIANT(!c->error && a->nc == c->nc && a->plane == c->plane && a->slices == c->slices,
              "ROI %d: re-encoded differs (%s)", a->number, c->error ? c->error : "counts");
    for (int k = 0; k < a->nc; k++) {
      INVARIANT(a->c[k].n == c->c[k].n && same_bits(a->c[k].h, c->c[k].h), "ROI %d contour %d", a->number, k);
      for (int j = 0; j < 3 * a->c[k].n; j++)
        INVARIANT(same_bits(a->c[k].p[j], c->c[k].p[j]), "ROI %d contour %d value %d", a->number, k, j);
    }
  }
  rtstruct_free(&t);
  free(b);
  for (int i = 0; i < s->nroi; i++) free(cs[i]);
  free(cs);
  free(roi);
}

/* The ROI's stack (rc, st) is its .contours text (rtstruct_roi_text) read
 * as a file with the same flags: refused alike, or the same stack bit for
 * bit, each contour named by the same line. */
static void as_text(const rtstruct *s, int roi, int cflags, int rc, const contour_stack *st) {
  static char terr[1 << 14];
  size_t tl;
  if (rtstruct_roi_check(s, roi, terr, sizeof terr) != 0) return;
  char *text = rtstruct_roi_text(s, roi, &tl);
  contour_stack t;
  int trc = contour_parse_flags(text, tl, NAME, cflags, &t, NULL, "fuzz", terr, sizeof terr);
  free(text);
  INVARIANT(trc == rc, "ROI %d: its stack %s, its text %s (%s)", s->roi[roi].number, rc ? "refused" : "made",
            trc ? "refused" : "read", trc ? terr : "");
  if (trc != 0) return;
  same_stacks(st, &t);
  for (int i = 0; i < t.n; i++) INVARIANT(st->c[i].line == t.c[i].line, "contour %d: another line", i);
  contour_stack_free(&t);
}

int pipeline_dicom(const unsigned char *buf, size_t len, double max_pair) {
  rtstruct s;
  static char err[1 << 14];
  if (rtstruct_parse(buf, len, NAME, &s, err, sizeof err) != 0) {
    one_line(err, NAME);
    return 1;
  }
  if (s.warnings) INVARIANT(strncmp(s.warnings, NAME ": ", strlen(NAME) + 2) == 0, "warnings: %s", s.warnings);
  reencode(&s);
  for (int i = 0; i < s.nroi; i++) {
    contour_stack st;
    int flags = CONTOUR_SKIP_BAD | CONTOUR_UNION | CONTOUR_DROP_DEGENERATE | CONTOUR_ONE_SLICE;
    int rc = rtstruct_roi_stack(&s, i, flags, &st, NULL, "fuzz", err, sizeof err);
    as_text(&s, i, flags, rc, &st);
    if (rc == 0) {
      surface(&st, max_pair);
      contour_stack_free(&st);
    } else
      one_line(err, NAME);
    rc = rtstruct_roi_stack(&s, i, CONTOUR_PAIRS, &st, NULL, "fuzz", err, sizeof err);
    as_text(&s, i, CONTOUR_PAIRS, rc, &st);
    if (rc != 0) {
      one_line(err, NAME);
      continue;
    }
    tile(&st, max_pair);
    contour_stack_free(&st);
  }
  rtstruct_free(&s);
  return 0;
}
