/* loader.c -- the program loaded once, each rank with its own writable copy
 * (loader.h).
 *
 * The image of a rank r is the program's address range [ro_lo, rw_hi) moved
 * by base(r).  Its read-only span [ro_lo, ro_hi) and writable span [rw_lo,
 * rw_hi) lie D = rw_lo - ro_lo apart.  With S the larger span, ranks go in
 * groups of m = D / S, and a group's images interleave:
 *
 *   G: | RO 0 | RO 1 | .. | RO m-1 |  ..  | RW 0 | RW 1 | .. | RW m-1 | G': ...
 *      <------------ D ------------------>
 *
 * so that rank j of a group starts at G + j S, every rank's RW lies D after
 * its RO, and the group's RW copies are one anonymous mapping.  The RO
 * copies come from the memory file, which holds c copies of the RO span,
 * each in S bytes: c consecutive ranks of a group share one mapping of it.
 * c is 1 unless the ranks are so many that the mappings would crowd
 * vm.max_map_count. */
#define _GNU_SOURCE
#include "mpirun/loader.h"

#include <dlfcn.h>
#include <elf.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "util/atomicfile.h"
#include "mpirun/cxx.h"
#include "mpirun/elfprog.h"
#include "mpirun/libc.h"
#include "mp/mp.h"
#include "util/xmem.h"

/* ==== relocations ========================================================= */

enum { RK_NONE, RK_RELATIVE, RK_ABS, RK_IREL, RK_DTPMOD, RK_DTPOFF, RK_TPOFF, RK_TLSDESC, RK_COPY, RK_UNKNOWN };

/* What a relocation of the machine's type t does. */
static int kind_of(int machine, uint32_t t) {
  if (machine == EM_X86_64) switch (t) {
    case R_X86_64_NONE: return RK_NONE;
    case R_X86_64_RELATIVE: return RK_RELATIVE;
    case R_X86_64_64: case R_X86_64_GLOB_DAT: case R_X86_64_JUMP_SLOT: return RK_ABS;
    case R_X86_64_IRELATIVE: return RK_IREL;
    case R_X86_64_DTPMOD64: return RK_DTPMOD;
    case R_X86_64_DTPOFF64: return RK_DTPOFF;
    case R_X86_64_TPOFF64: return RK_TPOFF;
    case R_X86_64_TLSDESC: return RK_TLSDESC;
    case R_X86_64_COPY: return RK_COPY;
    default: return RK_UNKNOWN;
    }
  if (machine == EM_AARCH64) switch (t) {
    case R_AARCH64_NONE: case 256: return RK_NONE;
    case R_AARCH64_RELATIVE: return RK_RELATIVE;
    case R_AARCH64_ABS64: case R_AARCH64_GLOB_DAT: case R_AARCH64_JUMP_SLOT: return RK_ABS;
    case R_AARCH64_IRELATIVE: return RK_IREL;
    case R_AARCH64_TLS_DTPMOD: return RK_DTPMOD;
    case R_AARCH64_TLS_DTPREL: return RK_DTPOFF;
    case R_AARCH64_TLS_TPREL: return RK_TPOFF;
    case R_AARCH64_TLSDESC: return RK_TLSDESC;
    case R_AARCH64_COPY: return RK_COPY;
    default: return RK_UNKNOWN;
    }
  return RK_UNKNOWN;
}

/* What a name is bound to. */
enum { B_UNSET, B_OWN, B_ABS, B_VAR, B_ZERO, B_TLS };
typedef struct {
  int kind;
  uint64_t val;   /* B_OWN: an image address; B_ABS: an address; B_TLS: an offset in the block; B_VAR: the var */
} binding;

typedef struct {
  uint64_t off;   /* in the writable span */
  int var;        /* RLIBC_OPT* */
  int64_t add;
} rankfix;

typedef struct {
  const char *name;   /* as the program names it (DT_NEEDED) */
  void *h;            /* dlopen's handle */
} library;

