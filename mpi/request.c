/* request.c -- completing requests: the Wait and Test families,
 * MPI_Request_free, MPI_Request_get_status, starting persistent requests
 * (MPI_Start, MPI_Startall), and requests of a kind of their own (core.h:
 * req_start, req_complete).
 *
 * A request is active from its start until it is done (a send: at once,
 * or when its ack comes; a receive: when a message is matched to it); a
 * call that completes it copies its status out and frees it, or leaves a
 * persistent one inactive for its next MPI_Start.  Waiting runs the
 * matching engine until the request is done (eng_wait, eng_step); testing
 * first acts on every message that has arrived (eng_poll), and a test that
 * finds nothing done charges the per-run poll cost (init.h) and counts
 * toward a rank that polls forever (spin.h).  A request of a kind of its
 * own advances by its kind's progress after the engine has acted on the
 * messages, its status comes from its kind when it completes, and its
 * kind's free ends it. */
#include <stdio.h>

#include "mpi/engine.h"
#include "mpi/init.h"
#include "mpi/err.h"
#include "mpi/label.h"
#include "mpi/pt2pt.h"
#include "mpi/spin.h"

/* ==== one request ========================================================= */

/* The request *h names: *q (NULL for MPI_REQUEST_NULL); MPI_SUCCESS, or
 * MPI_ERR_REQUEST raised. */
static int lookup(st_rank *R, const char *fn, MPI_Request h, st_req **q) {
  *q = NULL;
  if (h == MPI_REQUEST_NULL) return MPI_SUCCESS;
  *q = st_req_get(R, h);
  if (*q) return MPI_SUCCESS;
  return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "invalid request handle 0x%x (%s)", (unsigned)h,
                   H_KIND(h) == HK_REQ ? "freed, or not this rank's" : "not a request");
}

/* Lookups of n handles (after the array is checked). */
static int lookup_all(st_rank *R, const char *fn, int n, const MPI_Request *reqs) {
  if (n < 0) return err_raise(R, NULL, MPI_ERR_COUNT, fn, "invalid count %d (must be >= 0)", n);
  if (n > 0 && !reqs) return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "NULL array of requests");
  for (int i = 0; i < n; i++) {
    st_req *q;
    int rc = lookup(R, fn, reqs[i], &q);
    if (rc) return rc;
  }
  return MPI_SUCCESS;
}

/* Whether the request needs completing: 0 for MPI_REQUEST_NULL and an
 * inactive persistent request (their status is the empty one). */
static int live(const st_req *q) { return q && q->state != RS_INACTIVE; }

/* q (done) completes: its status out, its end; *h nulled unless it is
 * persistent.  Returns its error class, raised on its communicator for
 * call fn when raise is set (the single-status calls). */
static int finish(st_rank *R, const char *fn, MPI_Request *h, st_req *q, MPI_Status *st, int with_error,
                  int raise) {
  eng_send_done(R, q);
  if (q->kind == RQ_KIND) {   /* its kind's status, then its end */
    MPI_Status ks;
    pt2pt_status_empty(&ks);
    int err = q->ops->status ? q->ops->status(q->ext, &ks) : MPI_SUCCESS;
    ks.MPI_ERROR = err;
    pt2pt_status_out(st, &ks, with_error);
    const char *made = q->fn;
    int e2 = st_req_free(R, q);
    *h = MPI_REQUEST_NULL;
    if (!err) err = e2;
    if (err && raise)
      return err_raise(R, NULL, err, fn, "the request of %s failed (error %d from its callbacks)", made, err);
    return err;
  }
  pt2pt_status_out(st, &q->st, with_error);
  int err = q->st.MPI_ERROR;
  if (q->persistent) eng_settle(R, q);
  if (err && raise && q->kind != RQ_COLL) {   /* a collective's error was raised when it happened */
    st_req copy = *q;
    if (q->persistent)
      q->state = RS_INACTIVE;
    else
      st_req_free(R, q), *h = MPI_REQUEST_NULL;
    return pt2pt_req_error(R, st_comm_get(R, copy.comm), &copy, fn);
  }
  if (q->persistent) {
    q->state = RS_INACTIVE;
  } else {
    st_req_free(R, q);
    *h = MPI_REQUEST_NULL;
  }
  return err;
}

