// cxxenv.cc -- MPI's environment as a C++ object: MPI_Init in the
// constructor of a static object (before main), MPI_Finalize in its
// destructor (after main returns), as RAII wrappers do.  Each rank
// constructs and destroys its own; the sorted output must be Open MPI's
// (tests/cli_mpiwrap.sh).
#include <mpi.h>

#include <cstdio>

struct mpi_env {
  int rank = -1, size = 0;
  mpi_env() {
    MPI_Init(nullptr, nullptr);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
  }
  ~mpi_env() {
    int done = 0;
    MPI_Barrier(MPI_COMM_WORLD);
    MPI_Finalize();
    MPI_Finalized(&done);
    std::printf("rank %d: finalized %d after main\n", rank, done);
  }
};

static mpi_env env;

int main() {
  int sum = 0;
  MPI_Allreduce(&env.rank, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  std::printf("rank %d of %d: sum %d\n", env.rank, env.size, sum);
  return 0;
}
