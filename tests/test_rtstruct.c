/* test_rtstruct.c -- RT structure sets: the round trip through the test
 * writer (every encoding, bit for bit), the five sample files against the
 * data README's inventory, decimal strings whatever the locale, the planes,
 * every refusal and warning with its ROI, contour item and byte.
 *
 *   test_rtstruct --write DIR   writes the files tests/cli_dicom.sh uses */
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "input/contour.h"
#include "input/decimal.h"
#include "input/dicom.h"
#include "input/gen.h"
#include "util/rng.h"
#include "input/rtstruct.h"
#include "tests/rtwriter.h"
#include "util/xmem.h"

/* ---------------------------------------------------------------- a generated set */

enum { GEN_ROIS = 4, GEN_MAXC = 8, GEN_MAXP = 48 };

typedef struct {
  rtw_roi roi[GEN_ROIS];
  rtw_contour c[GEN_ROIS][GEN_MAXC];
  double xyz[GEN_ROIS][GEN_MAXC][3 * GEN_MAXP];
  contour_stack stack[GEN_ROIS];   /* what each ROI must read as: sorted by z */
  char names[GEN_ROIS][32];
} genset;

/* ROIs of random star contours on 3..8 slices (random spacing, one contour
 * each), written in a shuffled order; stack[] holds them sorted by z. */
static void gen_set(genset *g, uint64_t seed) {
  rng r;
  rng_seed(&r, seed);
  memset(g, 0, sizeof *g);
  static const char *types[] = {"ORGAN", NULL, "PTV", "AVOIDANCE"};
  for (int k = 0; k < GEN_ROIS; k++) {
    int nc = rng_int(&r, 3, GEN_MAXC);
    contour_stack *s = &g->stack[k];
    s->n = nc;
    s->c = xcalloc((size_t)nc, sizeof *s->c);
    double z = -50 + 100 * rng_uniform(&r);
    for (int i = 0; i < nc; i++) {
      contour *c = &s->c[i];
      c->n = rng_int(&r, 3, GEN_MAXP);
      c->pt = xmallocarray((size_t)c->n, sizeof *c->pt);
      c->z = z;
      gen_star(&r, c->pt, c->n, 200 * rng_uniform(&r) - 100, 200 * rng_uniform(&r) - 100,
               5 + 60 * rng_uniform(&r), 0.3);
      z += 0.5 + 4 * rng_uniform(&r);
    }
    /* Shuffled into the file. */
    int order[GEN_MAXC];
    for (int i = 0; i < nc; i++) order[i] = i;
    for (int i = nc - 1; i > 0; i--) {
      int j = rng_int(&r, 0, i), t = order[i];
      order[i] = order[j], order[j] = t;
    }
    for (int i = 0; i < nc; i++) {
      const contour *c = &s->c[order[i]];
      for (int j = 0; j < c->n; j++) {
        g->xyz[k][i][3 * j] = c->pt[j].x;
        g->xyz[k][i][3 * j + 1] = c->pt[j].y;
        g->xyz[k][i][3 * j + 2] = c->z;
      }
      g->c[k][i] = (rtw_contour){NULL, c->n, g->xyz[k][i], NULL, -1};
    }
    snprintf(g->names[k], sizeof g->names[k], "%s %d", k % 2 ? "Lung" : "Gland", k + 1);
    g->roi[k] = (rtw_roi){k * 3 + 1, g->names[k], types[k], nc, g->c[k], 0, 0};
  }
}

