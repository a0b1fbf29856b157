/* engine.c -- the matching engine (engine.h says what; doc/mpi-semantics.md
 * why and what it costs).
 *
 * Three queues per rank, all in order:
 *   posted   receives started and not yet matched (MPI_Irecv, MPI_Recv_init
 *            started, a blocking receive while others are posted);
 *   unexp    messages taken off mp that no posted receive wanted;
 *   sync     synchronous sends waiting for their receiver's ack.
 *
 * Invariant: for every source, the messages in unexp were sent before any
 * of that source's messages still in mp's mailbox.  It holds because the
 * engine only ever takes the earliest message of a source: mp_wait and
 * mp_probe show the earliest message of the source asked (or of all), and
 * mp_recv(source, tag) of the message shown takes exactly that one (the
 * earliest from that source with that tag).  So a receive that finds
 * nothing in unexp and then the first matching message in mp takes the
 * earliest matching message of its source: MPI's non-overtaking rule.
 *
 *   receive posted            message taken from mp
 *   first fit in unexp?       first fit among posted (posting order)?
 *     yes: take it              yes: into that receive's buffer
 *     no:  append to posted     no:  append to unexp (a copy)
 *
 * A message's K_SYNC kind asks for an ack when a receive takes it (here, in
 * complete()); the ack carries the message's context and tag back, and the
 * sender's sync queue gives it to the oldest send with those: acks of
 * messages with one (receiver, context, tag) come back in the order the
 * messages were sent, as the receiver takes those in that order.
 *
 * Copies (mp.h, "Messages without copies").  A request's send goes by
 * reference (mp_send_ref) and is settled when the request ends; a posted
 * receive of ENG_REF_MIN bytes or more into a contiguous buffer from a
 * named source promises its buffer (mp_promise_make) when every receive
 * posted before it has done so too (then the receives the promises name
 * are exactly the ones MPI's order gives, and a message delivered into one
 * is the one that receive takes); a blocking receive promises its buffer
 * while it waits; an unexpected message is held (mp_recv_msg) and read
 * into the receive that matches it. */
#include "mpi/engine.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/dlist.h"
#include "util/xmem.h"

/* ==== mp calls ============================================================ */

/* An mp call's result: a stopped run ends the rank; anything else but MP_OK
 * is a bug of this layer (the arguments are ours): failed. */
static _Noreturn void failed(st_rank *R, int rc, const char *call) {
  if (rc == MP_ESTOPPED || rc == MP_EDEADLOCK) st_stopped(R);
  fprintf(stderr, "tilesim MPI: internal error: rank %d: %s: %s\n", R->wrank, call, mp_strerror(rc));
  abort();
}
static inline void mpok(st_rank *R, int rc, const char *call) {
  if (rc != MP_OK) failed(R, rc, call);
}

/* ==== promises ============================================================ */

/* The mp tag mask of a receive's promise: the context, the MPI tag unless
 * MPI_ANY_TAG, and K_ACK's bit (a message of kind K_DATA or K_SYNC fits,
 * an ack never). */
static inline int prom_mask(int tag) {
  return 1 << (ENV_KIND_SHIFT + 1) | ((1 << ENV_CTX_BITS) - 1) << ENV_TAG_BITS | (tag >= 0 ? ST_TAG_UB : 0);
}

static inline mp_promise *promise_of(st_rank *R, int wsrc, int ctx, int tag, void *buf, size_t cap) {
  if (cap < ENG_REF_MIN || wsrc < 0 || !buf || R->posted_plain) return NULL;
  return mp_promise_make(R->self, wsrc, st_env_encode(K_DATA, ctx, tag >= 0 ? tag : 0), prom_mask(tag), buf, cap);
}

static void unpromise(st_rank *R, st_req *q) {
  if (!q->prom) return;
  mp_promise_drop(R->self, q->prom, 0);
  q->prom = NULL;
}

/* ==== queues ============================================================== */

/* The rank's queues (posted receives, synchronous sends, unexpected
 * messages) are doubly linked through their items' next and prev, with a
 * head and a tail (util/dlist.h). */

/* q goes to the end of the posted queue, with a promise if it may. */
static void post(st_rank *R, st_req *q) {
  q->prom = promise_of(R, q->wpeer, q->ctx, q->tag, q->contig, q->cap);
  if (!q->prom) R->posted_plain++;
  DLIST_APPEND(R->posted, R->posted_tail, q);
  q->state = RS_ACTIVE;
  q->g->refs++;
}

