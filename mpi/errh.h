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
 * windows and files use tsm_errh_check to accept a handler for them,
 * tsm_errh_hold and tsm_errh_drop while an object uses it, and err.h's
 * tsm_raise_on to apply it.
 *
 * CODES.  The predefined error codes are the classes, 0 .. MPI_ERR_LASTCODE
 * (74); the classes and codes a program adds are numbered on from 75 in the
 * order it adds them, the same on every rank that adds the same ones
 * (MPI_LASTUSEDCODE is the last). */
#ifndef TSMPI_ERRH_H
#define TSMPI_ERRH_H

#include "mpi/state.h"

enum { TSM_EH_COMM = 1, TSM_EH_WIN = 2, TSM_EH_FILE = 3 };

/* A handler's function: the object's handle and the error code, as MPI's
 * MPI_Comm_errhandler_function, MPI_Win_..., MPI_File_... (all handles are
 * ints here). */
typedef void tsm_errh_fn(int *handle, int *code, ...);

/* 0 if eh can be set on an object of kind (a predefined handler, or a live
 * one made for that kind); else -1 and why (96 bytes). */
int tsm_errh_check(tsm *R, MPI_Errhandler eh, int kind, char *why);

/* An object starts or stops using eh (predefined ones: nothing). */
void tsm_errh_hold(tsm *R, MPI_Errhandler eh);
void tsm_errh_drop(tsm *R, MPI_Errhandler eh);

/* The program's function of a created handler (NULL for the predefined). */
tsm_errh_fn *tsm_errh_function(tsm *R, MPI_Errhandler eh);

/* The class of error code `code`, or -1 if it is none (predefined or
 * added); its string ("" for an added one without one). */
int tsm_err_class(tsm *R, int code);
const char *tsm_err_string(tsm *R, int code);

/* The last code or class in use: MPI_ERR_LASTCODE, or the last added. */
int tsm_err_lastused(tsm *R);

/* Free the rank's handlers and codes (its end). */
void tsm_errs_release(tsm *R);

#endif