static void gen_free(genset *g) {
  for (int k = 0; k < GEN_ROIS; k++) contour_stack_free(&g->stack[k]);
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static int same_stack(const contour_stack *a, const contour_stack *b) {
  if (a->n != b->n) return 0;
  for (int i = 0; i < a->n; i++) {
    if (a->c[i].n != b->c[i].n || !same_bits(a->c[i].z, b->c[i].z)) return 0;
    for (int j = 0; j < a->c[i].n; j++)
      if (!same_bits(a->c[i].pt[j].x, b->c[i].pt[j].x) || !same_bits(a->c[i].pt[j].y, b->c[i].pt[j].y))
        return 0;
  }
  return 1;
}

/* The generator's stack through .contours text (contour_write, contour_parse):
 * the reference an ROI's stack must equal. */
static int reference(const contour_stack *s, contour_stack *out) {
  char *text = NULL, err[512];
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  contour_write(f, s);
  fclose(f);
  int rc = contour_parse(text, len, "ref", out, NULL, "t", err, sizeof err);
  free(text);
  return rc;
}

/* ---------------------------------------------------------------- round trip */

static void round_trip(void) {
  for (uint64_t seed = 1; seed <= 6; seed++) {
    genset g;
    gen_set(&g, seed);
    char *first_text[GEN_ROIS] = {0};
    for (int k = 0; k < 24; k++) {
      rtw_opts o = {k & 1, (k >> 1) & 1, (k >> 2) % 3, k >= 12, NULL, NULL, 0};
      size_t len;
      unsigned char *b = rtw_write(&o, g.roi, GEN_ROIS, &len);
      rtstruct s;
      char err[1024];
      if (rtstruct_parse(b, len, "gen.dcm", &s, err, sizeof err) != 0) {
        CHECK(0, "seed %llu variant %d: %s", (unsigned long long)seed, k, err);
        free(b);
        continue;
      }
      CHECK(s.nroi == GEN_ROIS && !s.warnings, "seed %llu variant %d: %d ROIs", (unsigned long long)seed, k, s.nroi);
      for (int r = 0; r < s.nroi && r < GEN_ROIS; r++) {
        const rtstruct_roi *roi = &s.roi[r];
        CHECK(roi->number == g.roi[r].number && strcmp(roi->name, g.roi[r].name) == 0 &&
                  strcmp(roi->type, g.roi[r].type ? g.roi[r].type : "") == 0 && !roi->error &&
                  roi->nc == g.roi[r].nc && roi->slices == g.roi[r].nc && roi->skipped == 0 &&
                  roi->plane == RTSTRUCT_AXIAL,
              "seed %llu variant %d ROI %d: %d '%s' '%s' %d contours %s", (unsigned long long)seed, k, r,
              roi->number, roi->name, roi->type, roi->nc, roi->error ? roi->error : "");
        /* Bit for bit: the ROI's contours, sorted, are the generator's. */
        const contour_stack *ref = &g.stack[r];
        int same = roi->nc == ref->n;
        for (int i = 0; same && i < roi->nc; i++) {
          same &= roi->c[i].n == ref->c[i].n && same_bits(roi->c[i].h, ref->c[i].z);
          for (int j = 0; same && j < roi->c[i].n; j++)
            same &= same_bits(roi->c[i].p[3 * j], ref->c[i].pt[j].x) &&
                    same_bits(roi->c[i].p[3 * j + 1], ref->c[i].pt[j].y) &&
                    same_bits(roi->c[i].p[3 * j + 2], ref->c[i].z);
        }
        CHECK(same, "seed %llu variant %d ROI %d: contours differ from the generator's",
              (unsigned long long)seed, k, r);
        /* The ROI's stack equals the generator's stack read as .contours. */
        contour_stack st, rs;
        int a = rtstruct_roi_stack(&s, r, CONTOUR_PAIRS, &st, NULL, "t", err, sizeof err);
        int bref = reference(ref, &rs);
        CHECK(a == 0 && bref == 0 && same_stack(&st, &rs), "seed %llu variant %d ROI %d: stack differs (%s)",
              (unsigned long long)seed, k, r, a ? err : "");
        contour_stack_free(&st);
        contour_stack_free(&rs);
        /* Every encoding gives the same text, so the same meshes. */
        size_t tl;
        char *t = rtstruct_roi_text(&s, r, &tl);
        if (!first_text[r]) first_text[r] = t;
        else {
          CHECK(strcmp(t, first_text[r]) == 0, "seed %llu variant %d ROI %d: text differs", (unsigned long long)seed, k, r);
          free(t);
        }
      }
      rtstruct_free(&s);
      free(b);
    }
    for (int r = 0; r < GEN_ROIS; r++) free(first_text[r]);
    gen_free(&g);
  }
}

/* ---------------------------------------------------------------- samples */

/* The data README's inventory (shared/data/rtstruct/README.md), by hand. */
typedef struct { int number; const char *name, *type; int contours, skipped, slices; long points; } inv;

static const inv dicompyler[] = {
    {1, "BODY", "EXTERNAL", 141, 0, 98, 51846}, {2, "Areola", "AVOIDANCE", 0, 0, 0, 0},
    {3, "Borders", "CTV", 2, 0, 2, -1},           {4, "Breast", "GTV", 48, 0, 47, -1},
    {5, "Heart", "ORGAN", 33, 0, 33, -1},         {6, "Lt Lung", "AVOIDANCE", 165, 0, 80, -1},
    {7, "Nodes", "AVOIDANCE", 4, 0, 4, -1},       {8, "Scar", "AVOIDANCE", 6, 0, 6, -1},
    {9, "Tumor Bed", "CTV", 18, 0, 18, -1},       {10, "Tumor Bed Block", "GTV", 24, 0, 24, -1},
};
static const inv pydicom[] = {{1, "patient", "EXTERNAL", 3, 0, 3, 17},
                              {2, "Isocenter 1", "ISOCENTER", 0, 1, 0, 0},
                              {3, "Isocenter 2", "ISOCENTER", 0, 1, 0, 0}};
static const inv mim[] = {{1, "ROI-1", "", 3, 0, 3, -1}, {2, "ROI-2", "", 3, 0, 3, -1},
                          {3, "ROI-3", "", 3, 0, 3, -1}, {4, "ROI-4", "", 3, 0, 3, -1}};
static const inv rt[] = {{1, "ROI-1", "", 2, 0, 1, 12}};

static void samples(void) {
  static const struct { const char *file; const inv *want; int n; } files[] = {
      {"dicompyler_rtss", dicompyler, 10}, {"pydicom_rtstruct", pydicom, 3},
      {"rtutils_dummy_rt", mim, 4},        {"rtutils_dummy_rt_explicit", mim, 4},
      {"rtutils_rt", rt, 1},
  };
  rtstruct mim_implicit = {0};
  for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
    char path[128], err[1024];
    snprintf(path, sizeof path, "tests/data/rtstruct/%s.dcm", files[f].file);
    rtstruct s;
    if (rtstruct_read(path, &s, err, sizeof err) != 0) {
      CHECK(0, "%s", err);
      continue;
    }
    CHECK(s.nroi == files[f].n && !s.warnings, "%s: %d ROIs", path, s.nroi);
    for (int i = 0; i < s.nroi && i < files[f].n; i++) {
      const inv *w = &files[f].want[i];
      const rtstruct_roi *r = &s.roi[i];
      CHECK(r->number == w->number && strcmp(r->name, w->name) == 0 && strcmp(r->type, w->type) == 0 &&
                r->nc == w->contours && r->skipped == w->skipped && r->slices == w->slices &&
                (w->points < 0 || r->points == w->points) && !r->error,
            "%s ROI %d: %d '%s' '%s' %d/%d/%d/%ld", path, i, r->number, r->name, r->type, r->nc, r->skipped,
            r->slices, r->points);
    }
    /* The MIM file stores z descending; the stacks come sorted. */
    if (strcmp(files[f].file, "rtutils_dummy_rt") == 0) {
      const rtstruct_roi *r = &s.roi[0];
      CHECK(r->nc == 3 && r->c[0].h == 60 && r->c[2].h == 70 && r->c[0].item == 3, "MIM: not sorted (%d)",
            r->nc ? r->c[0].item : 0);
      mim_implicit = s;
      continue;
    }
    /* The explicit re-encoding holds the same contours, bit for bit. */
    if (strcmp(files[f].file, "rtutils_dummy_rt_explicit") == 0 && mim_implicit.nroi == s.nroi) {
      for (int i = 0; i < s.nroi; i++) {
        size_t la, lb;
        char *a = rtstruct_roi_text(&mim_implicit, i, &la), *b = rtstruct_roi_text(&s, i, &lb);
        const char *pa = strchr(a, '\n'), *pb = strchr(b, '\n');   /* the first line names the file */
        CHECK(pa && pb && strcmp(pa, pb) == 0, "ROI %d: implicit and explicit encodings differ", i + 1);
        free(a), free(b);
      }
      rtstruct_free(&mim_implicit);
    }
    rtstruct_free(&s);
  }
  if (mim_implicit.nroi) rtstruct_free(&mim_implicit);
}

