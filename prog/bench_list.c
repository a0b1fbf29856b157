/* bench_list.c -- number lists and ranges for ./bench's options. */
#include "bench_list.h"

#include <math.h>
#include <stdlib.h>

int bench_list_parse(const char *s, bench_list *l, int whole, double lo, double hi) {
  l->n = 0;
  const char *p = s;
  while (*p) {
    char *e;
    double a, b;
    if (whole) {   /* strtod would read "1..16" as "1." then ".16" */
      a = b = (double)strtol(p, &e, 10);
      if (e == p) return -1;
      p = e;
      if (p[0] == '.' && p[1] == '.') {
        b = (double)strtol(p + 2, &e, 10);
        if (e == p + 2) return -1;
        p = e;
      }
    } else {
      a = b = strtod(p, &e);
      if (e == p) return -1;
      p = e;
    }
    if (!(a >= lo && b <= hi && a <= b) || (whole && (a != floor(a) || b != floor(b)))) return -1;
    for (double x = a; x <= b; x += 1) {
      if (l->n == BENCH_LIST_MAX) return -1;
      l->v[l->n++] = x;
      if (!whole) break;
    }
    if (*p == ',') p++;
    else if (*p) return -1;
  }
  return l->n > 0 ? 0 : -1;
}

