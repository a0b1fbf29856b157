/* funcs.h -- the list of MPI functions as data (from mpi_funcs.h), and the hook every function
 * tilesim does not implement calls.
 *
 * Not for programs.  funcs.c defines each unimplemented function of
 * mpi_funcs.h as a stub that calls funcs_unimplemented, and the PMPI_ name
 * of each of those; pmpi.c defines the PMPI_ name of each implemented one. */
#ifndef TSMPI_FUNCS_H
#define TSMPI_FUNCS_H

/* Stop the run: the calling rank called `name` ("MPI_Comm_spawn"), which
 * tilesim does not implement.  In a rank: mp_abort(self, 1, "rank 3 called
 * MPI_Comm_spawn, which tilesim does not implement"), which the runner
 * prints after "tilesim-mpirun: " and ends the run with exit status 1.
 * Outside a rank: that line on stderr (without the rank) and exit(1). */
_Noreturn void funcs_unimplemented(const char *name);

/* One function of the list: its name ("MPI_Send"), its chapter ("P2P",
 * mpi_funcs.h says which there are) and whether tilesim implements it. */
typedef struct {
  const char *name;
  const char *chapter;
  int implemented;
} funcs_info;

extern const funcs_info funcs_table[];   /* in mpi_funcs.h's order */
extern const int funcs_n;

#endif
