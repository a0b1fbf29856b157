/* coro.c -- stackful coroutines: sets of stacks in one mapping, and the context switch.
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

#include "sim/coro.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "util/xmem.h"

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

struct coro_stacks {
  unsigned char *map;       /* one mapping for every stack */
  size_t maplen;
  size_t page;
  size_t size;              /* usable bytes of each stack, whole pages */
  size_t soft;              /* the untouched zone below each stack (0: guarded) */
  size_t slot;              /* a page, soft and size: every stack's stride */
  long group;               /* stacks above each guard page */
  long count, made;         /* stacks, and coroutines made on them */
  coro *cos;                /* count coroutines, made in order */
};

struct coro {
#ifdef CORO_UC
  ucontext_t uc;            /* the saved context */
#else
  void *sp;                 /* the saved stack pointer (first: the asm uses it) */
#endif
  const uint64_t *watch;    /* the canary below this stack, checked when it
                               switches away; NULL where a guard page is */
  coro_fn *fn;              /* body, NULL for a coro_main_new handle */
  void *ud;
  coro_stacks *own;         /* coro_new's private set of one, freed with it */
  coro_stacks *set;         /* the set it lives on; NULL for main */
  unsigned char *guard;     /* the guard page an overflow reaches first */
  unsigned char *soft;      /* its soft zone: [soft, lo), untouched unless overflowed */
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

/* ---- overflow checks where stacks share a guard page ---------------------- */

/* The canary at the top of each stack of a set with shared guards: the
 * cache line there, CANARY_WORDS words of values a program does not write
 * by chance, different at every address. */
enum { CANARY_WORDS = 8 };

static inline uint64_t canary_at(const uint64_t *p) {
  return ((uint64_t)(uintptr_t)p * 0x9e3779b97f4a7c15u) ^ 0x74696c6573696d21u;
}

/* 1 if the canary line at c is intact. */
static inline int canary_ok(const uint64_t *c) {
  uint64_t diff = 0;
  for (int k = 0; k < CANARY_WORDS; k++) diff |= c[k] ^ canary_at(c + k);
  return diff == 0;
}

/* co has overflowed its stack: fault on its guard page, exactly as the
 * overflow would have had it run on, so that a crash handler names it as
 * a guard page's fault (coro_guard). */
static void overflowed(const coro *co) {
  *(volatile unsigned char *)co->guard = 1;
  xpanic("a coroutine overflowed its stack of %zu bytes", co->size);
}

/* Has co written its soft zone?  Its pages are never touched otherwise;
 * mincore says which are resident. */
static int soft_touched(const coro *co) {
  size_t len = (size_t)(co->lo - co->soft);
  if (len == 0) return 0;
  unsigned char vec[256];
  size_t pages = len / co->set->page;
  if (pages > sizeof vec) pages = sizeof vec, len = pages * co->set->page;
  if (mincore(co->soft, len, vec) != 0) return 0;
  for (size_t i = 0; i < pages; i++)
    if (vec[i] & 1) return 1;
  return 0;
}

static inline void check(const coro *co) {
  if (co->watch && !canary_ok(co->watch)) overflowed(co);
}

void coro_switch(coro *from, coro *to) {
  check(from);
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
  check(self);
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

/* Lay out a fresh stack so that the first switch into it starts
 * coro_start; its frames begin below top. */
static int init_context(coro *co, uintptr_t top, char *err, size_t errlen) {
#if defined(CORO_X64)
  uint32_t mxcsr;
  uint16_t fpucw;
  /* Inherit the creator's floating-point control state, as a new thread
   * inherits its creator's floating-point environment. */
  __asm__ volatile("stmxcsr %0" : "=m"(mxcsr));
  __asm__ volatile("fnstcw %0" : "=m"(fpucw));
  top &= ~(uintptr_t)15;
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
  top &= ~(uintptr_t)15;
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
  co->uc.uc_stack.ss_size = (size_t)((unsigned char *)top - co->lo);
  co->uc.uc_link = NULL;
  uintptr_t p = (uintptr_t)co;
  makecontext(&co->uc, (void (*)(void))uc_boot, 2, (unsigned)(p >> 16 >> 16),
              (unsigned)(p & 0xffffffffu));
#endif
  return 0;
}

/* ---- sets of stacks -------------------------------------------------------
 *
 * One mapping holds every stack of a set.  Up to CORO_GUARDED stacks, each
 * has a guard page of its own below it; a larger set has one guard page
 * per group of g = ceil(count / CORO_GUARDED) stacks, and each stack a soft
 * zone of SOFT_ZONE bytes below it that nothing but an overflow touches:
 *
 *   guarded:  | guard | stack 0 | guard | stack 1 | ...
 *   grouped:  | guard | soft | stack 0 | page | soft | stack 1 | ... (g) | guard | soft | ...
 *
 * so a set costs about 2 * CORO_GUARDED kernel mappings at most, whatever
 * its size.  Every slot is a page, a soft zone and a stack, so that the
 * stacks lie at one stride: the processor's stride prefetcher then fetches
 * the next rank's stack ahead of the switch (doc/measurements.md,
 * 2026-12-01: with a guard page every other stack the stride alternated,
 * and a ring of 30,000 ranks ran about twice as slow).  A grouped stack's
 * overflow is caught three ways: running on,
 * it faults on its group's guard page; reaching the top of the stack below
 * (a canary there, checked at every switch away), it is made to fault
 * there; staying within its soft zone, it harms no other stack, and
 * coro_overflowed (one stack) or coro_stacks_overflowed (a whole set, a
 * system call a group) finds the zone touched (mincore) when asked. */

enum { SOFT_ZONE = 64 * 1024, CANARY_ROOM = CANARY_WORDS * 8 };

/* ASan keeps a shadow byte for every 8 bytes: forget what it knew of the
 * set's stacks (frames left poisoned by coroutines that never finished)
 * without touching the shadow pages that were never written. */
static void forget_poison(unsigned char *p, size_t len, size_t page) {
#ifdef CORO_ASAN
  size_t scale, off;
  __asan_get_shadow_mapping(&scale, &off);
  uintptr_t s0 = ((uintptr_t)p >> scale) + off, s1 = (((uintptr_t)p + len) >> scale) + off;
  uintptr_t a0 = (s0 + page - 1) & ~(uintptr_t)(page - 1), a1 = s1 & ~(uintptr_t)(page - 1);
  if (a1 > a0 && madvise((void *)a0, a1 - a0, MADV_DONTNEED) == 0) {
    __asan_unpoison_memory_region(p, (a0 - s0) << scale);
    __asan_unpoison_memory_region((void *)((a1 - off) << scale), (s1 - a1) << scale);
  } else {
    __asan_unpoison_memory_region(p, len);
  }
#else
  (void)p, (void)len, (void)page;
#endif
}

coro_stacks *coro_stacks_new(long count, size_t stack, char *err, size_t errlen) {
  size_t page = page_size();
  if (!stack) stack = CORO_STACK_DEFAULT;
  if (count < 1 || stack > SIZE_MAX / 4) {
    snprintf(err, errlen, "%ld coroutine stacks of %zu bytes: not a size", count, stack);
    return NULL;
  }
  size_t size = (stack + page - 1) / page * page;
  long group = count <= CORO_GUARDED ? 1 : (count + CORO_GUARDED - 1) / CORO_GUARDED;
  size_t soft = group > 1 ? (SOFT_ZONE + page - 1) / page * page : 0;
  size_t slot = page + soft + size;
  long groups = (count + group - 1) / group;
  if ((size_t)count > (SIZE_MAX / 2) / slot) {
    snprintf(err, errlen, "%ld coroutine stacks of %zu bytes: more than the address space", count, stack);
    return NULL;
  }
  size_t maplen = (size_t)count * slot;
  int flags = MAP_PRIVATE | MAP_ANONYMOUS;
#ifdef MAP_NORESERVE
  flags |= MAP_NORESERVE; /* pages are committed only when touched */
#endif
#ifdef MAP_STACK
  flags |= MAP_STACK;
#endif
  unsigned char *map = mmap(NULL, maplen, PROT_READ | PROT_WRITE, flags, -1, 0);
  if (map == MAP_FAILED) {
    snprintf(err, errlen, "cannot map %ld coroutine stack%s (%zu bytes): %s", count,
             count == 1 ? "" : "s", maplen, strerror(errno));
    return NULL;
  }
#ifdef MADV_NOHUGEPAGE
  /* A huge page would commit 2 MiB where a stack touches 4 KiB. */
  madvise(map, maplen, MADV_NOHUGEPAGE);
#endif
  for (long g = 0; g < groups; g++) {
    if (mprotect(map + (size_t)(g * group) * slot, page, PROT_NONE) != 0) {
      int e = errno;
      munmap(map, maplen);
      snprintf(err, errlen,
               "cannot protect a coroutine stack's guard page: %s "
               "(too many mappings for vm.max_map_count?)",
               strerror(e));
      return NULL;
    }
  }
  coro_stacks *set = xmalloc(sizeof *set);
  *set = (coro_stacks){.map = map, .maplen = maplen, .page = page, .size = size, .soft = soft,
                       .slot = slot, .group = group, .count = count,
                       .cos = xcalloc((size_t)count, sizeof *set->cos)};
  return set;
}

coro *coro_new_on(coro_stacks *set, coro_fn *fn, void *ud, char *err, size_t errlen) {
  if (set->made == set->count) {
    snprintf(err, errlen, "all %ld coroutine stacks of the set are taken", set->count);
    return NULL;
  }
  long i = set->made, g = i / set->group, j = i % set->group;
  coro *co = &set->cos[i];
  memset(co, 0, sizeof *co);
  co->fn = fn;
  co->ud = ud;
  co->set = set;
  unsigned char *base = set->map + (size_t)i * set->slot;
  co->guard = set->map + (size_t)(g * set->group) * set->slot;
  co->soft = j == 0 ? base + set->page : base;   /* a page above another stack is soft too */
  co->lo = base + set->page + set->soft;
  co->size = set->size;
  co->asan_lo = co->lo;
  co->asan_size = co->size;
  uintptr_t top = (uintptr_t)(co->lo + co->size);
  if (set->group > 1) {
    /* Grouped: a canary at the top for the stack above, and one to watch
     * below, unless the group's guard page is there. */
    top -= CANARY_ROOM;
    uint64_t *c = (uint64_t *)(co->lo + co->size) - CANARY_WORDS;
    for (int k = 0; k < CANARY_WORDS; k++) c[k] = canary_at(c + k);
    if (j > 0) co->watch = (const uint64_t *)co->soft - CANARY_WORDS;
  }
#ifdef CORO_VALGRIND
  co->vg_id = VALGRIND_STACK_REGISTER(co->lo, co->lo + co->size);
#endif
  if (init_context(co, top, err, errlen) != 0) {
#ifdef CORO_VALGRIND
    VALGRIND_STACK_DEREGISTER(co->vg_id);
#endif
    return NULL;
  }
  set->made++;
  return co;
}

void coro_stacks_free(coro_stacks *set) {
  if (!set) return;
  /* The shadow first, while the range is still ours: once unmapped, other
   * threads may be given it. */
  forget_poison(set->map, set->maplen, set->page);
  if (munmap(set->map, set->maplen) != 0) xpanic("munmap: %s", strerror(errno));
  free(set->cos);
  free(set);
}

coro *coro_new(coro_fn *fn, void *ud, size_t stack, char *err, size_t errlen) {
  coro_stacks *set = coro_stacks_new(1, stack, err, errlen);
  if (!set) return NULL;
  coro *co = coro_new_on(set, fn, ud, err, errlen);
  if (!co) {
    coro_stacks_free(set);
    return NULL;
  }
  co->own = set;
  return co;
}

int coro_done(const coro *co) { return co->done; }

void coro_stack(const coro *co, void **lo, size_t *size) {
  *lo = co->lo;
  *size = co->size;
}

void *coro_guard(const coro *co) { return co->guard; }

int coro_overflowed(const coro *co) {
  if (!co->set) return 0;
  return (co->watch && !canary_ok(co->watch)) || soft_touched(co);
}

long coro_stacks_overflowed(const coro_stacks *set, long from) {
  if (!set || set->group == 1 || from < 0) return -1;
  size_t per = set->slot / set->page;   /* pages a slot */
  unsigned char *vec = NULL;
  long found = -1;
  for (long g = from / set->group; found < 0 && g * set->group < set->made; g++) {
    long first = g * set->group, n = set->made - first < set->group ? set->made - first : set->group;
    unsigned char *base = set->map + (size_t)first * set->slot;
    if (!vec) vec = xmalloc((size_t)set->group * per);
    /* One call for the group: its slots, soft zones and stacks. */
    if (mincore(base, (size_t)n * set->slot, vec) != 0) xpanic("mincore: %s", strerror(errno));
    for (long j = first < from ? from - first : 0; found < 0 && j < n; j++) {
      const coro *co = &set->cos[first + j];
      int hit = co->watch && !canary_ok(co->watch);
      size_t k0 = (size_t)(co->soft - base) / set->page, k1 = (size_t)(co->lo - base) / set->page;
      for (size_t k = k0; !hit && k < k1; k++) hit = vec[k] & 1;
      if (hit) found = first + j;
    }
  }
  free(vec);
  return found;
}

void coro_free(coro *co) {
  if (!co) return;
  if (!co->set) {   /* a coro_main_new handle */
    free(co);
    return;
  }
#ifdef CORO_VALGRIND
  VALGRIND_STACK_DEREGISTER(co->vg_id);
#endif
  coro_stacks_free(co->own);   /* its own set, or none: a set's stacks go with the set */
}
