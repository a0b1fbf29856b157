/* rtstruct.c -- DICOM RT structure sets: the ROIs, their closed planar
 * contours, and each ROI as a contour stack and as .contours text.
 *
 *   StructureSetROISequence (3006,0020)   item: ROINumber (3006,0022), ROIName (3006,0026)
 *   ROIContourSequence (3006,0039)        item: ReferencedROINumber (3006,0084),
 *     ContourSequence (3006,0040)           item: ContourGeometricType (3006,0042),
 *                                                 NumberOfContourPoints (3006,0046),
 *                                                 ContourData (3006,0050) x\y\z\x\y\z...
 *   RTROIObservationsSequence (3006,0080) item: ReferencedROINumber, RTROIInterpretedType (3006,00A4)
 *
 * The pitfalls real readers meet (doc/dicom.md) and
 * what happens here: only CLOSED_PLANAR is tiled, the others are counted and
 * skipped with a warning; NumberOfContourPoints must agree with ContourData;
 * decimal strings may carry blanks, exponents and -0, and are read whatever
 * the locale; contours come in any order and are sorted by their plane; an
 * ROI without contours, or contours naming an unknown ROI, give warnings. */
#include "input/rtstruct.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "input/decimal.h"
#include "input/dicom.h"
#include "input/rtframe.h"
#include "util/readfile.h"
#include "util/shown.h"
#include "util/strbuf.h"
#include "util/xmem.h"

#define MODALITY DICOM_TAG(0x0008, 0x0060)
#define SOP_CLASS DICOM_TAG(0x0008, 0x0016)
#define SS_ROI_SEQ DICOM_TAG(0x3006, 0x0020)
#define ROI_NUMBER DICOM_TAG(0x3006, 0x0022)
#define ROI_NAME DICOM_TAG(0x3006, 0x0026)
#define ROI_CONTOUR_SEQ DICOM_TAG(0x3006, 0x0039)
#define CONTOUR_SEQ DICOM_TAG(0x3006, 0x0040)
#define GEOMETRIC_TYPE DICOM_TAG(0x3006, 0x0042)
#define NUMBER_OF_POINTS DICOM_TAG(0x3006, 0x0046)
#define CONTOUR_DATA DICOM_TAG(0x3006, 0x0050)
#define OBSERVATIONS_SEQ DICOM_TAG(0x3006, 0x0080)
#define REF_ROI_NUMBER DICOM_TAG(0x3006, 0x0084)
#define INTERPRETED_TYPE DICOM_TAG(0x3006, 0x00A4)
#define RTSTRUCT_SOP_CLASS "1.2.840.10008.5.1.4.1.1.481.3"

static const uint32_t sequences[] = {SS_ROI_SEQ, ROI_CONTOUR_SEQ, CONTOUR_SEQ, OBSERVATIONS_SEQ};

/* ---------------------------------------------------------------- parsing */

typedef struct {
  const dicom *d;
  const char *name;
  char *err;
  size_t errlen;
  strbuf warn;
  int nwarn;           /* file warnings: the first few are shown, the rest counted */
  struct numbered *by_number;   /* the ROIs sorted by ROI number */
} reader;

typedef struct numbered {
  int number, i;       /* an ROI's number and index */
} numbered;

static int fail(reader *r, size_t off, const char *fmt, ...) {
  va_list ap;
  int k = snprintf(r->err, r->errlen, "%s: byte %zu: ", r->name, off);
  if (k < 0) k = 0;
  if ((size_t)k < r->errlen) {
    va_start(ap, fmt);
    vsnprintf(r->err + k, r->errlen - (size_t)k, fmt, ap);
    va_end(ap);
  }
  return -1;
}

/* An element's text: its value with trailing blanks and NULs removed (and
 * leading blanks, unless keep_lead); "" if absent.  Cut to cap - 1 bytes,
 * and then trimmed again, so that the text written back and read again is
 * the same text (a cut that ended on a blank was not: found by make fuzz). */
static size_t text(const dicom *d, int node, int keep_lead, char *buf, size_t cap) {
  size_t len = 0;
  const unsigned char *v = node >= 0 ? dicom_value(d, node, &len) : NULL;
  size_t i = 0, j = len;
  while (j > 0 && (v[j - 1] == ' ' || v[j - 1] == 0)) j--;
  while (!keep_lead && i < j && v[i] == ' ') i++;
  size_t n = j - i < cap - 1 ? j - i : cap - 1;
  while (n > 0 && (v[i + n - 1] == ' ' || v[i + n - 1] == 0)) n--;
  if (n) memcpy(buf, v + i, n);
  buf[n] = 0;
  return n;
}

/* An IS value: a whole number in int range.  0, or -1. */
static int integer(const dicom *d, int node, int *out) {
  char b[32];
  size_t len = 0;
  dicom_value(d, node, &len);
  if (len == 0 || len >= sizeof b) return -1;
  size_t n = text(d, node, 0, b, sizeof b);
  size_t i = 0;
  int neg = 0;
  if (i < n && (b[i] == '+' || b[i] == '-')) neg = b[i++] == '-';
  if (i == n) return -1;
  long long v = 0;
  for (; i < n; i++) {
    if (b[i] < '0' || b[i] > '9') return -1;
    v = v * 10 + (b[i] - '0');
    if (v > 2147483648LL) return -1;
  }
  if (neg) v = -v;
  if (v > 2147483647LL) return -1;
  *out = (int)v;
  return 0;
}