struct loader {
  elf_prog e;
  char *path;
  int n;
  size_t page;
  uint64_t ro_lo, ro_hi, rw_lo, rw_hi;   /* the spans, page-aligned */
  size_t S, D, gstride;                  /* rank and group strides, the spans' distance */
  int m, c;                              /* ranks a group, copies in the memory file */
  long mappings;
  unsigned char *res;                    /* every group's address range */
  size_t reslen;
  unsigned char *tmpl;                   /* the writable span, relocated for base 0 */
  size_t tlen;
  unsigned char *used;                   /* [pages]: the template's page is not all zeros */
  uint64_t *basefix;                     /* words of the span that hold an address of the image */
  size_t nbase, capbase;
  rankfix *rfix;                         /* words that hold the address of a rank's variable */
  size_t nrfix, caprfix;
  binding *bind;                         /* [nsyms] */
  library *libs;
  int nlibs;
  unsigned char *made, *ended;           /* [n]: the rank's copy is made; its destructors ran */
  void **tls, **tls_raw;                 /* [n + 1]: each rank's thread-local block once used, and
                                            what to free; the last outside any rank */
  const void **eh;                       /* [n + 1]: each rank's .eh_frame, registered */
  void *eh_object;
  void *(*deregister)(const void *);
  int cxx;
};

static loader *the;   /* for __tls_get_addr: one loader at a time */

static uintptr_t base(const loader *l, int r) {
  return (uintptr_t)l->res + (size_t)(r / l->m) * l->gstride + (size_t)(r % l->m) * l->S - l->ro_lo;
}

static uint64_t get64(const unsigned char *p) {
  uint64_t v;
  memcpy(&v, p, 8);
  return v;
}

static void put64(unsigned char *p, uint64_t v) { memcpy(p, &v, 8); }

/* ==== thread-local variables ============================================== */

typedef struct {
  unsigned long module, offset;
} tls_index;

/* The program's thread-local block for rank r (-1: outside a rank): its
 * template from the rank's image, the rest zeros (calloc's: a large block
 * costs the pages the rank writes); the block starts at the same place in
 * its alignment as the template does in the image.  *raw: what to free. */
static size_t tls_align(const loader *l) { return l->e.tls_align < sizeof(void *) ? sizeof(void *) : l->e.tls_align; }

/* Where the template starts in its first aligned unit. */
static size_t tls_first(const loader *l) { return l->e.tls_vaddr & (tls_align(l) - 1); }

static void *tls_block(loader *l, int r, void **raw) {
  size_t align = tls_align(l), first = tls_first(l);
  size_t size = first + l->e.tls_memsz;
  unsigned char *b = calloc(1, size + align);
  if (!b) xpanic("no memory for a rank's thread-local variables (%zu bytes)", size);
  *raw = b;
  b += (align - (uintptr_t)b % align) % align;
  memcpy(b + first, (const void *)(base(l, r < 0 ? 0 : r) + l->e.tls_vaddr), l->e.tls_filesz);
  return b + first;
}

/* The program's __tls_get_addr: its variable at ti->offset in the calling
 * rank's block. */
static void *tls_get_addr(tls_index *ti) {
  loader *l = the;
  mp *self = mp_self();
  int r = self ? mp_rank(self) : -1;
  int i = r >= 0 && r < l->n ? r : l->n;   /* the last slot: outside a rank */
  if (!l->tls[i]) l->tls[i] = tls_block(l, r, &l->tls_raw[i]);
  return (char *)l->tls[i] + ti->offset;
}

/* ==== libraries and names ================================================= */

/* name in the folder of a DT_RUNPATH entry ($ORIGIN: the program's), if a
 * file is there. */
static char *in_runpath(const loader *l, const char *name) {
  if (!l->e.runpath || strchr(name, '/')) return NULL;
  char origin[PATH_MAX];
  if (!realpath(l->path, origin)) snprintf(origin, sizeof origin, "%s", l->path);
  char *slash = strrchr(origin, '/');
  if (slash) *slash = 0;
  else snprintf(origin, sizeof origin, ".");
  const char *p = l->e.runpath;
  while (*p) {
    size_t k = strcspn(p, ":");
    char dir[PATH_MAX], full[2 * PATH_MAX];
    snprintf(dir, sizeof dir, "%.*s", (int)k, p);
    if (strncmp(dir, "$ORIGIN", 7) == 0) snprintf(full, sizeof full, "%s%s/%s", origin, dir + 7, name);
    else snprintf(full, sizeof full, "%s/%s", dir, name);
    if (k && access(full, R_OK) == 0) return xstrdup(full);
    p += k + (p[k] == ':');
  }
  return NULL;
}

