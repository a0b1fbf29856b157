/* tls.c -- thread-local variables (__thread, C11's _Thread_local) in an MPI
 * program: each rank has its own, initialized from the program's template
 * (an integer, an aligned array) or zero (an array of 8 MiB, of which each
 * rank writes one element), as each process has its own.  Rank 0 prints how
 * many ranks found theirs intact: the same line as under Open MPI
 * (tests/cli_mpiwrap.sh). */
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>

static __thread int counter = 5;
static __thread double big[1 << 20];   /* 8 MiB a rank, one page of it written */
static _Alignas(64) _Thread_local char aligned[64] = "rank";

int main(int argc, char **argv) {
  int r, p;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  counter += r;
  big[r] = r;
  aligned[1] = (char)('A' + r % 26);
  MPI_Barrier(MPI_COMM_WORLD);   /* every rank has written its own */
  int ok = counter == 5 + r && big[r] == r && big[(r + 1) % p] == 0 && (uintptr_t)aligned % 64 == 0 &&
           aligned[0] == 'r' && aligned[1] == 'A' + r % 26 && aligned[2] == 'n';
  int all = 0;
  MPI_Reduce(&ok, &all, 1, MPI_INT, MPI_SUM, 0, MPI_COMM_WORLD);
  if (r == 0) printf("%d of %d ranks see their own thread-local variables\n", all, p);
  MPI_Finalize();
  return 0;
}
