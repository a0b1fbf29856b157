/* p2p_grequest.c -- generalized requests (MPI_Grequest_start,
 * MPI_Grequest_complete) and the status setters (MPI_Status_set_elements,
 * MPI_Status_set_elements_x, MPI_Status_set_cancelled), checked by
 * themselves on any number of ranks: a request is active until
 * MPI_Grequest_complete; the Wait or Test that completes it takes its
 * status from query_fn, then calls free_fn, once each, in that order;
 * MPI_Request_get_status asks query_fn and leaves the request; a request
 * freed before it is complete is freed (free_fn) when it completes;
 * MPI_Cancel calls cancel_fn with whether it is complete; such requests
 * mix with point-to-point ones in MPI_Waitall, MPI_Waitany, MPI_Testsome;
 * query_fn's error is MPI_Wait's. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

typedef struct {
  int queries, frees, cancels, cancelled_complete;
  int order_ok;   /* free_fn came after a query_fn (or with none) */
  int count;      /* elements of MPI_INT query_fn reports */
  int cancel;     /* query_fn reports it cancelled */
  int fail;       /* query_fn returns this error */
} gstate;

static int query_fn(void *extra, MPI_Status *st) {
  gstate *g = extra;
  g->queries++;
  st->MPI_SOURCE = 3;
  st->MPI_TAG = 44;
  MPI_Status_set_elements(st, MPI_INT, g->count);
  MPI_Status_set_cancelled(st, g->cancel);
  return g->fail;
}

static int free_fn(void *extra) {
  gstate *g = extra;
  g->frees++;
  g->order_ok = g->order_ok && (g->queries > 0 || g->cancels >= 0);
  return MPI_SUCCESS;
}

static int cancel_fn(void *extra, int complete) {
  gstate *g = extra;
  g->cancels++;
  g->cancelled_complete = complete;
  return MPI_SUCCESS;
}

static MPI_Request start(gstate *g, int count) {
  memset(g, 0, sizeof *g);
  g->order_ok = 1;
  g->count = count;
  MPI_Request r;
  MPI_Grequest_start(query_fn, free_fn, cancel_fn, g, &r);
  return r;
}

/* Test before and after MPI_Grequest_complete; the status and counts. */
static void grequest_basic(mtest *t) {
  gstate g;
  MPI_Request r = start(&g, 5);
  MPI_Status st;
  int flag = -1, count = -1, bytes = -1, cancelled = -1;
  MPI_Test(&r, &flag, &st);
  MCHECK(t, flag == 0 && r != MPI_REQUEST_NULL && g.queries == 0 && g.frees == 0, "an incomplete request tested");
  MPI_Grequest_complete(r);
  MPI_Test(&r, &flag, &st);
  MPI_Get_count(&st, MPI_INT, &count);
  MPI_Get_count(&st, MPI_BYTE, &bytes);
  MPI_Test_cancelled(&st, &cancelled);
  MCHECK(t, flag == 1 && r == MPI_REQUEST_NULL && st.MPI_SOURCE == 3 && st.MPI_TAG == 44 && count == 5 &&
                bytes == 5 * (int)sizeof(int) && cancelled == 0,
         "a completed request: flag %d source %d tag %d count %d", flag, st.MPI_SOURCE, st.MPI_TAG, count);
  MCHECK(t, g.queries == 1 && g.frees == 1 && g.order_ok, "query_fn %d times, free_fn %d times", g.queries, g.frees);
  MPI_Status s2;
  MPI_Status_set_elements_x(&s2, MPI_DOUBLE, (MPI_Count)4);
  MPI_Get_count(&s2, MPI_DOUBLE, &count);
  MCHECK(t, count == 4, "MPI_Status_set_elements_x: count %d", count);
}

/* MPI_Request_get_status leaves the request; MPI_Wait completes it. */
static void grequest_get_status(mtest *t) {
  gstate g;
  MPI_Request r = start(&g, 2);
  MPI_Status st;
  int flag = -1;
  MPI_Request_get_status(r, &flag, &st);
  int before = flag;
  MPI_Grequest_complete(r);
  MPI_Request_get_status(r, &flag, &st);
  int count = -1;
  MPI_Get_count(&st, MPI_INT, &count);
  MCHECK(t, before == 0 && flag == 1 && count == 2 && r != MPI_REQUEST_NULL && g.frees == 0,
         "Request_get_status: %d then %d, count %d, frees %d", before, flag, count, g.frees);
  MPI_Wait(&r, &st);
  MCHECK(t, r == MPI_REQUEST_NULL && g.queries == 2 && g.frees == 1, "Wait after get_status: queries %d, frees %d",
         g.queries, g.frees);
}

