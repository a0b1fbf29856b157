/* group.h -- groups: handles for sets of ranks (state.h's tsm_ranks), and
 * the MPI_Group_* calls. */
#ifndef TSMPI_GROUP_H
#define TSMPI_GROUP_H

#include "mpi/state.h"

/* The ranks a group handle of R names (MPI_GROUP_EMPTY included), or NULL
 * (MPI_GROUP_NULL, freed, not a group). */
tsm_ranks *tsm_group_get(tsm *R, MPI_Group group);

/* A new group handle of R for g, whose count it takes over. */
MPI_Group tsm_group_add(tsm *R, tsm_ranks *g);

/* Same ranks in the same order: 2; the same ranks in another order: 1;
 * else 0. */
int tsm_ranks_same(const tsm_ranks *a, const tsm_ranks *b);

#endif
