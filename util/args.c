/* args.c -- strict option values: the syntax checked by hand, then strtoll,
 * strtoull or strtod on a string already known to be well formed, with
 * their overflow and underflow reports honoured. */
#include "util/args.h"

#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/progname.h"

/* ---- helpers --------------------------------------------------------- */

static int dig(char c) { return c >= '0' && c <= '9'; }

/* The value as the message shows it: quoted if empty or with blanks,
 * control bytes and non-ASCII escaped as \xNN, cut after 60 bytes. */
int args_usage(const char *prog, const char *usage, const char *why, const char *arg) {
  char shown[200];
  fprintf(stderr, "%s: ", progname_as(prog));
  progname_fputs(why, stderr);
  if (arg) {
    args_show(arg, shown, sizeof shown);
    fprintf(stderr, " (%s)", shown);
  }
  fputc('\n', stderr);
  progname_fputs(usage, stderr);
  return 2;
}

void args_show(const char *val, char *buf, size_t len) {
  size_t k = 0, n = strlen(val);
  int quote = n == 0 || strpbrk(val, " \t") != NULL;
  if (len < 8) {
    if (len) buf[0] = 0;
    return;
  }
  if (quote) buf[k++] = '\'';
  for (size_t i = 0; i < n && k + 6 < len; i++) {
    unsigned char c = (unsigned char)val[i];
    if (i == 60) {
      k += (size_t)snprintf(buf + k, len - k, "...");
      break;
    }
    if (c < 0x20 || c >= 0x7f) k += (size_t)snprintf(buf + k, len - k, "\\x%02x", c);
    else buf[k++] = (char)c;
  }
  if (quote && k + 1 < len) buf[k++] = '\'';
  buf[k] = 0;
}

void args_fmt_double(double v, char *buf, size_t len) {
  char tmp[40];
  if (v == floor(v) && fabs(v) < 1e6) {   /* whole numbers of up to 6 digits as they are */
    snprintf(buf, len, "%.0f", v);
    return;
  }
  for (int p = 1; p <= 17; p++) {
    snprintf(tmp, sizeof tmp, "%.*g", p, v);
    if (strtod(tmp, NULL) == v) break;
  }
  /* "1e+09" -> "1e9", "2.5e-05" -> "2.5e-5" */
  char out[40];
  size_t k = 0;
  for (const char *p = tmp; *p && k + 1 < sizeof out; p++) {
    out[k++] = *p;
    if (*p == 'e') {
      p++;
      if (*p == '-') out[k++] = *p++;
      else if (*p == '+') p++;
      while (*p == '0' && dig(p[1])) p++;
      while (*p && k + 1 < sizeof out) out[k++] = *p++;
      break;
    }
  }
  out[k] = 0;
  snprintf(buf, len, "%s", out);
}

char *args_g(char *buf, double v) {
  args_fmt_double(v, buf, ARGS_G_LEN);
  return buf;
}

/* [-]digits */
static int whole_syntax(const char *s, int neg_ok) {
  if (*s == '-' && neg_ok) s++;
  if (!dig(*s)) return 0;
  while (dig(*s)) s++;
  return *s == 0;
}

/* [-]digits[.digits][(e|E)[+-]digits], or [-].digits[...]; the number of
 * mantissa digits that are not 0 in *nonzero. */
static int real_syntax(const char *s, int *nonzero) {
  int digits = 0;
  *nonzero = 0;
  if (*s == '-') s++;
  for (; dig(*s); s++) digits++, *nonzero += *s != '0';
  if (*s == '.')
    for (s++; dig(*s); s++) digits++, *nonzero += *s != '0';
  if (!digits) return 0;
  if (*s == 'e' || *s == 'E') {
    s++;
    if (*s == '+' || *s == '-') s++;
    if (!dig(*s)) return 0;
    while (dig(*s)) s++;
  }
  return *s == 0;
}

/* Read a real number: 0, or 1 for bad syntax, 2 for overflow, 3 for
 * underflow (a nonzero value too close to 0 for a normal double). */
static int read_real(const char *s, double *out) {
  int nonzero;
  if (!real_syntax(s, &nonzero)) return 1;
  errno = 0;
  double v = strtod(s, NULL);
  if (isinf(v)) return 2;
  if (nonzero && (v == 0 || fabs(v) < DBL_MIN)) return 3;
  if (errno == ERANGE && v == 0) return 3;
  *out = v == 0 ? 0.0 : v;   /* no -0 */
  return 0;
}

/* ---- single values ------------------------------------------------------ */

int args_long(const char *opt, const char *val, long lo, long hi, long *out, char *err,
              size_t errlen) {
  char shown[300];
  if (whole_syntax(val, 1)) {
    errno = 0;
    long v = strtol(val, NULL, 10);
    if (errno != ERANGE && v >= lo && v <= hi) {
      *out = v;
      return 0;
    }
  }
  args_show(val, shown, sizeof shown);
  snprintf(err, errlen, "%s takes a whole number from %ld to %ld (%s)", opt, lo, hi, shown);
  return -1;
}

