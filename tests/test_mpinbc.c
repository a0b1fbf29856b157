/* test_mpinbc.c -- what the portable programs of tests/mpi cannot check of the nonblocking
 * collectives: their messages move in simulated time while the rank computes between the start
 * and the wait, as a network card or a progress thread would move them, so each rank's finish
 * against its closed form; the computing charged by mp_busy, by a runtime's hook at the next
 * MPI call (tilesim-mpirun --compute), and with a processor cost per message (taken from the
 * computing); the blocking forms' costs, unchanged; a deadlock inside MPI_Wait on one named in
 * the program's words; MPI_Cancel of one refused; the threads backend's results.
 *
 * The harness's machine: --net ideal, m = 1/4 s a message, 1/16 s a byte, a processor per rank
 * (binary fractions: the closed forms are exact).  A 4-byte message costs 1/2 s; an empty one
 * 1/4 s. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/mpi.h"
#include "tests/check.h"
#include "mp/mp.h"
#include "tests/mpiharness.h"

enum { BCAST, ALLREDUCE, BARRIER, BLOCKING_BCAST, NCASES };
static const char *const cname[NCASES] = {"MPI_Ibcast", "MPI_Iallreduce", "MPI_Ibarrier", "MPI_Bcast"};

enum { VIA_BUSY, VIA_HOOK, VIA_NONE };   /* how the computing is charged */

typedef struct {
  int which, via;
  double c;        /* seconds each rank computes between start and wait */
  int bad;         /* a rank's result was wrong */
} job;

/* tilesim-mpirun's --compute hooks, as mpirun/compute.c makes them: what a
 * rank computed since its last mp call is charged at the next one. */
static double pending[64];
static void hook_enter(mp *self) {
  double s = pending[mp_rank(self)];
  pending[mp_rank(self)] = 0;
  if (s > 0) mp_charge(self, s);
}
static void hook_leave(mp *self) { (void)self; }
static const mp_hooks hooks = {hook_enter, hook_leave};

static void compute(const job *j, double s) {
  mp *self = mp_self();
  if (j->via == VIA_BUSY) mp_busy(self, s);
  else if (j->via == VIA_HOOK) pending[mp_rank(self)] += s;
}

static int prog(void *ud) {
  job *j = ud;
  int me, size, x, sum = -1;
  me = mpih_init();
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  x = me == 0 ? 1234 : me;
  MPI_Request r = MPI_REQUEST_NULL;
  switch (j->which) {
  case BCAST: MPI_Ibcast(&x, 1, MPI_INT, 0, MPI_COMM_WORLD, &r); break;
  case ALLREDUCE: MPI_Iallreduce(&me, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD, &r); break;
  case BARRIER: MPI_Ibarrier(MPI_COMM_WORLD, &r); break;
  default: break;
  }
  compute(j, j->c);
  if (j->which == BLOCKING_BCAST) MPI_Bcast(&x, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  if ((j->which == BCAST || j->which == BLOCKING_BCAST) && x != 1234) j->bad = 1;
  if (j->which == ALLREDUCE && sum != size * (size - 1) / 2) j->bad = 1;
  MPI_Finalize();
  if (j->via == VIA_HOOK) hook_enter(mp_self());   /* tilesim-mpirun's compute_settle */
  return 0;
}

/* The nonblocking collectives' messages on 4 ranks (binomial broadcast from
 * 0, recursive-doubling allreduce, dissemination barrier), when each
 * arrives, and so each rank's finish = max(c, its last arrival); the
 * blocking broadcast after computing: its messages leave after c. */
static double closed(int which, int r, double c) {
  switch (which) {
  case BCAST: {   /* 0 -> 2 and 0 -> 1 at 0 (arriving at 1/2); 2 -> 3 at 1/2 (at 1) */
    static const double arrive[4] = {0, 0.5, 0.5, 1.0};
    return fmax(c, arrive[r]);
  }
  case ALLREDUCE: return fmax(c, 1.0);   /* two rounds of 4-byte exchanges */
  case BARRIER: return fmax(c, 0.5);     /* two rounds of empty messages */
  default: {   /* from c: 0 -> 2, 1 at c (c + 1/2), 2 -> 3 at c + 1/2 (c + 1) */
    static const double after[4] = {0, 0.5, 0.5, 1.0};
    return c + after[r];
  }
  }
}

static void overlap(void) {
  static const double cs[] = {0, 0.375, 0.75, 2};
  static const char *const vname[] = {"mp_busy", "a hook", "none"};
  for (int which = 0; which < NCASES; which++)
    for (int via = 0; via < 2; via++)
      for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
        job j = {which, via, cs[k], 0};
        mpih_config cfg;
        mpih_config_init(&cfg, MPIH_SIM, 4);
        mpih_result res;
        if (via == VIA_HOOK) mp_set_hooks(&hooks);
        mpih_run_fn(&cfg, prog, &j, &res);
        mp_set_hooks(NULL);
        int ok = res.rc == 0 && !j.bad;
        double got[4], want[4];
        for (int r = 0; r < 4; r++) {
          got[r] = res.finish[r];
          want[r] = closed(which, r, cs[k]);
          ok &= got[r] == want[r];
        }
        CHECK(ok, "%s, computing %g s by %s between start and wait on 4 ranks: finish %g %g %g %g, want %g %g %g %g%s%s",
              cname[which], cs[k], vname[via], got[0], got[1], got[2], got[3], want[0], want[1], want[2], want[3],
              res.rc ? ": " : "", res.rc ? res.err : "");
        mpih_result_free(&res);
      }
}

