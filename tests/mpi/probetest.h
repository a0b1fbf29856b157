/* probetest.h -- the messages the probe programs (p2p_probe, p2p_mprobe)
 * take apart: plain MPI C, header only, like mtest.h. */
#ifndef PROBETEST_H
#define PROBETEST_H

#include <mpi.h>
#include <stdlib.h>

#include "mtest.h"

/* Every rank but 0 sends rank 0, on comm, 3 * rank ints of its rank with
 * its rank as tag, and answers 0; rank 0 sends nothing and answers 1 (it is
 * to receive them). */
static inline int probetest_send(const mtest *t, MPI_Comm comm) {
  if (t->rank == 0) return 1;
  int n = 3 * t->rank, *v = malloc((size_t)n * sizeof *v);
  for (int i = 0; i < n; i++) v[i] = t->rank;
  MPI_Send(v, n, MPI_INT, 0, t->rank, comm);
  free(v);
  return 0;
}

#endif
