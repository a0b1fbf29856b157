/* test_mpi_comm.c -- what tilesim's communicators, attributes and error
 * handlers do that the portable programs of tests/mpi cannot check: the
 * simulated times of MPI_Intercomm_create and MPI_Intercomm_merge against
 * their closed forms (binary-fraction costs: exact), MPI_Comm_split_type's
 * node of one rank with no message, MPI_Comm_idup done on return, the
 * 1024 contexts (an intercommunicator takes two: 511 at once), the error
 * code a program adds ending the run under MPI_ERRORS_ARE_FATAL in its own
 * words, MPI_LASTUSEDCODE, a rank not in an intercommunicator's remote
 * group named so, and what a deadlock report says of a rank in
 * MPI_Intercomm_create.  On the simulator and on threads where it applies. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/mpi.h"
#include "tests/check.h"
#include "mp/mp.h"
#include "tests/mpiharness.h"

static const char *const bname[] = {"sim", "threads"};

/* Run fn on n ranks of backend b (the harness's machine: --net ideal,
 * m = 1/4, per_byte = 1/16). */
static mpih_result run(int b, int n, mpih_fn fn, void *ud) {
  mpih_config cfg;
  mpih_config_init(&cfg, b, n);
  return mpih_result_of(&cfg, fn, ud);
}

static int has(const char *s, const char *part) { return strstr(s, part) != NULL; }

typedef struct {
  double t[4][4];   /* by rank */
  int n[4];
} facts;

/* ==== simulated time ====================================================== */

/* Two ranks, each its own group (MPI_COMM_SELF): the leaders swap an 8-byte
 * length and then their 128-byte bitmap with the leader's and the group's
 * world ranks (8 bytes), both at 0: each arrives at 1/4 + 136/16 = 8.75,
 * with no message inside a group of one.  The merge swaps the length and
 * 128 + 4 bytes (high) the same way: 8.75 + 1/4 + 132/16 = 17.25. */
static int inter_time(void *ud) {
  facts *F = ud;
  int r = mpih_init();
  MPI_Comm ic, m;
  MPI_Intercomm_create(MPI_COMM_SELF, 0, MPI_COMM_WORLD, 1 - r, 5, &ic);
  F->t[r][0] = MPI_Wtime();
  MPI_Intercomm_merge(ic, r, &m);
  F->t[r][1] = MPI_Wtime();
  int mr = -1;
  MPI_Comm_rank(m, &mr);
  F->n[r] = mr;
  MPI_Comm_free(&m);
  MPI_Comm_free(&ic);
  MPI_Finalize();
  return 0;
}

/* MPI_Comm_split_type: each rank alone, no message, no time; idup's
 * request done at once. */
static int shared_node(void *ud) {
  facts *F = ud;
  int r = mpih_init();
  MPI_Comm node, d;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &F->n[r]);
  F->t[r][0] = MPI_Wtime();
  MPI_Request q;
  int flag = 0;
  MPI_Comm_idup(MPI_COMM_WORLD, &d, &q);
  MPI_Test(&q, &flag, MPI_STATUS_IGNORE);
  F->t[r][1] = flag;
  MPI_Comm_free(&d);
  MPI_Comm_free(&node);
  MPI_Finalize();
  return 0;
}

static void closed_forms(void) {
  facts F = {0};
  mpih_result res = run(MPIH_SIM, 2, inter_time, &F);
  double create = 0.25 + 136 * 0.0625, merge = create + 0.25 + 132 * 0.0625;
  CHECK(res.rc == 0 && F.t[0][0] == create && F.t[1][0] == create, "intercomm_create: %.17g %.17g (%.17g due)",
        F.t[0][0], F.t[1][0], create);
  CHECK(F.t[0][1] == merge && F.t[1][1] == merge && F.n[0] == 0 && F.n[1] == 1,
        "intercomm_merge: %.17g %.17g (%.17g due), ranks %d %d", F.t[0][1], F.t[1][1], merge, F.n[0], F.n[1]);
  mpih_result_free(&res);
  for (int b = 0; b < 2; b++) {
    memset(&F, 0, sizeof F);
    res = run(b, 3, shared_node, &F);
    CHECK(res.rc == 0 && F.n[0] == 1 && F.n[1] == 1 && F.n[2] == 1, "%s: split_type: nodes of %d %d %d ranks",
          bname[b], F.n[0], F.n[1], F.n[2]);
    CHECK(b == MPIH_THREADS || (F.t[0][0] == 0 && F.t[1][0] == 0 && F.t[2][0] == 0),
          "%s: split_type took %g %g %g s", bname[b], F.t[0][0], F.t[1][0], F.t[2][0]);
    CHECK(F.t[0][1] == 1 && F.t[1][1] == 1 && F.t[2][1] == 1, "%s: idup's request not done on return", bname[b]);
    mpih_result_free(&res);
  }
}

/* ==== contexts ============================================================ */

/* Intercommunicators on 2 ranks until none is left, under
 * MPI_ERRORS_RETURN: 1024 pairs, 2 for MPI_COMM_WORLD and MPI_COMM_SELF,
 * 2 each; then all freed and one more made. */
