/* coro.c -- stackful coroutines: guarded mmap'ed stacks and the context switch.
 *
 * Three switches, chosen at compile time:
 *
 *   x86-64 SysV (ELF)  save rbx rbp r12-r15, MXCSR and the x87 control word
 *                      on the old stack, store rsp, load the new rsp, restore.
 *   aarch64 (ELF)      save x19-x30 and d8-d15 on the old stack, store sp,
 *                      load the new sp, restore.
 *   anything else      ucontext's swapcontext (correct, but a system call).
 *
 * Exactly the callee-saved state of each ABI: everything else the compiler
 * already assumes the call to the switch clobbers.  A new coroutine's stack
 * is laid out as if it had just called the switch, so the first switch into
 * it "returns" into a tiny boot routine that calls coro_start(co).
 *
 * AddressSanitizer must be told about every switch (it tracks which stack is
 * current); valgrind must be told where the stacks are.  Both are done here,
 * only when the tool is present. */
#define _DEFAULT_SOURCE 1 /* MAP_ANONYMOUS, MAP_NORESERVE, MAP_STACK */

#include "coro.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "xmem.h"

/* ---- which switch -------------------------------------------------------- */

#if !defined(CORO_UCONTEXT) && defined(__x86_64__) && defined(__ELF__)
#define CORO_X64 1
#elif !defined(CORO_UCONTEXT) && defined(__aarch64__) && defined(__ELF__)
#define CORO_A64 1
#else
#define CORO_UC 1
#include <ucontext.h>
#endif

/* ---- the tools ----------------------------------------------------------- */

#if defined(__SANITIZE_ADDRESS__)
#define CORO_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CORO_ASAN 1
#endif
#endif
#ifdef CORO_ASAN
#include <sanitizer/asan_interface.h>
#include <sanitizer/common_interface_defs.h>
#endif

#if defined(__has_include)
#if __has_include(<valgrind/valgrind.h>)
#include <valgrind/valgrind.h>
#define CORO_VALGRIND 1
#endif
#endif

struct coro {
#ifdef CORO_UC
  ucontext_t uc;            /* the saved context */
#else
  void *sp;                 /* the saved stack pointer (first: the asm uses it) */
#endif
  coro_fn *fn;              /* body, NULL for a coro_main_new handle */
  void *ud;
  unsigned char *map;       /* the whole mapping, guard page first; NULL for main */
  size_t maplen;
  unsigned char *lo;        /* usable stack: [lo, lo + size) */
  size_t size;
  int done;                 /* the body has returned */
  unsigned vg_id;           /* valgrind's stack id */
  coro *caller;             /* the context that last switched to this one */
  void *fake;               /* ASan's fake stack while suspended */
  const void *asan_lo;      /* this context's stack as ASan knows it */
  size_t asan_size;
};

/* ---- the switch itself --------------------------------------------------- */

#ifdef CORO_X64
/* tilesim_coro_swap(void **save, void *load): push the callee-saved
 * registers and the FP control words, *save = rsp, rsp = load, pop, ret.
 * tilesim_coro_boot: a new stack's first "return" lands here with r12 =
 * coro_start and r13 = the coroutine; rsp is 16-byte aligned, as a call
 * needs. */
__asm__(
    ".pushsection .text\n"
    ".globl tilesim_coro_swap\n"
    ".hidden tilesim_coro_swap\n"
    ".type tilesim_coro_swap,@function\n"
    ".p2align 4\n"
    "tilesim_coro_swap:\n"
    "  pushq %rbp\n"
    "  pushq %rbx\n"
    "  pushq %r12\n"
    "  pushq %r13\n"
    "  pushq %r14\n"
    "  pushq %r15\n"
    "  subq $8, %rsp\n"
    "  stmxcsr (%rsp)\n"
    "  fnstcw 4(%rsp)\n"
    "  movq %rsp, (%rdi)\n"
    "  movq %rsi, %rsp\n"
    "  ldmxcsr (%rsp)\n"
    "  fldcw 4(%rsp)\n"
    "  addq $8, %rsp\n"
    "  popq %r15\n"
    "  popq %r14\n"
    "  popq %r13\n"
    "  popq %r12\n"
    "  popq %rbx\n"
    "  popq %rbp\n"
    "  ret\n"
    ".size tilesim_coro_swap,.-tilesim_coro_swap\n"
    ".globl tilesim_coro_boot\n"
    ".hidden tilesim_coro_boot\n"
    ".type tilesim_coro_boot,@function\n"
    ".p2align 4\n"
    "tilesim_coro_boot:\n"
    "  movq %r13, %rdi\n"
    "  callq *%r12\n"
    "  ud2\n"
    ".size tilesim_coro_boot,.-tilesim_coro_boot\n"
    ".popsection\n");
#endif

#ifdef CORO_A64
/* The same for AAPCS64: a 160-byte frame of x19-x30 and d8-d15.  A new
 * stack's first "return" (x30) lands in tilesim_coro_boot with x19 =
 * coro_start and x20 = the coroutine. */
