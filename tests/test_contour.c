/* test_contour.c -- reading contour stacks: what is repaired, what is
 * rejected, and that every rejection names the line and the value. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/contour.h"
#include "input/gen.h"
#include "util/rng.h"
#include "util/xmem.h"

/* Parse text; return the error (or "" on success) and the notes. */
static int parse(const char *text, size_t len, contour_stack *s, char *err, char *notes,
                 size_t cap) {
  char *buf = NULL;
  size_t blen = 0;
  FILE *f = open_memstream(&buf, &blen);
  err[0] = 0;
  int rc = contour_parse(text, len, "t.contours", s, f, "tile", err, 512);
  fclose(f);
  snprintf(notes, cap, "%s", buf ? buf : "");
  free(buf);
  return rc;
}

typedef struct {
  const char *text;
  int line;            /* the line the message must name (0: none) */
  const char *words;   /* must appear in the message */
  const char *value;   /* must appear in the message, in parentheses */
} bad;

static const bad cases[] = {
    {"", 1, "empty file", NULL},
    {"# only a comment\n\n   \n", 3, "no contours", NULL},
    {"1 2\n", 1, "expected a header", "1 2"},
    {"C 3\n0 0\n1 0\n0 1\n", 1, "garbled header", "C 3"},
    {"C 3 0 7\n0 0\n1 0\n0 1\n", 1, "garbled header", "C 3 0 7"},
    {"C three 0\n", 1, "bad point count", "three"},
    {"C 2.5 0\n", 1, "bad point count", "2.5"},
    {"C 0 0\n", 1, "bad point count", "0"},
    {"C -4 0\n", 1, "bad point count", "-4"},
    {"C 99999999999 0\n", 1, "point count too large", "99999999999"},
    {"C 3 zed\n", 1, "z is not a number", "zed"},
    {"C 3 nan\n", 1, "z is not finite", "nan"},
    {"C 3 inf\n", 1, "z is not finite", "inf"},
    {"C 3 1e999\n0 0\n1 0\n0 1\n", 1, "z is not finite", "1e999"},
    {"C 3 0\n0 0\n1 x\n0 1\n", 3, "y is not a number", "x"},
    {"C 3 0\n0 0\nNaN 0\n0 1\n", 3, "x is not finite", "NaN"},
    {"C 3 0\n0 0\n1 -inf\n0 1\n", 3, "y is not finite", "-inf"},
    {"C 3 0\n0 0\n1 0 5\n0 1\n", 3, "expected a point", "1 0 5"},
    {"C 3 0\n0 0\n1\n0 1\n", 3, "expected a point", "1"},
    {"C 4 0\n0 0\n1 0\n0 1\nC 3 1\n0 0\n1 0\n0 1\n", 5, "announced 4 points but has 3", NULL},
    {"C 4 0\n0 0\n1 0\n0 1\n", 4, "announced 4 points but has 3 (end of file)", NULL},
    {"C 3 0\n0 0\n1 0\n0 1\n5 5\n", 5, "more point lines than the 3 announced at line 1", "5 5"},
    {"C 3 0\n0 0\n1 0\n0 0\n", 1, "2 distinct points, needs at least 3", NULL},
    {"C 3 0\n0 0\n0 0\n0 0\n", 1, "1 distinct point, needs at least 3", NULL},
    {"C 4 0\n0 0\n1 1\n2 2\n3 3\n", 1, "collinear", NULL},
    {"C 4 0\n0 0\n1 1\n0 0\n1 1\n", 1, "collinear", NULL},
    {"C 3 0\n0 0\n1 0\n0 1\n", 1, "only one contour", NULL},
    {"C 3 2\n0 0\n1 0\n0 1\nC 3 2\n5 0\n6 0\n5 1\n", 1, "all 2 contours lie on one slice", NULL},
    /* Self-intersecting contours: the two segments by
     * the lines of their points, and where they meet. */
    {"C 4 0\n0 0\n1 1\n1 0\n0 1\n", 1,   /* a bowtie */
     "the contour crosses itself: the segment from line 2 to line 3 crosses the segment from line 4 to line 5", "0.5 0.5"},
    {"C 7 0\n1000 0\n-901 434\n623 -782\n-223 975\n-223 -975\n623 782\n-901 -434\n", 1,   /* {7/3} */
     "the contour crosses itself: the segment from line ", NULL},
    {"C 6 0\n0 0\n1 1\n2 0\n2 1\n1 0\n0 1\n", 1,   /* a figure eight */
     "the contour crosses itself: the segment from line 2 to line 3 crosses the segment from line 6 to line 7", "0.5 0.5"},
    {"C 6 0\n0 0\n2 0\n1 1\n2 2\n0 2\n1 1\n", 1,   /* touching at a vertex */
     "the contour crosses itself: the segment from line 3 to line 4 touches the segment from line 6 to line 7", "1 1"},
    {"C 5 0\n0 0\n2 0\n2 2\n1 0\n0 2\n", 1,   /* a vertex on an edge */
     "the contour crosses itself: the segment from line 2 to line 3 touches the segment from line 5 to line 6", "1 0"},
    {"C 6 0\n0 0\n3 0\n3 1\n-1 1\n-1 0\n1 0\n", 1,   /* collinear overlap */
     "the contour crosses itself: the segment from line 2 to line 3 overlaps the segment from line 7 to line 2", "0 0"},
    {"C 7 0\n0 0\n4 0\n4 4\n2 4\n2 0\n2 4\n0 4\n", 1,   /* a spur whose tip touches an edge */
     "the contour crosses itself: the segment from line 5 to line 6 overlaps the segment from line 6 to line 7", "2 0"},
    {"C 5 7\n0 0\n# a comment\n1 1\n\n1 1\n1 0\n0 1\n", 1,   /* lines as in the file, after repair */
     "the contour crosses itself: the segment from line 2 to line 4 crosses the segment from line 7 to line 8", "0.5 0.5"},
    {"C 4 0\n0 0\n1e300 1e300\n1e300 0\n0 1e300\n", 1,   /* at any scale */
     "the contour crosses itself: the segment from line 2 to line 3 crosses the segment from line 4 to line 5", "5e299 5e299"},
    {"C 4 0\n0 0\n4e-323 4e-323\n4e-323 0\n0 4e-323\n", 1,   /* subnormals */
     "the contour crosses itself: the segment from line 2 to line 3 crosses the segment from line 4 to line 5", NULL},
    {"C 3 0\n0 0\n1\x01 0\n0 1\n", 3, "binary data", "byte 0x01"},
    {"C 3 0\n\x7f\x45LF\n", 2, "binary data", "byte 0x7f"},
};