/* The value of node as shown in a message. */
static const char *value_shown(const dicom *d, int node, char *buf, size_t cap) {
  size_t len = 0;
  const unsigned char *v = dicom_value(d, node, &len);
  return shown_bytes((const char *)v, len, buf, cap);
}

static int sequence(reader *r, int node) {
  if (node >= 0 && !dicom_is_sequence(r->d, node))
    return fail(r, dicom_offset(r->d, node), "(%04X,%04X) is not a sequence",
                (unsigned)(dicom_tag(r->d, node) >> 16), (unsigned)(dicom_tag(r->d, node) & 0xFFFF));
  return 0;
}

static char *roi_error(const reader *r, const rtstruct_roi *roi, size_t off, const char *fmt, ...) {
  strbuf b = {0};
  va_list ap;
  strbuf_add(&b, "%s: byte %zu: ROI %d '%s', ", r->name, off, roi->number, roi->name);
  va_start(ap, fmt);
  strbuf_vadd(&b, fmt, ap);
  va_end(ap);
  return b.buf;
}

static void roi_warn(const reader *r, rtstruct_roi *roi, const char *fmt, ...) {
  strbuf b = {roi->warnings, roi->warnings ? strlen(roi->warnings) : 0, 0};
  b.cap = b.len + 1;
  va_list ap;
  strbuf_add(&b, "%s: ROI %d '%s': ", r->name, roi->number, roi->name);
  va_start(ap, fmt);
  strbuf_vadd(&b, fmt, ap);
  va_end(ap);
  strbuf_raw(&b, "\n", 1);
  roi->warnings = b.buf;
}

/* One ContourSequence item of a closed planar contour into c.  0, or -1
 * with roi->error set. */
static int read_contour(reader *r, rtstruct_roi *roi, int item, int k, rtstruct_contour *c) {
  const dicom *d = r->d;
  char vb[200];
  int data = dicom_child(d, item, CONTOUR_DATA), npts = dicom_child(d, item, NUMBER_OF_POINTS);
  memset(c, 0, sizeof *c);
  c->item = k;
  c->offset = dicom_offset(d, item);
  if (data < 0) {
    roi->error = roi_error(r, roi, c->offset, "contour item %d: no ContourData (3006,0050)", k);
    return -1;
  }
  c->offset = dicom_offset(d, data);
  size_t len = 0;
  const char *v = (const char *)dicom_value(d, data, &len);
  size_t base = dicom_value_offset(d, data);
  size_t nval = len ? 1 : 0;
  for (size_t i = 0; i < len; i++) nval += v[i] == '\\';
  if (nval == 0) {
    roi->error = roi_error(r, roi, c->offset, "contour item %d: ContourData is empty", k);
    return -1;
  }
  if (nval % 3 != 0) {
    roi->error = roi_error(r, roi, c->offset,
                           "contour item %d: ContourData holds %zu values, not x y z triplets", k, nval);
    return -1;
  }
  if (nval / 3 > CONTOUR_MAX_POINTS) {
    roi->error = roi_error(r, roi, c->offset, "contour item %d: more than %d points (%zu)", k,
                           CONTOUR_MAX_POINTS, nval / 3);
    return -1;
  }
  if (npts >= 0) {
    int want;
    if (integer(d, npts, &want) != 0) {
      roi->error = roi_error(r, roi, dicom_offset(d, npts),
                             "contour item %d: NumberOfContourPoints is not a whole number (%s)", k,
                             value_shown(d, npts, vb, sizeof vb));
      return -1;
    }
    if ((size_t)want * 3 != nval || want < 0) {
      roi->error = roi_error(r, roi, dicom_offset(d, npts),
                             "contour item %d: NumberOfContourPoints is %d but ContourData holds %zu "
                             "values (%zu points)", k, want, nval, nval / 3);
      return -1;
    }
  }
  c->n = (int)(nval / 3);
  c->p = xmallocarray(nval, sizeof *c->p);
  c->poff = xmallocarray((size_t)c->n, sizeof *c->poff);
  c->tok = xmallocarray(nval + 1, sizeof *c->tok);
  c->txt = xmalloc(len + 1);
  size_t at = 0, t = 0;
  for (size_t i = 0; i < nval; i++) {
    size_t e = at;
    while (e < len && v[e] != '\\') e++;
    double x;
    int rc = decimal_parse(v + at, e - at, &x);
    if (rc != 0) {
      roi->error = roi_error(r, roi, base + at, "contour item %d, point %zu: %c %s (%s)", k, i / 3 + 1,
                             "xyz"[i % 3], rc > 0 ? "is not finite" : "is not a number",
                             shown_bytes(v + at, e - at, vb, sizeof vb));
      return -1;
    }
    c->p[i] = x;
    if (i % 3 == 0) c->poff[i / 3] = base + at;
    /* The value as written, blanks trimmed; %.17g if it is long. */
    size_t a = at, z = e;
    while (a < z && v[a] == ' ') a++;
    while (z > a && (v[z - 1] == ' ' || v[z - 1] == 0)) z--;
    c->tok[i] = (uint32_t)t;
    if (z - a <= 40) {
      memcpy(c->txt + t, v + a, z - a);
      t += z - a;
    } else {   /* fits: the value took more than 40 of the len + 1 bytes */
      t += (size_t)snprintf(c->txt + t, 32, "%.17g", x);
    }
    at = e + 1;
  }
  c->tok[nval] = (uint32_t)t;
  return 0;
}

