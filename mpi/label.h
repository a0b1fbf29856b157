/* label.h -- what a rank blocked in an MPI call waits in, in the program's
 * words, for the simulator's deadlock report:
 *   rank 2 waits in MPI_Recv(source=1, tag=7, MPI_COMM_WORLD)
 *   rank 0 waits in MPI_Waitall(MPI_Irecv(source=3, tag=0, MPI_COMM_WORLD), ...)
 *   rank 1 waits in MPI_Comm_dup(MPI_COMM_WORLD)
 * A blocking call fills a label_rec on its stack and sets it (mp_label: two
 * stores); the words are made only when a report asks for them. */
#ifndef TSMPI_LABEL_H
#define TSMPI_LABEL_H

#include "mpi/state.h"

enum { L_SEND, L_RECV, L_PROBE, L_SENDRECV, L_REQS, L_COMM };

typedef struct {
  const char *fn;           /* "MPI_Recv" */
  int what;                 /* L_* */
  int peer, tag;            /* L_SEND: dest; L_RECV, L_PROBE: source; L_SENDRECV: dest */
  int peer2, tag2;          /* L_SENDRECV: source, recvtag */
  int pair;                 /* the communicator's context pair */
  st_rank *R;                   /* L_REQS: the rank and its requests */
  const MPI_Request *reqs;
  int n;
} label_rec;

/* Set l as the calling rank's label until label_clear. */
void label_describe(void *ud, char *buf, size_t len);
static inline void label_set(st_rank *R, label_rec *l) { mp_label(R->self, label_describe, l); }
static inline void label_clear(st_rank *R) { mp_label(R->self, NULL, NULL); }

#endif
