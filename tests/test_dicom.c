/* test_dicom.c -- the DICOM reader: every refusal with its byte offset and
 * value, the encodings it accepts, the sample files' structure, and
 * robustness: every truncation of the small sample files (and of the large
 * one at every element and item boundary), thousands of byte-level mutations,
 * each ending in an accepted file or a one-line refusal (tests/pipeline.c,
 * under the sanitizers). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/dicom.h"
#include "tests/pipeline.h"
#include "util/rng.h"
#include "tests/rtwriter.h"
#include "util/xmem.h"

static const uint32_t seqs[] = {DICOM_TAG(0x3006, 0x0020), DICOM_TAG(0x3006, 0x0039),
                                DICOM_TAG(0x3006, 0x0040), DICOM_TAG(0x3006, 0x0080)};
enum { NSEQ = sizeof seqs / sizeof *seqs };
/* Stacks are tiled when every pair has at most this many nodes (m * n). */
#define MAX_PAIR 2500

/* ---------------------------------------------------------------- bytes */

typedef struct {
  unsigned char b[8192];
  size_t n;
} buf;

static void raw(buf *o, const void *p, size_t n) {
  memcpy(o->b + o->n, p, n);
  o->n += n;
}
static void w16(buf *o, unsigned v) {
  unsigned char b[2] = {(unsigned char)v, (unsigned char)(v >> 8)};
  raw(o, b, 2);
}
static void w32(buf *o, uint32_t v) {
  unsigned char b[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16),
                        (unsigned char)(v >> 24)};
  raw(o, b, 4);
}
static void tag(buf *o, unsigned g, unsigned e) { w16(o, g), w16(o, e); }
/* Implicit VR: tag, 4-byte length, value. */
static void imp(buf *o, unsigned g, unsigned e, uint32_t len, const char *v) {
  tag(o, g, e), w32(o, len);
  if (v) raw(o, v, strlen(v));
}
/* Explicit VR, 2-byte length form. */
static void exs(buf *o, unsigned g, unsigned e, const char *vr, const char *v) {
  tag(o, g, e), raw(o, vr, 2), w16(o, (unsigned)strlen(v)), raw(o, v, strlen(v));
}
static void modality(buf *o, int ex) {   /* 16 bytes */
  if (ex) exs(o, 0x0008, 0x0060, "CS", "RTSTRUCT");
  else imp(o, 0x0008, 0x0060, 8, "RTSTRUCT");
}

/* Parsing must fail with "t.dcm: byte AT: " and words in the message. */
static void refused(const char *what, const buf *o, size_t at, const char *words) {
  char err[512], want[64];
  err[0] = 0;
  dicom *d = dicom_parse(o->b, o->n, "t.dcm", seqs, NSEQ, err, sizeof err);
  snprintf(want, sizeof want, "t.dcm: byte %zu: ", at);
  CHECK(d == NULL, "%s: accepted", what);
  CHECK(strncmp(err, want, strlen(want)) == 0 && strstr(err, words) && !strchr(err, '\n'),
        "%s: expected '%s...%s', got '%s'", what, want, words, err);
  dicom_free(d);
}