/* Every library the program needs but tilesim's own: already in the process
 * (libc, libm) or loaded now (libstdc++, ...), once for all the ranks. */
static int load_libraries(loader *l, char *err, size_t errlen) {
  l->libs = xcalloc((size_t)l->e.nneeded + 1, sizeof *l->libs);
  for (int i = 0; i < l->e.nneeded; i++) {
    const char *name = l->e.needed[i];
    if (strcmp(name, ELF_TILESIM_LIB) == 0) continue;
    library *lib = &l->libs[l->nlibs];
    lib->name = name;
    lib->h = dlopen(name, RTLD_NOW | RTLD_NOLOAD);
    if (!lib->h) {
      char *full = in_runpath(l, name);
      dlerror();
      lib->h = dlopen(full ? full : name, RTLD_NOW | RTLD_LOCAL);
      free(full);
      if (!lib->h) {
        const char *why = dlerror();
        snprintf(err, errlen, "%s needs %s, which cannot be loaded: %s", l->path, name, why ? why : "?");
        return -1;
      }
    }
    l->nlibs++;
  }
  return 0;
}

static void *lookup_in(void *h, const char *name, const char *version) {
#ifdef __GLIBC__
  if (version) return dlvsym(h, name, version);
#else
  (void)version;
#endif
  return dlsym(h, name);
}

/* A name from the libraries, in the order a process of the program's own
 * would search them: the process's (tilesim-mpirun's exports, libc, libm),
 * then the program's libraries; the version it asks for, else any. */
static void *lookup(const loader *l, const elf_sym *s) {
  void *a = lookup_in(RTLD_DEFAULT, s->name, s->version);
#ifdef __GLIBC__
  /* An interposer earlier in the search order wins, as ld.so lets an
   * unversioned definition satisfy a versioned reference: the sanitizer's
   * malloc and free in make check's build, a preloaded allocator.  (dlvsym
   * alone skips them: a program's malloc was glibc's while the runner's was
   * the sanitizer's, and glibc's arena count failed an assertion as a
   * rank's thread ended.) */
  void *first = a && s->version ? dlsym(RTLD_DEFAULT, s->name) : NULL;
  Dl_info in_a, in_first;
  if (first && first != a && dladdr(a, &in_a) && dladdr(first, &in_first) && in_a.dli_fbase != in_first.dli_fbase)
    a = first;
#endif
  for (int i = 0; !a && i < l->nlibs; i++) a = lookup_in(l->libs[i].h, s->name, s->version);
  if (!a && s->version) a = lookup_in(RTLD_DEFAULT, s->name, NULL);
  for (int i = 0; !a && s->version && i < l->nlibs; i++) a = lookup_in(l->libs[i].h, s->name, NULL);
  return a;
}

/* What symbol k is bound to (once), or -1 and a message. */
static int resolve(loader *l, uint32_t k, binding *b, char *err, size_t errlen) {
  if (l->bind[k].kind != B_UNSET) {
    *b = l->bind[k];
    return 0;
  }
  const elf_sym *s = &l->e.syms[k];
  rlibc_fn fn = NULL;
  int var = -1;
  if (s->defined) {
    *b = (binding){s->tls ? B_TLS : B_OWN, s->value};
  } else if (rlibc_bind(s->name, &fn, &var) || cxx_bind(s->name, &fn)) {
    *b = fn ? (binding){B_ABS, (uint64_t)(uintptr_t)fn} : (binding){B_VAR, (uint64_t)var};
  } else if (strcmp(s->name, "__tls_get_addr") == 0) {
    *b = (binding){B_ABS, (uint64_t)(uintptr_t)tls_get_addr};
  } else {
    void *a = lookup(l, s);
    if (a) {
      *b = (binding){B_ABS, (uint64_t)(uintptr_t)a};
    } else if (s->weak) {
      *b = (binding){B_ZERO, 0};
    } else {
      if (s->version)
        snprintf(err, errlen, "%s needs %s (version %s%s%s), which neither tilesim-mpirun nor the program's "
                 "libraries define", l->path, s->name, s->version, s->lib ? " of " : "", s->lib ? s->lib : "");
      else
        snprintf(err, errlen, "%s needs %s, which neither tilesim-mpirun nor the program's libraries define",
                 l->path, s->name);
      return -1;
    }
  }
  l->bind[k] = *b;
  return 0;
}