/* Every active request of a kind of its own among n handles advances. */
static void advance_all(st_rank *R, int n, const MPI_Request *reqs) {
  for (int i = 0; i < n; i++) {
    st_req *q = st_req_get(R, reqs[i]);
    if (q && q->kind == RQ_KIND) eng_advance(R, q);
  }
}

static void empty_out(MPI_Status *st, int with_error) {
  MPI_Status e;
  pt2pt_status_empty(&e);
  pt2pt_status_out(st, &e, with_error);
}

/* A test of fn that found nothing done. */
static void poll_charge(st_rank *R, const char *fn) {
  double cost = init_poll_cost();
  if (cost > 0 && mp_busy(R->self, cost) != MP_OK) st_stopped(R);
  spin_count(R, fn);
}

/* Several statuses: the first request that failed, raised as
 * MPI_ERR_IN_STATUS on its communicator. */
static int in_status(st_rank *R, const char *fn, const st_req *failed, int err) {
  if (failed->kind == RQ_KIND || failed->kind == RQ_COLL)
    return err_raise(R, NULL, MPI_ERR_IN_STATUS, fn, "the request of %s failed (error %d in its status)",
                     failed->fn, err);
  return err_raise(R, st_comm_get(R, failed->comm), MPI_ERR_IN_STATUS, fn,
                   "%s (from rank %d, tag %d): a %zu-byte message is longer than the receive buffer "
                   "(%d elements, %zu bytes): truncated (MPI_ERR_TRUNCATE in its status)",
                   failed->fn, failed->st.MPI_SOURCE, failed->st.MPI_TAG, failed->msglen, failed->count,
                   failed->cap);
}

/* Waitall's and Testall's end: every request (all done) completes; the
 * first that failed raised as MPI_ERR_IN_STATUS. */
static int finish_all(st_rank *R, const char *fn, int count, MPI_Request reqs[], MPI_Status sts[]) {
  st_req failed = {.slot = -1};
  int nfailed = 0, ferr = 0;
  for (int i = 0; i < count; i++) {
    MPI_Status *st = sts == MPI_STATUSES_IGNORE ? MPI_STATUS_IGNORE : &sts[i];
    st_req *q = st_req_get(R, reqs[i]);
    if (!live(q)) {
      empty_out(st, 1);
      continue;
    }
    st_req copy = *q;
    int e = finish(R, fn, &reqs[i], q, st, 1, 0);
    if (e && !nfailed++) failed = copy, ferr = e;
  }
  return nfailed ? in_status(R, fn, &failed, ferr) : MPI_SUCCESS;
}

/* ==== the Wait family ===================================================== */

int PMPI_Wait(MPI_Request *request, MPI_Status *status) {
  static const char fn[] = "MPI_Wait";
  st_rank *R = st_need(fn);
  if (!request) return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "NULL request argument");
  st_req *q;
  int rc = lookup(R, fn, *request, &q);
  if (rc) return rc;
  if (!live(q)) {
    empty_out(status, 0);
    return MPI_SUCCESS;
  }
  if (q->state == RS_ACTIVE) {
    label_rec l = {.fn = fn, .what = L_REQS, .R = R, .reqs = request, .n = 1};
    label_set(R, &l);
    eng_wait(R, q);
    label_clear(R);
  }
  return finish(R, fn, request, q, status, 0, 1);
}

int PMPI_Waitall(int count, MPI_Request array_of_requests[], MPI_Status array_of_statuses[]) {
  static const char fn[] = "MPI_Waitall";
  st_rank *R = st_need(fn);
  int rc = lookup_all(R, fn, count, array_of_requests);
  if (rc) return rc;
  label_rec l = {.fn = fn, .what = L_REQS, .R = R, .reqs = array_of_requests, .n = count};
  int labelled = 0;
  for (int i = 0; i < count; i++) {
    st_req *q = st_req_get(R, array_of_requests[i]);
    if (!q || q->state != RS_ACTIVE) continue;
    if (!labelled++) label_set(R, &l);
    eng_wait(R, q);
  }
  if (labelled) label_clear(R);
  return finish_all(R, fn, count, array_of_requests, array_of_statuses);
}

