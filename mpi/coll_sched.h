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
 *   tsmpi_sched_send(s, buf, n, dst)    mp_send                 mp_send when reached
 *   tsmpi_sched_recv(s, buf, n, src)    blocking receive        posted when reached; the
 *                                                               schedule waits there
 *   tsmpi_sched_isend/irecv(...)        posted, completed by the next waitall
 *   tsmpi_sched_waitall(s)              waits for those         waits there until all are done
 *   tsmpi_sched_reduce/copy/unpack/call local
 *
 * A blocking schedule runs each step as the algorithm adds it, and is never stored: the calls
 * are exactly, in exactly the order, those the algorithm's code would make in line, and the
 * blocking collectives' simulated times are the algorithm's.  A nonblocking one keeps its steps
 * and runs each only when every step before it has (a receive's buffer is free for it, a
 * send's data is there).
 *
 * MEMORY.  A schedule owns what tsmpi_sched_mem gives and is freed with it.  Every live
 * schedule of a rank is on the rank's list, so a run stopped while a rank waits inside one
 * frees it at the rank's end. */
#ifndef TSMPI_COLL_SCHED_H
#define TSMPI_COLL_SCHED_H

#include <stddef.h>

#include "mpi/coll.h"

typedef struct tsmpi_sched tsmpi_sched;

/* A new, empty schedule of the calling rank on group g (copied); r, if not NULL, is the
 * reduction its reduce steps apply (copied).  blocking: each step runs as it is added (the
 * receives blocking), so that the schedule is never stored: tsmpi_sched_run then ends it;
 * else the steps are kept for tsmpi_sched_step. */
tsmpi_sched *tsmpi_sched_new(const tsmpi_cg *g, const tsmpi_red *r, int blocking);

/* The schedule's group and reduction. */
const tsmpi_cg *tsmpi_sched_group(const tsmpi_sched *s);
const tsmpi_red *tsmpi_sched_red(const tsmpi_sched *s);
void tsmpi_sched_set_red(tsmpi_sched *s, const tsmpi_red *r);

/* The collective's frame (coll_frame.c's): a pointer it sets and reads. */
void *tsmpi_sched_frame(const tsmpi_sched *s);
void tsmpi_sched_set_frame(tsmpi_sched *s, void *frame);

/* n bytes (uninitialized) that live as long as the schedule. */
void *tsmpi_sched_mem(tsmpi_sched *s, size_t n);

/* The steps.  Bytes to and from ranks of the group (MPI_PROC_NULL: nothing); a receive takes
 * at most n bytes (a longer message is the ranks disagreeing on counts: MPI_ERR_TRUNCATE). */
void tsmpi_sched_send(tsmpi_sched *s, const void *buf, size_t n, int dst);
void tsmpi_sched_recv(tsmpi_sched *s, void *buf, size_t n, int src);
/* A send then a receive (blocking: in one call, the send's bytes by
 * reference until the receive is done). */
void tsmpi_sched_sendrecv(tsmpi_sched *s, const void *sbuf, size_t sn, int dst, void *rbuf, size_t rn, int src);
void tsmpi_sched_isend(tsmpi_sched *s, const void *buf, size_t n, int dst);
void tsmpi_sched_irecv(tsmpi_sched *s, void *buf, size_t n, int src);
void tsmpi_sched_waitall(tsmpi_sched *s);
/* right = left op right, count elements of the schedule's reduction. */
void tsmpi_sched_reduce(tsmpi_sched *s, const void *left, void *right, int count);
void tsmpi_sched_copy(tsmpi_sched *s, void *dst, const void *src, size_t n);
/* n packed bytes at p into buf, at most count elements of dt (dt held until the schedule is
 * freed: the program may free it before a nonblocking collective completes). */
void tsmpi_sched_unpack(tsmpi_sched *s, const void *p, size_t n, void *buf, int count, MPI_Datatype dt);
/* A local step of the algorithm's own: fn(ud) (ud in the schedule's memory, typically). */
void tsmpi_sched_call(tsmpi_sched *s, void (*fn)(void *ud), void *ud);

/* Blocking: the end of a schedule whose steps ran as they were added (receives and waitalls
 * blocking; none after an error): the requests an error left are waited for, s is freed.
 * MPI_SUCCESS or the first error, already raised under the communicator's handler. */
int tsmpi_sched_run(tsmpi_sched *s);

/* Nonblocking: run the steps from where s stands until one must wait (a receive or a waitall
 * whose requests are not all done) or the end: 1 at the end (then tsmpi_sched_error says how
 * it went), else 0.  Receives and sends go through core.h's requests, watched (tsmpi_p2p_watch),
 * so that the engine calls the progress function when one completes. */
int tsmpi_sched_step(tsmpi_sched *s);
int tsmpi_sched_error(const tsmpi_sched *s);

/* A schedule's end: its memory, its requests still posted, the types it holds. */
void tsmpi_sched_free(tsmpi_sched *s);

#endif
