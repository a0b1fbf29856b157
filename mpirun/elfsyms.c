/* elfsyms.c -- an ELF file's dynamic symbols (elfsyms.h), read with <elf.h>. */
#include "elfsyms.h"

#include <elf.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "xmem.h"

#if UINTPTR_MAX > 0xffffffffu
#define CLASS ELFCLASS64
typedef Elf64_Ehdr Ehdr;
typedef Elf64_Shdr Shdr;
typedef Elf64_Sym Sym;
#define BIND ELF64_ST_BIND
#else
#define CLASS ELFCLASS32
typedef Elf32_Ehdr Ehdr;
typedef Elf32_Shdr Shdr;
typedef Elf32_Sym Sym;
#define BIND ELF32_ST_BIND
#endif

static int host_data(void) {
  const uint16_t one = 1;
  return *(const unsigned char *)&one == 1 ? ELFDATA2LSB : ELFDATA2MSB;
}

/* The whole file in memory (programs are small), or NULL and *n = 0. */
static unsigned char *slurp(const char *path, size_t *n, char *err, size_t errlen) {
  FILE *f = fopen(path, "rb");
  *n = 0;
  if (!f) {
    snprintf(err, errlen, "%s: cannot open it", path);
    return NULL;
  }
  size_t cap = 1 << 16;
  unsigned char *b = xmalloc(cap);
  for (;;) {
    size_t k = fread(b + *n, 1, cap - *n, f);
    *n += k;
    if (*n < cap) break;
    b = xrealloc(b, cap *= 2);
  }
  int bad = ferror(f);
  fclose(f);
  if (bad) {
    snprintf(err, errlen, "%s: cannot read it", path);
    free(b);
    return NULL;
  }
  return b;
}

/* [off, off + len) lies within n bytes. */
static int within(size_t n, uint64_t off, uint64_t len) { return off <= n && len <= n - off; }

int elfsyms_read(const char *path, void (*fn)(void *ud, const char *name, int defined), void *ud, char *err,
                 size_t errlen) {
  size_t n;
  unsigned char *b = slurp(path, &n, err, errlen);
  if (!b) return -1;
  int res = -1;
  const Ehdr *eh = (const Ehdr *)b;
  if (n < sizeof *eh || memcmp(b, ELFMAG, SELFMAG) != 0) {
    snprintf(err, errlen, "%s: not an ELF file (byte 0)", path);
  } else if (b[EI_CLASS] != CLASS || b[EI_DATA] != host_data()) {
    snprintf(err, errlen, "%s: an ELF file of another machine (byte %d: class %d, data %d)", path, EI_CLASS,
             b[EI_CLASS], b[EI_DATA]);
  } else if (eh->e_shentsize != sizeof(Shdr) || !within(n, eh->e_shoff, (uint64_t)eh->e_shnum * sizeof(Shdr))) {
    snprintf(err, errlen, "%s: corrupt or truncated: its section headers (at byte %llu) are not in the file", path,
             (unsigned long long)eh->e_shoff);
  } else {
    const Shdr *sh = (const Shdr *)(b + eh->e_shoff);
    res = 0;
    for (int i = 0; i < eh->e_shnum && res == 0; i++) {
      if (sh[i].sh_type != SHT_DYNSYM) continue;
      const Shdr *ss = sh[i].sh_link < eh->e_shnum ? &sh[sh[i].sh_link] : NULL;
      if (!ss || !within(n, sh[i].sh_offset, sh[i].sh_size) || !within(n, ss->sh_offset, ss->sh_size) ||
          sh[i].sh_entsize != sizeof(Sym)) {
        snprintf(err, errlen, "%s: corrupt or truncated: its dynamic symbols (section %d at byte %llu)", path, i,
                 (unsigned long long)sh[i].sh_offset);
        res = -1;
        break;
      }
      const Sym *sym = (const Sym *)(b + sh[i].sh_offset);
      const char *str = (const char *)(b + ss->sh_offset);
      size_t nsym = sh[i].sh_size / sizeof(Sym);
      for (size_t k = 1; k < nsym; k++) {
        int bind = BIND(sym[k].st_info);
        if (bind != STB_GLOBAL && bind != STB_WEAK) continue;
        if (sym[k].st_name >= ss->sh_size || !memchr(str + sym[k].st_name, 0, ss->sh_size - sym[k].st_name)) {
          snprintf(err, errlen, "%s: corrupt: symbol %zu's name is outside its string table", path, k);
          res = -1;
          break;
        }
        fn(ud, str + sym[k].st_name, sym[k].st_shndx != SHN_UNDEF);
      }
    }
  }
  free(b);
  return res;
}

int elfsyms_is_shared(const char *path) {
  unsigned char h[sizeof(Ehdr)];
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  size_t k = fread(h, 1, sizeof h, f);
  fclose(f);
  const Ehdr *eh = (const Ehdr *)h;
  return k == sizeof h && memcmp(h, ELFMAG, SELFMAG) == 0 && h[EI_CLASS] == CLASS && eh->e_type == ET_DYN;
}
