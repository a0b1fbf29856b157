/* coll.h -- the collectives' inside: which algorithm runs (MPICH's choice, --coll linear, or an
 * override), and the algorithms themselves, on packed bytes over point-to-point (core.h).
 *
 * Not for programs.  The MPI_* functions (coll_api.c, coll_redapi.c, ...)
 * check their arguments, pack the data (dtype.h), pick an algorithm (the
 * run's setting, else MPICH's choice) and build its schedule (coll_sched.h),
 * which runs at once (the blocking collectives) or as messages arrive (the
 * nonblocking ones, nbc.h); a reduction combines packed elements with op.h.
 *
 * THE ALGORITHMS are MPICH's (pmodels/mpich, src/mpi/coll/<name>/), with its
 * names (its MPIR_CVAR_<COLL>_INTRA_ALGORITHM values), message for message:
 * the same peers, the same sizes, the same order of sends and receives, so a
 * run's simulated time is what MPICH's algorithm costs on the machine.  Each
 * file says the source of each.  --coll linear runs the plain ones (a root
 * sending to or receiving from every rank in turn), as Open MPI's "basic
 * linear" component does.
 *
 * REDUCTION ORDER.  Every algorithm combines in a fixed order that depends on
 * the algorithm, the number of ranks, the root and the count, never on when
 * messages arrive: MPICH's, operand for operand (a received partial result
 * on the left of the local one for commutative operations, ranks in order
 * for the others); the linear ones fold in rank order, ((a0 op a1) op a2)
 * ...  doc/mpi-support.md states each algorithm's order. */
#ifndef TSMPI_COLL_H
#define TSMPI_COLL_H

#include <stddef.h>

#include "mpi/mpi.h"

/* ==== choosing ============================================================ */

/* The collectives, each with its algorithms; ALG_AUTO is MPICH's choice. */
typedef enum {
  COLL_BARRIER, COLL_BCAST, COLL_REDUCE, COLL_ALLREDUCE, COLL_GATHER, COLL_GATHERV, COLL_SCATTER,
  COLL_SCATTERV, COLL_ALLGATHER, COLL_ALLGATHERV, COLL_ALLTOALL, COLL_ALLTOALLV, COLL_SCAN, COLL_EXSCAN,
  COLL_REDUCE_SCATTER, COLL_REDUCE_SCATTER_BLOCK, COLL_ALLTOALLW,
  COLL_NEIGHBOR_ALLGATHER, COLL_NEIGHBOR_ALLGATHERV, COLL_NEIGHBOR_ALLTOALL, COLL_NEIGHBOR_ALLTOALLV,
  COLL_NEIGHBOR_ALLTOALLW, COLL_N
} coll_id;

typedef enum {
  ALG_AUTO,
  ALG_LINEAR,
  ALG_DISSEMINATION,                         /* barrier */
  ALG_BINOMIAL,                              /* bcast, reduce, gather, scatter */
  ALG_SCATTER_RECURSIVE_DOUBLING_ALLGATHER,  /* bcast */
  ALG_SCATTER_RING_ALLGATHER,                /* bcast */
  ALG_RECURSIVE_DOUBLING,                    /* allreduce, allgather(v), scan, exscan, reduce_scatter(_block) */
  ALG_REDUCE_SCATTER_ALLGATHER,              /* allreduce (Rabenseifner) */
  ALG_REDUCE_SCATTER_GATHER,                 /* reduce (Rabenseifner) */
  ALG_BRUCKS,                                /* allgather(v), alltoall */
  ALG_RING,                                  /* allgather(v) */
  ALG_SCATTERED,                             /* alltoall(v) */
  ALG_PAIRWISE,                              /* alltoall, reduce_scatter(_block) */
  ALG_PAIRWISE_SENDRECV_REPLACE,             /* alltoall(v) in place */
  ALG_RECURSIVE_HALVING,                     /* reduce_scatter(_block) */
  ALG_NONCOMMUTATIVE,                        /* reduce_scatter(_block) */
  ALG_N
} coll_alg;

/* The collective's and the algorithm's names: "bcast", "binomial". */
const char *coll_name(coll_id c);
const char *coll_alg_name(coll_alg a);

/* The algorithm the run's setting gives collective c (ALG_AUTO: MPICH's
 * choice, which the caller makes). */
