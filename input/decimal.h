/* decimal.h -- DICOM decimal strings (DS, the numbers of ContourData),
 * read whatever the locale. */
#ifndef DECIMAL_H
#define DECIMAL_H

#include <stddef.h>

/* A decimal string (DS): optional blanks around [+-]digits[.digits][e[+-]digits].
 * 0 and *v; 1 if it is a number too large for a double; -1 if it is not a
 * number.  The result is the correctly rounded double, whatever the locale. */
int decimal_parse(const char *s, size_t len, double *v);

/* How finely v was written: the place value of the last digit of its
 * shortest decimal form that reads back as v (0.45 0.01, 12.3 0.1, 20 10,
 * 1.2345678901234567 1e-16, 0 none: 0).  A planning system that writes two
 * decimals (trailing zeros trimmed or not) gives 0.01 for most of its
 * values, whatever the text: written again at full precision, the same
 * doubles give the same answer.  Locale-free. */
double decimal_quantum(double v);

#endif
