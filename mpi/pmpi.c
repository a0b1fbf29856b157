/* pmpi.c -- every function tilesim implements under its two names (MPI 3.1
 * section 14.2, the profiling interface): the library's code is PMPI_Send,
 * and MPI_Send is PMPI_Send inside mp_call_begin and mp_call_end, so that
 * the simulator's trace shows every MPI call a rank makes as a slice of its
 * track (named by the function; the outermost call only, when it took time
 * or moved a message); a program's own MPI_Send wrapper can call PMPI_Send.
 * Made from mpi_funcs.h by the preprocessor; funcs.c has the unimplemented
 * ones'; MPI_Pcontrol is here too.
 *
 * While the rank has nonblocking collectives going on (mp_set_progress),
 * each call first settles what the rank computed since its last call (an
 * mp call, where tilesim-mpirun's --compute hooks charge it), so that their
 * progress during that computing runs before the call touches the engine. */
#include "mpi/mpi.h"
#include "mp/mp.h"

/* MPI 3.1 section 14.2.4: without a profiling library, MPI_Pcontrol does nothing. */
int PMPI_Pcontrol(const int level, ...) {
  (void)level;
  return MPI_SUCCESS;
}

/* The calling rank's call begins and ends, where a trace shows it, and its
 * progress is settled first (watched_NAME, out of line: the common case,
 * untraced and not progressing or outside a rank, is one thread-local read
 * and a jump; traced is set for a whole run). */
#if defined(__GNUC__)
#define SIDE __attribute__((noinline))
#else
#define SIDE
#endif
#define TSMPI_PMPI_0(ret, name, params, args)
#define TSMPI_PMPI_1(ret, name, params, args)      \
  static SIDE ret watched_##name params {           \
    mp *self_ = mp_self_watched();                  \
    int traced_ = mp_traced(self_);                 \
    if (mp_progressing(self_)) mp_time(self_);      \
    if (traced_) mp_call_begin(self_, #name);       \
    ret r_ = P##name args;                          \
    if (traced_) mp_call_end(self_);                \
    return r_;                                      \
  }                                                 \
  ret name params {                                 \
    if (!mp_self_watched()) return P##name args;   \
    return watched_##name args;                     \
  }
#define TSMPI_FN(impl, chapter, ret, name, params, args) TSMPI_PMPI_##impl(ret, name, params, args)
#include "mpi/mpi_funcs.h"
#undef TSMPI_FN
