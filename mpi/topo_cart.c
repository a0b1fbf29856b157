/* topo_cart.c -- Cartesian topologies (MPI 3.1 section 7.5): MPI_Cart_create, MPI_Cart_sub,
 * MPI_Cart_coords, MPI_Cart_rank, MPI_Cart_shift, MPI_Cart_get, MPI_Cartdim_get, MPI_Cart_map,
 * and MPI_Dims_create (mpi.h; topo.h).
 *
 * REORDER.  tilesim never reorders: a rank of the new communicator is its rank in the old one
 * (MPI 3.1 allows it; the simulated machine's places are fixed by the run's --place), so
 * MPI_Cart_map gives a rank itself, or MPI_UNDEFINED beyond the grid.  The new communicator is
 * made by MPI_Comm_split of the old one (its ranks beyond the grid get MPI_COMM_NULL), and costs
 * what that costs (doc/mpi-semantics.md).  MPI_Cart_sub keeping no dimension gives rank 0 a
 * grid of itself and the others MPI_COMM_NULL, as MPICH does (Open MPI gives each rank one).
 *
 * DIMS_CREATE.  MPI 3.1 section 7.5.2 asks for dimensions "as close to each other as possible",
 * in non-increasing order.  tilesim gives, among the non-increasing factorizations of nnodes
 * (divided by the dimensions the caller fixed) into the free dimensions, one with the smallest
 * difference between the largest and the smallest factor, and among those the one whose
 * smallest factor is largest, then its second smallest, ...: the balance MPICH's Dims_create
 * seeks (Traff and Luebbe, "Specification guideline violations by MPI_Dims_create", EuroMPI
 * 2015), which MPICH's search keeps on ties too.  Open MPI's can differ (it is not always the
 * most balanced). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/core.h"
#include "mpi/topo.h"

/* ==== creating ============================================================ */

/* The product of dims[0..ndims), each > 0; -1 if one is not, -2 if over INT_MAX. */
static long long grid_size(int ndims, const int *dims) {
  long long n = 1;
  for (int i = 0; i < ndims; i++) {
    if (dims[i] <= 0) return -1;
    n *= dims[i];
    if (n > 0x7fffffff) return -2;
  }
  return n;
}

/* The checks of a Cartesian grid's arguments for fn on comm: its size in *nnodes. */
static int grid_ok(MPI_Comm comm, const char *fn, int ndims, const int *dims, const int *periods,
                   long long *nnodes) {
  if (ndims < 0) return err_comm_raise(comm, MPI_ERR_DIMS, fn, "ndims %d < 0", ndims);
  if (ndims > 0 && (!dims || !periods)) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL dims or periods argument");
  *nnodes = grid_size(ndims, dims);
  if (*nnodes == -1) {
    int i = 0;
    while (dims[i] > 0) i++;
    return err_comm_raise(comm, MPI_ERR_DIMS, fn, "dims[%d] = %d (must be > 0)", i, dims[i]);
  }
  if (*nnodes == -2) return err_comm_raise(comm, MPI_ERR_DIMS, fn, "the grid has more than INT_MAX processes");
  int size = comm_size(comm);
  if (*nnodes > size)
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "the grid has %lld processes, %s only %d", *nnodes,
                          comm_get_name(comm), size);
  return MPI_SUCCESS;
}

/* The Cartesian topology of (ndims, dims, periods) for the calling rank, rank me of it, on
 * newcomm. */
static void attach(MPI_Comm newcomm, int ndims, const int *dims, const int *periods) {
  ptopo *t = ptopo_new(MPI_CART);
  t->ndims = ndims;
  t->dims = ptopo_ints(dims, ndims);
  t->periods = ptopo_ints(NULL, ndims);
  for (int i = 0; i < ndims; i++) t->periods[i] = periods[i] != 0;
  ptopo_neighbours(t, comm_rank(newcomm));
  comm_set_topo(newcomm, t);
}

int PMPI_Cart_create(MPI_Comm comm_old, int ndims, const int dims[], const int periods[], int reorder,
                    MPI_Comm *comm_cart) {
  static const char fn[] = "MPI_Cart_create";
  long long nnodes;
  int rc;
  (void)reorder;   /* never reordered: see the top of the file */
  if ((rc = comm_check(comm_old, fn)) || (rc = ptopo_intra_ok(comm_old, fn)) ||
      (rc = grid_ok(comm_old, fn, ndims, dims, periods, &nnodes)))
    return rc;
  if (!comm_cart) return err_comm_raise(comm_old, MPI_ERR_ARG, fn, "NULL comm_cart argument");
  int me = comm_rank(comm_old);
  if ((rc = PMPI_Comm_split(comm_old, me < nnodes ? 0 : MPI_UNDEFINED, me, comm_cart))) return rc;
  if (*comm_cart != MPI_COMM_NULL) attach(*comm_cart, ndims, dims, periods);
  return MPI_SUCCESS;
}