static void check_bad(void) {
  char err[512], notes[4096];
  int n = (int)(sizeof cases / sizeof cases[0]);
  for (int i = 0; i < n; i++) {
    contour_stack s;
    const bad *b = &cases[i];
    int rc = parse(b->text, strlen(b->text), &s, err, notes, sizeof notes);
    char want[64];
    snprintf(want, sizeof want, "t.contours:%d: ", b->line);
    CHECK(rc == -1, "case %d: accepted (%s)", i, b->text);
    CHECK(strncmp(err, want, strlen(want)) == 0, "case %d: message '%s' should begin '%s'", i, err, want);
    CHECK(strstr(err, b->words) != NULL, "case %d: message '%s' lacks '%s'", i, err, b->words);
    if (b->value) {
      char v[128];
      snprintf(v, sizeof v, "(%s)", b->value);
      CHECK(strstr(err, v) != NULL, "case %d: message '%s' lacks the value '%s'", i, err, v);
    }
    CHECK(strchr(err, '\n') == NULL, "case %d: message is not one line", i);
    CHECK(s.n == 0 && s.c == NULL, "case %d: output left behind", i);
  }
  /* A NUL byte, a line too long, and a file that is not there. */
  char nul[] = "C 3 0\n0 0\n1 0\0\n0 1\n";
  contour_stack s;
  CHECK(parse(nul, sizeof nul - 1, &s, err, notes, sizeof notes) == -1 &&
            strstr(err, "t.contours:3: binary data") && strstr(err, "0x00"),
        "NUL byte: '%s'", err);
  size_t L = CONTOUR_MAX_LINE + 100;
  char *lng = xmalloc(L + 20);
  memcpy(lng, "C 3 0\n", 6);
  memset(lng + 6, '1', L);
  memcpy(lng + 6 + L, "\n", 2);
  CHECK(parse(lng, strlen(lng), &s, err, notes, sizeof notes) == -1 &&
            strstr(err, "t.contours:2: line longer than"),
        "long line: '%s'", err);
  free(lng);
  CHECK(contour_read("/nonexistent/x.contours", &s, NULL, "tile", err, sizeof err) == -1 &&
            strstr(err, "/nonexistent/x.contours: cannot open (No such file or directory)"),
        "missing file: '%s'", err);
  CHECK(contour_read("/tmp", &s, NULL, "tile", err, sizeof err) == -1 && strstr(err, "/tmp: cannot read"),
        "a directory: '%s'", err);
}

