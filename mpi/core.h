/* core.h -- the MPI layer's inside: one rank's state, errors, communicators,
 * and point-to-point on a communicator's collective context, for the other
 * parts of the layer (datatypes, operations, collectives).
 *
 * Not for programs: mpi.h is theirs.  Everything here works on the calling
 * rank (mp_self) between its MPI_Init and MPI_Finalize, and runs on every mp
 * backend (the simulator, threads).
 *
 * COLLECTIVE CONTEXT.  Every communicator has two contexts, the same on every
 * one of its ranks: one for point-to-point and one for collectives.  The
 * calls below send and receive on the collective one, so a program's
 * receives (MPI_ANY_TAG and MPI_ANY_SOURCE included) never take a message of
 * a collective, and a collective never takes a program's.  The matching
 * rules are MPI's (doc/mpi-semantics.md): non-overtaking per source and tag,
 * receives matched in the order they were posted.  Peers are ranks in `comm`
 * (or MPI_PROC_NULL); tags are 0 .. COLL_TAG_MAX, chosen by the
 * collectives (MPI_ANY_SOURCE and MPI_ANY_TAG are allowed in receives).
 *
 * TIME.  A message of count elements is one mp message of exactly
 * count * type size bytes (packed if the type is not contiguous): on
 * --net ideal a send and its receive cost m + bytes * per_byte, so the
 * collectives' closed forms hold.  Sends are eager: they return at once.
 *
 * ERRORS.  These calls check nothing a caller could get wrong except what
 * only shows at run time (a message longer than the receive: MPI_ERR_TRUNCATE
 * in the status and the result) and return an MPI error class; they never
 * call an error handler.  The collectives check their arguments with the
 * checks below and report through err_comm_raise, which applies the
 * communicator's handler.  A run stopped by another rank (MPI_Abort, a
 * deadlock) ends the calling rank inside these calls (mp_exit): they never
 * return then.
 *
 * BLOCKING.  A collective that may block sets its own mp_label (what a
 * deadlock report prints for the rank, e.g. "MPI_Bcast(root=0,
 * MPI_COMM_WORLD)") before its first blocking call and clears it after;
 * the calls here leave the label alone. */
#ifndef TSMPI_CORE_H
#define TSMPI_CORE_H

#include <stddef.h>

#include "mpi/mpi.h"

/* ==== point-to-point on the collective context ============================ */

enum { COLL_TAG_MAX = 0x3feff };   /* the collectives' tags: 0 .. this */

/* Send count elements of dt from buf to rank dst of comm (MPI_PROC_NULL:
 * nothing).  Returns at once (eager); buf may be reused. */
int coll_p2p_send(const void *buf, int count, MPI_Datatype dt, int dst, int tag, MPI_Comm comm);

/* Receive into buf (at most count elements of dt) from rank src of comm
 * (MPI_ANY_SOURCE, MPI_PROC_NULL) with tag (MPI_ANY_TAG); st may be
 * MPI_STATUS_IGNORE.  MPI_SUCCESS or MPI_ERR_TRUNCATE (the first count
 * elements were stored). */
int coll_p2p_recv(void *buf, int count, MPI_Datatype dt, int src, int tag, MPI_Comm comm,
                  MPI_Status *st);

/* Send, then receive (the send is eager, so this never deadlocks on a pair
 * that exchanges).  The bytes received must not overlap those sent: the
 * send's payload may stay in sbuf until the call returns (one copy, when
 * the receiver takes it first or has promised its buffer). */
int coll_p2p_sendrecv(const void *sbuf, int scount, MPI_Datatype sdt, int dst, int stag,
                      void *rbuf, int rcount, MPI_Datatype rdt, int src, int rtag, MPI_Comm comm,
                      MPI_Status *st);

/* Nonblocking: *req is a request of the calling rank, completed and freed by
 * coll_p2p_waitall (or MPI_Wait*, MPI_Test*). */
int coll_p2p_isend(const void *buf, int count, MPI_Datatype dt, int dst, int tag, MPI_Comm comm,
                   MPI_Request *req);
int coll_p2p_irecv(void *buf, int count, MPI_Datatype dt, int src, int tag, MPI_Comm comm,
                   MPI_Request *req);

/* Complete n requests (MPI_REQUEST_NULL ones are skipped) and set each to
 * MPI_REQUEST_NULL; sts may be MPI_STATUSES_IGNORE.  MPI_SUCCESS, or
 * MPI_ERR_IN_STATUS with each status's MPI_ERROR set (with sts), or the
 * first error class (without). */
int coll_p2p_waitall(int n, MPI_Request *reqs, MPI_Status *sts);

/* Whether *req (of coll_p2p_isend or _irecv; MPI_REQUEST_NULL: done) is
 * done, without taking any message and without the poll cost of MPI_Test:
 * 1 and it completed (its status in *st, which may be MPI_STATUS_IGNORE;
 * *req MPI_REQUEST_NULL), or 0.  For a kind's progress (below), which runs
 * after the engine has acted on every message that has arrived. */