int PMPI_Cart_sub(MPI_Comm comm, const int remain_dims[], MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Cart_sub";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_CART, &rc);
  if (!t) return rc;
  if (t->ndims > 0 && !remain_dims) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL remain_dims argument");
  if (!newcomm) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL newcomm argument");
  int nd = t->ndims, *c = ptopo_ints(NULL, nd), *dims = ptopo_ints(NULL, nd),
      *periods = ptopo_ints(NULL, nd), kept = 0, color = 0, key = 0;
  ptopo_cart_coords(t, comm_rank(comm), c);
  /* The ranks with the same coordinates in the dimensions dropped make one
   * communicator, ordered by their coordinates in those kept. */
  for (int d = 0; d < nd; d++) {
    if (remain_dims[d]) {
      key = key * t->dims[d] + c[d];
      dims[kept] = t->dims[d];
      periods[kept++] = t->periods[d];
    } else {
      color = color * t->dims[d] + c[d];
    }
  }
  /* No dimension kept: a grid of one process, rank 0's (as MPICH: the
   * others get MPI_COMM_NULL). */
  if (!kept) color = comm_rank(comm) == 0 ? 0 : MPI_UNDEFINED;
  rc = PMPI_Comm_split(comm, color, key, newcomm);
  if (!rc && *newcomm != MPI_COMM_NULL) attach(*newcomm, kept, dims, periods);
  free(c);
  free(dims);
  free(periods);
  return rc;
}

int PMPI_Cart_map(MPI_Comm comm, int ndims, const int dims[], const int periods[], int *newrank) {
  static const char fn[] = "MPI_Cart_map";
  long long nnodes;
  int rc;
  if ((rc = comm_check(comm, fn)) || (rc = grid_ok(comm, fn, ndims, dims, periods, &nnodes))) return rc;
  if (!newrank) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL newrank argument");
  int me = comm_rank(comm);
  *newrank = me < nnodes ? me : MPI_UNDEFINED;
  return MPI_SUCCESS;
}

/* ==== questions =========================================================== */

int PMPI_Cartdim_get(MPI_Comm comm, int *ndims) {
  static const char fn[] = "MPI_Cartdim_get";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_CART, &rc);
  if (!t) return rc;
  if (!ndims) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL ndims argument");
  *ndims = t->ndims;
  return MPI_SUCCESS;
}

int PMPI_Cart_get(MPI_Comm comm, int maxdims, int dims[], int periods[], int coords[]) {
  static const char fn[] = "MPI_Cart_get";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_CART, &rc);
  if (!t) return rc;
  int n = maxdims < t->ndims ? maxdims : t->ndims;
  if (n > 0 && (!dims || !periods || !coords))
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL dims, periods or coords argument");
  int *c = ptopo_ints(NULL, t->ndims);
  ptopo_cart_coords(t, comm_rank(comm), c);
  for (int i = 0; i < n; i++) {
    dims[i] = t->dims[i];
    periods[i] = t->periods[i];
    coords[i] = c[i];
  }
  free(c);
  return MPI_SUCCESS;
}

int PMPI_Cart_coords(MPI_Comm comm, int rank, int maxdims, int coords[]) {
  static const char fn[] = "MPI_Cart_coords";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_CART, &rc);
  if (!t) return rc;
  if (rank < 0 || rank >= comm_size(comm))
    return err_comm_raise(comm, MPI_ERR_RANK, fn, "invalid rank %d (%s has %d ranks)", rank, comm_get_name(comm),
                          comm_size(comm));
  if (maxdims < t->ndims)
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "maxdims %d < the topology's %d dimensions", maxdims, t->ndims);
  if (t->ndims > 0 && !coords) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL coords argument");
  ptopo_cart_coords(t, rank, coords);
  return MPI_SUCCESS;
}

int PMPI_Cart_rank(MPI_Comm comm, const int coords[], int *rank) {
  static const char fn[] = "MPI_Cart_rank";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_CART, &rc);
  if (!t) return rc;
  if (!rank || (t->ndims > 0 && !coords)) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL coords or rank argument");
  int r = ptopo_cart_rank(t, coords);
  if (r < 0) {
    int d = 0;
    while (t->periods[d] || (coords[d] >= 0 && coords[d] < t->dims[d])) d++;
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "coords[%d] = %d is outside the non-periodic dimension of %d", d,
                          coords[d], t->dims[d]);
  }
  *rank = r;
  return MPI_SUCCESS;
}

int PMPI_Cart_shift(MPI_Comm comm, int direction, int disp, int *rank_source, int *rank_dest) {
  static const char fn[] = "MPI_Cart_shift";
  int rc = comm_check(comm, fn);
  if (rc) return rc;
  ptopo *t = ptopo_of(comm, fn, MPI_CART, &rc);
  if (!t) return rc;
  if (!rank_source || !rank_dest) return err_comm_raise(comm, MPI_ERR_ARG, fn, "NULL rank_source or rank_dest argument");
  if (direction < 0 || direction >= t->ndims)
    return err_comm_raise(comm, MPI_ERR_ARG, fn, "direction %d is not a dimension (0 .. %d)", direction, t->ndims - 1);
  int *c = ptopo_ints(NULL, t->ndims), me = comm_rank(comm);
  for (int k = 0; k < 2; k++) {
    ptopo_cart_coords(t, me, c);
    c[direction] += k ? disp : -disp;
    int r = ptopo_cart_rank(t, c);
    *(k ? rank_dest : rank_source) = r < 0 ? MPI_PROC_NULL : r;
  }
  free(c);
  return MPI_SUCCESS;
}

