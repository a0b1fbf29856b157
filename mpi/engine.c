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
 * messages were sent, as the receiver takes those in that order. */
#include "engine.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "xmem.h"

/* ==== mp calls ============================================================ */

/* An mp call's result: a stopped run ends the rank; anything else but MP_OK
 * is a bug of this layer (the arguments are ours). */
static void mpok(tsm *R, int rc, const char *call) {
  if (rc == MP_OK) return;
  if (rc == MP_ESTOPPED || rc == MP_EDEADLOCK) tsm_stopped(R);
  fprintf(stderr, "tilesim MPI: internal error: rank %d: %s: %s\n", R->wrank, call, mp_strerror(rc));
  abort();
}

/* ==== queues ============================================================== */

static void post(tsm *R, tsm_req *q) {
  q->next = NULL;
  q->prev = R->posted_tail;
  if (R->posted_tail)
    R->posted_tail->next = q;
  else
    R->posted = q;
  R->posted_tail = q;
  q->state = RS_ACTIVE;
  q->g->refs++;
}

static void unlink_posted(tsm *R, tsm_req *q) {
  if (q->prev)
    q->prev->next = q->next;
  else
    R->posted = q->next;
  if (q->next)
    q->next->prev = q->prev;
  else
    R->posted_tail = q->prev;
  q->next = q->prev = NULL;
}

void eng_unpost(tsm *R, tsm_req *q) {
  unlink_posted(R, q);
  tsm_ranks_drop(q->g);
  q->g = NULL;
}

static void sync_add(tsm *R, tsm_req *q) {
  q->next = NULL;
  q->prev = R->sync_tail;
  if (R->sync_tail)
    R->sync_tail->next = q;
  else
    R->sync = q;
  R->sync_tail = q;
}

static void sync_unlink(tsm *R, tsm_req *q) {
  if (q->prev)
    q->prev->next = q->next;
  else
    R->sync = q->next;
  if (q->next)
    q->next->prev = q->prev;
  else
    R->sync_tail = q->prev;
  q->next = q->prev = NULL;
}

static void unexp_unlink(tsm *R, tsm_msg *m) {
  if (m->prev)
    m->prev->next = m->next;
  else
    R->unexp = m->next;
  if (m->next)
    m->next->prev = m->prev;
  else
    R->unexp_tail = m->prev;
  R->nunexp--;
}

static inline int fits(const tsm_req *q, int src, int ctx, int tag) {
  return q->ctx == ctx && (q->wpeer < 0 || q->wpeer == src) && (q->tag < 0 || q->tag == tag);
}

static tsm_req *posted_fit(tsm *R, int src, int ctx, int tag) {
  for (tsm_req *q = R->posted; q; q = q->next)
    if (fits(q, src, ctx, tag)) return q;
  return NULL;
}

/* ==== completing ========================================================== */

/* n received bytes at data into q's buffer. */
static void place(tsm_req *q, const void *data, size_t n) {
  if (n == 0) return;
  if (q->contig)
    memcpy(q->contig, data, n);
  else
    tsmpi_type_unpack(data, n, q->buf, q->count, q->dt);
}

/* q has taken a len-byte message from world rank src with the envelope
 * (kind, ctx, tag): its status, the ack a synchronous send waits for, and
 * a freed request's end.  counted: q was posted (holds a count on q->g). */
static void complete(tsm *R, tsm_req *q, int src, int kind, int ctx, int tag, size_t len, int counted) {
  q->st.MPI_SOURCE = q->g->world ? tsm_ranks_find(q->g, src) : src;
  q->st.MPI_TAG = tag;
  q->st.MPI_ERROR = len > q->cap ? MPI_ERR_TRUNCATE : MPI_SUCCESS;
  q->st.tsmpi_cancelled = 0;
  q->st.tsmpi_count = (MPI_Count)(len < q->cap ? len : q->cap);
  q->msglen = len;
  if (counted) tsm_ranks_drop(q->g);
  q->g = NULL;
  q->state = RS_DONE;
  if (q->watch) R->progress_due = 1;
  if (kind == K_SYNC) mpok(R, mp_send(R->self, src, env_encode(K_ACK, ctx, tag), NULL, 0), "mp_send");
  if (q->freed) tsm_req_free(R, q);
}

