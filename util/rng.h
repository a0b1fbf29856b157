/* rng.h -- a small deterministic pseudo-random generator (xoshiro256**). */
#ifndef RNG_H
#define RNG_H

#include <stdint.h>

/* The same seed gives the same sequence on every platform. */
typedef struct { uint64_t s[4]; } rng;

void     rng_seed(rng *r, uint64_t seed);
uint64_t rng_next(rng *r);
double   rng_uniform(rng *r);              /* in [0, 1), 53 random bits */
int      rng_int(rng *r, int lo, int hi);  /* uniform in [lo, hi] */

#endif