static void refusals(void) {
  buf o;
  const uint32_t U = 0xFFFFFFFFu;
#define NEW(ex) (memset(&o, 0, sizeof o), modality(&o, ex))
  memset(&o, 0, sizeof o);
  raw(&o, "hello, world, this is not DICOM", 31);
  refused("not dicom", &o, 0, "not a DICOM file");

  NEW(0), imp(&o, 0x3006, 0x0020, U, NULL), imp(&o, 0xFFFE, 0xE000, U, NULL), imp(&o, 0x3006, 0x0022, 2, "1 ");
  refused("item without delimiter", &o, 42, "item has no item delimitation (FFFE,E00D); corrupt or truncated: the file ends at byte 42");

  NEW(0), raw(&o, "\x08\x00\x70\x00\x00", 5);
  refused("short header", &o, 16, "element header needs 8 bytes, 5 left; corrupt or truncated");

  NEW(0), imp(&o, 0x3006, 0x0020, 16, NULL), imp(&o, 0xFFFE, 0xE000, 8, NULL), imp(&o, 0xFFFE, 0xE00D, 0, NULL);
  refused("item delimiter in a defined item", &o, 32, "item delimitation (FFFE,E00D) in an item of defined length");

  NEW(0), imp(&o, 0x3006, 0x0020, U, NULL), imp(&o, 0xFFFE, 0xE000, U, NULL), imp(&o, 0xFFFE, 0xE00D, 4, NULL);
  refused("item delimiter with a length", &o, 32, "item delimitation with a non-zero length (4)");

  NEW(0), imp(&o, 0xFFFE, 0xE000, 0, NULL);
  refused("item at top level", &o, 16, "(FFFE,E000) where an element was expected");

  NEW(1), tag(&o, 0x0008, 0x0070), raw(&o, "\x01\x02\x00\x00", 4);
  refused("no VR", &o, 20, "(0008,0070) has no VR in explicit VR (bytes 0x01 0x02)");

  NEW(1), tag(&o, 0x0009, 0x1001), raw(&o, "OB\0\0\1\2", 6);
  refused("short long header", &o, 16, "element header needs 12 bytes, 10 left");

  NEW(1), tag(&o, 0x0008, 0x0070), raw(&o, "UT\0\0", 4), w32(&o, U);
  refused("undefined UT", &o, 16, "(0008,0070) VR UT has an undefined length");

  NEW(0), imp(&o, 0x0008, 0x0070, 100, "abcd");
  refused("length past the file", &o, 16, "(0008,0070) has length 100, past the end: corrupt or truncated: the file ends at byte 28");

  NEW(0), imp(&o, 0x3006, 0x0020, 20, NULL), imp(&o, 0xFFFE, 0xE000, 12, NULL), imp(&o, 0x3006, 0x0022, 6, "1 ");
  raw(&o, "\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0", 16);
  refused("length past its item", &o, 32, "(3006,0022) has length 6, past the end: its parent ends at byte 44");

  NEW(0), imp(&o, 0x3006, 0x0020, 8, NULL), imp(&o, 0xFFFE, 0xE000, 100, NULL);
  raw(&o, "\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0", 16);
  refused("item past its sequence", &o, 24, "item has length 100, past the end: its parent ends at byte 32");

  NEW(0);
  for (int d = 0; d < 17; d++) imp(&o, 0x0011, 0x1010, U, NULL), imp(&o, 0xFFFE, 0xE000, U, NULL);
  refused("too deep", &o, 16 + 16 * 16, "sequences nested deeper than 16");

  NEW(0), imp(&o, 0x3006, 0x0020, U, NULL), imp(&o, 0xFFFE, 0xE000, 0, NULL);
  refused("sequence without delimiter", &o, 16, "sequence has no sequence delimitation (FFFE,E0DD); corrupt or truncated: the file ends at byte 32");

  NEW(0), imp(&o, 0x3006, 0x0020, U, NULL), raw(&o, "\xfe\xff\x00\xe0", 4);
  refused("short item header", &o, 24, "item header needs 8 bytes, 4 left");

  NEW(0), imp(&o, 0x3006, 0x0020, 8, NULL), imp(&o, 0xFFFE, 0xE0DD, 0, NULL);
  refused("sequence delimiter in a defined sequence", &o, 24, "sequence delimitation (FFFE,E0DD) in a sequence of defined length");

  NEW(0), imp(&o, 0x3006, 0x0020, U, NULL), imp(&o, 0xFFFE, 0xE0DD, 2, NULL);
  refused("sequence delimiter with a length", &o, 24, "sequence delimitation with a non-zero length (2)");

  NEW(0), imp(&o, 0x3006, 0x0020, U, NULL), imp(&o, 0x3006, 0x0022, 2, "1 ");
  refused("not an item", &o, 24, "expected an item (FFFE,E000) in the sequence at byte 16 (3006,0022)");

  NEW(0), imp(&o, 0x7FE0, 0x0010, U, NULL), imp(&o, 0xFFFE, 0xE000, U, NULL);
  refused("undefined fragment", &o, 24, "a fragment item of undefined length");

  /* Transfer syntaxes, named by their UID; the offset is the meta group's. */
  static const struct { const char *ts, *words; } syntaxes[] = {
      {"1.2.840.10008.1.2.2", "transfer syntax Explicit VR Big Endian is not supported (1.2.840.10008.1.2.2)"},
      {"1.2.840.10008.1.2.1.99", "Deflated Explicit VR Little Endian is not supported (1.2.840.10008.1.2.1.99)"},
      {"1.2.3.4.5.6", "unsupported transfer syntax, only implicit and explicit VR little endian (1.2.3.4.5.6)"},
  };
  for (size_t i = 0; i < sizeof syntaxes / sizeof *syntaxes; i++) {
    rtw_opts op = {1, 0, 0, 0, syntaxes[i].ts, NULL, 0};
    size_t len;
    unsigned char *b = rtw_write(&op, NULL, 0, &len);
    memcpy(o.b, b, len);
    o.n = len;
    free(b);
    refused(syntaxes[i].ts, &o, 132, syntaxes[i].words);
  }
#undef NEW
}

