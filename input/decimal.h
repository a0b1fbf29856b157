/* decimal.h -- DICOM decimal strings (DS, the numbers of ContourData),
 * read whatever the locale. */
#ifndef DECIMAL_H
#define DECIMAL_H

#include <stddef.h>

/* A decimal string (DS): optional blanks around [+-]digits[.digits][e[+-]digits].
 * 0 and *v; 1 if it is a number too large for a double; -1 if it is not a
 * number.  The result is the correctly rounded double, whatever the locale. */
int decimal_parse(const char *s, size_t len, double *v);

#endif
