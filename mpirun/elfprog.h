/* elfprog.h -- a program's ELF file as tilesim's loader and tools read it: its
 * segments, dynamic section, symbols with the versions they ask for, its
 * relocations, libraries, thread-local template and unwind table, read
 * from the file's bytes without loading it.
 *
 * tilesim-mpicc reads the programs it links (which MPI functions their code
 * calls), tilesim-mpirun what it is given (is it a program built by
 * tilesim-mpicc, does it count its basic blocks) and its loader everything
 * else (mpirun/loader.h).  64-bit ELF of this machine's byte order only;
 * relocations are kept as the file has them (the machine's numbers), the
 * loader knows x86-64's and AArch64's. */
#ifndef TSMPI_ELFPROG_H
#define TSMPI_ELFPROG_H

#include <stddef.h>
#include <stdint.h>

/* The NEEDED name of the library every program tilesim-mpicc links needs:
 * the functions tilesim-mpirun provides, as stubs that say how to run the
 * program when it is run on its own. */
#define ELF_TILESIM_LIB "libtilesim_mpi.so"

typedef struct {
  uint64_t vaddr, memsz;    /* where it lies in the image, and its size there */
  uint64_t offset, filesz;  /* its bytes in the file (the rest are zeros) */
  int writable, exec;       /* PF_W, PF_X */
} elf_seg;

typedef struct {
  const char *name;
  uint64_t value, size;   /* address in the image (a TLS symbol: offset in the block) */
  int defined;            /* 0: the program needs it from elsewhere */
  int weak, tls, func;    /* STB_WEAK, STT_TLS, STT_FUNC or STT_GNU_IFUNC */
  const char *version;    /* the version it asks for (VERNEED), or NULL */
  const char *lib;        /* and the library that version belongs to, or NULL */
  int called;             /* a PLT slot's relocation names it: the code calls it */
  int referenced;         /* any relocation names it */
} elf_sym;

typedef struct {
  uint64_t offset;   /* the address it writes, in the image */
  uint32_t type;     /* the machine's relocation type */
  uint32_t sym;      /* index into syms; 0 for none */
  int64_t addend;
} elf_rel;

typedef struct {
  unsigned char *bytes;   /* the whole file */
  size_t len;
  int machine;            /* e_machine */
  int exec;               /* ET_EXEC: a fixed-address executable */
  const char *interp;     /* the program interpreter it asks for (PT_INTERP), or NULL */
  elf_seg *segs;          /* the PT_LOAD segments, in file order */
  int nsegs;
  elf_sym *syms;          /* the dynamic symbols; syms[0] is the null one */
  size_t nsyms;
  elf_rel *rels;          /* DT_RELA, DT_JMPREL and DT_RELR (as type `relative`) */
  size_t nrels;
  uint32_t relative;      /* the machine's RELATIVE type (DT_RELR entries get it) */
  const char **needed;    /* DT_NEEDED names */
  int nneeded;
  const char *runpath;    /* DT_RUNPATH, else DT_RPATH, or NULL */
  int textrel;            /* DT_TEXTREL or DF_TEXTREL */
  uint64_t init, fini;    /* DT_INIT, DT_FINI (0: none) */
  uint64_t preinit_array, init_array, fini_array;   /* addresses of the arrays */
  size_t npreinit, ninit, nfini;                    /* and their lengths */
  int has_tls;            /* PT_TLS: the thread-local template */
  uint64_t tls_vaddr, tls_filesz, tls_memsz, tls_align;
  uint64_t eh_frame;      /* .eh_frame's address (from PT_GNU_EH_FRAME), or 0 */
  int has_main;           /* main, from the dynamic symbols or else .symtab */
  uint64_t main;
} elf_prog;

/* Read the file at path.  0, or -1 with a message naming the file and what
 * is wrong with it (and the byte where it is damaged); *p is then empty. */
int elf_read(const char *path, elf_prog *p, char *err, size_t errlen);

/* What the file at path is, in a few words, for a message about a file
 * that is not what was expected: "a script", "not an ELF file", "a 32-bit
 * ELF file", "a shared library", ... */
const char *elf_describe(const char *path, char *buf, size_t len);

/* The symbol named name (defined or not), or NULL. */
const elf_sym *elf_find(const elf_prog *p, const char *name);

/* 1 if the program needs the library named name (DT_NEEDED). */
int elf_needs(const elf_prog *p, const char *name);

void elf_free(elf_prog *p);

#endif
