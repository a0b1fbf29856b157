/* mailbox.h -- the simulator's messages and each rank's mailbox (sim.c's
 * data): a message's envelope, times and payload, and the mailbox that
 * holds a rank's messages sent and not yet received, in the order a
 * receive takes them (arrival, then send order).  Spent messages are kept
 * for reuse. */
#ifndef MAILBOX_H
#define MAILBOX_H

#include <stddef.h>
#include <stdint.h>

enum { MSG_INLINE = 64 };   /* payloads up to this many bytes live in the message */

typedef struct msg msg;
struct msg {
  msg *prev, *next;        /* in the receiver's mailbox, by (arrival, seq) */
  double sent;             /* the sender's clock at mp_send */
  double arrival;          /* when it can be received */
  uint64_t seq;            /* send order, machine-wide; the message id in traces */
  int src, tag;
  size_t len;
  unsigned char *data;     /* inl, or a heap block for longer payloads */
  unsigned char inl[MSG_INLINE];
};

/* A rank's mailbox. */
typedef struct {
  msg *head, *tail;
} mbox;

/* The machine's spent messages, for reuse. */
typedef struct {
  msg *free;
} mstore;

/* A message with room for len bytes of payload at m->data; back to the
 * store with msg_free; mstore_free frees the store's messages. */
msg *msg_new(mstore *st, size_t len);
void msg_free(mstore *st, msg *m);
void mstore_free(mstore *st);

/* Insert m into b by (arrival, seq); its seq is the largest yet. */
void box_insert(mbox *b, msg *m);
void box_unlink(mbox *b, msg *m);

/* m's envelope fits a receive from src with tag (MP_ANY = -1: any). */
static inline int msg_matches(const msg *m, int src, int tag) {
  return (src < 0 || m->src == src) && (tag < 0 || m->tag == tag);
}

/* The earliest (arrival, seq) message of b matching src and tag, or NULL. */
msg *box_find(const mbox *b, int src, int tag);

/* Free every message of b into st. */
void box_clear(mbox *b, mstore *st);

#endif