/* ---------------------------------------------------------------- accepted */

static int count(const dicom *d, int node, int *seq, int *items) {
  int n = 0;
  for (int c = dicom_first(d, node); c >= 0; c = dicom_next(d, c)) {
    n++;
    if (dicom_tag(d, c) == DICOM_ITEM) (*items)++;
    else if (dicom_is_sequence(d, c)) (*seq)++;
    n += count(d, c, seq, items);
  }
  return n;
}

static unsigned char *slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 1 << 16, n = 0;
  unsigned char *b = xmalloc(cap);
  for (size_t got; (got = fread(b + n, 1, cap - n, f)) > 0;)
    if ((n += got) == cap) b = xrealloc(b, cap *= 2);
  fclose(f);
  *len = n;
  return b;
}

static const char *samples[] = {"pydicom_rtstruct", "rtutils_rt", "rtutils_dummy_rt",
                                "rtutils_dummy_rt_explicit", "dicompyler_rtss"};
enum { NSAMPLES = sizeof samples / sizeof *samples };

static unsigned char *sample(int i, size_t *len) {
  char path[128];
  snprintf(path, sizeof path, "tests/data/rtstruct/%s.dcm", samples[i]);
  unsigned char *b = slurp(path, len);
  CHECK(b != NULL, "cannot read %s", path);
  return b;
}

