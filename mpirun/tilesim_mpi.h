/* tilesim_mpi.h -- included before everything else in every file tilesim-mpicc
 * compiles (-include): the libc state an MPI program relies on becomes its
 * rank's own, and the clocks and sleeps become the simulated machine's.
 *
 * tilesim-mpirun runs every rank in one process, each with its own copy of
 * the program (its globals and statics are its own), but they share libc:
 * these macros send the calls whose state or meaning is per process to the
 * runner's versions, which keep one state per rank:
 *   getopt, getopt_long, getopt_long_only, optind, optarg, opterr, optopt;
 *   rand, srand, random, srandom, drand48, lrand48, mrand48, srand48, seed48
 *     (the same sequences as glibc's, each rank its own);
 *   strtok (its own position);
 *   time, gettimeofday, clock_gettime, clock: simulated time (seconds from
 *     the run's start; clock counts it as processor time);
 *   sleep, usleep, nanosleep: the rank's clock moves on, its processor free;
 *   exit: ends this rank (after MPI_Finalize; before it, the run stops);
 *   abort: stops the run; getpid: 100000 + the rank, the same on every run.
 * Functions with arguments are renamed where they are called or declared,
 * so a variable named `time` is left alone.  A program written for
 * SimGrid's SMPI may also call smpi_execute_flops(f) (f / --flops seconds of
 * computing) and smpi_execute(s); tilesim_compute(units) charges units x c.
 * Not privatised (tilesim-mpirun(1), CAVEATS): the state of libraries other
 * than libc, lcong48, locale, signal handlers, atexit, stdio buffers (the
 * ranks share stdout: a line printed in two parts around an MPI call may be
 * split by another rank's output). */
#ifndef TILESIM_MPI_H
#define TILESIM_MPI_H

#ifdef __cplusplus
extern "C" {
#endif

/* Charge computing to the calling rank's simulated processor. */
void tilesim_compute(double units);       /* units x --c seconds */
void smpi_execute_flops(double flops);    /* flops / --flops seconds (SMPI's name) */
void smpi_execute(double seconds);        /* seconds (SMPI's name) */
void smpi_execute_benched(double seconds);

int *tsmpi_optind(void);
char **tsmpi_optarg(void);
int *tsmpi_opterr(void);
int *tsmpi_optopt(void);

#ifdef __cplusplus
}
#endif

#define getopt(...) tsmpi_getopt(__VA_ARGS__)
#define getopt_long(...) tsmpi_getopt_long(__VA_ARGS__)
#define getopt_long_only(...) tsmpi_getopt_long_only(__VA_ARGS__)
#define optind (*tsmpi_optind())
#define optarg (*tsmpi_optarg())
#define opterr (*tsmpi_opterr())
#define optopt (*tsmpi_optopt())

#define rand tsmpi_rand
#define srand(...) tsmpi_srand(__VA_ARGS__)
#define random tsmpi_random
#define srandom(...) tsmpi_srandom(__VA_ARGS__)
#define drand48 tsmpi_drand48
#define lrand48 tsmpi_lrand48
#define mrand48 tsmpi_mrand48
#define srand48(...) tsmpi_srand48(__VA_ARGS__)
#define seed48(...) tsmpi_seed48(__VA_ARGS__)

#define strtok(...) tsmpi_strtok(__VA_ARGS__)

#define time(...) tsmpi_time(__VA_ARGS__)
#define gettimeofday(...) tsmpi_gettimeofday(__VA_ARGS__)
#define clock_gettime(...) tsmpi_clock_gettime(__VA_ARGS__)
#define clock tsmpi_clock
#define sleep(...) tsmpi_sleep(__VA_ARGS__)
#define usleep(...) tsmpi_usleep(__VA_ARGS__)
#define nanosleep(...) tsmpi_nanosleep(__VA_ARGS__)

#define exit(...) tsmpi_exit(__VA_ARGS__)
#define abort tsmpi_abort
#define getpid tsmpi_getpid

#endif
