/* win_sync.c -- the three synchronisations of one-sided communication (MPI
 * 3.1 section 11.5): MPI_Win_fence; MPI_Win_post, _start, _complete,
 * _wait and _test; MPI_Win_lock, _unlock, _lock_all, _unlock_all, the
 * flushes and MPI_Win_sync.  The work is rma.c's; here are the epochs'
 * rules, the arguments' checks and what a blocked rank waits in.
 *
 *   fence       the rank's operations complete (every reply back), then a
 *               barrier of the window's ranks (MPI_Barrier's algorithm on
 *               the window's communicator)
 *   post        a 0-byte message to each origin of the group
 *   start       nothing (operations to a target wait for its post)
 *   complete    every post received, a done to each target sent after its
 *               operations, the operations complete locally
 *   wait        every origin's done received
 *   lock        a request to the target and its grant back (2 transfers);
 *               queued at the target behind a conflicting holder
 *   unlock      a release to the target (after the operations on the
 *               channel) and its acknowledgement; every operation's reply
 *   flush       every operation's reply back; flush_local only those that
 *               bring data (a put's or an accumulate's data were copied
 *               when it was issued) */
#include "mpi/win.h"

#include <stdatomic.h>
#include <stdlib.h>

#include "mpi/engine.h"
#include "mpi/init.h"
#include "mpi/err.h"
#include "mpi/group.h"
#include "mpi/label.h"
#include "mpi/pt2pt.h"
#include "util/xmem.h"

/* ==== polling ============================================================= */

/* A synchronisation call that returns at the clock it was called at
 * (nothing remote to wait for: a flush with nothing pending, a lock of the
 * rank's own memory) is a poll, as a test that finds nothing: the engine
 * acts on what has arrived and the run's poll cost is charged, so that a
 * loop of such calls waiting for another rank moves the clock (with a poll
 * cost of 0 the simulator stops it after a million tries at one clock). */
static void idle(st_rank *R, double t0) {
  if (mp_time(R->self) != t0) return;
  eng_poll(R);
  double cost = init_poll_cost();
  if (cost > 0 && mp_busy(R->self, cost) != MP_OK) st_stopped(R);
}

/* ==== fence =============================================================== */

static int any_epoch(const rma_window *w) { return w->acc || w->expo || w->lockall || w->nlocked; }

int PMPI_Win_fence(int assert, MPI_Win win) {
  static const char fn[] = "MPI_Win_fence";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (any_epoch(w)) return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "inside a post/start or lock epoch");
  rma_wlabel l = {.fn = fn, .w = w, .rank = -1};
  rma_wlabel_set(R, &l);
  rma_complete(R, w, -1, 0);
  PMPI_Barrier(w->comm);
  label_clear(R);
  w->fence = !(assert & MPI_MODE_NOSUCCEED);
  return MPI_SUCCESS;
}

/* ==== post/start/complete/wait ============================================ */

/* The window ranks of group's members, malloc'd (*n of them), or NULL
 * with the error raised in *rc. */
static int *members(st_rank *R, rma_window *w, const char *fn, MPI_Group group, int *n, int *rc) {
  st_ranks *g = group_get(R, group);
  *rc = MPI_SUCCESS;
  if (!g || group == MPI_GROUP_NULL) {
    *rc = rma_win_raise(R, w, MPI_ERR_GROUP, fn, "invalid group");
    return NULL;
  }
  int *r = xmallocarray((size_t)g->n + 1, sizeof *r);
  for (int i = 0; i < g->n; i++) {
    int world = g->world ? g->world[i] : i;
    r[i] = st_comm_rank_of(w->c, world);
    if (r[i] < 0) {
      free(r);
      *rc = rma_win_raise(R, w, MPI_ERR_GROUP, fn, "member %d of the group (MPI_COMM_WORLD rank %d) is not in the window",
                          i, world);
      return NULL;
    }
  }
  *n = g->n;
  return r;
}

