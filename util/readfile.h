/* readfile.h -- a whole input file, or standard input, in memory. */
#ifndef READFILE_H
#define READFILE_H

#include <stddef.h>

/* The bytes of path ("-": standard input) in a malloc'd buffer, *len of
 * them; or NULL with "PATH: cannot open (why)" or "PATH: cannot read (why)"
 * in err. */
char *readfile(const char *path, size_t *len, char *err, size_t errlen);

/* What messages call the input path: "<stdin>" for "-". */
const char *readfile_name(const char *path);

#endif