/* A processor cost per received message (cpu.h's o_recv = 1/8): the
 * progress receives during the computing and takes the cost from it, so
 * the computing ends 1/8 later; rank 2 forwards at 1/2 + 1/8, rank 3's
 * message arrives at 9/8.  Computing 2 s: finish 2 + 1/8 on ranks 1-3. */
static void overhead(void) {
  job j = {BCAST, VIA_BUSY, 2, 0};
  mpih_config cfg;
  mpih_config_init(&cfg, MPIH_SIM, 4);
  cfg.sim.cpu.o_recv = 0.125;
  mpih_result res;
  mpih_run_fn(&cfg, prog, &j, &res);
  int ok = res.rc == 0 && !j.bad && res.finish[0] == 2;
  for (int r = 1; r < 4; r++) ok &= res.finish[r] == 2.125;
  CHECK(ok, "MPI_Ibcast with 1/8 s a received message, computing 2 s: finish %g %g %g %g, want 2 2.125 2.125 2.125%s",
        res.finish[0], res.finish[1], res.finish[2], res.finish[3], res.rc ? res.err : "");
  mpih_result_free(&res);
  /* ... and computing 1/2 s: rank 3's message arrives at 9/8, after its
   * computing: its wait receives it then, 9/8 + 1/8. */
  j.c = 0.5;
  j.bad = 0;
  mpih_run_fn(&cfg, prog, &j, &res);
  ok = res.rc == 0 && !j.bad && res.finish[0] == 0.5 && res.finish[1] == 0.625 && res.finish[2] == 0.625 &&
       res.finish[3] == 1.25;
  CHECK(ok, "MPI_Ibcast with 1/8 s a received message, computing 1/2 s: finish %g %g %g %g, want 0.5 0.625 0.625 1.25%s",
        res.finish[0], res.finish[1], res.finish[2], res.finish[3], res.rc ? res.err : "");
  mpih_result_free(&res);
}

