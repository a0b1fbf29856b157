/* stats.c -- stats_of (stats.h). */
#include "stats.h"

#include <math.h>

stats stats_of(const double *v, int n, MPI_Comm comm) {
  double lo = v[0], hi = v[0], sum = 0, sq = 0;
  for (int i = 0; i < n; i++) {
    if (v[i] < lo) lo = v[i];
    if (v[i] > hi) hi = v[i];
    sum += v[i];
    sq += v[i] * v[i];
  }
  double in[2] = {sum, sq}, out[2];
  int all;
  stats s;
  MPI_Allreduce(&lo, &s.min, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(&hi, &s.max, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(in, out, 2, MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(&n, &all, 1, MPI_INT, MPI_SUM, comm);
  s.mean = out[0] / all;
  s.norm = sqrt(out[1]);
  return s;
}