int PMPI_Waitany(int count, MPI_Request array_of_requests[], int *index, MPI_Status *status) {
  static const char fn[] = "MPI_Waitany";
  st_rank *R = st_need(fn);
  int rc = lookup_all(R, fn, count, array_of_requests);
  if (rc) return rc;
  if (!index) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL index argument");
  label_rec l = {.fn = fn, .what = L_REQS, .R = R, .reqs = array_of_requests, .n = count};
  int labelled = 0;
  for (;;) {
    int any = 0;
    advance_all(R, count, array_of_requests);
    for (int i = 0; i < count; i++) {
      st_req *q = st_req_get(R, array_of_requests[i]);
      if (!live(q)) continue;
      any = 1;
      if (q->state != RS_DONE) continue;
      if (labelled) label_clear(R);
      *index = i;
      return finish(R, fn, &array_of_requests[i], q, status, 0, 1);
    }
    if (!any) {   /* nothing to wait for */
      if (labelled) label_clear(R);
      *index = MPI_UNDEFINED;
      empty_out(status, 0);
      return MPI_SUCCESS;
    }
    if (!labelled++) label_set(R, &l);
    eng_step(R);
  }
}

/* Waitsome and Testsome: every done request completes (block: until one
 * is done). */
static int some(const char *fn, int block, int incount, MPI_Request reqs[], int *outcount,
                int indices[], MPI_Status sts[]) {
  st_rank *R = st_need(fn);
  int rc = lookup_all(R, fn, incount, reqs);
  if (rc) return rc;
  if (!outcount || (incount > 0 && !indices))
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL outcount or indices argument");
  label_rec l = {.fn = fn, .what = L_REQS, .R = R, .reqs = reqs, .n = incount};
  int labelled = 0, polled = 0;
  for (;;) {
    int any = 0, done = 0;
    advance_all(R, incount, reqs);
    for (int i = 0; i < incount; i++) {
      st_req *q = st_req_get(R, reqs[i]);
      if (!live(q)) continue;
      any = 1;
      done += q->state == RS_DONE;
    }
    if (!any) {
      if (labelled) label_clear(R);
      *outcount = MPI_UNDEFINED;
      return MPI_SUCCESS;
    }
    if (done || (!block && polled)) break;
    if (!block) {
      eng_poll(R);
      polled = 1;
      continue;   /* (advance_all at the top) */
    }
    if (!labelled++) label_set(R, &l);
    eng_step(R);
  }
  if (labelled) label_clear(R);
  int n = 0, nfailed = 0, ferr = 0;
  st_req failed = {.slot = -1};
  for (int i = 0; i < incount; i++) {
    st_req *q = st_req_get(R, reqs[i]);
    if (!live(q) || q->state != RS_DONE) continue;
    st_req copy = *q;
    int e = finish(R, fn, &reqs[i], q, sts == MPI_STATUSES_IGNORE ? MPI_STATUS_IGNORE : &sts[n], 1, 0);
    if (e && !nfailed++) failed = copy, ferr = e;
    indices[n++] = i;
  }
  *outcount = n;
  if (n == 0)
    poll_charge(R, fn);
  else
    spin_reset(R);
  return nfailed ? in_status(R, fn, &failed, ferr) : MPI_SUCCESS;
}

int PMPI_Waitsome(int incount, MPI_Request array_of_requests[], int *outcount,
                 int array_of_indices[], MPI_Status array_of_statuses[]) {
  return some("MPI_Waitsome", 1, incount, array_of_requests, outcount, array_of_indices,
              array_of_statuses);
}

/* ==== the Test family ===================================================== */

/* What MPI_Test and MPI_Request_get_status see of request h: a null or
 * inactive one is complete (*flag 1, the empty status, MPI_ERROR
 * (MPI_SUCCESS) too, as MPI 3.1 3.7.3 defines it) and *q NULL; a live one
 * in *q, moved on by the engine.  Returns the error raised for a bad h. */