/* Rank 1 waits on a broadcast from rank 0, which never starts it. */
static int stuck(void *ud) {
  (void)ud;
  int me, x = 0;
  me = mpih_init();
  if (me == 1) {
    MPI_Request r;
    MPI_Ibcast(&x, 1, MPI_INT, 0, MPI_COMM_WORLD, &r);
    MPI_Wait(&r, MPI_STATUS_IGNORE);
  } else {
    MPI_Recv(&x, 1, MPI_INT, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
  MPI_Finalize();
  return 0;
}

static void deadlock(void) {
  mpih_config cfg;
  mpih_config_init(&cfg, MPIH_SIM, 2);
  mpih_result res;
  mpih_run_fn(&cfg, stuck, NULL, &res);
  CHECK(res.rc != 0 && res.deadlock && strstr(res.err, "rank 1 waits in MPI_Wait(MPI_Ibcast(root=0, MPI_COMM_WORLD))"),
        "a deadlock in MPI_Wait on an MPI_Ibcast: rc %d, deadlock %d, \"%s\"", res.rc, res.deadlock, res.err);
  mpih_result_free(&res);
}

/* A communicator freed while its nonblocking collective goes on: MPI frees
 * it once the collective is done (Open MPI 4.1 crashes on this). */
static int freed_early(void *ud) {
  int *bad = ud, me, size, sum = -1, status;
  me = mpih_init();
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm d;
  MPI_Request r;
  MPI_Comm_dup(MPI_COMM_WORLD, &d);
  MPI_Iallreduce(&me, &sum, 1, MPI_INT, MPI_SUM, d, &r);
  MPI_Comm_free(&d);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  int rc = MPI_Topo_test(d, &status);   /* the program's handle is gone at once */
  MPI_Wait(&r, MPI_STATUS_IGNORE);
  if (d != MPI_COMM_NULL || rc == MPI_SUCCESS || sum != size * (size - 1) / 2) bad[me] = 1;
  MPI_Finalize();
  return 0;
}

static void freed(void) {
  int bad[5] = {0, 0, 0, 0, 0};
  mpih_config cfg;
  mpih_config_init(&cfg, MPIH_SIM, 5);
  mpih_result res;
  mpih_run_fn(&cfg, freed_early, bad, &res);
  CHECK(res.rc == 0 && !bad[0] && !bad[1] && !bad[2] && !bad[3] && !bad[4],
        "MPI_Comm_free before the wait of an MPI_Iallreduce on it, 5 ranks: rc %d (%s), bad %d %d %d %d %d", res.rc,
        res.err, bad[0], bad[1], bad[2], bad[3], bad[4]);
  mpih_result_free(&res);
}

/* Rank 0 finalizes with its MPI_Ibcast (request freed) still waiting for
 * the message, then computes while it arrives: nothing of the MPI layer
 * may run then. */
static int late(void *ud) {
  int *bad = ud, me, x = 5;
  me = mpih_init();
  MPI_Request r;
  MPI_Ibcast(&x, 1, MPI_INT, 1, MPI_COMM_WORLD, &r);
  if (me == 0) MPI_Request_free(&r);
  else MPI_Wait(&r, MPI_STATUS_IGNORE);
  MPI_Finalize();
  if (me == 0 && mp_busy(mp_self(), 1.0) != MP_OK) *bad = 1;
  return 0;
}

static void finalized(void) {
  int bad = 0;
  mpih_config cfg;
  mpih_config_init(&cfg, MPIH_SIM, 2);
  mpih_result res;
  mpih_run_fn(&cfg, late, &bad, &res);
  CHECK(res.rc == 0 && !bad && res.finish[0] == 1.0,
        "computing after MPI_Finalize with a nonblocking collective left: rc %d (%s), bad %d, rank 0 ends at %g",
        res.rc, res.err, bad, res.finish[0]);
  mpih_result_free(&res);
}

/* MPI_Cancel of a nonblocking collective's request is erroneous (MPI 3.1
 * section 5.12): refused, and the collective goes on to its result. */
static int cancel_prog(void *ud) {
  int *bad = ud, me, size, sum = -1, cls = -1;
  me = mpih_init();
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Request r;
  MPI_Iallreduce(&me, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD, &r);
  int rc = MPI_Cancel(&r);
  MPI_Error_class(rc, &cls);
  int wrc = MPI_Wait(&r, MPI_STATUS_IGNORE);
  if (cls != MPI_ERR_REQUEST || wrc != MPI_SUCCESS || r != MPI_REQUEST_NULL || sum != size * (size - 1) / 2)
    bad[me] = 1;
  MPI_Finalize();
  return 0;
}

static void cancelled(void) {
  int bad[3] = {0, 0, 0};
  mpih_config cfg;
  mpih_config_init(&cfg, MPIH_SIM, 3);
  mpih_result res;
  mpih_run_fn(&cfg, cancel_prog, bad, &res);
  CHECK(res.rc == 0 && !bad[0] && !bad[1] && !bad[2],
        "MPI_Cancel of an MPI_Iallreduce's request on 3 ranks: MPI_ERR_REQUEST, then the sum: rc %d (%s), bad %d %d %d",
        res.rc, res.err, bad[0], bad[1], bad[2]);
  mpih_result_free(&res);
}

/* On threads the results, whatever the order the messages come in. */
static void threads(void) {
  for (int which = 0; which < NCASES; which++) {
    job j = {which, VIA_BUSY, 0.001, 0};
    mpih_config cfg;
    mpih_config_init(&cfg, MPIH_THREADS, 6);
    mpih_result res;
    mpih_run_fn(&cfg, prog, &j, &res);
    CHECK(res.rc == 0 && !j.bad, "%s on 6 threads: rc %d, bad %d: %s", cname[which], res.rc, j.bad, res.err);
    mpih_result_free(&res);
  }
}

int main(void) {
  overlap();
  overhead();
  deadlock();
  freed();
  finalized();
  cancelled();
  threads();
  return check_done("test_mpinbc");
}