static void free_contour(rtstruct_contour *c) {
  free(c->p);
  free(c->poff);
  free(c->tok);
  free(c->txt);
}

/* Stable order by height. */
typedef struct {
  double h;
  int i;
} keyed;

static int by_h(const void *a, const void *b) {
  const keyed *p = a, *q = b;
  if (p->h != q->h) return p->h < q->h ? -1 : 1;
  return p->i - q->i;
}

/* ---------------------------------------------------------------- planes */

/* The plane of an ROI's contours, their heights, the order, the counts. */
static void finish_roi(reader *r, rtstruct_roi *roi) {
  if (roi->error || roi->nc == 0) return;
  char why[600], *warn = NULL;
  int bad = -1;
  if (rtframe_fit(roi, &warn, &bad, why, sizeof why) != 0) {
    roi->error = roi_error(r, roi, roi->c[bad].offset, "%s", why);
    return;
  }
  if (warn) roi_warn(r, roi, "%s", warn);
  free(warn);
  keyed *k = xmallocarray((size_t)roi->nc, sizeof *k);
  for (int i = 0; i < roi->nc; i++) {
    k[i].h = roi->c[i].h;
    k[i].i = i;
  }
  qsort(k, (size_t)roi->nc, sizeof *k, by_h);
  rtstruct_contour *sorted = xmallocarray((size_t)roi->nc, sizeof *sorted);
  for (int i = 0; i < roi->nc; i++) sorted[i] = roi->c[k[i].i];
  free(roi->c);
  roi->c = sorted;
  free(k);
  roi->slices = 0;
  roi->points = 0;
  /* Oblique heights are computed, a rounding apart within a plane. */
  double gap = roi->plane == RTSTRUCT_OBLIQUE ? roi->flat : 0;
  for (int i = 0; i < roi->nc; i++) {
    roi->points += roi->c[i].n;
    if (i == 0 || roi->c[i].h - roi->c[i - 1].h > gap) roi->slices++;
  }
  roi->hmin = roi->c[0].h;
  roi->hmax = roi->c[roi->nc - 1].h;
}

/* The ROI numbered `number`: a binary search of r->by_number. */
static rtstruct_roi *roi_by_number(const reader *r, rtstruct *s, int number) {
  int lo = 0, hi = s->nroi - 1;
  while (lo <= hi) {
    int mid = lo + (hi - lo) / 2, v = r->by_number[mid].number;
    if (v == number) return &s->roi[r->by_number[mid].i];
    if (v < number) lo = mid + 1;
    else hi = mid - 1;
  }
  return NULL;
}

static int by_number(const void *a, const void *b) {
  const numbered *p = a, *q = b;
  if (p->number != q->number) return p->number < q->number ? -1 : 1;
  return p->i - q->i;
}

/* The ContourSequence of one ROIContourSequence item into its ROI. */
static void read_contours(reader *r, rtstruct_roi *roi, int cseq) {
  const dicom *d = r->d;
  int kinds = 0, nkind[8] = {0};
  char kind[8][24];
  int k = 0, cap = roi->nc;
  for (int it = dicom_first(d, cseq); it >= 0; it = dicom_next(d, it)) {
    k++;
    char type[24];
    text(d, dicom_child(d, it, GEOMETRIC_TYPE), 0, type, sizeof type);
    if (strcmp(type, "CLOSED_PLANAR") != 0) {
      roi->skipped++;
      if (!type[0]) snprintf(type, sizeof type, "untyped");
      int j = 0;
      while (j < kinds && strcmp(kind[j], type) != 0) j++;
      if (j == kinds && kinds < 8) memcpy(kind[kinds++], type, sizeof type);
      if (j < 8) nkind[j]++;
      continue;
    }
    if (roi->error) {   /* counted, not read */
      roi->nc++;
      continue;
    }
    if (roi->nc == cap) {
      cap = cap ? 2 * cap : 16;
      roi->c = xreallocarray(roi->c, (size_t)cap, sizeof *roi->c);
    }
    if (read_contour(r, roi, it, k, &roi->c[roi->nc]) != 0) {
      free_contour(&roi->c[roi->nc]);
      for (int i = 0; i < roi->nc; i++) free_contour(&roi->c[i]);
      free(roi->c);
      roi->c = NULL;
      cap = 0;
    }
    roi->nc++;
  }
  if (kinds) {
    strbuf b = {0};
    for (int j = 0; j < kinds; j++) {
      char sh[80];
      strbuf_add(&b, "%s%d %s", j == 0 ? "" : j + 1 == kinds ? " and " : ", ", nkind[j],
             shown_bytes(kind[j], strlen(kind[j]), sh, sizeof sh));
    }
    roi_warn(r, roi, "skipped %s contour%s; only CLOSED_PLANAR contours are tiled", b.buf,
             roi->skipped == 1 ? "" : "s");
    free(b.buf);
  }
}

