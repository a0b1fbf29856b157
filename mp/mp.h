/* mp.h -- the small message-passing interface the algorithm is written against.
 *
 * Nothing here says what runs it.  The simulator (sim/), POSIX threads and MPI
 * each implement these calls behind the same handle, so the paper's algorithm
 * (algo/par*.c) is written once and runs unmodified on all of them.
 *
 * A program is one entry function per rank with a user pointer (mp_proc).
 * Ranks share no memory through this interface: a message is copied out of
 * the sender's buffer at mp_send and into the receiver's at mp_recv (a
 * layer that wants one copy instead of two has the calls of "Messages
 * without copies", below).
 * Messages between one pair of ranks are received in the order they were
 * sent (MPI's non-overtaking rule); every backend guarantees it. */
#ifndef MP_H
#define MP_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
#define MP_THREAD_LOCAL thread_local
#else
#define MP_THREAD_LOCAL _Thread_local
#endif

#if defined(__STDC_VERSION__) && __STDC_VERSION__ >= 201112L
#define MP_NORETURN _Noreturn
#elif defined(__GNUC__)
#define MP_NORETURN __attribute__((noreturn))
#else
#define MP_NORETURN
#endif

typedef struct mp mp;   /* one rank's handle on the machine (opaque) */

enum { MP_ANY = -1 };   /* wildcard for the source or the tag of mp_recv/mp_probe */

/* Status codes: MP_OK, or a negative error. */
enum {
  MP_OK = 0,
  MP_EDEADLOCK = -1,  /* every live rank waits in recv and nothing is in flight */
  MP_ERANK = -2,      /* no such rank */
  MP_ETRUNC = -3,     /* the message is longer than the buffer (it is consumed) */
  MP_EARG = -4,       /* bad argument: negative tag, negative compute, ... */
  MP_ESTOPPED = -5,   /* the run was stopped (deadlock or error): return now */
  MP_EGONE = -6       /* a held message its sender withdrew (mp_msg_read) */
};

typedef struct {
  int source;   /* sending rank */
  int tag;      /* the message's tag (>= 0) */
  size_t len;   /* its length in bytes */
} mp_status;

typedef void (*mp_main)(mp *self, void *ud);

typedef struct {
  mp_main main;   /* rank r runs procs[r].main(self, procs[r].ud) */
  void *ud;
} mp_proc;

int    mp_rank(const mp *self);   /* 0 .. mp_size-1 */
int    mp_size(const mp *self);

/* Send len bytes to rank dst with tag >= 0.  Buffered: returns at once, the
 * buffer may be reused.  MP_OK, MP_ERANK, MP_EARG or MP_ESTOPPED. */
int    mp_send(mp *self, int dst, int tag, const void *buf, size_t len);

/* Block until a message from src (or MP_ANY) with tag (or MP_ANY) is there,
 * copy it into buf (cap bytes) and fill *st (st may be NULL).  Among several
 * matching messages the one that arrived first is taken, ties in a fixed
 * order, so any-source receives resolve the same way on every run of a
 * deterministic backend.  MP_OK, MP_ETRUNC, MP_EDEADLOCK or MP_ESTOPPED. */
int    mp_recv(mp *self, int src, int tag, void *buf, size_t cap, mp_status *st);

/* Non-blocking: 1 and *st filled if a matching message can be received now,
 * 0 if not, or a negative error. */
int    mp_probe(mp *self, int src, int tag, mp_status *st);

/* Charge `units` of work to this rank (simulated: units * c seconds of its
 * processor).  A no-op on real backends.  MP_OK or MP_EARG (units < 0). */
int    mp_compute(mp *self, double units);

/* Seconds: simulated time on the simulator, wall time since the run began on
 * real backends. */
double mp_time(const mp *self);

/* "deadlock", "no such rank", ... */
const char *mp_strerror(int code);

/* --- for layers above mp (an MPI library, a runtime) ----------------------
 * A layer that offers calls without a handle (MPI_Send) finds the calling
 * rank with mp_self and keeps its per-rank state in mp_user. */