static void unlink_posted(st_rank *R, st_req *q) {
  if (!q->prom) R->posted_plain--;
  DLIST_UNLINK(R->posted, R->posted_tail, q);
  q->next = q->prev = NULL;
}

void eng_unpost(st_rank *R, st_req *q) {
  unlink_posted(R, q);
  unpromise(R, q);
  st_ranks_drop(q->g);
  q->g = NULL;
}

static void sync_add(st_rank *R, st_req *q) { DLIST_APPEND(R->sync, R->sync_tail, q); }

static void sync_unlink(st_rank *R, st_req *q) {
  DLIST_UNLINK(R->sync, R->sync_tail, q);
  q->next = q->prev = NULL;
}

static void unexp_unlink(st_rank *R, st_msg *m) {
  DLIST_UNLINK(R->unexp, R->unexp_tail, m);
  R->nunexp--;
}

/* An unexpected message's end (its mp message released). */
static void unexp_free(st_rank *R, st_msg *m) {
  mp_msg_read(R->self, m->h, NULL, 0);
  free(m);
}

/* m (unlinked) is gone if its sender withdrew it (MPI_Cancel): then freed. */
static int unexp_gone(st_rank *R, st_msg *m) {
  if (!mp_msg_gone(R->self, m->h)) return 0;
  unexp_free(R, m);
  return 1;
}

static inline int fits(const st_req *q, int src, int ctx, int tag) {
  return q->ctx == ctx && (q->wpeer < 0 || q->wpeer == src) && (q->tag < 0 || q->tag == tag);
}

static st_req *posted_fit(st_rank *R, int src, int ctx, int tag) {
  for (st_req *q = R->posted; q; q = q->next)
    if (fits(q, src, ctx, tag)) return q;
  return NULL;
}

/* ==== completing ========================================================== */

/* n received bytes at data into q's buffer. */
static void place(st_req *q, const void *data, size_t n) {
  if (n == 0) return;
  if (q->contig)
    memcpy(q->contig, data, n);
  else
    dtype_unpack(data, n, q->buf, q->count, q->dt);
}

/* q has taken a len-byte message from world rank src with the envelope
 * (kind, ctx, tag): its status, the ack a synchronous send waits for, and
 * a freed request's end.  counted: q was posted (holds a count on q->g). */
static void complete(st_rank *R, st_req *q, int src, int kind, int ctx, int tag, size_t len, int counted) {
  q->st.MPI_SOURCE = q->g->world ? st_ranks_find(q->g, src) : src;
  q->st.MPI_TAG = tag;
  q->st.MPI_ERROR = len > q->cap ? MPI_ERR_TRUNCATE : MPI_SUCCESS;
  q->st.tsmpi_cancelled = 0;
  q->st.tsmpi_count = (MPI_Count)(len < q->cap ? len : q->cap);
  q->msglen = len;
  if (counted) st_ranks_drop(q->g);
  q->g = NULL;
  q->state = RS_DONE;
  if (q->watch) R->progress_due = 1;
  if (kind == K_SYNC) mpok(R, mp_send(R->self, src, st_env_encode(K_ACK, ctx, tag), NULL, 0), "mp_send");
  if (q->freed) st_req_free(R, q);
}

/* The nonblocking collectives' progress, after a watched request completed
 * (never inside itself: what it starts is seen by its own loop). */
static void progress(st_rank *R) {
  if (R->in_progress || !R->progress) return;
  R->in_progress = 1;
  while (R->progress_due) {
    R->progress_due = 0;
    R->progress();
  }
  R->in_progress = 0;
}

/* Take the message shown (src, mptag, len) off mp into q's buffer. */
static void take_into(st_rank *R, st_req *q, int src, int mptag, size_t len) {
  if (len <= q->cap && q->contig) {
    mpok(R, mp_recv(R->self, src, mptag, len ? q->contig : NULL, len, NULL), "mp_recv");
    return;
  }
  unsigned char *tmp = len ? xmalloc(len) : NULL;
  mpok(R, mp_recv(R->self, src, mptag, tmp, len, NULL), "mp_recv");
  place(q, tmp, len < q->cap ? len : q->cap);
  free(tmp);
}

