/* topo_graph.c -- graph and distributed graph topologies (MPI 3.1 sections 7.5.3, 7.5.4,
 * 7.5.5): MPI_Graph_create, MPI_Graph_get, MPI_Graphdims_get, MPI_Graph_neighbors(_count),
 * MPI_Graph_map, MPI_Dist_graph_create(_adjacent), MPI_Dist_graph_neighbors(_count) (mpi.h;
 * topo.h).
 *
 * As topo_cart.c: never reordered (reorder and the info hints are accepted and change nothing);
 * MPI_Graph_create splits the old communicator (ranks beyond nnodes get MPI_COMM_NULL), the
 * distributed graphs duplicate it.  MPI_Dist_graph_create gives every rank the edges that
 * start or end at it with an all-to-all of the counts and one of the edges on the old
 * communicator; a rank's sources (destinations) are then in the order of the ranks that gave
 * them, and of the edges each gave. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/core.h"
#include "mpi/topo.h"

/* ==== graphs ============================================================== */

/* The checks of a graph's arguments for fn on comm. */
static int graph_ok(MPI_Comm comm, const char *fn, int nnodes, const int *index, const int *edges) {
  if (nnodes < 0) return err_comm_raise(comm, MPI_ERR_ARG, fn, "nnodes %d < 0", nnodes);
  if (nnodes > comm_size(comm))
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "the graph has %d nodes, %s only %d ranks", nnodes,
                          comm_get_name(comm), comm_size(comm));
  if (nnodes == 0) return MPI_SUCCESS;
  if (!index) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL index argument");
  for (int i = 0; i < nnodes; i++)
    if (index[i] < (i ? index[i - 1] : 0))
      return err_comm_raise(comm, MPI_ERR_ARG, fn, "index[%d] = %d is less than the one before", i, index[i]);
  if (index[nnodes - 1] > 0 && !edges) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL edges argument");
  for (int k = 0; k < index[nnodes - 1]; k++)
    if (edges[k] < 0 || edges[k] >= nnodes)
      return err_comm_raise(comm, MPI_ERR_ARG, fn, "edges[%d] = %d is not a node (0 .. %d)", k, edges[k], nnodes - 1);
  return MPI_SUCCESS;
}

int PMPI_Graph_create(MPI_Comm comm_old, int nnodes, const int indx[], const int edges[], int reorder,
                     MPI_Comm *comm_graph) {
  static const char fn[] = "MPI_Graph_create";
  int rc;
  (void)reorder;
  if ((rc = comm_check(comm_old, fn)) || (rc = ptopo_intra_ok(comm_old, fn)) ||
      (rc = graph_ok(comm_old, fn, nnodes, indx, edges)))
    return rc;
  if (!comm_graph) return err_comm_raise(comm_old, MPI_ERR_ARG, fn, "NULL comm_graph argument");
  int me = comm_rank(comm_old);
  if ((rc = PMPI_Comm_split(comm_old, me < nnodes ? 0 : MPI_UNDEFINED, me, comm_graph))) return rc;
  if (*comm_graph == MPI_COMM_NULL) return MPI_SUCCESS;
  ptopo *t = ptopo_new(MPI_GRAPH);
  t->nnodes = nnodes;
  t->index = ptopo_ints(indx, nnodes);
  t->edges = ptopo_ints(edges, indx[nnodes - 1]);
  ptopo_neighbours(t, me);
  comm_set_topo(*comm_graph, t);
  return MPI_SUCCESS;
}

int PMPI_Graph_map(MPI_Comm comm, int nnodes, const int indx[], const int edges[], int *newrank) {
  static const char fn[] = "MPI_Graph_map";
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = graph_ok(comm, fn, nnodes, indx, edges))) return rc;
  if (!newrank) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL newrank argument");
  int me = comm_rank(comm);
  *newrank = me < nnodes ? me : MPI_UNDEFINED;
  return MPI_SUCCESS;
}

int PMPI_Graphdims_get(MPI_Comm comm, int *nnodes, int *nedges) {
  static const char fn[] = "MPI_Graphdims_get";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_GRAPH, &rc);
  if (!t) return rc;
  if (!nnodes || !nedges) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL nnodes or nedges argument");
  *nnodes = t->nnodes;
  *nedges = t->index[t->nnodes - 1];
  return MPI_SUCCESS;
}

