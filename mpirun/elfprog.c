/* elfprog.c -- a program's ELF file, read with <elf.h> (elfprog.h). */
#include "mpirun/elfprog.h"

#include <elf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/xmem.h"

#if defined(__x86_64__)
#define HOST_MACHINE EM_X86_64
#elif defined(__aarch64__)
#define HOST_MACHINE EM_AARCH64
#else
#define HOST_MACHINE EM_NONE
#endif

static int host_data(void) {
  const uint16_t one = 1;
  return *(const unsigned char *)&one == 1 ? ELFDATA2LSB : ELFDATA2MSB;
}

/* The whole file, or NULL and a message. */
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

/* The file's bytes at image address v, len of them, all inside one
 * segment's file part; or NULL. */
static const unsigned char *at_vaddr(const elf_prog *p, uint64_t v, uint64_t len) {
  for (int i = 0; i < p->nsegs; i++) {
    const elf_seg *s = &p->segs[i];
    if (v >= s->vaddr && v - s->vaddr <= s->filesz && len <= s->filesz - (v - s->vaddr))
      return p->bytes + s->offset + (v - s->vaddr);
  }
  return NULL;
}

/* A string of the dynamic string table, or NULL if it runs out of it. */
static const char *dynstr(const unsigned char *str, uint64_t strsz, uint64_t off) {
  if (!str || off >= strsz || !memchr(str + off, 0, strsz - off)) return NULL;
  return (const char *)str + off;
}

/* How many dynamic symbols a DT_GNU_HASH table covers (for files without
 * section headers); 0 if it cannot tell. */
static size_t gnu_hash_count(const elf_prog *p, uint64_t v) {
  const unsigned char *h = at_vaddr(p, v, 16);
  if (!h) return 0;
  uint32_t nb, off, bloom;
  memcpy(&nb, h, 4);
  memcpy(&off, h + 4, 4);
  memcpy(&bloom, h + 8, 4);
  uint64_t bk = v + 16 + (uint64_t)bloom * 8;
  const unsigned char *b = at_vaddr(p, bk, (uint64_t)nb * 4);
  if (!b) return 0;
  uint32_t last = 0;
  for (uint32_t i = 0; i < nb; i++) {
    uint32_t x;
    memcpy(&x, b + 4 * (size_t)i, 4);
    if (x > last) last = x;
  }
  if (last < off) return off;
  for (uint64_t i = last;; i++) {
    const unsigned char *c = at_vaddr(p, bk + (uint64_t)nb * 4 + (i - off) * 4, 4);
    if (!c) return 0;
    uint32_t x;
    memcpy(&x, c, 4);
    if (x & 1) return (size_t)i + 1;
  }
}

/* .eh_frame's address from .eh_frame_hdr (at image address v): its second
 * field, encoded as the first byte's neighbour says; 0 if unknown. */
static uint64_t eh_frame_from_hdr(const elf_prog *p, uint64_t v) {
  const unsigned char *h = at_vaddr(p, v, 4);
  if (!h || h[0] != 1) return 0;
  int enc = h[1];
  uint64_t field = v + 4, x;
  if ((enc & 0x0f) == 0x0b || (enc & 0x0f) == 0x03) {   /* sdata4, udata4 */
    const unsigned char *q = at_vaddr(p, field, 4);
    if (!q) return 0;
    int32_t s;
    uint32_t u;
    memcpy(&s, q, 4);
    memcpy(&u, q, 4);
    x = (enc & 0x0f) == 0x0b ? (uint64_t)(int64_t)s : u;
  } else if ((enc & 0x0f) == 0x0c || (enc & 0x0f) == 0x04 || (enc & 0x0f) == 0x00) {   /* 8 bytes */
    const unsigned char *q = at_vaddr(p, field, 8);
    if (!q) return 0;
    memcpy(&x, q, 8);
  } else {
    return 0;
  }
  if ((enc & 0x70) == 0x10) return field + x;   /* pcrel */
  if ((enc & 0x70) == 0x00) return x;           /* absolute: an image address */
  return 0;
}

static int bad(elf_prog *p, char *err, size_t errlen, const char *path, const char *what, uint64_t byte) {
  snprintf(err, errlen, "%s: corrupt or truncated: %s (byte %llu)", path, what, (unsigned long long)byte);
  elf_free(p);
  return -1;
}