coll_alg coll_setting(coll_id c);

/* ==== the group a collective runs on ====================================== */

typedef struct {
  MPI_Comm comm;
  int rank, size;
  int tag;          /* the collective's tag on the collective context */
  const char *fn;   /* "MPI_Bcast", for errors */
} coll_cg;

/* Bytes to and from ranks of the group (core.h's calls with MPI_BYTE).
 * recv: *got, if not NULL, gets the bytes that came.  MPI_SUCCESS, or an
 * error class already raised under the communicator's handler (a message
 * longer than expected: the ranks disagree on the counts). */
int coll_cg_send(const coll_cg *g, const void *buf, size_t n, int dst);
int coll_cg_recv(const coll_cg *g, void *buf, size_t n, int src, size_t *got);
int coll_cg_sendrecv(const coll_cg *g, const void *sbuf, size_t sn, int dst, void *rbuf, size_t rn, int src,
                     size_t *got);
/* Nonblocking, completed together by coll_cg_waitall. */
int coll_cg_isend(const coll_cg *g, const void *buf, size_t n, int dst, MPI_Request *req);
int coll_cg_irecv(const coll_cg *g, void *buf, size_t n, int src, MPI_Request *req);
int coll_cg_waitall(const coll_cg *g, int n, MPI_Request *reqs);
/* A request of the group's (from src, or -1) that ended with error class err: raised. */
int coll_cg_failed(const coll_cg *g, int err, int src);

/* Scratch memory outside a schedule: malloc that aborts with a message when
 * memory runs out, kept on the rank's list so that a run stopped meanwhile
 * frees it at the rank's end; free it with coll_cg_free (NULL: nothing). */
void *coll_cg_alloc(const coll_cg *g, size_t n);
void coll_cg_free(void *p);

/* The largest power of two <= n (n >= 1), and whether n is one. */
int coll_pof2(int n);
int coll_is_pof2(int n);

/* ==== the frame of every MPI collective (coll_frame.c) ==================== */

typedef struct coll_sched coll_sched;   /* coll_sched.h */

/* What a rank waits in, for the deadlock report: "MPI_Bcast(root=0,
 * MPI_COMM_WORLD)". */
typedef struct {
  const char *fn;
  MPI_Comm comm;
  const char *comm_name;   /* comm_get_name's, valid while the call runs */
  int root;                /* -1: none */
} coll_label;

/* The start of collective fn (which: its tag and setting; root, or -1) on a
 * checked communicator: blocking when req is NULL (the collective's own
 * tag; the rank's label names the call for a deadlock report, and the trace
 * shows the call as one slice: mp_call_begin), nonblocking otherwise (a
 * fresh tag of the communicator's sequence: comm_nbc_tag).  Returns the
 * schedule its algorithm is built into (coll_sched.h), its group filled. */
coll_sched *coll_start(const char *fn, MPI_Comm comm, coll_id which, int root, MPI_Request *req);
/* The end: blocking, the schedule run (coll_sched_run), the label and the
 * slice ended, its result; nonblocking, the schedule started (nbc.h), *req
 * its request (done already if nothing was left to wait for), MPI_SUCCESS. */
int coll_finish(coll_sched *s);
/* An error found after the start (rc, raised): the schedule dropped, the
 * call ended; returns rc. */
int coll_fail(coll_sched *s, int rc);
/* A nonblocking collective fn on an intercommunicator: its blocking form
 * (coll_inter.h) has run, with result rc; *req (checked here) is a request
 * done already (MPI_REQUEST_NULL on an error).  Returns rc. */
int coll_ran(const char *fn, MPI_Comm comm, int rc, MPI_Request *req);

/* Argument checks; each returns MPI_SUCCESS or raises under comm's handler. */
int coll_type_ok(MPI_Comm comm, const char *fn, const char *what, MPI_Datatype dt);   /* committed */
int coll_op_ok(MPI_Comm comm, const char *fn, MPI_Op op, MPI_Datatype dt);           /* applies to dt */
/* count >= 0, dt committed, buf non-NULL if it must be (MPI_IN_PLACE passes). */
int coll_data_ok(MPI_Comm comm, const char *fn, const char *what, const void *buf, int count,
                 MPI_Datatype dt);