int coll_p2p_done(MPI_Request *req, MPI_Status *st);

/* ==== the nonblocking collectives' requests and progress ================== */

/* Mark a request of coll_p2p_isend/irecv as a step of a nonblocking
 * collective: when the engine completes it (in any MPI call of the rank, or
 * while the rank computes), the rank's progress function runs (see
 * coll_set_progress), after the message was acted on. */
void coll_p2p_watch(MPI_Request req);

/* A request given up (a schedule freed before it finished): a receive still
 * posted is taken out of the posted queue; the request is freed and *req is
 * MPI_REQUEST_NULL. */
void coll_p2p_drop(MPI_Request *req);

/* The rank's progress function: fn() runs after the engine completed a
 * watched request, at a point where it may send and post receives (never
 * block); while live (nonzero) the rank also makes progress while it
 * computes (mp_set_progress: each message that arrives while the rank
 * computes is acted on at its arrival).  fn NULL: none. */
void coll_set_progress(void (*fn)(void), int live);

/* A request of the program's for nonblocking collective fn on comm (root:
 * its root, or -1): active until coll_req_complete.  Its status is the
 * empty one; a program's MPI_Request_free lets it go on until complete. */
MPI_Request coll_req(const char *fn, MPI_Comm comm, int root);
/* The collective is done, with error class err (already raised under the
 * communicator's handler). */
void coll_req_complete(MPI_Request req, int err);

/* A nonblocking collective on comm keeps it alive: MPI_Comm_free while it
 * is held takes it from the program only, and the last release ends it
 * (MPI 3.1 section 6.4.3: freed once its pending operations complete). */
void comm_hold(MPI_Comm comm);
void comm_release(MPI_Comm comm);

/* The tag of the next nonblocking collective on comm: the same on every
 * rank, as every rank starts a communicator's collectives in the same
 * order (MPI 3.1 section 5.12), and never one of the blocking ones'
 * (NBC_TAG_MIN .. COLL_TAG_MAX, round and round). */
enum { NBC_TAG_MIN = 0x100 };
int comm_nbc_tag(MPI_Comm comm);

/* ==== requests of a kind of their own ===================================== */

/* A part of the layer (MPI_Grequest_start; the nonblocking collectives'
 * requests are of their own, above) makes requests that the program completes with the
 * Wait and Test families, frees with MPI_Request_free and cancels with
 * MPI_Cancel like any other.  Its kind says what they do; state is the
 * part's own, passed to each callback:
 *
 *   progress(state)  advance without blocking, after the engine has acted
 *                    on every message that has arrived (the Test family,
 *                    MPI_Request_get_status, MPI_Iprobe) or on each message
 *                    that comes while the rank waits in any MPI call (the
 *                    Wait family, a blocking receive with receives posted,
 *                    ...): every request of a kind not yet freed advances
 *                    then, whichever the call waits for, as MPI's progress
 *                    rule asks (not while the rank computes between calls):
 *                    1 once the request is done, 0 if not yet.  It may start and test
 *                    point-to-point requests of its own (coll_p2p_isend,
 *                    MPI_Test on them).  NULL: the request is done only by
 *                    req_complete.  A Wait on a request that nothing
 *                    can complete waits for messages, and the simulator
 *                    reports a deadlock naming the kind when no rank can
 *                    go on.
 *   cancel(state, done)  MPI_Cancel (done: whether it is done already);
 *                    returns an MPI error class (MPI_SUCCESS).  Whether a
 *                    request was cancelled is its status's (MPI_Status's
 *                    cancelled flag, set by status).  NULL: MPI_Cancel
 *                    does nothing.
 *   status(state, st)  when the request completes (a Wait or Test that
 *                    returns it, MPI_Request_get_status): fill *st (its
 *                    source, tag, count, cancelled flag; it comes in as the
 *                    empty status) and return an MPI error class, which
 *                    the call returns.  NULL: the empty status, success.
 *   free(state)      the request is gone (completed and freed, or freed by
 *                    MPI_Request_free once done); returns an error class
 *                    the call that freed it returns.  NULL: nothing.
 *   drop(state)      the rank ends with the request still there
 *                    (MPI_Finalize, a stopped run): release what state
 *                    holds, calling nothing of the program's.  NULL:
 *                    nothing.
 *
 * The calls run on the calling rank; a run stopped by another rank ends
 * the rank inside them as everywhere in the layer. */
typedef struct {
  const char *name;   /* the call that made it ("MPI_Ibarrier"): deadlock reports name it */
  int (*progress)(void *state);
  int (*cancel)(void *state, int done);
  int (*status)(void *state, MPI_Status *st);
  int (*free)(void *state);
  void (*drop)(void *state);
} req_kind;

/* A new active request of kind (which must outlive it) with state; its
 * handle in *req.  MPI_SUCCESS. */
int req_start(const req_kind *kind, void *state, MPI_Request *req);