/* An ack from src for the oldest synchronous send to it with (ctx, tag). */
static void acked(st_rank *R, int src, int ctx, int tag) {
  for (st_req *q = R->sync; q; q = q->next) {
    if (q->wpeer == src && q->ctx == ctx && q->tag == tag) {
      sync_unlink(R, q);
      q->state = RS_DONE;
      if (q->freed) st_req_free(R, q);
      return;
    }
  }
  fprintf(stderr, "tilesim MPI: internal error: rank %d: an ack from rank %d (context %d, tag %d) for no send\n",
          R->wrank, src, ctx, tag);
  abort();
}

/* The message h (held; envelope st) goes to the end of the unexpected
 * queue. */
static void unexpected(st_rank *R, const mp_status *st, mp_msg *h) {
  st_msg *m = xmalloc(sizeof *m);
  m->src = st->source;
  m->kind = st_env_kind(st->tag);
  m->ctx = st_env_ctx(st->tag);
  m->tag = st_env_tag(st->tag);
  m->len = st->len;
  m->h = h;
  DLIST_APPEND(R->unexp, R->unexp_tail, m);
  R->nunexp++;
}

/* Take the message mp has shown (st) and act on it: an ack, a posted
 * receive's message, or an unexpected one; then the progress of the
 * nonblocking collectives it moved. */
static void act(st_rank *R, const mp_status *st);
static void dispatch(st_rank *R, const mp_status *st) {
  act(R, st);
  if (R->progress_due) progress(R);
}

static void act(st_rank *R, const mp_status *st) {
  int kind = st_env_kind(st->tag), ctx = st_env_ctx(st->tag), tag = st_env_tag(st->tag);
  if (kind == K_ACK) {
    mpok(R, mp_recv(R->self, st->source, st->tag, NULL, 0, NULL), "mp_recv");
    acked(R, st->source, ctx, tag);
    return;
  }
  st_req *q = R->posted ? posted_fit(R, st->source, ctx, tag) : NULL;
  if (q) {
    unlink_posted(R, q);
    take_into(R, q, st->source, st->tag, st->len);
    unpromise(R, q);
    complete(R, q, st->source, kind, ctx, tag, st->len, 1);
    return;
  }
  mp_msg *h;
  mpok(R, mp_recv_msg(R->self, st->source, st->tag, &h, NULL), "mp_recv_msg");
  unexpected(R, st, h);
}

/* ==== the calls =========================================================== */

static void advance_all(st_rank *R);

/* A message copied now (mp_send).  One of ENG_YIELD_MIN bytes or more
 * gives way first (engine.h), out of line: the small message's path saves
 * no registers for it. */
#ifdef __GNUC__
__attribute__((noinline))
#endif
static void send_big(st_rank *R, int wdst, int mptag, const void *data, size_t len) {
  mpok(R, mp_yield(R->self), "mp_yield");
  mpok(R, mp_send(R->self, wdst, mptag, data, len), "mp_send");
}

static inline void send_copy(st_rank *R, int wdst, int mptag, const void *data, size_t len) {
  if (len >= ENG_YIELD_MIN)
    send_big(R, wdst, mptag, data, len);
  else
    mpok(R, mp_send(R->self, wdst, mptag, data, len), "mp_send");
}

void eng_send(st_rank *R, st_req *q, const void *data, size_t len) {
  int kind = q->mode == SM_SYNC ? K_SYNC : K_DATA, mptag = st_env_encode(kind, q->ctx, q->tag);
  q->sendlen = len;
  if (q->byref)
    mpok(R, mp_send_ref(R->self, q->wpeer, mptag, data, len, &q->ref), "mp_send_ref");
  else
    send_copy(R, q->wpeer, mptag, data, len);
  q->st = (MPI_Status){.MPI_SOURCE = MPI_ANY_SOURCE, .MPI_TAG = MPI_ANY_TAG, .MPI_ERROR = MPI_SUCCESS};
  if (kind == K_SYNC) {
    q->state = RS_ACTIVE;
    sync_add(R, q);
  } else {
    q->state = RS_DONE;
  }
}

int eng_send_data(st_rank *R, int wdst, int ctx, int tag, const void *data, size_t len) {
  send_copy(R, wdst, st_env_encode(K_DATA, ctx, tag), data, len);
  return MPI_SUCCESS;
}

