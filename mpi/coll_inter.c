/* coll_inter.c -- the collectives on an intercommunicator (coll_inter.h).
 *
 * Messages between the groups are point-to-point on the
 * intercommunicator's collective context (core.h: ranks name the remote
 * group), one tag per collective; a group's own steps are the MPI
 * collectives on its hidden local intracommunicator.  While a rank waits
 * in a step of its own, its label names the call and the
 * intercommunicator ("MPI_Bcast(communicator 5)"); inside a local step, the
 * local collective's. */
#include <stdlib.h>
#include <string.h>

#include "mpi/coll.h"
#include "mpi/coll_inter.h"
#include "mpi/dtype.h"
#include "mpi/err.h"
#include "mpi/label.h"
#include "mpi/core.h"

enum { T_BARRIER = 1, T_BCAST, T_GATHER, T_GATHERV, T_SCATTER, T_SCATTERV, T_ALLGATHER, T_ALLGATHERV, T_ALLTOALL,
       T_ALLTOALLV, T_ALLTOALLW, T_REDUCE, T_ALLREDUCE, T_REDUCE_SCATTER };

/* Scratch memory, freed at the rank's end if the run stops while a call
 * waits (coll.h's coll_cg_alloc); drop frees it. */
static void *grab(size_t n) {
  coll_cg g = {.fn = "an MPI collective on an intercommunicator"};
  return coll_cg_alloc(&g, n);
}

static void drop(void *p) { coll_cg_free(p); }

/* One call: the rank, the intercommunicator, its local one, the label. */
typedef struct {
  st_rank *R;
  st_comm *c;
  MPI_Comm comm, local;
  const char *fn;
  label_rec l;
} ic;

static void begin(ic *x, const char *fn, MPI_Comm comm) {
  x->R = st_need(fn);
  x->c = st_comm_get(x->R, comm);
  x->comm = comm;
  x->local = x->c->local;
  x->fn = fn;
  x->l = (label_rec){.fn = fn, .what = L_COMM, .pair = x->c->pair};
}

/* The label again (a local step clears it). */
static void label(ic *x) { label_set(x->R, &x->l); }

static int end(ic *x, int rc) {
  label_clear(x->R);
  return rc;
}

/* A receive between the groups that failed (a message longer than the
 * buffer: the groups disagree on the counts), raised. */
static int crossed(ic *x, int rc) {
  if (!rc) return rc;
  return err_comm_raise(x->comm, rc, x->fn, "a message from the remote group is longer than the receive buffer "
                                         "(the groups disagree on the counts or types)");
}

static int recv(ic *x, void *buf, int count, MPI_Datatype dt, int src, int tag) {
  label(x);
  return crossed(x, coll_p2p_recv(buf, count, dt, src, tag, x->comm, MPI_STATUS_IGNORE));
}

static int waitall(ic *x, int n, MPI_Request *reqs) {
  label(x);
  return crossed(x, coll_p2p_waitall(n, reqs, MPI_STATUSES_IGNORE));
}

/* root: MPI_ROOT, MPI_PROC_NULL, or a rank of the remote group. */
static int root_ok(ic *x, int root) {
  if (root == MPI_ROOT || root == MPI_PROC_NULL || (root >= 0 && root < x->c->size)) return MPI_SUCCESS;
  return err_comm_raise(x->comm, MPI_ERR_ROOT, x->fn,
                        "invalid root %d (MPI_ROOT, MPI_PROC_NULL, or a rank of the remote group, which has %d)", root,
                        x->c->size);
}

/* count elements of dt at buf (MPI_IN_PLACE refused). */
static int data_ok(ic *x, const char *what, const void *buf, int count, MPI_Datatype dt) {
  if (buf == MPI_IN_PLACE) return coll_in_place_bad(x->comm, x->fn, "a buffer on an intercommunicator");
  return coll_data_ok(x->comm, x->fn, what, buf, count, dt);
}

static int counts_ok(ic *x, const char *what, const int *counts, const int *displs, const void *buf, MPI_Datatype dt) {
  if (buf == MPI_IN_PLACE) return coll_in_place_bad(x->comm, x->fn, "a buffer on an intercommunicator");
  int rc = coll_counts_ok(x->comm, x->fn, what, counts, displs, x->c->size);
  return rc ? rc : coll_type_ok(x->comm, x->fn, what[0] == 's' ? "sendtype" : "recvtype", dt);
}