__asm__(
    ".pushsection .text\n"
    ".globl tilesim_coro_swap\n"
    ".hidden tilesim_coro_swap\n"
    ".type tilesim_coro_swap,%function\n"
    ".p2align 4\n"
    "tilesim_coro_swap:\n"
    "  sub sp, sp, #160\n"
    "  stp x19, x20, [sp, #0]\n"
    "  stp x21, x22, [sp, #16]\n"
    "  stp x23, x24, [sp, #32]\n"
    "  stp x25, x26, [sp, #48]\n"
    "  stp x27, x28, [sp, #64]\n"
    "  stp x29, x30, [sp, #80]\n"
    "  stp d8, d9, [sp, #96]\n"
    "  stp d10, d11, [sp, #112]\n"
    "  stp d12, d13, [sp, #128]\n"
    "  stp d14, d15, [sp, #144]\n"
    "  mov x9, sp\n"
    "  str x9, [x0]\n"
    "  mov sp, x1\n"
    "  ldp x19, x20, [sp, #0]\n"
    "  ldp x21, x22, [sp, #16]\n"
    "  ldp x23, x24, [sp, #32]\n"
    "  ldp x25, x26, [sp, #48]\n"
    "  ldp x27, x28, [sp, #64]\n"
    "  ldp x29, x30, [sp, #80]\n"
    "  ldp d8, d9, [sp, #96]\n"
    "  ldp d10, d11, [sp, #112]\n"
    "  ldp d12, d13, [sp, #128]\n"
    "  ldp d14, d15, [sp, #144]\n"
    "  add sp, sp, #160\n"
    "  ret\n"
    ".size tilesim_coro_swap,.-tilesim_coro_swap\n"
    ".globl tilesim_coro_boot\n"
    ".hidden tilesim_coro_boot\n"
    ".type tilesim_coro_boot,%function\n"
    ".p2align 4\n"
    "tilesim_coro_boot:\n"
    "  mov x0, x20\n"
    "  blr x19\n"
    "  brk #0\n"
    ".size tilesim_coro_boot,.-tilesim_coro_boot\n"
    ".popsection\n");
#endif

#ifndef CORO_UC
/* Defined in the assembly above (hidden symbols, not part of any header). */
void tilesim_coro_swap(void **save, void *load);
void tilesim_coro_boot(void);
#endif

const char *coro_backend(void) {
#if defined(CORO_X64)
  return "x86-64 asm";
#elif defined(CORO_A64)
  return "aarch64 asm";
#else
  return "ucontext";
#endif
}

/* Save the running context into `from` and resume `to`. */
static inline void swap(coro *from, coro *to) {
#ifdef CORO_UC
  if (swapcontext(&from->uc, &to->uc) != 0) xpanic("swapcontext: %s", strerror(errno));
#else
  tilesim_coro_swap(&from->sp, to->sp);
#endif
}

void coro_switch(coro *from, coro *to) {
#ifdef CORO_ASAN
  to->caller = from;
  __sanitizer_start_switch_fiber(&from->fake, to->asan_lo, to->asan_size);
  swap(from, to);
  /* Back in `from`: whoever switched here left its handle in from->caller. */
  __sanitizer_finish_switch_fiber(from->fake, &from->caller->asan_lo,
                                  &from->caller->asan_size);
#else
  swap(from, to);
#endif
}

/* The first code on a new stack: run the body, then switch away for good. */
static void coro_start(coro *self) {
#ifdef CORO_ASAN
  __sanitizer_finish_switch_fiber(NULL, &self->caller->asan_lo, &self->caller->asan_size);
#endif
  coro *next = self->fn(self->ud);
  if (!next || next == self) xpanic("coroutine body returned %s", next ? "itself" : "NULL");
  self->done = 1;
#ifdef CORO_ASAN
  next->caller = self;
  /* NULL: this stack is finished, ASan may drop its fake frames. */
  __sanitizer_start_switch_fiber(NULL, next->asan_lo, next->asan_size);
#endif
  swap(self, next);
  xpanic("a finished coroutine was resumed");
}

#ifdef CORO_UC
/* makecontext passes ints: the coroutine's address comes in two halves. */
static void uc_boot(unsigned hi, unsigned lo) {
  uintptr_t p = ((uintptr_t)hi << 16 << 16) | (uintptr_t)lo;
  coro_start((coro *)p);
}
#endif

/* ---- creation ------------------------------------------------------------ */

coro *coro_main_new(void) {
  coro *co = xcalloc(1, sizeof *co);
  return co;
}

static size_t page_size(void) {
  long p = sysconf(_SC_PAGESIZE);
  return p > 0 ? (size_t)p : 4096;
}

