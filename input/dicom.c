/* dicom.c -- a small DICOM Part 10 reader (PS3.10 7.1, PS3.5 7): the data set
 * as a tree of elements, every length checked against its parent.
 *
 *   file:     [128-byte preamble "DICM"] [group 0002, explicit VR LE] data set
 *   element:  implicit VR   tag(4) len(4) value
 *             explicit VR   tag(4) VR(2) len(2) value        (AE AS AT CS DA ...)
 *                           tag(4) VR(2) 00 00 len(4) value  (OB OW SQ UN UT ...)
 *   sequence: items (FFFE,E000) len(4), then (FFFE,E0DD) 0 if undefined length
 *   item:     elements, then (FFFE,E00D) 0 if undefined length
 *
 * Items and delimiters never carry a VR, in explicit VR too.  The reader is
 * recursive over sequences, at most DICOM_MAX_DEPTH deep. */
#include "input/dicom.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

#define UNDEFINED 0xFFFFFFFFu
#define ITEM_END DICOM_TAG(0xFFFE, 0xE00D)
#define SEQ_END DICOM_TAG(0xFFFE, 0xE0DD)
#define PIXEL_DATA DICOM_TAG(0x7FE0, 0x0010)
#define TRANSFER_SYNTAX DICOM_TAG(0x0002, 0x0010)

typedef struct {
  uint32_t tag;
  char vr[2];           /* explicit VR, or two zeros */
  unsigned char seq;    /* a sequence read into */
  int parent, first, last, next;
  size_t off;           /* of the tag */
  size_t voff, vlen;    /* the value; vlen 0 for sequences and undefined lengths */
} elem;

struct dicom {
  const unsigned char *buf;
  size_t len;
  elem *n;
  int nn, cap;
  int explicit_vr;
  char ts[72];
};

typedef struct {
  dicom *d;
  const char *name;
  const uint32_t *descend;
  int ndescend;
  char *err;
  size_t errlen;
} parser;

static int fail(parser *p, size_t off, const char *fmt, ...) {
  va_list ap;
  int k = snprintf(p->err, p->errlen, "%s: byte %zu: ", p->name, off);
  if (k < 0) k = 0;
  if ((size_t)k < p->errlen) {
    va_start(ap, fmt);
    vsnprintf(p->err + k, p->errlen - (size_t)k, fmt, ap);
    va_end(ap);
  }
  return -1;
}

static unsigned u16(const unsigned char *b) { return (unsigned)b[0] | (unsigned)b[1] << 8; }
static uint32_t u32(const unsigned char *b) {
  return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}
static uint32_t tag_at(const unsigned char *b) { return (uint32_t)u16(b) << 16 | u16(b + 2); }

static int add(parser *p, int parent, uint32_t tag, size_t off) {
  dicom *d = p->d;
  if (d->nn == d->cap) {
    d->cap = d->cap ? 2 * d->cap : 256;
    d->n = xreallocarray(d->n, (size_t)d->cap, sizeof *d->n);
  }
  int i = d->nn++;
  elem *x = &d->n[i];
  memset(x, 0, sizeof *x);
  x->tag = tag;
  x->parent = parent;
  x->first = x->last = x->next = -1;
  x->off = off;
  if (parent >= 0) {
    elem *q = &d->n[parent];
    if (q->last >= 0) d->n[q->last].next = i;
    else q->first = i;
    q->last = i;
  }
  return i;
}

static int descends(const parser *p, uint32_t tag) {
  for (int i = 0; i < p->ndescend; i++)
    if (p->descend[i] == tag) return 1;
  return 0;
}

/* "the file ends at byte N" or "its parent ends at byte N".  A length past
 * the file's end is what a cut file gives, and also a damaged one (a length
 * read from the wrong bytes): both are said. */
static const char *bound(const parser *p, size_t end, char *buf, size_t cap) {
  if (end == p->d->len) snprintf(buf, cap, "corrupt or truncated: the file ends at byte %zu", end);
  else snprintf(buf, cap, "its parent ends at byte %zu", end);
  return buf;
}

/* A binary file copied as text: every LF byte (0x0a) follows a CR (0x0d),
 * as LF turned into CR LF leaves it (at least two, for a chance match is
 * then below 1 in 65,536).  Appended to a refusal: the byte of the first. */
