/* crash.h -- a rank that crashes stops the run, naming the rank and the
 * signal, never a hang.
 *
 * tilesim-mpirun runs every rank in its own process's threads or
 * coroutines: a rank's SIGSEGV, SIGBUS, SIGFPE, SIGILL or SIGABRT (abort,
 * a failed assert) is the process's.  The handler, on a stack of its own
 * (a rank's stack may be what overflowed), writes one line
 *     tilesim-mpirun: rank 3 crashed: SIGSEGV (segmentation fault)
 * naming a stack overflow when the faulting address is just below the
 * rank's stack or on the guard page it shares with others (mp.h's
 * mp_stack: "its stack is 1 MiB; --stack sets it"), and ends the
 * process with status 128 + the signal's number.  On the threads backend
 * the handler runs only where the signal stack is (the main thread's), so a
 * rank thread's stack overflow ends the process with the signal. */
#ifndef TSMPI_CRASH_H
#define TSMPI_CRASH_H

/* Install the handler for this process; prog names it in the line. */
void crash_install(const char *prog);

#endif