/* count elements of dt packed into new memory. */
static char *packed(const void *buf, int count, MPI_Datatype dt) {
  size_t n = dtype_size(dt) * (size_t)count;
  char *p = grab(n ? n : 1);
  if (n) dtype_pack(buf, count, dt, p);
  return p;
}

/* Room for count elements of dt as the type lays them out: the buffer to
 * pass, and *base to free. */
static void *room(int count, MPI_Datatype dt, void **base) {
  MPI_Aint ext = dtype_extent(dt), text = dtype_true_extent(dt);
  size_t span = (size_t)(ext > text ? ext : text);
  *base = grab(count > 0 && span ? (size_t)count * span : 1);
  return (char *)*base - dtype_true_lb(dt);
}

/* ==== barrier and broadcast =============================================== */

int coll_inter_barrier(MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Barrier", comm);
  unsigned char b = 0;
  int rc = PMPI_Barrier(x.local);
  if (!rc && x.c->rank == 0) {
    if (!(rc = coll_p2p_send(&b, 1, MPI_BYTE, 0, T_BARRIER, comm))) rc = recv(&x, &b, 1, MPI_BYTE, 0, T_BARRIER);
  }
  if (!rc) rc = PMPI_Bcast(&b, 1, MPI_BYTE, 0, x.local);
  return end(&x, rc);
}

int coll_inter_bcast(void *buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Bcast", comm);
  int rc = root_ok(&x, root);
  if (rc || root == MPI_PROC_NULL || (rc = data_ok(&x, "datatype", buffer, count, datatype))) return end(&x, rc);
  if (root == MPI_ROOT) return end(&x, coll_p2p_send(buffer, count, datatype, 0, T_BCAST, comm));
  if (x.c->rank == 0 && (rc = recv(&x, buffer, count, datatype, root, T_BCAST))) return end(&x, rc);
  return end(&x, PMPI_Bcast(buffer, count, datatype, 0, x.local));
}

/* ==== gather and scatter ================================================== */

int coll_inter_gather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                      MPI_Datatype recvtype, int root, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Gather", comm);
  int rc = root_ok(&x, root);
  if (rc || root == MPI_PROC_NULL) return end(&x, rc);
  if (root == MPI_ROOT) {
    if ((rc = data_ok(&x, "recvtype", recvbuf, recvcount * x.c->size, recvtype))) return end(&x, rc);
    return end(&x, recv(&x, recvbuf, recvcount * x.c->size, recvtype, 0, T_GATHER));
  }
  if ((rc = data_ok(&x, "sendtype", sendbuf, sendcount, sendtype))) return end(&x, rc);
  /* The group's blocks meet at its rank 0, which sends them on. */
  int n = (int)(dtype_size(sendtype) * (size_t)sendcount), ln = st_comm_lsize(x.c);
  char *mine = packed(sendbuf, sendcount, sendtype), *all = x.c->rank == 0 ? grab((size_t)n * (size_t)ln + 1) : NULL;
  rc = PMPI_Gather(mine, n, MPI_BYTE, all, n, MPI_BYTE, 0, x.local);
  if (!rc && all) rc = coll_p2p_send(all, n * ln, MPI_BYTE, root, T_GATHER, comm);
  drop(mine);
  drop(all);
  return end(&x, rc);
}

int coll_inter_gatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                       const int recvcounts[], const int displs[], MPI_Datatype recvtype, int root, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Gatherv", comm);
  int rc = root_ok(&x, root);
  if (rc || root == MPI_PROC_NULL) return end(&x, rc);
  if (root != MPI_ROOT) {
    if ((rc = data_ok(&x, "sendtype", sendbuf, sendcount, sendtype))) return end(&x, rc);
    return end(&x, coll_p2p_send(sendbuf, sendcount, sendtype, root, T_GATHERV, comm));
  }
  if ((rc = counts_ok(&x, "recvcounts", recvcounts, displs, recvbuf, recvtype))) return end(&x, rc);
  int n = x.c->size;
  MPI_Request *reqs = grab(((size_t)n) * sizeof *reqs);
  for (int i = 0; i < n; i++)
    coll_p2p_irecv(coll_at(recvbuf, displs[i], recvtype), recvcounts[i], recvtype, i, T_GATHERV, comm, &reqs[i]);
  rc = waitall(&x, n, reqs);
  drop(reqs);
  return end(&x, rc);
}