/* ---------------------------------------------------------------- decimal strings */

static void decimal_strings(void) {
  static const struct { const char *s; double v; } good[] = {
      {"0", 0},       {"-0.0", -0.0},     {"5.4e-1", 0.54},  {"  12.5 ", 12.5}, {"+3", 3},
      {".5", 0.5},    {"5.", 5},          {"1E3", 1000},     {"-122.44", -122.44},
      {"1e-400", 0},  {"0.1", 0.1},       {"123456789012345678901234567890", 1.2345678901234568e29},
      {"4.9406564584124654e-324", 4.9406564584124654e-324}, {"2.2250738585072014e-308", 2.2250738585072014e-308},
      {"9007199254740993", 9007199254740992.0}, {"1.7976931348623157e308", 1.7976931348623157e308},
  };
  static const char *bad[] = {"", " ", "abc", "1.2.3", "1e", "e5", "+-1", "nan", "inf", "0x10",
                              "1,5", "1 2", "--1", ".", "-.", "1e+", "1d5"};
  double v;
  for (size_t i = 0; i < sizeof good / sizeof *good; i++) {
    int rc = decimal_parse(good[i].s, strlen(good[i].s), &v);
    CHECK(rc == 0 && same_bits(v, good[i].v), "DS '%s': %d %.17g", good[i].s, rc, v);
  }
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
    CHECK(decimal_parse(bad[i], strlen(bad[i]), &v) == -1, "DS '%s' accepted", bad[i]);
  CHECK(decimal_parse("1e999", 5, &v) == 1 && decimal_parse("-1e400", 6, &v) == 1, "DS overflow not refused");
  /* How finely a value was written: its shortest decimal form's last place. */
  static const struct { double v, q; } quanta[] = {{0.45, 0.01}, {12.3, 0.1}, {20, 10}, {-0.07, 0.01}, {1e-20, 1e-20},
                                                   {1.2345678901234567, 1e-16}, {-123.456, 0.001}, {0, 0}};
  for (size_t i = 0; i < sizeof quanta / sizeof *quanta; i++)
    CHECK(decimal_quantum(quanta[i].v) == quanta[i].q || fabs(decimal_quantum(quanta[i].v) / quanta[i].q - 1) < 1e-12,
          "decimal_quantum(%.17g) = %.17g, want %.17g", quanta[i].v, decimal_quantum(quanta[i].v), quanta[i].q);
  int coarse = 0;
  for (int i = -50000; i <= 50000; i += 7) {   /* two decimals, every last digit */
    double q = decimal_quantum(i / 100.0);
    coarse += i % 10 ? fabs(q / 0.01 - 1) > 1e-12 : !(i == 0 || q > 0.0099999);   /* a last digit 0: coarser (or 0) */
  }
  CHECK(coarse == 0, "%d values of two decimals not found written to 0.01", coarse);
  /* Random decimal strings against strtod in the C locale, bit for bit;
   * then again with a comma as the locale's decimal point. */
  enum { N = 20000 };
  static char str[N][48];
  static double want[N];
  rng g;
  rng_seed(&g, 77);
  for (int i = 0; i < N; i++) {
    int k = 0, digits = rng_int(&g, 1, 22), point = rng_int(&g, -1, digits);
    if (rng_int(&g, 0, 1)) str[i][k++] = '-';
    for (int d = 0; d < digits; d++) {
      if (d == point) str[i][k++] = '.';
      str[i][k++] = (char)('0' + rng_int(&g, 0, 9));
    }
    if (rng_int(&g, 0, 2) == 0) k += snprintf(str[i] + k, 12, "e%d", rng_int(&g, -330, 310));
    str[i][k] = 0;
    want[i] = strtod(str[i], NULL);
  }
  int same = 0;
  for (int i = 0; i < N; i++) {
    int rc = decimal_parse(str[i], strlen(str[i]), &v);
    same += (rc == 0 && same_bits(v, want[i])) || (rc == 1 && !isfinite(want[i]));
  }
  CHECK(same == N, "DS against strtod: %d of %d the same", same, N);
  /* A locale whose decimal point is a comma: the system's, or one built
   * here by localedef (into a temporary directory, removed after). */
  char dir[] = "/tmp/tilesim-locale.XXXXXX", cmd[256];
  int built = 0;
  if (!setlocale(LC_NUMERIC, "de_DE.UTF-8") && mkdtemp(dir)) {
    snprintf(cmd, sizeof cmd, "localedef -i de_DE -f UTF-8 %s/de_DE.UTF-8 >/dev/null 2>&1", dir);
    built = 1;
    if (system(cmd) == 0) {
      setenv("LOCPATH", dir, 1);
      setlocale(LC_NUMERIC, "de_DE.UTF-8");
    }
  }
  if (strtod("1.5", NULL) == 1.0) {
    same = 0;
    for (int i = 0; i < N; i++) {
      int rc = decimal_parse(str[i], strlen(str[i]), &v);
      same += (rc == 0 && same_bits(v, want[i])) || (rc == 1 && !isfinite(want[i]));
    }
    CHECK(same == N, "DS under a comma locale: %d of %d the same", same, N);
  } else {
    printf("test_rtstruct: no comma-decimal locale here (localedef failed): the locale check was skipped\n");
  }
  if (built) {
    check_rmtree(dir);
  }
  setlocale(LC_NUMERIC, "C");
  unsetenv("LOCPATH");
}