/* Request req (of a kind without progress, or whose part completes it from
 * outside) is done: MPI_SUCCESS, or MPI_ERR_REQUEST if req is no active
 * request of a kind of its own.  If the program freed it already, it goes
 * now (free's error class is returned). */
int req_complete(MPI_Request req);

/* ==== a communicator's process topology ================================== */

/* comm's topology (topo.h), or NULL; comm checked.  set: comm (just made
 * by the caller) takes t and the caller's count of it.  MPI_Comm_dup shares
 * it (counted), MPI_Comm_free drops its count. */
struct ptopo *comm_topo(MPI_Comm comm);
void comm_set_topo(MPI_Comm comm, struct ptopo *t);

/* ==== communicators ======================================================= */

/* MPI_SUCCESS if comm is a communicator of the calling rank (not freed, not
 * MPI_COMM_NULL); else raises MPI_ERR_COMM for fn (see err_comm_raise). */
int comm_check(MPI_Comm comm, const char *fn);

/* The calling rank's rank in comm and comm's size (comm checked; an
 * intercommunicator's local group's). */
int comm_rank(MPI_Comm comm);
int comm_size(MPI_Comm comm);

/* 1 if comm is a valid intercommunicator of the calling rank, else 0 (an
 * intracommunicator, or not a communicator: the caller's checks say so).
 * On an intercommunicator, the point-to-point calls above name ranks of
 * the remote group (comm_remote_size of them); each collective
 * hands an intercommunicator to coll_inter.h's before anything else. */
int comm_inter(MPI_Comm comm);
int comm_remote_size(MPI_Comm comm);

/* comm's name for messages: "MPI_COMM_WORLD", "MPI_COMM_SELF", or
 * "communicator N", N the same on every rank of it (valid until the
 * communicator is freed; "MPI_COMM_NULL" and "an invalid communicator" for
 * those). */
const char *comm_get_name(MPI_Comm comm);

/* The mp rank (MPI_COMM_WORLD rank) of rank r of comm (comm checked,
 * 0 <= r < size; the remote group's rank r on an intercommunicator). */
int comm_world_rank(MPI_Comm comm, int r);

/* ==== errors ============================================================== */

/* An error of MPI function fn (e.g. "MPI_Bcast") with class cls and a
 * message (printf format; no trailing newline), under comm's error handler
 * (MPI_COMM_WORLD's when comm is not a valid communicator: MPI 3.1 section
 * 8.3).  MPI_ERRORS_ARE_FATAL: the run ends with exit status 1 and the
 * message "rank R: FN: MESSAGE" (mp_abort; the runner prints it), and this
 * never returns.  MPI_ERRORS_RETURN: returns cls. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
int err_comm_raise(MPI_Comm comm, int cls, const char *fn, const char *fmt, ...);

/* Argument checks every call makes, in MPI's words; each returns
 * MPI_SUCCESS or raises (err_comm_raise) for fn on comm:
 *   err_comm_check_count   count >= 0                          MPI_ERR_COUNT
 *   err_comm_check_buf     buf != NULL, unless count elements of dt can go
 *                       with MPI_BOTTOM (dtype_bottom_ok)     MPI_ERR_BUFFER
 *   err_comm_check_rank    0 <= r < size of comm (MPI_PROC_NULL allowed;
 *                       MPI_ANY_SOURCE when any_ok)         MPI_ERR_RANK
 *   err_comm_check_root    0 <= root < size of comm            MPI_ERR_ROOT */
int err_comm_check_count(MPI_Comm comm, const char *fn, int count);
int err_comm_check_buf(MPI_Comm comm, const char *fn, const void *buf, int count, MPI_Datatype dt);
int err_comm_check_rank(MPI_Comm comm, const char *fn, int r, int any_ok);
int err_comm_check_root(MPI_Comm comm, const char *fn, int root);

/* ==== attributes of datatypes ============================================= */

/* MPI_Type_dup made dup from old: old's attributes copied by their
 * callbacks (attr.h); MPI_Type_free is freeing dt: its attributes deleted
 * first.  MPI_SUCCESS, or a callback's error raised for fn on
 * MPI_COMM_WORLD's handler (dup then has none of old's; dt keeps those
 * not deleted). */
int attr_type_copy(MPI_Datatype old, MPI_Datatype dup, const char *fn);
int attr_type_delete(MPI_Datatype dt, const char *fn);

/* ==== the rank's state for the other parts of the layer =================== */

/* One pointer per part of the MPI layer and rank (NULL after MPI_Init):
 * the datatype module's table of created types, the operations', the
 * collectives', the collectives' schedules, the nonblocking collectives',
 * the open files', the windows'.  release(p), if not NULL, is
 * called once at MPI_Finalize or when the rank ends without it (a stopped
 * run), parts in reverse order. */
enum { ST_PART_DTYPE, ST_PART_OP, ST_PART_COLL, ST_PART_SCHED, ST_PART_NBC, ST_PART_IO, ST_PART_WIN, ST_PARTS };
void *st_part(int part);
void st_part_set(int part, void *p, void (*release)(void *p));

#endif