int coll_inter_scatter(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                       MPI_Datatype recvtype, int root, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Scatter", comm);
  int rc = root_ok(&x, root);
  if (rc || root == MPI_PROC_NULL) return end(&x, rc);
  if (root == MPI_ROOT) {
    if ((rc = data_ok(&x, "sendtype", sendbuf, sendcount * x.c->size, sendtype))) return end(&x, rc);
    return end(&x, coll_p2p_send(sendbuf, sendcount * x.c->size, sendtype, 0, T_SCATTER, comm));
  }
  if ((rc = data_ok(&x, "recvtype", recvbuf, recvcount, recvtype))) return end(&x, rc);
  /* Rank 0 takes the group's blocks and scatters them. */
  int n = (int)(dtype_size(recvtype) * (size_t)recvcount), ln = st_comm_lsize(x.c);
  char *all = x.c->rank == 0 ? grab((size_t)n * (size_t)ln + 1) : NULL, *mine = grab((size_t)n + 1);
  if (all) rc = recv(&x, all, n * ln, MPI_BYTE, root, T_SCATTER);
  if (!rc) rc = PMPI_Scatter(all, n, MPI_BYTE, mine, n, MPI_BYTE, 0, x.local);
  if (!rc && n) dtype_unpack(mine, (size_t)n, recvbuf, recvcount, recvtype);
  drop(mine);
  drop(all);
  return end(&x, rc);
}

int coll_inter_scatterv(const void *sendbuf, const int sendcounts[], const int displs[], MPI_Datatype sendtype,
                        void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Scatterv", comm);
  int rc = root_ok(&x, root);
  if (rc || root == MPI_PROC_NULL) return end(&x, rc);
  if (root != MPI_ROOT) {
    if ((rc = data_ok(&x, "recvtype", recvbuf, recvcount, recvtype))) return end(&x, rc);
    return end(&x, recv(&x, recvbuf, recvcount, recvtype, root, T_SCATTERV));
  }
  if ((rc = counts_ok(&x, "sendcounts", sendcounts, displs, sendbuf, sendtype))) return end(&x, rc);
  for (int i = 0; i < x.c->size && !rc; i++)
    rc = coll_p2p_send(coll_at(sendbuf, displs[i], sendtype), sendcounts[i], sendtype, i, T_SCATTERV, comm);
  return end(&x, rc);
}

/* ==== allgather =========================================================== */

/* The group's packed blocks (mine: n bytes; sizes[r] bytes of local rank r,
 * sizes NULL: n each) meet at its rank 0, which swaps them with the remote
 * rank 0 for the remote group's (rn bytes), spread to the group in *out
 * (malloc'd). */
static int swap_all(ic *x, const char *mine, int n, int rn, int tag, char **out) {
  int ln = st_comm_lsize(x->c), rc, *sizes = NULL, *displs = NULL, total = 0;
  char *all = NULL;
  *out = grab((size_t)rn + 1);
  if (x->c->rank == 0) {
    sizes = grab((2 * (size_t)ln) * sizeof *sizes);
    displs = sizes + ln;
  }
  rc = PMPI_Gather(&n, 1, MPI_INT, sizes, 1, MPI_INT, 0, x->local);
  if (!rc && sizes) {
    for (int r = 0; r < ln; r++) displs[r] = total, total += sizes[r];
    all = grab((size_t)total + 1);
  }
  if (!rc) rc = PMPI_Gatherv(mine, n, MPI_BYTE, all, sizes, displs, MPI_BYTE, 0, x->local);
  if (!rc && all && !(rc = coll_p2p_send(all, total, MPI_BYTE, 0, tag, x->comm)))
    rc = recv(x, *out, rn, MPI_BYTE, 0, tag);
  if (!rc) rc = PMPI_Bcast(*out, rn, MPI_BYTE, 0, x->local);
  drop(all);
  drop(sizes);
  return rc;
}