static void accepted(void) {
  char err[512];
  /* The sample files: encodings and, where every length is undefined (so
   * every sequence is walked), the sequence and item counts of the data
   * README's inventory. */
  static const struct { int explicit_vr; const char *ts; int seq, items; } want[NSAMPLES] = {
      {0, "", 10, 18},
      {0, "1.2.840.10008.1.2", -1, -1},
      {0, "1.2.840.10008.1.2", 23, 44},
      {1, "1.2.840.10008.1.2.1", -1, -1},
      {0, "1.2.840.10008.1.2", -1, -1},
  };
  for (int i = 0; i < NSAMPLES; i++) {
    size_t len;
    unsigned char *b = sample(i, &len);
    if (!b) continue;
    dicom *d = dicom_parse(b, len, samples[i], seqs, NSEQ, err, sizeof err);
    CHECK(d != NULL, "%s: %s", samples[i], err);
    if (d) {
      CHECK(dicom_explicit(d) == want[i].explicit_vr && strcmp(dicom_transfer_syntax(d), want[i].ts) == 0,
            "%s: explicit %d, transfer syntax '%s'", samples[i], dicom_explicit(d), dicom_transfer_syntax(d));
      int seq = 0, items = 0;
      count(d, DICOM_ROOT, &seq, &items);
      if (want[i].seq >= 0)
        CHECK(seq == want[i].seq && items == want[i].items, "%s: %d sequences and %d items, expected %d and %d",
              samples[i], seq, items, want[i].seq, want[i].items);
    }
    dicom_free(d);
    free(b);
  }
  /* Every layout and encoding the writer makes, a compressed-pixel transfer
   * syntax (explicit VR LE data), and a meta group length that lies. */
  for (int k = 0; k < 24; k++) {
    rtw_opts op = {k & 1, (k >> 1) & 1, (k >> 2) % 3, k >= 12, NULL, NULL, 3};
    size_t len;
    unsigned char *b = rtw_write(&op, NULL, 0, &len);
    dicom *d = dicom_parse(b, len, "w.dcm", seqs, NSEQ, err, sizeof err);
    CHECK(d != NULL && dicom_explicit(d) == op.explicit_vr, "writer variant %d: %s", k, d ? "implicit" : err);
    dicom_free(d);
    free(b);
  }
  rtw_opts jp = {1, 1, 0, 1, "1.2.840.10008.1.2.4.50", NULL, 0};
  size_t len;
  unsigned char *b = rtw_write(&jp, NULL, 0, &len);
  b[140] = b[141] = b[142] = b[143] = 0;   /* (0002,0000) group length: 0 */
  dicom *d = dicom_parse(b, len, "j.dcm", seqs, NSEQ, err, sizeof err);
  CHECK(d != NULL && dicom_explicit(d), "JPEG baseline transfer syntax with a wrong group length: %s", d ? "" : err);
  dicom_free(d);
  free(b);
  /* A meta group written in implicit VR (old writers): read as such. */
  {
    buf o;
    memset(&o, 0, sizeof o);
    raw(&o, (unsigned char[128]){0}, 128), raw(&o, "DICM", 4);
    imp(&o, 0x0002, 0x0010, 18, NULL), raw(&o, "1.2.840.10008.1.2", 18), modality(&o, 0);
    d = dicom_parse(o.b, o.n, "m.dcm", seqs, NSEQ, err, sizeof err);
    CHECK(d != NULL && !dicom_explicit(d) && strcmp(dicom_transfer_syntax(d), "1.2.840.10008.1.2") == 0,
          "implicit meta group: %s", d ? dicom_transfer_syntax(d) : err);
    dicom_free(d);
  }
  /* 16 levels of nesting are fine. */
  rtw_opts deep = {0, 0, 2, 0, NULL, NULL, 16};
  b = rtw_write(&deep, NULL, 0, &len);
  d = dicom_parse(b, len, "deep.dcm", seqs, NSEQ, err, sizeof err);
  CHECK(d != NULL, "16 levels: %s", err);
  dicom_free(d);
  free(b);
  /* Sniffing: by content, not by name. */
  CHECK(!dicom_sniff((const unsigned char *)"C 3 0\n0 0\n", 10), "a .contours file sniffed as DICOM");
  CHECK(dicom_sniff((const unsigned char *)"\x08\x00\x05\x00\x0a\x00\x00\x00", 8), "a bare data set not sniffed");
}

/* ---------------------------------------------------------------- robustness */

/* Every node's extent, for the structural truncations of the large file. */
static void cuts(const dicom *d, int node, size_t *at, size_t *n, size_t cap) {
  for (int c = dicom_first(d, node); c >= 0; c = dicom_next(d, c)) {
    size_t off = dicom_offset(d, c), voff = dicom_value_offset(d, c), vlen;
    dicom_value(d, c, &vlen);
    for (size_t k = off; k <= voff && *n < cap; k++) at[(*n)++] = k;
    if (vlen > 1 && *n + 2 < cap) at[(*n)++] = voff + 1, at[(*n)++] = voff + vlen - 1;
    cuts(d, c, at, n, cap);
  }
}

static void truncations(void) {
  for (int i = 0; i < NSAMPLES; i++) {
    size_t len;
    unsigned char *b = sample(i, &len);
    if (!b) continue;
    int ok = 0, refused_ = 0;
    if (len < 65536) {
      for (size_t n = 0; n < len; n++) if (pipeline_dicom(b, n, MAX_PAIR)) refused_++; else ok++;
    } else {
      /* Every cut at and inside each element's and item's header, one byte
       * into and one byte before the end of each value. */
      char err[512];
      dicom *d = dicom_parse(b, len, samples[i], seqs, NSEQ, err, sizeof err);
      size_t cap = 1 << 20, n = 0, *at = xmallocarray(cap, sizeof *at);
      if (d) cuts(d, DICOM_ROOT, at, &n, cap);
      dicom_free(d);
      for (size_t k = 0; k < n; k++) if (pipeline_dicom(b, at[k], MAX_PAIR)) refused_++; else ok++;
      free(at);
    }
    /* pipeline_dicom aborts on a bad refusal: reaching here is the test. */
    CHECK(ok + refused_ > 0 && refused_ > 0, "%s: %d truncations accepted, %d refused", samples[i], ok, refused_);
    printf("test_dicom: %s: %d truncations, %d accepted, %d refused\n", samples[i], ok + refused_, ok, refused_);
    free(b);
  }
}

