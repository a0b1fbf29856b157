/* p2p_mprobe.c -- matched probes (MPI_Mprobe, MPI_Improbe, MPI_Mrecv,
 * MPI_Imrecv, MPI_MESSAGE_NO_PROC), checked by themselves on any number of
 * ranks >= 2: the message a matched probe shows is taken out of matching
 * (no other probe or receive sees it) and received by MPI_Mrecv or
 * MPI_Imrecv alone, intact, with the probe's envelope; messages from one
 * source keep their order around it; a probe from MPI_PROC_NULL gives
 * MPI_MESSAGE_NO_PROC, whose receive is empty; a message longer than the
 * receive truncates; a derived type receives as MPI_Recv would. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"
#include "probetest.h"

/* Every other rank sends rank 0 rank * 3 ints (each its rank), tag = rank;
 * rank 0 takes each with MPI_Mprobe from any source, checks that the
 * message is out of matching (an MPI_Iprobe by its source and tag finds
 * nothing), sizes its buffer by the count and receives it with MPI_Mrecv. */
static void mprobe_any_on(mtest *t, MPI_Comm comm) {
  if (!probetest_send(t, comm)) return;
  int bad = 0;
  for (int k = 1; k < t->size; k++) {
    MPI_Message msg = MPI_MESSAGE_NULL;
    MPI_Status st, st2;
    int count = -1, flag = -1;
    MPI_Mprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm, &msg, &st);
    int s = st.MPI_SOURCE;
    MPI_Get_count(&st, MPI_INT, &count);
    MPI_Iprobe(s, st.MPI_TAG, comm, &flag, MPI_STATUS_IGNORE);
    bad += msg == MPI_MESSAGE_NULL || s < 1 || s >= t->size || st.MPI_TAG != s || count != 3 * s || flag != 0;
    if (s < 1 || s >= t->size || count < 0) continue;
    int *v = malloc((size_t)(count + 1) * sizeof *v);
    MPI_Mrecv(v, count, MPI_INT, &msg, &st2);
    int wrong = 0;
    for (int i = 0; i < count; i++) wrong += v[i] != s;
    MPI_Get_count(&st2, MPI_INT, &count);
    bad += wrong || msg != MPI_MESSAGE_NULL || st2.MPI_SOURCE != s || st2.MPI_TAG != s || count != 3 * s;
    free(v);
  }
  MCHECK(t, bad == 0, "matched probes from any source: %d wrong", bad);
}

/* mprobe_any on a duplicate of MPI_COMM_WORLD. */
static void mprobe_any(mtest *t) {
  MPI_Comm comm;
  MPI_Comm_dup(MPI_COMM_WORLD, &comm);
  mprobe_any_on(t, comm);
  MPI_Comm_free(&comm);
}

/* Rank 1 sends rank 0 three messages, tag 7, values 1, 2, 3, then one of
 * tag 8.  Rank 0 takes the first by MPI_Improbe (polling), the second by a
 * plain receive, the third by MPI_Mprobe and MPI_Imrecv, and only then
 * receives the first: 1, 2, 3 where they belong.  Tag 8's message is shown
 * by MPI_Probe, taken by MPI_Mprobe, and received. */