/* ==== the template ======================================================== */

static void add_basefix(loader *l, uint64_t off) {
  if (l->nbase == l->capbase) l->basefix = xreallocarray(l->basefix, l->capbase = l->capbase ? 2 * l->capbase : 64, 8);
  l->basefix[l->nbase++] = off;
}

static int fail_rel(const loader *l, const elf_rel *r, const char *why, char *err, size_t errlen) {
  const char *name = r->sym ? l->e.syms[r->sym].name : "";
  snprintf(err, errlen, "%s: %s%s%s (relocation type %u at 0x%llx)", l->path, why, *name ? ": " : "", name, r->type,
           (unsigned long long)r->offset);
  return -1;
}

/* The writable span's bytes, every relocation applied for base 0: words that
 * hold an address of the image are listed to have base(r) added, those
 * that hold a rank's variable's address to get it.  IRELATIVE ones are left
 * for run_resolvers (their resolvers run in rank 0's image). */
static int make_template(loader *l, char *err, size_t errlen) {
  l->tlen = l->rw_hi - l->rw_lo;
  l->tmpl = xcalloc(l->tlen ? l->tlen : 1, 1);
  for (int i = 0; i < l->e.nsegs; i++) {
    const elf_seg *s = &l->e.segs[i];
    if (s->writable) memcpy(l->tmpl + (s->vaddr - l->rw_lo), l->e.bytes + s->offset, s->filesz);
  }
  l->bind = xcalloc(l->e.nsyms + 1, sizeof *l->bind);
  for (size_t i = 0; i < l->e.nrels; i++) {
    const elf_rel *r = &l->e.rels[i];
    int kind = kind_of(l->e.machine, r->type);
    if (kind == RK_NONE) continue;
    if (kind == RK_UNKNOWN) return fail_rel(l, r, "a relocation the loader does not know", err, errlen);
    if (r->offset < l->rw_lo || r->offset - l->rw_lo + 8 > l->tlen)
      return fail_rel(l, r, "a relocation of its read-only part (compile every file with -fPIC: tilesim-mpicc does)",
                      err, errlen);
    unsigned char *at = l->tmpl + (r->offset - l->rw_lo);
    binding b = {B_ZERO, 0};
    if (r->sym && resolve(l, r->sym, &b, err, errlen) != 0) return -1;
    switch (kind) {
    case RK_RELATIVE:
      put64(at, (uint64_t)r->addend);
      add_basefix(l, r->offset - l->rw_lo);
      break;
    case RK_ABS:
      if (b.kind == B_VAR) {
        if (l->nrfix == l->caprfix) l->rfix = xreallocarray(l->rfix, l->caprfix = l->caprfix ? 2 * l->caprfix : 8, sizeof *l->rfix);
        l->rfix[l->nrfix++] = (rankfix){r->offset - l->rw_lo, (int)b.val, r->addend};
      } else if (b.kind == B_TLS) {
        return fail_rel(l, r, "the address of a thread-local variable", err, errlen);
      } else {
        put64(at, b.val + (uint64_t)r->addend);
        if (b.kind == B_OWN) add_basefix(l, r->offset - l->rw_lo);
      }
      break;
    case RK_IREL:
      put64(at, 0);
      break;
    case RK_DTPMOD:
      if (r->sym && b.kind != B_TLS)
        return fail_rel(l, r, "a thread-local variable of a library, which the loader cannot give each rank", err,
                        errlen);
      put64(at, 1);   /* the program's own module: tls_get_addr reads only the offset */
      break;
    case RK_DTPOFF:
      put64(at, (r->sym ? b.val : 0) + (uint64_t)r->addend);
      break;
    case RK_TPOFF:
    case RK_TLSDESC:
      return fail_rel(l, r, "thread-local variables in the initial-exec or descriptor model (compile with -fPIC and "
                      "-ftls-model=global-dynamic)", err, errlen);
    case RK_COPY:
      if (b.kind != B_ABS)
        return fail_rel(l, r, "a copied libc variable that is each rank's own (compile every file with -fPIC: "
                        "tilesim-mpicc does)", err, errlen);
      if (l->e.syms[r->sym].size > l->tlen - (r->offset - l->rw_lo))
        return fail_rel(l, r, "a copy larger than the writable part", err, errlen);
      memcpy(at, (const void *)(uintptr_t)b.val, l->e.syms[r->sym].size);
      break;
    default: break;
    }
  }
  return 0;
}