void eng_hold(st_rank *R, st_req *q) {
  R->held_ref = q->ref;
  R->held_tmp = q->tmp;
}

void eng_unhold(st_rank *R, const st_req *q) {
  if (q->slot < 0 && q->ref && q->ref == R->held_ref) R->held_ref = NULL, R->held_tmp = NULL;
}

void eng_send_done(st_rank *R, const st_req *q) {
  if (q->ref && q->sendlen >= ENG_YIELD_MIN) mpok(R, mp_yield(R->self), "mp_yield");
}

void eng_settle(st_rank *R, st_req *q) {
  eng_unhold(R, q);
  if (q->ref) {
    mp_settle(R->self, q->ref);
    q->ref = NULL;
  }
  if (q->tmp) {
    free(q->tmp);
    q->tmp = NULL;
  }
}

/* A path of the receives out of their common case's code (no registers
 * saved there). */
#if defined(__GNUC__)
#define SIDE __attribute__((noinline))
#else
#define SIDE
#endif

/* eng_recv_data's message (held at h, its envelope st) that is not the one:
 * an ack acted on, anything else unexpected.  0. */
static SIDE int recv_other(st_rank *R, const mp_status *st, mp_msg *h) {
  if (st_env_kind(st->tag) == K_ACK) {
    mp_msg_read(R->self, h, NULL, 0);
    acked(R, st->source, st_env_ctx(st->tag), st_env_tag(st->tag));
  } else {
    unexpected(R, st, h);
  }
  return 0;
}

/* eng_recv_data of cap >= ENG_REF_MIN bytes: the message is received into
 * p, where its sender may have copied it already (a promise). */
static SIDE int recv_promised(st_rank *R, int wsrc, int ctx, int tag, void *p, size_t cap, mp_status *got) {
  mp_status st;
  mp_promise *pr = promise_of(R, wsrc, ctx, tag, p, cap);
  mpok(R, mp_wait(R->self, wsrc, MP_ANY, &st), "mp_wait");
  if (st_env_kind(st.tag) != K_DATA || st_env_ctx(st.tag) != ctx || (tag >= 0 && st_env_tag(st.tag) != tag) ||
      st.len > cap) {
    if (pr) mp_promise_drop(R->self, pr, 0);
    return 0;
  }
  mpok(R, mp_recv(R->self, st.source, st.tag, st.len ? p : NULL, st.len, NULL), "mp_recv");
  if (pr) mp_promise_drop(R->self, pr, 0);
  *got = (mp_status){st.source, st_env_tag(st.tag), st.len};
  return 1;
}

int eng_recv_data(st_rank *R, int wsrc, int ctx, int tag, void *p, size_t cap, mp_status *got) {
  if (cap >= ENG_REF_MIN) return recv_promised(R, wsrc, ctx, tag, p, cap, got);
  /* The source's next message, taken; read into p if it is the one, else
   * acted on as a message taken off mp (no posted receive wants it). */
  mp_status st;
  mp_msg *h;
  int mask = tag < 0 ? ~ST_TAG_UB : -1;   /* a data message of ctx, of the tag or any */
  mpok(R, mp_recv_msg_into(R->self, wsrc, MP_ANY, mask, st_env_encode(K_DATA, ctx, tag < 0 ? 0 : tag), p, cap, &h, &st),
       "mp_recv_msg");
  if (!h) {
    *got = (mp_status){st.source, st_env_tag(st.tag), st.len};
    return 1;
  }
  return recv_other(R, &st, h);
}

/* m, an unexpected message taken out of matching, read into q, which
 * completes with it; m freed. */
static void take_held(st_rank *R, st_req *q, st_msg *m) {
  size_t n = m->len < q->cap ? m->len : q->cap;
  if (q->contig || !n) {
    mp_msg_read(R->self, m->h, n ? q->contig : NULL, n);
  } else {
    unsigned char *tmp = xmalloc(n);
    mp_msg_read(R->self, m->h, tmp, n);
    place(q, tmp, n);
    free(tmp);
  }
  complete(R, q, m->src, m->kind, m->ctx, m->tag, m->len, 0);
  free(m);
}

