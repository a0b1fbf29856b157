/* lang.c -- language interoperability (MPI 3.1 section 17.2.4): handles
 * between C and Fortran.  Every handle is an int (mpi.h), the same in both
 * languages: the conversions give it back unchanged, valid or not, as
 * MPICH's do; a status is the same words (MPI_F_STATUS_SIZE of them). */
#include <string.h>

#include "mpi/mpi.h"

#define IDENTITY(type, c2f, f2c)                         \
  MPI_Fint P##c2f(type h) { return (MPI_Fint)h; }        \
  type P##f2c(MPI_Fint h) { return (type)h; }

IDENTITY(MPI_Comm, MPI_Comm_c2f, MPI_Comm_f2c)
IDENTITY(MPI_Errhandler, MPI_Errhandler_c2f, MPI_Errhandler_f2c)
IDENTITY(MPI_File, MPI_File_c2f, MPI_File_f2c)
IDENTITY(MPI_Group, MPI_Group_c2f, MPI_Group_f2c)
IDENTITY(MPI_Info, MPI_Info_c2f, MPI_Info_f2c)
IDENTITY(MPI_Message, MPI_Message_c2f, MPI_Message_f2c)
IDENTITY(MPI_Op, MPI_Op_c2f, MPI_Op_f2c)
IDENTITY(MPI_Request, MPI_Request_c2f, MPI_Request_f2c)
IDENTITY(MPI_Datatype, MPI_Type_c2f, MPI_Type_f2c)
IDENTITY(MPI_Win, MPI_Win_c2f, MPI_Win_f2c)

/* MPI_STATUS_IGNORE and MPI_F_STATUS_IGNORE cannot be converted:
 * MPI_ERR_ARG, returned (no handler: these may be called outside MPI_Init). */
int PMPI_Status_c2f(const MPI_Status *c_status, MPI_Fint *f_status) {
  if (!c_status || !f_status) return MPI_ERR_ARG;
  memcpy(f_status, c_status, sizeof *c_status);
  return MPI_SUCCESS;
}

int PMPI_Status_f2c(const MPI_Fint *f_status, MPI_Status *c_status) {
  if (!c_status || !f_status) return MPI_ERR_ARG;
  memcpy(c_status, f_status, sizeof *c_status);
  return MPI_SUCCESS;
}
