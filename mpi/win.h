/* win.h -- one-sided communication inside the MPI layer: windows, the
 * operations on them and their synchronisation (MPI 3.1 chapter 11), for
 * win.c (windows: creation, memory, attributes, names, info, handlers),
 * rma.c (operations: issued, applied, completed), rma_api.c (MPI_Put,
 * MPI_Get, ... and their request-based forms) and win_sync.c (fence,
 * post/start/complete/wait, locks, flushes).
 *
 * Not for programs (mpi.h is theirs).
 *
 * ORIGIN-DRIVEN.  Every rank of a run lives in one address space, so an
 * origin applies its operations to the target's memory itself, as a network
 * card with remote memory access would: the target takes no part and
 * needs no progress.  What an operation costs is what its messages would:
 * its request (the origin's data for a put or an accumulate) travels from
 * the origin to the target, charged on the network (mp_transfer), and is
 * applied when it arrives; its reply (a get's data, or an acknowledgement
 * of 0 bytes) travels back, and the operation is complete at the origin
 * when that arrives.  On the simulator the origin applies an operation at
 * its arrival time, in the global order of simulated time (it sleeps until
 * then, mp_sleep): it does so at its next one-sided call on the window that
 * needs it, so an operation whose origin computes past its arrival is
 * applied when the origin comes back (doc/mpi-semantics.md says what that
 * changes: only the order of concurrent accumulates, which MPI leaves
 * open).  On the threads backend an operation is applied when it is
 * issued.
 *
 * SHARED STATE.  The ranks of a window share one object (rma_shared),
 * made by the window's rank 0: each rank's memory (base, size, unit), the
 * regions attached to a dynamic window, and each rank's passive-target lock
 * with its queue of waiting origins.  Its mutex guards all of it and every
 * data move into the window's memory (the threads backend's ranks run at
 * once; on the simulator it is never contended).  The last rank of the
 * window to let go of it frees it.  Nothing that may switch ranks (an mp
 * call) is called while the mutex is held.
 *
 * MESSAGES.  A window has a communicator of its own (hidden: a duplicate of
 * the one it was made on), whose collective context carries its barriers
 * and whose point-to-point context its notifications: a post to each
 * origin of MPI_Win_start, a done to each target of MPI_Win_wait, a lock's
 * grant to a waiting origin, a request's wake-up to its own rank. */
#ifndef TSMPI_WIN_H
#define TSMPI_WIN_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

#include "mpi/state.h"

/* The notifications' tags on the window's point-to-point context. */
enum { WTAG_POST = 1, WTAG_DONE = 2, WTAG_GRANT = 3, WTAG_WAKE = 4 };

/* ==== what the ranks share ================================================ */

typedef struct {
  char *base;
  MPI_Aint size;
} rma_region;

typedef struct {
  int rank;                /* the origin's rank in the window */
  int excl;                /* it asked for MPI_LOCK_EXCLUSIVE */
} rma_lockwait;

/* One rank's part of a window. */
typedef struct {
  char *base;              /* its memory (NULL: none, or a dynamic window) */
  MPI_Aint size;
  int disp_unit;
  int wrank;               /* its MPI_COMM_WORLD rank */
  char *mem;               /* MPI_Win_allocate's memory, freed with the window */
  rma_region *regs;        /* a dynamic window's attached regions */
  int nregs, capregs;
  int excl;                /* its lock: held exclusively, */
  int shared;              /* or by this many shared holders */
  rma_lockwait *q;         /* origins waiting for it, in the order their requests came */
  int nq, capq;
} rma_part;

typedef struct {
  pthread_mutex_t mu;      /* everything here, and data moves into the window's memory */
  int refs;                /* ranks that still hold it */
  int n;
  char *seg;               /* MPI_Win_allocate_shared's memory, freed with it */
  rma_part part[];        /* n: rank r's at part[r] */
} rma_shared;

/* ==== a rank's window ===================================================== */

typedef struct rma_op rma_op;   /* an operation issued and not yet applied (rma.c) */
typedef struct rma_tgt rma_tgt; /* what a rank knows of one target (rma.c) */

/* The hints a window keeps (MPI 3.1 section 11.2.1; MPI_Win_get_info). */
typedef struct {
  int no_locks;
  int same_size, same_disp_unit;
  int alloc_shared_noncontig;
  char ordering[64];       /* accumulate_ordering */
  char ops[32];            /* accumulate_ops */
} rma_hints;

typedef struct {
  MPI_Win h;
  int flavor;              /* MPI_WIN_FLAVOR_* */
  MPI_Comm comm;           /* its own communicator (hidden) */
  st_comm *c;             /* that communicator */
  int rank, size;          /* in it */
  rma_shared *sh;
  char name[MPI_MAX_OBJECT_NAME];
  MPI_Errhandler eh;       /* held */
  rma_hints hints;
  /* epochs */
  int fence;               /* a fence's epoch is open: every rank may be a target */
  int lockall;             /* MPI_Win_lock_all's epoch */
  int nlocked;             /* targets locked one by one (their rma_tgt says how) */
  int *acc;                /* MPI_Win_start's group (ranks in the window), or NULL */
  int nacc;
  MPI_Request *postrq;     /* its posts, one receive each */
  int *expo;               /* MPI_Win_post's group, or NULL */
  int nexpo;
  MPI_Request *donerq;     /* its dones, one receive each */
  /* operations (rma.c) */
  rma_op *ops, *ops_tail;  /* issued, not yet applied: by (arrival, order issued) */
  rma_op *deferred;        /* to targets whose post has not come */
  uint64_t seq;
  rma_tgt *tg;             /* the targets it has known: open addressing */
  int ntg, captg;
  double done_all;         /* the latest reply of every operation applied */
} rma_window;