/* ---------------------------------------------------------------- refusals */

static const double sq[] = {0, 0, 5, 10, 0, 5, 10, 10, 5, 0, 10, 5};   /* a ccw square at z 5 */
static double sq2[12], sq3[12];
/* the square at z 5 moved by (2, 2): on its slice, it crosses the square (a
 * copy of it would be dropped as a duplicate) */
static const double sqm[] = {2, 2, 5, 12, 2, 5, 12, 12, 5, 2, 12, 5};
static const double sqd[] = {20, 0, 5, 30, 0, 5, 30, 10, 5, 20, 10, 5};   /* apart from sq, on its slice */

static unsigned char *write1(const rtw_roi *roi, int n, size_t *len) {
  rtw_opts o = {0, 1, 0, 0, NULL, NULL, 0};
  return rtw_write(&o, roi, n, len);
}

/* The file is refused: "set.dcm: byte N: ..." holding words. */
static void file_refused(const char *what, const unsigned char *b, size_t len, const char *words) {
  rtstruct s;
  char err[1024] = "";
  int rc = rtstruct_parse(b, len, "set.dcm", &s, err, sizeof err);
  CHECK(rc == -1 && strncmp(err, "set.dcm: byte ", 14) == 0 && strstr(err, words) && !strchr(err, '\n'),
        "%s: expected '%s', got %d '%s'", what, words, rc, err);
  if (rc == 0) rtstruct_free(&s);
}

/* The file reads; ROI 0's stack is refused with words. */
static void roi_refused(const char *what, const unsigned char *b, size_t len, const char *words) {
  rtstruct s;
  char err[1024] = "";
  if (rtstruct_parse(b, len, "set.dcm", &s, err, sizeof err) != 0) {
    CHECK(0, "%s: the file is refused: %s", what, err);
    return;
  }
  contour_stack st;
  int rc = rtstruct_roi_stack(&s, 0, CONTOUR_PAIRS, &st, NULL, "t", err, sizeof err);
  CHECK(rc == -1 && strncmp(err, "set.dcm: ", 9) == 0 && strstr(err, words) && !strchr(err, '\n'),
        "%s: expected '%s', got %d '%s'", what, words, rc, err);
  if (rc == 0) contour_stack_free(&st);
  rtstruct_free(&s);
}

