/* comm_more.c -- the rest of the communicator calls, checked by themselves
 * on any number of ranks >= 2: MPI_Comm_split_type (the nodes partition
 * the ranks, each rank in its own node's communicator with the members
 * all agreeing on it; MPI_UNDEFINED gives MPI_COMM_NULL), MPI_Comm_idup,
 * MPI_Comm_get_parent (none), MPI_Comm_disconnect, MPI_Alloc_mem and
 * MPI_Free_mem, and the C and Fortran handles and statuses (MPI_Comm_c2f,
 * ...). */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

/* Open MPI's C header has no MPI_F_SOURCE and MPI_F_TAG (its mpif.h's
 * status puts them first too). */
#ifndef MPI_F_SOURCE
#define MPI_F_SOURCE 0
#define MPI_F_TAG 1
#endif

static void cm_split_type(mtest *t) {
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, t->rank, MPI_INFO_NULL, &node);
  int r = -1, n = -1;
  MPI_Comm_rank(node, &r);
  MPI_Comm_size(node, &n);
  /* The members' world ranks, in the node's order, by key = world rank. */
  int *w = malloc((size_t)n * sizeof *w), bad = 0;
  MPI_Allgather(&t->rank, 1, MPI_INT, w, 1, MPI_INT, node);
  for (int i = 0; i < n; i++) bad += w[i] < 0 || w[i] >= t->size || (i > 0 && w[i] <= w[i - 1]);
  bad += w[r] != t->rank;
  MCHECK(t, node != MPI_COMM_NULL && n >= 1 && n <= t->size && bad == 0, "a node of %d: rank %d", n, r);
  /* Each rank is in exactly one node: the nodes' sizes add up. */
  int mine = r == 0 ? n : 0, total = 0;
  MPI_Allreduce(&mine, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  MCHECK(t, total == t->size, "the nodes hold %d ranks of %d", total, t->size);
  free(w);
  MPI_Comm_free(&node);
  MPI_Comm_split_type(MPI_COMM_WORLD, t->rank % 2 ? MPI_UNDEFINED : MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  MCHECK(t, (t->rank % 2) == (node == MPI_COMM_NULL), "MPI_UNDEFINED");
  if (node != MPI_COMM_NULL) MPI_Comm_free(&node);
}

/* No rank was spawned. */
static void cm_parent(mtest *t) {
  MPI_Comm parent = MPI_COMM_WORLD;
  MPI_Comm_get_parent(&parent);
  MCHECK(t, parent == MPI_COMM_NULL, "MPI_Comm_get_parent gave a communicator");
}

static void cm_idup(mtest *t) {
  MPI_Comm c[3];
  MPI_Request req[3];
  for (int i = 0; i < 3; i++) MPI_Comm_idup(MPI_COMM_WORLD, &c[i], &req[i]);
  MPI_Waitall(3, req, MPI_STATUSES_IGNORE);
  int bad = 0;
  for (int i = 0; i < 3; i++) {
    int sum = -1, size = -1;
    MPI_Comm_size(c[i], &size);
    MPI_Allreduce(&t->rank, &sum, 1, MPI_INT, MPI_SUM, c[i]);
    bad += size != t->size || sum != t->size * (t->size - 1) / 2;
    bad += req[i] != MPI_REQUEST_NULL;
  }
  MCHECK(t, bad == 0, "MPI_Comm_idup: %d wrong", bad);
  /* Their messages stay apart: rank 0 sends rank 1 on c[2], then c[0]. */
  if (t->rank == 0) {
    int a = 0, b = 2;
    MPI_Send(&b, 1, MPI_INT, 1, 0, c[2]);
    MPI_Send(&a, 1, MPI_INT, 1, 0, c[0]);
  } else if (t->rank == 1) {
    int a = -1, b = -1;
    MPI_Recv(&a, 1, MPI_INT, MPI_ANY_SOURCE, MPI_ANY_TAG, c[0], MPI_STATUS_IGNORE);
    MPI_Recv(&b, 1, MPI_INT, MPI_ANY_SOURCE, MPI_ANY_TAG, c[2], MPI_STATUS_IGNORE);
    MCHECK(t, a == 0 && b == 2, "idup'ed communicators apart: %d %d", a, b);
  }
  for (int i = 0; i < 3; i++) MPI_Comm_free(&c[i]);
}

static void cm_disconnect(mtest *t) {
  MPI_Comm c;
  MPI_Comm_dup(MPI_COMM_WORLD, &c);
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size, got = -1;
  MPI_Request r;
  MPI_Isend(&t->rank, 1, MPI_INT, right, 0, c, &r);
  MPI_Recv(&got, 1, MPI_INT, left, 0, c, MPI_STATUS_IGNORE);
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  int rc = MPI_Comm_disconnect(&c);
  MCHECK(t, rc == MPI_SUCCESS && c == MPI_COMM_NULL && got == left, "MPI_Comm_disconnect: %d", rc);
}

static void cm_alloc_mem(mtest *t) {
  double *p = NULL;
  int rc = MPI_Alloc_mem(1000 * sizeof *p, MPI_INFO_NULL, &p);
  MCHECK(t, rc == MPI_SUCCESS && p != NULL, "MPI_Alloc_mem: %d", rc);
  for (int i = 0; i < 1000; i++) p[i] = i * 0.5;
  /* Memory from MPI_Alloc_mem carries messages as any other. */
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size;
  MPI_Sendrecv_replace(p, 1000, MPI_DOUBLE, right, 0, left, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  int bad = 0;
  for (int i = 0; i < 1000; i++) bad += p[i] != i * 0.5;
  MCHECK(t, bad == 0, "%d values wrong in MPI_Alloc_mem's memory", bad);
  rc = MPI_Free_mem(p);
  MCHECK(t, rc == MPI_SUCCESS, "MPI_Free_mem: %d", rc);
  MPI_Info info;
  MPI_Info_create(&info);
  void *q = NULL;
  rc = MPI_Alloc_mem(0, info, &q);
  MCHECK(t, rc == MPI_SUCCESS, "MPI_Alloc_mem of 0 bytes: %d", rc);
  MPI_Free_mem(q);
  MPI_Info_free(&info);
}

/* Handles through Fortran's and back, and a status. */
static void cm_c2f(mtest *t) {
  MPI_Group g;
  MPI_Info info;
  MPI_Comm_group(MPI_COMM_WORLD, &g);
  MPI_Info_create(&info);
  int bad = 0;
  bad += MPI_Comm_f2c(MPI_Comm_c2f(MPI_COMM_WORLD)) != MPI_COMM_WORLD;
  bad += MPI_Comm_f2c(MPI_Comm_c2f(MPI_COMM_NULL)) != MPI_COMM_NULL;
  bad += MPI_Group_f2c(MPI_Group_c2f(g)) != g;
  bad += MPI_Type_f2c(MPI_Type_c2f(MPI_DOUBLE)) != MPI_DOUBLE;
  bad += MPI_Op_f2c(MPI_Op_c2f(MPI_SUM)) != MPI_SUM;
  bad += MPI_Info_f2c(MPI_Info_c2f(info)) != info;
  bad += MPI_Errhandler_f2c(MPI_Errhandler_c2f(MPI_ERRORS_RETURN)) != MPI_ERRORS_RETURN;
  bad += MPI_Request_f2c(MPI_Request_c2f(MPI_REQUEST_NULL)) != MPI_REQUEST_NULL;
  bad += MPI_Win_f2c(MPI_Win_c2f(MPI_WIN_NULL)) != MPI_WIN_NULL;
  bad += MPI_File_f2c(MPI_File_c2f(MPI_FILE_NULL)) != MPI_FILE_NULL;
  bad += MPI_Message_f2c(MPI_Message_c2f(MPI_MESSAGE_NULL)) != MPI_MESSAGE_NULL;
  MCHECK(t, bad == 0, "%d handles changed on their way", bad);
  /* A live request too. */
  MPI_Request r;
  int v = t->rank, got = -1;
  MPI_Irecv(&got, 1, MPI_INT, MPI_ANY_SOURCE, 6, MPI_COMM_SELF, &r);
  MPI_Fint fr = MPI_Request_c2f(r);
  MPI_Send(&v, 1, MPI_INT, 0, 6, MPI_COMM_SELF);
  MPI_Request back = MPI_Request_f2c(fr);
  MPI_Status st, st2;
  MPI_Wait(&back, &st);
  MPI_Fint fst[16];   /* MPI_F_STATUS_SIZE is 6 here, Open MPI's mpif.h's MPI_STATUS_SIZE 6 */
  MPI_Status_c2f(&st, fst);
  MPI_Status_f2c(fst, &st2);
  int count = -1;
  MPI_Get_count(&st2, MPI_INT, &count);
  MCHECK(t, got == t->rank && st2.MPI_SOURCE == 0 && st2.MPI_TAG == 6 && count == 1 && fst[MPI_F_SOURCE] == 0 &&
                fst[MPI_F_TAG] == 6,
         "a request and a status through Fortran: %d from %d tag %d count %d", got, st2.MPI_SOURCE, st2.MPI_TAG,
         count);
  MPI_Group_free(&g);
  MPI_Info_free(&info);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {cm_split_type, cm_parent, cm_idup, cm_disconnect, cm_alloc_mem, cm_c2f, NULL};
  return mtest_main(&argc, &argv, "comm_more", 2, 0, checks);
}
