/* pmpi.c -- the PMPI_ name of every function tilesim implements (MPI 3.1 section 14.2, the
 * profiling interface): PMPI_Send calls MPI_Send, so a program's own MPI_Send wrapper can call
 * the library's.  Made from mpi_funcs.h by the preprocessor; funcs.c has the unimplemented
 * ones'; MPI_Pcontrol is here too. */
#include "mpi.h"

/* MPI 3.1 section 14.2.4: without a profiling library, MPI_Pcontrol does nothing. */
int MPI_Pcontrol(const int level, ...) {
  (void)level;
  return MPI_SUCCESS;
}

#define TSMPI_PMPI_0(ret, name, params, args)
#define TSMPI_PMPI_1(ret, name, params, args) \
  ret P##name params { return name args; }
#define TSMPI_FN(impl, chapter, ret, name, params, args) TSMPI_PMPI_##impl(ret, name, params, args)
#include "mpi_funcs.h"
#undef TSMPI_FN