static int contexts(void *ud) {
  facts *F = ud;
  int r = mpih_init();
  MPI_Comm_set_errhandler(MPI_COMM_SELF, MPI_ERRORS_RETURN);
  MPI_Comm *ic = malloc(600 * sizeof *ic);
  int n = 0, rc = MPI_SUCCESS;
  while (n < 600 && (rc = MPI_Intercomm_create(MPI_COMM_SELF, 0, MPI_COMM_WORLD, 1 - r, 1, &ic[n])) == MPI_SUCCESS) n++;
  F->n[r] = n;
  F->n[2 + r] = rc;
  for (int i = 0; i < n; i++) MPI_Comm_free(&ic[i]);
  MPI_Comm again;
  F->t[r][0] = MPI_Intercomm_create(MPI_COMM_SELF, 0, MPI_COMM_WORLD, 1 - r, 1, &again) == MPI_SUCCESS;
  MPI_Comm_free(&again);
  free(ic);
  MPI_Finalize();
  return 0;
}

static void context_limit(void) {
  for (int b = 0; b < 2; b++) {
    facts F = {0};
    mpih_result res = run(b, 2, contexts, &F);
    CHECK(res.rc == 0 && F.n[0] == 511 && F.n[1] == 511 && F.n[2] == MPI_ERR_OTHER && F.n[3] == MPI_ERR_OTHER,
          "%s: %d and %d intercommunicators at once (511 due), then %d %d", bname[b], F.n[0], F.n[1], F.n[2],
          F.n[3]);
    CHECK(F.t[0][0] == 1 && F.t[1][0] == 1, "%s: no intercommunicator after all were freed", bname[b]);
    mpih_result_free(&res);
  }
}

/* ==== errors ============================================================== */

static int added_code(void *ud) {
  facts *F = ud;
  MPI_Init(NULL, NULL);
  int c, e, *last, flag;
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_LASTUSEDCODE, &last, &flag);
  F->n[0] = *last;
  MPI_Add_error_class(&c);
  MPI_Add_error_code(c, &e);
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_LASTUSEDCODE, &last, &flag);
  F->n[1] = *last;
  F->n[2] = c;
  F->n[3] = e;
  MPI_Add_error_string(e, "the reactor is too hot");
  MPI_Comm_call_errhandler(MPI_COMM_WORLD, e);   /* MPI_ERRORS_ARE_FATAL */
  F->t[0][0] = 1;                                  /* not reached */
  MPI_Finalize();
  return 0;
}

/* A rank of the remote group that is not there. */
static int inter_bad_rank(void *ud) {
  (void)ud;
  int r = mpih_init(), v = 0;
  MPI_Comm ic;
  MPI_Intercomm_create(MPI_COMM_SELF, 0, MPI_COMM_WORLD, 1 - r, 3, &ic);
  if (r == 0) MPI_Send(&v, 1, MPI_INT, 3, 0, ic);
  MPI_Recv(&v, 1, MPI_INT, 0, 0, ic, MPI_STATUS_IGNORE);
  MPI_Finalize();
  return 0;
}

/* Rank 1 makes an intercommunicator; rank 0 waits for a message. */
static int inter_stuck(void *ud) {
  (void)ud;
  int r = mpih_init(), v;
  MPI_Comm ic;
  if (r == 1)
    MPI_Intercomm_create(MPI_COMM_SELF, 0, MPI_COMM_WORLD, 0, 3, &ic);
  else
    MPI_Recv(&v, 1, MPI_INT, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Finalize();
  return 0;
}

static void errors(void) {
  for (int b = 0; b < 2; b++) {
    facts F = {0};
    mpih_result res = run(b, 1, added_code, &F);
    CHECK(F.n[0] == MPI_ERR_LASTCODE && F.n[2] == MPI_ERR_LASTCODE + 1 && F.n[3] == MPI_ERR_LASTCODE + 2 &&
              F.n[1] == F.n[3],
          "%s: MPI_LASTUSEDCODE %d, then %d; class %d, code %d", bname[b], F.n[0], F.n[1], F.n[2], F.n[3]);
    CHECK(res.rc != 0 && res.abort_code == 1 && F.t[0][0] == 0 &&
              has(res.err, "rank 0: MPI_Comm_call_errhandler: error code 76: the reactor is too hot"),
          "%s: a fatal added code: %s", bname[b], res.err);
    mpih_result_free(&res);
    res = run(b, 2, inter_bad_rank, NULL);
    CHECK(res.rc != 0 && res.abort_code == 1 &&
              has(res.err, "rank 0: MPI_Send: invalid rank 3 (the remote group of communicator 2 has 1 rank)"),
          "%s: a bad rank on an intercommunicator: %s", bname[b], res.err);
    mpih_result_free(&res);
    res = run(b, 2, inter_stuck, NULL);
    CHECK(res.rc != 0 && res.deadlock && has(res.err, "rank 1 waits in MPI_Intercomm_create(MPI_COMM_SELF)") &&
              has(res.err, "rank 0 waits in MPI_Recv(source=1, tag=0, MPI_COMM_WORLD)"),
          "%s: the report: %s", bname[b], res.err);
    mpih_result_free(&res);
  }
}

int main(void) {
  closed_forms();
  context_limit();
  errors();
  return check_done("test_mpi_comm");
}
