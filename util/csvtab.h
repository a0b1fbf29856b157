/* csvtab.h -- a CSV file with a header row, as a table of strings. */
#ifndef CSVTAB_H
#define CSVTAB_H

#include <stddef.h>

typedef struct {
  int ncol, nrow;
  char **head;    /* ncol names */
  char ***cell;   /* nrow rows of ncol fields */
} csvtab;

/* Read path: a header row, then rows of as many fields; a field plain or
 * quoted as RFC 4180 writes it ("a, b" keeps its comma, "" is a quote),
 * one record a line (no line break inside a field), lines up to 8190
 * bytes.  0, or -1 with "PATH:LINE: why". */
int csvtab_read(const char *path, csvtab *t, char *err, size_t errlen);
int csvtab_col(const csvtab *t, const char *name);   /* index, or -1 */
void csvtab_free(csvtab *t);

#endif
