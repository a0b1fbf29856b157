/* attr.h -- attribute keys (keyvals) and the attributes set on objects
 * (MPI 3.1 section 6.7), for every kind of object that has them:
 * communicators (comm.c), datatypes (dtype_api.c calls attr_copy and
 * attr_delete_all from MPI_Type_dup and MPI_Type_free) and windows
 * (whose part calls the same when a window is made and freed, and
 * attr_set/get/delete for MPI_Win_set_attr, ...).
 *
 * KEYVALS.  A keyval is made for one kind of object, with a copy callback
 * (called by attr_copy: MPI_Comm_dup, MPI_Type_dup) and a delete
 * callback (called when an attribute is replaced or deleted, and for each
 * attribute of an object that is freed); NULL stands for the null copy
 * and the null delete.  A keyval the program frees stays alive while
 * attributes use it; freeing it again meanwhile is allowed and does
 * nothing, and a copy of its handle still reaches the attributes (as
 * MPICH).  Keyvals are numbered from 16 on, in the order made,
 * never reused; the predefined keys (mpi.h: MPI_TAG_UB .. MPI_WIN_MODEL)
 * are below, and the part that owns an object answers for them.
 *
 * ATTRIBUTES.  An object's attributes are kept in the order they were first
 * set; attr_delete_all deletes them last first (MPI 3.1 section 8.7.1
 * asks that order of MPI_COMM_SELF's at MPI_Finalize).
 *
 * ERRORS.  These calls return an MPI error class and never raise: the
 * caller applies the object's error handler, with the words left in why
 * (128 bytes).  A callback's failure is its return value (or
 * MPI_ERR_OTHER if that is not an error code), and the attribute stays as
 * it was. */
#ifndef TSMPI_ATTR_H
#define TSMPI_ATTR_H

#include "mpi/state.h"

enum { ATTR_COMM = 1, ATTR_TYPE = 2, ATTR_WIN = 3 };

/* The callbacks of every kind, handles being ints (MPI_Comm_copy_attr_function, ...). */
typedef int attr_copy_fn(int old, int keyval, void *extra_state, void *in, void *out, int *flag);
typedef int attr_delete_fn(int obj, int keyval, void *value, void *extra_state);

/* A new keyval of kind for the program (*keyval). */
int attr_keyval_create(st_rank *R, int kind, attr_copy_fn *copy, attr_delete_fn *del, void *extra_state,
                       int *keyval);

/* The program frees *keyval (MPI_KEYVAL_INVALID after). */
int attr_keyval_free(st_rank *R, int kind, int *keyval, char *why);

/* Set, get, delete the attribute of keyval on object obj of kind.  get:
 * *flag 0 and nothing stored if it has none. */
int attr_set(st_rank *R, int kind, int obj, int keyval, void *value, char *why);
int attr_get(st_rank *R, int kind, int obj, int keyval, void **value, int *flag, char *why);
int attr_delete(st_rank *R, int kind, int obj, int keyval, char *why);

/* The object `old` was duplicated as `obj`: each attribute of old whose
 * copy callback says so is set on obj.  On a callback's failure, what was
 * copied to obj is deleted again (errors ignored) and the failure
 * returned. */
int attr_copy(st_rank *R, int kind, int old, int obj, char *why);

/* Object obj is freed: its attributes deleted, last set first.  A delete
 * callback's failure stops there (the rest stay) and is returned. */
int attr_delete_all(st_rank *R, int kind, int obj, char *why);

/* Is keyval a live keyval of kind?  (Predefined keys are not.) */
int attr_keyval_is(st_rank *R, int kind, int keyval);

/* Free every keyval and attribute of the rank, calling nothing (its end). */
void attr_release_all(st_rank *R);

#endif
