/* names.c -- an MPI program that uses libc's per-process names for purposes
 * of its own, as real programs do: a struct with members optarg, optind,
 * rand, exit, abort, time and getpid (the OSU micro-benchmarks have an
 * options struct with an optarg), locals named rand, time, random and
 * clock, a parameter named sleep, a global named strtok_calls; and, in the
 * same program, libc's getopt, rand, strtok, time and exit used as libc's.
 * tilesim-mpicc must compile it as any mpicc does and tilesim-mpirun run it
 * with each rank's libc state its own: the sorted output must be Open MPI's
 * (tests/cli_mpiwrap.sh).
 *   names -n WORD [-v] [ARGS] */
#define _DEFAULT_SOURCE
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

struct options {   /* as the OSU benchmarks' options */
  const char *optarg;
  int optind;
  int (*rand)(void);
  void (*exit)(int);
  int abort;
  double time;
  long getpid;
};

int strtok_calls;   /* a global of the program's */

static int four(void) { return 4; }
static int exits_seen;
static void note_exit(int code) { exits_seen += code; }

/* A parameter named sleep, a local named clock. */
static double scaled(double sleep, const struct options *o) {
  double clock = sleep * o->time;
  return clock;
}

int main(int argc, char **argv) {
  int rank, size;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);

  struct options o = {"member", 7 + rank, four, note_exit, 1, 1.5, 100};
  o.exit(rank + 1);
  {
    int rand = 10 + rank;   /* locals that hide libc's names */
    double time = 0.25 * rank;
    long random = (long)rand * 3;
    printf("rank %d: o.optarg %s o.optind %d o.rand() %d exits %d o.abort %d o.getpid %ld scaled %g\n", rank,
           o.optarg, o.optind, o.rand(), exits_seen, o.abort, o.getpid, scaled(2.0, &o));
    printf("rank %d: locals rand %d time %g random %ld\n", rank, rand, time, random);
  }

  /* libc's own, each rank's: getopt (one option per barrier), rand, strtok. */
  int c;
  const char *word = "-";
  int verbose = 0;
  opterr = 0;
  while ((c = getopt(argc, argv, "n:v")) != -1) {
    if (c == 'n') word = optarg;
    if (c == 'v') verbose = 1;
    MPI_Barrier(MPI_COMM_WORLD);
  }
  srand(77 + rank);
  int r1 = rand();
  MPI_Barrier(MPI_COMM_WORLD);
  int r2 = rand();
  char text[64] = "one two three";
  char *w = strtok(text, " ");
  MPI_Barrier(MPI_COMM_WORLD);
  for (; w; w = strtok(NULL, " ")) strtok_calls++;
  printf("rank %d: getopt -n %s -v %d optind %d of %d; rand %d %d; strtok %d words\n", rank, word, verbose, optind,
         argc, r1, r2, strtok_calls);
  time_t t0 = time(NULL);
  printf("rank %d: time() %s\n", rank, t0 != (time_t)-1 ? "ok" : "failed");
  MPI_Finalize();
  exit(rank == size - 1 ? 0 : 0);
}
