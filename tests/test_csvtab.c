/* test_csvtab.c -- util/csvtab reads CSV as RFC 4180 writes it: plain and
 * quoted fields (commas and doubled quotes inside, empty ones), CRLF line
 * ends, blank lines; refuses, naming the line, a quote left open, text after
 * a closing quote, a row of another width and a line too long.  The
 * expected fields are written out here by hand. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tests/check.h"
#include "util/csvtab.h"

static char dir[64];

static const char *write_file(const char *name, const char *text) {
  static char path[128];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
  return path;
}

static void reads(void) {
  const char *p = write_file("ok.csv",
                             "claim,holds,detail\r\n"
                             "\"1 two, then one\",yes,\"T(2)/T(1) = 1.0006; \"\"quoted\"\"\"\n"
                             "\n"
                             "plain,,\"\"\n"
                             "\",\",\"\"\"\",x\n");
  csvtab t;
  char err[300];
  if (csvtab_read(p, &t, err, sizeof err) != 0) {
    CHECK(0, "ok.csv: %s", err);
    return;
  }
  static const char *want[4][3] = {{"claim", "holds", "detail"},
                                   {"1 two, then one", "yes", "T(2)/T(1) = 1.0006; \"quoted\""},
                                   {"plain", "", ""},
                                   {",", "\"", "x"}};
  CHECK(t.ncol == 3 && t.nrow == 3, "ok.csv: %d columns, %d rows", t.ncol, t.nrow);
  for (int r = 0; r < 4 && r <= t.nrow && t.ncol == 3; r++)
    for (int c = 0; c < 3; c++) {
      const char *got = r ? t.cell[r - 1][c] : t.head[c];
      CHECK(strcmp(got, want[r][c]) == 0, "ok.csv row %d field %d: [%s], want [%s]", r, c, got, want[r][c]);
    }
  CHECK(csvtab_col(&t, "detail") == 2 && csvtab_col(&t, "nope") == -1, "csvtab_col");
  csvtab_free(&t);
}

static void refuses(void) {
  static const struct {
    const char *text, *want;
  } cases[] = {
      {"a,b\n\"open,1\n", "bad.csv:2: a quoted field is not closed"},
      {"a,b\n\"x\"y,1\n", "bad.csv:2: text after a quoted field's closing quote"},
      {"a,b\n1,2\n1,2,3\n", "bad.csv:3: 3 fields, the header has 2"},
      {"", "bad.csv:1: empty, no header row"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    const char *p = write_file("bad.csv", cases[i].text);
    csvtab t;
    char err[300] = "";
    int rc = csvtab_read(p, &t, err, sizeof err);
    CHECK(rc == -1 && strstr(err, cases[i].want), "case %zu: rc %d, [%s], want [%s]", i, rc, err, cases[i].want);
  }
  /* A line longer than the reader's buffer. */
  size_t n = 9000;
  char *big = malloc(n + 16);
  if (!big) return;
  memcpy(big, "a\n", 2);
  memset(big + 2, 'x', n);
  memcpy(big + 2 + n, "\n", 2);
  const char *p = write_file("bad.csv", big);
  free(big);
  csvtab t;
  char err[300] = "";
  CHECK(csvtab_read(p, &t, err, sizeof err) == -1 && strstr(err, "bad.csv:2: a line longer than"), "long line: [%s]",
        err);
}

int main(void) {
  snprintf(dir, sizeof dir, "/tmp/tilesim-csvtab.XXXXXX");
  if (!mkdtemp(dir)) return 1;
  reads();
  refuses();
  if (check_rmtree(dir) != 0) return 1;
  return check_done("test_csvtab");
}