static void check_good(void) {
  char err[512], notes[4096];
  contour_stack s;
  /* Comments, blank lines, CRLF, tabs, exponents; the second contour runs
   * clockwise, repeats its closing point and has a duplicate. */
  const char *t =
      "# a stack\r\n"
      "C 4 0.5\r\n"
      "0 0\r\n"
      "2 0\n"
      "\t2\t2 \n"
      "0 2e0\n"
      "\n"
      "  # between contours\n"
      "C 6 1.5\n"
      "0 0\n"
      "0 2\n"
      "0 2\n"
      "2 2\n"
      "2 0\n"
      "0 0\n";
  int rc = parse(t, strlen(t), &s, err, notes, sizeof notes);
  CHECK(rc == 0, "good file rejected: %s", err);
  if (rc != 0) return;
  CHECK(s.n == 2 && s.c[0].n == 4 && s.c[1].n == 4, "contours %d, points %d %d", s.n,
        s.n > 0 ? s.c[0].n : -1, s.n > 1 ? s.c[1].n : -1);
  CHECK(s.c[0].z == 0.5 && s.c[1].z == 1.5 && s.c[0].line == 2 && s.c[1].line == 9, "z or lines");
  CHECK(geom_area2(s.c[1].pt, s.c[1].n) > 0, "clockwise contour not reversed");
  CHECK(s.c[1].pt[0].x == 0 && s.c[1].pt[0].y == 0 && s.c[1].pt[1].x == 2 && s.c[1].pt[1].y == 0,
        "reversed contour should keep its first point and run (0,0) (2,0) ...");
  CHECK(s.c[0].pt[2].x == 2 && s.c[0].pt[2].y == 2, "tabs");
  CHECK(strstr(notes, "tile: t.contours:12: dropped a duplicate of the point before (0 2)") != NULL,
        "notes lack the duplicate: %s", notes);
  CHECK(strstr(notes, "tile: t.contours:15: dropped the repeated closing point (0 0)") != NULL,
        "notes lack the closing point: %s", notes);
  CHECK(strstr(notes, "1 of 2 contours ran clockwise; reversed to counter-clockwise") != NULL,
        "notes lack the reversal: %s", notes);
  /* Written and read back: the same stack, exactly. */
  char *buf = NULL;
  size_t blen = 0;
  FILE *f = open_memstream(&buf, &blen);
  contour_write(f, &s);
  fclose(f);
  contour_stack s2;
  CHECK(parse(buf, blen, &s2, err, notes, sizeof notes) == 0, "write/read: %s", err);
  int same = s2.n == s.n;
  for (int i = 0; same && i < s.n; i++) {
    same &= s.c[i].n == s2.c[i].n && s.c[i].z == s2.c[i].z;
    for (int j = 0; same && j < s.c[i].n; j++)
      same &= s.c[i].pt[j].x == s2.c[i].pt[j].x && s.c[i].pt[j].y == s2.c[i].pt[j].y;
  }
  CHECK(same, "written stack reads back different");
  CHECK(notes[0] == 0, "a clean stack gave notes: %s", notes);
  free(buf);
  contour_stack_free(&s2);
  contour_stack_free(&s);
  /* Decreasing z is fine. */
  const char *d = "C 3 5\n0 0\n1 0\n0 1\nC 3 4\n0 0\n1 0\n0 1\nC 3 -1\n0 0\n1 0\n0 1\n";
  CHECK(parse(d, strlen(d), &s, err, notes, sizeof notes) == 0 && s.n == 3, "decreasing z: %s", err);
  contour_stack_free(&s);
}

