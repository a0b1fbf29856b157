/* coro.h -- stackful coroutines: a hand-written context switch, or ucontext.
 *
 * The simulator runs every rank as a coroutine on its own stack and switches
 * between them directly.  The switch is a few instructions of assembly on
 * x86-64 (SysV) and aarch64 (AAPCS64) ELF targets; anything else falls back to
 * POSIX ucontext (getcontext/makecontext/swapcontext, a system call per
 * switch).  Define CORO_UCONTEXT to force the fallback.
 *
 * Stacks are mmap'ed with a PROT_NONE guard page below them, so an overflow
 * faults instead of writing over a neighbour.  Pages are reserved, not
 * committed: a coroutine costs only the pages its stack actually touches, so
 * 10,000 of them at the default 256 KiB are fine.  Each stack is two kernel
 * mappings (stack + guard): vm.max_map_count (65530 by default on Linux)
 * bounds the number of live coroutines at about 30,000.
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

enum { CORO_STACK_DEFAULT = 256 * 1024 };

/* A handle on the calling thread's own context (its ordinary stack), so that
 * it can switch into coroutines and be switched back to.  Free it with
 * coro_free when no coroutine will switch to it any more. */
coro *coro_main_new(void);

/* A coroutine that will run fn(ud) on a stack of `stack` bytes (0: the
 * default, CORO_STACK_DEFAULT), rounded up to whole pages, plus a guard page.
 * It does not start until switched to.  Returns NULL and fills err (errlen
 * bytes, may be 0) when the stack cannot be mapped, e.g. when
 * vm.max_map_count is reached. */
coro *coro_new(coro_fn *fn, void *ud, size_t stack, char *err, size_t errlen);

/* Suspend `from`, which must be the context running now, and resume `to`.
 * Returns when some coroutine switches back to `from`.  Callee-saved state
 * is preserved across the switch, including the floating-point control
 * state (MXCSR and the x87 control word on x86-64; d8-d15 on aarch64). */
void coro_switch(coro *from, coro *to);

/* 1 once the coroutine's body has returned. */
int coro_done(const coro *co);

/* The usable stack of a coroutine: lowest address and size in bytes (the
 * guard page lies just below lo).  Both 0 for a coro_main_new handle. */
void coro_stack(const coro *co, void **lo, size_t *size);

/* Free a coroutine that is not running now (the running context cannot
 * free itself).  A coroutine that never finished is dropped without
 * unwinding its stack: whatever it had allocated is lost.  NULL is fine. */
void coro_free(coro *co);

/* Which switch was compiled in: "x86-64 asm", "aarch64 asm" or "ucontext". */
const char *coro_backend(void);

#endif