int args_u64(const char *opt, const char *val, unsigned long long lo, unsigned long long hi,
             unsigned long long *out, char *err, size_t errlen) {
  char shown[300];
  if (whole_syntax(val, 0)) {
    errno = 0;
    unsigned long long v = strtoull(val, NULL, 10);
    if (errno != ERANGE && v >= lo && v <= hi) {
      *out = v;
      return 0;
    }
  }
  args_show(val, shown, sizeof shown);
  snprintf(err, errlen, "%s takes a whole number from %llu to %llu (%s)", opt, lo, hi, shown);
  return -1;
}

int args_real(const char *opt, const char *val, const char *what, double lo, double hi,
              double *out, char *err, size_t errlen) {
  char shown[300], a[40], b[40];
  double v = 0;
  int r = read_real(val, &v);
  if (r == 0 && v >= lo && v <= hi) {
    *out = v;
    return 0;
  }
  args_show(val, shown, sizeof shown);
  args_fmt_double(lo, a, sizeof a);
  args_fmt_double(hi, b, sizeof b);
  if (r == 3)
    snprintf(err, errlen, "%s takes %s from %s to %s (%s is too close to 0 to represent)", opt, what,
             a, b, shown);
  else
    snprintf(err, errlen, "%s takes %s from %s to %s (%s)", opt, what, a, b, shown);
  return -1;
}

int args_double(const char *opt, const char *val, double lo, double hi, double *out,
                char *err, size_t errlen) {
  return args_real(opt, val, "a number", lo, hi, out, err, errlen);
}

/* ---- lists ---------------------------------------------------------------- */

/* One item of a list, [s, e): 0 and its numbers appended, or -1 with why. */
static int list_item(const char *s, const char *e, int whole, double lo, double hi, int max,
                     args_list *l, char *why, size_t whylen) {
  char item[128], a[40];
  size_t n = (size_t)(e - s);
  if (n == 0) {
    snprintf(why, whylen, "an empty item");
    return -1;
  }
  if (n >= sizeof item) {
    snprintf(why, whylen, "an item of %zu bytes", n);
    return -1;
  }
  memcpy(item, s, n);
  item[n] = 0;
  args_show(item, a, sizeof a);
  if (whole) {
    char *dots = strstr(item, "..");
    char *second = dots ? dots + 2 : NULL;
    if (dots) *dots = 0;
    long long x, y;
    if (!whole_syntax(item, 1) || (second && !whole_syntax(second, 1))) {
      snprintf(why, whylen, "%s is not a whole number or a range a..b", a);
      return -1;
    }
    errno = 0;
    x = strtoll(item, NULL, 10);
    y = second ? strtoll(second, NULL, 10) : x;
    if (errno == ERANGE || (double)x < lo || (double)y > hi || (double)y < lo || (double)x > hi) {
      snprintf(why, whylen, "%s is out of range", a);
      return -1;
    }
    if (y < x) {
      snprintf(why, whylen, "%s is an empty range", a);
      return -1;
    }
    if ((double)y - (double)x + 1 > (double)(max - l->n)) {
      snprintf(why, whylen, "more than %d numbers", max);
      return -1;
    }
    for (long long k = x; k <= y; k++) l->v[l->n++] = (double)k;
    return 0;
  }
  double v = 0;
  int r = read_real(item, &v);
  if (r == 1) snprintf(why, whylen, "%s is not a number", a);
  else if (r == 3) snprintf(why, whylen, "%s is too close to 0 to represent", a);
  else if (r == 2 || !(v >= lo && v <= hi)) snprintf(why, whylen, "%s is out of range", a);
  else if (l->n == max) snprintf(why, whylen, "more than %d numbers", max);
  else {
    l->v[l->n++] = v;
    return 0;
  }
  return -1;
}

int args_list_max(const char *opt, const char *val, int whole, double lo, double hi, int max,
                  args_list *l, char *err, size_t errlen) {
  char why[200] = "", shown[300], a[40], b[40];
  if (max < 1 || max > ARGS_LIST_MAX) max = ARGS_LIST_MAX;
  l->n = 0;
  const char *p = val;
  int bad = 0;
  if (!*val) {
    snprintf(why, sizeof why, "an empty list");
    bad = 1;
  }
  while (!bad) {
    const char *e = strchr(p, ',');
    if (!e) e = p + strlen(p);
    if (list_item(p, e, whole, lo, hi, max, l, why, sizeof why) != 0) bad = 1;
    else if (!*e) break;
    else p = e + 1;
  }
  if (!bad) return 0;
  l->n = 0;
  args_show(val, shown, sizeof shown);
  if (whole) {   /* whole bounds as whole numbers: 100000, not 1e5 */
    snprintf(a, sizeof a, "%.0f", lo);
    snprintf(b, sizeof b, "%.0f", hi);
  } else {
    args_fmt_double(lo, a, sizeof a);
    args_fmt_double(hi, b, sizeof b);
  }
  if (whole)
    snprintf(err, errlen,
             "%s takes whole numbers from %s to %s, listed and in ranges like 1,2,4 or 1..16, "
             "at most %d in all (%s: %s)",
             opt, a, b, max, shown, why);
  else
    snprintf(err, errlen, "%s takes numbers from %s to %s, comma-separated, at most %d (%s: %s)",
             opt, a, b, max, shown, why);
  return -1;
}