int PMPI_Win_post(MPI_Group group, int assert, MPI_Win win) {
  static const char fn[] = "MPI_Win_post";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  (void)assert;
  if (rc) return rc;
  if (w->expo) return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "an exposure epoch is open already (MPI_Win_post without MPI_Win_wait)");
  int n, *r = members(R, w, fn, group, &n, &rc);
  if (!r) return rc;
  w->fence = 0;
  w->expo = r;
  w->nexpo = n;
  w->donerq = xmallocarray((size_t)n + 1, sizeof *w->donerq);
  for (int i = 0; i < n; i++) {
    st_req *q = st_req_new(R);
    pt2pt_recv_fill(q, w->c, 0, NULL, 0, MPI_BYTE, r[i], WTAG_DONE, w->comm, "MPI_Win_post");
    pt2pt_recv_start(R, q);
    w->donerq[i] = st_req_handle(q);
  }
  for (int i = 0; i < n; i++) {
    st_req q;
    st_req_stack(&q);
    pt2pt_send_fill(&q, w->c, 0, SM_STANDARD, NULL, 0, MPI_BYTE, r[i], WTAG_POST, w->comm, fn);
    pt2pt_send_start(R, &q, w->c);
  }
  return MPI_SUCCESS;
}

int PMPI_Win_start(MPI_Group group, int assert, MPI_Win win) {
  static const char fn[] = "MPI_Win_start";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  (void)assert;
  if (rc) return rc;
  if (w->acc || w->lockall || w->nlocked)
    return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "an access epoch is open already");
  int n, *r = members(R, w, fn, group, &n, &rc);
  if (!r) return rc;
  w->fence = 0;
  w->acc = r;
  w->nacc = n;
  rma_access_begin(R, w);
  return MPI_SUCCESS;
}

int PMPI_Win_complete(MPI_Win win) {
  static const char fn[] = "MPI_Win_complete";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!w->acc) return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "no access epoch (MPI_Win_start) is open");
  rma_wlabel l = {.fn = fn, .w = w, .rank = -1};
  rma_wlabel_set(R, &l);
  rma_access_end(R, w);
  label_clear(R);
  free(w->acc);
  w->acc = NULL;
  w->nacc = 0;
  return MPI_SUCCESS;
}

/* The exposure epoch ends: its requests are all done. */
static void exposure_end(st_rank *R, rma_window *w) {
  for (int i = 0; i < w->nexpo; i++) {
    st_req *q = st_req_get(R, w->donerq[i]);
    if (q) st_req_free(R, q);
  }
  free(w->donerq);
  free(w->expo);
  w->donerq = NULL;
  w->expo = NULL;
  w->nexpo = 0;
}

int PMPI_Win_wait(MPI_Win win) {
  static const char fn[] = "MPI_Win_wait";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!w->expo) return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "no exposure epoch (MPI_Win_post) is open");
  rma_wlabel l = {.fn = fn, .w = w, .rank = -1};
  rma_wlabel_set(R, &l);
  for (int i = 0; i < w->nexpo; i++) {
    st_req *q = st_req_get(R, w->donerq[i]);
    if (q->state == RS_ACTIVE) eng_wait(R, q);
  }
  label_clear(R);
  exposure_end(R, w);
  return MPI_SUCCESS;
}

int PMPI_Win_test(MPI_Win win, int *flag) {
  static const char fn[] = "MPI_Win_test";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!flag) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL flag argument");
  if (!w->expo) return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "no exposure epoch (MPI_Win_post) is open");
  eng_poll(R);
  *flag = 1;
  for (int i = 0; i < w->nexpo && *flag; i++) *flag = st_req_get(R, w->donerq[i])->state != RS_ACTIVE;
  if (*flag)
    exposure_end(R, w);
  else
    idle(R, mp_time(R->self));
  return MPI_SUCCESS;
}

/* ==== passive target ====================================================== */

/* target a rank of w, or MPI_PROC_NULL: MPI_SUCCESS or MPI_ERR_RANK raised. */
static int check_rank(st_rank *R, rma_window *w, const char *fn, int rank) {
  if (rank == MPI_PROC_NULL || (rank >= 0 && rank < w->size)) return MPI_SUCCESS;
  return rma_win_raise(R, w, MPI_ERR_RANK, fn, "invalid rank %d (the window has %d rank%s)", rank, w->size,
                       w->size == 1 ? "" : "s");
}