/* main's address from .symtab, for a program that does not export it. */
static void main_from_symtab(elf_prog *p) {
  const Elf64_Ehdr *eh = (const Elf64_Ehdr *)p->bytes;
  if (eh->e_shentsize != sizeof(Elf64_Shdr) || !within(p->len, eh->e_shoff, (uint64_t)eh->e_shnum * sizeof(Elf64_Shdr)))
    return;
  const Elf64_Shdr *sh = (const Elf64_Shdr *)(p->bytes + eh->e_shoff);
  for (int i = 0; i < eh->e_shnum; i++) {
    if (sh[i].sh_type != SHT_SYMTAB || sh[i].sh_link >= eh->e_shnum || sh[i].sh_entsize != sizeof(Elf64_Sym)) continue;
    const Elf64_Shdr *ss = &sh[sh[i].sh_link];
    if (!within(p->len, sh[i].sh_offset, sh[i].sh_size) || !within(p->len, ss->sh_offset, ss->sh_size)) return;
    const Elf64_Sym *sym = (const Elf64_Sym *)(p->bytes + sh[i].sh_offset);
    for (size_t k = 0; k < sh[i].sh_size / sizeof *sym; k++) {
      const char *name = dynstr(p->bytes + ss->sh_offset, ss->sh_size, sym[k].st_name);
      if (name && strcmp(name, "main") == 0 && sym[k].st_shndx != SHN_UNDEF &&
          ELF64_ST_TYPE(sym[k].st_info) == STT_FUNC) {
        p->has_main = 1;
        p->main = sym[k].st_value;
        return;
      }
    }
  }
}

