/* rtwriter.c -- a DICOM RTSTRUCT writer for the tests (PS3.10 7.1 file meta,
 * PS3.5 7.1 element encodings, 7.5 sequences and items).
 *
 * A growing byte buffer; an open sequence or item of defined length keeps
 * the position of its length field, patched when it is closed. */
#include "tests/rtwriter.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

typedef struct {
  unsigned char *b;
  size_t len, cap;
  int explicit_vr, undefined;
} out;

static void put(out *o, const void *p, size_t n) {
  if (o->len + n > o->cap) {
    o->cap = (o->len + n) * 2 + 256;
    o->b = xrealloc(o->b, o->cap);
  }
  memcpy(o->b + o->len, p, n);
  o->len += n;
}

static void put16(out *o, unsigned v) {
  unsigned char b[2] = {(unsigned char)v, (unsigned char)(v >> 8)};
  put(o, b, 2);
}

static void put32(out *o, uint32_t v) {
  unsigned char b[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16),
                        (unsigned char)(v >> 24)};
  put(o, b, 4);
}

static void patch32(out *o, size_t at, uint32_t v) {
  for (int i = 0; i < 4; i++) o->b[at + (size_t)i] = (unsigned char)(v >> (8 * i));
}

static int long_vr(const char *vr) {
  static const char *longs[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC", "UN", "UR", "UT", "UV"};
  for (size_t i = 0; i < sizeof longs / sizeof *longs; i++)
    if (strcmp(vr, longs[i]) == 0) return 1;
  return 0;
}

/* An element with its value; pad (' ' or 0) to even length unless odd. */
static void elem_raw(out *o, int ex, unsigned g, unsigned e, const char *vr, const void *v, size_t n,
                     int pad, int odd) {
  size_t len = n + (!odd && n % 2 ? 1 : 0);
  put16(o, g);
  put16(o, e);
  if (ex) {
    put(o, vr, 2);
    if (long_vr(vr)) {
      put16(o, 0);
      put32(o, (uint32_t)len);
    } else {
      put16(o, (unsigned)len);
    }
  } else {
    put32(o, (uint32_t)len);
  }
  put(o, v, n);
  if (len > n) {
    unsigned char c = (unsigned char)pad;
    put(o, &c, 1);
  }
}

static void str(out *o, unsigned g, unsigned e, const char *vr, const char *s) {
  elem_raw(o, o->explicit_vr, g, e, vr, s, strlen(s), strcmp(vr, "UI") == 0 ? 0 : ' ', 0);
}

/* Open a sequence (explicit: VR SQ) or an item; returns where its length is. */
static size_t seq_open(out *o, unsigned g, unsigned e) {
  put16(o, g);
  put16(o, e);
  if (o->explicit_vr) {
    put(o, "SQ", 2);
    put16(o, 0);
  }
  size_t at = o->len;
  put32(o, o->undefined ? 0xFFFFFFFFu : 0);
  return at;
}

static void seq_close(out *o, size_t at) {
  if (o->undefined) {
    put16(o, 0xFFFE), put16(o, 0xE0DD), put32(o, 0);
  } else {
    patch32(o, at, (uint32_t)(o->len - at - 4));
  }
}

static size_t item_open(out *o) {
  put16(o, 0xFFFE);
  put16(o, 0xE000);
  size_t at = o->len;
  put32(o, o->undefined ? 0xFFFFFFFFu : 0);
  return at;
}

static void item_close(out *o, size_t at) {
  if (o->undefined) {
    put16(o, 0xFFFE), put16(o, 0xE00D), put32(o, 0);
  } else {
    patch32(o, at, (uint32_t)(o->len - at - 4));
  }
}

static void number(out *o, unsigned g, unsigned e, int v) {
  char b[24];
  snprintf(b, sizeof b, "%d", v);
  str(o, g, e, "IS", b);
}

/* Extra elements a reader must skip, before the structure set's own. */
static void extras(out *o) {
  str(o, 0x0009, 0x0010, "LO", "TILESIM TEST");
  /* An odd-length private value. */
  elem_raw(o, o->explicit_vr, 0x0009, 0x1001, o->explicit_vr ? "LO" : "", "odd", 3, ' ', 1);
  if (o->explicit_vr) {
    /* UN of undefined length: an implicit VR sequence inside (PS3.5 6.2.2). */
    put16(o, 0x0009), put16(o, 0x1002), put(o, "UN", 2), put16(o, 0), put32(o, 0xFFFFFFFFu);
    put16(o, 0xFFFE), put16(o, 0xE000), put32(o, 0xFFFFFFFFu);
    elem_raw(o, 0, 0x0009, 0x1003, "", "implicit inside", 16, ' ', 0);
    put16(o, 0xFFFE), put16(o, 0xE00D), put32(o, 0);
    put16(o, 0xFFFE), put16(o, 0xE0DD), put32(o, 0);
    /* A long text (4-byte length form). */
    elem_raw(o, 1, 0x0009, 0x1004, "UT", "a long text", 11, ' ', 0);
  } else {
    /* A private sequence the reader does not know: skipped by length, or
     * walked when its length is undefined. */
    size_t s = seq_open(o, 0x0009, 0x1002);
    size_t i = item_open(o);
    str(o, 0x0009, 0x1003, "LO", "inside");
    item_close(o, i);
    seq_close(o, s);
  }
}

/* (3006,0010) ReferencedFrameOfReferenceSequence, nested four deep. */
static void frame_refs(out *o) {
  size_t s1 = seq_open(o, 0x3006, 0x0010), i1 = item_open(o);
  str(o, 0x0020, 0x0052, "UI", "1.2.3.4");
  size_t s2 = seq_open(o, 0x3006, 0x0012), i2 = item_open(o);
  str(o, 0x0008, 0x1150, "UI", "1.2.840.10008.3.1.2.3.1");
  size_t s3 = seq_open(o, 0x3006, 0x0014), i3 = item_open(o);
  str(o, 0x0020, 0x000E, "UI", "1.2.3.4.5");
  size_t s4 = seq_open(o, 0x3006, 0x0016), i4 = item_open(o);
  str(o, 0x0008, 0x1155, "UI", "1.2.3.4.5.6");
  item_close(o, i4), seq_close(o, s4);
  item_close(o, i3), seq_close(o, s3);
  item_close(o, i2), seq_close(o, s2);
  item_close(o, i1), seq_close(o, s1);
}

static void contour_data(out *o, const rtw_contour *c) {
  if (c->data) {
    str(o, 0x3006, 0x0050, "DS", c->data);
    return;
  }
  size_t cap = (size_t)c->n * 3 * 26 + 2, k = 0;
  char *t = xmalloc(cap);
  for (int i = 0; i < 3 * c->n; i++)
    k += (size_t)snprintf(t + k, cap - k, "%s%.17g", i ? "\\" : "", c->xyz[i]);
  /* DS values over 16 bytes: long VR text, as real files have; an explicit
   * 2-byte length caps the value at 65534 bytes, so long data goes as UN
   * there (a reader takes DS text from either). */
  if (o->explicit_vr && k > 65534) elem_raw(o, 1, 0x3006, 0x0050, "UN", t, k, ' ', 0);
  else str(o, 0x3006, 0x0050, "DS", t);
  free(t);
}

unsigned char *rtw_write(const rtw_opts *op, const rtw_roi *roi, int nroi, size_t *len) {
  out o = {NULL, 0, 0, op->explicit_vr, op->undefined};
  const char *ts = op->ts ? op->ts : op->explicit_vr ? "1.2.840.10008.1.2.1" : "1.2.840.10008.1.2";
  const char *sop = "1.2.840.10008.5.1.4.1.1.481.3";
  if (op->layout == 0) {
    unsigned char pre[128];
    memset(pre, 0, sizeof pre);
    put(&o, pre, sizeof pre);
    put(&o, "DICM", 4);
  }
  if (op->layout <= 1) {
    /* The meta group: always explicit VR LE, with its group length. */
    int ex = o.explicit_vr;
    o.explicit_vr = 1;
    size_t gl = o.len;
    elem_raw(&o, 1, 0x0002, 0x0000, "UL", "\0\0\0\0", 4, 0, 0);
    size_t start = o.len;
    elem_raw(&o, 1, 0x0002, 0x0001, "OB", "\0\1", 2, 0, 0);
    str(&o, 0x0002, 0x0002, "UI", sop);
    str(&o, 0x0002, 0x0003, "UI", "1.2.3.4.5.6.7");
    str(&o, 0x0002, 0x0010, "UI", ts);
    str(&o, 0x0002, 0x0012, "UI", "1.2.3.4.9");
    patch32(&o, gl + 8, (uint32_t)(o.len - start));
    o.explicit_vr = ex;
  }
  str(&o, 0x0008, 0x0005, "CS", "ISO_IR 100");
  str(&o, 0x0008, 0x0016, "UI", sop);
  str(&o, 0x0008, 0x0060, "CS", op->modality ? op->modality : "RTSTRUCT");
  if (op->extras) extras(&o);
  if (op->deep > 0) {
    size_t *at = xmallocarray((size_t)op->deep * 2, sizeof *at);
    int undef = o.undefined;
    o.undefined = 1;
    for (int d = 0; d < op->deep; d++) at[2 * d] = seq_open(&o, 0x0011, 0x1010), at[2 * d + 1] = item_open(&o);
    for (int d = op->deep - 1; d >= 0; d--) item_close(&o, at[2 * d + 1]), seq_close(&o, at[2 * d]);
    o.undefined = undef;
    free(at);
  }
  str(&o, 0x3006, 0x0002, "SH", "tilesim");
  if (op->extras) frame_refs(&o);
  size_t s = seq_open(&o, 0x3006, 0x0020);
  for (int r = 0; r < nroi; r++) {
    size_t it = item_open(&o);
    number(&o, 0x3006, 0x0022, roi[r].number);
    str(&o, 0x3006, 0x0024, "UI", "1.2.3.4");
    if (roi[r].name) str(&o, 0x3006, 0x0026, "LO", roi[r].name);
    str(&o, 0x3006, 0x0036, "CS", "MANUAL");
    item_close(&o, it);
  }
  seq_close(&o, s);
  s = seq_open(&o, 0x3006, 0x0039);
  for (int r = 0; r < nroi; r++) {
    size_t it = item_open(&o);
    str(&o, 0x3006, 0x002A, "IS", "255\\0\\0");
    if (!roi[r].no_contours) {
      size_t cs = seq_open(&o, 0x3006, 0x0040);
      for (int k = 0; k < roi[r].nc; k++) {
        const rtw_contour *c = &roi[r].c[k];
        size_t ci = item_open(&o);
        if (op->extras) {
          size_t im = seq_open(&o, 0x3006, 0x0016), ii = item_open(&o);
          str(&o, 0x0008, 0x1150, "UI", "1.2.840.10008.5.1.4.1.1.2");
          str(&o, 0x0008, 0x1155, "UI", "1.2.3.4.5.6.7.8");
          item_close(&o, ii), seq_close(&o, im);
        }
        str(&o, 0x3006, 0x0042, "CS", c->geom ? c->geom : "CLOSED_PLANAR");
        if (c->npoints != -2) number(&o, 0x3006, 0x0046, c->npoints == -1 ? c->n : c->npoints);
        contour_data(&o, c);
        item_close(&o, ci);
      }
      seq_close(&o, cs);
    }
    number(&o, 0x3006, 0x0084, roi[r].ref ? roi[r].ref : roi[r].number);
    item_close(&o, it);
  }
  seq_close(&o, s);
  s = seq_open(&o, 0x3006, 0x0080);
  for (int r = 0; r < nroi; r++) {
    size_t it = item_open(&o);
    number(&o, 0x3006, 0x0082, r + 1);
    number(&o, 0x3006, 0x0084, roi[r].number);
    if (roi[r].type) str(&o, 0x3006, 0x00A4, "CS", roi[r].type);
    str(&o, 0x3006, 0x00A6, "PN", "");
    item_close(&o, it);
  }
  seq_close(&o, s);
  *len = o.len;
  return o.b;
}

int rtw_save(const char *dir, const char *name, const unsigned char *b, size_t len) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "wb");
  if (!f || fwrite(b, 1, len, f) != len || fclose(f) != 0) {
    fprintf(stderr, "cannot write %s\n", path);
    return 1;
  }
  return 0;
}