enum { FILE_WARNINGS = 10 };   /* shown; the rest are counted */

static void file_warn(reader *r, size_t off, const char *fmt, ...) {
  va_list ap;
  if (++r->nwarn > FILE_WARNINGS) return;
  strbuf_add(&r->warn, "%s: byte %zu: ", r->name, off);
  va_start(ap, fmt);
  strbuf_vadd(&r->warn, fmt, ap);
  va_end(ap);
  strbuf_raw(&r->warn, "\n", 1);
}

static int read_set(reader *r, rtstruct *s) {
  const dicom *d = r->d;
  char vb[200];
  int mod = dicom_child(d, DICOM_ROOT, MODALITY);
  if (mod >= 0) {
    char m[64];
    text(d, mod, 0, m, sizeof m);
    if (strcmp(m, "RTSTRUCT") != 0)
      return fail(r, dicom_offset(d, mod), "not an RT structure set: the Modality (0008,0060) is %s",
                  value_shown(d, mod, vb, sizeof vb));
  } else {
    char uid[80];
    int sop = dicom_child(d, DICOM_ROOT, SOP_CLASS);
    text(d, sop, 0, uid, sizeof uid);
    if (strcmp(uid, RTSTRUCT_SOP_CLASS) != 0)
      return fail(r, 0, "not an RT structure set: no Modality (0008,0060), and the SOP class (0008,0016) "
                  "is not RT Structure Set Storage (%s)", sop >= 0 ? value_shown(d, sop, vb, sizeof vb) : "none");
  }
  int ss = dicom_child(d, DICOM_ROOT, SS_ROI_SEQ);
  if (ss < 0) return fail(r, 0, "an RT structure set without a StructureSetROISequence (3006,0020)");
  if (sequence(r, ss) != 0) return -1;
  int n = 0;
  for (int it = dicom_first(d, ss); it >= 0; it = dicom_next(d, it)) n++;
  s->roi = xcalloc(n ? (size_t)n : 1, sizeof *s->roi);
  size_t *numoff = xmallocarray(n ? (size_t)n : 1, sizeof *numoff);
  for (int it = dicom_first(d, ss), k = 1; it >= 0; it = dicom_next(d, it), k++) {
    rtstruct_roi *roi = &s->roi[s->nroi];
    int num = dicom_child(d, it, ROI_NUMBER);
    if (num < 0) {
      free(numoff);
      return fail(r, dicom_offset(d, it), "StructureSetROISequence item %d has no ROINumber (3006,0022)", k);
    }
    if (integer(d, num, &roi->number) != 0) {
      free(numoff);
      return fail(r, dicom_offset(d, num), "StructureSetROISequence item %d: ROINumber is not a whole number (%s)",
                  k, value_shown(d, num, vb, sizeof vb));
    }
    roi->offset = dicom_offset(d, it);
    numoff[s->nroi] = dicom_offset(d, num);
    size_t len = 0;
    int nm = dicom_child(d, it, ROI_NAME);
    if (nm >= 0) dicom_value(d, nm, &len);
    roi->name = xmalloc(len + 1);
    size_t l = text(d, nm, 1, roi->name, len + 1);
    for (size_t i = 0; i < l; i++)
      if ((unsigned char)roi->name[i] < 32 || roi->name[i] == 127) roi->name[i] = '?';
    roi->type = xstrdup("");
    s->nroi++;
  }
  /* ROI numbers sorted (so that lookups take log n), each used once: the
   * first item, in file order, whose number an earlier item has is refused. */
  r->by_number = xmallocarray(s->nroi ? (size_t)s->nroi : 1, sizeof *r->by_number);
  for (int i = 0; i < s->nroi; i++) r->by_number[i] = (numbered){s->roi[i].number, i};
  qsort(r->by_number, (size_t)s->nroi, sizeof *r->by_number, by_number);
  int dup = -1, first = -1;
  for (int i = 1; i < s->nroi; i++)
    if (r->by_number[i].number == r->by_number[i - 1].number && (dup < 0 || r->by_number[i].i < dup))
      dup = r->by_number[i].i, first = r->by_number[i - 1].i;
  if (dup >= 0) {
    fail(r, numoff[dup], "StructureSetROISequence item %d: ROI number %d is already used by the item at "
         "byte %zu (%d)", dup + 1, s->roi[dup].number, s->roi[first].offset, s->roi[dup].number);
    free(numoff);
    return -1;
  }
  free(numoff);
  int obs = dicom_child(d, DICOM_ROOT, OBSERVATIONS_SEQ);
  if (sequence(r, obs) != 0) return -1;
  for (int it = obs >= 0 ? dicom_first(d, obs) : -1; it >= 0; it = dicom_next(d, it)) {
    int ref = dicom_child(d, it, REF_ROI_NUMBER), num;
    rtstruct_roi *roi = ref >= 0 && integer(d, ref, &num) == 0 ? roi_by_number(r, s, num) : NULL;
    int ty = dicom_child(d, it, INTERPRETED_TYPE);
    if (!roi || ty < 0 || roi->type[0]) continue;
    char t[64];
    size_t l = text(d, ty, 0, t, sizeof t);
    for (size_t i = 0; i < l; i++)
      if ((unsigned char)t[i] < 32 || t[i] == 127) t[i] = '?';
    free(roi->type);
    roi->type = xstrdup(t);
  }
  int rc = dicom_child(d, DICOM_ROOT, ROI_CONTOUR_SEQ);
  if (sequence(r, rc) != 0) return -1;
  for (int it = rc >= 0 ? dicom_first(d, rc) : -1, k = 1; it >= 0; it = dicom_next(d, it), k++) {
    int ref = dicom_child(d, it, REF_ROI_NUMBER), num;
    int cs = dicom_child(d, it, CONTOUR_SEQ);
    if (sequence(r, cs) != 0) return -1;
    int ncont = 0;
    for (int c = cs >= 0 ? dicom_first(d, cs) : -1; c >= 0; c = dicom_next(d, c)) ncont++;
    if (ref < 0) {
      file_warn(r, dicom_offset(d, it), "ROIContourSequence item %d has no ReferencedROINumber (3006,0084); "
                "its %d contour%s ignored", k, ncont, ncont == 1 ? " is" : "s are");
      continue;
    }
    if (integer(d, ref, &num) != 0)
      return fail(r, dicom_offset(d, ref), "ROIContourSequence item %d: ReferencedROINumber is not a whole "
                  "number (%s)", k, value_shown(d, ref, vb, sizeof vb));
    rtstruct_roi *roi = roi_by_number(r, s, num);
    if (!roi) {
      file_warn(r, dicom_offset(d, it), "ROIContourSequence item %d references ROI %d, which the "
                "StructureSetROISequence does not define; its %d contour%s ignored", k, num, ncont,
                ncont == 1 ? " is" : "s are");
      continue;
    }
    if (cs >= 0) read_contours(r, roi, cs);
  }
  if (r->nwarn > FILE_WARNINGS)
    strbuf_add(&r->warn, "%s: and %d more warnings like these\n", r->name, r->nwarn - FILE_WARNINGS);
  for (int i = 0; i < s->nroi; i++) finish_roi(r, &s->roi[i]);
  return 0;
}

