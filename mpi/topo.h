/* topo.h -- a communicator's process topology (MPI 3.1 chapter 7): Cartesian, graph or
 * distributed graph, and the neighbours the neighbourhood collectives exchange with.
 *
 * Not for programs.  A topology is made by MPI_Cart_create, MPI_Cart_sub, MPI_Graph_create,
 * MPI_Dist_graph_create(_adjacent) (topo_cart.c, topo_graph.c), hangs on its communicator
 * (core.h: comm_topo), never changes, and is shared, counted, by the communicator's
 * duplicates (MPI_Comm_dup keeps it, MPI 3.1 section 7.1); it goes with the last of them.
 *
 * NEIGHBOURS (MPI 3.1 section 7.6).  Cartesian: for each dimension in turn, the rank one step
 * down then the rank one step up (MPI_Cart_shift's source and destination; MPI_PROC_NULL at the
 * edge of a non-periodic dimension), as sources and as destinations alike.  Graph: the rank's
 * neighbours in the order MPI_Graph_create was given them, as both.  Distributed graph: the
 * sources and the destinations in the order MPI_Dist_graph_neighbors returns them. */
#ifndef TSMPI_TOPO_H
#define TSMPI_TOPO_H

#include "mpi/mpi.h"

typedef struct ptopo ptopo;
struct ptopo {
  int refs;
  int kind;               /* MPI_CART, MPI_GRAPH, MPI_DIST_GRAPH */
  /* Cartesian */
  int ndims;
  int *dims, *periods;    /* ndims each */
  /* graph: the whole graph, as MPI_Graph_create's arguments */
  int nnodes;
  int *index, *edges;     /* nnodes; index[nnodes - 1] */
  /* the calling rank's neighbours: every kind (distributed graph: its own) */
  int indeg, outdeg;
  int *sources, *dests;
  int weighted;           /* distributed graph: weights given (MPI_UNWEIGHTED not) */
  int *sweights, *dweights;
};

/* A new topology of kind (counted once, zeroed), and its arrays: n ints each, from src
 * (NULL: zeros) into memory of the topology's own. */
ptopo *ptopo_new(int kind);
int *ptopo_ints(const int *src, int n);

void ptopo_ref(ptopo *t);
void ptopo_unref(ptopo *t);   /* NULL: nothing */

/* The Cartesian coordinates of rank r (t Cartesian) into coords (ndims), and back (a
 * coordinate out of its dimension is taken round a periodic one; -1 if it lies outside a
 * non-periodic one). */
void ptopo_cart_coords(const ptopo *t, int r, int *coords);
int ptopo_cart_rank(const ptopo *t, const int *coords);

/* The calling rank's (rank me of comm, of size size) neighbours of a Cartesian or graph
 * topology, filled in t's sources and dests. */
void ptopo_neighbours(ptopo *t, int me);

/* comm (checked) an intracommunicator, as a topology's constructors need:
 * else MPI_ERR_COMM raised for fn. */
int ptopo_intra_ok(MPI_Comm comm, const char *fn);

/* The topology of comm for call fn, of any kind (kind 0) or that kind; NULL and the error
 * raised (MPI_ERR_TOPOLOGY) under comm's handler in *rc if it has none, or another. */
ptopo *ptopo_of(MPI_Comm comm, const char *fn, int kind, int *rc);

#endif
