/* variant.h -- ./bench's variants of the parallel algorithm, side by
 * side with the paper's in one sweep: --variant LIST, or the cross product
 * of the --alloc, --block and --schedule lists.
 *
 * A variant is words joined by '+': an allocation (half, the paper's; size,
 * section 7.1; fit, par_fit.h), a schedule (static, the paper's; dynamic,
 * par_dynamic.h) and blockK (run-boundary costs every K diagonals,
 * par_block.h); "paper" is half+static+block1.  Its name in the CSV is the
 * words that differ from the paper's ("paper" if none), e.g. "fit",
 * "block16", "dynamic+block16".  With the dynamic schedule the allocation
 * plays no part and is left out of the name. */
#ifndef BENCH_VARIANT_H
#define BENCH_VARIANT_H

#include <stddef.h>

#include "algo/par.h"

typedef struct {
  split_alloc alloc;
  int block;             /* >= 1 */
  par_schedule sched;
} bench_variant;

enum { BENCH_VARIANTS_MAX = 64 };

/* "paper,fit,block16,dynamic+block16" into v[0 .. *n-1]: 0, or -1 with a
 * message in err. */
int bench_variant_parse(const char *list, bench_variant *v, int *n, char *err, size_t errlen);

/* The variant's name, as above. */
void bench_variant_name(const bench_variant *v, char *buf, size_t len);

#endif