int PMPI_Graph_get(MPI_Comm comm, int maxindex, int maxedges, int indx[], int edges[]) {
  static const char fn[] = "MPI_Graph_get";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_GRAPH, &rc);
  if (!t) return rc;
  int ni = maxindex < t->nnodes ? maxindex : t->nnodes, ne = t->index[t->nnodes - 1];
  if (maxedges < ne) ne = maxedges;
  if ((ni > 0 && !indx) || (ne > 0 && !edges)) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL index or edges argument");
  for (int i = 0; i < ni; i++) indx[i] = t->index[i];
  for (int k = 0; k < ne; k++) edges[k] = t->edges[k];
  return MPI_SUCCESS;
}

/* A graph's node r of comm (checked: fn's error raised in *rc). */
static ptopo *graph_node(MPI_Comm comm, const char *fn, int r, int *rc) {
  if ((*rc = comm_check(comm, fn))) return NULL;
  ptopo *t = ptopo_of(comm, fn, MPI_GRAPH, rc);
  if (t && (r < 0 || r >= t->nnodes)) {
    *rc = err_comm_raise(comm, MPI_ERR_RANK, fn, "invalid rank %d (the graph has %d nodes)", r, t->nnodes);
    return NULL;
  }
  return t;
}

int PMPI_Graph_neighbors_count(MPI_Comm comm, int rank, int *nneighbors) {
  static const char fn[] = "MPI_Graph_neighbors_count";
  int rc;
  ptopo *t = graph_node(comm, fn, rank, &rc);
  if (!t) return rc;
  if (!nneighbors) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL nneighbors argument");
  *nneighbors = t->index[rank] - (rank ? t->index[rank - 1] : 0);
  return MPI_SUCCESS;
}

int PMPI_Graph_neighbors(MPI_Comm comm, int rank, int maxneighbors, int neighbors[]) {
  static const char fn[] = "MPI_Graph_neighbors";
  int rc;
  ptopo *t = graph_node(comm, fn, rank, &rc);
  if (!t) return rc;
  int lo = rank ? t->index[rank - 1] : 0, n = t->index[rank] - lo;
  if (maxneighbors < n) n = maxneighbors;
  if (n > 0 && !neighbors) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL neighbors argument");
  for (int k = 0; k < n; k++) neighbors[k] = t->edges[lo + k];
  return MPI_SUCCESS;
}

/* ==== distributed graphs ================================================== */

/* n ranks of comm in list (what: "sources"), each a rank of it. */
static int ranks_ok(MPI_Comm comm, const char *fn, const char *what, const int *list, int n) {
  if (n < 0) return err_comm_raise(comm, MPI_ERR_ARG, fn, "a negative count of %s (%d)", what, n);
  if (n > 0 && !list) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL %s argument", what);
  int size = comm_size(comm);
  for (int i = 0; i < n; i++)
    if (list[i] < 0 || list[i] >= size)
      return err_comm_raise(comm, MPI_ERR_RANK, fn, "%s[%d] = %d is not a rank of %s", what, i, list[i],
                            comm_get_name(comm));
  return MPI_SUCCESS;
}

/* Weights given: not MPI_UNWEIGHTED (MPI_WEIGHTS_EMPTY or NULL for no edges). */
static int weighted(const int *w) { return w != MPI_UNWEIGHTED; }

/* n weights at w, when there are some: NULL if w is MPI_WEIGHTS_EMPTY or
 * MPI_UNWEIGHTED, an error for a NULL array or a negative weight. */
static int weights_ok(MPI_Comm comm, const char *fn, const char *what, const int *w, int n) {
  if (!weighted(w) || n == 0) return MPI_SUCCESS;
  if (!w || w == MPI_WEIGHTS_EMPTY) return err_comm_raise(comm, MPI_ERR_ARG, fn, "no %s for %d edges", what, n);
  for (int i = 0; i < n; i++)
    if (w[i] < 0) return err_comm_raise(comm, MPI_ERR_ARG, fn, "%s[%d] = %d < 0", what, i, w[i]);
  return MPI_SUCCESS;
}

