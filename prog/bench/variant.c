/* variant.c -- variant names for ./bench (variant.h). */
#include "prog/bench/variant.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int word(const char *w, bench_variant *v) {
  if (strcmp(w, "paper") == 0) return 0;
  if (split_alloc_parse(w, &v->alloc) == 0) return 0;
  if (par_schedule_parse(w, &v->sched) == 0) return 0;
  if (strncmp(w, "block", 5) == 0 && w[5] >= '1' && w[5] <= '9') {
    char *end;
    long k = strtol(w + 5, &end, 10);
    if (*end == 0 && k >= 1 && k <= 1 << 20) {
      v->block = (int)k;
      return 0;
    }
  }
  return -1;
}

int bench_variant_parse(const char *list, bench_variant *v, int *n, char *err, size_t errlen) {
  char buf[1024];
  *n = 0;
  if (strlen(list) >= sizeof buf) {
    snprintf(err, errlen, "--variant: the list is too long");
    return -1;
  }
  snprintf(buf, sizeof buf, "%s", list);
  for (char *item = buf, *next; item; item = next) {
    next = strchr(item, ',');
    if (next) *next++ = 0;
    if (*n == BENCH_VARIANTS_MAX) {
      snprintf(err, errlen, "--variant: more than %d variants", BENCH_VARIANTS_MAX);
      return -1;
    }
    bench_variant x = {ALLOC_HALF, 1, PAR_STATIC};
    for (char *w = item, *wn; w; w = wn) {
      wn = strchr(w, '+');
      if (wn) *wn++ = 0;
      if (word(w, &x) != 0) {
        snprintf(err, errlen,
                 "--variant takes variants like paper, fit, size, block16, dynamic, dynamic+block16 (%s)",
                 *w ? w : list);
        return -1;
      }
    }
    v[(*n)++] = x;
  }
  return 0;
}

void bench_variant_name(const bench_variant *v, char *buf, size_t len) {
  size_t k = 0;
  buf[0] = 0;
  if (v->sched == PAR_DYNAMIC) k += (size_t)snprintf(buf + k, len - k, "dynamic");
  else if (v->alloc != ALLOC_HALF) k += (size_t)snprintf(buf + k, len - k, "%s", split_alloc_name(v->alloc));
  if (v->block > 1 && k < len) k += (size_t)snprintf(buf + k, len - k, "%sblock%d", k ? "+" : "", v->block);
  if (k == 0) snprintf(buf, len, "paper");
}
