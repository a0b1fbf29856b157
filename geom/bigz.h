/* bigz.h -- small signed big integers for exact geometry: add, subtract,
 * multiply, compare, shift, and a quotient rounded correctly to a double.
 *
 * Made for the exact union of polygons (polyunion.h) and exact distances
 * (exactdist.h): every finite double is an integer times a power of two, so
 * the coordinates of a set of points are integers at the scale of their
 * least significant bit, at most about 2,100 bits apart (2^-1074 to 2^1024),
 * and the predicates those need are polynomials of degree 6 at most in them:
 * BIGZ_LIMBS 32-bit limbs hold any such value.  A bigz is a plain value
 * (1.7 KB; callers keep theirs thread-local rather than on the stack); the
 * operations touch only the limbs in use, so the common case -- coordinates
 * of 60 to 110 bits, a few limbs -- is cheap.  Operations abort (xpanic) on
 * overflow of the capacity: a bug, not an input. */
#ifndef BIGZ_H
#define BIGZ_H

#include <stdint.h>

enum { BIGZ_LIMBS = 420 };   /* 13,440 bits: exactdist.h's degree-6 products too */

typedef struct {
  int n;      /* limbs in use: l[n-1] != 0, or n = 0 for zero */
  int neg;    /* 1 for a negative value (never for zero) */
  uint32_t l[BIGZ_LIMBS];
} bigz;

/* The least significant bit's exponent of x != 0 (x = odd m times 2^e);
 * INT32_MAX for 0. */
int bigz_lsb_exp(double x);

/* x times 2^-e, which must be an integer (e <= bigz_lsb_exp(x)); x finite. */
void bigz_from_double(bigz *r, double x, int e);

void bigz_set_int(bigz *r, long long v);
void bigz_copy(bigz *r, const bigz *a);

/* r = a + b, r = a - b (r may be a or b); r = a b (r must be neither). */
void bigz_add(bigz *r, const bigz *a, const bigz *b);
void bigz_sub(bigz *r, const bigz *a, const bigz *b);
void bigz_mul(bigz *r, const bigz *a, const bigz *b);
void bigz_neg(bigz *r);

int bigz_sign(const bigz *a);                  /* -1, 0, +1 */
int bigz_cmp(const bigz *a, const bigz *b);    /* the sign of a - b */

/* num / den times 2^e, rounded to the nearest double (ties to even), den >
 * 0: the correctly rounded value, subnormals included (0 or inf beyond a
 * double's range). */
double bigz_ratio(const bigz *num, const bigz *den, int e);

#endif