static void refusals(void) {
  for (int i = 0; i < 12; i++) sq2[i] = sq[i] + (i % 3 == 2 ? 3 : 0), sq3[i] = sq[i] + (i % 3 == 2 ? 6 : 0);
  size_t len;
  unsigned char *b;
  rtw_contour two[3] = {{NULL, 4, sq, NULL, -1}, {NULL, 4, sq2, NULL, -1}, {NULL, 4, sq3, NULL, -1}};
  rtw_roi ok = {7, "Prostate", "PTV", 3, two, 0, 0};

  rtw_opts ct = {0, 0, 0, 0, NULL, "CT", 0};
  b = rtw_write(&ct, &ok, 1, &len);
  file_refused("modality", b, len, "not an RT structure set: the Modality (0008,0060) is CT");
  free(b);

  rtw_roi dup[2] = {ok, ok};
  b = write1(dup, 2, &len);
  file_refused("duplicate number", b, len, "ROI number 7 is already used by the item at byte");
  free(b);

  rtw_contour c1 = {NULL, 4, sq, NULL, 5};
  rtw_contour cs[3] = {c1, two[1], two[2]};
  rtw_roi r = {7, "Prostate", "PTV", 3, cs, 0, 0};
  b = write1(&r, 1, &len);
  roi_refused("count", b, len, "ROI 7 'Prostate', contour item 1: NumberOfContourPoints is 5 but ContourData holds 12 values (4 points)");
  free(b);

  cs[0] = (rtw_contour){NULL, 4, NULL, "0\\0\\5\\10\\0\\5\\10\\abc\\5\\0\\10\\5", -1};
  b = write1(&r, 1, &len);
  roi_refused("non-numeric", b, len, "ROI 7 'Prostate', contour item 1, point 3: y is not a number (abc)");
  free(b);

  cs[0] = (rtw_contour){NULL, 4, NULL, "0\\0\\5\\10\\0\\5\\10\\10\\5\\1e999\\10\\5", -1};
  b = write1(&r, 1, &len);
  roi_refused("non-finite", b, len, "contour item 1, point 4: x is not finite (1e999)");
  free(b);

  cs[0] = (rtw_contour){NULL, 4, NULL, "0\\0\\5\\10\\0\\5\\10", -2};
  b = write1(&r, 1, &len);
  roi_refused("triplets", b, len, "contour item 1: ContourData holds 7 values, not x y z triplets");
  free(b);

  cs[0] = (rtw_contour){NULL, 4, NULL, "", -2};
  b = write1(&r, 1, &len);
  roi_refused("empty data", b, len, "contour item 1: ContourData is empty");
  free(b);

  cs[0] = (rtw_contour){NULL, 4, sq, NULL, -1};
  cs[1] = (rtw_contour){NULL, 4, NULL, "0\\0\\5\\10\\0\\6\\10\\10\\7\\0\\10\\5", -1};
  b = write1(&r, 1, &len);
  roi_refused("not planar", b, len, "contour item 2: not planar (its points spread 0.497 mm off their best plane, more than the 0.1 mm "
              "their precision allows): contours must lie in parallel planes");
  free(b);
  cs[1] = two[1];

  rtw_roi one = {7, "Prostate", "PTV", 1, cs, 0, 0};
  b = write1(&one, 1, &len);
  roi_refused("one contour", b, len, "ROI 7 'Prostate', contour item 1: only one contour; tiling needs at least 2");
  free(b);

  cs[1] = (rtw_contour){NULL, 4, sqd, NULL, -1};
  b = write1(&r, 1, &len);
  roi_refused("two on a slice", b, len, "contour item 2: slice z=5 already has a contour (contour item 1); this program tiles each contour with the next and needs one contour per slice");
  free(b);
  cs[1] = two[1];

  cs[1] = (rtw_contour){NULL, 3, NULL, "1\\1\\8\\2\\2\\8\\3\\3\\8", -1};
  b = write1(&r, 1, &len);
  roi_refused("collinear", b, len, "contour item 2: all 3 points of the contour are collinear");
  free(b);
  cs[1] = two[1];

  cs[1] = (rtw_contour){NULL, 4, NULL, "0\\0\\8\\10\\10\\8\\10\\0\\8\\0\\10\\8", -1};
  b = write1(&r, 1, &len);
  roi_refused("bowtie", b, len, "contour item 2: the contour crosses itself: the segment from point 1 to point 2 crosses the segment from point 3 to point 4 (5 5)");
  free(b);
  cs[1] = two[1];

  rtw_roi empty = {2, "Areola", NULL, 0, NULL, 0, 1};
  b = write1(&empty, 1, &len);
  roi_refused("empty", b, len, "ROI 2 'Areola' has no contours to tile");
  free(b);

  /* Lookup: by name, then number; unknown and shared names refused. */
  rtw_roi two_rois[3] = {ok, {9, "7", NULL, 3, two, 0, 0}, {11, "Same", NULL, 3, two, 0, 0}};
  rtw_roi same2[2] = {{3, "Same", NULL, 3, two, 0, 0}, {4, "Same", NULL, 3, two, 0, 0}};
  b = write1(two_rois, 3, &len);
  rtstruct s;
  char err[1024];
  if (rtstruct_parse(b, len, "set.dcm", &s, err, sizeof err) == 0) {
    CHECK(rtstruct_find(&s, "Prostate", err, sizeof err) == 0, "by name");
    CHECK(rtstruct_find(&s, "7", err, sizeof err) == 1, "a name wins over a number");
    CHECK(rtstruct_find(&s, "11", err, sizeof err) == 2, "by number");
    CHECK(rtstruct_find(&s, "prostate", err, sizeof err) == -1 &&
              strstr(err, "set.dcm: no ROI named or numbered 'prostate' (the ROIs: 7 'Prostate', 9 '7', 11 'Same')"),
          "unknown: %s", err);
    rtstruct_free(&s);
  }
  free(b);
  b = write1(same2, 2, &len);
  if (rtstruct_parse(b, len, "set.dcm", &s, err, sizeof err) == 0) {
    CHECK(rtstruct_find(&s, "Same", err, sizeof err) == -1 && strstr(err, "ROIs 3 and 4 are both named 'Same'"),
          "shared name: %s", err);
    CHECK(rtstruct_find(&s, "4", err, sizeof err) == 1, "by number when names are shared");
    rtstruct_free(&s);
  }
  free(b);
}

/* Three squares in parallel planes tilted 30 degrees about x, at 1e300 mm:
 * the frame's sums overflow, so the stack's computed values are not finite
 * and the ROI is refused as the .contours reader refuses such a text. */
static void oblique_overflow(void) {
  static double xyz[3][12];
  rtw_contour c[3];
  double t = 0.5235987755982988, corner[4][2] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  for (int k = 0; k < 3; k++) {
    for (int j = 0; j < 4; j++) {
      double u = corner[j][0], v = corner[j][1], h = 5.0 * k;
      xyz[k][3 * j] = 1e300 * u;
      xyz[k][3 * j + 1] = 1e300 * (v * cos(t) - h * sin(t));
      xyz[k][3 * j + 2] = 1e300 * (v * sin(t) + h * cos(t));
    }
    c[k] = (rtw_contour){NULL, 4, xyz[k], NULL, -1};
  }
  rtw_roi roi = {1, "Far", NULL, 3, c, 0, 0};
  size_t len;
  unsigned char *b = write1(&roi, 1, &len);
  roi_refused("an oblique ROI at 1e300 mm", b, len, "ROI 1 'Far', contour item 3: z is not finite (nan)");
  free(b);
}

/* ---------------------------------------------------------------- warnings */