/* The calling rank's window of handle h, or NULL (MPI_WIN_NULL, freed, not a window). */
rma_window *rma_win_get(st_rank *R, MPI_Win h);

/* h valid for call fn: *w, or the error raised (MPI_ERR_WIN under
 * MPI_COMM_WORLD's handler, as MPICH: a window that is not one has none). */
int rma_win_check(st_rank *R, MPI_Win h, const char *fn, rma_window **w);

/* An error of call fn on w under its handler: the class returned, or the
 * run ended (fatal). */
#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
int rma_win_raise(st_rank *R, rma_window *w, int cls, const char *fn, const char *fmt, ...);

/* The window's name for messages and deadlock reports: "window N" (N its
 * communicator's context pair, the same on its every rank). */
const char *rma_win_words(const rma_window *w, char *buf);

/* What a rank blocked in a window's call waits in, for the deadlock
 * report: "MPI_Win_lock(MPI_LOCK_EXCLUSIVE, rank=1, window 3)". */
typedef struct {
  const char *fn;
  const rma_window *w;
  int rank;                /* a target, or -1 */
  int lock;                /* MPI_LOCK_*, or 0 */
} rma_wlabel;
void rma_wlabel_set(st_rank *R, rma_wlabel *l);

/* ==== operations (rma.c) ================================================== */

enum { OP_PUT, OP_GET, OP_ACC, OP_GACC, OP_CAS, OP_LOCK, OP_UNLOCK };

/* An operation's arguments, checked by the caller (rma_api.c): kind OP_*,
 * the target's rank in the window (not MPI_PROC_NULL) and where its
 * elements lie (tcount of tdt at taddr), the origin's (ocount of odt at
 * obuf: put's and accumulate's data), the result's (rcount of rdt at rbuf:
 * get's and fetching accumulate's), compare (MPI_Compare_and_swap's value),
 * op, and for OP_LOCK the lock's kind. */
typedef struct {
  int kind;
  int target;
  char *taddr;
  int tcount;
  MPI_Datatype tdt;
  const void *obuf;
  int ocount;
  MPI_Datatype odt;
  void *rbuf;
  int rcount;
  MPI_Datatype rdt;
  const void *compare;
  MPI_Op op;
  int lock;
} rma_args;

/* A request-based operation's completion: the time its reply arrives,
 * known once it is applied (done set then). */
typedef struct {
  int applied;
  double at;
} rma_done;

/* Issue an operation now: its request leaves for the target (deferred
 * while the target's post has not come, in a post/start epoch), the origin
 * data are copied, the types held; applied when it arrives (rma_progress).
 * done (or NULL) learns its completion. */
void rma_issue(st_rank *R, rma_window *w, const rma_args *a, rma_done *done);

/* Apply every operation that has arrived by time t (sleeping to each
 * arrival, in order). */
void rma_progress(st_rank *R, rma_window *w, double t);

/* Wait until the operation that done belongs to is complete (its reply
 * back). */
void rma_wait_done(st_rank *R, rma_window *w, rma_done *d);

/* Complete the operations to target (-1: every target): apply them all and
 * sleep until their replies have come (local = 1: only those whose reply
 * carries data, MPI_Win_flush_local). */
void rma_complete(st_rank *R, rma_window *w, int target, int local);

/* Issue the operations deferred for target's post, which has come. */
void rma_posted(st_rank *R, rma_window *w, int target);

/* Lock target (MPI_LOCK_SHARED or MPI_LOCK_EXCLUSIVE) or release it: the
 * request travels, is granted or queued at the target, and the call
 * returns when the grant (or the release's acknowledgement and every
 * operation's reply) is back; with nocheck (MPI_MODE_NOCHECK) nothing is
 * asked of the target, and the release only completes the operations.  The
 * _all forms ask every rank at once (the caller does nocheck's nothing). */
void rma_lock(st_rank *R, rma_window *w, int target, int lock, int nocheck);
void rma_unlock(st_rank *R, rma_window *w, int target);
void rma_lock_all(st_rank *R, rma_window *w);
void rma_unlock_all(st_rank *R, rma_window *w);

/* The lock w holds on target (0: none). */
int rma_locked(rma_window *w, int target);

/* MPI_Win_start's group (w->acc, w->nacc): a receive for each target's
 * post; operations to a target whose post has not come wait for it. */
void rma_access_begin(st_rank *R, rma_window *w);

/* 1 if target is in the start group. */
int rma_access_has(rma_window *w, int target);

/* 1 if target is in the start group and its post has come. */
int rma_access_posted(st_rank *R, rma_window *w, int target);

/* MPI_Win_complete: every post waited for (the operations deferred for one
 * leave when it comes), a done notification to each target (leaving now,
 * after the operations on its channel, sent once they are applied), and
 * the operations complete locally (their replies with data in). */
void rma_access_end(st_rank *R, rma_window *w);

/* Free the window's operation state (its end; nothing pending). */
void rma_release(rma_window *w);

/* The clock moves on to t if it is before (mp_sleep: the processor is free
 * meanwhile). */
void rma_until(st_rank *R, double t);

#endif
