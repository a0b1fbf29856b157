/* label.c -- the words of a blocked MPI call (label.h). */
#include "mpi/label.h"

#include <stdarg.h>
#include <stdio.h>

/* Append to buf (len bytes, *at used so far). */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static void add(char *buf, size_t len, size_t *at, const char *fmt, ...) {
  if (*at >= len) return;
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(buf + *at, len - *at, fmt, ap);
  va_end(ap);
  if (n > 0) *at += (size_t)n < len - *at ? (size_t)n : len - *at;
}

static void peer_words(char *buf, size_t len, size_t *at, const char *what, int r) {
  if (r == MPI_ANY_SOURCE)
    add(buf, len, at, "%s=MPI_ANY_SOURCE", what);
  else
    add(buf, len, at, "%s=%d", what, r);
}

static void tag_words(char *buf, size_t len, size_t *at, const char *what, int t) {
  if (t == MPI_ANY_TAG)
    add(buf, len, at, ", %s=MPI_ANY_TAG", what);
  else
    add(buf, len, at, ", %s=%d", what, t);
}

void label_describe(void *ud, char *buf, size_t len) {
  const label_rec *l = ud;
  size_t at = 0;
  char b[32];
  add(buf, len, &at, "%s(", l->fn);
  switch (l->what) {
  case L_COMM:
    add(buf, len, &at, "%s)", st_pair_name(l->pair, b));
    return;
  case L_SEND:
    peer_words(buf, len, &at, "dest", l->peer);
    tag_words(buf, len, &at, "tag", l->tag);
    break;
  case L_RECV:
  case L_PROBE:
    peer_words(buf, len, &at, "source", l->peer);
    tag_words(buf, len, &at, "tag", l->tag);
    break;
  case L_SENDRECV:
    peer_words(buf, len, &at, "dest", l->peer);
    tag_words(buf, len, &at, "sendtag", l->tag);
    add(buf, len, &at, ", ");
    peer_words(buf, len, &at, "source", l->peer2);
    tag_words(buf, len, &at, "recvtag", l->tag2);
    break;
  case L_REQS: {
    int shown = 0;
    for (int i = 0; i < l->n; i++) {
      st_req *q = st_req_get(l->R, l->reqs[i]);
      if (!q || q->state != RS_ACTIVE) continue;
      if (shown++ == 4) {
        add(buf, len, &at, ", ...");
        break;
      }
      if (q->kind == RQ_KIND) {   /* a kind of its own: the call that made it */
        add(buf, len, &at, "%s%s", shown > 1 ? ", " : "", q->fn);
        continue;
      }
      add(buf, len, &at, "%s%s(", shown > 1 ? ", " : "", q->fn);
      if (q->kind == RQ_COLL) {   /* a nonblocking collective: its root, if any, and communicator */
        if (q->peer >= 0) add(buf, len, &at, "root=%d, ", q->peer);
        add(buf, len, &at, "%s)", st_pair_name(q->pair, b));
        continue;
      }
      peer_words(buf, len, &at, q->kind == RQ_SEND ? "dest" : "source", q->peer);
      tag_words(buf, len, &at, "tag", q->tag);
      add(buf, len, &at, ", %s)", st_pair_name(q->pair, b));
    }
    add(buf, len, &at, ")");
    return;
  }
  }
  add(buf, len, &at, ", %s)", st_pair_name(l->pair, b));
}