static void crlf_hint(const unsigned char *buf, size_t len, char *err, size_t errlen) {
  size_t lf = 0, first = 0;
  for (size_t i = 0; i < len; i++) {
    if (buf[i] != '\n') continue;
    if (i == 0 || buf[i - 1] != '\r') return;
    if (lf++ == 0) first = i - 1;
  }
  if (lf < 2) return;
  size_t k = strlen(err);
  if (k + 1 < errlen)
    snprintf(err + k, errlen - k, "; every LF byte in the file follows a CR (%zu of them, the first CR at byte %zu): "
             "LF turned into CR LF (a binary file copied as text) corrupts it from there", lf, first);
}

/* The VRs with a 2-byte length in explicit VR (PS3.5 7.1.2); every other,
 * unknown ones included, has two reserved bytes and a 4-byte length. */
static int short_vr(const unsigned char *v) {
  static const char shorts[] = "AEASATCSDADSDTFLFDISLOLTPNSHSLSSSTTMUIULUS";
  for (int i = 0; shorts[i]; i += 2)
    if (v[0] == shorts[i] && v[1] == shorts[i + 1]) return 1;
  return 0;
}

static int read_items(parser *p, size_t *pos, size_t end, int undefined, int explicit_vr,
                      int fragments, int parent, int depth);

/* Elements from *pos: up to end when the parent has a defined length
 * (undefined = 0), or through an item delimitation item (undefined = 1),
 * which must come before end.  meta: stop at the first element not in group
 * 0002 (the file meta group). */
static int read_elements(parser *p, size_t *pos, size_t end, int undefined, int explicit_vr,
                         int meta, int parent, int depth) {
  const unsigned char *b = p->d->buf;
  char bb[64];
  for (;;) {
    size_t at = *pos;
    if (at == end) {
      if (undefined)
        return fail(p, at, "item has no item delimitation (FFFE,E00D); %s", bound(p, end, bb, sizeof bb));
      return 0;
    }
    if (meta && (end - at < 2 || u16(b + at) != 0x0002)) return 0;
    if (end - at < 8)
      return fail(p, at, "element header needs 8 bytes, %zu left; %s", end - at, bound(p, end, bb, sizeof bb));
    uint32_t tag = tag_at(b + at);
    if (tag == ITEM_END) {
      if (!undefined) return fail(p, at, "item delimitation (FFFE,E00D) in an item of defined length");
      uint32_t l = u32(b + at + 4);
      if (l != 0) return fail(p, at, "item delimitation with a non-zero length (%lu)", (unsigned long)l);
      *pos = at + 8;
      return 0;
    }
    if (tag >> 16 == 0xFFFE)
      return fail(p, at, "(FFFE,%04X) where an element was expected", (unsigned)(tag & 0xFFFF));
    size_t hdr = 8;
    uint32_t len;
    char vr[2] = {0, 0};
    if (explicit_vr) {
      if (b[at + 4] < 'A' || b[at + 4] > 'Z' || b[at + 5] < 'A' || b[at + 5] > 'Z')
        return fail(p, at + 4, "(%04X,%04X) has no VR in explicit VR (bytes 0x%02x 0x%02x)",
                    (unsigned)(tag >> 16), (unsigned)(tag & 0xFFFF), b[at + 4], b[at + 5]);
      vr[0] = (char)b[at + 4], vr[1] = (char)b[at + 5];
      if (short_vr(b + at + 4)) {
        len = u16(b + at + 6);
      } else {
        if (end - at < 12)
          return fail(p, at, "element header needs 12 bytes, %zu left; %s", end - at,
                      bound(p, end, bb, sizeof bb));
        len = u32(b + at + 8);
        hdr = 12;
      }
    } else {
      len = u32(b + at + 4);
    }
    int x = add(p, parent, tag, at);
    elem *nd = &p->d->n[x];
    memcpy(nd->vr, vr, 2);
    nd->voff = at + hdr;
    *pos = at + hdr;
    int is_sq = explicit_vr ? vr[0] == 'S' && vr[1] == 'Q' : 0;
    int is_un = explicit_vr && vr[0] == 'U' && vr[1] == 'N';
    if (len == UNDEFINED) {
      /* A sequence (SQ, or UN as an implicit VR sequence, or in implicit VR
       * any element but pixel data), or encapsulated pixel data (items of
       * raw fragments). */
      int frag = explicit_vr ? !is_sq && !is_un : tag == PIXEL_DATA;
      if (explicit_vr && frag && !(vr[0] == 'O' && (vr[1] == 'B' || vr[1] == 'W')))
        return fail(p, at, "(%04X,%04X) VR %c%c has an undefined length", (unsigned)(tag >> 16),
                    (unsigned)(tag & 0xFFFF), vr[0], vr[1]);
      p->d->n[x].seq = !frag;
      if (read_items(p, pos, end, 1, is_sq ? explicit_vr : 0, frag, x, depth + 1) != 0) return -1;
      continue;
    }
    if (len > end - *pos) {
      return fail(p, at, "(%04X,%04X) has length %lu, past the end: %s", (unsigned)(tag >> 16),
                  (unsigned)(tag & 0xFFFF), (unsigned long)len, bound(p, end, bb, sizeof bb));
    }
    if (descends(p, tag) && (!explicit_vr || is_sq || is_un)) {
      p->d->n[x].seq = 1;
      if (read_items(p, pos, *pos + len, 0, is_sq ? explicit_vr : 0, 0, x, depth + 1) != 0) return -1;
      continue;
    }
    p->d->n[x].vlen = len;
    *pos += len;
    if (meta && tag == TRANSFER_SYNTAX) {
      size_t l = len < sizeof p->d->ts - 1 ? len : sizeof p->d->ts - 1;
      memcpy(p->d->ts, b + at + hdr, l);
      while (l > 0 && (p->d->ts[l - 1] == 0 || p->d->ts[l - 1] == ' ')) l--;
      p->d->ts[l] = 0;
    }
  }
}

