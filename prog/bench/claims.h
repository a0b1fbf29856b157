/* bench_claims.h -- ./bench --claims: the paper's seven claims (sections 6
 * and 7), checked against the sweeps' CSV. */
#ifndef BENCH_CLAIMS_H
#define BENCH_CLAIMS_H

/* The whole command line (argv[1] is --claims); the exit status. */
int bench_claims(int argc, char **argv);

#endif