int rtstruct_parse(const unsigned char *buf, size_t len, const char *name, rtstruct *out,
                   char *err, size_t errlen) {
  memset(out, 0, sizeof *out);
  dicom *d = dicom_parse(buf, len, name, sequences, (int)(sizeof sequences / sizeof *sequences), err, errlen);
  if (!d) return -1;
  reader r = {d, name, err, errlen, {0}, 0, NULL};
  out->name = xstrdup(name);
  int rc = read_set(&r, out);
  free(r.by_number);
  dicom_free(d);
  if (rc != 0) {
    free(r.warn.buf);
    rtstruct_free(out);
    return -1;
  }
  out->warnings = r.warn.buf;
  return 0;
}

int rtstruct_read(const char *path, rtstruct *out, char *err, size_t errlen) {
  size_t len;
  char *buf = readfile(path, &len, err, errlen);
  memset(out, 0, sizeof *out);
  if (!buf) return -1;
  int rc = rtstruct_parse((const unsigned char *)buf, len, readfile_name(path), out, err, errlen);
  free(buf);
  return rc;
}

void rtstruct_free(rtstruct *s) {
  for (int i = 0; i < s->nroi; i++) {
    rtstruct_roi *roi = &s->roi[i];
    if (roi->c)
      for (int j = 0; j < roi->nc; j++) free_contour(&roi->c[j]);
    free(roi->c);
    free(roi->name);
    free(roi->type);
    free(roi->error);
    free(roi->warnings);
  }
  free(s->roi);
  free(s->name);
  free(s->warnings);
  memset(s, 0, sizeof *s);
}

/* ---------------------------------------------------------------- lookup */

int rtstruct_find(const rtstruct *s, const char *key, char *err, size_t errlen) {
  char vb[200];
  int found = -1;
  for (int i = 0; i < s->nroi; i++)
    if (strcmp(s->roi[i].name, key) == 0) {
      if (found >= 0) {
        snprintf(err, errlen, "%s: ROIs %d and %d are both named '%s'; choose one by its number (%s)",
                 s->name, s->roi[found].number, s->roi[i].number, s->roi[i].name,
                 shown_bytes(key, strlen(key), vb, sizeof vb));
        return -1;
      }
      found = i;
    }
  if (found >= 0) return found;
  char *end;
  errno = 0;
  long v = strtol(key, &end, 10);
  if (key[0] && *end == 0 && errno == 0 && key[0] != ' ')
    for (int i = 0; i < s->nroi; i++)
      if (s->roi[i].number == v) return i;
  strbuf b = {0};
  for (int i = 0; i < s->nroi && b.len < 300; i++)
    strbuf_add(&b, "%s%d '%s'", i ? ", " : "", s->roi[i].number, s->roi[i].name);
  if (b.len >= 300) strbuf_add(&b, ", ...");
  snprintf(err, errlen, "%s: no ROI named or numbered '%s' (the ROIs: %s)", s->name,
           shown_bytes(key, strlen(key), vb, sizeof vb), b.buf ? b.buf : "none");
  free(b.buf);
  return -1;
}

