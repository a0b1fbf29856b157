/* bigz.c -- small signed big integers (bigz.h): sign and magnitude, 32-bit
 * limbs, least significant first; schoolbook multiplication; a quotient by
 * binary long division, rounded once. */
#include "geom/bigz.h"

#include <math.h>
#include <string.h>

#include "util/xmem.h"

static void trim(bigz *r) {
  while (r->n > 0 && r->l[r->n - 1] == 0) r->n--;
  if (r->n == 0) r->neg = 0;
}

static void room(int n) {
  if (n > BIGZ_LIMBS) xpanic("bigz: %d limbs needed, %d held", n, BIGZ_LIMBS);
}

int bigz_lsb_exp(double x) {
  if (x == 0) return INT32_MAX;
  int k;
  double f = frexp(x, &k);   /* x = f 2^k, 0.5 <= |f| < 1, exact */
  int64_t m = (int64_t)ldexp(fabs(f), 53);
  int e = k - 53;
  while ((m & 1) == 0) m >>= 1, e++;
  return e;
}

void bigz_set_int(bigz *r, long long v) {
  unsigned long long m = v < 0 ? 0ull - (unsigned long long)v : (unsigned long long)v;
  r->neg = v < 0;
  r->l[0] = (uint32_t)m, r->l[1] = (uint32_t)(m >> 32);
  r->n = 2;
  trim(r);
}

/* r = a shifted left by s bits (r may be a). */
static void shl(bigz *r, const bigz *a, int s) {
  int w = s / 32, b = s % 32, n = a->n;
  if (n == 0) {
    r->n = 0, r->neg = 0;
    return;
  }
  room(n + w + 1);
  int neg = a->neg;
  r->l[n + w] = 0;
  for (int i = n - 1; i >= 0; i--) {
    uint32_t v = a->l[i];
    if (b) {
      r->l[i + w + 1] |= v >> (32 - b);
      r->l[i + w] = v << b;
    } else {
      r->l[i + w] = v;
    }
  }
  for (int i = 0; i < w; i++) r->l[i] = 0;
  r->n = n + w + 1;
  r->neg = neg;
  trim(r);
}

void bigz_from_double(bigz *r, double x, int e) {
  if (x == 0) {
    r->n = 0, r->neg = 0;
    return;
  }
  if (!isfinite(x)) xpanic("bigz_from_double: not finite (%g)", x);
  int k;
  double f = frexp(x, &k);
  int64_t m = (int64_t)ldexp(fabs(f), 53);
  int s = k - 53 - e;
  while (s < 0 && (m & 1) == 0) m >>= 1, s++;
  if (s < 0) xpanic("bigz_from_double: %.17g is not an integer at 2^%d", x, e);
  bigz_set_int(r, m);
  shl(r, r, s);
  r->neg = x < 0;
}

void bigz_copy(bigz *r, const bigz *a) {
  if (r == a) return;
  r->n = a->n, r->neg = a->neg;
  memcpy(r->l, a->l, (size_t)a->n * sizeof *a->l);
}

static int mag_cmp(const bigz *a, const bigz *b) {
  if (a->n != b->n) return a->n < b->n ? -1 : 1;
  for (int i = a->n - 1; i >= 0; i--)
    if (a->l[i] != b->l[i]) return a->l[i] < b->l[i] ? -1 : 1;
  return 0;
}

/* r = |a| + |b|, sign neg (r may be a or b). */
static void mag_add(bigz *r, const bigz *a, const bigz *b, int neg) {
  int n = a->n > b->n ? a->n : b->n;
  room(n + 1);
  uint64_t c = 0;
  for (int i = 0; i < n; i++) {
    c += (uint64_t)(i < a->n ? a->l[i] : 0) + (i < b->n ? b->l[i] : 0);
    r->l[i] = (uint32_t)c;
    c >>= 32;
  }
  r->l[n] = (uint32_t)c;
  r->n = n + 1;
  r->neg = neg;
  trim(r);
}

/* r = |a| - |b| with |a| >= |b|, sign neg (r may be a or b). */
static void mag_sub(bigz *r, const bigz *a, const bigz *b, int neg) {
  int n = a->n;
  int64_t c = 0;
  for (int i = 0; i < n; i++) {
    c += (int64_t)a->l[i] - (i < b->n ? (int64_t)b->l[i] : 0);
    r->l[i] = (uint32_t)c;
    c = c < 0 ? -1 : 0;
  }
  r->n = n;
  r->neg = neg;
  trim(r);
}