/* The real stacks read cleanly (tinypatient_0 has two contours per slice). */
static void check_real(void) {
  const char *ok[] = {"prostate_0", "prostate_1", "prostate_2", "prostate_3",
                      "prostate_4", "prostate_5", "tinypatient_1"};
  char err[512], path[256];
  for (int i = 0; i < 7; i++) {
    contour_stack s;
    snprintf(path, sizeof path, "tests/data/slicerrt/%s.contours", ok[i]);
    int rc = contour_read(path, &s, NULL, "tile", err, sizeof err);
    CHECK(rc == 0, "%s: %s", path, err);
    for (int j = 0; rc == 0 && j < s.n; j++)
      CHECK(geom_area2(s.c[j].pt, s.c[j].n) > 0, "%s contour %d not counter-clockwise", path, j);
    if (rc == 0) contour_stack_free(&s);
  }
  /* tinypatient_0: two contours on each of 9 slices; not a stack of pairs. */
  contour_stack s;
  int rc = contour_read("tests/data/slicerrt/tinypatient_0.contours", &s, NULL, "tile", err, sizeof err);
  CHECK(rc == 0 && s.n == 18 && s.nslices == 9, "tinypatient_0: %s", err);
  if (rc != 0) return;
  int per[9] = {0};
  for (int j = 0; j < s.n; j++)
    if (s.c[j].slice >= 0 && s.c[j].slice < 9) per[s.c[j].slice]++;
  for (int k = 0; k < 9; k++) CHECK(per[k] == 2, "tinypatient_0 slice %d has %d contours", k, per[k]);
  CHECK(contour_stack_pairs(&s, "tp0", err, sizeof err) == -1 &&
            strstr(err, "tp0:29: slice z=-123.75 already has a contour (line 1)"),
        "tinypatient_0 as pairs: %s", err);
  contour_stack_free(&s);
}

/* Slices: any order, any number of contours; z jitter within a tenth of the
 * spacing is snapped to one value (the lower median) and reported; the
 * pairs check gives the old rules. */
static void check_slices(void) {
  char err[512], notes[4096];
  contour_stack s;
  /* Slices at 0, 3, 6 (given out of order), the one at 3 with jitter. */
  const char *t = "C 3 6\n0 0\n1 0\n0 1\n"
                  "C 3 3.001\n0 0\n1 0\n0 1\n"
                  "C 3 0\n0 0\n1 0\n0 1\n"
                  "C 3 2.999\n5 0\n6 0\n5 1\n"
                  "C 3 3\n9 0\n10 0\n9 1\n";
  int rc = parse(t, strlen(t), &s, err, notes, sizeof notes);
  CHECK(rc == 0 && s.n == 5 && s.nslices == 3, "jittered stack: %s (%d slices)", err, rc == 0 ? s.nslices : -1);
  if (rc == 0) {
    int want[5] = {2, 1, 0, 1, 1};
    for (int i = 0; i < 5; i++) CHECK(s.c[i].slice == want[i], "contour %d on slice %d", i, s.c[i].slice);
    CHECK(s.c[1].z == 3 && s.c[3].z == 3 && s.c[4].z == 3 && s.c[0].z == 6 && s.c[2].z == 0,
          "snapped z: %g %g %g", s.c[1].z, s.c[3].z, s.c[4].z);
    CHECK(strstr(notes, "tile: t.contours:5: snapped the z of 2 contours to their slice's") != NULL,
          "snapping note: %s", notes);
    CHECK(contour_stack_pairs(&s, "t.contours", err, sizeof err) == -1 &&
              strstr(err, "t.contours:13: slice z=3 already has a contour (line 5)"),
          "pairs: %s", err);
    contour_stack_free(&s);
  }
  /* Uneven spacing is kept; z going back is fine for a stack, not for pairs. */
  const char *u = "C 3 0\n0 0\n1 0\n0 1\nC 3 2\n0 0\n1 0\n0 1\nC 3 1\n0 0\n1 0\n0 1\n"
                  "C 3 1.3\n0 0\n1 0\n0 1\n";
  rc = parse(u, strlen(u), &s, err, notes, sizeof notes);
  CHECK(rc == 0 && s.nslices == 4 && notes[0] == 0, "uneven: %s %s", err, notes);
  if (rc == 0) {
    CHECK(s.c[0].slice == 0 && s.c[1].slice == 3 && s.c[2].slice == 1 && s.c[3].slice == 2, "uneven slices");
    CHECK(contour_stack_pairs(&s, "t.contours", err, sizeof err) == -1 &&
              strstr(err, "t.contours:9: z goes back") && strstr(err, "(1 after 2)"),
          "pairs: %s", err);
    contour_stack_free(&s);
  }
  /* A clockwise contour on a slice with another: no reversal note here (the
   * surface orients by nesting), but the flag is kept. */
  const char *w = "C 3 0\n0 0\n0 1\n1 0\nC 3 0\n5 0\n6 0\n5 1\nC 3 1\n0 0\n1 0\n0 1\n";
  rc = parse(w, strlen(w), &s, err, notes, sizeof notes);
  CHECK(rc == 0 && s.c[0].cw == 1 && s.c[1].cw == 0 && strstr(notes, "clockwise") == NULL,
        "clockwise flag: %s %s", err, notes);
  if (rc == 0) {
    CHECK(geom_area2(s.c[0].pt, 3) > 0, "still made counter-clockwise");
    contour_stack_free(&s);
  }
}