int PMPI_Win_lock(int lock_type, int rank, int assert, MPI_Win win) {
  static const char fn[] = "MPI_Win_lock";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc || (rc = check_rank(R, w, fn, rank))) return rc;
  if (lock_type != MPI_LOCK_SHARED && lock_type != MPI_LOCK_EXCLUSIVE)
    return rma_win_raise(R, w, MPI_ERR_LOCKTYPE, fn, "invalid lock_type %d (MPI_LOCK_SHARED or MPI_LOCK_EXCLUSIVE)",
                         lock_type);
  if (rank == MPI_PROC_NULL) return MPI_SUCCESS;
  if (w->acc || w->lockall || rma_locked(w, rank))
    return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "rank %d is in an access epoch already", rank);
  w->fence = 0;
  rma_wlabel l = {.fn = fn, .w = w, .rank = rank, .lock = lock_type};
  rma_wlabel_set(R, &l);
  double t0 = mp_time(R->self);
  rma_lock(R, w, rank, lock_type, (assert & MPI_MODE_NOCHECK) != 0);
  idle(R, t0);
  label_clear(R);
  w->nlocked++;
  return MPI_SUCCESS;
}

int PMPI_Win_unlock(int rank, MPI_Win win) {
  static const char fn[] = "MPI_Win_unlock";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc || (rc = check_rank(R, w, fn, rank))) return rc;
  if (rank == MPI_PROC_NULL) return MPI_SUCCESS;
  if (!rma_locked(w, rank)) return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "rank %d is not locked", rank);
  rma_wlabel l = {.fn = fn, .w = w, .rank = rank};
  rma_wlabel_set(R, &l);
  double t0 = mp_time(R->self);
  rma_unlock(R, w, rank);
  idle(R, t0);
  label_clear(R);
  w->nlocked--;
  return MPI_SUCCESS;
}

int PMPI_Win_lock_all(int assert, MPI_Win win) {
  static const char fn[] = "MPI_Win_lock_all";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (w->acc || w->lockall || w->nlocked) return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "an access epoch is open already");
  w->fence = 0;
  if (assert & MPI_MODE_NOCHECK) {
    w->lockall = 2;
    return MPI_SUCCESS;
  }
  rma_wlabel l = {.fn = fn, .w = w, .rank = -1, .lock = MPI_LOCK_SHARED};
  rma_wlabel_set(R, &l);
  double t0 = mp_time(R->self);
  rma_lock_all(R, w);
  idle(R, t0);
  label_clear(R);
  w->lockall = 1;
  return MPI_SUCCESS;
}

int PMPI_Win_unlock_all(MPI_Win win) {
  static const char fn[] = "MPI_Win_unlock_all";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!w->lockall) return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "no MPI_Win_lock_all epoch is open");
  rma_wlabel l = {.fn = fn, .w = w, .rank = -1};
  rma_wlabel_set(R, &l);
  double t0 = mp_time(R->self);
  if (w->lockall == 2)
    rma_complete(R, w, -1, 0);
  else
    rma_unlock_all(R, w);
  idle(R, t0);
  label_clear(R);
  w->lockall = 0;
  return MPI_SUCCESS;
}

/* The flushes: in a passive-target epoch on rank (all: on every rank). */
static int flush(const char *fn, int rank, int all, MPI_Win win, int local) {
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (all) rank = -1;
  if (!all && (rc = check_rank(R, w, fn, rank))) return rc;
  if (rank == MPI_PROC_NULL) return MPI_SUCCESS;
  if (!w->lockall && (all ? !w->nlocked : !rma_locked(w, rank)))
    return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "not in a passive-target epoch%s", all ? "" : " on that rank");
  rma_wlabel l = {.fn = fn, .w = w, .rank = rank};
  rma_wlabel_set(R, &l);
  double t0 = mp_time(R->self);
  rma_complete(R, w, rank, local);
  idle(R, t0);
  label_clear(R);
  return MPI_SUCCESS;
}

int PMPI_Win_flush(int rank, MPI_Win win) { return flush("MPI_Win_flush", rank, 0, win, 0); }
int PMPI_Win_flush_local(int rank, MPI_Win win) { return flush("MPI_Win_flush_local", rank, 0, win, 1); }
int PMPI_Win_flush_all(MPI_Win win) { return flush("MPI_Win_flush_all", 0, 1, win, 0); }
int PMPI_Win_flush_local_all(MPI_Win win) { return flush("MPI_Win_flush_local_all", 0, 1, win, 1); }

/* The memory model is unified (every rank's window is one copy in one
 * address space): MPI_Win_sync is a memory barrier. */
int PMPI_Win_sync(MPI_Win win) {
  static const char fn[] = "MPI_Win_sync";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  double t0 = mp_time(R->self);
  rma_progress(R, w, t0);
  atomic_thread_fence(memory_order_seq_cst);
  idle(R, t0);
  return MPI_SUCCESS;
}
