// cxxranks.cc -- a C++ MPI program on the C bindings, as people write them:
// static objects constructed before main and destroyed after it (each rank
// its own, as each process has its own), a function-local static, a
// thread_local, exceptions (the program's own hierarchy, libstdc++'s
// std::out_of_range, one thrown through a std::sort comparator, one
// rethrown with `throw;` after an MPI call inside the catch, while other
// ranks catch theirs), std:: containers, strings and iostreams, a function
// named time in a namespace and members named rand and exit.  The sorted
// output must be Open MPI's (tests/cli_mpiwrap.sh).
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace clocks {
int time(int x) { return 3 * x; }   // a time of the program's own
}

struct dice {   // members with libc's names
  int rand;
  void (*exit)(int);
};

static int exits;
static void count_exit(int code) { exits += code; }

// Constructed once per process before main: each rank must see one.
static int constructions;
static std::vector<std::string> order;
struct registry {
  std::map<std::string, int> seen;
  int rank;
  registry() : rank(-1) {
    constructions++;
    order.push_back("registry");
  }
  ~registry() {
    if (rank >= 0) std::printf("rank %d: registry destroyed after main, %zu entries\n", rank, seen.size());
  }
};
static registry reg;
struct second {
  second() { order.push_back("second"); }
};
static second after_reg;

static int &calls() {
  static int n = 100;   // a function-local static: its guard is each rank's
  return ++n;
}

thread_local int depth_seen = 0;

struct app_error : std::runtime_error {
  int code;
  app_error(const std::string &what, int c) : std::runtime_error(what), code(c) {}
};
struct deep_error : app_error {
  deep_error(const std::string &what, int c) : app_error(what, c) {}
};

static int dive(int rank, int d) {
  depth_seen++;
  if (d == 0) throw deep_error("rank " + std::to_string(rank) + " hit bottom", rank * 10);
  std::string keep(static_cast<size_t>(d), 'x');   // destroyed while unwinding
  return dive(rank, d - 1) + static_cast<int>(keep.size());
}

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int rank, size;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  reg.rank = rank;
  std::ostringstream os;

  // Static objects: this rank's own, constructed once, in order.
  reg.seen["main"] = rank;
  os << "rank " << rank << ": constructions " << constructions << " order";
  for (const auto &s : order) os << " " << s;
  os << "; local static " << calls() << " " << calls();
  os << '\n';
  std::cout << os.str() << std::flush;   // one write: the ranks share stdout (on threads, at once)

  // Exceptions: caught by a base class, after unwinding through frames; the
  // catch makes an MPI call (other ranks throw and catch meanwhile), then
  // rethrows the same exception.
  std::string caught;
  try {
    try {
      dive(rank, 3 + rank);
    } catch (const app_error &e) {
      MPI_Barrier(MPI_COMM_WORLD);
      caught = std::string("first ") + e.what();
      throw;
    }
  } catch (const deep_error &e) {
    caught += "; again " + std::string(e.what()) + " code " + std::to_string(e.code);
  }
  std::printf("rank %d: %s; depth %d\n", rank, caught.c_str(), depth_seen);

  // Thrown by libstdc++, and through a comparator inside std::sort.
  std::vector<int> v(5);
  try {
    v.at(static_cast<size_t>(rank + 7)) = 1;
  } catch (const std::out_of_range &) {
    std::printf("rank %d: out_of_range from vector::at\n", rank);
  }
  std::vector<int> w = {5, 3, 9, rank, 1, 7};
  try {
    std::sort(w.begin(), w.end(), [&](int a, int b) {
      if (a == 9 && rank % 2 == 1) throw std::invalid_argument("nine");
      return a < b;
    });
    std::printf("rank %d: sorted %d..%d\n", rank, w.front(), w.back());
  } catch (const std::invalid_argument &e) {
    std::printf("rank %d: the comparator threw %s\n", rank, e.what());
  }

  // Containers and iostreams with an MPI exchange: each rank sends its set
  // to the next.
  std::set<int> mine;
  for (int i = 0; i <= rank; i++) mine.insert(i * i);
  std::vector<int> out(mine.begin(), mine.end()), in(static_cast<size_t>(size));
  int n = static_cast<int>(out.size()), got = 0;
  MPI_Status st;
  MPI_Sendrecv(out.data(), n, MPI_INT, (rank + 1) % size, 5, in.data(), size, MPI_INT, (rank + size - 1) % size, 5,
               MPI_COMM_WORLD, &st);
  MPI_Get_count(&st, MPI_INT, &got);
  std::unique_ptr<std::ostringstream> line(new std::ostringstream);
  *line << "rank " << rank << ": got " << got << " from " << st.MPI_SOURCE << ":";
  for (int i = 0; i < got; i++) *line << " " << std::setw(3) << in[static_cast<size_t>(i)];
  double sum = 0, mysum = 0.5 * (rank + 1);
  MPI_Allreduce(&mysum, &sum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  *line << std::fixed << std::setprecision(3) << "; sum " << sum;
  std::function<int(int)> twice = [](int x) { return 2 * x; };
  dice d = {twice(rank), count_exit};
  d.exit(d.rand + 1);
  *line << "; clocks::time " << clocks::time(rank) << " dice " << d.rand << " exits " << exits;
  *line << '\n';
  std::cout << line->str() << std::flush;

  MPI_Finalize();
  return 0;
}