/* Freed before it completes: free_fn when it completes, not before, and no
 * query_fn. */
static void grequest_freed(mtest *t) {
  gstate g;
  MPI_Request r = start(&g, 0), keep = r;
  MPI_Request_free(&r);
  int early = g.frees;
  MPI_Grequest_complete(keep);
  MCHECK(t, r == MPI_REQUEST_NULL && early == 0 && g.frees == 1 && g.queries == 0,
         "freed early: frees %d then %d, queries %d", early, g.frees, g.queries);
}

/* MPI_Cancel calls cancel_fn (complete = 0, then 1); query_fn reports it
 * cancelled. */
static void grequest_cancel(mtest *t) {
  gstate g;
  MPI_Request r = start(&g, 0);
  MPI_Cancel(&r);
  int first = g.cancelled_complete;
  g.cancel = 1;
  MPI_Grequest_complete(r);
  MPI_Cancel(&r);
  MPI_Status st;
  int cancelled = -1;
  MPI_Wait(&r, &st);
  MPI_Test_cancelled(&st, &cancelled);
  MCHECK(t, g.cancels == 2 && first == 0 && g.cancelled_complete == 1 && cancelled == 1,
         "cancel_fn %d times (complete %d, then %d), cancelled %d", g.cancels, first, g.cancelled_complete, cancelled);
}

/* Mixed with point-to-point requests: a ring exchange and two generalized
 * requests in one MPI_Waitall; MPI_Waitany and MPI_Testsome find the one
 * completed. */
static void grequest_mixed(mtest *t) {
  gstate g1, g2;
  MPI_Request r[4];
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size, v = t->rank, w = -1;
  r[0] = start(&g1, 1);
  MPI_Irecv(&w, 1, MPI_INT, left, 60, MPI_COMM_WORLD, &r[1]);
  MPI_Isend(&v, 1, MPI_INT, right, 60, MPI_COMM_WORLD, &r[2]);
  r[3] = start(&g2, 7);
  MPI_Grequest_complete(r[3]);
  int idx = -1, outcount = -1, indices[4];
  MPI_Status st, sts[4];
  MPI_Testsome(1, &r[3], &outcount, indices, sts);
  int count = -1;
  MPI_Get_count(&sts[0], MPI_INT, &count);
  MCHECK(t, outcount == 1 && indices[0] == 0 && r[3] == MPI_REQUEST_NULL && count == 7 && g2.frees == 1,
         "Testsome: %d done, count %d", outcount, count);
  MPI_Grequest_complete(r[0]);
  MPI_Waitany(1, &r[0], &idx, &st);
  MCHECK(t, idx == 0 && r[0] == MPI_REQUEST_NULL && g1.queries == 1 && g1.frees == 1, "Waitany: index %d", idx);
  r[0] = start(&g1, 3);
  MPI_Grequest_complete(r[0]);
  MPI_Waitall(4, r, sts);
  MPI_Get_count(&sts[0], MPI_INT, &count);
  MCHECK(t, w == left && count == 3 && sts[1].MPI_SOURCE == left && g1.frees == 1 && r[0] == MPI_REQUEST_NULL &&
                r[1] == MPI_REQUEST_NULL,
         "Waitall of generalized and point-to-point requests: value %d, count %d", w, count);
}

/* query_fn's error is MPI_Wait's (MPI_ERRORS_RETURN). */
static void grequest_error(mtest *t) {
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  gstate g;
  MPI_Request r = start(&g, 0);
  g.fail = MPI_ERR_OTHER;
  MPI_Grequest_complete(r);
  int rc = MPI_Wait(&r, MPI_STATUS_IGNORE), cls = -1;
  MPI_Error_class(rc, &cls);
  MCHECK(t, cls == MPI_ERR_OTHER && g.frees == 1, "query_fn's error: class %d", cls);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_ARE_FATAL);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {grequest_basic, grequest_get_status, grequest_freed, grequest_cancel, grequest_mixed, grequest_error, NULL};
  return mtest_main(&argc, &argv, "p2p_grequest", 1, MTEST_BARRIER, checks);
}
