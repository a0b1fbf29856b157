/* p2p_probe.c -- MPI_Probe and MPI_Iprobe, checked by themselves on any
 * number of ranks >= 2: a probe shows the message the same receive would
 * take and leaves it there (a receive by the probe's source and tag gets
 * exactly that one), its count sizes the buffer, a message that a posted
 * receive takes is not shown, MPI_PROC_NULL answers at once. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"
#include "probetest.h"

/* Every other rank sends rank 0 a message of rank * 3 ints, each int its
 * rank, with tag = rank; rank 0 probes from any source, sizes the buffer by
 * the count, receives by the status's source and tag, and finds exactly
 * the probed message.  On a communicator of their own: the later parts'
 * messages on MPI_COMM_WORLD are no match. */
static void probe_sizes_on(mtest *t, MPI_Comm comm);

static void probe_sizes(mtest *t) {
  MPI_Comm comm;
  MPI_Comm_dup(MPI_COMM_WORLD, &comm);
  probe_sizes_on(t, comm);
  MPI_Comm_free(&comm);
}

static void probe_sizes_on(mtest *t, MPI_Comm comm) {
  if (!probetest_send(t, comm)) return;
  int *seen = calloc((size_t)t->size, sizeof *seen);
  for (int k = 1; k < t->size; k++) {
    MPI_Status st, st2, st3;
    MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm, &st);
    /* Probing again by the source and tag shown shows the same message. */
    MPI_Probe(st.MPI_SOURCE, st.MPI_TAG, comm, &st2);
    int count = -1, s = st.MPI_SOURCE;
    MPI_Get_count(&st, MPI_INT, &count);
    MCHECK(t, st2.MPI_SOURCE == s && st2.MPI_TAG == st.MPI_TAG, "probe twice: %d then %d", s, st2.MPI_SOURCE);
    MCHECK(t, s > 0 && s < t->size && !seen[s] && st.MPI_TAG == s && count == 3 * s, "probe: from %d tag %d count %d",
           s, st.MPI_TAG, count);
    if (s <= 0 || s >= t->size || count < 0) continue;
    seen[s] = 1;
    int *v = malloc((size_t)(count + 1) * sizeof *v);
    MPI_Recv(v, count, MPI_INT, s, st.MPI_TAG, comm, &st3);
    int bad = 0;
    for (int i = 0; i < count; i++) bad += v[i] != s;
    MCHECK(t, bad == 0 && st3.MPI_SOURCE == s, "received after the probe: %d wrong", bad);
    free(v);
  }
  free(seen);
}

/* Iprobe until the message is there, then receive it from any source with
 * its tag: the probed one. */
static void probe_poll(mtest *t) {
  int last = t->size - 1;
  if (t->rank == last) {
    int v = 77;
    MPI_Send(&v, 1, MPI_INT, 0, 60, MPI_COMM_WORLD);
  }
  if (t->rank != 0) return;
  int flag = 0;
  MPI_Status st;
  while (!flag) MPI_Iprobe(MPI_ANY_SOURCE, 60, MPI_COMM_WORLD, &flag, &st);
  int v = 0;
  MPI_Status st2;
  MPI_Recv(&v, 1, MPI_INT, MPI_ANY_SOURCE, 60, MPI_COMM_WORLD, &st2);
  MCHECK(t, st.MPI_SOURCE == last && st2.MPI_SOURCE == last && v == 77, "iprobe then recv: %d %d %d",
         st.MPI_SOURCE, st2.MPI_SOURCE, v);
  /* Nothing is ever sent with tag 61. */
  MPI_Iprobe(MPI_ANY_SOURCE, 61, MPI_COMM_WORLD, &flag, &st);
  MCHECK(t, flag == 0, "iprobe of nothing: %d", flag);
}

/* A receive posted before the probe takes the message it fits: the probe
 * shows the next one. */
static void probe_posted(mtest *t) {
  if (t->rank == 0) {
    int v[2] = {5, 6};
    MPI_Send(&v[0], 1, MPI_INT, 1, 65, MPI_COMM_WORLD);
    MPI_Send(&v[1], 1, MPI_INT, 1, 66, MPI_COMM_WORLD);
  } else if (t->rank == 1) {
    int a = 0, b = 0;
    MPI_Request r;
    MPI_Status st;
    MPI_Irecv(&a, 1, MPI_INT, 0, 65, MPI_COMM_WORLD, &r);
    MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
    MCHECK(t, st.MPI_TAG == 66, "probe past a posted receive: tag %d (66 due)", st.MPI_TAG);
    MPI_Recv(&b, 1, MPI_INT, 0, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Wait(&r, MPI_STATUS_IGNORE);
    MCHECK(t, a == 5 && b == 6, "probe past a posted receive: %d %d", a, b);
  }
}

static void probe_null(mtest *t) {
  MPI_Status st;
  int flag = 0, count = -1;
  MPI_Probe(MPI_PROC_NULL, 3, MPI_COMM_WORLD, &st);
  MPI_Get_count(&st, MPI_INT, &count);
  MCHECK(t, st.MPI_SOURCE == MPI_PROC_NULL && st.MPI_TAG == MPI_ANY_TAG && count == 0, "probe of MPI_PROC_NULL");
  MPI_Iprobe(MPI_PROC_NULL, 3, MPI_COMM_WORLD, &flag, &st);
  MCHECK(t, flag == 1 && st.MPI_SOURCE == MPI_PROC_NULL, "iprobe of MPI_PROC_NULL");
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {probe_sizes, probe_poll, probe_posted, probe_null, NULL};
  return mtest_main(&argc, &argv, "p2p_probe", 2, 0, checks);
}
