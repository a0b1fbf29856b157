/* pt2pt.h -- starting sends and receives of count elements of a datatype:
 * what MPI's point-to-point calls (pt2pt.c), persistent requests
 * (request.c), the collectives' point-to-point (coll_transport.c) and the
 * communicator constructors (comm.c) share.  The arguments are checked by
 * the caller. */
#ifndef TSMPI_PT2PT_H
#define TSMPI_PT2PT_H

#include "mpi/state.h"

/* q (zeroed, or a table request) made a send of fn: mode SM_*, to rank dst
 * of c (MPI_PROC_NULL), on c's point-to-point context (coll = 0) or its
 * collective one (coll = 1). */
void pt2pt_send_fill(st_req *q, const st_comm *c, int coll, int mode, const void *buf, int count,
                     MPI_Datatype dt, int dst, int tag, MPI_Comm comm, const char *fn);

/* The send's message leaves (packed first if the type is not contiguous;
 * through the attached buffer for SM_BUFFERED).  q is then done, or active
 * (SM_SYNC: until its ack).  MPI_SUCCESS, or MPI_ERR_BUFFER raised on c (a
 * buffered send that does not fit the attached buffer; q is done). */
int pt2pt_send_start(st_rank *R, st_req *q, const st_comm *c);

/* q made a receive of fn from rank src of c (MPI_ANY_SOURCE,
 * MPI_PROC_NULL) with tag (MPI_ANY_TAG). */
void pt2pt_recv_fill(st_req *q, const st_comm *c, int coll, void *buf, int count, MPI_Datatype dt,
                     int src, int tag, MPI_Comm comm, const char *fn);

/* The receive starts (eng_recv_start; from MPI_PROC_NULL it is done at
 * once with the empty status MPI gives). */
void pt2pt_recv_start(st_rank *R, st_req *q);

/* A blocking receive (eng_recv; MPI_PROC_NULL as above). */
void pt2pt_recv_block(st_rank *R, st_req *q);

/* Copy a request's status out (out may be MPI_STATUS_IGNORE); MPI_ERROR
 * only with with_error (the calls that return several statuses). */
void pt2pt_status_out(MPI_Status *out, const MPI_Status *in, int with_error);

/* A receive's truncation (q->st.MPI_ERROR is MPI_ERR_TRUNCATE), raised for
 * call fn (the receive's own, or the MPI_Wait that completed it) on c (NULL:
 * MPI_COMM_WORLD's handler). */
int pt2pt_req_error(st_rank *R, const st_comm *c, const st_req *q, const char *fn);

/* The empty status (MPI 3.1 section 3.7.3) and MPI_PROC_NULL's. */
void pt2pt_status_empty(MPI_Status *st);

#endif