int args_list_parse(const char *opt, const char *val, int whole, double lo, double hi,
                    args_list *l, char *err, size_t errlen) {
  return args_list_max(opt, val, whole, lo, hi, ARGS_LIST_MAX, l, err, errlen);
}

/* ---- words ---------------------------------------------------------------- */

/* The index of [s, s+n) among the words, or -1. */
static int word_index(const char *s, size_t n, const char *words) {
  int i = 0;
  for (const char *w = words;; i++) {
    const char *e = strchr(w, '|');
    size_t len = e ? (size_t)(e - w) : strlen(w);
    if (len == n && n > 0 && strncmp(w, s, n) == 0) return i;
    if (!e) return -1;
    w = e + 1;
  }
}

/* "a, b or c" */
static void word_choice(const char *words, char *buf, size_t len) {
  size_t k = 0;
  int count = 1;
  for (const char *p = words; *p; p++) count += *p == '|';
  int i = 0;
  buf[0] = 0;
  for (const char *w = words; k + 1 < len; i++) {
    const char *e = strchr(w, '|');
    int n = e ? (int)(e - w) : (int)strlen(w);
    const char *sep = i == 0 ? "" : i == count - 1 ? " or " : ", ";
    k += (size_t)snprintf(buf + k, len - k, "%s%.*s", sep, n, w);
    if (!e || k >= len) break;
    w = e + 1;
  }
}

int args_word(const char *opt, const char *val, const char *words, char *err, size_t errlen) {
  int i = word_index(val, strlen(val), words);
  if (i >= 0) return i;
  char choice[200], shown[300];
  word_choice(words, choice, sizeof choice);
  args_show(val, shown, sizeof shown);
  snprintf(err, errlen, "%s takes %s (%s)", opt, choice, shown);
  return -1;
}

int args_word_list(const char *opt, const char *val, const char *words, int *idx, int max,
                   char *err, size_t errlen) {
  int n = 0, bad = !*val;
  for (const char *p = val; !bad;) {
    const char *e = strchr(p, ',');
    size_t len = e ? (size_t)(e - p) : strlen(p);
    int i = word_index(p, len, words);
    if (i < 0 || n == max) bad = 1;
    else idx[n++] = i;
    if (!e) break;
    p = e + 1;
  }
  if (!bad) return n;
  char choice[200], shown[300];
  word_choice(words, choice, sizeof choice);
  args_show(val, shown, sizeof shown);
  snprintf(err, errlen, "%s takes %s, or up to %d of them comma-separated (%s)", opt, choice, max,
           shown);
  return -1;
}

/* ---- bytes and names ------------------------------------------------------ */

int args_bytes(const char *opt, const char *val, unsigned long long *out, char *err,
               size_t errlen) {
  if (strcmp(val, "none") == 0) {
    *out = ULLONG_MAX;
    return 0;
  }
  if (whole_syntax(val, 0)) {
    errno = 0;
    unsigned long long v = strtoull(val, NULL, 10);
    if (errno != ERANGE) {
      *out = v;
      return 0;
    }
  } else {
    size_t n = strlen(val);
    static const char suffix[] = "kKMGT";
    static const double mult[] = {1e3, 1e3, 1e6, 1e9, 1e12};
    const char *s = n > 1 ? strchr(suffix, val[n - 1]) : NULL;
    char mant[64];
    double v;
    if (s && n - 1 < sizeof mant) {
      memcpy(mant, val, n - 1);
      mant[n - 1] = 0;
      if (mant[0] != '-' && read_real(mant, &v) == 0) {
        v *= mult[s - suffix];
        if (v == floor(v) && v < 18446744073709551616.0) {
          *out = (unsigned long long)v;
          return 0;
        }
      }
    }
  }
  char shown[300];
  args_show(val, shown, sizeof shown);
  snprintf(err, errlen,
           "%s takes bytes from 0 to %llu: a whole number, or with k, M, G or T "
           "(10^3, 10^6, 10^9, 10^12) like 500M or 1.5G, or none (%s)",
           opt, ULLONG_MAX, shown);
  return -1;
}

int args_name(const char *opt, const char *val, const char *what, int dash_ok, char *err,
              size_t errlen) {
  char shown[300];
  args_show(val, shown, sizeof shown);
  if (!*val) {
    snprintf(err, errlen, "%s takes %s (%s)", opt, what, shown);
    return -1;
  }
  if (val[0] == '-' && !(dash_ok && val[1] == 0)) {
    snprintf(err, errlen, "%s takes %s, not an option (%s; write ./%s for a file of that name)", opt,
             what, shown, shown);
    return -1;
  }
  return 0;
}