/* n counts >= 0, and the arrays there (displs may be NULL when what starts
 * with 'r' and none are needed). */
int coll_counts_ok(MPI_Comm comm, const char *fn, const char *what, const int *counts, const int *displs,
                   int n);
int coll_in_place_bad(MPI_Comm comm, const char *fn, const char *which);
/* A nonblocking call's request argument (NULL: MPI_ERR_ARG raised). */
int coll_req_ok(MPI_Comm comm, const char *fn, const MPI_Request *req);

/* count elements of dt at buf packed into the schedule's memory, and the
 * step that unpacks them at the end. */
char *coll_pack(coll_sched *s, const void *buf, int count, MPI_Datatype dt);
/* count elements of dt at buf as packed bytes to read: where they lie when
 * they are contiguous (dtype_contig: no copy), else coll_pack's. */
const char *coll_view(coll_sched *s, const void *buf, int count, MPI_Datatype dt);
/* Where a collective builds the packed bytes it leaves in count elements of
 * dt at buf: buf's own bytes when they are contiguous, else the schedule's
 * memory (packed from buf first when fill), which coll_sched_unpack copies
 * back at the end; onto bytes in place, coll_sched_unpack does nothing.  So
 * a contiguous buffer costs no copy and no memory of the collective's. */
char *coll_place(coll_sched *s, void *buf, int count, MPI_Datatype dt, int fill);
/* A v or w collective's blocks where they lie: block i, of bytes[i] bytes, is
 * counts[i] elements of types[i] at displs[i] bytes from buf (the w forms),
 * or, types NULL, of dt at displs[i] extents of dt.  If every block with
 * bytes is contiguous, the lowest one's address, each block's distance from
 * it in off[] (0 for empty blocks); else NULL, off untouched. */
char *coll_vdirect(const void *buf, const int *counts, const int *displs, const MPI_Datatype *types, MPI_Datatype dt,
                   int n, const size_t *bytes, size_t *off);
/* Element i of dt at buf (i extents on). */
void *coll_at(const void *buf, MPI_Aint i, MPI_Datatype dt);

/* ==== the algorithms: builders of schedules on packed bytes ===============
 * Each adds the calling rank's steps to s (coll_sched.h); buffers hold packed
 * data (dtype.h), in the schedule's memory or lasting as long.  A
 * reduction's elements are `count` elements of the schedule's reduction
 * (coll_sched_red: its type, op, packed size tsize), combined with op.h. */

/* The reductions' element description. */
typedef struct {
  MPI_Datatype dt;
  MPI_Op op;
  size_t tsize;    /* packed bytes of one element */
  int commute;     /* op is commutative */
} coll_red;

void coll_barrier_linear(coll_sched *s);
void coll_barrier_dissemination(coll_sched *s);

void coll_bcast_linear(coll_sched *s, void *buf, size_t n, int root);
void coll_bcast_binomial(coll_sched *s, void *buf, size_t n, int root);
void coll_bcast_scatter_rdb_allgather(coll_sched *s, void *buf, size_t n, int root);
void coll_bcast_scatter_ring_allgather(coll_sched *s, void *buf, size_t n, int root);

/* Gather: sbuf's n bytes from every rank into rbuf at the root, rank r's at
 * r * n (rbuf used at the root only).  sbuf NULL at the root: its block is
 * in place. */
void coll_gather_linear(coll_sched *s, const void *sbuf, void *rbuf, size_t n, int root);
void coll_gather_binomial(coll_sched *s, const void *sbuf, void *rbuf, size_t n, int root);
/* Scatter: block r of sbuf (the root's, n bytes each) into rank r's rbuf
 * (rbuf NULL at the root: its block stays in place). */
void coll_scatter_linear(coll_sched *s, const void *sbuf, void *rbuf, size_t n, int root);
void coll_scatter_binomial(coll_sched *s, const void *sbuf, void *rbuf, size_t n, int root);
/* The v forms: counts[r] bytes at displs[r] of the root's buffer. */
void coll_gatherv_linear(coll_sched *s, const void *sbuf, size_t sn, void *rbuf, const size_t *counts,
                         const size_t *displs, int root);
void coll_scatterv_linear(coll_sched *s, const void *sbuf, const size_t *counts, const size_t *displs,
                          void *rbuf, size_t rn, int root);