/* Random mutations of valid stacks: every input is either rejected with one
 * line naming the file, or accepted as a stack that keeps every promise of
 * contour.h.  Never a crash (ASan and UBSan watch). */
static void check_fuzz(void) {
  static const char *seeds[] = {
      "C 4 0\n0 0\n2 0\n2 2\n0 2\nC 3 1.5\n0 0\n2 0\n1 2\n",
      "# c\nC 5 -1\n1e0 2\n-3.5 4\n0 0\n7 -2\n1 1\n\nC 4 2\n0 0\n0 3\n3 3\n3 0\n0 0\n",
  };
  static const char alphabet[] = "C0123456789.-+eE#\n \t\rinfnaxC\0\x01\xff";
  unsigned long long x = 88172645463325252ULL;
  int broken = 0, accepted = 0;
  char err[512], notes[4096], buf[512];
  for (int it = 0; it < 4000; it++) {
    const char *seed = seeds[it % 2];
    size_t len = strlen(seed);
    memcpy(buf, seed, len);
    int muts = 1 + (int)((x >> 7) % 4);
    for (int k = 0; k < muts; k++) {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;
      size_t at = len ? (size_t)(x % len) : 0;
      switch ((x >> 32) % 5) {
      case 0:   /* overwrite a byte */
        if (len) buf[at] = alphabet[(x >> 40) % (sizeof alphabet - 1)];
        break;
      case 1:   /* insert a byte */
        if (len + 1 < sizeof buf) {
          memmove(buf + at + 1, buf + at, len - at);
          buf[at] = alphabet[(x >> 40) % (sizeof alphabet - 1)];
          len++;
        }
        break;
      case 2:   /* delete a run */
        if (len) {
          size_t n = 1 + (x >> 44) % 6;
          if (at + n > len) n = len - at;
          memmove(buf + at, buf + at + n, len - at - n);
          len -= n;
        }
        break;
      case 3:   /* duplicate a run */
        if (len && len + 12 < sizeof buf) {
          size_t n = 1 + (x >> 44) % 12;
          if (at + n > len) n = len - at;
          memmove(buf + at + n, buf + at, len - at);
          len += n;
        }
        break;
      default:   /* truncate */
        len = at;
      }
    }
    contour_stack s;
    int rc = parse(buf, len, &s, err, notes, sizeof notes);
    if (rc != 0) {
      if (strncmp(err, "t.contours:", 11) != 0 || strchr(err, '\n')) broken++;
      continue;
    }
    accepted++;
    int okst = s.n >= 2 && s.nslices >= 2;
    for (int i = 0; i < s.n; i++) {
      const contour *c = &s.c[i];
      okst &= c->n >= 3 && isfinite(c->z) && geom_area2(c->pt, c->n) >= 0 && !geom_collinear(c->pt, c->n);
      for (int j = 0; j < c->n; j++) {
        okst &= isfinite(c->pt[j].x) && isfinite(c->pt[j].y);
        const vec2 *q = &c->pt[(j + 1) % c->n];
        okst &= !(q->x == c->pt[j].x && q->y == c->pt[j].y);   /* no consecutive duplicates */
      }
      okst &= c->slice >= 0 && c->slice < s.nslices;
      for (int j = 0; j < s.n; j++)   /* one z per slice, slices in increasing z */
        okst &= (s.c[j].slice == c->slice) == (s.c[j].z == c->z) &&
                (s.c[j].slice < c->slice) == (s.c[j].z < c->z);
    }
    if (!okst) broken++;
    contour_stack_free(&s);
  }
  CHECK(broken == 0, "%d of 4000 mutated inputs broke the reader's promises", broken);
  CHECK(accepted > 50 && accepted < 3950, "fuzzing reached both outcomes (%d accepted)", accepted);
}

