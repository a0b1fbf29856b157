/* test_args.c -- util/args against expectations written by hand (tables of
 * values with what each must give), and against a second, independent
 * reading of whole numbers (digit by digit, with its own overflow check)
 * over every string of a small alphabet up to five characters. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "util/args.h"
#include "tests/check.h"

static char err[400];

/* ---- whole numbers ---------------------------------------------------- */

/* The reference: "-"? digits, read digit by digit with an exact overflow
 * test; 1 and *v if it is a whole number in [lo, hi]. */
static int ref_long(const char *s, long lo, long hi, long *v) {
  int neg = 0;
  if (*s == '-') neg = 1, s++;
  if (!*s) return 0;
  unsigned long mag = 0, limit = neg ? (unsigned long)LONG_MAX + 1 : (unsigned long)LONG_MAX;
  for (; *s; s++) {
    if (*s < '0' || *s > '9') return 0;
    unsigned d = (unsigned)(*s - '0');
    if (mag > (limit - d) / 10) return 0;
    mag = mag * 10 + d;
  }
  long x = neg ? (mag == (unsigned long)LONG_MAX + 1 ? LONG_MIN : -(long)mag) : (long)mag;
  if (x < lo || x > hi) return 0;
  *v = x;
  return 1;
}

static void whole_sweep(void) {
  static const char alpha[] = "0159- x.+e";
  int n = (int)strlen(alpha), bad = 0, tried = 0;
  char s[8];
  for (int len = 0; len <= 5; len++) {
    long total = 1;
    for (int i = 0; i < len; i++) total *= n;
    for (long k = 0; k < total; k++) {
      long x = k;
      for (int i = 0; i < len; i++) s[i] = alpha[x % n], x /= n;
      s[len] = 0;
      long got = -7, want = -7;
      int ok = args_long("--n", s, -500, 9999, &got, err, sizeof err) == 0;
      int rok = ref_long(s, -500, 9999, &want);
      tried++;
      if (ok != rok || (ok && got != want)) {
        if (bad++ < 5) CHECK(0, "args_long('%s'): %d %ld, the reference %d %ld", s, ok, got, rok, want);
      }
      if (!ok && !strstr(err, "--n takes a whole number from -500 to 9999 (")) bad++;
      unsigned long long u = 0;
      int uok = args_u64("--u", s, 0, 9999, &u, err, sizeof err) == 0;
      int urok = s[0] != '-' && ref_long(s, 0, 9999, &want);
      if (uok != urok || (uok && (long)u != want)) {
        if (bad++ < 5) CHECK(0, "args_u64('%s'): %d %llu, the reference %d %ld", s, uok, u, urok, want);
      }
    }
  }
  CHECK(bad == 0, "%d of %d strings read differently from the reference", bad, tried);
}

static void whole_table(void) {
  long v;
  unsigned long long u;
  CHECK(args_long("--procs", "16", 1, 4096, &v, err, sizeof err) == 0 && v == 16, "16");
  CHECK(args_long("--procs", "4096", 1, 4096, &v, err, sizeof err) == 0 && v == 4096, "4096");
  CHECK(args_long("--procs", "007", 1, 4096, &v, err, sizeof err) == 0 && v == 7, "007");
  CHECK(args_long("--pair", "-3", -5, 5, &v, err, sizeof err) == 0 && v == -3, "-3");
  const char *badl[] = {"", " 3", "3 ", "0x10", "1e3", "1.0", "+3", "4097", "0", "-1", "abc",
                        "99999999999999999999", "3\n", "1..2", "--", "-"};
  for (size_t i = 0; i < sizeof badl / sizeof *badl; i++)
    CHECK(args_long("--procs", badl[i], 1, 4096, &v, err, sizeof err) == -1, "'%s' accepted", badl[i]);
  args_long("--procs", "0", 1, 4096, &v, err, sizeof err);
  CHECK(strcmp(err, "--procs takes a whole number from 1 to 4096 (0)") == 0, "message: %s", err);
  args_long("--procs", "", 1, 4096, &v, err, sizeof err);
  CHECK(strcmp(err, "--procs takes a whole number from 1 to 4096 ('')") == 0, "message: %s", err);
  args_long("--procs", " 3", 1, 4096, &v, err, sizeof err);
  CHECK(strcmp(err, "--procs takes a whole number from 1 to 4096 (' 3')") == 0, "message: %s", err);
  args_long("--procs", "3\n4", 1, 4096, &v, err, sizeof err);
  CHECK(strcmp(err, "--procs takes a whole number from 1 to 4096 (3\\x0a4)") == 0, "message: %s", err);

  CHECK(args_u64("--seed", "18446744073709551615", 0, ULLONG_MAX, &u, err, sizeof err) == 0 &&
            u == ULLONG_MAX, "2^64-1");
  CHECK(args_u64("--seed", "0", 0, ULLONG_MAX, &u, err, sizeof err) == 0 && u == 0, "0");
  const char *badu[] = {"-1", "18446744073709551616", "abc", "", "1 ", "0x1", "+1", "-0"};
  for (size_t i = 0; i < sizeof badu / sizeof *badu; i++)
    CHECK(args_u64("--seed", badu[i], 0, ULLONG_MAX, &u, err, sizeof err) == -1, "'%s' accepted", badu[i]);
  args_u64("--seed", "abc", 0, ULLONG_MAX, &u, err, sizeof err);
  CHECK(strcmp(err, "--seed takes a whole number from 0 to 18446744073709551615 (abc)") == 0, "message: %s", err);
  args_u64("--seed", "-1", 0, ULLONG_MAX, &u, err, sizeof err);
  CHECK(strcmp(err, "--seed takes a whole number from 0 to 18446744073709551615 (-1)") == 0, "message: %s", err);
  /* A long value is cut short, so the message stays one short line. */
  char longval[300];
  memset(longval, '7', sizeof longval - 1);
  longval[sizeof longval - 1] = 0;
  args_u64("--seed", longval, 0, ULLONG_MAX, &u, err, sizeof err);
  CHECK(strlen(err) < 160 && strstr(err, "...)"), "long value: %s", err);
}

