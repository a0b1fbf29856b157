/* funcs.c -- the list as data, the unimplemented-call hook, and the stubs of every function
 * tilesim does not implement, with their PMPI_ names (funcs.h).  The stubs are made from
 * mpi_funcs.h by the preprocessor: the list is the only place to edit. */
#include "mpi/funcs.h"

#include <stdio.h>
#include <stdlib.h>

#include "mp/mp.h"
#include "mpi/mpi.h"

const funcs_info funcs_table[] = {
#define TSMPI_FN(impl, chapter, ret, name, params, args) {#name, #chapter, impl},
#include "mpi/mpi_funcs.h"
#undef TSMPI_FN
};
const int funcs_n = (int)(sizeof funcs_table / sizeof funcs_table[0]);

void funcs_unimplemented(const char *name) {
  char why[200];
  mp *self = mp_self();
  if (self) {
    snprintf(why, sizeof why, "rank %d called %s, which tilesim does not implement", mp_rank(self), name);
    mp_abort(self, 1, why);
  }
  fprintf(stderr, "tilesim: %s was called, which tilesim does not implement\n", name);
  exit(1);
}

/* A stub's parameters are unused; it never returns, so it returns nothing. */
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#define TSMPI_STUB_1(ret, name, params)
#define TSMPI_STUB_0(ret, name, params)                  \
  ret name params { funcs_unimplemented(#name); }        \
  ret P##name params { funcs_unimplemented(#name); }
#define TSMPI_FN(impl, chapter, ret, name, params, args) TSMPI_STUB_##impl(ret, name, params)
#include "mpi/mpi_funcs.h"
#undef TSMPI_FN
