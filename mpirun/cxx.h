/* cxx.h -- the C++ runtime as a rank of an MPI program sees it: the
 * standard clocks and sleeps of the simulated machine, and exceptions in
 * flight that stay the rank's own.
 *
 * The loader binds the program's references to libstdc++'s
 * std::chrono::system_clock::now, steady_clock::now and
 * std::this_thread::sleep_for's out-of-line part to the functions here, as
 * it binds libc's time and nanosleep (mpirun/libc.h).  On the simulator all
 * the ranks share one thread, and with it libstdc++'s per-thread record of
 * the exceptions caught and not yet finished (what `throw;` rethrows) and of
 * the uncaught ones: cxx_ranks_begin keeps one record per rank, taken from
 * the thread when the rank makes a call of the machine (where it may be
 * switched out) and given back when the call returns (mp.h's hooks). */
#ifndef TSMPI_CXX_H
#define TSMPI_CXX_H

#include "mpirun/libc.h"
#include "mp/mp.h"

/* What the program's reference to `name` binds to in libstdc++'s place: 1
 * and *fn, or 0 for a name that stays the library's. */
int cxx_bind(const char *name, rlibc_fn *fn);

/* One exception record per rank for n ranks that share the calling thread
 * (the simulator), get_globals being libstdc++'s __cxa_get_globals; until
 * cxx_ranks_end.  Call before the run, on the thread that runs it.  The
 * hooks to install (mp_set_hooks): enter takes the rank's record off the
 * thread, leave puts it back; a runtime with hooks of its own calls these
 * first on entering and last on leaving (its own may switch ranks). */
const mp_hooks *cxx_ranks_begin(int n, void *(*get_globals)(void));
void cxx_ranks_end(void);

#endif