/* ---------------------------------------------------------------- stacks */

const char *rtstruct_plane_name(rtstruct_plane plane) {
  return plane == RTSTRUCT_AXIAL      ? "axial"
         : plane == RTSTRUCT_SAGITTAL ? "sagittal"
         : plane == RTSTRUCT_CORONAL  ? "coronal"
                                      : "oblique";
}

/* The stack frame: axial (x, y, z); sagittal (y, z, x); coronal (z, x, y):
 * cyclic permutations of the axes, so rotations; oblique: x u + y v + h n. */
void rtstruct_to_patient(const rtstruct_roi *roi, double *x, double *y, double *z) {
  double u = *x, v = *y, h = *z;
  if (roi->plane == RTSTRUCT_SAGITTAL) *x = h, *y = u, *z = v;
  else if (roi->plane == RTSTRUCT_CORONAL) *x = v, *y = h, *z = u;
  else if (roi->plane == RTSTRUCT_OBLIQUE) {
    const rtstruct_frame *f = &roi->frame;
    *x = u * f->u[0] + v * f->v[0] + h * f->n[0];
    *y = u * f->u[1] + v * f->v[1] + h * f->n[1];
    *z = u * f->u[2] + v * f->v[2] + h * f->n[2];
  }
}

void rtstruct_height_text(const rtstruct_roi *roi, int k, char *buf, size_t cap) {
  const rtstruct_contour *c = &roi->c[k];
  if (roi->plane == RTSTRUCT_OBLIQUE) {
    snprintf(buf, cap, "%.17g", c->h);
    return;
  }
  int ih = roi->plane == RTSTRUCT_AXIAL ? 2 : roi->plane == RTSTRUCT_SAGITTAL ? 0 : 1;
  size_t n = c->tok[ih + 1] - c->tok[ih];
  if (n > cap - 1) n = cap - 1;
  memcpy(buf, c->txt + c->tok[ih], n);
  buf[n] = 0;
}

/* Comment lines the text starts with (the line map counts them). */
enum { HEADER_LINES = 2 };

static void clean(const char *s, char *buf, size_t cap) {
  size_t j = 0;
  for (size_t i = 0; s[i] && j + 1 < cap; i++)
    buf[j++] = (unsigned char)s[i] < 32 || s[i] == 127 ? '?' : s[i];
  buf[j] = 0;
}

char *rtstruct_roi_text(const rtstruct *s, int ri, size_t *len) {
  const rtstruct_roi *roi = &s->roi[ri];
  strbuf b = {0};
  char file[512], type[80];
  clean(s->name, file, sizeof file);
  clean(roi->type, type, sizeof type);
  strbuf_add(&b, "# ROI %d '%s'%s%s%s of %s: %d closed planar contours, patient LPS mm\n", roi->number,
         roi->name, type[0] ? " (" : "", type, type[0] ? ")" : "", file, roi->nc);
  if (roi->plane == RTSTRUCT_OBLIQUE)
    strbuf_add(&b, "# oblique contours turned into z: each point is x' = u.p, y' = v.p, each plane h = n.p, u = (%.17g %.17g %.17g), v = (%.17g %.17g %.17g), n = (%.17g %.17g %.17g)\n",
               roi->frame.u[0], roi->frame.u[1], roi->frame.u[2], roi->frame.v[0], roi->frame.v[1], roi->frame.v[2],
               roi->frame.n[0], roi->frame.n[1], roi->frame.n[2]);
  else if (roi->plane == RTSTRUCT_AXIAL)
    strbuf_add(&b, "# axial contours, sorted by z; each point is x y\n");
  else if (roi->plane == RTSTRUCT_SAGITTAL)
    strbuf_add(&b, "# sagittal contours turned into z: each point is patient y z, each plane patient x\n");
  else
    strbuf_add(&b, "# coronal contours turned into z: each point is patient z x, each plane patient y\n");
  /* The numbers as the file wrote them (the same doubles: both readers
   * round correctly), in the frame's order. */
  int iu = roi->plane == RTSTRUCT_AXIAL ? 0 : roi->plane == RTSTRUCT_SAGITTAL ? 1 : 2;
  int iv = (iu + 1) % 3, ih = (iu + 2) % 3;
  char line[96];
  for (int i = 0; i < roi->nc; i++) {
    const rtstruct_contour *c = &roi->c[i];
    if (roi->plane == RTSTRUCT_OBLIQUE) {   /* computed: %.17g reads back exactly */
      const rtstruct_frame *f = &roi->frame;
      strbuf_add(&b, "C %d %.17g\n", c->n, c->h);
      for (int j = 0; j < c->n; j++) strbuf_add(&b, "%.17g %.17g\n", rtframe_dot(f->u, c->p + 3 * j), rtframe_dot(f->v, c->p + 3 * j));
      continue;
    }
    int k = snprintf(line, sizeof line, "C %d ", c->n);
    strbuf_raw(&b, line, (size_t)k);
    strbuf_raw(&b, c->txt + c->tok[ih], c->tok[ih + 1] - c->tok[ih]);
    strbuf_raw(&b, "\n", 1);
    for (int j = 0; j < c->n; j++) {
      const uint32_t *t = c->tok + 3 * j;
      strbuf_raw(&b, c->txt + t[iu], t[iu + 1] - t[iu]);
      strbuf_raw(&b, " ", 1);
      strbuf_raw(&b, c->txt + t[iv], t[iv + 1] - t[iv]);
      strbuf_raw(&b, "\n", 1);
    }
  }
  *len = b.len;
  return b.buf ? b.buf : xstrdup("");
}