/* Every LF turned into CR LF (a binary file copied as text): each
 * sample refused in one line that says it is corrupt, names the byte where
 * the reading went wrong (an element whose header reaches the first CR, or a
 * later one: the data is sound before it) and the first CR's byte. */
static void crlf(void) {
  for (int i = 0; i < NSAMPLES; i++) {
    size_t len, n = 0;
    unsigned char *b = sample(i, &len);
    if (!b) continue;
    unsigned char *m = xmalloc(2 * len + 1);
    size_t first = (size_t)-1;
    for (size_t k = 0; k < len; k++) {
      if (b[k] == '\n') {
        if (first == (size_t)-1) first = n;
        m[n++] = '\r';
      }
      m[n++] = b[k];
    }
    char err[1024], want[96];
    err[0] = 0;
    dicom *d = dicom_parse(m, n, "t.dcm", seqs, NSEQ, err, sizeof err);
    snprintf(want, sizeof want, "the first CR at byte %zu): LF turned into CR LF", first);
    size_t at = 0;
    int named = sscanf(err, "t.dcm: byte %zu: ", &at) == 1;
    CHECK(d == NULL && first != (size_t)-1 && strstr(err, want) && !strchr(err, '\n') && named && at + 12 > first &&
              (strstr(err, "corrupt or truncated") || strstr(err, "has no VR")),
          "%s with CR LF: '%s' (the first CR at %zu)", samples[i], err, first);
    dicom_free(d);
    free(m);
    free(b);
  }
}

static void mutations(void) {
  rng g;
  rng_seed(&g, 2026);
  for (int i = 0; i < NSAMPLES; i++) {
    size_t len;
    unsigned char *b = sample(i, &len);
    if (!b) continue;
    int runs = len < 65536 ? 1000 : 20, ok = 0, refused_ = 0;
    unsigned char *m = xmalloc(len + 16);
    for (int r = 0; r < runs; r++) {
      memcpy(m, b, len);
      size_t n = len;
      int k = rng_int(&g, 1, 4);
      for (int j = 0; j < k; j++) {
        size_t at = (size_t)rng_int(&g, 0, (int)n - 1);
        switch (rng_int(&g, 0, 5)) {
          case 0: m[at] ^= (unsigned char)(1u << rng_int(&g, 0, 7)); break;   /* a bit */
          case 1: m[at] = (unsigned char)rng_int(&g, 0, 255); break;          /* a byte */
          case 2: m[at] = (unsigned char)"\x00\xff\\.e-+ 9"[rng_int(&g, 0, 8)]; break;
          case 3:   /* a length or tag field: 4 bytes of 0, ff or random */
            if (at + 4 <= n) {
              uint32_t v = rng_int(&g, 0, 2) == 0 ? 0xFFFFFFFFu : (uint32_t)rng_next(&g);
              memcpy(m + at, &v, 4);
            }
            break;
          case 4:   /* delete a byte */
            if (n > 1) memmove(m + at, m + at + 1, n - at - 1), n--;
            break;
          default:  /* insert a byte */
            if (n < len + 16) memmove(m + at + 1, m + at, n - at), m[at] = (unsigned char)rng_next(&g), n++;
        }
      }
      if (pipeline_dicom(m, n, MAX_PAIR)) refused_++; else ok++;
    }
    CHECK(ok + refused_ == runs, "%s: mutations", samples[i]);
    printf("test_dicom: %s: %d mutations, %d accepted, %d refused\n", samples[i], runs, ok, refused_);
    free(m);
    free(b);
  }
}

int main(void) {
  refusals();
  accepted();
  truncations();
  mutations();
  crlf();
  return check_done("test_dicom");
}
