/* comm_query.c -- what the other parts of the MPI layer ask of a communicator
 * (core.h): its rank, size and name, its topology, the holds of nonblocking
 * collectives and their tags. */
#include "mpi/core.h"

#include <stdio.h>

#include "mpi/comm.h"
#include "mpi/err.h"
#include "mpi/topo.h"

void comm_hold(MPI_Comm comm) {
  st_rank *R = st_need("comm_hold");
  st_comm_must(R, comm, "comm_hold")->holds++;
}

void comm_release(MPI_Comm comm) {
  st_rank *R = st_need("comm_release");
  st_comm *c = st_comm_must(R, comm, "comm_release");
  if (--c->holds == 0 && c->freed) comm_end(R, &comm);
}

int comm_nbc_tag(MPI_Comm comm) {
  st_rank *R = st_need("comm_nbc_tag");
  st_comm *c = st_comm_must(R, comm, "comm_nbc_tag");
  unsigned span = COLL_TAG_MAX - NBC_TAG_MIN + 1;
  return NBC_TAG_MIN + (int)(c->nbc_seq++ % span);
}

/* ==== a communicator's process topology ================================== */

struct ptopo *comm_topo(MPI_Comm comm) {
  st_rank *R = st_need("comm_topo");
  return st_comm_must(R, comm, "comm_topo")->topo;
}

void comm_set_topo(MPI_Comm comm, struct ptopo *t) {
  st_rank *R = st_need("comm_set_topo");
  st_comm *c = st_comm_must(R, comm, "comm_set_topo");
  ptopo_unref(c->topo);
  c->topo = t;
}

/* ==== communicators ======================================================= */

int comm_check(MPI_Comm comm, const char *fn) {
  st_rank *R = st_need(fn);
  st_comm *c;
  return err_check_comm(R, comm, fn, &c);
}

int comm_rank(MPI_Comm comm) {
  st_rank *R = st_need("comm_rank");
  return st_comm_must(R, comm, "comm_rank")->rank;
}

int comm_size(MPI_Comm comm) {
  st_rank *R = st_need("comm_size");
  return st_comm_lsize(st_comm_must(R, comm, "comm_size"));
}

int comm_inter(MPI_Comm comm) {
  st_rank *R = st_need("comm_inter");
  if (comm == MPI_COMM_WORLD) return 0;
  st_comm *c = st_comm_get(R, comm);
  return c && c->inter;
}

int comm_remote_size(MPI_Comm comm) {
  st_rank *R = st_need("comm_remote_size");
  return st_comm_must(R, comm, "comm_remote_size")->size;
}

int comm_world_rank(MPI_Comm comm, int r) {
  st_rank *R = st_need("comm_world_rank");
  return st_world_of(st_comm_must(R, comm, "comm_world_rank"), r);
}

const char *comm_get_name(MPI_Comm comm) {
  st_rank *R = st_need("comm_get_name");
  if (comm == MPI_COMM_NULL) return "MPI_COMM_NULL";
  st_comm *c = st_comm_get(R, comm);
  if (!c) return "an invalid communicator";
  if (c->pair < 2) return c->pair ? "MPI_COMM_SELF" : "MPI_COMM_WORLD";
  /* The words live in the communicator (its name field holds the user's). */
  snprintf(c->words, sizeof c->words, "communicator %d", c->pair);
  return c->words;
}