static int look(st_rank *R, const char *fn, MPI_Request h, int *flag, MPI_Status *status, st_req **q) {
  int rc = lookup(R, fn, h, q);
  if (rc) return rc;
  if (!live(*q)) {
    *flag = 1;
    empty_out(status, 1);
    *q = NULL;
    return MPI_SUCCESS;
  }
  if ((*q)->state == RS_ACTIVE) {
    eng_poll(R);
    eng_advance(R, *q);
  }
  return MPI_SUCCESS;
}

int PMPI_Test(MPI_Request *request, int *flag, MPI_Status *status) {
  static const char fn[] = "MPI_Test";
  st_rank *R = st_need(fn);
  if (!request || !flag) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL request or flag argument");
  st_req *q;
  int rc = look(R, fn, *request, flag, status, &q);
  if (rc || !q) return rc;
  if (q->state != RS_DONE) {
    *flag = 0;
    poll_charge(R, fn);
    return MPI_SUCCESS;
  }
  *flag = 1;
  spin_reset(R);
  return finish(R, fn, request, q, status, 0, 1);
}

int PMPI_Testall(int count, MPI_Request array_of_requests[], int *flag, MPI_Status array_of_statuses[]) {
  static const char fn[] = "MPI_Testall";
  st_rank *R = st_need(fn);
  int rc = lookup_all(R, fn, count, array_of_requests);
  if (rc) return rc;
  if (!flag) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL flag argument");
  int pending = 0;
  for (int pass = 0; pass < 2; pass++) {
    pending = 0;
    for (int i = 0; i < count; i++) {
      st_req *q = st_req_get(R, array_of_requests[i]);
      pending += live(q) && q->state == RS_ACTIVE;
    }
    if (!pending || pass) break;
    eng_poll(R);
    advance_all(R, count, array_of_requests);
  }
  if (pending) {   /* nothing changes: MPI 3.1 section 3.7.5 */
    *flag = 0;
    poll_charge(R, fn);
    return MPI_SUCCESS;
  }
  *flag = 1;
  spin_reset(R);
  return finish_all(R, fn, count, array_of_requests, array_of_statuses);
}

int PMPI_Testany(int count, MPI_Request array_of_requests[], int *index, int *flag, MPI_Status *status) {
  static const char fn[] = "MPI_Testany";
  st_rank *R = st_need(fn);
  int rc = lookup_all(R, fn, count, array_of_requests);
  if (rc) return rc;
  if (!index || !flag) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL index or flag argument");
  for (int pass = 0; pass < 2; pass++) {
    int any = 0;
    for (int i = 0; i < count; i++) {
      st_req *q = st_req_get(R, array_of_requests[i]);
      if (!live(q)) continue;
      any = 1;
      if (q->state != RS_DONE) continue;
      *flag = 1;
      *index = i;
      spin_reset(R);
      return finish(R, fn, &array_of_requests[i], q, status, 0, 1);
    }
    if (!any) {   /* nothing active: flag true, no index (MPI 3.1 section 3.7.5) */
      *flag = 1;
      *index = MPI_UNDEFINED;
      empty_out(status, 0);
      return MPI_SUCCESS;
    }
    if (pass == 0) {
      eng_poll(R);
      advance_all(R, count, array_of_requests);
    }
  }
  *flag = 0;
  *index = MPI_UNDEFINED;
  poll_charge(R, fn);
  return MPI_SUCCESS;
}

int PMPI_Testsome(int incount, MPI_Request array_of_requests[], int *outcount, int array_of_indices[],
                 MPI_Status array_of_statuses[]) {
  return some("MPI_Testsome", 0, incount, array_of_requests, outcount, array_of_indices,
              array_of_statuses);
}