/* The calling rank's handle, or NULL outside a rank's main (on the
 * simulator: the rank whose coroutine runs; on threads and MPI: this
 * thread's or process's rank). */
mp    *mp_self(void);

/* One pointer per rank for the layer above (NULL when the rank starts). */
void  *mp_user(const mp *self);
void   mp_set_user(mp *self, void *p);

/* mp_user(mp_self()), or NULL outside a rank: a thread-local read where a
 * layer's every call would make two calls (mp keeps mp_user_now; read it
 * through mp_self_user, never write it). */
extern MP_THREAD_LOCAL void *mp_user_now;
static inline void *mp_self_user(void) { return mp_user_now; }

/* Block until a message from src (or MP_ANY) with tag (or MP_ANY) can be
 * received, fill *st with the one mp_recv(src, tag) would take now, and
 * leave it there (a blocking mp_probe).  No processor time is charged: the
 * receive that takes it pays.  MP_OK, MP_EDEADLOCK, MP_ESTOPPED, MP_ERANK
 * or MP_EARG, as mp_recv. */
int    mp_wait(mp *self, int src, int tag, mp_status *st);

/* What this rank's blocking calls wait in, for the deadlock report:
 * describe(ud, buf, len) writes e.g. "MPI_Recv(source=1, tag=7,
 * MPI_COMM_WORLD)" into buf, and is called only when a report is made, so
 * that setting it costs two stores.  describe = NULL: mp's own words
 * ("recv(src=1, tag=7)"). */
typedef void (*mp_describe)(void *ud, char *buf, size_t len);
void   mp_label(mp *self, mp_describe describe, void *ud);

/* Charge `seconds` of computing to this rank, as mp_compute charges units *
 * c (the simulator's processor-side model applies).  A no-op on real
 * backends.  MP_OK or MP_EARG (negative or not finite). */
int    mp_busy(mp *self, double seconds);

/* Sleep: the rank's clock moves on `seconds` without holding its processor
 * (the simulator), or the thread sleeps that long (real backends).  MP_OK
 * or MP_EARG. */
int    mp_sleep(mp *self, double seconds);

/* Give way: on the simulator the ranks due at this rank's simulated time act
 * before it goes on (it is queued behind them, as when its clock moves; the
 * clock stays).  Nothing happens within a progress function (mp_set_progress)
 * nor on real backends.  MP_OK (MP_ESTOPPED once the run has stopped). */
int    mp_yield(mp *self);

/* End this rank here, as if its main had returned (never returns). */
MP_NORETURN void mp_exit(mp *self);

/* Stop the whole run: every other rank's mp calls return MP_ESTOPPED from
 * now on, the run fails with `why` (copied) and reports `code` as its exit
 * status (the first abort's, in simulated time on the simulator); this rank
 * ends here (never returns). */
MP_NORETURN void mp_abort(mp *self, int code, const char *why);

/* A layer's own calls in a trace (tilesim-mpirun: every MPI call): between
 * mp_call_begin and mp_call_end the rank is in the call named `name` (a
 * string that outlives the run: "MPI_Bcast").  The simulator's trace shows
 * such a call as a slice of the rank's track, around the sends, receives
 * and waits it made, if it took time or made any; calls nest, and only the
 * outermost is shown.  Two tests and nothing else without a trace. */
void   mp_call_begin(mp *self, const char *name);
void   mp_call_end(mp *self);

/* Progress while computing (a layer's progress engine, as a network card or
 * a progress thread would run it): while fn is set, each message that comes
 * to this rank while it computes (mp_compute, mp_busy, a hook's
 * mp_charge) makes the backend call fn(self, ud) at that message's
 * arrival, mp_time reading it: fn acts on the messages that have arrived
 * (mp_probe, mp_recv) and may send, but must not block.  The computing goes
 * on meanwhile and ends when it would have without fn, later only by the
 * processor time fn's own calls charge (LogGP's o, cpu.h's costs: taken from
 * the computing).  Messages already there when the computing starts are
 * acted on at its start.  On real backends, where computing is the
 * program's own and not simulated, fn runs at each charge if a message is
 * there.  fn NULL: none (the default). */