int elf_read(const char *path, elf_prog *p, char *err, size_t errlen) {
  memset(p, 0, sizeof *p);
  p->bytes = slurp(path, &p->len, err, errlen);
  if (!p->bytes) return -1;
  const Elf64_Ehdr *eh = (const Elf64_Ehdr *)p->bytes;
  if (p->len < EI_NIDENT || memcmp(p->bytes, ELFMAG, SELFMAG) != 0) {
    snprintf(err, errlen, "%s: not an ELF file (byte 0)", path);
    elf_free(p);
    return -1;
  }
  if (p->bytes[EI_CLASS] != ELFCLASS64 || p->bytes[EI_DATA] != host_data() || p->len < sizeof *eh) {
    snprintf(err, errlen, "%s: an ELF file of another machine (byte %d: class %d, data %d)", path, EI_CLASS,
             p->bytes[EI_CLASS], p->bytes[EI_DATA]);
    elf_free(p);
    return -1;
  }
  p->machine = eh->e_machine;
  p->exec = eh->e_type == ET_EXEC;
  p->relative = p->machine == EM_X86_64 ? R_X86_64_RELATIVE : p->machine == EM_AARCH64 ? R_AARCH64_RELATIVE : 0;
  if (eh->e_phentsize != sizeof(Elf64_Phdr) || !within(p->len, eh->e_phoff, (uint64_t)eh->e_phnum * sizeof(Elf64_Phdr)))
    return bad(p, err, errlen, path, "its program headers are not in the file", eh->e_phoff);

  /* ---- segments ---- */
  const Elf64_Phdr *ph = (const Elf64_Phdr *)(p->bytes + eh->e_phoff);
  const Elf64_Phdr *dyn = NULL;
  uint64_t ehdr_v = 0;
  int has_ehdr = 0;
  p->segs = xcalloc((size_t)eh->e_phnum + 1, sizeof *p->segs);
  for (int i = 0; i < eh->e_phnum; i++) {
    const Elf64_Phdr *q = &ph[i];
    uint64_t where = eh->e_phoff + (uint64_t)i * sizeof *q;
    if (q->p_type == PT_LOAD) {
      if (!within(p->len, q->p_offset, q->p_filesz) || q->p_filesz > q->p_memsz)
        return bad(p, err, errlen, path, "a segment's bytes are not in the file", where);
      p->segs[p->nsegs++] = (elf_seg){q->p_vaddr, q->p_memsz, q->p_offset, q->p_filesz, (q->p_flags & PF_W) != 0,
                                      (q->p_flags & PF_X) != 0};
    } else if (q->p_type == PT_DYNAMIC) {
      dyn = q;
    } else if (q->p_type == PT_INTERP) {
      if (!within(p->len, q->p_offset, q->p_filesz) || q->p_filesz == 0 ||
          p->bytes[q->p_offset + q->p_filesz - 1] != 0)
        return bad(p, err, errlen, path, "its interpreter's name is not in the file", where);
      p->interp = (const char *)p->bytes + q->p_offset;
    } else if (q->p_type == PT_TLS) {
      p->has_tls = 1;
      p->tls_vaddr = q->p_vaddr;
      p->tls_filesz = q->p_filesz;
      p->tls_memsz = q->p_memsz;
      p->tls_align = q->p_align ? q->p_align : 1;
    } else if (q->p_type == PT_GNU_EH_FRAME) {
      has_ehdr = 1;
      ehdr_v = q->p_vaddr;
    }
  }
  if (has_ehdr) p->eh_frame = eh_frame_from_hdr(p, ehdr_v);
  if (!dyn) return 0;   /* a static file: nothing more to read */

  /* ---- the dynamic section ---- */
  if (!within(p->len, dyn->p_offset, dyn->p_filesz))
    return bad(p, err, errlen, path, "its dynamic section is not in the file", dyn->p_offset);
  const Elf64_Dyn *d = (const Elf64_Dyn *)(p->bytes + dyn->p_offset);
  size_t nd = dyn->p_filesz / sizeof *d;
  uint64_t strtab = 0, strsz = 0, symtab = 0, rela = 0, relasz = 0, jmprel = 0, pltrelsz = 0, relr = 0, relrsz = 0;
  uint64_t versym = 0, verneed = 0, verneednum = 0, gnuhash = 0, hash = 0, runpath = 0, rpath = 0;
  int has_runpath = 0, has_rpath = 0, has_rel = 0;
  for (size_t i = 0; i < nd && d[i].d_tag != DT_NULL; i++) {
    uint64_t v = d[i].d_un.d_val;
    switch (d[i].d_tag) {
    case DT_STRTAB: strtab = v; break;
    case DT_STRSZ: strsz = v; break;
    case DT_SYMTAB: symtab = v; break;
    case DT_RELA: rela = v; break;
    case DT_RELASZ: relasz = v; break;
    case DT_JMPREL: jmprel = v; break;
    case DT_PLTRELSZ: pltrelsz = v; break;
    case DT_PLTREL: has_rel |= v == DT_REL; break;
    case DT_REL: has_rel = 1; break;
    case DT_RELR: relr = v; break;
    case DT_RELRSZ: relrsz = v; break;
    case DT_VERSYM: versym = v; break;
    case DT_VERNEED: verneed = v; break;
    case DT_VERNEEDNUM: verneednum = v; break;
    case DT_GNU_HASH: gnuhash = v; break;
    case DT_HASH: hash = v; break;
    case DT_RUNPATH: runpath = v; has_runpath = 1; break;
    case DT_RPATH: rpath = v; has_rpath = 1; break;
    case DT_TEXTREL: p->textrel = 1; break;
    case DT_FLAGS: p->textrel |= (v & DF_TEXTREL) != 0; break;
    case DT_INIT: p->init = v; break;
    case DT_FINI: p->fini = v; break;
    case DT_PREINIT_ARRAY: p->preinit_array = v; break;
    case DT_PREINIT_ARRAYSZ: p->npreinit = v / 8; break;
    case DT_INIT_ARRAY: p->init_array = v; break;
    case DT_INIT_ARRAYSZ: p->ninit = v / 8; break;
    case DT_FINI_ARRAY: p->fini_array = v; break;
    case DT_FINI_ARRAYSZ: p->nfini = v / 8; break;
    default: break;
    }
  }
  if (has_rel) {
    snprintf(err, errlen, "%s: has REL relocations, which tilesim's loader does not read (64-bit RELA only)", path);
    elf_free(p);
    return -1;
  }
  const unsigned char *str = at_vaddr(p, strtab, strsz);
  if (!str) return bad(p, err, errlen, path, "its dynamic string table is not in the file", dyn->p_offset);
  p->needed = xcalloc(nd + 1, sizeof *p->needed);
  for (size_t i = 0; i < nd && d[i].d_tag != DT_NULL; i++) {
    if (d[i].d_tag != DT_NEEDED) continue;
    const char *s = dynstr(str, strsz, d[i].d_un.d_val);
    if (!s) return bad(p, err, errlen, path, "a NEEDED name is outside the string table", dyn->p_offset);
    p->needed[p->nneeded++] = s;
  }
  if (has_runpath || has_rpath) p->runpath = dynstr(str, strsz, has_runpath ? runpath : rpath);

  /* ---- symbols: how many (the section headers say; else the hash) ---- */
  size_t nsym = 0;
  const Elf64_Shdr *sh = NULL;
  if (eh->e_shentsize == sizeof(Elf64_Shdr) && within(p->len, eh->e_shoff, (uint64_t)eh->e_shnum * sizeof *sh))
    sh = (const Elf64_Shdr *)(p->bytes + eh->e_shoff);
  for (int i = 0; sh && i < eh->e_shnum; i++)
    if (sh[i].sh_type == SHT_DYNSYM && sh[i].sh_addr == symtab) nsym = sh[i].sh_size / sizeof(Elf64_Sym);
  if (!nsym && gnuhash) nsym = gnu_hash_count(p, gnuhash);
  if (!nsym && hash) {
    const unsigned char *h = at_vaddr(p, hash, 8);
    uint32_t nchain = 0;
    if (h) memcpy(&nchain, h + 4, 4);
    nsym = nchain;
  }
  const Elf64_Sym *sym = nsym ? (const Elf64_Sym *)at_vaddr(p, symtab, nsym * sizeof(Elf64_Sym)) : NULL;
  if (nsym && !sym) return bad(p, err, errlen, path, "its dynamic symbols are not in the file", dyn->p_offset);
  const unsigned char *vs = versym ? at_vaddr(p, versym, nsym * 2) : NULL;
  p->syms = xcalloc(nsym + 1, sizeof *p->syms);
  p->nsyms = nsym;
  for (size_t k = 0; k < nsym; k++) {
    elf_sym *s = &p->syms[k];
    s->name = dynstr(str, strsz, sym[k].st_name);
    if (!s->name) return bad(p, err, errlen, path, "a symbol's name is outside the string table", dyn->p_offset);
    int type = ELF64_ST_TYPE(sym[k].st_info);
    s->value = sym[k].st_value;
    s->size = sym[k].st_size;
    s->defined = sym[k].st_shndx != SHN_UNDEF;
    s->weak = ELF64_ST_BIND(sym[k].st_info) == STB_WEAK;
    s->tls = type == STT_TLS;
    s->func = type == STT_FUNC || type == STT_GNU_IFUNC;
    if (s->defined || !vs) continue;
    /* The version it asks for: VERNEED's entry whose vna_other is its index. */
    uint16_t idx;
    memcpy(&idx, vs + 2 * k, 2);
    idx &= 0x7fff;
    uint64_t vn = verneed;
    for (uint64_t i = 0; idx >= 2 && i < verneednum; i++) {
      const Elf64_Verneed *n = (const Elf64_Verneed *)at_vaddr(p, vn, sizeof(Elf64_Verneed));
      if (!n) break;
      uint64_t va = vn + n->vn_aux;
      for (int j = 0; j < n->vn_cnt; j++) {
        const Elf64_Vernaux *a = (const Elf64_Vernaux *)at_vaddr(p, va, sizeof(Elf64_Vernaux));
        if (!a) break;
        if (a->vna_other == idx) {
          s->version = dynstr(str, strsz, a->vna_name);
          s->lib = dynstr(str, strsz, n->vn_file);
        }
        if (!a->vna_next) break;
        va += a->vna_next;
      }
      if (!n->vn_next) break;
      vn += n->vn_next;
    }
  }

  /* ---- relocations ---- */
  size_t cap = relasz / sizeof(Elf64_Rela) + pltrelsz / sizeof(Elf64_Rela) + 16;
  p->rels = xmallocarray(cap, sizeof *p->rels);
  const uint64_t tab[2][2] = {{rela, relasz}, {jmprel, pltrelsz}};
  for (int t = 0; t < 2; t++) {
    if (!tab[t][1]) continue;
    const Elf64_Rela *r = (const Elf64_Rela *)at_vaddr(p, tab[t][0], tab[t][1]);
    if (!r) return bad(p, err, errlen, path, "its relocations are not in the file", dyn->p_offset);
    for (size_t i = 0; i < tab[t][1] / sizeof *r; i++) {
      uint32_t si = (uint32_t)ELF64_R_SYM(r[i].r_info);
      if (si >= (nsym ? nsym : 1)) return bad(p, err, errlen, path, "a relocation names no symbol", dyn->p_offset);
      p->rels[p->nrels++] = (elf_rel){r[i].r_offset, (uint32_t)ELF64_R_TYPE(r[i].r_info), si, r[i].r_addend};
      if (si) {
        p->syms[si].referenced = 1;
        if (t == 1) p->syms[si].called = 1;
      }
    }
  }
  if (relrsz) {   /* DT_RELR: an address, then bitmaps of the 63 words after */
    const unsigned char *w = at_vaddr(p, relr, relrsz);
    if (!w || !p->relative) return bad(p, err, errlen, path, "its RELR relocations are not in the file", dyn->p_offset);
    uint64_t where = 0;
    for (size_t i = 0; i < relrsz / 8; i++) {
      uint64_t e;
      memcpy(&e, w + 8 * i, 8);
      if (!(e & 1)) {
        if (p->nrels + 1 > cap) p->rels = xreallocarray(p->rels, cap *= 2, sizeof *p->rels);
        p->rels[p->nrels++] = (elf_rel){e, p->relative, 0, 0};
        where = e + 8;
        continue;
      }
      for (int b = 0; b < 63; b++)
        if (e >> (b + 1) & 1) {
          if (p->nrels + 1 > cap) p->rels = xreallocarray(p->rels, cap *= 2, sizeof *p->rels);
          p->rels[p->nrels++] = (elf_rel){where + 8 * (uint64_t)b, p->relative, 0, 0};
        }
      where += 63 * 8;
    }
  }

  const elf_sym *m = elf_find(p, "main");
  if (m && m->defined && m->func) {
    p->has_main = 1;
    p->main = m->value;
  } else {
    main_from_symtab(p);
  }
  return 0;
}

