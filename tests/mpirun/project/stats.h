/* stats.h -- the statistics of a distributed array (a project's module). */
#ifndef STATS_H
#define STATS_H

#include <mpi.h>

typedef struct {
  double min, max, mean, norm;
} stats;

/* Over every rank's n values. */
stats stats_of(const double *v, int n, MPI_Comm comm);

#endif
