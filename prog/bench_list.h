/* bench_list.h -- ./bench's number lists: "1..16", "100,200,300", "1e-4,2e-4". */
#ifndef BENCH_LIST_H
#define BENCH_LIST_H

enum { BENCH_LIST_MAX = 256 };

typedef struct {
  int n;
  double v[BENCH_LIST_MAX];
} bench_list;

/* Comma-separated numbers, and (whole numbers only) ranges a..b, each within
 * [lo, hi].  0, or -1 if malformed, out of range or too long. */
int bench_list_parse(const char *s, bench_list *l, int whole, double lo, double hi);

#endif