/* Extreme coordinates: star contours scaled by 2^k, by
 * 1e300 and 1e-300, and into subnormals are read as at unit scale: accepted,
 * the same points, reversed or not alike.  (With a tolerance scaled by the
 * extent, 1e300 overflowed and 1e-300 underflowed, and 50-point stars were
 * refused as "collinear".) */
static void check_extreme(void) {
  rng g;
  rng_seed(&g, 99);
  char err[512];
  int fails = 0;
  for (int trial = 0; trial < 40; trial++) {
    int n = 50;
    vec2 p[2][50];
    int np[2];
    for (int c = 0; c < 2; c++) {
      np[c] = gen_grid(&g, p[c], n, 200);   /* integers: every scaling by 2^k is exact */
      if ((trial + c) % 2) geom_reverse(p[c], np[c]);
    }
    static const double muls[] = {1, 0x1p-1000, 0x1p1000, 1e300, 1e-300, 0x1p-1060, 0x1p-1066};
    int cw0[2] = {-1, -1};
    for (size_t m = 0; m < sizeof muls / sizeof *muls; m++) {
      char *text = NULL;
      size_t len = 0;
      FILE *f = open_memstream(&text, &len);
      for (int c = 0; c < 2; c++) {
        fprintf(f, "C %d %.17g\n", np[c], c * 3 * muls[m]);
        for (int i = 0; i < np[c]; i++) fprintf(f, "%.17g %.17g\n", p[c][i].x * muls[m], p[c][i].y * muls[m]);
      }
      fclose(f);
      contour_stack s;
      int rc = contour_parse(text, len, "x.contours", &s, NULL, "tile", err, sizeof err);
      int ok = rc == 0 && s.n == 2;
      for (int c = 0; ok && c < 2; c++) {
        if (m == 0) cw0[c] = s.c[c].cw;
        ok = s.c[c].n == np[c] && s.c[c].cw == cw0[c];
        /* the points as written, in the order the unit-scale read gave */
        for (int i = 0; ok && i < np[c]; i++) {
          int j = s.c[c].cw ? (np[c] - i) % np[c] : i;
          ok = s.c[c].pt[i].x == p[c][j].x * muls[m] && s.c[c].pt[i].y == p[c][j].y * muls[m];
        }
      }
      if (!ok && fails++ < 5) CHECK(0, "trial %d, scale %g: %s", trial, muls[m], rc ? err : "points differ");
      if (rc == 0) contour_stack_free(&s);
      free(text);
    }
  }
  CHECK(fails == 0, "%d extreme-scale stacks read differently", fails);
  /* The sliver of item 8 (50 points on a line, one 1e-8 off it) is a thin
   * triangle, not collinear; exactly on the line it is. */
  char t[8192];
  size_t k = (size_t)snprintf(t, sizeof t, "C 51 0\n");
  for (int i = 0; i < 50; i++) k += (size_t)snprintf(t + k, sizeof t - k, "%.17g %.17g\n", 1e8 + i, 1e8 + i);
  k += (size_t)snprintf(t + k, sizeof t - k, "100000000 100000000.00000001\nC 3 1\n0 0\n1 0\n0 1\n");
  contour_stack s;
  int rc = contour_parse(t, k, "s.contours", &s, NULL, "tile", err, sizeof err);
  CHECK(rc == 0, "the sliver refused: %s", err);
  if (rc == 0) contour_stack_free(&s);
  char *on = strstr(t, "100000000 100000000.00000001");
  memcpy(on, "100000000 100000000          ", strlen("100000000 100000000.00000001"));
  rc = contour_parse(t, k, "s.contours", &s, NULL, "tile", err, sizeof err);
  CHECK(rc == -1 && strstr(err, "s.contours:1: all 50 points of the contour are collinear"),
        "exactly on the line: '%s'", rc ? err : "accepted");
}