/* The items of a sequence (or the fragments of encapsulated data): up to end
 * (defined length) or through a sequence delimitation item. */
static int read_items(parser *p, size_t *pos, size_t end, int undefined, int explicit_vr,
                      int fragments, int parent, int depth) {
  const unsigned char *b = p->d->buf;
  char bb[64];
  if (depth > DICOM_MAX_DEPTH)
    return fail(p, p->d->n[parent].off, "sequences nested deeper than %d", DICOM_MAX_DEPTH);
  for (;;) {
    size_t at = *pos;
    if (at == end) {
      if (undefined)
        return fail(p, p->d->n[parent].off,
                    "sequence has no sequence delimitation (FFFE,E0DD); %s", bound(p, end, bb, sizeof bb));
      return 0;
    }
    if (end - at < 8)
      return fail(p, at, "item header needs 8 bytes, %zu left; %s", end - at, bound(p, end, bb, sizeof bb));
    uint32_t tag = tag_at(b + at), len = u32(b + at + 4);
    if (tag == SEQ_END) {
      if (!undefined) return fail(p, at, "sequence delimitation (FFFE,E0DD) in a sequence of defined length");
      if (len != 0) return fail(p, at, "sequence delimitation with a non-zero length (%lu)", (unsigned long)len);
      *pos = at + 8;
      return 0;
    }
    if (tag != DICOM_ITEM)
      return fail(p, at, "expected an item (FFFE,E000) in the sequence at byte %zu (%04X,%04X)",
                  p->d->n[parent].off, (unsigned)(tag >> 16), (unsigned)(tag & 0xFFFF));
    int x = add(p, parent, tag, at);
    *pos = at + 8;
    p->d->n[x].voff = at + 8;
    if (len == UNDEFINED) {
      if (fragments) return fail(p, at, "a fragment item of undefined length");
      if (read_elements(p, pos, end, 1, explicit_vr, 0, x, depth) != 0) return -1;
      continue;
    }
    if (len > end - *pos)
      return fail(p, at, "item has length %lu, past the end: %s", (unsigned long)len, bound(p, end, bb, sizeof bb));
    if (fragments) {
      p->d->n[x].vlen = len;
      *pos += len;
      continue;
    }
    if (read_elements(p, pos, *pos + len, 0, explicit_vr, 0, x, depth) != 0) return -1;
  }
}

int dicom_sniff(const unsigned char *buf, size_t len) {
  if (len >= 132 && memcmp(buf + 128, "DICM", 4) == 0) return 1;
  return len >= 8 && (u16(buf) == 0x0002 || u16(buf) == 0x0008);
}

/* What the transfer syntax means: 1 explicit VR LE, 0 implicit VR LE, -1
 * refused (with a message). */