/* The contour of the ROI whose header (*j = 0) or point *j is line `line`
 * of its text: its index, or -1 (a comment line, or past the end). */
static int contour_of_line(const rtstruct_roi *roi, long line, long *j) {
  long at = HEADER_LINES + 1;
  for (int i = 0; i < roi->nc; i++) {
    if (line >= at && line <= at + roi->c[i].n) {
      *j = line - at;
      return i;
    }
    at += roi->c[i].n + 1;
  }
  return -1;
}

/* Where line `line` of the ROI's text came from: "FILE: byte N: ROI r 'name',
 * contour item k[, point j]" (with_byte), else "contour item k[, point j]",
 * or "point j" alone when it is a point of contour `cur`.  Returns the
 * contour's index when the line is its header (the message is about that
 * contour: its points may be named alone), else -1 (a comment line, or a
 * point: that names a loop of a keyhole contour, and the message's other
 * lines name contours in full). */
static int locate(const rtstruct_roi *roi, long line, strbuf *b, int with_byte, int cur, const char *file) {
  long j;
  int i = contour_of_line(roi, line, &j);
  if (i >= 0) {
    const rtstruct_contour *c = &roi->c[i];
    if (with_byte) strbuf_add(b, "%s: byte %zu: ROI %d '%s', ", file, j ? c->poff[j - 1] : c->offset,
                              roi->number, roi->name);
    if (j && i == cur) strbuf_add(b, "point %ld", j);
    else if (j) strbuf_add(b, "contour item %d, point %ld", c->item, j);
    else strbuf_add(b, "contour item %d", c->item);
    return j ? -1 : i;   /* a point names a loop of a keyhole contour, not the contour */
  }
  if (with_byte) strbuf_add(b, "%s: ROI %d '%s', ", file, roi->number, roi->name);
  strbuf_add(b, "line %ld of its stack", line);
  return -1;
}

/* ---------------------------------------------------------------- places */

/* The places of an ROI's stack (contour.h): each contour and point is
 * named by the line the ROI's text gives it, and said as the file's byte,
 * the ROI and the contour item. */
typedef struct {
  const rtstruct *s;
  const rtstruct_roi *roi;
} roi_places;

static void roi_head(void *ud, strbuf *b, int line) {
  const roi_places *p = ud;
  if (line > 0) locate(p->roi, line, b, 1, -1, p->s->name);
  else strbuf_add(b, "%s: ROI %d '%s'", p->s->name, p->roi->number, p->roi->name);
}

static void roi_ref(void *ud, char *buf, size_t cap, int line, int head) {
  const roi_places *p = ud;
  long j = 0;
  int cur = head > 0 ? contour_of_line(p->roi, head, &j) : -1;
  strbuf b = {0};
  locate(p->roi, line, &b, 0, j == 0 ? cur : -1, p->s->name);
  snprintf(buf, cap, "%s", b.buf);
  free(b.buf);
}

static int digit(char c) { return c >= '0' && c <= '9'; }

/* A message with `name` and its line numbers rewritten; within a line,
 * points of the contour its prefix names are "point j". */
static char *rewrite(const rtstruct *s, const rtstruct_roi *roi, const char *name, const char *msg) {
  strbuf b = {0};
  size_t sl = strlen(name);
  int cur = -1;
  strbuf_raw(&b, "", 0);
  for (const char *p = msg; *p;) {
    if (sl && strncmp(p, name, sl) == 0) {
      const char *q = p + sl;
      if (q[0] == ':' && digit(q[1])) {
        long line = strtol(q + 1, (char **)&q, 10);
        if (*q == ':') q++;
        cur = locate(roi, line, &b, 1, -1, s->name);
        strbuf_raw(&b, ":", 1);
      } else {
        strbuf_add(&b, "%s: ROI %d '%s'", s->name, roi->number, roi->name);
      }
      p = q;
    } else if (strncmp(p, "line ", 5) == 0 && digit(p[5]) && (p == msg || !((p[-1] >= 'a' && p[-1] <= 'z') ||
                                                                           (p[-1] >= 'A' && p[-1] <= 'Z')))) {
      const char *q;
      long line = strtol(p + 5, (char **)&q, 10);
      locate(roi, line, &b, 0, cur, s->name);
      p = q;
    } else {
      if (*p == '\n') cur = -1;
      strbuf_raw(&b, p, 1);
      p++;
    }
  }
  return b.buf;
}