typedef void (*mp_progress)(mp *self, void *ud);
void   mp_set_progress(mp *self, mp_progress fn, void *ud);

/* Hooks around every mp call of every rank, process-wide (NULL: none; set
 * before a run, not during one): enter(self) before the call, leave(self)
 * after it returns.  How a runtime charges a program's own computing
 * between its calls (tilesim-mpirun --compute blocks|host): enter may charge
 * it with mp_charge (not mp_busy, which would call the hooks again). */
typedef struct {
  void (*enter)(mp *self);
  void (*leave)(mp *self);
} mp_hooks;
void   mp_set_hooks(const mp_hooks *hooks);

/* mp_busy without the hooks: for a hook's enter, which charges what the
 * rank computed since its last call.  The same costs, checks and codes. */
int    mp_charge(mp *self, double seconds);

/* 1 if the backend traces this rank's calls (mp_call_begin and mp_call_end
 * then show in a trace; the same for a whole run), else 0: a layer may skip
 * them. */
int    mp_traced(const mp *self);

/* 1 while a progress function is set (mp_set_progress), else 0. */
int    mp_progressing(const mp *self);

/* mp_self() if its calls are traced or a progress function is set (what a
 * layer's call wrapper acts on: mp_traced, mp_progressing), else NULL, as
 * outside a rank: the common case in a thread-local read (mp keeps
 * mp_watched_now; read it through mp_self_watched, never write it). */
extern MP_THREAD_LOCAL mp *mp_watched_now;
static inline mp *mp_self_watched(void) { return mp_watched_now; }

/* The rank's own stack, where the backend knows it (the simulator's
 * coroutines): its lowest address and size, and the start of the guard
 * below it (a fault in [*guard, *lo) is the stack overflowing).  NULL, 0
 * and NULL elsewhere.  Only reads: callable from a signal handler. */
void   mp_stack(const mp *self, void **lo, size_t *size, void **guard);

/* --- messages without copies (for layers above mp) -----------------------
 * mp_send copies a payload out at once and mp_recv copies it in: for large
 * messages the two copies cost more than the rest.  A layer that knows when
 * it needs a buffer back can do with one:
 *   - a send by reference leaves the payload in the sender's buffer until a
 *     receive copies it straight out, or until the sender settles it
 *     (needs its buffer back): then a payload still unread is copied out;
 *   - a receive may take a message now and copy it later, once it knows
 *     where it goes (mp_recv_msg, mp_msg_read: an MPI library's unexpected
 *     messages);
 *   - a rank may promise where it will receive the next message from a
 *     source (mp_promise: an MPI library's posted receive): a message that
 *     will certainly be received there is copied there when its sender
 *     settles it (or at mp_send), and the receive then copies nothing.
 * Which calls move a message changes nothing but the host's copying: the
 * simulator's times, statistics and traces are the same as with mp_send
 * and mp_recv.  A backend may copy at once (the MPI backend does; promises
 * are hints the threads backend ignores): the calls then behave as mp_send
 * and mp_recv, a withdrawal always fails, and a promise is NULL. */

typedef struct mp_ref mp_ref;           /* a send by reference, until settled */
typedef struct mp_msg mp_msg;           /* a message taken and not yet read */
typedef struct mp_promise mp_promise;   /* a promise of a receive buffer */

/* As mp_send (the same costs, order and errors), but the payload may stay
 * in buf: buf must not change until mp_settle(*ref).  *ref is set on MP_OK
 * (possibly NULL: nothing to settle), else NULL. */
int    mp_send_ref(mp *self, int dst, int tag, const void *buf, size_t len, mp_ref **ref);

/* The sender wants buf back: a payload still unread is copied out first
 * (into the buffer promised for it, or the backend's memory).  ref (from
 * this rank's mp_send_ref; NULL is fine) is spent. */
void   mp_settle(mp *self, mp_ref *ref);

/* Take the message back if no receive has read it: 1 (it is gone: no rank
 * receives it, the statistics still count its send; ref is spent) or 0 (a
 * receive read it: nothing changes, settle ref as before).  A message held
 * by mp_recv_msg and not yet read counts as unread. */
