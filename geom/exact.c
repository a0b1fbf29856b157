/* exact.c -- exact orientation: a floating-point filter, then an exact sum of
 * six products in a big integer. */
#include "geom/exact.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "util/xmem.h"

/* --- the exact path ------------------------------------------------------- */

/* x = m 2^e with m an integer, |m| < 2^53 (m = 0 for x = 0). */
static void split(double x, int64_t *m, int *e) {
  if (x == 0) {
    *m = 0, *e = 0;
    return;
  }
  if (!isfinite(x)) xpanic("exact_orient: a coordinate is not finite (%g)", x);
  int k;
  double f = frexp(x, &k);          /* x = f 2^k, 0.5 <= |f| < 1: exact, subnormals too */
  *m = (int64_t)ldexp(f, 53);       /* an integer, |m| < 2^53 */
  *e = k - 53;
}

/* A product of two doubles, exactly: sign, a 106-bit magnitude in four
 * 32-bit limbs (least significant first), and the power of two. */
typedef struct {
  int sign;          /* -1, 0, +1 */
  uint32_t l[4];
  int e;
} term;

static term product(double x, double y, int sign) {
  term t = {0, {0, 0, 0, 0}, 0};
  int64_t mx, my;
  int ex, ey;
  split(x, &mx, &ex);
  split(y, &my, &ey);
  if (mx == 0 || my == 0) return t;
  if (mx < 0) mx = -mx, sign = -sign;
  if (my < 0) my = -my, sign = -sign;
  uint64_t a0 = (uint64_t)mx & 0xffffffffu, a1 = (uint64_t)mx >> 32;   /* a1 < 2^21 */
  uint64_t b0 = (uint64_t)my & 0xffffffffu, b1 = (uint64_t)my >> 32;
  uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
  /* limb 0 */
  t.l[0] = (uint32_t)p00;
  uint64_t c = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
  t.l[1] = (uint32_t)c;
  c = (c >> 32) + (p01 >> 32) + (p10 >> 32) + (p11 & 0xffffffffu);
  t.l[2] = (uint32_t)c;
  c = (c >> 32) + (p11 >> 32);
  t.l[3] = (uint32_t)c;
  XASSERT((c >> 32) == 0);
  t.sign = sign;
  t.e = ex + ey;
  return t;
}

/* Limbs enough for any spread of exponents: products lie between 2^-2252
 * and 2^2048, so at most 4300 bits, plus carries. */
enum { LIMBS = 144 };

/* acc += t's magnitude shifted left by s bits. */
static void add_shifted(uint32_t *acc, int nl, const term *t, int s) {
  int o = s / 32, b = s % 32;
  uint32_t w[5];
  for (int i = 0; i < 5; i++) {
    uint64_t lo = i < 4 ? (uint64_t)t->l[i] << b : 0;
    uint64_t hi = (i > 0 && b > 0) ? (uint64_t)t->l[i - 1] >> (32 - b) : 0;
    w[i] = (uint32_t)(lo | hi);
  }
  uint64_t carry = 0;
  int i = 0;
  for (; i < 5; i++) {
    XASSERT(o + i < nl);
    uint64_t v = (uint64_t)acc[o + i] + w[i] + carry;
    acc[o + i] = (uint32_t)v;
    carry = v >> 32;
  }
  for (; carry && o + i < nl; i++) {
    uint64_t v = (uint64_t)acc[o + i] + carry;
    acc[o + i] = (uint32_t)v;
    carry = v >> 32;
  }
  XASSERT(carry == 0);
}

int exact_orient_slow(vec2 a, vec2 b, vec2 c) {
  term t[6] = {product(b.x, c.y, 1),  product(b.x, a.y, -1), product(a.x, c.y, -1),
               product(b.y, c.x, -1), product(b.y, a.x, 1),  product(a.y, c.x, 1)};
  int emin = 0, emax = 0, any = 0;
  for (int i = 0; i < 6; i++) {
    if (!t[i].sign) continue;
    if (!any || t[i].e < emin) emin = t[i].e;
    if (!any || t[i].e > emax) emax = t[i].e;
    any = 1;
  }
  if (!any) return 0;
  int nl = (emax - emin + 106 + 8) / 32 + 2;
  XASSERT(nl <= LIMBS);
  uint32_t pos[LIMBS], neg[LIMBS];
  memset(pos, 0, sizeof(uint32_t) * (size_t)nl);
  memset(neg, 0, sizeof(uint32_t) * (size_t)nl);
  for (int i = 0; i < 6; i++)
    if (t[i].sign) add_shifted(t[i].sign > 0 ? pos : neg, nl, &t[i], t[i].e - emin);
  for (int i = nl - 1; i >= 0; i--)
    if (pos[i] != neg[i]) return pos[i] > neg[i] ? 1 : -1;
  return 0;
}

/* --- the filter ----------------------------------------------------------- */

int exact_orient(vec2 a, vec2 b, vec2 c) {
  double acx = a.x - c.x, bcx = b.x - c.x, acy = a.y - c.y, bcy = b.y - c.y;
  /* A factor that is exactly zero (a difference of doubles is zero only for
   * equal doubles) makes its product exactly zero. */
  int lz = acx == 0 || bcy == 0, rz = acy == 0 || bcx == 0;
  if (lz && rz) return 0;
  double l = acx * bcy, r = acy * bcx, det = l - r;
  double sum = fabs(l) + fabs(r);
  /* Shewchuk's orient2dfast bound, valid without overflow (sum finite) and
   * where underflow's absolute errors (2^-1074 a product) are far below it. */
  if (sum <= DBL_MAX && sum >= 0x1p-900) {
    const double eps = 0x1p-53, bound = (3.0 + 16.0 * eps) * eps * sum;
    if (det > bound) return 1;
    if (-det > bound) return -1;
  }
  return exact_orient_slow(a, b, c);
}
