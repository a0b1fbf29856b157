/* group.h -- groups: handles for sets of ranks (state.h's st_ranks), and
 * the MPI_Group_* calls. */
#ifndef TSMPI_GROUP_H
#define TSMPI_GROUP_H

#include "mpi/state.h"

/* The ranks a group handle of R names (MPI_GROUP_EMPTY included), or NULL
 * (MPI_GROUP_NULL, freed, not a group). */
st_ranks *group_get(st_rank *R, MPI_Group group);

/* A new group handle of R for g, whose count it takes over. */
MPI_Group group_add(st_rank *R, st_ranks *g);

/* Same ranks in the same order: 2; the same ranks in another order: 1;
 * else 0. */
int group_ranks_same(const st_ranks *a, const st_ranks *b);

#endif
