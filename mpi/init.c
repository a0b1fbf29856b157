/* init.c -- MPI's environment calls: Init, Finalize, Abort, the clock, the
 * version, the processor's name; the runner's settings and a rank's end. */
#include "mpi/init.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mpi/attr.h"
#include "mpi/engine.h"
#include "mpi/err.h"
#include "mpi/info.h"
#include "mpi/spin.h"
#include "mpi/state.h"
#include "util/xmem.h"

const char init_marks[2];

/* ==== per-run settings ==================================================== */

/* Written before the ranks start, read by all of them. */
static double poll_cost = 1e-6;
static double wtime_cost = 0;

int init_set_poll_cost(double seconds) {
  if (!(seconds >= 0) || isinf(seconds)) return -1;
  poll_cost = seconds;
  return 0;
}

double init_poll_cost(void) { return poll_cost; }

int init_set_wtime_cost(double seconds) {
  if (!(seconds >= 0) || isinf(seconds)) return -1;
  wtime_cost = seconds;
  return 0;
}

/* ==== Init and Finalize =================================================== */

static void comm_init(st_comm *c, MPI_Comm h, int pair, int rank, st_ranks *g, const char *name) {
  c->live = 1;
  c->h = h;
  c->local = MPI_COMM_NULL;
  c->pair = pair;
  c->rank = rank;
  c->size = g->n;
  c->g = g;
  c->eh = MPI_ERRORS_ARE_FATAL;
  snprintf(c->name, sizeof c->name, "%s", name);
}

static int init(const char *fn, int *argc, char ***argv, int required, int *provided) {
  mp *self = mp_self();
  if (!self) {
    fprintf(stderr, "tilesim MPI: %s called outside a rank: MPI programs run under tilesim-mpirun\n", fn);
    exit(1);
  }
  void *u = mp_user(self);
  if (u) {
    char why[160];
    snprintf(why, sizeof why, "rank %d: %s: MPI is %s", mp_rank(self), fn,
             u == INIT_MARK_FINALIZED ? "finalized already (MPI_Init after MPI_Finalize)"
                                     : "initialized already (MPI_Init called twice)");
    if (u != INIT_MARK_FINALIZED && u != INIT_MARK_STOPPED) {
      st_release(u);
      mp_set_user(self, INIT_MARK_STOPPED);
    }
    mp_abort(self, 1, why);
  }
  st_rank *R = xcalloc(1, sizeof *R);
  R->state = ST_LIVE;
  R->self = self;
  R->wrank = mp_rank(self);
  R->wsize = mp_size(self);
  /* Ranks are coroutines or threads that mp_self names: one thread of a
   * rank may call MPI, and only the one that called MPI_Init. */
  R->thread_level = required < MPI_THREAD_FUNNELED ? (required < MPI_THREAD_SINGLE ? MPI_THREAD_SINGLE : required)
                                                   : MPI_THREAD_FUNNELED;
  if (provided) *provided = R->thread_level;
  comm_init(&R->world, MPI_COMM_WORLD, 0, R->wrank, st_ranks_new(R->wsize, NULL), "MPI_COMM_WORLD");
  int me = R->wrank;
  comm_init(&R->selfc, MPI_COMM_SELF, 1, 0, st_ranks_new(1, &me), "MPI_COMM_SELF");
  R->empty = st_ranks_new(0, NULL);
  R->pairs[0] = 3;   /* pairs 0 and 1: MPI_COMM_WORLD, MPI_COMM_SELF */
  if (argc && argv && *argv) R->argc = *argc, R->argv = *argv;
  mp_set_user(self, R);
  return MPI_SUCCESS;
}

int PMPI_Init(int *argc, char ***argv) { return init("MPI_Init", argc, argv, MPI_THREAD_SINGLE, NULL); }

int PMPI_Init_thread(int *argc, char ***argv, int required, int *provided) {
  return init("MPI_Init_thread", argc, argv, required, provided);
}

int PMPI_Initialized(int *flag) {
  mp *self = mp_self();
  *flag = self && mp_user(self) && mp_user(self) != INIT_MARK_STOPPED;
  return MPI_SUCCESS;
}

int PMPI_Finalized(int *flag) {
  mp *self = mp_self();
  *flag = self && mp_user(self) == INIT_MARK_FINALIZED;
  return MPI_SUCCESS;
}

int PMPI_Query_thread(int *provided) {
  st_rank *R = st_need("MPI_Query_thread");
  *provided = R->thread_level;
  return MPI_SUCCESS;
}

int PMPI_Is_thread_main(int *flag) {
  st_need("MPI_Is_thread_main");
  *flag = 1;   /* only the rank's own thread reaches its state (mp_self) */
  return MPI_SUCCESS;
}

/* What a rank leaves behind at MPI_Finalize: messages it never received
 * and requests never completed are the program's bugs, said on stderr
 * (as the simulator says of unread messages). */
