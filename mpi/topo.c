/* topo.c -- process topologies: their objects, coordinates and neighbours, MPI_Topo_test
 * (topo.h). */
#include "mpi/topo.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/core.h"

static void oom(void) {
  fprintf(stderr, "tilesim MPI: a process topology: out of memory\n");
  abort();
}

tsmpi_topo *tsmpi_topo_new(int kind) {
  tsmpi_topo *t = calloc(1, sizeof *t);
  if (!t) oom();
  t->refs = 1;
  t->kind = kind;
  return t;
}

int *tsmpi_topo_ints(const int *src, int n) {
  int *p = calloc(n > 0 ? (size_t)n : 1, sizeof *p);
  if (!p) oom();
  if (src && n > 0) memcpy(p, src, (size_t)n * sizeof *p);
  return p;
}

void tsmpi_topo_ref(tsmpi_topo *t) { t->refs++; }

void tsmpi_topo_unref(tsmpi_topo *t) {
  if (!t || --t->refs > 0) return;
  free(t->dims);
  free(t->periods);
  free(t->index);
  free(t->edges);
  free(t->sources);
  free(t->dests);
  free(t->sweights);
  free(t->dweights);
  free(t);
}

/* Row-major: the last dimension varies fastest (MPI 3.1 section 7.5.1). */
void tsmpi_cart_coords(const tsmpi_topo *t, int r, int *coords) {
  for (int d = t->ndims - 1; d >= 0; d--) {
    coords[d] = r % t->dims[d];
    r /= t->dims[d];
  }
}

int tsmpi_cart_rank(const tsmpi_topo *t, const int *coords) {
  int r = 0;
  for (int d = 0; d < t->ndims; d++) {
    int c = coords[d], n = t->dims[d];
    if (c < 0 || c >= n) {
      if (!t->periods[d]) return -1;
      c %= n;
      if (c < 0) c += n;
    }
    r = r * n + c;
  }
  return r;
}

void tsmpi_topo_neighbours(tsmpi_topo *t, int me) {
  if (t->kind == MPI_CART) {
    int n = 2 * t->ndims, *c = tsmpi_topo_ints(NULL, t->ndims);
    t->indeg = t->outdeg = n;
    t->sources = tsmpi_topo_ints(NULL, n);
    for (int d = 0; d < t->ndims; d++) {
      for (int k = 0; k < 2; k++) {
        tsmpi_cart_coords(t, me, c);
        c[d] += k ? 1 : -1;
        int r = tsmpi_cart_rank(t, c);
        t->sources[2 * d + k] = r < 0 ? MPI_PROC_NULL : r;
      }
    }
    free(c);
  } else {
    int lo = me ? t->index[me - 1] : 0, n = t->index[me] - lo;
    t->indeg = t->outdeg = n;
    t->sources = tsmpi_topo_ints(t->edges + lo, n);
  }
  t->dests = tsmpi_topo_ints(t->sources, t->outdeg);
}

int tsmpi_topo_intra_ok(MPI_Comm comm, const char *fn) {
  if (!tsmpi_comm_inter(comm)) return MPI_SUCCESS;
  return tsmpi_raise(comm, MPI_ERR_COMM, fn, "%s is an intercommunicator", tsmpi_comm_name(comm));
}

tsmpi_topo *tsmpi_topo_of(MPI_Comm comm, const char *fn, int kind, int *rc) {
  static const char *const names[] = {"", "graph", "Cartesian", "distributed graph"};
  tsmpi_topo *t = tsmpi_comm_topo(comm);
  if (t && (!kind || t->kind == kind)) {
    *rc = MPI_SUCCESS;
    return t;
  }
  if (!t)
    *rc = tsmpi_raise(comm, MPI_ERR_TOPOLOGY, fn, "%s has no process topology", tsmpi_comm_name(comm));
  else
    *rc = tsmpi_raise(comm, MPI_ERR_TOPOLOGY, fn, "%s has a %s topology, not a %s one", tsmpi_comm_name(comm),
                      names[t->kind], names[kind]);
  return NULL;
}

int PMPI_Topo_test(MPI_Comm comm, int *status) {
  static const char fn[] = "MPI_Topo_test";
  int rc = tsmpi_comm_check(comm, fn);
  if (rc) return rc;
  if (!status) return tsmpi_raise(comm, MPI_ERR_ARG, fn, "NULL status argument");
  tsmpi_topo *t = tsmpi_comm_topo(comm);
  *status = t ? t->kind : MPI_UNDEFINED;
  return MPI_SUCCESS;
}