int coll_inter_allgather(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                         MPI_Datatype recvtype, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Allgather", comm);
  int rc, rn = x.c->size;
  if ((rc = data_ok(&x, "sendtype", sendbuf, sendcount, sendtype)) ||
      (rc = data_ok(&x, "recvtype", recvbuf, recvcount * rn, recvtype)))
    return end(&x, rc);
  char *mine = packed(sendbuf, sendcount, sendtype), *theirs;
  int bytes = (int)(dtype_size(recvtype) * (size_t)recvcount * (size_t)rn);
  rc = swap_all(&x, mine, (int)(dtype_size(sendtype) * (size_t)sendcount), bytes, T_ALLGATHER, &theirs);
  if (!rc && bytes) dtype_unpack(theirs, (size_t)bytes, recvbuf, recvcount * rn, recvtype);
  drop(mine);
  drop(theirs);
  return end(&x, rc);
}

int coll_inter_allgatherv(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
                          const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Allgatherv", comm);
  int rc;
  if ((rc = data_ok(&x, "sendtype", sendbuf, sendcount, sendtype)) ||
      (rc = counts_ok(&x, "recvcounts", recvcounts, displs, recvbuf, recvtype)))
    return end(&x, rc);
  size_t ts = dtype_size(recvtype), bytes = 0;
  for (int i = 0; i < x.c->size; i++) bytes += (size_t)recvcounts[i] * ts;
  char *mine = packed(sendbuf, sendcount, sendtype), *theirs;
  rc = swap_all(&x, mine, (int)(dtype_size(sendtype) * (size_t)sendcount), (int)bytes, T_ALLGATHERV, &theirs);
  for (int i = 0, off = 0; !rc && i < x.c->size; off += recvcounts[i] * (int)ts, i++)
    if (recvcounts[i])
      dtype_unpack(theirs + off, (size_t)recvcounts[i] * ts, coll_at(recvbuf, displs[i], recvtype),
                   recvcounts[i], recvtype);
  drop(mine);
  drop(theirs);
  return end(&x, rc);
}

/* ==== all-to-all ========================================================== */

/* Each remote rank i's block: send scount[i] of stype[i] at sbuf + sd[i],
 * receive rcount[i] of rtype[i] at rbuf + rd[i] (byte offsets), all at
 * once. */
static int exchange(ic *x, const void *sbuf, const int *sc, const MPI_Aint *sd, const MPI_Datatype *st, void *rbuf,
                    const int *rcnt, const MPI_Aint *rd, const MPI_Datatype *rt, int tag) {
  int n = x->c->size;
  MPI_Request *reqs = grab((2 * (size_t)n) * sizeof *reqs);
  for (int i = 0; i < n; i++) {
    coll_p2p_irecv((char *)rbuf + rd[i], rcnt[i], rt[i], i, tag, x->comm, &reqs[i]);
    coll_p2p_isend((const char *)sbuf + sd[i], sc[i], st[i], i, tag, x->comm, &reqs[n + i]);
  }
  int rc = waitall(x, 2 * n, reqs);
  drop(reqs);
  return rc;
}

/* The arrays of exchange for counts and element displacements of one
 * type each side (counts NULL: count each, at i * count). */
static int exchange_v(ic *x, const void *sbuf, int scount, const int *sc, const int *sdis, MPI_Datatype stype,
                      void *rbuf, int rcount, const int *rcnt, const int *rdis, MPI_Datatype rtype, int tag) {
  int n = x->c->size;
  int *c = grab((2 * (size_t)n + 1) * sizeof *c);
  MPI_Aint *d = grab((2 * (size_t)n + 1) * sizeof *d), se = dtype_extent(stype), re = dtype_extent(rtype);
  MPI_Datatype *t = grab((2 * (size_t)n + 1) * sizeof *t);
  for (int i = 0; i < n; i++) {
    c[i] = sc ? sc[i] : scount;
    d[i] = (MPI_Aint)(sc ? sdis[i] : i * scount) * se;
    t[i] = stype;
    c[n + i] = rcnt ? rcnt[i] : rcount;
    d[n + i] = (MPI_Aint)(rcnt ? rdis[i] : i * rcount) * re;
    t[n + i] = rtype;
  }
  int rc = exchange(x, sbuf, c, d, t, rbuf, c + n, d + n, t + n, tag);
  drop(c);
  drop(d);
  drop(t);
  return rc;
}

