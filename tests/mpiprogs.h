/* mpiprogs.h -- the programs of tests/mpi/ as their drivers (test_mpiprogs,
 * test_mpiprogs_p2p) link them: each main renamed tsmpi_main_NAME (the
 * Makefile), all of them listed in the generated progs.h; progs[] names
 * them, in that order. */
#ifndef MPIPROGS_H
#define MPIPROGS_H

#include "tests/mpiharness.h"

#define TSMPI_PROG(name) int tsmpi_main_##name(int argc, char **argv);
#include "progs.h"
#undef TSMPI_PROG

static const struct {
  const char *name;
  mpih_main fn;
} progs[] = {
#define TSMPI_PROG(name) {#name, tsmpi_main_##name},
#include "progs.h"
#undef TSMPI_PROG
};
enum { NPROGS = sizeof progs / sizeof progs[0] };

#endif
