/* decimal.c -- DICOM decimal strings (decimal.h). */
#include "input/decimal.h"

#include <locale.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

/* Powers of ten a double holds exactly. */
static const double pow10_exact[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                     1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* strtod in the "C" locale, for the numbers the fast path cannot round. */
static double c_strtod(const char *s, size_t len) {
  char small[64];
  char *buf = len < sizeof small ? small : xmalloc(len + 1);
  memcpy(buf, s, len);
  buf[len] = 0;
  locale_t c = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
  locale_t old = c ? uselocale(c) : (locale_t)0;
  double v = strtod(buf, NULL);
  if (c) {
    uselocale(old);
    freelocale(c);
  }
  if (buf != small) free(buf);
  return v;
}

int decimal_parse(const char *s, size_t len, double *v) {
  size_t i = 0, j = len;
  while (i < j && s[i] == ' ') i++;
  while (j > i && (s[j - 1] == ' ' || s[j - 1] == 0)) j--;
  if (i == j) return -1;
  size_t start = i;
  int neg = 0;
  if (s[i] == '+' || s[i] == '-') neg = s[i++] == '-';
  uint64_t m = 0;
  long digits = 0, sig = 0, exp10 = 0;
  int ok = 1;
  for (; i < j && s[i] >= '0' && s[i] <= '9'; i++, digits++) {
    if (m == 0 && s[i] == '0') continue;
    if (sig < 19) m = m * 10 + (uint64_t)(s[i] - '0'), sig++;
    else exp10++, ok &= s[i] == '0';
  }
  if (i < j && s[i] == '.') {
    for (i++; i < j && s[i] >= '0' && s[i] <= '9'; i++, digits++) {
      if (m == 0 && s[i] == '0') {
        exp10--;
        continue;
      }
      if (sig < 19) m = m * 10 + (uint64_t)(s[i] - '0'), sig++, exp10--;
      else ok &= s[i] == '0';
    }
  }
  if (digits == 0) return -1;
  if (i < j && (s[i] == 'e' || s[i] == 'E')) {
    i++;
    int eneg = 0;
    long e = 0, ed = 0;
    if (i < j && (s[i] == '+' || s[i] == '-')) eneg = s[i++] == '-';
    for (; i < j && s[i] >= '0' && s[i] <= '9'; i++, ed++)
      if (e < 100000) e = e * 10 + (s[i] - '0');
    if (ed == 0) return -1;
    exp10 += eneg ? -e : e;
  }
  if (i != j) return -1;
  double r;
  if (m == 0) {
    r = neg ? -0.0 : 0.0;
  } else if (ok && m <= (UINT64_C(1) << 53) && exp10 >= -22 && exp10 <= 22) {
    /* Clinger's fast path: both operands exact, one rounding. */
    r = exp10 >= 0 ? (double)m * pow10_exact[exp10] : (double)m / pow10_exact[-exp10];
    if (neg) r = -r;
  } else {
    r = c_strtod(s + start, j - start);   /* the sign included */
  }
  *v = r;
  return isfinite(r) ? 0 : 1;
}

double decimal_quantum(double v) {
  if (v == 0 || !isfinite(v)) return 0;
  double a = fabs(v);
  int e10 = (int)floor(log10(a));
  char buf[48];
  for (int p = 1; p <= 17; p++) {
    int x = e10 - p + 1;   /* the place value of the p-th significant digit: 10^x */
    double m = nearbyint(v / pow(10, x));
    for (int d = -1; d <= 1; d++) {   /* the quotient is rounded: its neighbours too */
      double w;
      int n = snprintf(buf, sizeof buf, "%.0fe%d", m + d, x);   /* no decimal point: no locale */
      if (n > 0 && (size_t)n < sizeof buf && decimal_parse(buf, (size_t)n, &w) == 0 && w == v) return pow(10, x);
    }
  }
  return pow(10, e10 - 16);
}
