/* op_api.c -- the MPI functions of operations: MPI_Op_create, MPI_Op_free, MPI_Op_commutative,
 * MPI_Reduce_local (mpi.h; built on op.h).  Errors go to MPI_COMM_WORLD's handler (MPI 3.1
 * section 8.3: calls with no communicator). */
#include <stddef.h>

#include "mpi/dtype.h"
#include "mpi/mpi.h"
#include "mpi/op.h"
#include "mpi/core.h"

int PMPI_Op_create(MPI_User_function *user_fn, int commute, MPI_Op *op) {
  static const char fn[] = "MPI_Op_create";
  if (!user_fn || !op) return err_comm_raise(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "%s is NULL", user_fn ? "op" : "user_fn");
  int rc = op_create(user_fn, commute, op);
  return rc ? err_comm_raise(MPI_COMM_WORLD, rc, fn, "out of memory") : rc;
}

int PMPI_Op_free(MPI_Op *op) {
  static const char fn[] = "MPI_Op_free";
  char why[96];
  if (!op) return err_comm_raise(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "op is NULL");
  if (op_valid(*op, why, sizeof why) != MPI_SUCCESS)
    return err_comm_raise(MPI_COMM_WORLD, MPI_ERR_OP, fn, "invalid operation: %s", why);
  if (op_free(*op) != MPI_SUCCESS)
    return err_comm_raise(MPI_COMM_WORLD, MPI_ERR_OP, fn, "%s is predefined and cannot be freed", op_name(*op));
  *op = MPI_OP_NULL;
  return MPI_SUCCESS;
}

int PMPI_Op_commutative(MPI_Op op, int *commute) {
  static const char fn[] = "MPI_Op_commutative";
  char why[96];
  if (op_valid(op, why, sizeof why) != MPI_SUCCESS)
    return err_comm_raise(MPI_COMM_WORLD, MPI_ERR_OP, fn, "invalid operation: %s", why);
  if (!commute) return err_comm_raise(MPI_COMM_WORLD, MPI_ERR_ARG, fn, "commute is NULL");
  *commute = op_commutative(op);
  return MPI_SUCCESS;
}

/* MPI 3.1 section 5.9.7: inoutbuf = inbuf op inoutbuf, locally. */
int PMPI_Reduce_local(const void *inbuf, void *inoutbuf, int count, MPI_Datatype datatype, MPI_Op op) {
  static const char fn[] = "MPI_Reduce_local";
  MPI_Comm w = MPI_COMM_WORLD;
  char why[96];
  int rc;
  if ((rc = err_comm_check_count(w, fn, count))) return rc;
  if (dtype_check(datatype, why, sizeof why) != MPI_SUCCESS)
    return err_comm_raise(w, MPI_ERR_TYPE, fn, "invalid datatype: %s", why);
  if (op_valid(op, why, sizeof why) != MPI_SUCCESS)
    return err_comm_raise(w, MPI_ERR_OP, fn, "invalid operation: %s", why);
  if (op_check(op, datatype, why, sizeof why) != MPI_SUCCESS) return err_comm_raise(w, MPI_ERR_OP, fn, "%s", why);
  if (inbuf == MPI_IN_PLACE || inoutbuf == MPI_IN_PLACE)
    return err_comm_raise(w, MPI_ERR_BUFFER, fn, "MPI_IN_PLACE is not allowed here");
  if ((rc = err_comm_check_buf(w, fn, inbuf, count, datatype)) || (rc = err_comm_check_buf(w, fn, inoutbuf, count, datatype)))
    return rc;
  if (count > 0) op_reduce(op, datatype, inbuf, inoutbuf, count);
  return MPI_SUCCESS;
}
