/* test_svgchart.c -- the charts' text stays on the picture, and their series
 * can be told apart.
 *
 * The reference is the fonts a viewer draws the text in, read from their own
 * files, not the plotter's table: Helvetica and Helvetica-Bold as groff's
 * PostScript device describes them (font/devps/HR and HB, made from Adobe's
 * AFM files; Arial and Liberation Sans have the same widths), and DejaVu
 * Sans and DejaVu Sans Bold from their TrueType tables (cmap and hmtx), the
 * fonts most Linux viewers fall back on.  Each one found is used; none
 * found skips the checks and says so.
 *
 *  - charts the plotter draws (svgchart_write) from awkward inputs -- a
 *    title of 200 characters, legend labels of 70, 24 series, long axis
 *    labels, ticks of large and small numbers -- and every committed
 *    picture under plots/ (make bench's): every text's box, at its anchor,
 *    size, weight and rotation, lies inside the picture in every font;
 *  - the legend: every series has its own colour, marker and dash pattern;
 *    the y columns of one group (simulated and model) share colour and
 *    marker and differ in dash; a series that lies exactly on another gets
 *    a dash pattern of its own. */
#include <ctype.h>
#include <glob.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "prog/plot/svgchart.h"

/* ==== fonts: advance widths of characters 32..126, in 1/1000 em ========== */

typedef struct {
  char name[64];
  double w[2][95];   /* regular, bold */
  int have[2];
} font;

/* groff's font description: "charset" lines "NAME\tWIDTH,...\tTYPE\tCODE". */
static int groff_font(const char *path, double *w) {
  FILE *f = fopen(path, "r");
  if (!f) return -1;
  char line[512];
  int on = 0, n = 0;
  while (fgets(line, sizeof line, f)) {
    if (strncmp(line, "charset", 7) == 0) { on = 1; continue; }
    if (!on) continue;
    char name[64], metrics[128];
    int type, code;
    if (sscanf(line, "%63s %127s %d %d", name, metrics, &type, &code) != 4) continue;
    int width = atoi(metrics);
    /* ASCII ' ^ ` ~ are quotesingle, asciicircum, grave, asciitilde. */
    int c = strcmp(name, "aq") == 0 ? '\'' : strcmp(name, "ha") == 0 ? '^' : strcmp(name, "ga") == 0 ? '`'
          : strcmp(name, "ti") == 0 ? '~' : code;
    if (c == '\'' || c == '^' || c == '`' || c == '~') {
      if (c != code || w[c - 32] == 0) w[c - 32] = fmax(w[c - 32], width);
    } else if (c >= 32 && c <= 126) {
      w[c - 32] = width, n++;
    }
  }
  fclose(f);
  return n >= 90 ? 0 : -1;
}

static unsigned be16(const unsigned char *p) { return (unsigned)p[0] << 8 | p[1]; }
static uint32_t be32(const unsigned char *p) { return (uint32_t)be16(p) << 16 | be16(p + 2); }