int    mp_withdraw(mp *self, mp_ref *ref);

/* As mp_recv (the same choice of message, costs and statistics), but
 * nothing is copied: *msg holds the message, *st its envelope, until
 * mp_msg_read.  MP_OK, MP_EDEADLOCK or MP_ESTOPPED (*msg NULL), as mp_recv. */
int    mp_recv_msg(mp *self, int src, int tag, mp_msg **msg, mp_status *st);

/* mp_recv_msg and mp_msg_read in one call where the message is the one the
 * caller wants: if its tag t has (t & mask) == (want & mask) and it is at
 * most cap bytes long, it is read into buf at once and *msg is NULL; any
 * other is held in *msg as mp_recv_msg holds it.  *st is its envelope
 * either way; the same choice of message, costs and statistics as
 * mp_recv_msg.  MP_OK, MP_EDEADLOCK or MP_ESTOPPED (*msg NULL). */
int    mp_recv_msg_into(mp *self, int src, int tag, int mask, int want, void *buf, size_t cap, mp_msg **msg,
                        mp_status *st);

/* Copy the held message's first min(len, cap) bytes into buf and release
 * it (buf NULL, cap 0: release only).  MP_OK, MP_ETRUNC (it was longer
 * than cap), or MP_EGONE (its sender withdrew it: nothing copied). */
int    mp_msg_read(mp *self, mp_msg *msg, void *buf, size_t cap);

/* 1 if the sender of the held message has withdrawn it (mp_withdraw). */
int    mp_msg_gone(mp *self, const mp_msg *msg);

/* A promise of this rank's: the first message from rank src (not MP_ANY)
 * whose tag t has (t & mask) == (tag & mask), among those it has not yet
 * received, will be received into buf (cap bytes) with mp_recv, unless the
 * promise is withdrawn first.  Promises are kept in the order made: a
 * message is the one of the first promise it fits whose message has not
 * come.  Returns the promise, or NULL where the backend ignores them. */
mp_promise *mp_promise_make(mp *self, int src, int tag, int mask, void *buf, size_t cap);

/* Withdraw a promise (NULL is fine).  keep = 1 and a message was copied
 * into its buffer already: nothing changes, 1 is returned (the message is
 * to be received there as promised).  Else the promise is gone, 0 (a
 * message copied into its buffer and not received is moved out first; buf
 * is the caller's again). */
int    mp_promise_drop(mp *self, mp_promise *p, int keep);

/* --- one-sided transfers (for layers above mp: an MPI library's RMA) -----
 * The ranks of a run share one address space, so a layer can move data
 * between them itself (a remote put is a memcpy); these two calls give such
 * a move its cost on the machine, as a network card's transfer would have
 * (MPI's one-sided operations: doc/mpi-semantics.md). */

/* A transfer of len bytes from rank src's processor to rank dst's starting
 * at time `at`, charged on the network as a message of len bytes would be
 * (the model's latency and bytes, the bus, the links of its route, the NIC's
 * gap), after every earlier message and transfer from src to dst (the
 * channel's order), but delivered to no mailbox and taken by no receive.
 * When src is the calling rank and `at` its clock, its processor pays what
 * a send's does (LogGP's o, cpu.h's send costs: its clock moves on, and the
 * transfer starts after); otherwise no processor is involved (a network
 * card acting for src).  The statistics count it as a message src sent
 * and dst received.  Returns the arrival time (>= at).  Real backends:
 * `at`, nothing charged. */
double mp_transfer(mp *self, int src, int dst, size_t len, double at);

/* A 0-byte message with tag from the calling rank to dst that arrives at
 * `at` (its clock if that is later), charged nothing on the network or the
 * sender's processor: how a layer wakes a rank (dst may be the caller) at
 * a time it computed with mp_transfer.  It is received like any message
 * (and counted as one).  MP_OK, MP_ERANK, MP_EARG or MP_ESTOPPED as
 * mp_send.  Real backends: an mp_send of 0 bytes. */
int    mp_notify(mp *self, int dst, int tag, double at);

#ifdef __cplusplus
}
#endif

#endif