/* ---- real numbers ------------------------------------------------------- */

static void real_table(void) {
  double v;
  static const struct { const char *s; double want; } good[] = {
      {"0", 0},          {"3", 3},        {"1e9", 1e9},      {"0.5", 0.5},   {".5", 0.5},
      {"5.", 5},         {"2.5E-3", 2.5e-3}, {"275e-6", 275e-6}, {"1e+2", 100}, {"0e-400", 0},
      {"0.000", 0},      {"1000000000", 1e9}, {"2.2250738585072014e-308", DBL_MIN}};
  for (size_t i = 0; i < sizeof good / sizeof *good; i++)
    CHECK(args_double("--m", good[i].s, 0, 1e9, &v, err, sizeof err) == 0 && v == good[i].want,
          "'%s': %s", good[i].s, err);
  CHECK(args_double("--m", "-0", 0, 1e9, &v, err, sizeof err) == 0 && v == 0 && !signbit(v), "-0 gives +0");
  CHECK(args_double("--x", "-2.5", -3, 3, &v, err, sizeof err) == 0 && v == -2.5, "-2.5");
  const char *bad[] = {"",      " 3",   "3 ",     "0x10", "0X1p3", "1e-400", "1e-310", "-1e-400",
                       "1.5e9", "inf",  "-inf",   "nan",  "infinity", "1e",  "e5",     ".",
                       "-",     "+3",   "1..2",   "1,2",  "1e999", "-1",    "3s",     "1e5.5",
                       "--1",   "1ee5", "1e+-5",  "\t1"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
    CHECK(args_double("--m", bad[i], 0, 1e9, &v, err, sizeof err) == -1, "'%s' accepted (%g)", bad[i], v);
  args_real("--m", "1.5e9", "seconds", 0, 1e9, &v, err, sizeof err);
  CHECK(strcmp(err, "--m takes seconds from 0 to 1e9 (1.5e9)") == 0, "message: %s", err);
  args_real("--m", "1e-400", "seconds", 0, 1e9, &v, err, sizeof err);
  CHECK(strcmp(err, "--m takes seconds from 0 to 1e9 (1e-400 is too close to 0 to represent)") == 0,
        "message: %s", err);
  args_double("--c", "0x10", 0, 1e9, &v, err, sizeof err);
  CHECK(strcmp(err, "--c takes a number from 0 to 1e9 (0x10)") == 0, "message: %s", err);
  /* Every double written with 17 digits reads back exactly. */
  int bad_rt = 0;
  double x = 1.2345678901234567e-300;
  for (int i = 0; i < 2000; i++, x *= 1.7320508075688772) {
    if (x > 1e300) x = x * 1e-290 + 0.1;
    char buf[64];
    snprintf(buf, sizeof buf, "%.17g", x);
    if (args_double("--x", buf, 0, 1e308, &v, err, sizeof err) != 0 || v != x) bad_rt++;
  }
  CHECK(bad_rt == 0, "%d doubles did not read back exactly", bad_rt);
}

static void fmt_table(void) {
  static const struct { double v; const char *s; } t[] = {
      {1e9, "1e9"}, {0.000275, "0.000275"}, {2.5e-5, "2.5e-5"}, {50e-6, "5e-5"}, {4096, "4096"},
      {0, "0"}, {1.5, "1.5"}, {1e300, "1e300"}, {0.1, "0.1"}, {-3, "-3"}, {1e-300, "1e-300"},
      {10, "10"}, {100000, "100000"}, {1e6, "1e6"}, {1.5e9, "1.5e9"}, {-0.5, "-0.5"}};
  char buf[40];
  for (size_t i = 0; i < sizeof t / sizeof *t; i++) {
    args_fmt_double(t[i].v, buf, sizeof buf);
    CHECK(strcmp(buf, t[i].s) == 0, "args_fmt_double(%.17g): %s, expected %s", t[i].v, buf, t[i].s);
  }
}

/* ---- lists -------------------------------------------------------------------- */

static void list_table(void) {
  args_list l;
  CHECK(args_list_parse("--procs", "1..16", 1, 1, 4096, &l, err, sizeof err) == 0 && l.n == 16 &&
            l.v[0] == 1 && l.v[15] == 16, "1..16");
  CHECK(args_list_parse("--points", "100,200,300", 1, 3, 1e5, &l, err, sizeof err) == 0 && l.n == 3 &&
            l.v[2] == 300, "100,200,300");
  CHECK(args_list_parse("--procs", "1,3..5,2", 1, 1, 4096, &l, err, sizeof err) == 0 && l.n == 5 &&
            l.v[1] == 3 && l.v[3] == 5 && l.v[4] == 2, "1,3..5,2");
  CHECK(args_list_parse("--procs", "7..7", 1, 1, 4096, &l, err, sizeof err) == 0 && l.n == 1 && l.v[0] == 7, "7..7");
  CHECK(args_list_parse("--m", "1e-4,2e-4", 0, 0, 1e9, &l, err, sizeof err) == 0 && l.n == 2 &&
            l.v[0] == 1e-4 && l.v[1] == 2e-4, "1e-4,2e-4");
  CHECK(args_list_parse("--procs", "1..256", 1, 1, 4096, &l, err, sizeof err) == 0 && l.n == 256, "1..256");
  const char *bad[] = {"",      "5..1",  "1,,2", "1,",    ",1",     "1..",    "..3",  "1...3",
                       "1..2..3", "0..3", "1..4097", "x",  "1 ,2",   " 1",     "1..257", "1,1..256",
                       "1.5",   "0x2",   "1e2",  "-1",    "1,2,",   "9999999999999999999999"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
    CHECK(args_list_parse("--procs", bad[i], 1, 1, 4096, &l, err, sizeof err) == -1, "'%s' accepted", bad[i]);
  args_list_parse("--procs", "5..1", 1, 1, 4096, &l, err, sizeof err);
  CHECK(strcmp(err, "--procs takes whole numbers from 1 to 4096, listed and in ranges like 1,2,4 or "
                    "1..16, at most 256 in all (5..1: 5..1 is an empty range)") == 0, "message: %s", err);
  args_list_parse("--procs", "1,,2", 1, 1, 4096, &l, err, sizeof err);
  CHECK(strstr(err, "(1,,2: an empty item)") != NULL, "message: %s", err);
  args_list_parse("--procs", "1..300", 1, 1, 4096, &l, err, sizeof err);
  CHECK(strstr(err, "(1..300: more than 256 numbers)") != NULL, "message: %s", err);
  const char *badr[] = {"1..2", "1e-400", "abc", "", "1,,2", "-1", "2e9", "0x1", "nan"};
  for (size_t i = 0; i < sizeof badr / sizeof *badr; i++)
    CHECK(args_list_parse("--m", badr[i], 0, 0, 1e9, &l, err, sizeof err) == -1, "'%s' accepted", badr[i]);
  args_list_parse("--m", "1e-400", 0, 0, 1e9, &l, err, sizeof err);
  CHECK(strcmp(err, "--m takes numbers from 0 to 1e9, comma-separated, at most 256 (1e-400: 1e-400 is "
                    "too close to 0 to represent)") == 0, "message: %s", err);
  /* A smaller maximum. */
  CHECK(args_list_max("--points", "1,2,3", 1, 1, 10, 3, &l, err, sizeof err) == 0 && l.n == 3, "max 3");
  CHECK(args_list_max("--points", "1,2,3,4", 1, 1, 10, 3, &l, err, sizeof err) == -1 &&
            strstr(err, "at most 3 in all (1,2,3,4: more than 3 numbers)"), "max 3: %s", err);
  CHECK(args_list_max("--points", "1..4", 1, 1, 10, 3, &l, err, sizeof err) == -1, "1..4 with max 3");
}

/* ---- words, bytes, names -------------------------------------------------------------- */

static void word_table(void) {
  CHECK(args_word("--backend", "sim", "sim|threads", err, sizeof err) == 0, "sim");
  CHECK(args_word("--backend", "threads", "sim|threads", err, sizeof err) == 1, "threads");
  const char *bad[] = {"", "Sim", "s", "sim ", "simthreads", "sim|threads", "threads,sim", "|"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
    CHECK(args_word("--backend", bad[i], "sim|threads", err, sizeof err) == -1, "'%s' accepted", bad[i]);
  args_word("--backend", "mpi", "sim|threads", err, sizeof err);
  CHECK(strcmp(err, "--backend takes sim or threads (mpi)") == 0, "message: %s", err);
  args_word("--net", "token", "ideal|bus|loggp", err, sizeof err);
  CHECK(strcmp(err, "--net takes ideal, bus or loggp (token)") == 0, "message: %s", err);
  int idx[4];
  CHECK(args_word_list("--alloc", "half,size", "half|size", idx, 2, err, sizeof err) == 2 && idx[0] == 0 &&
            idx[1] == 1, "half,size");
  CHECK(args_word_list("--alloc", "size", "half|size", idx, 2, err, sizeof err) == 1 && idx[0] == 1, "size");
  const char *badl[] = {"", "half,", ",size", "half,,size", "half,size,half", "third", "half size"};
  for (size_t i = 0; i < sizeof badl / sizeof *badl; i++)
    CHECK(args_word_list("--alloc", badl[i], "half|size", idx, 2, err, sizeof err) == -1, "'%s' accepted", badl[i]);
  CHECK(strcmp(err, "--alloc takes half or size, or up to 2 of them comma-separated ('half size')") == 0,
        "message: %s", err);
}

static void bytes_table(void) {
  static const struct { const char *s; unsigned long long v; } good[] = {
      {"0", 0}, {"1000", 1000}, {"1k", 1000}, {"1K", 1000}, {"64k", 64000}, {"500M", 500000000},
      {"1.5G", 1500000000}, {"20T", 20000000000000ULL}, {"none", ULLONG_MAX},
      {"18446744073709551615", ULLONG_MAX}, {"0.001M", 1000}};
  unsigned long long v;
  for (size_t i = 0; i < sizeof good / sizeof *good; i++)
    CHECK(args_bytes("--trace-limit", good[i].s, &v, err, sizeof err) == 0 && v == good[i].v, "'%s': %llu %s",
          good[i].s, v, err);
  const char *bad[] = {"", "-1", "1.5", "0.0001k", "1X", "k", "18446744073709551616", "1e3", " 1k",
                       "1k ", "0x10", "None", "-1k", "1GB", "99999999T"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
    CHECK(args_bytes("--trace-limit", bad[i], &v, err, sizeof err) == -1, "'%s' accepted (%llu)", bad[i], v);
  CHECK(strstr(err, "--trace-limit takes bytes from 0 to 18446744073709551615") == err, "message: %s", err);
}

static void name_table(void) {
  CHECK(args_name("-o", "a.csv", "a file name", 0, err, sizeof err) == 0, "a.csv");
  CHECK(args_name("--input", "-", "a contour stack", 1, err, sizeof err) == 0, "- with dash_ok");
  CHECK(args_name("-o", "-", "a file name", 0, err, sizeof err) == -1, "- without dash_ok");
  CHECK(args_name("-o", "", "a file name", 0, err, sizeof err) == -1 &&
            strcmp(err, "-o takes a file name ('')") == 0, "empty: %s", err);
  CHECK(args_name("-o", "--caps", "a file name", 0, err, sizeof err) == -1 && strstr(err, "not an option"),
        "--caps: %s", err);
}

int main(void) {
  whole_sweep();
  whole_table();
  real_table();
  fmt_table();
  list_table();
  word_table();
  bytes_table();
  name_table();
  return check_done("test_args");
}