/* A TrueType file: the (3,1) cmap of format 4, hmtx, head's units per em. */
static int ttf_font(const char *path, double *w) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  fseek(f, 0, SEEK_END);
  long size = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char *d = size > 12 ? malloc((size_t)size) : NULL;
  if (!d || fread(d, 1, (size_t)size, f) != (size_t)size) {
    fclose(f), free(d);
    return -1;
  }
  fclose(f);
  uint32_t head = 0, hhea = 0, hmtx = 0, cmap = 0;
  unsigned nt = be16(d + 4);
  for (unsigned i = 0; i < nt && 12 + 16 * i + 16 <= (unsigned long)size; i++) {
    const unsigned char *e = d + 12 + 16 * i;
    uint32_t off = be32(e + 8);
    if (memcmp(e, "head", 4) == 0) head = off;
    if (memcmp(e, "hhea", 4) == 0) hhea = off;
    if (memcmp(e, "hmtx", 4) == 0) hmtx = off;
    if (memcmp(e, "cmap", 4) == 0) cmap = off;
  }
  int ok = head && hhea && hmtx && cmap;
  uint32_t sub = 0;
  if (ok) {
    unsigned upem = be16(d + head + 18), nh = be16(d + hhea + 34), nsub = be16(d + cmap + 2);
    for (unsigned i = 0; i < nsub; i++) {
      const unsigned char *e = d + cmap + 4 + 8 * i;
      if (be16(e) == 3 && be16(e + 2) == 1) sub = cmap + be32(e + 4);
    }
    ok = sub && be16(d + sub) == 4 && upem > 0 && nh > 0;
    if (ok) {
      unsigned seg = be16(d + sub + 6) / 2;
      const unsigned char *ends = d + sub + 14, *starts = ends + 2 * seg + 2, *delta = starts + 2 * seg,
                          *roff = delta + 2 * seg;
      for (int c = 32; c <= 126; c++) {
        unsigned g = 0;
        for (unsigned i = 0; i < seg; i++) {
          if (c > (int)be16(ends + 2 * i) || c < (int)be16(starts + 2 * i)) continue;
          unsigned ro = be16(roff + 2 * i), del = be16(delta + 2 * i);
          if (ro == 0) g = (c + del) & 0xFFFF;
          else {
            unsigned gg = be16(roff + 2 * i + ro + 2 * (c - be16(starts + 2 * i)));
            g = gg ? (gg + del) & 0xFFFF : 0;
          }
          break;
        }
        unsigned k = g < nh ? g : nh - 1;
        w[c - 32] = be16(d + hmtx + 4 * k) * 1000.0 / upem;
      }
    }
  }
  free(d);
  return ok ? 0 : -1;
}

static int nfonts;
static font fonts[4];

static void load_fonts(void) {
  glob_t g;
  font *h = &fonts[nfonts];
  snprintf(h->name, sizeof h->name, "Helvetica (groff)");
  if (glob("/usr/share/groff/*/font/devps/HR", 0, NULL, &g) == 0 && g.gl_pathc > 0) {
    char bold[4096];
    snprintf(bold, sizeof bold, "%s", g.gl_pathv[0]);
    bold[strlen(bold) - 1] = 'B';
    h->have[0] = groff_font(g.gl_pathv[0], h->w[0]) == 0;
    h->have[1] = groff_font(bold, h->w[1]) == 0;
    globfree(&g);
  }
  if (h->have[0] && h->have[1]) nfonts++;
  font *v = &fonts[nfonts];
  memset(v, 0, sizeof *v);
  snprintf(v->name, sizeof v->name, "DejaVu Sans");
  v->have[0] = ttf_font("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", v->w[0]) == 0;
  v->have[1] = ttf_font("/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf", v->w[1]) == 0;
  if (v->have[0] && v->have[1]) nfonts++;
}

static double width(const font *fo, const char *s, double px, int bold) {
  double em = 0;
  for (const unsigned char *p = (const unsigned char *)s; *p; p++)
    em += *p >= 32 && *p <= 126 ? fo->w[bold][*p - 32] / 1000.0 : (*p & 0xC0) != 0x80 ? 1.0 : 0.0;
  return em * px;
}

/* ==== an SVG's texts ======================================================== */

/* The value of attribute a in the tag at t (up to '>'), into buf; 0 if none. */
static int attr(const char *t, const char *a, char *buf, size_t len) {
  const char *end = strchr(t, '>');
  char key[64];
  snprintf(key, sizeof key, " %s=\"", a);
  const char *p = strstr(t, key);
  if (!p || (end && p > end)) return 0;
  p += strlen(key);
  const char *q = strchr(p, '"');
  if (!q) return 0;
  snprintf(buf, len, "%.*s", (int)(q - p), p);
  return 1;
}

static double num(const char *t, const char *a, double dflt) {
  char b[128];
  return attr(t, a, b, sizeof b) ? atof(b) : dflt;
}

/* Every <text> of svg inside the picture in every font: the failures are
 * reported naming what (the picture) and the text. */