static void warnings(void) {
  static double cw[12], cw2[12];   /* the squares, clockwise */
  for (int j = 0; j < 4; j++)
    for (int a = 0; a < 3; a++) cw[3 * j + a] = sq[3 * ((4 - j) % 4) + a], cw2[3 * j + a] = sq2[3 * ((4 - j) % 4) + a];
  rtw_contour cs[5] = {{NULL, 4, cw, NULL, -1}, {"POINT", 1, sq, NULL, -1}, {NULL, 4, cw2, NULL, -1},
                       {"OPEN_PLANAR", 2, sq, NULL, -1}, {"OPEN_PLANAR", 2, sq3, NULL, -1}};
  rtw_roi rois[3] = {{1, "Body  ", "EXTERNAL", 5, cs, 0, 0}, {2, "Nothing", NULL, 0, NULL, 0, 1},
                     {3, "Orphan", NULL, 1, cs, 99, 0}};
  size_t len;
  unsigned char *b = write1(rois, 3, &len);
  rtstruct s;
  char err[1024];
  if (rtstruct_parse(b, len, "w.dcm", &s, err, sizeof err) != 0) {
    CHECK(0, "warnings: %s", err);
    free(b);
    return;
  }
  CHECK(strcmp(s.roi[0].name, "Body") == 0, "trailing spaces kept: '%s'", s.roi[0].name);
  CHECK(s.roi[0].nc == 2 && s.roi[0].skipped == 3 && s.roi[0].warnings &&
            strstr(s.roi[0].warnings, "w.dcm: ROI 1 'Body': skipped 1 POINT and 2 OPEN_PLANAR contours; only "
                                      "CLOSED_PLANAR contours are tiled\n"),
        "skipped: %s", s.roi[0].warnings ? s.roi[0].warnings : "none");
  CHECK(s.warnings && strstr(s.warnings, "ROIContourSequence item 3 references ROI 99, which the "
                                         "StructureSetROISequence does not define; its 1 contour is ignored") &&
            s.roi[2].nc == 0,
        "unknown reference: %s", s.warnings ? s.warnings : "none");
  CHECK(s.roi[1].nc == 0 && !s.roi[1].error, "empty ROI");
  /* A clockwise contour is reversed, and the note names the ROI. */
  char *notes = NULL;
  size_t nl = 0;
  FILE *f = open_memstream(&notes, &nl);
  contour_stack st;
  int rc = rtstruct_roi_stack(&s, 0, CONTOUR_PAIRS, &st, f, "tile", err, sizeof err);
  fclose(f);
  CHECK(rc == 0, "Body: %s", err);
  if (rc == 0) contour_stack_free(&st);
  CHECK(notes && strstr(notes, "tile: w.dcm: ROI 1 'Body': 2 of 2 contours ran clockwise; reversed to counter-clockwise"),
        "clockwise note: %s", notes ? notes : "none");
  free(notes);
  rtstruct_free(&s);
  free(b);
}

/* Many ROIs: numbers looked up in log time (a quadratic search would take
 * minutes here under the sanitizers), file warnings capped. */
static void many(void) {
  enum { N = 20000 };
  rtw_roi *rois = xcalloc(N, sizeof *rois);
  for (int i = 0; i < N; i++) rois[i] = (rtw_roi){N - i, "r", NULL, 0, NULL, i % 2 ? 2 * N + i : 0, 1};
  size_t len;
  unsigned char *b = write1(rois, N, &len);
  rtstruct s;
  char err[1024];
  if (rtstruct_parse(b, len, "many.dcm", &s, err, sizeof err) != 0) {
    CHECK(0, "many: %s", err);
  } else {
    int lines = 0;
    for (const char *p = s.warnings; p && *p; p++) lines += *p == '\n';
    CHECK(s.nroi == N && lines == 11 && strstr(s.warnings, "many.dcm: and 9990 more warnings like these\n"),
          "many: %d ROIs, %d warning lines", s.nroi, lines);
    rtstruct_free(&s);
  }
  free(b);
  /* The first duplicate in file order is named, with the item it repeats. */
  rois[N - 1].number = 7;
  rois[N - 2].number = 9;
  b = write1(rois, N, &len);
  file_refused("duplicate among many", b, len, "StructureSetROISequence item 19999: ROI number 9 is already used by the item at byte");
  free(b);
  free(rois);
}

/* ---------------------------------------------------------------- planes */

/* One generated ROI written axial, sagittal and coronal: the same stack;
 * the stack's points turned back are the file's. */
static void planes(void) {
  genset g;
  gen_set(&g, 99);
  static double p[3][GEN_MAXC][3 * GEN_MAXP];
  rtw_contour c[3][GEN_MAXC];
  rtw_roi roi[3];
  const rtw_roi *a = &g.roi[0];
  for (int pl = 0; pl < 3; pl++) {
    for (int i = 0; i < a->nc; i++) {
      for (int j = 0; j < a->c[i].n; j++) {
        const double *q = a->c[i].xyz + 3 * j;   /* u v h */
        double *o = p[pl][i] + 3 * j;
        if (pl == 0) o[0] = q[0], o[1] = q[1], o[2] = q[2];
        else if (pl == 1) o[0] = q[2], o[1] = q[0], o[2] = q[1];   /* sagittal: x = h */
        else o[0] = q[1], o[1] = q[2], o[2] = q[0];                 /* coronal: y = h */
      }
      c[pl][i] = (rtw_contour){NULL, a->c[i].n, p[pl][i], NULL, -1};
    }
    roi[pl] = (rtw_roi){pl + 1, "Plane", NULL, a->nc, c[pl], 0, 0};
  }
  contour_stack st[3];
  char err[1024];
  for (int pl = 0; pl < 3; pl++) {
    size_t len;
    unsigned char *b = write1(&roi[pl], 1, &len);
    rtstruct s;
    memset(&st[pl], 0, sizeof st[pl]);
    if (rtstruct_parse(b, len, "p.dcm", &s, err, sizeof err) != 0) {
      CHECK(0, "plane %d: %s", pl, err);
      free(b);
      continue;
    }
    CHECK((int)s.roi[0].plane == pl, "plane %d read as %s", pl, rtstruct_plane_name(s.roi[0].plane));
    CHECK(rtstruct_roi_stack(&s, 0, CONTOUR_PAIRS, &st[pl], NULL, "t", err, sizeof err) == 0, "plane %d: %s", pl, err);
    int back = 1;
    for (int i = 0; i < s.roi[0].nc; i++)
      for (int j = 0; j < s.roi[0].c[i].n; j++) {
        const double *q = s.roi[0].c[i].p + 3 * j;
        double x = 0, y = 0, z = s.roi[0].c[i].h;
        /* The stack frame's point, from the text's columns. */
        if (pl == 0) x = q[0], y = q[1];
        else if (pl == 1) x = q[1], y = q[2];
        else x = q[2], y = q[0];
        rtstruct_to_patient(&s.roi[0], &x, &y, &z);
        back &= same_bits(x, q[0]) && same_bits(y, q[1]) && same_bits(z, q[2]);
      }
    CHECK(back, "plane %d: turned back differs", pl);
    rtstruct_free(&s);
    free(b);
  }
  CHECK(same_stack(&st[0], &st[1]) && same_stack(&st[0], &st[2]), "the three planes give different stacks");
  for (int pl = 0; pl < 3; pl++) contour_stack_free(&st[pl]);
  gen_free(&g);
}