static void leftovers(st_rank *R) {
  if (R->nunexp) {
    char b[32];
    st_msg *m = R->unexp;
    fprintf(stderr,
            "tilesim MPI: warning: rank %d: MPI_Finalize with %ld message%s never received "
            "(the first from rank %d, tag %d, on %s%s)\n",
            R->wrank, R->nunexp, R->nunexp == 1 ? "" : "s", m->src, m->tag, st_pair_name(m->ctx / 2, b),
            m->ctx % 2 ? ", a collective's" : "");
  }
  long active = 0;
  for (int i = 0; i < R->nreqs; i++)   /* the program's (a nonblocking collective's own steps are its) */
    active += R->reqs[i]->used && R->reqs[i]->state == RS_ACTIVE && !R->reqs[i]->watch;
  if (active)
    fprintf(stderr, "tilesim MPI: warning: rank %d: MPI_Finalize with %ld request%s still active\n",
            R->wrank, active, active == 1 ? "" : "s");
}

/* MPI 3.1 section 8.7.1: MPI_Finalize first frees MPI_COMM_SELF's
 * attributes, as MPI_Comm_free would, last set first; MPI_COMM_WORLD's
 * follow (as MPICH).  The callbacks may call MPI (MPI_Finalized says 0). */
int PMPI_Finalize(void) {
  static const char fn[] = "MPI_Finalize";
  st_rank *R = st_need(fn);
  char why[128];
  int rc = attr_delete_all(R, ATTR_COMM, MPI_COMM_SELF, why);
  if (!rc) rc = attr_delete_all(R, ATTR_COMM, MPI_COMM_WORLD, why);
  if (rc) return err_raise(R, NULL, rc, fn, "%s", why);
  leftovers(R);
  mp *self = R->self;
  st_release(R);
  mp_set_user(self, INIT_MARK_FINALIZED);
  return MPI_SUCCESS;
}

int init_rank_end(mp *self) {
  void *u = mp_user(self);
  mp_set_user(self, NULL);
  if (!u) return INIT_NEVER;
  if (u == INIT_MARK_FINALIZED) return INIT_FINALIZED;
  if (u != INIT_MARK_STOPPED) st_release(u);
  return INIT_UNFINALIZED;
}

int PMPI_Abort(MPI_Comm comm, int errorcode) {
  st_rank *R = st_need("MPI_Abort");
  char b[32], why[200];
  st_comm *c = st_comm_get(R, comm);
  snprintf(why, sizeof why, "rank %d called MPI_Abort(%s, %d)", R->wrank,
           c ? st_pair_name(c->pair, b) : "an invalid communicator", errorcode);
  mp *self = R->self;
  st_release(R);
  mp_set_user(self, INIT_MARK_STOPPED);
  mp_abort(self, errorcode, why);
}

/* ==== the clock and the machine =========================================== */

double init_clock_read(mp *self, const char *fn) {
  double t = mp_time(self);
  st_rank *R = st_get();
  if (wtime_cost > 0 && mp_busy(self, wtime_cost) != MP_OK && R) st_stopped(R);
  if (R)
    spin_count(R, fn);   /* a loop that waits for a clock that cannot move */
  else
    spin_count_outside(self, fn);
  return t;
}

double PMPI_Wtime(void) {
  mp *self = mp_self();
  return self ? init_clock_read(self, "MPI_Wtime") : 0;
}

double PMPI_Wtick(void) { return 1e-9; }

int PMPI_Get_processor_name(char *name, int *resultlen) {
  st_need("MPI_Get_processor_name");
  /* The host's name, as an MPI library on this machine gives it (the ranks
   * share it, as processes on one node do). */
  char host[MPI_MAX_PROCESSOR_NAME];
  if (gethostname(host, sizeof host) != 0) snprintf(host, sizeof host, "localhost");
  host[sizeof host - 1] = 0;
  size_t n = strlen(host);
  memcpy(name, host, n + 1);
  *resultlen = (int)n;
  return MPI_SUCCESS;
}

int PMPI_Get_version(int *version, int *subversion) {
  *version = MPI_VERSION;
  *subversion = MPI_SUBVERSION;
  return MPI_SUCCESS;
}

int PMPI_Get_library_version(char *version, int *resultlen) {
  static const char text[] = "tilesim MPI 3.1: on tilesim's mp.h (the simulated machine, or threads)";
  memcpy(version, text, sizeof text);
  *resultlen = (int)sizeof text - 1;
  return MPI_SUCCESS;
}

/* ==== memory ============================================================== */

/* MPI_Alloc_mem is malloc (no memory is special on the simulated machine);
 * info is checked, its hints ignored.  Size 0 gives a pointer all the
 * same, which MPI_Free_mem takes. */
int PMPI_Alloc_mem(MPI_Aint size, MPI_Info info, void *baseptr) {
  static const char fn[] = "MPI_Alloc_mem";
  st_rank *R = st_need(fn);
  if (size < 0) return err_raise(R, NULL, MPI_ERR_SIZE, fn, "invalid size %td", size);
  if (!baseptr) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL baseptr argument");
  unsigned hints = 0;
  int rc = info_hints(R, NULL, fn, info, &hints);
  if (rc) return rc;
  void *p = malloc(size ? (size_t)size : 1);
  if (!p) return err_raise(R, NULL, MPI_ERR_NO_MEM, fn, "no memory for %td bytes", size);
  memcpy(baseptr, &p, sizeof p);
  return MPI_SUCCESS;
}

int PMPI_Free_mem(void *base) {
  st_need("MPI_Free_mem");
  free(base);
  return MPI_SUCCESS;
}
