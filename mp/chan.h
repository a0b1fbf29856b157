/* chan.h -- the threads backend's channels (threads.c): a queue of
 * messages from one rank to another, with one writer (the sender's thread)
 * and one reader (the receiver's), so that a send takes no lock and no
 * read-modify-write operation.
 *
 * The queue is a list of 16 KiB chunks of records, each record on cache
 * lines of its own: a header (tag, length, Lamport stamp), then the payload
 * inline (up to INLINE_MAX bytes) or a pointer to a copy.  The writer fills
 * a record and then publishes it with one store of its size (sequentially
 * consistent: threads.c's Sleeping says why); the reader polls that word.
 * A message thus costs the two cores about two cache-line transfers (the
 * record and, now and then, a fresh line of the chunk), and no allocation
 * below INLINE_MAX bytes.  The reader frees a chunk when it has taken
 * everything in it; a record taken out of order (a tag or source passed
 * over) is marked and skipped. */
#ifndef CHAN_H
#define CHAN_H

#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

enum {
  LINE = 64,                      /* a cache line: records start on one */
  CHUNK = 16384,                  /* a chunk of a channel, its header line included */
  CHUNK_DATA = CHUNK - LINE,
  REC_JUMP = 1                    /* size word of the record that says: the next chunk */
};
enum {
  REC_BIG = 1,                    /* flags: the payload is a pointer to a copy */
  REC_TAKEN = 2,                  /* flags: received out of order (the reader's mark) */
  REC_REF = 4                     /* flags: a send by reference: a ticket pointer, then
                                     the payload if it fits INLINE_MAX */
};

/* A record.  `size` is 0 until the writer publishes it (seq_cst), then the
 * record's bytes (a multiple of LINE), or REC_JUMP. */
typedef struct rec {
  _Atomic uint32_t size;
  int32_t tag;
  uint32_t flags;
  uint32_t src;
  uint64_t stamp;     /* the sender's Lamport clock */
  uint64_t len;       /* the payload's bytes */
} rec;                /* 32 bytes; the payload (or its pointer) follows */

enum { INLINE_MAX = 1024 - (int)sizeof(rec) };   /* longer payloads go by pointer */

typedef struct chunk chunk;
struct chunk {
  chunk *next;        /* written before the REC_JUMP that leads to it */
  char pad[LINE - sizeof(chunk *)];
  /* CHUNK_DATA bytes of records follow, zeroed */
};

static inline rec *rec_at(chunk *c, size_t off) { return (rec *)((char *)c + LINE + off); }
static inline unsigned char *rec_data(rec *x) { return (unsigned char *)(x + 1); }

/* A new chunk, zeroed. */
chunk *chunk_new(void);

/* A channel from one rank to another. */
typedef struct chan {
  /* The writer's, on lines of their own. */
  chunk *wc;
  size_t woff;
  char pad1[LINE - sizeof(chunk *) - sizeof(size_t)];
  /* The reader's. */
  chunk *hc;          /* head: the first record not yet taken (or a jump) */
  size_t hoff;
  chunk *sc;          /* scan: the first record the reader has not yet seen */
  size_t soff;
  int src;
  char pad2[LINE - 2 * sizeof(chunk *) - 2 * sizeof(size_t) - sizeof(int)];
} chan;

/* Append a record (tag, buf[0..len)) and publish it.  Returns it. */
rec *chan_put(chan *q, int src, int tag, uint64_t stamp, const void *buf, size_t len);

/* SENDS BY REFERENCE (mp_send_ref).  The record holds a ticket that its
 * sender and its reader share: the payload is in the record (up to
 * INLINE_MAX bytes) or stays in the sender's buffer, and the ticket's state
 * says who may do what, each step one compare-and-swap:
 *
 *   T_REF   unseen          reader: looks at it -> T_SEEN; sender: settles
 *                           -> T_MOVING, copies out -> T_OWN; withdraws
 *                           -> T_GONE (the reader skips it)
 *   T_SEEN  a receive has   reader: copies -> T_BUSY ... T_READ; sender:
 *           looked at it    settles as from T_REF; cannot withdraw
 *   T_BUSY  the reader copies (from the sender's buffer: a settle waits
 *           for T_READ)
 *   T_MOVING the sender copies its buffer out: the reader waits for T_OWN
 *
 * A message taken by mp_recv_msg goes back from T_SEEN to T_REF (a held
 * message may still be withdrawn; its holder sees T_GONE).  The ticket is
 * freed by the last of its two owners to let go (the sender when it
 * settles or withdraws, the reader when it takes the record). */
enum { T_REF, T_SEEN, T_BUSY, T_READ, T_MOVING, T_OWN, T_GONE };

typedef struct {
  _Atomic int state;          /* T_* */
  _Atomic int refs;           /* owners left: 2, 1, then freed */
  const unsigned char *buf;   /* the sender's buffer, or NULL: in the record */
  unsigned char *copy;        /* T_OWN: the payload, copied out by the settle */
  size_t len;
} ticket;

/* Append a record by reference and publish it; *t its ticket. */
rec *chan_put_ref(chan *q, int src, int tag, uint64_t stamp, const void *buf, size_t len, ticket **t);

static inline ticket *rec_ticket(rec *x) {
  ticket *t;
  memcpy(&t, rec_data(x), sizeof t);
  return t;
}

/* The reader copies n bytes of t's payload (in the sender's buffer, or at
 * inl: the record's, or a held copy of it) into buf; 0, or -1 if its
 * sender withdrew it (only a held message can be: one in a channel has
 * been seen). */
int ticket_read(ticket *t, const unsigned char *inl, void *buf, size_t n);

/* The sender: settles (buf is its own again when this returns), withdraws
 * (1, or 0: a receive has looked at it or read it; then settle it). */
void ticket_settle(ticket *t);
int ticket_withdraw(ticket *t);

/* One owner lets go. */
void ticket_drop(ticket *t);

static inline int tag_ok(int want, int tag) { return want < 0 || want == tag; }

/* The first record of q not yet taken whose tag matches, or NULL; records
 * published since the last look are seen now.  Only q's reader calls it. */
rec *chan_find(chan *q, int tag);

/* Anything published in q since the reader last looked? */
static inline int chan_news(chan *q) {
  return atomic_load_explicit(&rec_at(q->sc, q->soff)->size, memory_order_relaxed) != 0;
}

/* x (found by chan_find, its payload already copied out) is taken: passed
 * by the head if it is the first record not taken, else marked. */
void chan_take(chan *q, rec *x);

/* Every chunk of q, and the copies of the big payloads never taken; q. */
void chan_free(chan *q);

#endif