/* ---------------------------------------------------------------- fixtures */


/* The files tests/cli_dicom.sh runs ./tile on. */
static int write_fixtures(const char *dir) {
  int bad = 0;
  size_t len;
  unsigned char *b;
  genset g;
  gen_set(&g, 5);
  static const struct { const char *name; rtw_opts o; } enc[] = {
      {"gen_implicit.dcm", {0, 0, 0, 0, NULL, NULL, 0}},
      {"gen_implicit_undefined.dcm", {0, 1, 2, 1, NULL, NULL, 0}},
      {"gen_explicit.dcm", {1, 0, 0, 1, NULL, NULL, 0}},
      {"gen_explicit_undefined.dcm", {1, 1, 1, 1, NULL, NULL, 0}},
  };
  for (size_t i = 0; i < sizeof enc / sizeof *enc; i++) {
    b = rtw_write(&enc[i].o, g.roi, GEN_ROIS, &len);
    bad |= rtw_save(dir, enc[i].name, b, len);
    free(b);
  }
  /* The generator's stacks as .contours, for comparison. */
  for (int k = 0; k < GEN_ROIS; k++) {
    char path[512];
    snprintf(path, sizeof path, "%s/gen_%d.contours", dir, g.roi[k].number);
    FILE *f = fopen(path, "w");
    if (!f) return 1;
    contour_write(f, &g.stack[k]);
    fclose(f);
  }
  gen_free(&g);

  for (int i = 0; i < 12; i++) sq2[i] = sq[i] + (i % 3 == 2 ? 3 : 0), sq3[i] = sq[i] + (i % 3 == 2 ? 6 : 0);
  rtw_contour sl[3] = {{NULL, 4, sq, NULL, -1}, {NULL, 4, sq2, NULL, -1}, {NULL, 4, sq3, NULL, -1}};
  rtw_roi ok = {7, "Prostate", "PTV", 3, sl, 0, 0};
  /* Small files in every encoding (the fuzz target's seeds). */
  for (int k = 0; k < 12; k++) {
    rtw_opts o = {k & 1, (k >> 1) & 1, (k >> 2) % 3, 1, NULL, NULL, 0};
    char name[32];
    snprintf(name, sizeof name, "seed_%d.dcm", k);
    b = rtw_write(&o, &ok, 1, &len);
    bad |= rtw_save(dir, name, b, len);
    free(b);
  }
  static const struct { const char *name; const char *ts, *modality; int deep; } opts[] = {
      {"bigendian.dcm", "1.2.840.10008.1.2.2", NULL, 0},
      {"deflated.dcm", "1.2.840.10008.1.2.1.99", NULL, 0},
      {"private_ts.dcm", "1.2.3.4.5.6", NULL, 0},
      {"ct.dcm", NULL, "CT", 0},
      {"deep.dcm", NULL, NULL, 17},
  };
  for (size_t i = 0; i < sizeof opts / sizeof *opts; i++) {
    rtw_opts o = {0, 1, 0, 0, opts[i].ts, opts[i].modality, opts[i].deep};
    b = rtw_write(&o, &ok, 1, &len);
    bad |= rtw_save(dir, opts[i].name, b, len);
    free(b);
  }
  /* A length running past its parent: the first ROI item two bytes longer. */
  rtw_opts def = {0, 0, 0, 0, NULL, NULL, 0};
  b = rtw_write(&def, &ok, 1, &len);
  char err[512];
  static const uint32_t ss[] = {DICOM_TAG(0x3006, 0x0020)};
  dicom *d = dicom_parse(b, len, "x", ss, 1, err, sizeof err);
  if (d) {
    size_t at = dicom_offset(d, dicom_first(d, dicom_child(d, DICOM_ROOT, ss[0]))) + 4;
    b[at] = (unsigned char)(b[at] + 2);
    dicom_free(d);
  }
  bad |= rtw_save(dir, "pastparent.dcm", b, len);
  free(b);

  rtw_contour cs[3] = {sl[0], sl[1], sl[2]};
  rtw_roi r = {7, "Prostate", "PTV", 3, cs, 0, 0};
  static const struct { const char *name; rtw_contour c; int at; } bad_roi[] = {
      {"count.dcm", {NULL, 4, sq, NULL, 5}, 0},
      {"nonnumeric.dcm", {NULL, 4, NULL, "0\\0\\5\\10\\0\\5\\10\\abc\\5\\0\\10\\5", -1}, 0},
      {"nonfinite.dcm", {NULL, 4, NULL, "0\\0\\5\\10\\0\\5\\10\\10\\5\\1e999\\10\\5", -1}, 0},
      {"triplets.dcm", {NULL, 4, NULL, "0\\0\\5\\10\\0\\5\\10", -2}, 0},
      {"oblique.dcm", {NULL, 4, NULL, "0\\0\\5\\10\\0\\6\\10\\10\\7\\0\\10\\5", -1}, 1},
      {"twoperslice.dcm", {NULL, 4, sqm, NULL, -1}, 1},
  };
  for (size_t i = 0; i < sizeof bad_roi / sizeof *bad_roi; i++) {
    cs[bad_roi[i].at] = bad_roi[i].c;
    b = write1(&r, 1, &len);
    bad |= rtw_save(dir, bad_roi[i].name, b, len);
    free(b);
    cs[0] = sl[0], cs[1] = sl[1];
  }
  rtw_roi one = {7, "Prostate", "PTV", 1, sl, 0, 0};
  b = write1(&one, 1, &len);
  bad |= rtw_save(dir, "onecontour.dcm", b, len);
  free(b);
  /* Warnings: skipped POINT and OPEN contours, an empty ROI, an unknown
   * reference, clockwise contours; and names to sanitise. */
  rtw_contour mixed[5] = {{NULL, 4, sq, NULL, -1}, {"POINT", 1, sq, NULL, -1}, {NULL, 4, sq2, NULL, -1},
                          {"OPEN_PLANAR", 2, sq, NULL, -1}, {NULL, 4, sq3, NULL, -1}};
  rtw_roi w[6] = {{1, "Body", "EXTERNAL", 5, mixed, 0, 0}, {2, "Nothing", NULL, 0, NULL, 0, 1},
                  {3, "Orphan", NULL, 3, sl, 99, 0},       {4, "Lt Lung/left", NULL, 3, sl, 0, 0},
                  {5, "lt lung_left", NULL, 3, sl, 0, 0},  {6, "..", NULL, 3, sl, 0, 0}};
  b = write1(w, 6, &len);
  bad |= rtw_save(dir, "warnings.dcm", b, len);
  free(b);
  rtw_roi same2[2] = {{3, "Same", NULL, 3, sl, 0, 0}, {4, "Same", NULL, 3, sl, 0, 0}};
  b = write1(same2, 2, &len);
  bad |= rtw_save(dir, "samenames.dcm", b, len);
  free(b);
  /* One ROI in three planes (the square stack: axial, sagittal, coronal). */
  static double p[3][3][12];
  rtw_contour pc[3][3];
  for (int pl = 0; pl < 3; pl++) {
    for (int i = 0; i < 3; i++) {
      const double *q = sl[i].xyz;
      for (int j = 0; j < 4; j++) {
        double u = q[3 * j] + (j == 2 ? i : 0), v = q[3 * j + 1] + (j == 1 ? 2 * i : 0), h = q[3 * j + 2];
        double *o = p[pl][i] + 3 * j;
        if (pl == 0) o[0] = u, o[1] = v, o[2] = h;
        else if (pl == 1) o[0] = h, o[1] = u, o[2] = v;
        else o[0] = v, o[1] = h, o[2] = u;
      }
      pc[pl][i] = (rtw_contour){NULL, 4, p[pl][i], NULL, -1};
    }
    rtw_roi pr = {1, "Plane", NULL, 3, pc[pl], 0, 0};
    static const char *names[] = {"axial.dcm", "sagittal.dcm", "coronal.dcm"};
    b = write1(&pr, 1, &len);
    bad |= rtw_save(dir, names[pl], b, len);
    free(b);
  }
  return bad;
}

