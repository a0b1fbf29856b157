/* op.h -- reduction operations inside the MPI layer: every predefined operation on every
 * predefined type it applies to (MPI 3.1 section 5.9.2), MINLOC and MAXLOC on the pair types
 * (5.9.4), each rank's user-defined operations (5.9.5), and applying one to elements.
 *
 * Not for programs (mpi.h is theirs).  The collectives and MPI_Reduce_local
 * reduce with these.
 *
 * ORDER.  Every call computes inout[i] = in[i] op inout[i]: `in` is the
 * left operand, as for a user function (MPI 3.1 section 5.9.5).  Integers
 * wrap around (two's complement) as on every MPI library; floating point is
 * IEEE arithmetic in the order the caller combines (the collectives
 * document theirs); MPI_MAX and MPI_MIN keep the right operand unless the
 * left is greater (smaller), so a NaN on the left is dropped and one on the
 * right kept; MINLOC and MAXLOC take the smaller index on equal values.
 *
 * TYPES.  A predefined operation applies to the predefined types of its
 * classes (dtype.h), and, as MPICH allows (Open MPI does not, and MPI 3.1
 * asks only for predefined types), to a derived type whose basic entries
 * are all of one such type (a pair type counting as one).  MPI_CHAR counts
 * as a C integer, as in MPICH and Open MPI.  A user-defined operation
 * applies to any type. */
#ifndef TSMPI_OP_H
#define TSMPI_OP_H

#include <stddef.h>

#include "mpi/mpi.h"

/* MPI_SUCCESS if op is an operation of this rank (predefined, or created
 * and not freed); else MPI_ERR_OP and why. */
int op_valid(MPI_Op op, char *why, size_t len);

/* MPI_SUCCESS if op (valid) can reduce elements of dt (checked) in a
 * collective; else MPI_ERR_OP and why ("MPI_SUM does not apply to
 * MPI_WCHAR").  MPI_REPLACE and MPI_NO_OP apply to none (they are for
 * MPI_Accumulate). */
int op_check(MPI_Op op, MPI_Datatype dt, char *why, size_t len);

/* 1 if op (valid) is predefined (MPICH's "builtin"). */
int op_is_predefined(MPI_Op op);

/* 1 if op (valid) is commutative: every predefined one is. */
int op_commutative(MPI_Op op);

/* "MPI_SUM", or "a user operation". */
const char *op_name(MPI_Op op);

/* inout = in op inout for count elements of dt, both packed (dtype.h).
 * op and dt passed op_check. */
void op_reduce_packed(MPI_Op op, MPI_Datatype dt, const void *in, void *inout, int count);

/* The same on count elements laid out as dt says (MPI_Reduce_local). */
void op_reduce(MPI_Op op, MPI_Datatype dt, const void *in, void *inout, int count);

/* A new operation of the calling rank (MPI_Op_create), and its end. */
int op_create(MPI_User_function *fn, int commute, MPI_Op *op);
int op_free(MPI_Op op);   /* MPI_ERR_OP for a predefined one */

/* Keep a valid operation usable by op_reduce(_packed) until
 * op_release, whatever MPI_Op_free does meanwhile (a nonblocking
 * collective started with it); nothing for a predefined one. */
void op_hold(MPI_Op op);
void op_release(MPI_Op op);

#endif
