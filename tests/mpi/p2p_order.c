/* p2p_order.c -- point-to-point semantics and ordering, checked by itself
 * on any number of ranks >= 2: blocking sends and receives around a ring,
 * non-overtaking per source and tag, receives matched in the order they
 * were posted with MPI_ANY_SOURCE and MPI_ANY_TAG, statuses and counts,
 * MPI_PROC_NULL, zero-length and long messages, Sendrecv and
 * Sendrecv_replace.  Every outcome checked here is the only one MPI allows,
 * whatever the timing. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

/* A ring: each rank sends its rank to the right and receives the left
 * one's, evens sending first. */
static void ring(mtest *t) {
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size;
  int out = 1000 + t->rank, in = -1;
  MPI_Status st;
  if (t->rank % 2 == 0) {
    MPI_Send(&out, 1, MPI_INT, right, 1, MPI_COMM_WORLD);
    MPI_Recv(&in, 1, MPI_INT, left, 1, MPI_COMM_WORLD, &st);
  } else {
    MPI_Recv(&in, 1, MPI_INT, left, 1, MPI_COMM_WORLD, &st);
    MPI_Send(&out, 1, MPI_INT, right, 1, MPI_COMM_WORLD);
  }
  int count = -1;
  MPI_Get_count(&st, MPI_INT, &count);
  MCHECK(t, in == 1000 + left, "ring: got %d from %d", in, left);
  MCHECK(t, st.MPI_SOURCE == left && st.MPI_TAG == 1 && count == 1, "ring: status %d %d %d", st.MPI_SOURCE,
         st.MPI_TAG, count);
  /* The same with Sendrecv, and Sendrecv_replace the other way round. */
  in = -1;
  MPI_Sendrecv(&out, 1, MPI_INT, right, 2, &in, 1, MPI_INT, left, 2, MPI_COMM_WORLD, &st);
  MCHECK(t, in == 1000 + left && st.MPI_SOURCE == left && st.MPI_TAG == 2, "sendrecv: %d from %d", in,
         st.MPI_SOURCE);
  int v[3] = {t->rank, 7 * t->rank, -t->rank};
  MPI_Sendrecv_replace(v, 3, MPI_INT, left, 3, right, 3, MPI_COMM_WORLD, &st);
  MCHECK(t, v[0] == right && v[1] == 7 * right && v[2] == -right && st.MPI_SOURCE == right,
         "sendrecv_replace: %d %d %d from %d", v[0], v[1], v[2], st.MPI_SOURCE);
}

/* Rank 0 sends rank 1 N messages on two tags interleaved; rank 1 takes
 * all of tag 5 first, then all of tag 6: each tag's in send order. */