static void texts_inside(const char *what, const char *svg) {
  const char *s = strstr(svg, "<svg ");
  CHECK(s != NULL, "%s: no <svg> element", what);
  if (!s) return;
  double W = num(s, "width", 0), H = num(s, "height", 0), size0 = num(s, "font-size", 16);
  int ntext = 0, bad = 0;
  for (const char *t = strstr(s, "<text"); t; t = strstr(t + 5, "<text")) {
    const char *gt = strchr(t, '>'), *close = gt ? strstr(gt, "</text>") : NULL;
    if (!close) break;
    char text[2048], anchor[32] = "start", weight[32] = "", tr[128] = "";
    size_t n = 0;
    for (const char *p = gt + 1; p < close && n < sizeof text - 1; p++) {   /* unescaped */
      if (*p == '&') {
        const char *semi = strchr(p, ';');
        text[n++] = strncmp(p, "&lt;", 4) == 0 ? '<' : strncmp(p, "&gt;", 4) == 0 ? '>' : '&';
        p = semi ? semi : p;
      } else {
        text[n++] = *p;
      }
    }
    text[n] = 0;
    attr(t, "text-anchor", anchor, sizeof anchor);
    attr(t, "font-weight", weight, sizeof weight);
    double px = num(t, "font-size", size0), x = num(t, "x", 0), y = num(t, "y", 0);
    int bold = strcmp(weight, "bold") == 0, rot = 0;
    if (attr(t, "transform", tr, sizeof tr)) {   /* translate(X Y) rotate(-90) */
      double tx, ty;
      if (sscanf(tr, "translate(%lf %lf) rotate(-90)", &tx, &ty) == 2) x = tx, y = ty, rot = 1;
    }
    ntext++;
    for (int k = 0; k < nfonts; k++) {
      double w = width(&fonts[k], text, px, bold);
      double a = strcmp(anchor, "middle") == 0 ? w / 2 : strcmp(anchor, "end") == 0 ? w : 0;
      double lo, hi, asc, desc;   /* along the text; across it, the ascent and descent */
      if (!rot) lo = x - a, hi = x - a + w, asc = y - 0.95 * px, desc = y + 0.25 * px;
      else lo = y - w + a, hi = y + a, asc = x - 0.95 * px, desc = x + 0.25 * px;   /* up the page */
      double along = rot ? H : W, across = rot ? W : H;
      if (lo < -0.5 || hi > along + 0.5 || asc < -0.5 || desc > across + 0.5) {
        if (bad++ < 5)
          CHECK(0, "%s: '%s' (%.0f px%s%s) spans %.1f to %.1f of %.0f in %s", what, text, px, bold ? " bold" : "",
                rot ? ", upright" : "", lo, hi, along, fonts[k].name);
      }
    }
  }
  CHECK(ntext > 0, "%s: no text", what);
  CHECK(bad == 0, "%s: %d texts leave the picture", what, bad);
}

/* ==== the legend ============================================================ */

typedef struct {
  char label[256], colour[16], dash[32], mark[16];
} entry;

/* The legend's entries: a sample <line stroke-width="2"> (its colour and
 * dash), the marker drawn on it, the label. */