/* The first unexpected message q fits, taken into q; 1, or 0 if none. */
static int from_unexp(st_rank *R, st_req *q) {
  for (st_msg *m = R->unexp, *next; m; m = next) {
    next = m->next;
    if (!fits(q, m->src, m->ctx, m->tag)) continue;
    unexp_unlink(R, m);
    if (unexp_gone(R, m)) continue;
    take_held(R, q, m);
    return 1;
  }
  return 0;
}

void eng_recv_start(st_rank *R, st_req *q) {
  if (R->nunexp && from_unexp(R, q)) return;
  post(R, q);
}

void eng_recv(st_rank *R, st_req *q) {
  if (R->nunexp && from_unexp(R, q)) return;
  if (R->posted) {   /* others are posted: in line behind them */
    post(R, q);
    eng_wait(R, q);
    return;
  }
  q->prom = promise_of(R, q->wpeer, q->ctx, q->tag, q->contig, q->cap);
  for (;;) {   /* the fast path: the source's (or anyone's) next message */
    mp_status st;
    mpok(R, mp_wait(R->self, q->wpeer, MP_ANY, &st), "mp_wait");
    int kind = st_env_kind(st.tag), ctx = st_env_ctx(st.tag), tag = st_env_tag(st.tag);
    if (kind != K_ACK && fits(q, st.source, ctx, tag)) {
      take_into(R, q, st.source, st.tag, st.len);
      unpromise(R, q);
      complete(R, q, st.source, kind, ctx, tag, st.len, 0);
      return;
    }
    dispatch(R, &st);
  }
}

void eng_step(st_rank *R) {
  mp_status st;
  mpok(R, mp_wait(R->self, MP_ANY, MP_ANY, &st), "mp_wait");
  dispatch(R, &st);
  advance_all(R);
}

void eng_advance(st_rank *R, st_req *q) {
  if (q->kind != RQ_KIND || q->state != RS_ACTIVE || !q->ops->progress || !q->ops->progress(q->ext)) return;
  q->state = RS_DONE;
  if (q->freed) st_req_free(R, q);
}

/* Every active request of a kind of its own advances (once each; not from
 * within a kind's own progress). */
static void advance_all(st_rank *R) {
  if (!R->nkinds || R->advancing) return;
  R->advancing = 1;
  for (int i = 0; i < R->nreqs; i++) {
    st_req *q = R->reqs[i];
    if (q->used && q->kind == RQ_KIND) eng_advance(R, q);
  }
  R->advancing = 0;
}

void eng_wait(st_rank *R, st_req *q) {
  while (q->state == RS_ACTIVE) {
    if (q->kind == RQ_KIND) {   /* its progress, between the messages that come */
      eng_advance(R, q);
      if (q->state == RS_ACTIVE) eng_step(R);
    } else if (q->kind == RQ_SEND && !R->posted) {
      /* Nothing posted to progress: the ack itself (acks of one key come
       * in the order of the sends, acked() gives each to its send). */
      int wpeer = q->wpeer, ctx = q->ctx, tag = q->tag;
      mpok(R, mp_recv(R->self, wpeer, st_env_encode(K_ACK, ctx, tag), NULL, 0, NULL), "mp_recv");
      acked(R, wpeer, ctx, tag);
    } else if (q->kind == RQ_RECV && R->posted == q && !q->next && q->wpeer >= 0) {
      /* The only receive posted, from one source: that source's messages. */
      mp_status st;
      mpok(R, mp_wait(R->self, q->wpeer, MP_ANY, &st), "mp_wait");
      dispatch(R, &st);
    } else {
      eng_step(R);
    }
  }
}

void eng_take(st_rank *R) {
  mp_status st;
  for (;;) {
    int rc = mp_probe(R->self, MP_ANY, MP_ANY, &st);
    if (rc == 0) break;
    if (rc < 0) mpok(R, rc, "mp_probe");
    dispatch(R, &st);
  }
}

void eng_poll(st_rank *R) {
  eng_take(R);
  advance_all(R);
}