/* Which of the template's pages a rank's copy must be written: those with
 * a byte not zero, or a word to fix. */
static void mark_used(loader *l) {
  size_t np = (l->tlen + l->page - 1) / l->page;
  free(l->used);
  l->used = xcalloc(np + 1, 1);
  for (size_t p = 0; p < np; p++) {
    size_t lo = p * l->page, hi = lo + l->page < l->tlen ? lo + l->page : l->tlen;
    for (size_t i = lo; i < hi && !l->used[p]; i++) l->used[p] = l->tmpl[i] != 0;
  }
  for (size_t i = 0; i < l->nbase; i++) l->used[l->basefix[i] / l->page] = l->used[(l->basefix[i] + 7) / l->page] = 1;
  for (size_t i = 0; i < l->nrfix; i++) l->used[l->rfix[i].off / l->page] = l->used[(l->rfix[i].off + 7) / l->page] = 1;
}

/* Rank r's writable copy. */
static void instantiate(loader *l, int r) {
  uintptr_t b = base(l, r);
  unsigned char *rw = (unsigned char *)(b + l->rw_lo);
  for (size_t p = 0, np = (l->tlen + l->page - 1) / l->page; p < np; p++) {
    if (!l->used[p]) continue;
    size_t lo = p * l->page, k = lo + l->page < l->tlen ? l->page : l->tlen - lo;
    memcpy(rw + lo, l->tmpl + lo, k);
  }
  for (size_t i = 0; i < l->nbase; i++) put64(rw + l->basefix[i], get64(rw + l->basefix[i]) + b);
  for (size_t i = 0; i < l->nrfix; i++)
    put64(rw + l->rfix[i].off, (uint64_t)(uintptr_t)rlibc_var(r, l->rfix[i].var) + (uint64_t)l->rfix[i].add);
}

/* The IRELATIVE relocations: each resolver runs once, in rank 0's image, and
 * what it chose goes into the template (an address of the image moves with
 * each rank's base). */
static void run_resolvers(loader *l) {
  int any = 0;
  for (size_t i = 0; i < l->e.nrels && !any; i++) any = kind_of(l->e.machine, l->e.rels[i].type) == RK_IREL;
  if (!any) return;
  instantiate(l, 0);
  uintptr_t b = base(l, 0);
  for (size_t i = 0; i < l->e.nrels; i++) {
    const elf_rel *r = &l->e.rels[i];
    if (kind_of(l->e.machine, r->type) != RK_IREL) continue;
    uintptr_t (*resolver)(void) = (uintptr_t (*)(void))(b + (uint64_t)r->addend);
    uintptr_t a = resolver();
    uint64_t off = r->offset - l->rw_lo;
    if (a >= b + l->ro_lo && a < b + l->rw_hi) {
      put64(l->tmpl + off, a - b);
      add_basefix(l, off);
    } else {
      put64(l->tmpl + off, a);
    }
  }
}

/* ==== the layout and the mappings ========================================= */

/* How many mappings the system lets this loader take: a quarter of what
 * vm.max_map_count leaves, so that the coroutine stacks, the heap and the
 * libraries keep room. */