static void mprobe_order(mtest *t) {
  if (t->rank == 1) {
    for (int v = 1; v <= 3; v++) MPI_Send(&v, 1, MPI_INT, 0, 7, MPI_COMM_WORLD);
    int w = 8;
    MPI_Send(&w, 1, MPI_INT, 0, 8, MPI_COMM_WORLD);
  }
  if (t->rank != 0) return;
  MPI_Message m1 = MPI_MESSAGE_NULL, m3 = MPI_MESSAGE_NULL, m8 = MPI_MESSAGE_NULL;
  MPI_Status st;
  int flag = 0, a = 0, b = 0, c = 0, d = 0;
  while (!flag) MPI_Improbe(1, 7, MPI_COMM_WORLD, &flag, &m1, &st);
  MPI_Recv(&b, 1, MPI_INT, 1, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Mprobe(1, 7, MPI_COMM_WORLD, &m3, &st);
  MPI_Request r;
  MPI_Imrecv(&c, 1, MPI_INT, &m3, &r);
  MPI_Wait(&r, &st);
  MPI_Mrecv(&a, 1, MPI_INT, &m1, MPI_STATUS_IGNORE);
  MCHECK(t, a == 1 && b == 2 && c == 3 && st.MPI_SOURCE == 1 && st.MPI_TAG == 7 && m1 == MPI_MESSAGE_NULL &&
                m3 == MPI_MESSAGE_NULL,
         "order around matched probes: %d %d %d", a, b, c);
  MPI_Status ps, ms;
  MPI_Probe(1, 8, MPI_COMM_WORLD, &ps);
  MPI_Mprobe(MPI_ANY_SOURCE, 8, MPI_COMM_WORLD, &m8, &ms);
  MPI_Mrecv(&d, 1, MPI_INT, &m8, MPI_STATUS_IGNORE);
  MCHECK(t, d == 8 && ps.MPI_SOURCE == 1 && ms.MPI_SOURCE == 1, "tag 8: %d", d);
}

/* A receive posted before the probe takes the first message it fits: the
 * matched probe takes the next. */
static void mprobe_posted(mtest *t) {
  if (t->rank == 1) {
    int v = 10, w = 20;
    MPI_Send(&v, 1, MPI_INT, 0, 9, MPI_COMM_WORLD);
    MPI_Send(&w, 1, MPI_INT, 0, 9, MPI_COMM_WORLD);
  }
  if (t->rank != 0) return;
  int v = 0, w = 0;
  MPI_Request r;
  MPI_Irecv(&v, 1, MPI_INT, 1, 9, MPI_COMM_WORLD, &r);
  MPI_Message m;
  MPI_Mprobe(1, 9, MPI_COMM_WORLD, &m, MPI_STATUS_IGNORE);
  MPI_Mrecv(&w, 1, MPI_INT, &m, MPI_STATUS_IGNORE);
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  MCHECK(t, v == 10 && w == 20, "a posted receive, then a matched probe: %d %d", v, w);
}

/* MPI_PROC_NULL: MPI_MESSAGE_NO_PROC, and an empty receive. */
static void mprobe_null(mtest *t) {
  MPI_Message m = MPI_MESSAGE_NULL;
  MPI_Status st;
  int flag = 0, count = -1, v = 42;
  MPI_Mprobe(MPI_PROC_NULL, 3, MPI_COMM_WORLD, &m, &st);
  MPI_Get_count(&st, MPI_INT, &count);
  MCHECK(t, m == MPI_MESSAGE_NO_PROC && st.MPI_SOURCE == MPI_PROC_NULL && st.MPI_TAG == MPI_ANY_TAG && count == 0,
         "Mprobe(MPI_PROC_NULL): source %d tag %d count %d", st.MPI_SOURCE, st.MPI_TAG, count);
  MPI_Mrecv(&v, 1, MPI_INT, &m, &st);
  MPI_Get_count(&st, MPI_INT, &count);
  MCHECK(t, m == MPI_MESSAGE_NULL && st.MPI_SOURCE == MPI_PROC_NULL && count == 0 && v == 42,
         "Mrecv(MPI_MESSAGE_NO_PROC): source %d count %d", st.MPI_SOURCE, count);
  MPI_Improbe(MPI_PROC_NULL, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &m, &st);
  MPI_Request r;
  MPI_Imrecv(&v, 1, MPI_INT, &m, &r);
  MPI_Wait(&r, &st);
  MCHECK(t, flag == 1 && st.MPI_SOURCE == MPI_PROC_NULL && r == MPI_REQUEST_NULL, "Improbe, Imrecv of MPI_PROC_NULL");
}

/* A message longer than the receive: MPI_ERR_TRUNCATE (MPI_ERRORS_RETURN),
 * the first elements stored; and a vector type: every other int. */
static void mprobe_truncate_vector(mtest *t) {
  if (t->rank == 1) {
    int v[6] = {1, 2, 3, 4, 5, 6};
    MPI_Send(v, 6, MPI_INT, 0, 11, MPI_COMM_WORLD);
    MPI_Send(v, 3, MPI_INT, 0, 12, MPI_COMM_WORLD);
  }
  if (t->rank != 0) return;
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  int v[6] = {0}, cls = -1;
  MPI_Message m;
  MPI_Status st;
  MPI_Mprobe(1, 11, MPI_COMM_WORLD, &m, MPI_STATUS_IGNORE);
  int rc = MPI_Mrecv(v, 4, MPI_INT, &m, &st);
  MPI_Error_class(rc, &cls);
  MCHECK(t, cls == MPI_ERR_TRUNCATE && v[0] == 1 && v[3] == 4 && v[4] == 0, "truncated Mrecv: class %d", cls);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_ARE_FATAL);
  MPI_Datatype vec;
  MPI_Type_vector(3, 1, 2, MPI_INT, &vec);
  MPI_Type_commit(&vec);
  int w[6] = {0, 0, 0, 0, 0, 0}, count = -1;
  MPI_Mprobe(1, 12, MPI_COMM_WORLD, &m, MPI_STATUS_IGNORE);
  MPI_Mrecv(w, 1, vec, &m, &st);
  MPI_Get_count(&st, MPI_INT, &count);
  MCHECK(t, w[0] == 1 && w[1] == 0 && w[2] == 2 && w[4] == 3 && count == 3, "Mrecv into a vector: %d %d %d", w[0],
         w[2], w[4]);
  MPI_Type_free(&vec);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {mprobe_any, mprobe_order, mprobe_posted, mprobe_null, mprobe_truncate_vector, NULL};
  return mtest_main(&argc, &argv, "p2p_mprobe", 1, MTEST_BARRIER, checks);
}