/* The nonblocking collectives' progress, after a watched request completed
 * (never inside itself: what it starts is seen by its own loop). */
static void progress(tsm *R) {
  if (R->in_progress || !R->progress) return;
  R->in_progress = 1;
  while (R->progress_due) {
    R->progress_due = 0;
    R->progress();
  }
  R->in_progress = 0;
}

/* Take the message shown (src, mptag, len) off mp into q's buffer. */
static void take_into(tsm *R, tsm_req *q, int src, int mptag, size_t len) {
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
static void acked(tsm *R, int src, int ctx, int tag) {
  for (tsm_req *q = R->sync; q; q = q->next) {
    if (q->wpeer == src && q->ctx == ctx && q->tag == tag) {
      sync_unlink(R, q);
      q->state = RS_DONE;
      if (q->freed) tsm_req_free(R, q);
      return;
    }
  }
  fprintf(stderr, "tilesim MPI: internal error: rank %d: an ack from rank %d (context %d, tag %d) for no send\n",
          R->wrank, src, ctx, tag);
  abort();
}

/* Take the message mp has shown (st) and act on it: an ack, a posted
 * receive's message, or an unexpected one; then the progress of the
 * nonblocking collectives it moved. */
static void act(tsm *R, const mp_status *st);
static void dispatch(tsm *R, const mp_status *st) {
  act(R, st);
  if (R->progress_due) progress(R);
}

static void act(tsm *R, const mp_status *st) {
  int kind = env_kind(st->tag), ctx = env_ctx(st->tag), tag = env_tag(st->tag);
  if (kind == K_ACK) {
    mpok(R, mp_recv(R->self, st->source, st->tag, NULL, 0, NULL), "mp_recv");
    acked(R, st->source, ctx, tag);
    return;
  }
  tsm_req *q = R->posted ? posted_fit(R, st->source, ctx, tag) : NULL;
  if (q) {
    unlink_posted(R, q);
    take_into(R, q, st->source, st->tag, st->len);
    complete(R, q, st->source, kind, ctx, tag, st->len, 1);
    return;
  }
  tsm_msg *m = xmalloc(sizeof *m);
  m->src = st->source;
  m->kind = kind;
  m->ctx = ctx;
  m->tag = tag;
  m->len = st->len;
  m->data = st->len ? xmalloc(st->len) : NULL;
  mpok(R, mp_recv(R->self, st->source, st->tag, m->data, st->len, NULL), "mp_recv");
  m->next = NULL;
  m->prev = R->unexp_tail;
  if (R->unexp_tail)
    R->unexp_tail->next = m;
  else
    R->unexp = m;
  R->unexp_tail = m;
  R->nunexp++;
}

/* ==== the calls =========================================================== */

void eng_send(tsm *R, tsm_req *q, const void *data, size_t len) {
  int kind = q->mode == SM_SYNC ? K_SYNC : K_DATA;
  mpok(R, mp_send(R->self, q->wpeer, env_encode(kind, q->ctx, q->tag), data, len), "mp_send");
  q->st = (MPI_Status){.MPI_SOURCE = MPI_ANY_SOURCE, .MPI_TAG = MPI_ANY_TAG, .MPI_ERROR = MPI_SUCCESS};
  if (kind == K_SYNC) {
    q->state = RS_ACTIVE;
    sync_add(R, q);
  } else {
    q->state = RS_DONE;
  }
}

void eng_send_data(tsm *R, int wdst, int ctx, int tag, const void *data, size_t len) {
  mpok(R, mp_send(R->self, wdst, env_encode(K_DATA, ctx, tag), data, len), "mp_send");
}

int eng_recv_data(tsm *R, int wsrc, int ctx, int tag, void *p, size_t cap, mp_status *got) {
  mp_status st;
  mpok(R, mp_wait(R->self, wsrc, MP_ANY, &st), "mp_wait");
  if (env_kind(st.tag) != K_DATA || env_ctx(st.tag) != ctx || (tag >= 0 && env_tag(st.tag) != tag) ||
      st.len > cap)
    return 0;
  mpok(R, mp_recv(R->self, st.source, st.tag, st.len ? p : NULL, st.len, NULL), "mp_recv");
  *got = (mp_status){st.source, env_tag(st.tag), st.len};
  return 1;
}

/* The first unexpected message q fits, taken into q; 1, or 0 if none. */
static int from_unexp(tsm *R, tsm_req *q) {
  for (tsm_msg *m = R->unexp; m; m = m->next) {
    if (!fits(q, m->src, m->ctx, m->tag)) continue;
    unexp_unlink(R, m);
    place(q, m->data, m->len < q->cap ? m->len : q->cap);
    complete(R, q, m->src, m->kind, m->ctx, m->tag, m->len, 0);
    free(m->data);
    free(m);
    return 1;
  }
  return 0;
}

void eng_recv_start(tsm *R, tsm_req *q) {
  if (R->nunexp && from_unexp(R, q)) return;
  post(R, q);
}

void eng_recv(tsm *R, tsm_req *q) {
  if (R->nunexp && from_unexp(R, q)) return;
  if (R->posted) {   /* others are posted: in line behind them */
    post(R, q);
    eng_wait(R, q);
    return;
  }
  for (;;) {   /* the fast path: the source's (or anyone's) next message */
    mp_status st;
    mpok(R, mp_wait(R->self, q->wpeer, MP_ANY, &st), "mp_wait");
    int kind = env_kind(st.tag), ctx = env_ctx(st.tag), tag = env_tag(st.tag);
    if (kind != K_ACK && fits(q, st.source, ctx, tag)) {
      take_into(R, q, st.source, st.tag, st.len);
      complete(R, q, st.source, kind, ctx, tag, st.len, 0);
      return;
    }
    dispatch(R, &st);
  }
}

void eng_step(tsm *R) {
  mp_status st;
  mpok(R, mp_wait(R->self, MP_ANY, MP_ANY, &st), "mp_wait");
  dispatch(R, &st);
}

void eng_wait(tsm *R, tsm_req *q) {
  while (q->state == RS_ACTIVE) {
    if (q->kind == RQ_SEND && !R->posted) {
      /* Nothing posted to progress: the ack itself (acks of one key come
       * in the order of the sends, acked() gives each to its send). */
      int wpeer = q->wpeer, ctx = q->ctx, tag = q->tag;
      mpok(R, mp_recv(R->self, wpeer, env_encode(K_ACK, ctx, tag), NULL, 0, NULL), "mp_recv");
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

void eng_poll(tsm *R) {
  mp_status st;
  for (;;) {
    int rc = mp_probe(R->self, MP_ANY, MP_ANY, &st);
    if (rc == 0) return;
    if (rc < 0) mpok(R, rc, "mp_probe");
    dispatch(R, &st);
  }
}

int eng_probe(tsm *R, int wsrc, int ctx, int tag, int block, int *src, int *mtag, size_t *len) {
  for (tsm_msg *m = R->unexp; m; m = m->next) {
    if (m->ctx == ctx && (wsrc < 0 || m->src == wsrc) && (tag < 0 || m->tag == tag)) {
      *src = m->src;
      *mtag = m->tag;
      *len = m->len;
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
    int k = env_kind(st.tag), c = env_ctx(st.tag), t = env_tag(st.tag);
    if (k != K_ACK && c == ctx && (wsrc < 0 || st.source == wsrc) && (tag < 0 || t == tag) &&
        !(R->posted && posted_fit(R, st.source, c, t))) {
      *src = st.source;
      *mtag = t;
      *len = st.len;
      return 1;
    }
    dispatch(R, &st);
  }
}

void eng_release(tsm *R) {
  while (R->posted) eng_unpost(R, R->posted);
  R->sync = R->sync_tail = NULL;
  for (tsm_msg *m = R->unexp, *n; m; m = n) {
    n = m->next;
    free(m->data);
    free(m);
  }
  R->unexp = R->unexp_tail = NULL;
  R->nunexp = 0;
}
