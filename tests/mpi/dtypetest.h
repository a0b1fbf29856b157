/* dtypetest.h -- a check the datatype programs of tests/mpi/ share (plain
 * MPI C, header only, like mtest.h). */
#ifndef DTYPETEST_H
#define DTYPETEST_H

#include <mpi.h>

#include "mtest.h"

/* size, lb, extent, true lb, true extent of dt against the expected. */
static inline void shape(mtest *t, const char *what, MPI_Datatype dt, int size, MPI_Aint lb, MPI_Aint extent,
                         MPI_Aint tlb, MPI_Aint textent) {
  int s;
  MPI_Aint l, e, tl, te;
  MPI_Type_size(dt, &s);
  MPI_Type_get_extent(dt, &l, &e);
  MPI_Type_get_true_extent(dt, &tl, &te);
  MCHECK(t, s == size && l == lb && e == extent && tl == tlb && te == textent,
         "%s: size %d lb %ld extent %ld true %ld %ld; want %d %ld %ld %ld %ld", what, s, (long)l, (long)e, (long)tl,
         (long)te, size, (long)lb, (long)extent, (long)tlb, (long)textent);
}

#endif
