/* exactdist.c -- squared point-segment distances: an interval filter, then
 * big integers (exactdist.h). */
#include "geom/exactdist.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "util/xmem.h"

/* --- big integers: sign and magnitude, 32-bit limbs, least first --------- */

/* Every coordinate is an odd integer times 2^e with e >= -1074 and a value
 * below 2^1024, so over a common 2^emin it is an integer of at most 2098
 * bits (66 limbs); a difference 67; a product of six differences 402. */
enum { LIMBS = 420 };

typedef struct {
  int sign;          /* -1, 0, +1 */
  int n;             /* limbs in use; l[n-1] != 0 unless n = 0 */
  uint32_t l[LIMBS];
} big;

static void trim(big *a) {
  while (a->n > 0 && a->l[a->n - 1] == 0) a->n--;
  if (a->n == 0) a->sign = 0;
}

/* x = m 2^e, m an odd integer (|m| < 2^53), or m = 0. */
static void split(double x, int64_t *m, int *e) {
  if (x == 0) {
    *m = 0, *e = 0;
    return;
  }
  if (!isfinite(x)) xpanic("exactdist: a coordinate is not finite (%g)", x);
  int k;
  double f = frexp(x, &k);
  *m = (int64_t)ldexp(f, 53);
  *e = k - 53;
  while ((*m & 1) == 0) *m /= 2, ++*e;
}

/* The least power of two of x (a large value for 0). */
static int low_exp(double x) {
  int64_t m;
  int e;
  split(x, &m, &e);
  return m ? e : 1 << 20;
}

/* r = x / 2^emin, an integer (emin at most x's lowest power of two). */
static void from_double(big *r, double x, int emin) {
  int64_t m;
  int e;
  split(x, &m, &e);
  r->sign = m > 0 ? 1 : m < 0 ? -1 : 0;
  r->n = 0;
  if (!m) return;
  uint64_t u = (uint64_t)(m < 0 ? -m : m), lo;
  int s = e - emin, o = s / 32, b = s % 32;
  XASSERT(s >= 0 && o + 3 <= LIMBS);
  memset(r->l, 0, sizeof(uint32_t) * (size_t)o);
  lo = u << b;   /* u < 2^53: the bits above 64 go to the third limb */
  r->l[o] = (uint32_t)lo;
  r->l[o + 1] = (uint32_t)(lo >> 32);
  r->l[o + 2] = b ? (uint32_t)(u >> (64 - b)) : 0;
  r->n = o + 3;
  trim(r);
}

static int mag_cmp(const big *a, const big *b) {
  if (a->n != b->n) return a->n < b->n ? -1 : 1;
  for (int i = a->n - 1; i >= 0; i--)
    if (a->l[i] != b->l[i]) return a->l[i] < b->l[i] ? -1 : 1;
  return 0;
}

/* |r| = |a| + |b| (r distinct from a and b). */
static void mag_add(big *r, const big *a, const big *b) {
  int n = a->n > b->n ? a->n : b->n;
  uint64_t c = 0;
  for (int i = 0; i < n; i++) {
    c += (uint64_t)(i < a->n ? a->l[i] : 0) + (i < b->n ? b->l[i] : 0);
    r->l[i] = (uint32_t)c;
    c >>= 32;
  }
  XASSERT(n < LIMBS);
  r->l[n] = (uint32_t)c;
  r->n = n + 1;
}

/* |r| = |a| - |b|, |a| >= |b| (r distinct from a and b). */
static void mag_sub(big *r, const big *a, const big *b) {
  int64_t c = 0;
  for (int i = 0; i < a->n; i++) {
    c += (int64_t)a->l[i] - (i < b->n ? b->l[i] : 0);
    r->l[i] = (uint32_t)c;
    c = c < 0 ? -1 : 0;
  }
  r->n = a->n;
}

/* r = a + sb b, sb = +1 or -1 (r distinct from a and b). */
static void add(big *r, const big *a, const big *b, int sb) {
  int bs = b->sign * sb;
  if (!bs) {
    *r = *a;
    return;
  }
  if (!a->sign) {
    *r = *b;
    r->sign = bs;
    return;
  }
  if (a->sign == bs) {
    mag_add(r, a, b);
    r->sign = bs;
  } else if (mag_cmp(a, b) >= 0) {
    mag_sub(r, a, b);
    r->sign = a->sign;
  } else {
    mag_sub(r, b, a);
    r->sign = bs;
  }
  trim(r);
}