static int legend(const char *svg, entry *e, int max) {
  int n = 0;
  char col[16] = "", dsh[32] = "", mark[16] = "";
  int state = 0;   /* 1: after a sample line, 2: after its marker */
  for (const char *t = strchr(svg, '<'); t && n < max; t = strchr(t + 1, '<')) {
    if (strncmp(t, "<line ", 6) == 0 && strstr(t, "stroke-width=\"2\"") && strstr(t, "stroke-width=\"2\"") < strchr(t, '>')) {
      attr(t, "stroke", col, sizeof col);
      if (!attr(t, "stroke-dasharray", dsh, sizeof dsh)) dsh[0] = 0;
      state = 1;
    } else if (state == 1 && strncmp(t, "<circle", 7) == 0) {
      snprintf(mark, sizeof mark, "circle"), state = 2;
    } else if (state == 1 && strncmp(t, "<rect", 5) == 0) {
      snprintf(mark, sizeof mark, "square"), state = 2;
    } else if (state == 1 && strncmp(t, "<polygon", 8) == 0) {
      char pts[256];
      attr(t, "points", pts, sizeof pts);
      double x1, y1, x2, y2;
      int k = 0;
      for (const char *p = pts; *p; p++) k += *p == ',';
      sscanf(pts, "%lf,%lf %lf,%lf", &x1, &y1, &x2, &y2);
      snprintf(mark, sizeof mark, "%s", k == 4 ? "diamond" : y1 < y2 ? "triangle" : "down");
      state = 2;
    } else if (state == 1 && strncmp(t, "<path", 5) == 0) {
      char d[256];
      attr(t, "d", d, sizeof d);
      double a, b, c, e2;
      sscanf(d, "M%lf %lfL%lf %lf", &a, &b, &c, &e2);
      snprintf(mark, sizeof mark, "%s", b == e2 ? "plus" : "cross");
      state = 2;
    } else if (state == 2 && strncmp(t, "<text", 5) == 0) {
      const char *gt = strchr(t, '>'), *close = strstr(t, "</text>");
      snprintf(e[n].label, sizeof e[n].label, "%.*s", (int)(close - gt - 1), gt + 1);
      snprintf(e[n].colour, sizeof e[n].colour, "%s", col);
      snprintf(e[n].dash, sizeof e[n].dash, "%s", dsh);
      snprintf(e[n].mark, sizeof e[n].mark, "%s", mark);
      n++;
      state = 0;
    } else if (strncmp(t, "<polyline", 9) == 0 || strncmp(t, "<text", 5) == 0) {
      state = 0;
    }
  }
  return n;
}

static char *slurp(const char *path) {
  FILE *f = fopen(path, "r");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = malloc((size_t)n + 1);
  size_t got = fread(b, 1, (size_t)n, f);
  b[got] = 0;
  fclose(f);
  return b;
}

static char *draw(const svgchart_opts *o, const svgchart_series *s, int ns) {
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  svgchart_write(f, o, s, ns);
  fclose(f);
  return buf;
}

/* ==== the charts ============================================================ */

static double xs[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};

static void awkward(void) {
  enum { NS = 24 };
  static double ys[NS][16];
  static char labels[NS][96];
  svgchart_series s[NS];
  for (int i = 0; i < NS; i++) {
    for (int k = 0; k < 16; k++) ys[i][k] = 1 + i * 0.37 + k * (0.1 + 0.05 * (i % 5));
    snprintf(labels[i], sizeof labels[i], "variant=dynamic+block%d, 16-core host, 1000 points, WWWMMM %d", 8 << (i % 4),
             i);
    s[i] = (svgchart_series){labels[i], 16, xs, ys[i], i % 2, i / 2};
  }
  char title[256];
  memset(title, 0, sizeof title);
  for (int k = 0; k < 20; k++) strcat(title, k % 3 ? "Weighted " : "speedup, ");
  strcat(title, "WWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWWW");   /* a word wider than the picture */
  svgchart_opts o = {title, "processors on the simulated machine, from one to sixteen, each a run of its own",
                     "speedup T(1)/T(P) of the whole run, simulated seconds against simulated seconds", 1, 1};
  char *svg = draw(&o, s, NS);
  texts_inside("24 series, long labels and title", svg);
  entry e[NS];
  int n = legend(svg, e, NS);
  CHECK(n == NS, "24 series: %d legend entries", n);
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++) {
      int same = strcmp(e[i].colour, e[j].colour) == 0 && strcmp(e[i].mark, e[j].mark) == 0 &&
                 strcmp(e[i].dash, e[j].dash) == 0;
      CHECK(!same, "legend entries %d and %d look alike (%s %s '%s')", i, j, e[i].colour, e[i].mark, e[i].dash);
      if (i / 2 == j / 2)   /* one group: simulated and model */
        CHECK(strcmp(e[i].colour, e[j].colour) == 0 && strcmp(e[i].mark, e[j].mark) == 0 &&
                  strcmp(e[i].dash, e[j].dash) != 0,
              "a group's two columns: %s %s '%s' and %s %s '%s'", e[i].colour, e[i].mark, e[i].dash, e[j].colour,
              e[j].mark, e[j].dash);
    }
  free(svg);

  /* Large and small numbers on the axes. */
  double big[16], tiny[16];
  for (int k = 0; k < 16; k++) big[k] = 1e7 * (k + 1) + 123456, tiny[k] = -3e-6 * k;
  svgchart_series s2[2] = {{"big", 16, xs, big, 0, 0}, {"tiny", 16, xs, tiny, 0, 1}};
  svgchart_opts o2 = {"numbers", "x", "y", 0, 1};
  svg = draw(&o2, s2, 1);
  texts_inside("ticks of 1e8", svg);
  free(svg);
  svg = draw(&o2, s2 + 1, 1);
  texts_inside("ticks of -5e-5", svg);
  free(svg);

  /* Series that lie on one another: each its own dash pattern. */
  double same[16];
  for (int k = 0; k < 16; k++) same[k] = 2 + k;
  svgchart_series s3[4] = {{"line: linear", 16, xs, same, 0, 0},
                           {"mesh: snake", 16, xs, same, 0, 1},
                           {"hypercube: Gray", 16, xs, same, 0, 2},
                           {"apart", 16, xs, big, 0, 3}};
  svg = draw(&o2, s3, 4);
  n = legend(svg, e, 4);
  CHECK(n == 4 && strcmp(e[0].dash, e[1].dash) != 0 && strcmp(e[0].dash, e[2].dash) != 0 &&
            strcmp(e[1].dash, e[2].dash) != 0 && e[3].dash[0] == 0,
        "series on one another: dashes '%s' '%s' '%s', apart '%s'", e[0].dash, e[1].dash, e[2].dash, e[3].dash);
  free(svg);
}

