/* libc.h -- the libc a rank of an MPI program sees through tilesim_mpi.h:
 * its own getopt, rand, drand48 and strtok state; the simulated machine's
 * clocks and sleeps; exit and abort that end a rank or the run.
 *
 * The functions are the targets of tilesim_mpi.h's macros: tilesim-mpirun
 * exports them to the programs it loads.  Each works on the calling rank's
 * state (mp_self); called outside any rank (a constructor of the program),
 * it behaves as libc's own. */
#ifndef TSMPI_LIBC_H
#define TSMPI_LIBC_H

#include <getopt.h>
#include <sys/time.h>
#include <sys/types.h>
#include <time.h>

#include "mp.h"

/* A rank called exit(status) (tsmpi_exit): the runner's say before the rank
 * ends (it may stop the run with mp_abort instead). */
typedef void (*tsmpi_exit_fn)(mp *self, int status);

/* A rank called abort() (tsmpi_abort): the runner's last word before the
 * run stops. */
typedef void (*tsmpi_abort_fn)(mp *self);

/* State for n ranks, all as a fresh process has it; on_exit and on_abort
 * (or NULL) hear of every exit and abort.  Call before a run;
 * tsmpi_libc_free after it. */
void tsmpi_libc_setup(int n, tsmpi_exit_fn on_exit, tsmpi_abort_fn on_abort);
void tsmpi_libc_free(void);

int *tsmpi_optind(void);
char **tsmpi_optarg(void);
int *tsmpi_opterr(void);
int *tsmpi_optopt(void);
int tsmpi_getopt(int argc, char *const *argv, const char *shortopts);
int __posix_getopt(int argc, char *const *argv, const char *shortopts);   /* glibc's POSIX-mode getopt */
int tsmpi_getopt_long(int argc, char *const *argv, const char *shortopts, const struct option *longopts,
                      int *longind);
int tsmpi_getopt_long_only(int argc, char *const *argv, const char *shortopts, const struct option *longopts,
                           int *longind);

int tsmpi_rand(void);
void tsmpi_srand(unsigned seed);
long tsmpi_random(void);
void tsmpi_srandom(unsigned seed);
double tsmpi_drand48(void);
long tsmpi_lrand48(void);
long tsmpi_mrand48(void);
void tsmpi_srand48(long seed);
unsigned short *tsmpi_seed48(unsigned short seed16v[3]);

char *tsmpi_strtok(char *restrict str, const char *restrict delim);

time_t tsmpi_time(time_t *t);
int tsmpi_gettimeofday(struct timeval *restrict tv, void *restrict tz);
int tsmpi_clock_gettime(clockid_t id, struct timespec *tp);
clock_t tsmpi_clock(void);
unsigned tsmpi_sleep(unsigned seconds);
int tsmpi_usleep(unsigned us);   /* useconds_t: unsigned int */
int tsmpi_nanosleep(const struct timespec *req, struct timespec *rem);

_Noreturn void tsmpi_exit(int status);
_Noreturn void tsmpi_abort(void);
pid_t tsmpi_getpid(void);

#endif
