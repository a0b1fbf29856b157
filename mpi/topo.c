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

ptopo *ptopo_new(int kind) {
  ptopo *t = calloc(1, sizeof *t);
  if (!t) oom();
  t->refs = 1;
  t->kind = kind;
  return t;
}

int *ptopo_ints(const int *src, int n) {
  int *p = calloc(n > 0 ? (size_t)n : 1, sizeof *p);
  if (!p) oom();
  if (src && n > 0) memcpy(p, src, (size_t)n * sizeof *p);
  return p;
}

void ptopo_ref(ptopo *t) { t->refs++; }

void ptopo_unref(ptopo *t) {
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
void ptopo_cart_coords(const ptopo *t, int r, int *coords) {
  for (int d = t->ndims - 1; d >= 0; d--) {
    coords[d] = r % t->dims[d];
    r /= t->dims[d];
  }
}

int ptopo_cart_rank(const ptopo *t, const int *coords) {
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

void ptopo_neighbours(ptopo *t, int me) {
  if (t->kind == MPI_CART) {
    int n = 2 * t->ndims, *c = ptopo_ints(NULL, t->ndims);
    t->indeg = t->outdeg = n;
    t->sources = ptopo_ints(NULL, n);
    for (int d = 0; d < t->ndims; d++) {
      for (int k = 0; k < 2; k++) {
        ptopo_cart_coords(t, me, c);
        c[d] += k ? 1 : -1;
        int r = ptopo_cart_rank(t, c);
        t->sources[2 * d + k] = r < 0 ? MPI_PROC_NULL : r;
      }
    }
    free(c);
  } else {
    int lo = me ? t->index[me - 1] : 0, n = t->index[me] - lo;
    t->indeg = t->outdeg = n;
    t->sources = ptopo_ints(t->edges + lo, n);
  }
  t->dests = ptopo_ints(t->sources, t->outdeg);
}

int ptopo_intra_ok(MPI_Comm comm, const char *fn) {
  if (!comm_inter(comm)) return MPI_SUCCESS;
  return err_comm_raise(comm, MPI_ERR_COMM, fn, "%s is an intercommunicator", comm_get_name(comm));
}

ptopo *ptopo_of(MPI_Comm comm, const char *fn, int kind, int *rc) {
  static const char *const names[] = {"", "graph", "Cartesian", "distributed graph"};
  ptopo *t = comm_topo(comm);
  if (t && (!kind || t->kind == kind)) {
    *rc = MPI_SUCCESS;
    return t;
  }
  if (!t)
    *rc = err_comm_raise(comm, MPI_ERR_TOPOLOGY, fn, "%s has no process topology", comm_get_name(comm));
  else
    *rc = err_comm_raise(comm, MPI_ERR_TOPOLOGY, fn, "%s has a %s topology, not a %s one", comm_get_name(comm),
                         names[t->kind], names[kind]);
  return NULL;
}

int PMPI_Topo_test(MPI_Comm comm, int *status) {
  static const char fn[] = "MPI_Topo_test";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  if (!status) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL status argument");
  ptopo *t = comm_topo(comm);
  *status = t ? t->kind : MPI_UNDEFINED;
  return MPI_SUCCESS;
}
