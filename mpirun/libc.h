/* libc.h -- the libc a rank of an MPI program sees: its own getopt, rand,
 * drand48 and strtok state and its own exit handlers; the simulated
 * machine's clocks and sleeps; exit, _exit and abort that end a rank or the
 * run; getpid, a number of its own.
 *
 * Nothing here is named in the program's headers: when tilesim-mpirun loads
 * the program (mpirun/loader.h), each reference of its code to one of libc's
 * names below is bound to this module's function instead, and each
 * reference to getopt's variables (optind, optarg, opterr, optopt) to the
 * rank's own variable, so that the program's source means what it says and
 * any name it uses for its own purposes stays its own:
 *   getopt, getopt_long, getopt_long_only, __posix_getopt, optind, optarg,
 *     opterr, optopt;
 *   rand, srand, random, srandom, drand48, lrand48, mrand48, srand48, seed48
 *     (glibc's sequences, each rank its own);
 *   strtok (its own position);
 *   time, gettimeofday, clock_gettime, clock: simulated time (seconds from
 *     the run's start; clock counts it as processor time);
 *   sleep, usleep, nanosleep: the rank's clock moves on, its processor free;
 *   atexit, on_exit, __cxa_atexit, __cxa_finalize, __cxa_thread_atexit,
 *     __cxa_thread_atexit_impl: the rank's own handlers, run when it ends;
 *   exit: ends this rank (its handlers first); _exit, _Exit: without them;
 *   abort: stops the run; getpid: 100000 + the rank, the same on every run.
 * Each works on the calling rank's state (mp_self); called outside any rank,
 * it behaves as libc's own. */
#ifndef TSMPI_RLIBC_H
#define TSMPI_RLIBC_H

#include "mp/mp.h"

/* A rank called exit(status) or _exit(status) (run_handlers: exit, which
 * runs its handlers first): the runner's say before the rank ends (it may
 * stop the run with mp_abort instead).  The runner runs the rank's handlers
 * (rlibc_run_exit) and the program's destructors when run_handlers. */
typedef void (*rlibc_exit_fn)(mp *self, int status, int run_handlers);

/* A rank called abort(): the runner's last word before the run stops. */
typedef void (*rlibc_abort_fn)(mp *self);

/* State for n ranks, all as a fresh process has it; on_exit and on_abort
 * (or NULL) hear of every exit and abort.  Call before loading the program
 * (its variables' addresses are bound then); rlibc_free after the run. */
void rlibc_setup(int n, rlibc_exit_fn on_exit, rlibc_abort_fn on_abort);
void rlibc_free(void);

/* The per-rank variables a program may name. */
enum { RLIBC_OPTIND, RLIBC_OPTARG, RLIBC_OPTERR, RLIBC_OPTOPT, RLIBC_NVARS };

/* What the program's reference to `name` binds to in libc's place: 1 with
 * *fn (a function of this module, to be called with libc's function's
 * arguments) or with *fn NULL and *var (a per-rank variable, RLIBC_OPT*);
 * 0 for a name that stays libc's. */
typedef void (*rlibc_fn)(void);
int rlibc_bind(const char *name, rlibc_fn *fn, int *var);

/* Rank r's variable var (after rlibc_setup): where its GOT points. */
void *rlibc_var(int r, int var);

/* Run rank r's exit handlers, each once: its thread-local destructors, then
 * those of atexit, on_exit (given status) and __cxa_atexit, the last
 * registered first, as libc's exit does (a handler may register more).  On
 * the rank's own thread or coroutine. */
void rlibc_run_exit(int r, int status);

#endif
