/* coll_opt.c -- the run's choice of collective algorithms: names, --coll, the setting
 * (settings.h, coll.h). */
#include <stdio.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/settings.h"

static const char *const coll_names[COLL_N] = {
  "barrier", "bcast", "reduce", "allreduce", "gather", "gatherv", "scatter", "scatterv", "allgather",
  "allgatherv", "alltoall", "alltoallv", "scan", "exscan", "reduce_scatter", "reduce_scatter_block", "alltoallw",
  "neighbor_allgather", "neighbor_allgatherv", "neighbor_alltoall", "neighbor_alltoallv", "neighbor_alltoallw"};

/* MPICH's names (its MPIR_CVAR_<COLL>_INTRA_ALGORITHM values). */
static const char *const alg_names[ALG_N] = {
  "auto", "linear", "dissemination", "binomial", "scatter_recursive_doubling_allgather",
  "scatter_ring_allgather", "recursive_doubling", "reduce_scatter_allgather", "reduce_scatter_gather",
  "brucks", "ring", "scattered", "pairwise", "pairwise_sendrecv_replace", "recursive_halving",
  "noncommutative"};

/* Each collective's algorithms, ALG_N-terminated (auto and linear first). */
#define ALGS(...) {ALG_AUTO, ALG_LINEAR, __VA_ARGS__, ALG_N}
static const coll_alg coll_algs[COLL_N][8] = {
  [COLL_BARRIER] = ALGS(ALG_DISSEMINATION),
  [COLL_BCAST] = ALGS(ALG_BINOMIAL, ALG_SCATTER_RECURSIVE_DOUBLING_ALLGATHER, ALG_SCATTER_RING_ALLGATHER),
  [COLL_REDUCE] = ALGS(ALG_BINOMIAL, ALG_REDUCE_SCATTER_GATHER),
  [COLL_ALLREDUCE] = ALGS(ALG_RECURSIVE_DOUBLING, ALG_REDUCE_SCATTER_ALLGATHER),
  [COLL_GATHER] = ALGS(ALG_BINOMIAL),
  [COLL_GATHERV] = {ALG_AUTO, ALG_LINEAR, ALG_N},
  [COLL_SCATTER] = ALGS(ALG_BINOMIAL),
  [COLL_SCATTERV] = {ALG_AUTO, ALG_LINEAR, ALG_N},
  [COLL_ALLGATHER] = ALGS(ALG_RECURSIVE_DOUBLING, ALG_BRUCKS, ALG_RING),
  [COLL_ALLGATHERV] = ALGS(ALG_RECURSIVE_DOUBLING, ALG_BRUCKS, ALG_RING),
  [COLL_ALLTOALL] = ALGS(ALG_BRUCKS, ALG_SCATTERED, ALG_PAIRWISE, ALG_PAIRWISE_SENDRECV_REPLACE),
  [COLL_ALLTOALLV] = ALGS(ALG_SCATTERED, ALG_PAIRWISE_SENDRECV_REPLACE),
  [COLL_SCAN] = ALGS(ALG_RECURSIVE_DOUBLING),
  [COLL_EXSCAN] = ALGS(ALG_RECURSIVE_DOUBLING),
  [COLL_REDUCE_SCATTER] = ALGS(ALG_RECURSIVE_HALVING, ALG_PAIRWISE, ALG_RECURSIVE_DOUBLING, ALG_NONCOMMUTATIVE),
  [COLL_REDUCE_SCATTER_BLOCK] = ALGS(ALG_RECURSIVE_HALVING, ALG_PAIRWISE, ALG_RECURSIVE_DOUBLING,
                                     ALG_NONCOMMUTATIVE),
  [COLL_ALLTOALLW] = ALGS(ALG_SCATTERED, ALG_PAIRWISE_SENDRECV_REPLACE),
  [COLL_NEIGHBOR_ALLGATHER] = {ALG_AUTO, ALG_LINEAR, ALG_N},
  [COLL_NEIGHBOR_ALLGATHERV] = {ALG_AUTO, ALG_LINEAR, ALG_N},
  [COLL_NEIGHBOR_ALLTOALL] = {ALG_AUTO, ALG_LINEAR, ALG_N},
  [COLL_NEIGHBOR_ALLTOALLV] = {ALG_AUTO, ALG_LINEAR, ALG_N},
  [COLL_NEIGHBOR_ALLTOALLW] = {ALG_AUTO, ALG_LINEAR, ALG_N},
};

/* The run's setting: written before the ranks start (coll_option),
 * only read while they run, so ranks that are threads share it safely. */
static coll_alg setting[COLL_N];

const char *coll_name(coll_id c) { return coll_names[c]; }
const char *coll_alg_name(coll_alg a) { return alg_names[a]; }
coll_alg coll_setting(coll_id c) { return setting[c]; }

void coll_reset(void) {
  for (int c = 0; c < COLL_N; c++) setting[c] = ALG_AUTO;
}

static int has(coll_id c, coll_alg a) {
  for (int i = 0; coll_algs[c][i] != ALG_N; i++)
    if (coll_algs[c][i] == a) return 1;
  return 0;
}

/* The collective's algorithms as "linear, binomial, ..." into buf. */
static void list(coll_id c, char *buf, size_t len, const char *sep) {
  size_t n = 0;
  buf[0] = '\0';
  for (int i = 0; coll_algs[c][i] != ALG_N && n < len; i++)
    n += (size_t)snprintf(buf + n, len - n, "%s%s", i ? sep : "", alg_names[coll_algs[c][i]]);
}

int coll_option(const char *spec, char *err, size_t errlen) {
  coll_alg next[COLL_N];
  memcpy(next, setting, sizeof next);
  const char *p = spec;
  for (;;) {
    const char *end = strchr(p, ',');
    size_t n = end ? (size_t)(end - p) : strlen(p);
    char item[96];
    if (n == 0 || n >= sizeof item) {
      snprintf(err, errlen, "--coll: %s item in '%s'", n ? "a too long" : "an empty", spec);
      return -1;
    }
    memcpy(item, p, n);
    item[n] = '\0';
    char *eq = strchr(item, '=');
    if (!eq) {
      if (strcmp(item, "mpich") && strcmp(item, "linear")) {
        snprintf(err, errlen, "--coll: '%s' is neither mpich, linear nor COLL=ALGORITHM", item);
        return -1;
      }
      for (int c = 0; c < COLL_N; c++) next[c] = item[0] == 'm' ? ALG_AUTO : ALG_LINEAR;
    } else {
      *eq = '\0';
      int c, a;
      for (c = 0; c < COLL_N && strcmp(item, coll_names[c]); c++)
        ;
      if (c == COLL_N) {
        snprintf(err, errlen, "--coll: no collective '%s' (--coll help lists them)", item);
        return -1;
      }
      for (a = 0; a < ALG_N && strcmp(eq + 1, alg_names[a]); a++)
        ;
      if (a == ALG_N || !has((coll_id)c, (coll_alg)a)) {
        char algs[256];
        list((coll_id)c, algs, sizeof algs, ", ");
        snprintf(err, errlen, "--coll: %s has no algorithm '%s' (%s)", item, eq + 1, algs);
        return -1;
      }
      next[c] = (coll_alg)a;
    }
    if (!end) break;
    p = end + 1;
  }
  memcpy(setting, next, sizeof setting);
  return 0;
}

void coll_usage(FILE *out) {
  for (int c = 0; c < COLL_N; c++) {
    char algs[256];
    list((coll_id)c, algs, sizeof algs, " ");
    fprintf(out, "%s: %s\n", coll_names[c], algs);
  }
}
