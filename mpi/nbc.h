/* nbc.h -- the nonblocking collectives: a started schedule (coll_sched.h) behind a request of the
 * program's, moved on as its messages arrive.
 *
 * Not for programs.  Progress: a schedule waits at a receive (or a waitall) until the engine
 * completes it; the engine then runs this part's progress (coll_set_progress), which steps
 * every live schedule that can go on, in the order they started.  That happens in any MPI
 * call of the rank that acts on messages (a wait of any kind, a test, a blocking receive,
 * another collective), and while the rank computes (mp_set_progress: each message that comes
 * meanwhile is acted on at its arrival, as a network card or a progress thread would).  So a
 * nonblocking collective's messages move in simulated time while the program computes between
 * its start and its wait, and the wait costs only what is left.  doc/mpi-semantics.md says
 * what it costs. */
#ifndef TSMPI_NBC_H
#define TSMPI_NBC_H

#include "mpi/coll_sched.h"

/* Start schedule s (built for collective fn on comm, root or -1): *req becomes its request,
 * done at once if s needs no message; else it is stepped by the progress until its end, when
 * the request completes and s is freed. */
void nbc_start(coll_sched *s, const char *fn, MPI_Comm comm, int root, MPI_Request *req);

#endif
