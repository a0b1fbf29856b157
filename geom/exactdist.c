/* exactdist.c -- squared point-segment distances: an interval filter, then
 * big integers (exactdist.h). */
#include "geom/exactdist.h"

#include <math.h>
#include <string.h>

#include "geom/bigz.h"
#include "util/xmem.h"

/* A coordinate's least power of two (bigz_lsb_exp), 1 << 20 for 0 so that
 * zeros never lower a common exponent.  Every coordinate over a common
 * 2^emin is an integer of at most 2098 bits (66 limbs): a difference 67, a
 * product of six differences 402, within BIGZ_LIMBS. */
static int low_exp(double x) {
  if (!isfinite(x)) xpanic("exactdist: a coordinate is not finite (%g)", x);
  return x == 0 ? 1 << 20 : bigz_lsb_exp(x);
}

/* --- the exact values ---------------------------------------------------- */

/* An exactdist's value as num / den over a common 2^emin: POINT
 * num = |p - a|^2, den = 1; LINE num = ((b - a) x (p - a))^2, den = |b - a|^2.
 * Both homogeneous in the coordinates (degrees 2, 0 or 4, 2). */
static void value(const exactdist *d, int emin, bigz *num, bigz *den) {
  static _Thread_local bigz px, py, ax, ay, dx, dy, t, u, bx, by, ux, uy, c;
  bigz_from_double(&px, d->p.x, emin), bigz_from_double(&py, d->p.y, emin);
  bigz_from_double(&ax, d->a.x, emin), bigz_from_double(&ay, d->a.y, emin);
  bigz_sub(&dx, &px, &ax), bigz_sub(&dy, &py, &ay);   /* p - a */
  if (d->kind == EXACTDIST_POINT) {
    bigz_mul(&t, &dx, &dx), bigz_mul(&u, &dy, &dy), bigz_add(num, &t, &u);
    bigz_set_int(den, 1);
    return;
  }
  bigz_from_double(&bx, d->b.x, emin), bigz_from_double(&by, d->b.y, emin);
  bigz_sub(&ux, &bx, &ax), bigz_sub(&uy, &by, &ay);   /* b - a */
  bigz_mul(&t, &ux, &dy), bigz_mul(&u, &uy, &dx), bigz_sub(&c, &t, &u);
  bigz_mul(num, &c, &c);
  bigz_mul(&t, &ux, &ux), bigz_mul(&u, &uy, &uy), bigz_add(den, &t, &u);
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
  static _Thread_local bigz nx, dx, ny, dy, l, r;
  value(x, emin, &nx, &dx);
  value(y, emin, &ny, &dy);
  bigz_mul(&l, &nx, &dy);
  bigz_mul(&r, &ny, &dx);
  return bigz_cmp(&l, &r);
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
  static _Thread_local bigz n, d, rr, t, l;
  value(x, emin, &n, &d);
  bigz_from_double(&rr, r, emin);
  bigz_mul(&t, &rr, &rr);
  bigz_mul(&l, &t, &d);
  return bigz_cmp(&n, &l);
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
  static _Thread_local bigz px, py, ax, ay, bx, by, wx, wy, ux, uy, t, u, w;
  bigz_from_double(&px, p.x, emin), bigz_from_double(&py, p.y, emin);
  bigz_from_double(&ax, a.x, emin), bigz_from_double(&ay, a.y, emin);
  bigz_from_double(&bx, b.x, emin), bigz_from_double(&by, b.y, emin);
  bigz_sub(&wx, &px, &ax), bigz_sub(&wy, &py, &ay);
  bigz_sub(&ux, &bx, &ax), bigz_sub(&uy, &by, &ay);
  bigz_mul(&t, &wx, &ux), bigz_mul(&u, &wy, &uy), bigz_add(&w, &t, &u);
  return bigz_sign(&w);
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
