/* callbacks.c -- the predefined attribute callbacks MPI 3.1 names (section 6.7.2): null copy,
 * duplicate, null delete, for communicators, types and windows, and the deprecated MPI-1 ones
 * (declared in mpi.h). */
#include "mpi/mpi.h"

/* Copy nothing: the new object has no such attribute. */
#define NULL_COPY(name, handle)                                                            \
  int name(handle old, int keyval, void *extra_state, void *in, void *out, int *flag) {  \
    (void)old, (void)keyval, (void)extra_state, (void)in, (void)out;                     \
    *flag = 0;                                                                            \
    return MPI_SUCCESS;                                                                   \
  }
/* Copy the attribute's value (a pointer-sized word). */
#define DUP(name, handle)                                                                  \
  int name(handle old, int keyval, void *extra_state, void *in, void *out, int *flag) {  \
    (void)old, (void)keyval, (void)extra_state;                                          \
    *(void **)out = in;                                                                   \
    *flag = 1;                                                                            \
    return MPI_SUCCESS;                                                                   \
  }
#define NULL_DELETE(name, handle)                                                          \
  int name(handle obj, int keyval, void *value, void *extra_state) {                     \
    (void)obj, (void)keyval, (void)value, (void)extra_state;                             \
    return MPI_SUCCESS;                                                                   \
  }

NULL_COPY(MPI_COMM_NULL_COPY_FN, MPI_Comm)
DUP(MPI_COMM_DUP_FN, MPI_Comm)
NULL_DELETE(MPI_COMM_NULL_DELETE_FN, MPI_Comm)
NULL_COPY(MPI_TYPE_NULL_COPY_FN, MPI_Datatype)
DUP(MPI_TYPE_DUP_FN, MPI_Datatype)
NULL_DELETE(MPI_TYPE_NULL_DELETE_FN, MPI_Datatype)
NULL_COPY(MPI_WIN_NULL_COPY_FN, MPI_Win)
DUP(MPI_WIN_DUP_FN, MPI_Win)
NULL_DELETE(MPI_WIN_NULL_DELETE_FN, MPI_Win)
NULL_COPY(MPI_NULL_COPY_FN, MPI_Comm)
DUP(MPI_DUP_FN, MPI_Comm)
NULL_DELETE(MPI_NULL_DELETE_FN, MPI_Comm)