/* ==== MPI_Dims_create ===================================================== */

/* The search for the most balanced factorization (see the top of the file). */
typedef struct {
  const int *divs;   /* the divisors of the whole, ascending */
  int ndivs;
} divisors;

/* Whether e^j > m. */
static int over(int e, int j, int m) {
  long long p = 1;
  for (int i = 0; i < j; i++)
    if ((p *= e) > m) return 1;
  return 0;
}

/* The factorizations of m into j factors, each >= lo and dividing m,
 * non-increasing (out[0] the largest), the smallest one given: the one with
 * the smallest largest factor, ties to the later next smallest factor (and
 * so on); its largest factor, or 0 if there is none. */
static int least_top(const divisors *D, int m, int j, int lo, int *out) {
  if (j == 1) {
    if (m < lo) return 0;
    out[0] = m;
    return m;
  }
  int found = 0, *sub = malloc((size_t)j * sizeof *sub);
  if (!sub) return 0;
  for (int k = 0; k < D->ndivs && !over(D->divs[k], j, m); k++) {
    int e = D->divs[k];
    if (e < lo || m % e) continue;
    int top = least_top(D, m / e, j - 1, e, sub);
    if (top && (!found || top <= found)) {
      found = top;
      memcpy(out, sub, (size_t)(j - 1) * sizeof *out);
      out[j - 1] = e;
    }
  }
  free(sub);
  return found;
}

/* The most balanced: for each smallest factor e, the least largest one;
 * the smallest difference, ties to the later e. */
static void balanced(const divisors *D, int m, int j, int *out) {
  if (j == 1) {
    out[0] = m;
    return;
  }
  int found = 0, bal = 0, *sub = malloc((size_t)j * sizeof *sub);
  if (!sub) return;
  for (int k = 0; k < D->ndivs && !over(D->divs[k], j, m); k++) {
    int e = D->divs[k];
    if (m % e) continue;
    int top = least_top(D, m / e, j - 1, e, sub);
    if (top && (!found || top - e <= bal)) {
      found = 1;
      bal = top - e;
      memcpy(out, sub, (size_t)(j - 1) * sizeof *out);
      out[j - 1] = e;
    }
  }
  free(sub);
}

int PMPI_Dims_create(int nnodes, int ndims, int dims[]) {
  static const char fn[] = "MPI_Dims_create";
  MPI_Comm w = MPI_COMM_WORLD;
  if (nnodes <= 0) return err_comm_raise(w, MPI_ERR_ARG, fn, "nnodes %d (must be > 0)", nnodes);
  if (ndims < 0) return err_comm_raise(w, MPI_ERR_DIMS, fn, "ndims %d < 0", ndims);
  if (ndims > 0 && !dims) return err_comm_raise(w, MPI_ERR_ARG, fn, "NULL dims argument");
  long long fixed = 1;
  int free_dims = 0;
  for (int i = 0; i < ndims; i++) {
    if (dims[i] < 0) return err_comm_raise(w, MPI_ERR_DIMS, fn, "dims[%d] = %d < 0", i, dims[i]);
    if (dims[i] == 0)
      free_dims++;
    else if ((fixed *= dims[i]) > nnodes)
      fixed = (long long)nnodes + 1;
  }
  if (nnodes % fixed)
    return err_comm_raise(w, MPI_ERR_DIMS, fn, "the dimensions given do not divide nnodes %d", nnodes);
  if (!free_dims) {
    if (fixed != nnodes)
      return err_comm_raise(w, MPI_ERR_DIMS, fn, "the dimensions given make %lld processes, not %d", fixed, nnodes);
    return MPI_SUCCESS;
  }
  int m = (int)(nnodes / fixed), nlow = 0, nd = 0;
  for (long long d = 1; d * d <= m; d++) nlow += m % d == 0;
  int *divs = malloc(2 * (size_t)nlow * sizeof *divs), *out = malloc((size_t)free_dims * sizeof *out);
  if (!divs || !out) {
    free(divs);
    free(out);
    return err_comm_raise(w, MPI_ERR_NO_MEM, fn, "out of memory");
  }
  /* The divisors of m, ascending: those up to its root, then their cofactors. */
  for (long long d = 1; d * d <= m; d++)
    if (m % d == 0) divs[nd++] = (int)d;
  for (int k = nlow - 1; k >= 0; k--)
    if ((long long)divs[k] * divs[k] != m) divs[nd++] = m / divs[k];
  divisors D = {divs, nd};
  for (int i = 0; i < free_dims; i++) out[i] = 1;
  balanced(&D, m, free_dims, out);
  for (int i = 0, k = 0; i < ndims; i++)
    if (dims[i] == 0) dims[i] = out[k++];
  free(divs);
  free(out);
  return MPI_SUCCESS;
}