static long map_budget(void) {
  long max = 65530, now = 0;
  FILE *f = fopen("/proc/sys/vm/max_map_count", "r");
  if (f) {
    if (fscanf(f, "%ld", &max) != 1) max = 65530;
    fclose(f);
  }
  f = fopen("/proc/self/maps", "r");
  if (f) {
    for (int ch; (ch = getc(f)) != EOF;) now += ch == '\n';
    fclose(f);
  } else {
    now = 1000;
  }
  return (max - now) / 4;
}

/* The spans, the strides and c, the copies of the read-only part. */
static int layout(loader *l, char *err, size_t errlen) {
  uint64_t pg = l->page;
  int any_ro = 0, any_rw = 0;
  for (int i = 0; i < l->e.nsegs; i++) {
    const elf_seg *s = &l->e.segs[i];
    uint64_t lo = s->vaddr / pg * pg, hi = (s->vaddr + s->memsz + pg - 1) / pg * pg;
    uint64_t *a = s->writable ? &l->rw_lo : &l->ro_lo, *z = s->writable ? &l->rw_hi : &l->ro_hi;
    int *any = s->writable ? &any_rw : &any_ro;
    if (!*any || lo < *a) *a = lo;
    if (!*any || hi > *z) *z = hi;
    *any = 1;
  }
  if (!any_ro || !any_rw || l->ro_hi > l->rw_lo) {
    snprintf(err, errlen, "%s: its segments are not laid out as a linker lays out a program (read-only, then "
             "writable): rebuild it with tilesim-mpicc", l->path);
    return -1;
  }
  size_t X = l->ro_hi - l->ro_lo, Y = l->rw_hi - l->rw_lo;
  l->D = l->rw_lo - l->ro_lo;
  l->S = X > Y ? X : Y;
  l->m = (int)(l->D / l->S < 1 ? 1 : l->D / l->S > (size_t)l->n ? (size_t)l->n : l->D / l->S);
  l->gstride = l->D + (size_t)l->m * l->S;
  long groups = (l->n + l->m - 1) / l->m, budget = map_budget();
  /* Each group: one mapping for its writable copies, ceil(m / c) for its
   * read-only ones. */
  long per = groups > 0 ? budget / groups - 1 : 0;
  if (per < 1) {
    snprintf(err, errlen, "%d ranks of %s need %ld memory mappings at least, more than vm.max_map_count leaves "
             "(%ld)%s", l->n, l->path, 2 * groups, 4 * budget,
             l->m == 1 ? ": rebuild it with tilesim-mpicc, which links programs so that their ranks share mappings" : "");
    return -1;
  }
  l->c = (int)((l->m + per - 1) / per);
  if (l->c < 1) l->c = 1;
  l->mappings = groups * (1 + (l->m + l->c - 1) / l->c);
  if ((uint64_t)groups > SIZE_MAX / l->gstride) {
    snprintf(err, errlen, "%d ranks of %s need more address space than there is", l->n, l->path);
    return -1;
  }
  l->reslen = (size_t)groups * l->gstride;
  return 0;
}

/* The memory file: c copies of the read-only span, each in S bytes.  Its
 * descriptor, or -1 and a message. */
