/* args.h -- strict parsing of command-line option values: whole numbers,
 * real numbers, lists and ranges, words, byte counts and file names.
 *
 * Every function takes the option's name (for the message) and its value,
 * and returns 0, or -1 with one line in err of the form
 *     OPT takes WHAT from LO to HI (VALUE)
 * that names the option and the accepted range (the caller prefixes its
 * program's name).  Values are whole strings only: no leading or trailing
 * blanks, no hexadecimal, no "inf" or "nan", no empty string, and no value
 * that overflows or underflows (1e-400 is refused, not read as 0).  A value
 * with control characters or of more than 60 bytes is shown escaped and cut
 * short, so the message stays one line. */
#ifndef ARGS_H
#define ARGS_H

#include <stddef.h>

/* A whole number in [lo, hi]: decimal digits, an optional leading '-'. */
int args_long(const char *opt, const char *val, long lo, long hi, long *out, char *err,
              size_t errlen);

/* An unsigned whole number in [lo, hi]: decimal digits only ("-1" is refused). */
int args_u64(const char *opt, const char *val, unsigned long long lo, unsigned long long hi,
             unsigned long long *out, char *err, size_t errlen);

/* A real number in [lo, hi]: [-]digits[.digits][e[+-]digits] (or .digits);
 * "a number" in the message. */
int args_double(const char *opt, const char *val, double lo, double hi, double *out,
                char *err, size_t errlen);

/* The same, with what the number is in the message ("seconds", "units"):
 * "--m takes seconds from 0 to 1e9 (abc)". */
int args_real(const char *opt, const char *val, const char *what, double lo, double hi,
              double *out, char *err, size_t errlen);

/* "1..16", "100,200,300", "1e-4,2e-4": comma-separated numbers within
 * [lo, hi]; whole != 0 asks for whole numbers and allows ranges a..b
 * (a <= b).  No empty items ("1,,2", "1,"), at most ARGS_LIST_MAX numbers
 * in all (a range counts its every number). */
enum { ARGS_LIST_MAX = 256 };
typedef struct { int n; double v[ARGS_LIST_MAX]; } args_list;
int args_list_parse(const char *opt, const char *val, int whole, double lo, double hi,
                    args_list *l, char *err, size_t errlen);

/* The same with at most max numbers (1 <= max <= ARGS_LIST_MAX). */
int args_list_max(const char *opt, const char *val, int whole, double lo, double hi, int max,
                  args_list *l, char *err, size_t errlen);

/* One of the words of a '|'-separated set, e.g. "sim|threads": its index,
 * or -1 and "--backend takes sim or threads (x)". */
int args_word(const char *opt, const char *val, const char *words, char *err, size_t errlen);

/* Comma-separated words of the set, at most max of them: their indices in
 * idx[], the count returned; or -1 and a message. */
int args_word_list(const char *opt, const char *val, const char *words, int *idx, int max,
                   char *err, size_t errlen);

/* A byte count: a whole number, or a number with k, M, G or T (10^3, 10^6,
 * 10^9, 10^12) that makes a whole number ("1.5G"), or "none" (no limit:
 * the largest value).  *out gets the bytes. */
int args_bytes(const char *opt, const char *val, unsigned long long *out, char *err,
               size_t errlen);

/* A file name: not empty, and not an option ("-o --caps" is refused; a name
 * starting with '-' is refused unless it is "-" itself and dash_ok).  what
 * says what it names in the message ("a file name", "a CSV file"). */
int args_name(const char *opt, const char *val, const char *what, int dash_ok, char *err,
              size_t errlen);

/* The value as the messages show it (quoted if empty or with blanks,
 * control bytes as \xNN, cut after 60 bytes), for a program's own
 * messages about a value. */
void args_show(const char *val, char *buf, size_t len);

/* Bad usage, the one way every mode says it: "PROG: why" on stderr, arg (or
 * NULL) shown after it as args_show shows values, then the usage text.
 * PROG, as a word of why and of the usage text too, is written as the name
 * the program was run by (util/progname.h).  Returns 2, the exit status of
 * bad usage. */
int args_usage(const char *prog, const char *usage, const char *why, const char *arg);

/* A real number in the shortest form that reads back exactly, with a short
 * exponent ("1e9", "0.000275", "2.5e-5"): how the messages print ranges,
 * and every number a message or summary line shows (CSV keeps %.17g). */
void args_fmt_double(double v, char *buf, size_t len);

/* The same into buf (ARGS_G_LEN bytes), returned: ARGS_G(x) gives a buffer
 * that lasts to the end of the enclosing block, for a printf argument:
 *     fprintf(stderr, "at (%s %s)\n", ARGS_G(p.x), ARGS_G(p.y)); */
enum { ARGS_G_LEN = 40 };
char *args_g(char *buf, double v);
#define ARGS_G(v) args_g((char[ARGS_G_LEN]){0}, (v))

#endif