int coll_inter_alltoall(const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf, int recvcount,
                        MPI_Datatype recvtype, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Alltoall", comm);
  int rc, rn = x.c->size;
  if ((rc = data_ok(&x, "sendtype", sendbuf, sendcount * rn, sendtype)) ||
      (rc = data_ok(&x, "recvtype", recvbuf, recvcount * rn, recvtype)))
    return end(&x, rc);
  return end(&x, exchange_v(&x, sendbuf, sendcount, NULL, NULL, sendtype, recvbuf, recvcount, NULL, NULL, recvtype,
                            T_ALLTOALL));
}

int coll_inter_alltoallv(const void *sendbuf, const int sendcounts[], const int sdispls[], MPI_Datatype sendtype,
                         void *recvbuf, const int recvcounts[], const int rdispls[], MPI_Datatype recvtype,
                         MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Alltoallv", comm);
  int rc;
  if ((rc = counts_ok(&x, "sendcounts", sendcounts, sdispls, sendbuf, sendtype)) ||
      (rc = counts_ok(&x, "recvcounts", recvcounts, rdispls, recvbuf, recvtype)))
    return end(&x, rc);
  return end(&x, exchange_v(&x, sendbuf, 0, sendcounts, sdispls, sendtype, recvbuf, 0, recvcounts, rdispls, recvtype,
                            T_ALLTOALLV));
}

int coll_inter_alltoallw(const void *sendbuf, const int sendcounts[], const int sdispls[],
                         const MPI_Datatype sendtypes[], void *recvbuf, const int recvcounts[], const int rdispls[],
                         const MPI_Datatype recvtypes[], MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Alltoallw", comm);
  int rc = MPI_SUCCESS, n = x.c->size;
  if (sendbuf == MPI_IN_PLACE || recvbuf == MPI_IN_PLACE)
    return end(&x, coll_in_place_bad(comm, x.fn, "a buffer on an intercommunicator"));
  if (!sendtypes || !recvtypes) return end(&x, err_comm_raise(comm, MPI_ERR_ARG, x.fn, "NULL array of types"));
  if ((rc = coll_counts_ok(comm, x.fn, "sendcounts", sendcounts, sdispls, n)) ||
      (rc = coll_counts_ok(comm, x.fn, "recvcounts", recvcounts, rdispls, n)))
    return end(&x, rc);
  for (int i = 0; i < n && !rc; i++)
    if (!(rc = coll_type_ok(comm, x.fn, "sendtypes[i]", sendtypes[i])))
      rc = coll_type_ok(comm, x.fn, "recvtypes[i]", recvtypes[i]);
  if (rc) return end(&x, rc);
  MPI_Aint *d = grab((2 * (size_t)n + 1) * sizeof *d);
  for (int i = 0; i < n; i++) d[i] = sdispls[i], d[n + i] = rdispls[i];
  rc = exchange(&x, sendbuf, sendcounts, d, sendtypes, recvbuf, recvcounts, d + n, recvtypes, T_ALLTOALLW);
  drop(d);
  return end(&x, rc);
}

/* ==== reductions ========================================================== */

static int red_ok(ic *x, const void *sendbuf, int count, MPI_Datatype dt, MPI_Op op) {
  int rc = data_ok(x, "datatype", sendbuf, count, dt);
  return rc ? rc : coll_op_ok(x->comm, x->fn, op, dt);
}

/* The group's operands reduced at its rank 0 (into *base's room there). */
static int reduce_local(ic *x, const void *sendbuf, int count, MPI_Datatype dt, MPI_Op op, void **res, void **base) {
  *res = *base = NULL;
  if (x->c->rank == 0) *res = room(count, dt, base);
  return PMPI_Reduce(sendbuf, *res, count, dt, op, 0, x->local);
}