char *rtstruct_rewrite(const rtstruct *s, int ri, const char *name, const char *msg) {
  return rewrite(s, &s->roi[ri], name, msg);
}

int rtstruct_roi_check(const rtstruct *s, int ri, char *err, size_t errlen) {
  const rtstruct_roi *roi = &s->roi[ri];
  if (roi->error) {
    snprintf(err, errlen, "%s", roi->error);
    return -1;
  }
  if (roi->nc > 0) return 0;
  if (roi->skipped)
    snprintf(err, errlen, "%s: ROI %d '%s' has no closed planar contours to tile (%d contour%s)", s->name,
             roi->number, roi->name, roi->skipped, roi->skipped == 1 ? " of another type" : "s of other types");
  else
    snprintf(err, errlen, "%s: ROI %d '%s' has no contours to tile", s->name, roi->number, roi->name);
  return -1;
}

/* msg into err[0..cap-1]: whole, or as many of its first lines as fit with
 * its last line (the summary of a list) and one saying how many were left
 * out. */
static void fit_lines(const char *msg, char *err, size_t cap) {
  size_t n = strlen(msg);
  if (n < cap) {
    memcpy(err, msg, n + 1);
    return;
  }
  const char *last = strrchr(msg, '\n');
  last = last ? last + 1 : msg;
  int left = 0;
  for (const char *p = msg; p < last; p++) left += *p == '\n';
  size_t at = 0, tail = strlen(last) + 64;
  const char *p = msg;
  while (p < last) {
    const char *e = strchr(p, '\n');
    size_t l = (size_t)(e - p) + 1;
    if (at + l + tail >= cap) break;
    memcpy(err + at, p, l);
    at += l;
    left--;
    p = e + 1;
  }
  if (at + tail < cap) {
    at += (size_t)snprintf(err + at, cap - at, "(%d more line%s not shown)\n", left, left == 1 ? "" : "s");
    snprintf(err + at, cap - at, "%s", last);
  } else {
    snprintf(err, cap, "%s", last);
  }
}

/* A computed value v of the ROI's stack at `line` that is not finite: -1
 * with "PLACE: C is not finite (V)" in err, as the .contours reader says it
 * of the text; else 0. */
static int not_finite(const contour_places *pl, int line, char c, double v, char *err, size_t errlen) {
  if (isfinite(v)) return 0;
  strbuf b = {0};
  pl->head(pl->ud, &b, line);
  strbuf_add(&b, ": %c is not finite (%.17g)", c, v);
  snprintf(err, errlen, "%s", b.buf);
  free(b.buf);
  return -1;
}

int rtstruct_roi_stack(const rtstruct *s, int ri, int flags, contour_stack *out, FILE *notes,
                       const char *prefix, char *err, size_t errlen) {
  const rtstruct_roi *roi = &s->roi[ri];
  memset(out, 0, sizeof *out);
  if (rtstruct_roi_check(s, ri, err, errlen) != 0) return -1;
  roi_places rp = {s, roi};
  contour_places pl = {roi_head, roi_ref, &rp};
  contour_build *b = contour_build_open(&pl, flags, prefix);
  size_t e2len = errlen > 1024 ? errlen : 1024;
  char *e2 = xmalloc(e2len);
  /* The contours in their order, each named by the line the ROI's text
   * gives it; the values those of the text (oblique: computed, and refused
   * as the text is when one is not finite). */
  int iu = roi->plane == RTSTRUCT_AXIAL ? 0 : roi->plane == RTSTRUCT_SAGITTAL ? 1 : 2, iv = (iu + 1) % 3;
  const rtstruct_frame *f = &roi->frame;
  int line = HEADER_LINES + 1, rc = 0;
  for (int i = 0; i < roi->nc && rc == 0; i++) {
    const rtstruct_contour *c = &roi->c[i];
    rc = not_finite(&pl, line, 'z', c->h, e2, e2len);
    contour_build_begin(b, c->h, line);
    for (int j = 0; j < c->n && rc == 0; j++) {
      const double *p = c->p + 3 * j;
      vec2 q = roi->plane == RTSTRUCT_OBLIQUE ? (vec2){rtframe_dot(f->u, p), rtframe_dot(f->v, p)}
                                              : (vec2){p[iu], p[iv]};
      if ((rc = not_finite(&pl, line + 1 + j, 'x', q.x, e2, e2len)) == 0 &&
          (rc = not_finite(&pl, line + 1 + j, 'y', q.y, e2, e2len)) == 0)
        contour_build_point(b, q, line + 1 + j);
    }
    if (rc == 0) contour_build_end(b);
    line += c->n + 1;
  }
  /* A refusal that lists bad contours is fitted to err whole lines at a
   * time, its summary kept. */
  if (rc == 0) rc = contour_build_close(b, out, notes, e2, e2len);
  else contour_build_free(b);
  if (rc != 0) fit_lines(e2, err, errlen);
  free(e2);
  return rc;
}
