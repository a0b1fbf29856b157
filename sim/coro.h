/* coro.h -- stackful coroutines: a hand-written context switch, or ucontext.
 *
 * The simulator runs every rank as a coroutine on its own stack and switches
 * between them directly.  The switch is a few instructions of assembly on
 * x86-64 (SysV) and aarch64 (AAPCS64) ELF targets; anything else falls back to
 * POSIX ucontext (getcontext/makecontext/swapcontext, a system call per
 * switch).  Define CORO_UCONTEXT to force the fallback.
 *
 * Stacks come in sets (coro_stacks), one mapping each, so that a run of a
 * million coroutines needs a million stacks but not a million mappings.
 * Pages are reserved, not committed: a coroutine costs only the pages its
 * stack actually touches (one, for a shallow one).  Up to CORO_GUARDED
 * stacks, each has a PROT_NONE guard page below it, so an overflow faults
 * instead of writing over a neighbour.  Beyond that, guard pages would
 * exhaust vm.max_map_count (65530 mappings by default on Linux, two a
 * guard), so the stacks of a larger set share them, one per group of
 * ceil(count / CORO_GUARDED), and an overflow is caught by checks instead:
 * a soft zone of 64 KiB below each stack that only an overflow touches
 * (coro_overflowed and coro_stacks_overflowed look at it); a canary at the top of the stack below,
 * looked at whenever the coroutine switches away, which then writes to the
 * guard page, so that the overflow faults exactly where a guard page's
 * would (coro_guard); and, running on, the group's guard page.  What the
 * checks cannot see: an overflow of more than the soft zone that skips the
 * canary's 64 bytes and returns before reaching the guard page may write
 * over the stack below unnoticed until the soft zone is looked at.
 *
 * Stacks are registered with valgrind when <valgrind/valgrind.h> is there, and
 * switches are annotated for AddressSanitizer when it is on, so neither
 * reports false stack errors.
 *
 * Not thread-safe per coroutine (a coroutine belongs to one thread), but no
 * global state: threads may each run their own coroutines. */
#ifndef CORO_H
#define CORO_H

#include <stddef.h>

typedef struct coro coro;

/* A coroutine's body.  It runs on the coroutine's stack and returns the
 * coroutine to switch to when it ends: never NULL, never itself.  A finished
 * coroutine must not be switched to again. */
typedef coro *coro_fn(void *ud);

/* CORO_STACK_DEFAULT: the stack of coro_new(..., 0, ...); CORO_GUARDED:
 * the largest set whose every stack has a guard page of its own. */
enum { CORO_STACK_DEFAULT = 256 * 1024, CORO_GUARDED = 16384 };

/* A handle on the calling thread's own context (its ordinary stack), so that
 * it can switch into coroutines and be switched back to.  Free it with
 * coro_free when no coroutine will switch to it any more. */
coro *coro_main_new(void);

/* A set of `count` stacks of `stack` bytes each (0: CORO_STACK_DEFAULT),
 * rounded up to whole pages, guarded as said above.  NULL and a message in
 * err (errlen bytes, may be 0) when it cannot be mapped. */
typedef struct coro_stacks coro_stacks;
coro_stacks *coro_stacks_new(long count, size_t stack, char *err, size_t errlen);

/* A coroutine that will run fn(ud) on the set's next free stack (they are
 * taken in order); it does not start until switched to.  NULL and a
 * message when all are taken.  The set owns it: coro_free lets it go, and
 * coro_stacks_free frees it with the others. */
coro *coro_new_on(coro_stacks *set, coro_fn *fn, void *ud, char *err, size_t errlen);

/* Unmap the set, once none of its coroutines runs or will run again (the
 * coroutines that never finished are dropped without unwinding).  NULL is
 * fine. */
void coro_stacks_free(coro_stacks *set);

/* A coroutine on a set of its own: coro_new_on(coro_stacks_new(1, stack)),
 * freed with coro_free.  NULL and a message in err when the stack cannot be
 * mapped, e.g. when vm.max_map_count is reached. */
coro *coro_new(coro_fn *fn, void *ud, size_t stack, char *err, size_t errlen);

/* Suspend `from`, which must be the context running now, and resume `to`.
 * Returns when some coroutine switches back to `from`.  Callee-saved state
 * is preserved across the switch, including the floating-point control
 * state (MXCSR and the x87 control word on x86-64; d8-d15 on aarch64). */
void coro_switch(coro *from, coro *to);

/* 1 once the coroutine's body has returned. */
int coro_done(const coro *co);

/* The usable stack of a coroutine: lowest address and size in bytes.  Both
 * 0 for a coro_main_new handle. */
void coro_stack(const coro *co, void **lo, size_t *size);

/* The guard page an overflow of co faults on: just below its stack, or its
 * group's, further down.  A fault in [coro_guard(co), lo) while co runs is
 * its stack overflowing.  NULL for a coro_main_new handle. */
void *coro_guard(const coro *co);

/* 1 if a check finds that co has overflowed its stack (its soft zone
 * touched, or the canary below it overwritten): what a body asks before it
 * returns, or its owner after the fact.  Always 0 where it has a guard page
 * of its own (the fault would have said so).  A system call. */
int coro_overflowed(const coro *co);

/* The first coroutine of the set, from the from-th made on, that
 * coro_overflowed would say has overflowed (its index in the order made),
 * or -1: the whole set looked at in a system call a group.  -1 at once for
 * a set whose every stack has a guard page. */
long coro_stacks_overflowed(const coro_stacks *set, long from);

/* Free a coroutine that is not running now (the running context cannot
 * free itself): its stack with it when coro_new made it, else only the
 * set's claim on it.  A coroutine that never finished is dropped without
 * unwinding its stack: whatever it had allocated is lost.  NULL is fine. */
void coro_free(coro *co);

/* Which switch was compiled in: "x86-64 asm", "aarch64 asm" or "ucontext". */
const char *coro_backend(void);

#endif