int coll_inter_reduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op, int root,
                      MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Reduce", comm);
  int rc = root_ok(&x, root);
  if (rc || root == MPI_PROC_NULL) return end(&x, rc);
  if (root == MPI_ROOT) {
    if ((rc = data_ok(&x, "datatype", recvbuf, count, datatype)) || (rc = coll_op_ok(comm, x.fn, op, datatype)))
      return end(&x, rc);
    return end(&x, recv(&x, recvbuf, count, datatype, 0, T_REDUCE));
  }
  if ((rc = red_ok(&x, sendbuf, count, datatype, op))) return end(&x, rc);
  void *res, *base;
  rc = reduce_local(&x, sendbuf, count, datatype, op, &res, &base);
  if (!rc && res) rc = coll_p2p_send(res, count, datatype, root, T_REDUCE, comm);
  drop(base);
  return end(&x, rc);
}

/* Each group's operands reduced at its rank 0; the two swap, and each
 * spreads the other's in its group. */
int coll_inter_allreduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype, MPI_Op op,
                         MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Allreduce", comm);
  int rc;
  if ((rc = red_ok(&x, sendbuf, count, datatype, op)) || (rc = data_ok(&x, "datatype", recvbuf, count, datatype)))
    return end(&x, rc);
  void *res, *base;
  rc = reduce_local(&x, sendbuf, count, datatype, op, &res, &base);
  if (!rc && res && !(rc = coll_p2p_send(res, count, datatype, 0, T_ALLREDUCE, comm)))
    rc = recv(&x, recvbuf, count, datatype, 0, T_ALLREDUCE);
  if (!rc) rc = PMPI_Bcast(recvbuf, count, datatype, 0, x.local);
  drop(base);
  return end(&x, rc);
}

/* The same over the whole vector (the sum of counts), then scattered. */
static int redscat(ic *x, const void *sendbuf, void *recvbuf, const int *counts, MPI_Datatype dt, MPI_Op op) {
  int ln = st_comm_lsize(x->c), total = 0, *displs = grab(((size_t)ln + 1) * sizeof *displs), rc;
  for (int i = 0; i < ln; i++) displs[i] = total, total += counts[i];
  if ((rc = red_ok(x, sendbuf, total, dt, op)) || (rc = data_ok(x, "datatype", recvbuf, counts[x->c->rank], dt))) {
    drop(displs);
    return rc;
  }
  void *res, *base, *theirs = NULL, *tbase = NULL;
  rc = reduce_local(x, sendbuf, total, dt, op, &res, &base);
  if (!rc && res) {
    theirs = room(total, dt, &tbase);
    if (!(rc = coll_p2p_send(res, total, dt, 0, T_REDUCE_SCATTER, x->comm)))
      rc = recv(x, theirs, total, dt, 0, T_REDUCE_SCATTER);
  }
  if (!rc) rc = PMPI_Scatterv(theirs, counts, displs, dt, recvbuf, counts[x->c->rank], dt, 0, x->local);
  drop(base);
  drop(tbase);
  drop(displs);
  return rc;
}

int coll_inter_reduce_scatter(const void *sendbuf, void *recvbuf, const int recvcounts[], MPI_Datatype datatype,
                              MPI_Op op, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Reduce_scatter", comm);
  int rc = coll_counts_ok(comm, x.fn, "recvcounts", recvcounts, NULL, st_comm_lsize(x.c));
  return end(&x, rc ? rc : redscat(&x, sendbuf, recvbuf, recvcounts, datatype, op));
}

int coll_inter_reduce_scatter_block(const void *sendbuf, void *recvbuf, int recvcount, MPI_Datatype datatype,
                                    MPI_Op op, MPI_Comm comm) {
  ic x;
  begin(&x, "MPI_Reduce_scatter_block", comm);
  int ln = st_comm_lsize(x.c), rc = err_comm_check_count(comm, x.fn, recvcount);
  if (rc) return end(&x, rc);
  int *counts = grab(((size_t)ln) * sizeof *counts);
  for (int i = 0; i < ln; i++) counts[i] = recvcount;
  rc = redscat(&x, sendbuf, recvbuf, counts, datatype, op);
  drop(counts);
  return end(&x, rc);
}

int coll_inter_none(MPI_Comm comm, const char *fn) {
  return err_comm_raise(comm, MPI_ERR_COMM, fn, "an intercommunicator (%s is for intracommunicators only)", fn);
}