static void overtaking(mtest *t) {
  enum { N = 40 };
  if (t->rank == 0) {
    for (int i = 0; i < N; i++) {
      int v = i;
      MPI_Send(&v, 1, MPI_INT, 1, 5 + i % 2, MPI_COMM_WORLD);
    }
  } else if (t->rank == 1) {
    for (int tag = 5; tag <= 6; tag++) {
      for (int i = tag - 5; i < N; i += 2) {
        int v = -1;
        MPI_Recv(&v, 1, MPI_INT, 0, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        MCHECK(t, v == i, "tag %d: message %d came where %d was due", tag, v, i);
      }
    }
    /* From one source with MPI_ANY_TAG: in send order. */
  }
  if (t->rank == 0) {
    for (int i = 0; i < N; i++) {
      int v = i;
      MPI_Send(&v, 1, MPI_INT, 1, i % 7, MPI_COMM_WORLD);
    }
  } else if (t->rank == 1) {
    for (int i = 0; i < N; i++) {
      int v = -1;
      MPI_Status st;
      MPI_Recv(&v, 1, MPI_INT, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
      MCHECK(t, v == i && st.MPI_TAG == i % 7, "any tag: message %d (tag %d) where %d was due", v,
             st.MPI_TAG, i);
    }
  }
}

/* Receives posted before the messages can match them, in posting order. */
static void posted_order(mtest *t) {
  if (t->rank == 0) {
    int v[3] = {1, 2, 3};
    MPI_Send(&v[0], 1, MPI_INT, 1, 7, MPI_COMM_WORLD);
    MPI_Send(&v[1], 1, MPI_INT, 1, 5, MPI_COMM_WORLD);
    MPI_Send(&v[2], 1, MPI_INT, 1, 9, MPI_COMM_WORLD);
    /* (source 0, tag 5) then anything, with a message of tag 7 sent first:
     * the exact receive takes the tag-5 message, whenever each came. */
    int w[2] = {10, 11};
    MPI_Send(&w[0], 1, MPI_INT, 1, 7, MPI_COMM_WORLD);
    MPI_Send(&w[1], 1, MPI_INT, 1, 5, MPI_COMM_WORLD);
    /* Two receives fit both messages: the first posted takes the first sent. */
    int u[2] = {20, 21};
    MPI_Send(&u[0], 1, MPI_INT, 1, 5, MPI_COMM_WORLD);
    MPI_Send(&u[1], 1, MPI_INT, 1, 5, MPI_COMM_WORLD);
  } else if (t->rank == 1) {
    int a = 0, b = 0, c = 0;
    MPI_Request r[3];
    MPI_Status st[3];
    MPI_Irecv(&a, 1, MPI_INT, MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &r[0]);
    MPI_Irecv(&b, 1, MPI_INT, 0, 5, MPI_COMM_WORLD, &r[1]);
    MPI_Irecv(&c, 1, MPI_INT, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &r[2]);
    MPI_Waitall(3, r, st);
    MCHECK(t, a == 1 && b == 2 && c == 3, "posted order: %d %d %d (1 2 3 due)", a, b, c);
    MCHECK(t, st[0].MPI_TAG == 7 && st[1].MPI_TAG == 5 && st[2].MPI_TAG == 9 && st[0].MPI_SOURCE == 0,
           "posted order: tags %d %d %d", st[0].MPI_TAG, st[1].MPI_TAG, st[2].MPI_TAG);
    int x = 0, y = 0;
    MPI_Irecv(&x, 1, MPI_INT, 0, 5, MPI_COMM_WORLD, &r[0]);
    MPI_Irecv(&y, 1, MPI_INT, MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &r[1]);
    MPI_Waitall(2, r, st);
    MCHECK(t, x == 11 && y == 10, "exact before wildcard: %d %d (11 10 due)", x, y);
    MPI_Irecv(&x, 1, MPI_INT, MPI_ANY_SOURCE, 5, MPI_COMM_WORLD, &r[0]);
    MPI_Irecv(&y, 1, MPI_INT, 0, 5, MPI_COMM_WORLD, &r[1]);
    /* Complete them in the other order: the matching is the posting's. */
    MPI_Wait(&r[1], &st[1]);
    MPI_Wait(&r[0], &st[0]);
    MCHECK(t, x == 20 && y == 21, "two fitting receives: %d %d (20 21 due)", x, y);
  }
}

/* Every other rank sends rank 0 four messages, tagged 100, its rank, 200
 * and 300; rank 0 first takes the tag-300 ones from each named source in
 * reverse (past the others), then the rest from any source with any tag:
 * each source's in its order. */
static void any_source(mtest *t) {
  if (t->rank != 0) {
    int v[2] = {t->rank, t->rank * t->rank};
    MPI_Send(v, 1, MPI_INT, 0, 100, MPI_COMM_WORLD);
    MPI_Send(v, 2, MPI_INT, 0, t->rank, MPI_COMM_WORLD);
    MPI_Send(v, 1, MPI_INT, 0, 200, MPI_COMM_WORLD);
    MPI_Send(v, 1, MPI_INT, 0, 300, MPI_COMM_WORLD);
    return;
  }
  for (int s = t->size - 1; s >= 1; s--) {
    int v = -1, count = -1;
    MPI_Status st;
    MPI_Recv(&v, 1, MPI_INT, s, 300, MPI_COMM_WORLD, &st);
    MPI_Get_count(&st, MPI_INT, &count);
    MCHECK(t, v == s && st.MPI_SOURCE == s && st.MPI_TAG == 300 && count == 1, "named source %d: %d", s, v);
  }
  int *seen = calloc((size_t)t->size, sizeof *seen);
  for (int i = 0; i < 3 * (t->size - 1); i++) {
    int v[2] = {-1, -1}, count = -1;
    MPI_Status st;
    MPI_Recv(v, 2, MPI_INT, MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
    MPI_Get_count(&st, MPI_INT, &count);
    int s = st.MPI_SOURCE;
    if (s <= 0 || s >= t->size) {
      MCHECK(t, 0, "any source: from %d", s);
      continue;
    }
    int k = seen[s]++, tag = k == 0 ? 100 : k == 1 ? s : 200;
    MCHECK(t, st.MPI_TAG == tag && v[0] == s && count == (k == 1 ? 2 : 1) && (k != 1 || v[1] == s * s),
           "any source: message %d from %d has tag %d (%d due), values %d %d, count %d", k, s, st.MPI_TAG,
           tag, v[0], v[1], count);
  }
  free(seen);
}

/* MPI_PROC_NULL: sends vanish, receives complete at once with source
 * MPI_PROC_NULL, tag MPI_ANY_TAG and count 0. */
static void proc_null(mtest *t) {
  int v = 42;
  MPI_Status st;
  MPI_Send(&v, 1, MPI_INT, MPI_PROC_NULL, 1, MPI_COMM_WORLD);
  MPI_Recv(&v, 1, MPI_INT, MPI_PROC_NULL, 1, MPI_COMM_WORLD, &st);
  int count = -1;
  MPI_Get_count(&st, MPI_INT, &count);
  MCHECK(t, v == 42 && st.MPI_SOURCE == MPI_PROC_NULL && st.MPI_TAG == MPI_ANY_TAG && count == 0,
         "proc null: %d %d %d %d", v, st.MPI_SOURCE, st.MPI_TAG, count);
  MPI_Request r;
  MPI_Irecv(&v, 1, MPI_INT, MPI_PROC_NULL, 1, MPI_COMM_WORLD, &r);
  MPI_Wait(&r, &st);
  MCHECK(t, r == MPI_REQUEST_NULL && st.MPI_SOURCE == MPI_PROC_NULL, "proc null irecv: %d", st.MPI_SOURCE);
}

/* Zero-length and long messages between ranks 0 and the last, both ways,
 * with a receive buffer longer than the message (the count is the
 * message's). */
static void lengths(mtest *t) {
  int last = t->size - 1;
  enum { BIG = 1 << 20 };
  if (t->rank != 0 && t->rank != last) return;
  int peer = t->rank == 0 ? last : 0;
  unsigned char *out = malloc(BIG), *in = malloc(BIG + 100);
  for (int i = 0; i < BIG; i++) out[i] = (unsigned char)(i * 7 + t->rank);
  MPI_Status st;
  int count = -1;
  if (t->rank == 0) {
    MPI_Send(NULL, 0, MPI_BYTE, peer, 1, MPI_COMM_WORLD);
    MPI_Send(out, BIG, MPI_BYTE, peer, 2, MPI_COMM_WORLD);
    MPI_Recv(in, BIG + 100, MPI_BYTE, peer, 3, MPI_COMM_WORLD, &st);
  } else {
    MPI_Recv(in, 10, MPI_BYTE, peer, 1, MPI_COMM_WORLD, &st);
    MPI_Get_count(&st, MPI_BYTE, &count);
    MCHECK(t, count == 0 && st.MPI_TAG == 1, "zero-length: count %d", count);
    MPI_Recv(in, BIG + 100, MPI_BYTE, peer, 2, MPI_COMM_WORLD, &st);
    MPI_Send(out, BIG, MPI_BYTE, peer, 3, MPI_COMM_WORLD);
  }
  MPI_Get_count(&st, MPI_BYTE, &count);
  int bad = 0;
  for (int i = 0; i < BIG; i++) bad += in[i] != (unsigned char)(i * 7 + peer);
  MCHECK(t, count == BIG && bad == 0, "long message: count %d, %d bytes wrong", count, bad);
  int dcount = -1;
  MPI_Get_count(&st, MPI_DOUBLE, &dcount);
  MCHECK(t, dcount == BIG / 8, "count in doubles %d", dcount);
  free(out);
  free(in);
}

/* A rank's messages to itself (nonblocking send, so as not to rely on
 * buffering). */
static void to_self(mtest *t) {
  int v[4] = {t->rank, 1, 2, 3}, w[4] = {0};
  MPI_Request r;
  MPI_Status st;
  MPI_Isend(v, 4, MPI_INT, t->rank, 9, MPI_COMM_WORLD, &r);
  MPI_Recv(w, 4, MPI_INT, MPI_ANY_SOURCE, 9, MPI_COMM_WORLD, &st);
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  MCHECK(t, memcmp(v, w, sizeof v) == 0 && st.MPI_SOURCE == t->rank, "self: %d %d from %d", w[0], w[3],
         st.MPI_SOURCE);
  MPI_Sendrecv(v, 4, MPI_INT, 0, 10, w, 4, MPI_INT, 0, 10, MPI_COMM_SELF, &st);
  MCHECK(t, memcmp(v, w, sizeof v) == 0 && st.MPI_SOURCE == 0, "self on MPI_COMM_SELF: from %d",
         st.MPI_SOURCE);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {ring, overtaking, posted_order, any_source, proc_null, lengths, to_self, NULL};
  return mtest_main(&argc, &argv, "p2p_order", 2, 0, checks);
}
