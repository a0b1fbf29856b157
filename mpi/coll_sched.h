/* coll_sched.h -- a collective's algorithm as a schedule: the steps one rank takes, in order (sends,
 * receives, local reductions and copies), built once by the algorithm (coll.h), then either
 * run through at once, receives blocking (the blocking collectives), or stepped as messages
 * arrive (the nonblocking ones, nbc.h).
 *
 * Not for programs.  Each algorithm is written once, as a builder: it adds the steps of the
 * calling rank to a schedule, with every size known when it is built (the sizes a rank
 * receives are computed, as MPICH's schedules compute them, never read from a message).
 *
 *   step                                blocking (at once)      nonblocking (stepped)
 *   coll_sched_send(s, buf, n, dst)    mp_send                 mp_send when reached
 *   coll_sched_recv(s, buf, n, src)    blocking receive        posted when reached; the
 *                                                               schedule waits there
 *   coll_sched_isend/irecv(...)        posted, completed by the next waitall
 *   coll_sched_waitall(s)              waits for those         waits there until all are done
 *   coll_sched_reduce/copy/unpack/call local
 *
 * A blocking schedule runs each step as the algorithm adds it, and is never stored: the calls
 * are exactly, in exactly the order, those the algorithm's code would make in line, and the
 * blocking collectives' simulated times are the algorithm's.  A nonblocking one keeps its steps
 * and runs each only when every step before it has (a receive's buffer is free for it, a
 * send's data is there).
 *
 * MEMORY.  A schedule owns what coll_sched_mem gives and is freed with it.  Every live
 * schedule of a rank is on the rank's list, so a run stopped while a rank waits inside one
 * frees it at the rank's end. */
#ifndef TSMPI_COLL_SCHED_H
#define TSMPI_COLL_SCHED_H

#include <stddef.h>

#include "mpi/coll.h"

typedef struct coll_sched coll_sched;

/* A new, empty schedule of the calling rank on group g (copied); r, if not NULL, is the
 * reduction its reduce steps apply (copied).  blocking: each step runs as it is added (the
 * receives blocking), so that the schedule is never stored: coll_sched_run then ends it;
 * else the steps are kept for coll_sched_step. */
coll_sched *coll_sched_new(const coll_cg *g, const coll_red *r, int blocking);

/* The schedule's group and reduction. */
const coll_cg *coll_sched_group(const coll_sched *s);
const coll_red *coll_sched_red(const coll_sched *s);
void coll_sched_set_red(coll_sched *s, const coll_red *r);

/* The collective's frame (coll_frame.c's): a pointer it sets and reads. */
void *coll_sched_frame(const coll_sched *s);
void coll_sched_set_frame(coll_sched *s, void *frame);

/* n bytes (uninitialized) that live as long as the schedule. */
void *coll_sched_mem(coll_sched *s, size_t n);
/* The bytes coll_sched_mem has given since the process started, every rank's (the
 * collectives' own memory, which a contiguous buffer spares: coll.h, coll_place). */
long long coll_sched_mem_given(void);

/* The steps.  Bytes to and from ranks of the group (MPI_PROC_NULL: nothing); a receive takes
 * at most n bytes (a longer message is the ranks disagreeing on counts: MPI_ERR_TRUNCATE). */
void coll_sched_send(coll_sched *s, const void *buf, size_t n, int dst);
void coll_sched_recv(coll_sched *s, void *buf, size_t n, int src);
/* A send then a receive (blocking: in one call, the send's bytes by
 * reference until the receive is done). */
void coll_sched_sendrecv(coll_sched *s, const void *sbuf, size_t sn, int dst, void *rbuf, size_t rn, int src);
void coll_sched_isend(coll_sched *s, const void *buf, size_t n, int dst);
void coll_sched_irecv(coll_sched *s, void *buf, size_t n, int src);
void coll_sched_waitall(coll_sched *s);
/* right = left op right, count elements of the schedule's reduction. */
void coll_sched_reduce(coll_sched *s, const void *left, void *right, int count);
void coll_sched_copy(coll_sched *s, void *dst, const void *src, size_t n);
/* n packed bytes at p into buf, at most count elements of dt (dt held until the schedule is
 * freed: the program may free it before a nonblocking collective completes); nothing when p
 * is buf's own contiguous bytes (coll.h: coll_place). */
void coll_sched_unpack(coll_sched *s, const void *p, size_t n, void *buf, int count, MPI_Datatype dt);
/* A local step of the algorithm's own: fn(ud) (ud in the schedule's memory, typically). */
void coll_sched_call(coll_sched *s, void (*fn)(void *ud), void *ud);

/* Blocking: the end of a schedule whose steps ran as they were added (receives and waitalls
 * blocking; none after an error): the requests an error left are waited for, s is freed.
 * MPI_SUCCESS or the first error, already raised under the communicator's handler. */
int coll_sched_run(coll_sched *s);

/* Nonblocking: run the steps from where s stands until one must wait (a receive or a waitall
 * whose requests are not all done) or the end: 1 at the end (then coll_sched_error says how
 * it went), else 0.  Receives and sends go through core.h's requests, watched (coll_p2p_watch),
 * so that the engine calls the progress function when one completes. */
int coll_sched_step(coll_sched *s);
int coll_sched_error(const coll_sched *s);

/* A schedule's end: its memory, its requests still posted, the types it holds. */
void coll_sched_free(coll_sched *s);

#endif
