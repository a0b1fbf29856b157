/* mailbox.c -- the simulator's messages and mailboxes (mailbox.h). */
#include "mailbox.h"

#include <stdlib.h>

#include "xmem.h"

msg *msg_new(mstore *st, size_t len) {
  msg *m = st->free;
  if (m)
    st->free = m->next;
  else
    m = xmalloc(sizeof *m);
  m->data = len <= MSG_INLINE ? m->inl : xmalloc(len);
  return m;
}

void msg_free(mstore *st, msg *m) {
  if (m->data != m->inl) free(m->data);
  m->next = st->free;
  st->free = m;
}

void mstore_free(mstore *st) {
  while (st->free) {
    msg *m = st->free;
    st->free = m->next;
    free(m);
  }
}

void box_insert(mbox *b, msg *m) {
  msg *p = b->tail;
  while (p && p->arrival > m->arrival) p = p->prev;
  m->prev = p;
  m->next = p ? p->next : b->head;
  if (m->next)
    m->next->prev = m;
  else
    b->tail = m;
  if (p)
    p->next = m;
  else
    b->head = m;
}

void box_unlink(mbox *b, msg *m) {
  if (m->prev)
    m->prev->next = m->next;
  else
    b->head = m->next;
  if (m->next)
    m->next->prev = m->prev;
  else
    b->tail = m->prev;
}

msg *box_find(const mbox *b, int src, int tag) {
  for (msg *m = b->head; m; m = m->next)
    if (msg_matches(m, src, tag)) return m;
  return NULL;
}

void box_clear(mbox *b, mstore *st) {
  while (b->head) {
    msg *m = b->head;
    b->head = m->next;
    msg_free(st, m);
  }
  b->tail = NULL;
}