/* A long RTROIInterpretedType is kept to 63 bytes; a cut that ends on a
 * blank is trimmed as the value's end is, so that the type written back and
 * read again is the type read (make fuzz found one that was not).  Blanks at
 * every place around the cut. */
static void long_type(void) {
  double xyz[9] = {0, 0, 1, 1, 0, 1, 0, 1, 1};
  rtw_contour c = {NULL, 3, xyz, NULL, -1};
  for (int at = 55; at < 70; at++) {
    char ty[81];
    for (int i = 0; i < 80; i++) ty[i] = (char)('A' + i % 26);
    ty[80] = 0;
    ty[at] = ' ', ty[at + 2] = ' ';
    rtw_roi roi = {1, "R", ty, 1, &c, 0, 0};
    rtw_opts o = {1, 0, 0, 0, NULL, NULL, 0};
    size_t len, len2;
    unsigned char *b = rtw_write(&o, &roi, 1, &len);
    rtstruct s, t;
    char err[1024];
    if (rtstruct_parse(b, len, "long.dcm", &s, err, sizeof err) != 0) {
      CHECK(0, "long type, blank at %d: %s", at, err);
      free(b);
      continue;
    }
    size_t n = strlen(s.roi[0].type);
    CHECK(n > 0 && n <= 63 && s.roi[0].type[n - 1] != ' ' && strncmp(s.roi[0].type, ty, n) == 0,
          "long type, blank at %d: '%s'", at, s.roi[0].type);
    roi.type = s.roi[0].type;
    unsigned char *b2 = rtw_write(&o, &roi, 1, &len2);
    if (rtstruct_parse(b2, len2, "long2.dcm", &t, err, sizeof err) == 0) {
      CHECK(strcmp(t.roi[0].type, s.roi[0].type) == 0, "long type, blank at %d: '%s' read back as '%s'", at,
            s.roi[0].type, t.roi[0].type);
      rtstruct_free(&t);
    } else
      CHECK(0, "long type written back: %s", err);
    rtstruct_free(&s);
    free(b);
    free(b2);
  }
}

int main(int argc, char **argv) {
  if (argc == 3 && strcmp(argv[1], "--write") == 0) return write_fixtures(argv[2]);
  round_trip();
  long_type();
  samples();
  decimal_strings();
  refusals();
  oblique_overflow();
  warnings();
  many();
  planes();
  return check_done("test_rtstruct");
}