const elf_sym *elf_find(const elf_prog *p, const char *name) {
  for (size_t k = 1; k < p->nsyms; k++)
    if (strcmp(p->syms[k].name, name) == 0) return &p->syms[k];
  return NULL;
}

int elf_needs(const elf_prog *p, const char *name) {
  for (int i = 0; i < p->nneeded; i++)
    if (strcmp(p->needed[i], name) == 0) return 1;
  return 0;
}

const char *elf_describe(const char *path, char *buf, size_t len) {
  unsigned char h[sizeof(Elf64_Ehdr)] = {0};
  FILE *f = fopen(path, "rb");
  if (!f) {
    snprintf(buf, len, "a file that cannot be read");
    return buf;
  }
  size_t k = fread(h, 1, sizeof h, f);
  fclose(f);
  const Elf64_Ehdr *eh = (const Elf64_Ehdr *)h;
  if (k >= 2 && h[0] == '#' && h[1] == '!') snprintf(buf, len, "a script");
  else if (k < EI_NIDENT || memcmp(h, ELFMAG, SELFMAG) != 0) snprintf(buf, len, "not an ELF file");
  else if (h[EI_CLASS] != ELFCLASS64) snprintf(buf, len, "a 32-bit ELF file");
  else if (h[EI_DATA] != host_data()) snprintf(buf, len, "an ELF file of the other byte order");
  else if (k < sizeof h) snprintf(buf, len, "a damaged ELF file (cut short in its header)");
  else if (eh->e_machine != HOST_MACHINE) snprintf(buf, len, "an ELF file for another machine (e_machine %d)", eh->e_machine);
  else if (eh->e_type == ET_REL) snprintf(buf, len, "an object file, not a program");
  else if (eh->e_type == ET_CORE) snprintf(buf, len, "a core dump");
  else {
    elf_prog p;
    char err[300];
    if (elf_read(path, &p, err, sizeof err) != 0) {
      size_t n = strlen(path);
      snprintf(buf, len, "a damaged ELF file (%s)", strncmp(err, path, n) == 0 && err[n] == ':' ? err + n + 2 : err);
      return buf;
    }
    const char *mpi = NULL;
    for (int i = 0; i < p.nneeded; i++)
      if (strncmp(p.needed[i], "libmpi", 6) == 0 || strncmp(p.needed[i], "libsimgrid", 10) == 0) mpi = p.needed[i];
    if (elf_needs(&p, ELF_TILESIM_LIB)) snprintf(buf, len, "a program built by tilesim-mpicc");
    else if (mpi) snprintf(buf, len, "a program built for another MPI (it needs %s)", mpi);
    else if (p.exec) snprintf(buf, len, "a program not built by tilesim-mpicc (a fixed-address executable)");
    else if (!p.interp) snprintf(buf, len, "a shared library, not a program");
    else snprintf(buf, len, "a program not built by tilesim-mpicc (it does not use tilesim's MPI)");
    elf_free(&p);
  }
  return buf;
}

void elf_free(elf_prog *p) {
  free(p->bytes);
  free(p->segs);
  free(p->syms);
  free(p->rels);
  free(p->needed);
  memset(p, 0, sizeof *p);
}