/* What make bench drew: every picture under plots/. */
static void committed(void) {
  glob_t g;
  int n = 0;
  if (glob("plots/*.svg", 0, NULL, &g) == 0) {
    for (size_t i = 0; i < g.gl_pathc; i++) {
      char *svg = slurp(g.gl_pathv[i]);
      if (!svg) continue;
      texts_inside(g.gl_pathv[i], svg);
      n++;
      if (strstr(g.gl_pathv[i], "section8_topology") || strstr(g.gl_pathv[i], "variants")) {
        entry e[32];
        int k = legend(svg, e, 32);
        CHECK(k >= 7, "%s: %d legend entries", g.gl_pathv[i], k);
        for (int a = 0; a < k; a++)
          for (int b = a + 1; b < k; b++)
            CHECK(strcmp(e[a].colour, e[b].colour) || strcmp(e[a].mark, e[b].mark) || strcmp(e[a].dash, e[b].dash),
                  "%s: '%s' and '%s' look alike", g.gl_pathv[i], e[a].label, e[b].label);
      }
      free(svg);
    }
    globfree(&g);
  }
  CHECK(n >= 10, "plots/*.svg: %d pictures found (run from the source tree)", n);
}

int main(void) {
  load_fonts();
  if (nfonts == 0) {
    printf("test_svgchart: skipped: no font metrics to measure the text with (groff's font/devps/HR: apt-get "
           "install groff-base; DejaVu Sans: fonts-dejavu-core)\n");
    return check_done("test_svgchart");
  }
  /* The references read as they should: a few widths everyone agrees on. */
  for (int k = 0; k < nfonts; k++)
    CHECK(fonts[k].w[0]['0' - 32] > 500 && fonts[k].w[0]['i' - 32] < fonts[k].w[0]['m' - 32] &&
              fonts[k].w[1]['a' - 32] >= fonts[k].w[0]['a' - 32],
          "%s: widths of 0 %g, i %g, m %g", fonts[k].name, fonts[k].w[0]['0' - 32], fonts[k].w[0]['i' - 32],
          fonts[k].w[0]['m' - 32]);
  awkward();
  committed();
  return check_done("test_svgchart");
}