/* The new communicator (a duplicate of comm_old) with t. */
static int dist_attach(MPI_Comm comm_old, ptopo *t, MPI_Comm *out) {
  int rc = PMPI_Comm_dup(comm_old, out);
  if (rc) {
    ptopo_unref(t);
    return rc;
  }
  comm_set_topo(*out, t);
  return MPI_SUCCESS;
}

int PMPI_Dist_graph_create_adjacent(MPI_Comm comm_old, int indegree, const int sources[], const int sourceweights[],
                                   int outdegree, const int destinations[], const int destweights[], MPI_Info info,
                                   int reorder, MPI_Comm *comm_dist_graph) {
  static const char fn[] = "MPI_Dist_graph_create_adjacent";
  int rc;
  (void)info, (void)reorder;
  if ((rc = comm_check(comm_old, fn)) || (rc = ptopo_intra_ok(comm_old, fn)) ||
      (rc = ranks_ok(comm_old, fn, "sources", sources, indegree)) ||
      (rc = ranks_ok(comm_old, fn, "destinations", destinations, outdegree)) ||
      (rc = weights_ok(comm_old, fn, "sourceweights", sourceweights, indegree)) ||
      (rc = weights_ok(comm_old, fn, "destweights", destweights, outdegree)))
    return rc;
  if (!comm_dist_graph) return err_comm_raise(comm_old, MPI_ERR_ARG, fn, "NULL comm_dist_graph argument");
  ptopo *t = ptopo_new(MPI_DIST_GRAPH);
  t->indeg = indegree;
  t->outdeg = outdegree;
  t->sources = ptopo_ints(sources, indegree);
  t->dests = ptopo_ints(destinations, outdegree);
  t->weighted = weighted(sourceweights) && weighted(destweights);
  if (t->weighted) {
    t->sweights = ptopo_ints(indegree ? sourceweights : NULL, indegree);
    t->dweights = ptopo_ints(outdegree ? destweights : NULL, outdegree);
  }
  return dist_attach(comm_old, t, comm_dist_graph);
}

