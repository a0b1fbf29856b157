/* comm.h -- what the communicator constructors share (comm.c, intercomm.c,
 * and the calls of comm_query.c, info.c, win.c and coll_transport.c that
 * make or read one): messages among the ranks that make a communicator,
 * agreeing on a context pair, and a new communicator in the rank's table.
 *
 * CONTEXTS.  A new communicator needs a context pair (state.h) that no rank
 * of it uses for another communicator, the same on all of them.  Each rank
 * keeps a bitmap of the pairs it uses; the ranks that make the
 * communicator OR theirs up a binomial tree to one of them, which takes the
 * lowest pair free on all (MPICH's way, with an allreduce), and the pair
 * comes back down the tree.  An intercommunicator's two groups do that each
 * to its leader, and the leaders swap their bitmaps.  Every message is a
 * message of the simulated machine, on a parent's collective context with
 * the constructors' tags (state.h: TAG_CTXID ...): a communicator costs
 * simulated time, as on a real machine. */
#ifndef TSMPI_COMM_H
#define TSMPI_COMM_H

#include <stddef.h>

#include "mpi/state.h"

enum { PAIR_BYTES = CTX_PAIRS / 8 };

/* Scratch memory for a constructor that may block (n bytes, from fn's
 * call): freed at the rank's end if the run stops meanwhile (coll.h's
 * coll_cg_alloc); comm_scratch_free frees it (NULL: nothing). */
void *comm_scratch(const char *fn, size_t n);
void comm_scratch_free(void *p);

/* The world rank of member i of g. */
static inline int comm_member(const st_ranks *g, int i) { return g->world ? g->world[i] : i; }

/* A message of len bytes to, or from, world rank w on context ctx with tag
 * (a receive takes exactly len bytes: any other length is the layer's bug). */
void comm_xsend(st_rank *R, int ctx, int w, int tag, const void *buf, size_t len);
void comm_xrecv(st_rank *R, int ctx, int w, int tag, void *buf, size_t len);

/* The leaders of two groups swap a message of any length: *in (scratch,
 * *inlen bytes) gets the other's. */
void comm_xswap(st_rank *R, int ctx, int w, int tag, const void *out, size_t outlen, void **in, size_t *inlen);

/* Broadcast len bytes from member root of g (the calling rank is member
 * me) down a binomial tree. */
void comm_tree_bcast(st_rank *R, int ctx, const st_ranks *g, int me, int root, int tag, void *buf, size_t len);

/* OR each member's used[PAIR_BYTES] up a binomial tree to member root
 * (whose used holds the OR after; the others' are spoilt), with tag. */
void comm_tree_or(st_rank *R, int ctx, const st_ranks *g, int me, int root, int tag, unsigned char *used);

/* The lowest pair not set in used and not `except`, or -1. */
int comm_pair_lowest(const unsigned char *used, int except);

/* Pair p taken by, or given back by, the calling rank. */
void comm_pair_take(st_rank *R, int p);
void comm_pair_give(st_rank *R, int p);

/* The lowest context pair that no member of g uses, agreed by all of them
 * on ctx with tags tag (up) and tag + 1 (down), and taken by the calling
 * rank; -1 if every pair is used by one. */
int comm_agree_pair(st_rank *R, int ctx, const st_ranks *g, int me, int tag);

/* A new communicator of R with ranks g (counted: taken), pair, the
 * calling rank's rank, handler (held) and hints; its handle. */
MPI_Comm comm_add(st_rank *R, st_ranks *g, int pair, int rank, MPI_Errhandler eh, unsigned hints);

/* "no context left" raised for call fn on c. */
int comm_no_pair(st_rank *R, const st_comm *c, const char *fn);

/* The end of communicator *comm (its attributes deleted already): its
 * pairs given back, its handle MPI_COMM_NULL. */
void comm_end(st_rank *R, MPI_Comm *comm);

/* MPI_Comm_dup's work (dup, idup, dup_with_info): a duplicate of comm for
 * call fn with its attributes copied, or an error raised. */
int comm_dup(st_rank *R, MPI_Comm comm, const char *fn, MPI_Comm *newcomm);

/* The world ranks of the ranks of `table` ((color, key) by rank of g, n
 * ranks) with color, ordered by key then rank (malloc'd): their number in
 * *m, and the place of rank `mine` of g among them in *me (-1 if it is not
 * there). */
int *comm_split_members(const int *table, int n, const st_ranks *g, int color, int mine, int *m, int *me);

/* Intercommunicators (intercomm.c): the ones made from an
 * intercommunicator by MPI_Comm_dup, MPI_Comm_split and MPI_Comm_create;
 * color MPI_UNDEFINED, and a rank outside group, get MPI_COMM_NULL. */
int comm_inter_dup(st_rank *R, st_comm *c, const char *fn, MPI_Comm *newcomm);
int comm_inter_split(st_rank *R, st_comm *c, const char *fn, int color, int key, MPI_Comm *newcomm);
int comm_inter_create(st_rank *R, st_comm *c, const char *fn, const st_ranks *group, MPI_Comm *newcomm);

#endif