/* Allgather: every rank's block (already at buf + displs[rank], counts[r]
 * bytes each, the blocks in rank order from displs[0] = 0) to every rank
 * (counts and displs last as long as the schedule). */
void coll_allgatherv_linear(coll_sched *s, void *buf, const size_t *counts, const size_t *displs);
void coll_allgatherv_recursive_doubling(coll_sched *s, void *buf, const size_t *counts, const size_t *displs);
void coll_allgatherv_brucks(coll_sched *s, void *buf, const size_t *counts, const size_t *displs);
void coll_allgatherv_ring(coll_sched *s, void *buf, const size_t *counts, const size_t *displs);
/* The ring as MPICH's allgatherv runs it: pipelined when a block is longer
 * than 32 KiB of the receive type (unit packed bytes, extent bytes laid
 * out, per element). */
void coll_allgatherv_ring_pipelined(coll_sched *s, void *buf, const size_t *counts, const size_t *displs,
                                    size_t unit, size_t extent);

/* Alltoall(v): sbuf's block for rank r (counts sc[r] at sd[r]) to rank r's
 * rbuf block from us (rc[us] at rd[us]).  The pairwise sendrecv_replace one
 * is in place (rbuf holds the blocks to send and gets the blocks
 * received). */
void coll_alltoallv_linear(coll_sched *s, const void *sbuf, const size_t *sc, const size_t *sd, void *rbuf,
                           const size_t *rc, const size_t *rd);
void coll_alltoallv_scattered(coll_sched *s, const void *sbuf, const size_t *sc, const size_t *sd, void *rbuf,
                              const size_t *rc, const size_t *rd);
void coll_alltoallv_pairwise_sendrecv_replace(coll_sched *s, void *rbuf, const size_t *rc, const size_t *rd);
void coll_alltoall_scattered(coll_sched *s, const void *sbuf, void *rbuf, size_t n);
void coll_alltoall_brucks(coll_sched *s, const void *sbuf, void *rbuf, size_t n);
void coll_alltoall_pairwise(coll_sched *s, const void *sbuf, void *rbuf, size_t n);

/* Reduce: count elements of every rank's sbuf combined into the root's
 * rbuf (sbuf NULL at the root: its operand is in rbuf). */
void coll_reduce_linear(coll_sched *s, const void *sbuf, void *rbuf, int count, int root);
void coll_reduce_binomial(coll_sched *s, const void *sbuf, void *rbuf, int count, int root);
void coll_reduce_scatter_gather(coll_sched *s, const void *sbuf, void *rbuf, int count, int root);
/* Allreduce: buf holds this rank's operand and gets the result. */
void coll_allreduce_linear(coll_sched *s, void *buf, int count);
void coll_allreduce_recursive_doubling(coll_sched *s, void *buf, int count);
void coll_allreduce_reduce_scatter_allgather(coll_sched *s, void *buf, int count);
/* Reduce_scatter: buf holds this rank's whole operand (the sum of counts
 * elements); block r of the result (counts[r] elements) goes to rank r's
 * out (counts last as long as the schedule). */
void coll_reduce_scatter_linear(coll_sched *s, void *buf, void *out, const int *counts);
void coll_reduce_scatter_recursive_halving(coll_sched *s, void *buf, void *out, const int *counts);
void coll_reduce_scatter_pairwise(coll_sched *s, void *buf, void *out, const int *counts);
void coll_reduce_scatter_recursive_doubling(coll_sched *s, void *buf, void *out, const int *counts);
void coll_reduce_scatter_noncommutative(coll_sched *s, void *buf, void *out, const int *counts);
/* Scan (inclusive) and exscan: rank r's out gets ranks 0..r's (0..r-1's)
 * operands combined; exscan leaves rank 0's out alone. */
void coll_scan_linear(coll_sched *s, const void *in, void *out, int count);
void coll_scan_recursive_doubling(coll_sched *s, const void *in, void *out, int count);
void coll_exscan_linear(coll_sched *s, const void *in, void *out, int count);
void coll_exscan_recursive_doubling(coll_sched *s, const void *in, void *out, int count);

/* left op right into right, count elements (op.h's order: in is left). */
void coll_red_apply(const coll_red *r, const void *left, void *right, int count);

#endif
