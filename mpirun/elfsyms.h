/* elfsyms.h -- the dynamic symbols of an ELF shared object: which names a
 * program built by tilesim-mpicc defines and which it needs from the runner
 * (the MPI functions it references), read from the file without loading it.
 *
 * tilesim-mpicc lists, after linking, the MPI functions a program references
 * that tilesim does not implement; tilesim-mpirun checks the same before a
 * run, and that the program has a main and was built for the compute mode
 * asked for. */
#ifndef ELFSYMS_H
#define ELFSYMS_H

#include <stddef.h>

/* Call fn(ud, name, defined) for every global or weak symbol of the dynamic
 * symbol table of the ELF file at path (defined: 0 for a symbol the object
 * needs from elsewhere).  0, or -1 and a message naming the file and the
 * byte where it is not an ELF object of this machine's class (32 or 64
 * bits, this byte order) or is cut short. */
int elfsyms_read(const char *path, void (*fn)(void *ud, const char *name, int defined), void *ud, char *err,
                 size_t errlen);

/* 1 if the file at path is an ELF shared object (ET_DYN) of this machine's
 * class, else 0 (absent, another kind of file). */
int elfsyms_is_shared(const char *path);

#endif