static void add_signed(bigz *r, const bigz *a, const bigz *b, int bneg) {
  int aneg = a->neg;
  if (aneg == bneg) mag_add(r, a, b, aneg);
  else if (mag_cmp(a, b) >= 0) mag_sub(r, a, b, aneg);
  else mag_sub(r, b, a, bneg);
}

void bigz_add(bigz *r, const bigz *a, const bigz *b) { add_signed(r, a, b, b->neg); }
void bigz_sub(bigz *r, const bigz *a, const bigz *b) { add_signed(r, a, b, b->n ? !b->neg : 0); }

void bigz_neg(bigz *r) {
  if (r->n) r->neg = !r->neg;
}

void bigz_mul(bigz *r, const bigz *a, const bigz *b) {
  if (r == a || r == b) xpanic("bigz_mul: the result may not be an operand");
  if (a->n == 0 || b->n == 0) {
    r->n = 0, r->neg = 0;
    return;
  }
  int n = a->n + b->n;
  room(n);
  memset(r->l, 0, (size_t)n * sizeof *r->l);
  for (int i = 0; i < a->n; i++) {
    uint64_t c = 0, x = a->l[i];
    for (int j = 0; j < b->n; j++) {
      c += x * b->l[j] + r->l[i + j];
      r->l[i + j] = (uint32_t)c;
      c >>= 32;
    }
    r->l[i + b->n] = (uint32_t)c;
  }
  r->n = n;
  r->neg = a->neg != b->neg;
  trim(r);
}

int bigz_sign(const bigz *a) { return a->n == 0 ? 0 : a->neg ? -1 : 1; }

int bigz_cmp(const bigz *a, const bigz *b) {
  int sa = bigz_sign(a), sb = bigz_sign(b);
  if (sa != sb) return sa < sb ? -1 : 1;
  int m = mag_cmp(a, b);
  return sa >= 0 ? m : -m;
}

static int bits(const bigz *a) {
  if (a->n == 0) return 0;
  int b = 32 * (a->n - 1);
  for (uint32_t v = a->l[a->n - 1]; v; v >>= 1) b++;
  return b;
}

double bigz_ratio(const bigz *num, const bigz *den, int e) {
  if (bigz_sign(den) <= 0) xpanic("bigz_ratio: the denominator must be positive");
  if (num->n == 0) return 0;
  /* |num| 2^s / den has 56 or 57 bits before the point: Q and a sticky bit. */
  static _Thread_local bigz A, B, T;
  int s = 56 - bits(num) + bits(den);
  bigz_copy(&A, num);
  A.neg = 0;
  bigz_copy(&B, den);
  if (s >= 0) shl(&A, &A, s);
  else shl(&B, &B, -s);
  uint64_t q = 0;
  int k = bits(&A) - bits(&B);
  for (int i = k; i >= 0; i--) {
    shl(&T, &B, i);
    if (mag_cmp(&A, &T) >= 0) {
      mag_sub(&A, &A, &T, 0);
      q |= 1ull << i;
    }
  }
  int sticky = A.n != 0;
  /* value = q 2^(e - s) (+ sticky); q has qb bits.  Keep p bits: 53, fewer
   * where the value is subnormal. */
  int qb = 0;
  for (uint64_t v = q; v; v >>= 1) qb++;
  int top = qb - 1 + e - s;   /* the exponent of the leading bit */
  int p = 53;
  if (top < -1022) p = 53 - (-1022 - top);
  double r;
  if (p <= 0) {
    /* Below half the least subnormal, or between it and the least: q's
     * leading bit is at 2^top; the least subnormal is 2^-1074. */
    int up = top == -1075 && (q != (1ull << (qb - 1)) || sticky);
    r = up ? ldexp(1, -1074) : 0;
  } else {
    int drop = qb - p;
    uint64_t m = q;
    if (drop > 0) {
      uint64_t rest = q & ((1ull << drop) - 1), half = 1ull << (drop - 1);
      m = q >> drop;
      if (rest > half || (rest == half && (sticky || (m & 1)))) m++;
    } else {
      drop = 0;
    }
    r = ldexp((double)m, e - s + drop);
  }
  return num->neg ? -r : r;
}