/* r = a b (r distinct from a and b). */
static void mul(big *r, const big *a, const big *b) {
  r->n = 0;
  r->sign = a->sign * b->sign;
  if (!r->sign) return;
  int n = a->n + b->n;
  XASSERT(n <= LIMBS);
  memset(r->l, 0, sizeof(uint32_t) * (size_t)n);
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
  trim(r);
}

static int cmp(const big *a, const big *b) {
  if (a->sign != b->sign) return a->sign < b->sign ? -1 : 1;
  int m = mag_cmp(a, b);
  return a->sign >= 0 ? m : -m;
}

/* --- the exact values ---------------------------------------------------- */

/* An exactdist's value as num / den over a common 2^emin: POINT
 * num = |p - a|^2, den = 1; LINE num = ((b - a) x (p - a))^2, den = |b - a|^2.
 * Both homogeneous in the coordinates (degrees 2, 0 or 4, 2). */
static void value(const exactdist *d, int emin, big *num, big *den) {
  big px, py, ax, ay, dx, dy, t, u;
  from_double(&px, d->p.x, emin), from_double(&py, d->p.y, emin);
  from_double(&ax, d->a.x, emin), from_double(&ay, d->a.y, emin);
  add(&dx, &px, &ax, -1), add(&dy, &py, &ay, -1);   /* p - a */
  if (d->kind == EXACTDIST_POINT) {
    mul(&t, &dx, &dx), mul(&u, &dy, &dy), add(num, &t, &u, 1);
    den->sign = 1, den->n = 1, den->l[0] = 1;
    return;
  }
  big bx, by, ux, uy, c;
  from_double(&bx, d->b.x, emin), from_double(&by, d->b.y, emin);
  add(&ux, &bx, &ax, -1), add(&uy, &by, &ay, -1);   /* b - a */
  mul(&t, &ux, &dy), mul(&u, &uy, &dx), add(&c, &t, &u, -1);
  mul(num, &c, &c);
  mul(&t, &ux, &ux), mul(&u, &uy, &uy), add(den, &t, &u, 1);
}

static int min_exp(const exactdist *d, int e) {
  const double v[6] = {d->p.x, d->p.y, d->a.x, d->a.y, d->b.x, d->b.y};
  int n = d->kind == EXACTDIST_POINT ? 4 : 6;
  for (int i = 0; i < n; i++) {
    int k = low_exp(v[i]);
    if (k < e) e = k;
  }
  return e;
}

int exactdist_cmp_slow(const exactdist *x, const exactdist *y) {
  int emin = min_exp(y, min_exp(x, 1 << 20));
  if (emin == 1 << 20) emin = 0;   /* every coordinate 0 */
  static _Thread_local big nx, dx, ny, dy, l, r;
  value(x, emin, &nx, &dx);
  value(y, emin, &ny, &dy);
  mul(&l, &nx, &dy);
  mul(&r, &ny, &dx);
  return cmp(&l, &r);
}

int exactdist_cmp(const exactdist *x, const exactdist *y) {
  if (x->hi < y->lo) return -1;
  if (y->hi < x->lo) return 1;
  return exactdist_cmp_slow(x, y);
}

int exactdist_cmp_len(const exactdist *x, double r) {
  double r2 = r * r;
  if (r2 >= 0x1p-900 && r2 <= 0x1p+1000) {
    if (x->hi < r2 * (1 - 0x1p-48)) return -1;
    if (x->lo > r2 * (1 + 0x1p-48)) return 1;
  }
  int emin = min_exp(x, low_exp(r));
  if (emin == 1 << 20) emin = 0;
  static _Thread_local big n, d, rr, t, l;
  value(x, emin, &n, &d);
  from_double(&rr, r, emin);
  mul(&t, &rr, &rr);
  mul(&l, &t, &d);
  return cmp(&n, &l);
}

/* --- the filter ---------------------------------------------------------- */