static int syntax(parser *p, size_t off, const char *ts) {
  static const struct { const char *uid, *what; } refused[] = {
      {"1.2.840.10008.1.2.2", "Explicit VR Big Endian"},
      {"1.2.840.10008.1.2.1.99", "Deflated Explicit VR Little Endian"},
  };
  if (strcmp(ts, "1.2.840.10008.1.2") == 0) return 0;
  if (strcmp(ts, "1.2.840.10008.1.2.1") == 0 || strcmp(ts, "1.2.840.10008.1.2.1.98") == 0) return 1;
  /* The compressed-pixel syntaxes (JPEG, JPEG-LS, JPEG 2000, MPEG, HEVC,
   * HTJ2K, ... under .4; RLE .5): their data sets are explicit VR LE. */
  if (strncmp(ts, "1.2.840.10008.1.2.4.", 20) == 0 || strcmp(ts, "1.2.840.10008.1.2.5") == 0) return 1;
  for (size_t i = 0; i < sizeof refused / sizeof *refused; i++)
    if (strcmp(ts, refused[i].uid) == 0)
      return fail(p, off, "transfer syntax %s is not supported (%s)", refused[i].what, ts);
  char shown[80];
  size_t j = 0;
  for (size_t i = 0; ts[i] && j + 5 < sizeof shown; i++) {
    unsigned char c = (unsigned char)ts[i];
    if (c >= 32 && c < 127) shown[j++] = (char)c;
    else j += (size_t)snprintf(shown + j, sizeof shown - j, "\\x%02x", c);
  }
  shown[j] = 0;
  return fail(p, off, "unsupported transfer syntax, only implicit and explicit VR little endian (%s)", shown);
}

dicom *dicom_parse(const unsigned char *buf, size_t len, const char *name,
                   const uint32_t *descend, int ndescend, char *err, size_t errlen) {
  dicom *d = xcalloc(1, sizeof *d);
  parser p = {d, name, descend, ndescend, err, errlen};
  d->buf = buf;
  d->len = len;
  add(&p, -1, 0, 0);   /* the root */
  size_t pos = 0;
  if (!dicom_sniff(buf, len)) {
    fail(&p, 0, "not a DICOM file: no \"DICM\" at byte 128, and no data set of group 0002 or 0008 at byte 0");
    goto fail;
  }
  if (len >= 132 && memcmp(buf + 128, "DICM", 4) == 0) pos = 132;
  /* The file meta group: explicit VR LE, read while the group is 0002 (in
   * implicit VR if its first element has no VR, as some old writers did). */
  size_t meta_at = pos;
  int meta_explicit = !(len - pos >= 6 && u16(buf + pos) == 0x0002 && !(buf[pos + 4] >= 'A' && buf[pos + 4] <= 'Z' &&
                                                                        buf[pos + 5] >= 'A' && buf[pos + 5] <= 'Z'));
  if (read_elements(&p, &pos, len, 0, meta_explicit, 1, DICOM_ROOT, 0) != 0) goto fail;
  if (d->ts[0]) {
    int e = syntax(&p, meta_at, d->ts);
    if (e < 0) goto fail;
    d->explicit_vr = e;
  } else {
    /* No transfer syntax: guess as pydicom does from the first element. */
    d->explicit_vr = len - pos >= 6 && buf[pos + 4] >= 'A' && buf[pos + 4] <= 'Z' &&
                     buf[pos + 5] >= 'A' && buf[pos + 5] <= 'Z';
  }
  if (read_elements(&p, &pos, len, 0, d->explicit_vr, 0, DICOM_ROOT, 0) != 0) goto fail;
  return d;
fail:
  crlf_hint(buf, len, err, errlen);
  dicom_free(d);
  return NULL;
}

void dicom_free(dicom *d) {
  if (!d) return;
  free(d->n);
  free(d);
}

const char *dicom_transfer_syntax(const dicom *d) { return d->ts; }
int dicom_explicit(const dicom *d) { return d->explicit_vr; }
int dicom_nodes(const dicom *d) { return d->nn; }
int dicom_first(const dicom *d, int node) { return d->n[node].first; }
int dicom_next(const dicom *d, int node) { return d->n[node].next; }
uint32_t dicom_tag(const dicom *d, int node) { return d->n[node].tag; }
size_t dicom_offset(const dicom *d, int node) { return d->n[node].off; }
int dicom_is_sequence(const dicom *d, int node) { return d->n[node].seq; }
size_t dicom_value_offset(const dicom *d, int node) { return d->n[node].voff; }

int dicom_child(const dicom *d, int node, uint32_t tag) {
  for (int c = d->n[node].first; c >= 0; c = d->n[c].next)
    if (d->n[c].tag == tag) return c;
  return -1;
}

const unsigned char *dicom_value(const dicom *d, int node, size_t *len) {
  const elem *x = &d->n[node];
  *len = x->vlen;
  return x->vlen ? d->buf + x->voff : NULL;
}

int dicom_sniff_file(const char *path) {
  if (strcmp(path, "-") == 0) return 0;
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  unsigned char b[132];
  size_t n = fread(b, 1, sizeof b, f);
  fclose(f);
  return dicom_sniff(b, n);
}