/* Bad contours: every one named in one run, a line each in file
 * order and a summary; in a small buffer as many whole lines as fit and a
 * summary that says so; with CONTOUR_SKIP_BAD dropped, a note each (its own
 * repair notes dropped with it) and one that counts them. */
static void check_many_bad(void) {
  static char text[8192], err[8192];
  size_t n = 0;
  int lines[12];
  for (int k = 0; k < 12; k++) {
    lines[k] = 1;
    for (size_t i = 0; i < n; i++) lines[k] += text[i] == '\n';
    if (k % 3 == 0)   /* good: a square, z = k */
      n += (size_t)snprintf(text + n, sizeof text - n, "C 4 %d\n0 0\n4 0\n4 4\n0 4\n", k);
    else if (k % 3 == 1)   /* a bow tie, with a duplicate point first */
      n += (size_t)snprintf(text + n, sizeof text - n, "C 5 %d\n0 0\n0 0\n1 1\n1 0\n0 1\n", k);
    else   /* collinear */
      n += (size_t)snprintf(text + n, sizeof text - n, "C 3 %d\n0 0\n1 1\n2 2\n", k);
  }
  contour_stack s;
  char *nb = NULL;
  size_t nl = 0;
  FILE *f = open_memstream(&nb, &nl);
  int rc = contour_parse(text, n, "m.contours", &s, f, "tile", err, sizeof err);
  fclose(f);
  int nlines = 1, named = 0;
  for (char *p = err; *p; p++) nlines += *p == '\n';
  for (int k = 0; k < 12; k++) {
    char want[64];
    snprintf(want, sizeof want, "m.contours:%d: %s", lines[k], k % 3 == 1 ? "the contour crosses itself" : "all 3 points");
    named += k % 3 != 0 && strstr(err, want) != NULL;
  }
  CHECK(rc == -1 && nlines == 9 && named == 8 && nl == 0 &&
            strstr(err, "\nm.contours: 8 of 12 contours cannot be tiled (32 of 48 points), each named above; --skip-bad "
                        "drops them and tiles the rest"),
        "8 bad of 12: %d, %d lines, %d named: '%s'", rc, nlines, named, err);
  free(nb);
  /* a buffer for three lines: the first ones and a summary that says so */
  rc = contour_parse(text, n, "m.contours", &s, NULL, "tile", err, 400);
  nlines = 1;
  for (char *p = err; *p; p++) nlines += *p == '\n';
  CHECK(rc == -1 && strlen(err) < 400 && nlines >= 2 && strstr(err, "8 of 12 contours cannot be tiled") &&
            strstr(err, "named above") && !strstr(err, "each named above"),
        "8 bad in 400 bytes: %d lines: '%s'", nlines, err);
  /* --skip-bad */
  nb = NULL, nl = 0;
  f = open_memstream(&nb, &nl);
  rc = contour_parse_flags(text, n, "m.contours", CONTOUR_SKIP_BAD, &s, f, "tile", err, sizeof err);
  fclose(f);
  int dropped = 0;
  for (char *p = nb; p && (p = strstr(p, ": dropped, it cannot be tiled: ")); p++) dropped++;
  CHECK(rc == 0 && s.n == 4 && dropped == 8 && !strstr(nb, "duplicate") &&
            strstr(nb, "tile: m.contours: --skip-bad dropped 8 bad contours of 12 (32 of 48 points); the rest are tiled\n"),
        "--skip-bad: %d, %d contours, %d dropped: '%s' '%s'", rc, rc ? 0 : s.n, dropped, nb ? nb : "", err);
  if (rc == 0) contour_stack_free(&s);
  free(nb);
}

int main(void) {
  check_many_bad();
  check_bad();
  check_fuzz();
  check_good();
  check_real();
  check_slices();
  check_extreme();
  return check_done("test_contour");
}
