/* comm_query.c -- what the other parts of the MPI layer ask of a communicator
 * (core.h): its rank, size and name, its topology, the holds of nonblocking
 * collectives and their tags. */
#include "mpi/core.h"

#include <stdio.h>

#include "mpi/comm.h"
#include "mpi/err.h"
#include "mpi/topo.h"

void tsmpi_comm_hold(MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_comm_hold");
  tsm_comm_must(R, comm, "tsmpi_comm_hold")->holds++;
}

void tsmpi_comm_release(MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_comm_release");
  tsm_comm *c = tsm_comm_must(R, comm, "tsmpi_comm_release");
  if (--c->holds == 0 && c->freed) tsm_comm_end(R, &comm);
}

int tsmpi_comm_nbc_tag(MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_comm_nbc_tag");
  tsm_comm *c = tsm_comm_must(R, comm, "tsmpi_comm_nbc_tag");
  unsigned span = TSMPI_COLL_TAG_MAX - TSMPI_NBC_TAG_MIN + 1;
  return TSMPI_NBC_TAG_MIN + (int)(c->nbc_seq++ % span);
}

/* ==== a communicator's process topology ================================== */

struct tsmpi_topo *tsmpi_comm_topo(MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_comm_topo");
  return tsm_comm_must(R, comm, "tsmpi_comm_topo")->topo;
}

void tsmpi_comm_set_topo(MPI_Comm comm, struct tsmpi_topo *t) {
  tsm *R = tsm_need("tsmpi_comm_set_topo");
  tsm_comm *c = tsm_comm_must(R, comm, "tsmpi_comm_set_topo");
  tsmpi_topo_unref(c->topo);
  c->topo = t;
}

/* ==== communicators ======================================================= */

int tsmpi_comm_check(MPI_Comm comm, const char *fn) {
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  return tsm_check_comm(R, comm, fn, &c);
}

int tsmpi_comm_rank(MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_comm_rank");
  return tsm_comm_must(R, comm, "tsmpi_comm_rank")->rank;
}

int tsmpi_comm_size(MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_comm_size");
  return tsm_comm_lsize(tsm_comm_must(R, comm, "tsmpi_comm_size"));
}

int tsmpi_comm_inter(MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_comm_inter");
  if (comm == MPI_COMM_WORLD) return 0;
  tsm_comm *c = tsm_comm_get(R, comm);
  return c && c->inter;
}

int tsmpi_comm_remote_size(MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_comm_remote_size");
  return tsm_comm_must(R, comm, "tsmpi_comm_remote_size")->size;
}

int tsmpi_comm_world_rank(MPI_Comm comm, int r) {
  tsm *R = tsm_need("tsmpi_comm_world_rank");
  return tsm_world_of(tsm_comm_must(R, comm, "tsmpi_comm_world_rank"), r);
}

const char *tsmpi_comm_name(MPI_Comm comm) {
  tsm *R = tsm_need("tsmpi_comm_name");
  if (comm == MPI_COMM_NULL) return "MPI_COMM_NULL";
  tsm_comm *c = tsm_comm_get(R, comm);
  if (!c) return "an invalid communicator";
  if (c->pair < 2) return c->pair ? "MPI_COMM_SELF" : "MPI_COMM_WORLD";
  /* The words live in the communicator (its name field holds the user's). */
  snprintf(c->words, sizeof c->words, "communicator %d", c->pair);
  return c->words;
}
