/* engine.h -- the matching engine: MPI's matching rules on top of mp.h's
 * messages (posted receives, unexpected messages, synchronous sends' acks).
 *
 * Messages stay in mp's mailbox until a receive looks for them.  A receive
 * from a source s looks at s's earliest message (mp_wait(s, MP_ANY)); one
 * from any source at the earliest of all; a message that does not match is
 * taken into the unexpected queue (the engine's own copy, in the order
 * taken), where later receives look first.  Each source's messages thus
 * reach the engine in the order they were sent (mp's non-overtaking rule),
 * and each is matched in that order against the receives posted, in the
 * order they were posted: MPI 3.1 section 3.5's rules.  While receives are
 * posted, a rank that blocks takes every message that comes (from any
 * source) and matches it at once, so a synchronous send to a posted receive
 * is acknowledged even while its receiver waits for something else (MPI's
 * progress rule).  doc/mpi-semantics.md tells the whole story, with the
 * costs.
 *
 * All calls work on the calling rank's state R; a run that stops while one
 * blocks ends the rank (st_stopped). */
#ifndef TSMPI_ENGINE_H
#define TSMPI_ENGINE_H

#include <stddef.h>

#include "mpi/state.h"

/* Messages of this many bytes or more are worth a promise (shorter ones are
 * copied twice: cheaper than the bookkeeping). */
enum { ENG_REF_MIN = 1024 };

/* A send of this many bytes or more gives way: one copied at once (a
 * blocking send, eng_send without byref, eng_send_data) before it leaves,
 * a request's when it completes (eng_send_done); util/bigcopy.h's big
 * payloads. */
enum { ENG_YIELD_MIN = 256 << 10 };

/* A send's message leaves: len bytes at data to q->wpeer with q's context,
 * tag and mode (SM_SYNC: q waits in R->sync for its ack, state RS_ACTIVE;
 * else q is RS_DONE).  With q->byref, by reference: data must stay as it
 * is until eng_settle(q); without, copied now, after giving way (mp_yield)
 * if it is ENG_YIELD_MIN bytes or more: a receiver due at the same time
 * then posts its receive first, and the copy goes straight there. */
void eng_send(st_rank *R, st_req *q, const void *data, size_t len);

/* q's buffers are the program's again (a send by reference settled, its
 * packed copy freed): when a request ends, or a blocking call that sent by
 * reference returns. */
void eng_settle(st_rank *R, st_req *q);
/* Send request q is complete (a Wait or Test returns it, before its
 * eng_settle): a send by reference of ENG_YIELD_MIN bytes or more gives way
 * first (mp_yield), so that a receiver due at the same simulated time posts
 * its receive before the settle.  Its promise then takes the payload
 * straight from the sender's buffer, where the settle would otherwise copy
 * it into the simulator's memory (fresh pages: 256 MB for a window of 64
 * sends of 4 MB) for the receive to copy it again.  A rule of the model
 * (doc/mpi-semantics.md), whatever was copied. */
void eng_send_done(st_rank *R, const st_req *q);
/* q, a blocking call's request on its stack, sent by reference: until
 * eng_settle(q), the rank's end (eng_settle_all, a run stopped inside the
 * call) settles its message and frees its packed copy. */
void eng_hold(st_rank *R, st_req *q);
/* q's send by reference is no longer the blocking call's (settled, or
 * handed to a request of the program's, which settles it when it ends). */
void eng_unhold(st_rank *R, const st_req *q);
/* The rank's end: every request's send and a blocking call's (eng_hold)
 * settled, while the buffers they refer to (the program's, the
 * collectives' scratch and schedules) are still there. */
void eng_settle_all(st_rank *R);

/* The fast paths of MPI_Send and MPI_Recv (the common case of a blocking
 * exchange, with no request made):
 *   eng_send_data: an eager message of len bytes to world rank wdst
 *     (MPI_SUCCESS, MPI_Send's result);
 *   eng_recv_data: when nothing is posted and nothing unexpected, the next
 *     message from wsrc (MP_ANY) is waited for; if it is an eager one that
 *     a receive of (ctx, tag) takes and it fits cap bytes at p, it is
 *     taken there: 1 and *got (world source, MPI tag, bytes).  Else 0, and
 *     the general way (eng_recv) finds the same message: in mp's mailbox,
 *     or, for cap < ENG_REF_MIN, taken already into the unexpected queue
 *     (an ack acted on). */
int eng_send_data(st_rank *R, int wdst, int ctx, int tag, const void *data, size_t len);
int eng_recv_data(st_rank *R, int wsrc, int ctx, int tag, void *p, size_t cap, mp_status *got);

/* A receive starts: matched at once by the first unexpected message that
 * fits (q RS_DONE), else posted (q RS_ACTIVE).  q->g is counted while q is
 * active. */
void eng_recv_start(st_rank *R, st_req *q);

/* A blocking receive: as eng_recv_start then eng_wait, in one mp_wait and
 * one mp_recv when nothing else is posted. */
void eng_recv(st_rank *R, st_req *q);

/* Block until q (active) is done (a request of a kind of its own: its
 * progress between the messages that come, core.h). */
void eng_wait(st_rank *R, st_req *q);

/* A request of a kind of its own, active: its progress, once (done: it
 * goes if the program freed it). */
void eng_advance(st_rank *R, st_req *q);

/* Block until at least one message has been taken and acted on (a receive
 * matched, an ack, an unexpected message): for waits on several requests.
 * Then every request of a kind of its own advances (MPI's progress: a
 * nonblocking collective moves on while its rank waits for anything). */
void eng_step(st_rank *R);

/* Act on every message that has arrived, without blocking (the
 * nonblocking collectives' progress included); eng_poll: then every
 * request of a kind of its own advances. */
void eng_take(st_rank *R);
void eng_poll(st_rank *R);

/* Take q out of the posted queue (a request freed or a stopped rank). */
void eng_unpost(st_rank *R, st_req *q);

/* The message a receive from wsrc (MP_ANY) with ctx and tag (MPI_ANY_TAG)
 * would take now: 1 and its world source, tag and bytes; 0 if none has
 * arrived (block = 0); with block, waits until one has.  The message stays
 * to be received (in mp's mailbox or the unexpected queue); with take, it
 * is taken out of matching (MPI_Mprobe: *take, for eng_msg_read or
 * eng_msg_free). */
int eng_probe(st_rank *R, int wsrc, int ctx, int tag, int block, int *src, int *mtag, size_t *len, st_msg **take);

/* Receive m (taken by eng_probe) into q (filled, not started): q done,
 * with its status (an empty one if m's sender withdrew it since); m freed.
 * eng_msg_free: m released unread (the rank's end). */
void eng_msg_read(st_rank *R, st_req *q, st_msg *m);
void eng_msg_free(st_rank *R, st_msg *m);

/* MPI_Cancel: a posted receive taken out of the posted queue (1: q done,
 * cancelled), or not (0: a message is in its buffer already, and it
 * completes as usual); a send's message withdrawn if no receive has read
 * it (1: q done, cancelled; a synchronous send no longer waits for its
 * ack), else 0. */
int eng_cancel_recv(st_rank *R, st_req *q);
int eng_cancel_send(st_rank *R, st_req *q);

/* Free the unexpected queue, settle every request's send, drop every
 * promise (the rank's end). */
void eng_release(st_rank *R);

#endif