/* Lay out a fresh stack so that the first switch into it starts coro_start. */
static int init_context(coro *co, char *err, size_t errlen) {
#if defined(CORO_X64)
  uint32_t mxcsr;
  uint16_t fpucw;
  /* Inherit the creator's floating-point control state, as a new thread
   * inherits its creator's floating-point environment. */
  __asm__ volatile("stmxcsr %0" : "=m"(mxcsr));
  __asm__ volatile("fnstcw %0" : "=m"(fpucw));
  uintptr_t top = ((uintptr_t)(co->lo + co->size)) & ~(uintptr_t)15;
  uint64_t *sp = (uint64_t *)(top - 24); /* the return slot: rsp = top-16 after ret */
  sp[0] = (uint64_t)(uintptr_t)tilesim_coro_boot;
  sp[1] = sp[2] = 0;
  sp -= 7;
  sp[0] = (uint64_t)mxcsr | (uint64_t)fpucw << 32; /* stmxcsr (rsp), fnstcw 4(rsp) */
  sp[1] = 0;                                       /* r15 */
  sp[2] = 0;                                       /* r14 */
  sp[3] = (uint64_t)(uintptr_t)co;                 /* r13: the argument */
  sp[4] = (uint64_t)(uintptr_t)coro_start;         /* r12: the function */
  sp[5] = 0;                                       /* rbx */
  sp[6] = 0;                                       /* rbp: ends backtraces */
  co->sp = sp;
  (void)err, (void)errlen;
#elif defined(CORO_A64)
  uintptr_t top = ((uintptr_t)(co->lo + co->size)) & ~(uintptr_t)15;
  uint64_t *sp = (uint64_t *)(top - 160);
  memset(sp, 0, 160);
  sp[0] = (uint64_t)(uintptr_t)coro_start;  /* x19: the function */
  sp[1] = (uint64_t)(uintptr_t)co;          /* x20: the argument */
  sp[11] = (uint64_t)(uintptr_t)tilesim_coro_boot; /* x30: where ret goes */
  co->sp = sp;
  (void)err, (void)errlen;
#else
  if (getcontext(&co->uc) != 0) {
    snprintf(err, errlen, "getcontext: %s", strerror(errno));
    return -1;
  }
  co->uc.uc_stack.ss_sp = co->lo;
  co->uc.uc_stack.ss_size = co->size;
  co->uc.uc_link = NULL;
  uintptr_t p = (uintptr_t)co;
  makecontext(&co->uc, (void (*)(void))uc_boot, 2, (unsigned)(p >> 16 >> 16),
              (unsigned)(p & 0xffffffffu));
#endif
  return 0;
}

coro *coro_new(coro_fn *fn, void *ud, size_t stack, char *err, size_t errlen) {
  size_t page = page_size();
  if (!stack) stack = CORO_STACK_DEFAULT;
  if (stack > SIZE_MAX / 2) {
    snprintf(err, errlen, "coroutine stack of %zu bytes is too large", stack);
    return NULL;
  }
  size_t size = (stack + page - 1) / page * page;
  int flags = MAP_PRIVATE | MAP_ANONYMOUS;
#ifdef MAP_NORESERVE
  flags |= MAP_NORESERVE; /* pages are committed only when touched */
#endif
#ifdef MAP_STACK
  flags |= MAP_STACK;
#endif
  unsigned char *map = mmap(NULL, size + page, PROT_READ | PROT_WRITE, flags, -1, 0);
  if (map == MAP_FAILED) {
    snprintf(err, errlen, "cannot map a %zu-byte coroutine stack: %s", size + page,
             strerror(errno));
    return NULL;
  }
  if (mprotect(map, page, PROT_NONE) != 0) {
    int e = errno;
    munmap(map, size + page);
    snprintf(err, errlen,
             "cannot protect a coroutine stack's guard page: %s "
             "(too many coroutines for vm.max_map_count?)",
             strerror(e));
    return NULL;
  }
  coro *co = xcalloc(1, sizeof *co);
  co->fn = fn;
  co->ud = ud;
  co->map = map;
  co->maplen = size + page;
  co->lo = map + page;
  co->size = size;
  co->asan_lo = co->lo;
  co->asan_size = co->size;
#ifdef CORO_VALGRIND
  co->vg_id = VALGRIND_STACK_REGISTER(co->lo, co->lo + co->size);
#endif
  if (init_context(co, err, errlen) != 0) {
    coro_free(co);
    return NULL;
  }
  return co;
}

int coro_done(const coro *co) { return co->done; }

void coro_stack(const coro *co, void **lo, size_t *size) {
  *lo = co->lo;
  *size = co->size;
}

void coro_free(coro *co) {
  if (!co) return;
  if (co->map) {
#ifdef CORO_VALGRIND
    VALGRIND_STACK_DEREGISTER(co->vg_id);
#endif
#ifdef CORO_ASAN
    /* Frames left on the stack keep their redzones poisoned; clear them so
     * that memory mapped here later does not inherit them. */
    __asan_unpoison_memory_region(co->lo, co->size);
#endif
    if (munmap(co->map, co->maplen) != 0) xpanic("munmap: %s", strerror(errno));
  }
  free(co);
}