/* The sign of (p - a).(b - a), exactly. */
static int dot_sign(vec2 p, vec2 a, vec2 b) {
  double l = (p.x - a.x) * (b.x - a.x), r = (p.y - a.y) * (b.y - a.y), s = l + r;
  double mag = fabs(l) + fabs(r);
  /* Shewchuk's bound for a sum of two products of differences (as for
   * orient2d), doubled; valid without overflow and far above underflow. */
  if (mag <= 0x1p+1000 && mag >= 0x1p-900) {
    double bound = 0x1p-51 * mag;
    if (s > bound) return 1;
    if (-s > bound) return -1;
  }
  int emin = 1 << 20;
  const double v[6] = {p.x, p.y, a.x, a.y, b.x, b.y};
  for (int i = 0; i < 6; i++) {
    int k = low_exp(v[i]);
    if (k < emin) emin = k;
  }
  static _Thread_local big px, py, ax, ay, bx, by, wx, wy, ux, uy, t, u, w;
  from_double(&px, p.x, emin), from_double(&py, p.y, emin);
  from_double(&ax, a.x, emin), from_double(&ay, a.y, emin);
  from_double(&bx, b.x, emin), from_double(&by, b.y, emin);
  add(&wx, &px, &ax, -1), add(&wy, &py, &ay, -1);
  add(&ux, &bx, &ax, -1), add(&uy, &by, &ay, -1);
  mul(&t, &wx, &ux), mul(&u, &wy, &uy), add(&w, &t, &u, 1);
  return w.sign;
}

void exactdist_points(vec2 p, vec2 a, exactdist *d) {
  memset(d, 0, sizeof *d);
  d->kind = EXACTDIST_POINT;
  d->p = p, d->a = a, d->b = a;
  double x = p.x - a.x, y = p.y - a.y, v = x * x + y * y;
  d->approx = v;
  if (v >= 0x1p-900 && v <= 0x1p+1000) {
    /* Three roundings of relative size 2^-53 at most (each difference, its
     * square, the sum): 2^-48 is ample. */
    d->lo = v * (1 - 0x1p-48), d->hi = v * (1 + 0x1p-48);
  } else if (x == 0 && y == 0) {   /* p = a: a difference is 0 only for equal doubles */
    d->lo = d->hi = 0;
  } else {
    d->lo = 0, d->hi = INFINITY;
  }
}

void exactdist_segment(vec2 p, vec2 a, vec2 b, exactdist *d) {
  if (dot_sign(p, a, b) <= 0) {
    exactdist_points(p, a, d);
    return;
  }
  if (dot_sign(p, b, a) <= 0) {
    exactdist_points(p, b, d);
    return;
  }
  memset(d, 0, sizeof *d);
  d->kind = EXACTDIST_LINE;
  d->p = p, d->a = a, d->b = b;
  double ux = b.x - a.x, uy = b.y - a.y, wx = p.x - a.x, wy = p.y - a.y;
  double l = ux * wy, r = uy * wx, c = l - r, s = fabs(l) + fabs(r), len = ux * ux + uy * uy;
  d->approx = c * c / len;
  if (s >= 0x1p-400 && s <= 0x1p+500 && len >= 0x1p-900 && len <= 0x1p+1000) {
    /* |c - cross| <= 2^-50 s (Shewchuk's orient2d bound is (3 + 16 eps)
     * eps s, eps = 2^-53); len within 4 eps of |b - a|^2; the rest rounds
     * a few times more, well inside the 2^-48 margins; cmax >= 2^-450, so
     * its square is a normal double, and a quotient that underflows is off
     * by at most 2^-1074, well inside the 2^-1060 added. */
    double delta = 0x1p-50 * s, cmax = fabs(c) + delta, cmin = fabs(c) - delta;
    d->hi = cmax * cmax / len * (1 + 0x1p-48) + 0x1p-1060;
    d->lo = cmin > 0 ? fmax(0, cmin * cmin / len * (1 - 0x1p-48) - 0x1p-1060) : 0;
  } else {
    d->lo = 0, d->hi = INFINITY;
  }
}

double exactdist_value(const exactdist *d) { return sqrt(d->approx); }