int eng_probe(st_rank *R, int wsrc, int ctx, int tag, int block, int *src, int *mtag, size_t *len, st_msg **take) {
  for (st_msg *m = R->unexp, *next; m; m = next) {
    next = m->next;
    if (m->ctx == ctx && (wsrc < 0 || m->src == wsrc) && (tag < 0 || m->tag == tag)) {
      if (mp_msg_gone(R->self, m->h)) {
        unexp_unlink(R, m);
        unexp_free(R, m);
        continue;
      }
      *src = m->src;
      *mtag = m->tag;
      *len = m->len;
      if (take) {
        unexp_unlink(R, m);
        *take = m;
      }
      return 1;
    }
  }
  for (;;) {
    /* With receives posted, every message that comes is matched to them
     * first (a probe sees what they leave); without, the source's own. */
    int from = R->posted ? MP_ANY : wsrc;
    mp_status st;
    if (block) {
      mpok(R, mp_wait(R->self, from, MP_ANY, &st), "mp_wait");
    } else {
      int rc = mp_probe(R->self, from, MP_ANY, &st);
      if (rc == 0) return 0;
      if (rc < 0) mpok(R, rc, "mp_probe");
    }
    int k = st_env_kind(st.tag), c = st_env_ctx(st.tag), t = st_env_tag(st.tag);
    if (k != K_ACK && c == ctx && (wsrc < 0 || st.source == wsrc) && (tag < 0 || t == tag) &&
        !(R->posted && posted_fit(R, st.source, c, t))) {
      *src = st.source;
      *mtag = t;
      *len = st.len;
      if (take) {   /* taken off mp: no receive will match it but the program's own */
        st_msg *m = xmalloc(sizeof *m);
        *m = (st_msg){.src = st.source, .kind = k, .ctx = c, .tag = t, .len = st.len};
        mpok(R, mp_recv_msg(R->self, st.source, st.tag, &m->h, NULL), "mp_recv_msg");
        *take = m;
      }
      return 1;
    }
    dispatch(R, &st);
  }
}

void eng_msg_read(st_rank *R, st_req *q, st_msg *m) {
  if (unexp_gone(R, m)) {   /* withdrawn since the probe: nothing came */
    q->st = (MPI_Status){.MPI_SOURCE = MPI_ANY_SOURCE, .MPI_TAG = MPI_ANY_TAG, .MPI_ERROR = MPI_SUCCESS};
    q->msglen = 0;
    q->state = RS_DONE;
    return;
  }
  take_held(R, q, m);
}

void eng_msg_free(st_rank *R, st_msg *m) { unexp_free(R, m); }

int eng_cancel_recv(st_rank *R, st_req *q) {
  /* A promise that holds its message already: the receive has it. */
  if (q->prom && mp_promise_drop(R->self, q->prom, 1)) return 0;
  unlink_posted(R, q);   /* (counts q by its promise, gone now) */
  q->prom = NULL;
  st_ranks_drop(q->g);
  q->g = NULL;
  q->st = (MPI_Status){.MPI_SOURCE = MPI_ANY_SOURCE, .MPI_TAG = MPI_ANY_TAG, .MPI_ERROR = MPI_SUCCESS,
                       .tsmpi_cancelled = 1};
  q->msglen = 0;
  q->state = RS_DONE;
  return 1;
}

int eng_cancel_send(st_rank *R, st_req *q) {
  if (!q->ref || !mp_withdraw(R->self, q->ref)) return 0;
  q->ref = NULL;   /* spent */
  if (q->state == RS_ACTIVE) sync_unlink(R, q);   /* a synchronous send's ack will not come */
  q->st = (MPI_Status){.MPI_SOURCE = MPI_ANY_SOURCE, .MPI_TAG = MPI_ANY_TAG, .MPI_ERROR = MPI_SUCCESS,
                       .tsmpi_cancelled = 1};
  q->state = RS_DONE;
  return 1;
}

void eng_settle_all(st_rank *R) {
  for (int i = 0; i < R->nreqs; i++)
    if (R->reqs[i]->used) eng_settle(R, R->reqs[i]);
  if (R->held_ref) {   /* the rank ended inside a blocking call that sent by reference */
    mp_settle(R->self, R->held_ref);
    free(R->held_tmp);
    R->held_ref = NULL, R->held_tmp = NULL;
  }
}

void eng_release(st_rank *R) {
  while (R->posted) eng_unpost(R, R->posted);
  R->sync = R->sync_tail = NULL;
  eng_settle_all(R);
  for (st_msg *m = R->unexp, *n; m; m = n) {
    n = m->next;
    unexp_free(R, m);
  }
  R->unexp = R->unexp_tail = NULL;
  R->nunexp = 0;
}
