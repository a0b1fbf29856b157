/* decimal.h -- DICOM decimal strings (DS, the numbers of ContourData),
 * read whatever the locale. */
#ifndef DECIMAL_H
#define DECIMAL_H

#include <stddef.h>

/* A decimal string (DS): optional blanks around [+-]digits[.digits][e[+-]digits].
 * 0 and *v; 1 if it is a number too large for a double; -1 if it is not a
 * number.  The result is the correctly rounded double, whatever the locale. */
int decimal_parse(const char *s, size_t len, double *v);

/* The place value of the last digit written in the decimal string s: how
 * finely it was rounded ("12.34" 0.01, "-5" 1, "1.5e-3" 0.0001,
 * "1.2345678901234567" 1e-16): 10^(exponent - digits after the point).  0
 * when s has no digit.  A value so written is within half of it of the
 * number it stands for. */
double decimal_quantum(const char *s, size_t len);

#endif
