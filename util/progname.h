/* progname.h -- the name a program was run by, in its messages.
 *
 * The sources call a program by one name (bench); installed it has another
 * (tilesim-bench), and a user who types one should read the same in what it
 * says.  progname_init records both; the printers below write the sources'
 * name as the name it was run by: every line that starts "bench:" (the
 * messages), and every word "bench" of a usage text ("usage: bench --ring
 * ...  (bench --help: every mode)").  A program that never calls
 * progname_init keeps its texts as written. */
#ifndef PROGNAME_H
#define PROGNAME_H

#include <stdio.h>

/* name: what the sources call the program ("bench"); argv0: how it was run
 * (its last path component is the name; name itself if argv0 is NULL or
 * empty).  Both strings must outlive the program's messages. */
void progname_init(const char *name, const char *argv0);

/* The name the program was run by ("tilesim-bench", "bench"); before
 * progname_init, "". */
const char *progname(void);

/* prog itself, or the name the program was run by if prog is the sources'
 * name: what a message about prog's own work starts with. */
const char *progname_as(const char *prog);

/* fprintf(stderr, fmt, ...), with the sources' name at the start of every
 * line ("bench:" after a newline, or at the start when the last write ended
 * one) written as the name the program was run by.  Any thread may call it. */
void progname_eprintf(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* fputs(text, f), with the sources' name as a word (after the start, a
 * blank or '(', before a blank, ':', ',', ';' or ')'; not after "make ")
 * written as the name the program was run by: usage lines and reasons. */
void progname_fputs(const char *text, FILE *f);

#endif