int PMPI_Request_get_status(MPI_Request request, int *flag, MPI_Status *status) {
  static const char fn[] = "MPI_Request_get_status";
  st_rank *R = st_need(fn);
  if (!flag) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL flag argument");
  st_req *q;
  int rc = look(R, fn, request, flag, status, &q);
  if (rc || !q) return rc;
  *flag = q->state == RS_DONE;
  if (!*flag) {
    poll_charge(R, fn);
    return MPI_SUCCESS;
  }
  spin_reset(R);
  if (q->kind != RQ_KIND) {
    pt2pt_status_out(status, &q->st, 0);
    return MPI_SUCCESS;
  }
  MPI_Status ks;   /* its kind's status; the request stays */
  pt2pt_status_empty(&ks);
  int err = q->ops->status ? q->ops->status(q->ext, &ks) : MPI_SUCCESS;
  pt2pt_status_out(status, &ks, 0);
  return err ? err_raise(R, NULL, err, fn, "the request of %s failed (error %d from its callbacks)", q->fn, err)
             : MPI_SUCCESS;
}

/* ==== freeing and starting ================================================ */

int PMPI_Request_free(MPI_Request *request) {
  static const char fn[] = "MPI_Request_free";
  st_rank *R = st_need(fn);
  if (!request || *request == MPI_REQUEST_NULL)
    return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "MPI_REQUEST_NULL");
  st_req *q;
  int rc = lookup(R, fn, *request, &q);
  if (rc) return rc;
  *request = MPI_REQUEST_NULL;
  if (q->state == RS_ACTIVE) {
    q->freed = 1;   /* it goes on, and goes when it is done (engine.c) */
    return MPI_SUCCESS;
  }
  const char *made = q->fn;
  int err = st_req_free(R, q);
  return err ? err_raise(R, NULL, err, fn, "the request of %s failed (error %d from its free callback)", made, err)
             : MPI_SUCCESS;
}

static int start(st_rank *R, const char *fn, MPI_Request h) {
  st_req *q;
  int rc = lookup(R, fn, h, &q);
  if (rc) return rc;
  if (!q) return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "MPI_REQUEST_NULL");
  if (!q->persistent || q->state != RS_INACTIVE)
    return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "request 0x%x is %s", (unsigned)h,
                     q->persistent ? "active already" : "not persistent (made by MPI_Send_init, MPI_Recv_init, ...)");
  st_comm *c = st_comm_get(R, q->comm);
  if (!c) {
    char b[64];
    return err_raise(R, NULL, MPI_ERR_COMM, fn, "the request's communicator is gone: %s",
                     err_comm_words(q->comm, b));
  }
  if (q->kind == RQ_SEND) return pt2pt_send_start(R, q, c);
  q->g = c->g;
  pt2pt_recv_start(R, q);
  return MPI_SUCCESS;
}

int PMPI_Start(MPI_Request *request) {
  static const char fn[] = "MPI_Start";
  st_rank *R = st_need(fn);
  if (!request) return err_raise(R, NULL, MPI_ERR_REQUEST, fn, "NULL request argument");
  return start(R, fn, *request);
}

int PMPI_Startall(int count, MPI_Request array_of_requests[]) {
  static const char fn[] = "MPI_Startall";
  st_rank *R = st_need(fn);
  int rc = lookup_all(R, fn, count, array_of_requests);
  if (rc) return rc;
  for (int i = 0; i < count; i++)
    if ((rc = start(R, fn, array_of_requests[i]))) return rc;
  return MPI_SUCCESS;
}

/* ==== requests of a kind of their own (core.h) ============================= */

int req_start(const req_kind *kind, void *state, MPI_Request *req) {
  st_rank *R = st_need(kind->name);
  st_req *q = st_req_new(R);
  q->kind = RQ_KIND;
  q->ops = kind;
  q->ext = state;
  q->fn = kind->name;
  q->comm = MPI_COMM_NULL;
  q->peer = MPI_PROC_NULL;
  q->state = RS_ACTIVE;
  pt2pt_status_empty(&q->st);
  R->nkinds++;
  *req = st_req_handle(q);
  return MPI_SUCCESS;
}

int req_complete(MPI_Request req) {
  st_rank *R = st_need("req_complete");
  st_req *q = st_req_get(R, req);
  if (!q || q->kind != RQ_KIND || q->state != RS_ACTIVE) return MPI_ERR_REQUEST;
  q->state = RS_DONE;
  return q->freed ? st_req_free(R, q) : MPI_SUCCESS;
}