static int image_file(loader *l, char *err, size_t errlen) {
  size_t X = l->ro_hi - l->ro_lo, total = (size_t)l->c * l->S;
  unsigned char *ro = xcalloc(X, 1);
  for (int i = 0; i < l->e.nsegs; i++) {
    const elf_seg *s = &l->e.segs[i];
    if (!s->writable) memcpy(ro + (s->vaddr - l->ro_lo), l->e.bytes + s->offset, s->filesz);
  }
  int fd = memfd_create("tilesim-program", MFD_CLOEXEC);
  if (fd < 0) {   /* no memory files here: a file in $TMPDIR, removed once open */
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir) dir = "/tmp";
    char target[PATH_MAX], why[600];
    snprintf(target, sizeof target, "%s/tilesim-mpirun-%ld.image", dir, (long)getpid());
    atomicfile a;
    if (atomicfile_open(&a, target, "wb", why, sizeof why) != 0) {
      snprintf(err, errlen, "cannot write the copy of %s: %s ($TMPDIR says where)", l->path, why);
      free(ro);
      return -1;
    }
    fd = open(a.tmp, O_RDWR | O_CLOEXEC);
    atomicfile_close(&a, 0, why, sizeof why);   /* removed: the descriptor stays */
    if (fd < 0) {
      snprintf(err, errlen, "cannot write the copy of %s in %s: %s", l->path, dir, strerror(errno));
      free(ro);
      return -1;
    }
  }
  int ok = ftruncate(fd, (off_t)total) == 0;
  for (int k = 0; ok && k < l->c; k++) {
    size_t done = 0;
    while (ok && done < X) {
      ssize_t w = pwrite(fd, ro + done, X - done, (off_t)((size_t)k * l->S + done));
      ok = w > 0;
      if (ok) done += (size_t)w;
    }
  }
  free(ro);
  if (!ok) {
    snprintf(err, errlen, "no memory for the copy of %s (%zu bytes): %s", l->path, total, strerror(errno));
    close(fd);
    return -1;
  }
  return fd;
}

/* Reserve every group's range (writable, committed only where written) and
 * map the read-only copies over it. */
