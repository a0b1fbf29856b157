/* errh.h -- error handlers as objects, and the error classes, codes and
 * strings a program adds (MPI 3.1 sections 8.3 to 8.5).
 *
 * HANDLERS.  MPI_ERRORS_ARE_FATAL and MPI_ERRORS_RETURN are predefined and
 * apply to every kind of object; a handler the program makes
 * (MPI_Comm_create_errhandler, MPI_Win_create_errhandler,
 * MPI_File_create_errhandler, the removed MPI_Errhandler_create) is of one
 * kind, holds the program's function, and lives while the program holds its
 * handle or any object uses it: MPI_Errhandler_free drops the program's
 * handle, an object keeps the handler it was given.  The parts that own
 * windows and files use errh_check to accept a handler for them,
 * errh_hold and errh_drop while an object uses it, and err.h's
 * err_raise_on to apply it.
 *
 * CODES.  The predefined error codes are the classes, 0 .. MPI_ERR_LASTCODE
 * (74); the classes and codes a program adds are numbered on from 75 in the
 * order it adds them, the same on every rank that adds the same ones
 * (MPI_LASTUSEDCODE is the last). */
#ifndef TSMPI_ERRH_H
#define TSMPI_ERRH_H

#include "mpi/state.h"

enum { ERRH_COMM = 1, ERRH_WIN = 2, ERRH_FILE = 3 };

/* A handler's function: the object's handle and the error code, as MPI's
 * MPI_Comm_errhandler_function, MPI_Win_..., MPI_File_... (all handles are
 * ints here). */
typedef void errh_fn(int *handle, int *code, ...);

/* 0 if eh can be set on an object of kind (a predefined handler, or a live
 * one made for that kind); else -1 and why (96 bytes). */
int errh_check(st_rank *R, MPI_Errhandler eh, int kind, char *why);

/* An object starts or stops using eh (predefined ones: nothing). */
void errh_hold(st_rank *R, MPI_Errhandler eh);
void errh_drop(st_rank *R, MPI_Errhandler eh);

/* An object's handler *slot becomes eh (checked by the caller): eh held,
 * the one it had dropped. */
void errh_set(st_rank *R, MPI_Errhandler *slot, MPI_Errhandler eh);

/* The program's function of a created handler (NULL for the predefined). */
errh_fn *errh_function(st_rank *R, MPI_Errhandler eh);

/* The class of error code `code`, or -1 if it is none (predefined or
 * added); its string ("" for an added one without one). */
int errh_class(st_rank *R, int code);
const char *errh_string(st_rank *R, int code);

/* The last code or class in use: MPI_ERR_LASTCODE, or the last added. */
int errh_lastused(st_rank *R);

/* Free the rank's handlers and codes (its end). */
void errh_release_all(st_rank *R);

#endif
