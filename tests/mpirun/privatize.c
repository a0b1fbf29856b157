/* privatize.c -- every rank its own globals, statics and libc state
 * (tilesim-mpirun): a static counter, a global array, getopt's
 * state, the rand, random and drand48 sequences and strtok's position, each
 * used by all ranks at once with MPI calls (where the simulator switches
 * ranks) between their steps.  Each rank prints what it saw; under Open
 * MPI, every process has its own of all of these, so the sorted output must
 * be the same line for line (tests/cli_mpirun.sh).
 *   privatize -a A -b B [WORDS]: options parsed by getopt, one per barrier */
#define _DEFAULT_SOURCE
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int counter;            /* a static: every rank counts its own */
int table[64];                 /* a global array, filled with the rank */
static char text[128] = "alpha,beta;gamma,delta";

static void sync_all(void) { MPI_Barrier(MPI_COMM_WORLD); }

int main(int argc, char **argv) {
  int rank, size, bad = 0;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);

  /* The static and the global: written by each rank, read after every rank
   * has written (a shared copy would hold the last writer's). */
  for (int i = 0; i <= rank; i++) counter++;
  for (int i = 0; i < 64; i++) table[i] = rank * 1000 + i;
  sync_all();
  for (int i = 0; i < 64; i++) bad += table[i] != rank * 1000 + i;
  printf("rank %d: counter %d, table %s\n", rank, counter, bad ? "overwritten" : "its own");

  /* getopt: one option per step, a barrier between. */
  int c;
  char got[200] = "";
  opterr = 0;
  while ((c = getopt(argc, argv, "a:b:c")) != -1) {
    char one[64];
    snprintf(one, sizeof one, "%c=%s ", c, c == 'c' || c == '?' ? "-" : optarg);
    strcat(got, one);
    sync_all();
  }
  printf("rank %d: getopt %s; optind %d of %d, first operand %s\n", rank, got, optind, argc,
         optind < argc ? argv[optind] : "(none)");

  /* A second parse from the start (optind = 1) of grouped options, each
   * rank at its barrier after another number of calls (odd ranks inside
   * -cb, even ones past it): glibc's place inside a group must stay the
   * rank's own. */
  char *v2[] = {argv[0], "-cb", "two", "word", "-xa", "one", "-c", NULL};
  int steps = 0, stop = 1 + rank % 2;
  got[0] = '\0';
  optind = 1;
  while ((c = getopt(7, v2, "a:b:c")) != -1) {
    char one[64], q[2] = {(char)optopt, 0};
    snprintf(one, sizeof one, "%c=%s ", c, c == 'c' ? "-" : c == '?' ? q : optarg);
    strcat(got, one);
    if (++steps == stop) sync_all();
  }
  if (steps < stop) sync_all();
  printf("rank %d: getopt again %s; optind %d, then %s\n", rank, got, optind, optind < 7 ? v2[optind] : "(none)");

  /* The generators, seeded per rank, drawn in turns. */
  srand(rank + 1);
  srandom(rank + 101);
  srand48(rank + 1001);
  int r[4];
  long q[4];
  double d[4];
  for (int i = 0; i < 4; i++) {
    r[i] = rand();
    q[i] = random();
    d[i] = drand48();
    sync_all();
  }
  printf("rank %d: rand %d %d %d %d\n", rank, r[0], r[1], r[2], r[3]);
  printf("rank %d: random %ld %ld %ld %ld\n", rank, q[0], q[1], q[2], q[3]);
  printf("rank %d: drand48 %.17g %.17g %.17g %.17g\n", rank, d[0], d[1], d[2], d[3]);

  /* strtok, its position its own. */
  char words[200] = "";
  for (char *w = strtok(text, ",;"); w; w = strtok(NULL, ",;")) {
    strcat(words, w);
    strcat(words, " ");
    sync_all();
  }
  printf("rank %d: strtok %s\n", rank, words);

  /* Sleeping moves the clock. */
  double t0 = MPI_Wtime();
  usleep(2000);
  double t1 = MPI_Wtime();
  printf("rank %d: usleep(2000) %s\n", rank, t1 - t0 >= 0.0019999 ? "took 2 ms or more" : "took less");
  MPI_Finalize();
  return 0;
}