static int map_image(loader *l, char *err, size_t errlen) {
  int fd = image_file(l, err, errlen);
  if (fd < 0) return -1;
  void *res = mmap(NULL, l->reslen, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (res == MAP_FAILED) {
    snprintf(err, errlen, "%d ranks of %s: no address space for %zu bytes: %s", l->n, l->path, l->reslen,
             strerror(errno));
    close(fd);
    return -1;
  }
  l->res = res;
#ifdef MADV_NOHUGEPAGE
  madvise(res, l->reslen, MADV_NOHUGEPAGE);   /* a rank's page is a page, not a share of 2 MiB */
#endif
  for (int g = 0; g * l->m < l->n; g++) {
    int cnt = l->n - g * l->m < l->m ? l->n - g * l->m : l->m;
    for (int j = 0; j < cnt; j += l->c) {
      int k = cnt - j < l->c ? cnt - j : l->c;
      size_t at = (size_t)j * l->S, len = (size_t)k * l->S;
      if (len > l->D - at) len = l->D - at;
      void *want = l->res + (size_t)g * l->gstride + at;
      if (mmap(want, len, PROT_READ | PROT_EXEC, MAP_SHARED | MAP_FIXED, fd, 0) == MAP_FAILED) {
        snprintf(err, errlen, "rank %d: cannot map its copy of %s: %s", g * l->m + j, l->path, strerror(errno));
        close(fd);
        return -1;
      }
    }
  }
  close(fd);
  return 0;
}

/* ==== exception tables ==================================================== */

/* Every rank's .eh_frame in one table, for the unwinder of the C++ runtime
 * (libgcc_s's) where the program has one and that runtime is loaded. */
static void register_frames(loader *l) {
  if (!l->e.eh_frame) return;
  void *g = dlopen("libgcc_s.so.1", RTLD_NOW | RTLD_NOLOAD);
  if (!g) return;
  void (*reg)(const void *, void *) = NULL;
  *(void **)&reg = dlsym(g, "__register_frame_info_table");
  *(void **)&l->deregister = dlsym(g, "__deregister_frame_info");
  dlclose(g);
  if (!reg || !l->deregister) return;
  l->eh = xcalloc((size_t)l->n + 1, sizeof *l->eh);
  for (int r = 0; r < l->n; r++) l->eh[r] = (const void *)(base(l, r) + l->e.eh_frame);
  l->eh_object = xcalloc(64, sizeof(void *));   /* libgcc's struct object, a few words */
  reg(l->eh, l->eh_object);
}

/* ==== the loader ========================================================== */

loader *loader_new(const char *path, int n, char *err, size_t errlen) {
  loader *l = xcalloc(1, sizeof *l);
  l->path = xstrdup(path);
  l->n = n;
  l->page = (size_t)sysconf(_SC_PAGESIZE);
  if (elf_read(path, &l->e, err, errlen) != 0) {
    free(l->path);
    free(l);
    return NULL;
  }
  the = l;
  if (!l->e.has_main) {
    snprintf(err, errlen, "%s has no main", path);
    goto fail;
  }
  if (l->e.textrel) {
    snprintf(err, errlen, "%s relocates its code (compile every file with -fPIC: tilesim-mpicc does)", path);
    goto fail;
  }
  for (int i = 0; i < l->e.nneeded; i++)
    l->cxx |= strncmp(l->e.needed[i], "libstdc++", 9) == 0 || strncmp(l->e.needed[i], "libc++", 6) == 0;
  if (layout(l, err, errlen) != 0 || load_libraries(l, err, errlen) != 0 || make_template(l, err, errlen) != 0 ||
      map_image(l, err, errlen) != 0)
    goto fail;
  mark_used(l);
  run_resolvers(l);
  mark_used(l);
  l->made = xcalloc((size_t)n, 1);
  l->ended = xcalloc((size_t)n, 1);
  l->tls = xcalloc((size_t)n + 1, sizeof *l->tls);
  l->tls_raw = xcalloc((size_t)n + 1, sizeof *l->tls_raw);
  register_frames(l);
  return l;
fail:
  loader_free(l);
  return NULL;
}

typedef void (*init_fn)(int argc, char **argv, char **envp);
typedef void (*fini_fn)(void);

/* The function pointer at an address of rank r's copy (0 and -1: none). */
static uintptr_t fn_at(uintptr_t at) {
  uintptr_t v = (uintptr_t)get64((const unsigned char *)at);
  return v == UINTPTR_MAX ? 0 : v;
}

loader_main_fn loader_start(loader *l, int r, int argc, char **argv, char **envp) {
  uintptr_t b = base(l, r);
  if (!l->made[r]) {
    instantiate(l, r);
    l->made[r] = 1;
  }
  uintptr_t f;
  for (size_t i = 0; i < l->e.npreinit; i++)
    if ((f = fn_at(b + l->e.preinit_array + 8 * i))) ((init_fn)f)(argc, argv, envp);
  if (l->e.init) ((init_fn)(b + l->e.init))(argc, argv, envp);
  for (size_t i = 0; i < l->e.ninit; i++)
    if ((f = fn_at(b + l->e.init_array + 8 * i))) ((init_fn)f)(argc, argv, envp);
  return (loader_main_fn)(b + l->e.main);
}

void loader_finish(loader *l, int r, int status) {
  rlibc_run_exit(r, status);
  if (!l->made[r] || l->ended[r]) return;
  l->ended[r] = 1;
  uintptr_t b = base(l, r);
  uintptr_t f;
  for (size_t i = l->e.nfini; i-- > 0;)
    if ((f = fn_at(b + l->e.fini_array + 8 * i))) ((fini_fn)f)();
  if (l->e.fini) ((fini_fn)(b + l->e.fini))();
}

int loader_cxx(const loader *l) { return l->cxx; }

void *loader_library_symbol(const loader *l, const char *name) {
  void *a = NULL;
  for (int i = 0; !a && i < l->nlibs; i++) a = dlsym(l->libs[i].h, name);
  return a;
}

void loader_counts(const loader *l, long *mappings, int *copies) {
  *mappings = l->mappings;
  *copies = l->c;
}

void loader_free(loader *l) {
  if (!l) return;
  if (l->eh_object && l->deregister) l->deregister(l->eh);
  free(l->eh);
  free(l->eh_object);
  for (int r = 0; l->tls_raw && r <= l->n; r++) free(l->tls_raw[r]);
  free(l->tls);
  free(l->tls_raw);
  if (l->res) munmap(l->res, l->reslen);
  for (int i = 0; i < l->nlibs; i++)
    if (l->libs[i].h) dlclose(l->libs[i].h);
  free(l->libs);
  free(l->tmpl);
  free(l->used);
  free(l->basefix);
  free(l->rfix);
  free(l->bind);
  free(l->made);
  free(l->ended);
  elf_free(&l->e);
  free(l->path);
  if (the == l) the = NULL;
  free(l);
}