int PMPI_Dist_graph_create(MPI_Comm comm_old, int n, const int sources[], const int degrees[],
                          const int destinations[], const int weights[], MPI_Info info, int reorder,
                          MPI_Comm *comm_dist_graph) {
  static const char fn[] = "MPI_Dist_graph_create";
  int rc;
  (void)info, (void)reorder;
  if ((rc = comm_check(comm_old, fn)) || (rc = ptopo_intra_ok(comm_old, fn)) ||
      (rc = ranks_ok(comm_old, fn, "sources", sources, n)))
    return rc;
  if (n > 0 && !degrees) return err_comm_raise(comm_old, MPI_ERR_ARG, fn, "NULL degrees argument");
  long long nedges = 0;
  for (int i = 0; i < n; i++) {
    if (degrees[i] < 0) return err_comm_raise(comm_old, MPI_ERR_ARG, fn, "degrees[%d] = %d < 0", i, degrees[i]);
    nedges += degrees[i];
  }
  if (nedges > 0x7fffffff / 3) return err_comm_raise(comm_old, MPI_ERR_ARG, fn, "%lld edges", nedges);
  if ((rc = ranks_ok(comm_old, fn, "destinations", destinations, (int)nedges)) ||
      (rc = weights_ok(comm_old, fn, "weights", weights, (int)nedges)))
    return rc;
  if (!comm_dist_graph) return err_comm_raise(comm_old, MPI_ERR_ARG, fn, "NULL comm_dist_graph argument");
  /* Every edge (s, d, w) goes to s (for its destinations) and to d (for
   * its sources): three ints each, in the order given, to ranks in turn. */
  int size = comm_size(comm_old), me = comm_rank(comm_old), w = weighted(weights);
  int *scount = calloc(4 * (size_t)size, sizeof *scount), *sdispl = scount + size, *rcount = sdispl + size,
      *rdispl = rcount + size;
  int *sbuf = malloc((6 * (size_t)nedges + 1) * sizeof *sbuf), *rbuf = NULL;
  if (!scount || !sbuf) {
    free(scount);
    free(sbuf);
    return err_comm_raise(comm_old, MPI_ERR_NO_MEM, fn, "out of memory");
  }
  for (int pass = 0; pass < 2; pass++) {   /* counts, then the edges in place */
    int k = 0, *at = pass ? rcount : NULL;
    if (pass) {
      for (int r = 0, off = 0; r < size; r++) {
        sdispl[r] = off;
        off += scount[r];
        at[r] = sdispl[r];   /* the next free slot of r's part */
      }
    }
    for (int i = 0; i < n; i++)
      for (int j = 0; j < degrees[i]; j++, k++) {
        int e[3] = {sources[i], destinations[k], w && weights != MPI_WEIGHTS_EMPTY ? weights[k] : 0};
        for (int end = 0; end < 2 && (end == 0 || e[1] != e[0]); end++) {   /* a self-loop once */
          int r = e[end];
          if (!pass) {
            scount[r] += 3;
          } else {
            memcpy(sbuf + at[r], e, sizeof e);
            at[r] += 3;
          }
        }
      }
  }
  if ((rc = PMPI_Alltoall(scount, 1, MPI_INT, rcount, 1, MPI_INT, comm_old))) goto out;
  int total = 0;
  for (int r = 0; r < size; r++) {
    rdispl[r] = total;
    total += rcount[r];
  }
  if (!(rbuf = malloc(((size_t)total + 1) * sizeof *rbuf))) {
    rc = err_comm_raise(comm_old, MPI_ERR_NO_MEM, fn, "out of memory");
    goto out;
  }
  if ((rc = PMPI_Alltoallv(sbuf, scount, sdispl, MPI_INT, rbuf, rcount, rdispl, MPI_INT, comm_old))) goto out;
  ptopo *t = ptopo_new(MPI_DIST_GRAPH);
  t->weighted = w;   /* MPI_UNWEIGHTED on every rank or on none (MPI 3.1 section 7.5.4) */
  for (int pass = 0; pass < 2; pass++) {   /* count, then fill */
    int in = 0, outd = 0;
    for (int k = 0; k < total; k += 3) {
      const int *e = rbuf + k;
      if (e[1] == me) {   /* an edge into me: a source (a self-loop is both) */
        if (pass) {
          t->sources[in] = e[0];
          if (t->weighted) t->sweights[in] = e[2];
        }
        in++;
      }
      if (e[0] == me) {
        if (pass) {
          t->dests[outd] = e[1];
          if (t->weighted) t->dweights[outd] = e[2];
        }
        outd++;
      }
    }
    if (!pass) {
      t->indeg = in;
      t->outdeg = outd;
      t->sources = ptopo_ints(NULL, in);
      t->dests = ptopo_ints(NULL, outd);
      if (t->weighted) {
        t->sweights = ptopo_ints(NULL, in);
        t->dweights = ptopo_ints(NULL, outd);
      }
    }
  }
  rc = dist_attach(comm_old, t, comm_dist_graph);
out:
  free(scount);
  free(sbuf);
  free(rbuf);
  return rc;
}

int PMPI_Dist_graph_neighbors_count(MPI_Comm comm, int *indegree, int *outdegree, int *weighted_) {
  static const char fn[] = "MPI_Dist_graph_neighbors_count";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_DIST_GRAPH, &rc);
  if (!t) return rc;
  if (!indegree || !outdegree || !weighted_) return err_comm_raise(comm, MPI_ERR_ARG, fn, "a NULL argument");
  *indegree = t->indeg;
  *outdegree = t->outdeg;
  *weighted_ = t->weighted;
  return MPI_SUCCESS;
}

int PMPI_Dist_graph_neighbors(MPI_Comm comm, int maxindegree, int sources[], int sourceweights[], int maxoutdegree,
                             int destinations[], int destweights[]) {
  static const char fn[] = "MPI_Dist_graph_neighbors";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_DIST_GRAPH, &rc);
  if (!t) return rc;
  int ni = maxindegree < t->indeg ? maxindegree : t->indeg, no = maxoutdegree < t->outdeg ? maxoutdegree : t->outdeg;
  if ((ni > 0 && !sources) || (no > 0 && !destinations))
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL sources or destinations argument");
  for (int i = 0; i < ni; i++) {
    sources[i] = t->sources[i];
    if (t->weighted && weighted(sourceweights) && sourceweights) sourceweights[i] = t->sweights[i];
  }
  for (int i = 0; i < no; i++) {
    destinations[i] = t->dests[i];
    if (t->weighted && weighted(destweights) && destweights) destweights[i] = t->dweights[i];
  }
  return MPI_SUCCESS;
}
