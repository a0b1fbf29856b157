/* mpi_funcs.h -- every C function of MPI 3.1, and whether tilesim implements it (an X-macro list).
 *
 * One line per function, grouped by the standard's chapters:
 *
 *   TSMPI_FN(impl, chapter, return type, name, (parameters), (argument names))
 *
 *   impl      1: tilesim implements it; 0: it is declared so that programs
 *             compile, and defined as a stub that stops the run when called
 *             (funcs_unimplemented in mpi/funcs.h: "rank 3 called
 *             MPI_Comm_spawn, which tilesim does not implement").
 *   chapter   ENV (environment, errors), P2P, DTYPE (datatypes), COLL
 *             (collectives and operations), COMM (groups, communicators,
 *             attributes), TOPO, INFO, SPAWN, RMA, EXT (external interfaces,
 *             threads), IO, TOOL (MPI_T), LANG (language interoperability),
 *             REMOVED (removed by MPI 3.0, kept as MPICH keeps them, because
 *             old programs still call them).
 *
 * The list holds the 407 functions of MPI 3.1 (Open MPI 4.1's, an MPI 3.1
 * library, plus MPI_Aint_add and MPI_Aint_diff, which it has as macros) and
 * the 10 REMOVED ones, then MPI-4's additions that tilesim has (MPI4); the
 * parameter names are those of MPICH's manual pages, which follow the
 * standard.
 * tests/cli_mpihdr.sh checks every prototype's types against Open MPI's mpi.h.
 *
 * Define TSMPI_FN, include this file, undefine it: mpi.h declares every
 * function and its PMPI_ name so; mpi/funcs.c defines the stubs and the list
 * as data (funcs_table[], funcs.h), mpi/pmpi.c the implemented functions'
 * PMPI_ names; tests/test_mpilist.c links every function and writes the list
 * of doc/mpi-support.md (which must agree: edit here, then run
 * build/chk/tests/test_mpilist --write doc/mpi-support.md).
 * No include guard: it is meant to be included more than once. */

/* --- ENV --- */
TSMPI_FN(1, ENV, int, MPI_Abort, (MPI_Comm comm, int errorcode),
         (comm, errorcode))
TSMPI_FN(1, ENV, int, MPI_Add_error_class, (int *errorclass),
         (errorclass))
TSMPI_FN(1, ENV, int, MPI_Add_error_code, (int errorclass, int *errorcode),
         (errorclass, errorcode))
TSMPI_FN(1, ENV, int, MPI_Add_error_string, (int errorcode, const char *string),
         (errorcode, string))
TSMPI_FN(1, ENV, int, MPI_Alloc_mem, (MPI_Aint size, MPI_Info info, void *baseptr),
         (size, info, baseptr))
TSMPI_FN(1, ENV, int, MPI_Comm_call_errhandler, (MPI_Comm comm, int errorcode),
         (comm, errorcode))
TSMPI_FN(1, ENV, int, MPI_Comm_create_errhandler, (MPI_Comm_errhandler_function *comm_errhandler_fn,
         MPI_Errhandler *errhandler),
         (comm_errhandler_fn, errhandler))
TSMPI_FN(1, ENV, int, MPI_Comm_get_errhandler, (MPI_Comm comm, MPI_Errhandler *errhandler),
         (comm, errhandler))
TSMPI_FN(1, ENV, int, MPI_Comm_set_errhandler, (MPI_Comm comm, MPI_Errhandler errhandler),
         (comm, errhandler))
TSMPI_FN(1, ENV, int, MPI_Errhandler_free, (MPI_Errhandler *errhandler),
         (errhandler))
TSMPI_FN(1, ENV, int, MPI_Error_class, (int errorcode, int *errorclass),
         (errorcode, errorclass))
TSMPI_FN(1, ENV, int, MPI_Error_string, (int errorcode, char *string, int *resultlen),
         (errorcode, string, resultlen))
TSMPI_FN(1, ENV, int, MPI_Finalize, (void),
         ())
TSMPI_FN(1, ENV, int, MPI_Finalized, (int *flag),
         (flag))
TSMPI_FN(1, ENV, int, MPI_Free_mem, (void *base),
         (base))
TSMPI_FN(1, ENV, int, MPI_Get_library_version, (char *version, int *resultlen),
         (version, resultlen))
TSMPI_FN(1, ENV, int, MPI_Get_processor_name, (char *name, int *resultlen),
         (name, resultlen))
TSMPI_FN(1, ENV, int, MPI_Get_version, (int *version, int *subversion),
         (version, subversion))
TSMPI_FN(1, ENV, int, MPI_Init, (int *argc, char ***argv),
         (argc, argv))
TSMPI_FN(1, ENV, int, MPI_Initialized, (int *flag),
         (flag))
TSMPI_FN(1, ENV, int, MPI_Pcontrol, (const int level, ...),
         (level))
TSMPI_FN(1, ENV, double, MPI_Wtick, (void),
         ())
TSMPI_FN(1, ENV, double, MPI_Wtime, (void),
         ())

/* --- P2P --- */
TSMPI_FN(1, P2P, int, MPI_Bsend, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm),
         (buf, count, datatype, dest, tag, comm))
TSMPI_FN(1, P2P, int, MPI_Bsend_init, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, dest, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Buffer_attach, (void *buffer, int size),
         (buffer, size))
TSMPI_FN(1, P2P, int, MPI_Buffer_detach, (void *buffer_addr, int *size),
         (buffer_addr, size))
TSMPI_FN(1, P2P, int, MPI_Cancel, (MPI_Request *request),
         (request))
TSMPI_FN(1, P2P, int, MPI_Get_count, (const MPI_Status *status, MPI_Datatype datatype, int *count),
         (status, datatype, count))
TSMPI_FN(1, P2P, int, MPI_Ibsend, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, dest, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Improbe, (int source, int tag, MPI_Comm comm, int *flag, MPI_Message *message,
         MPI_Status *status),
         (source, tag, comm, flag, message, status))
TSMPI_FN(1, P2P, int, MPI_Imrecv, (void *buf, int count, MPI_Datatype datatype, MPI_Message *message,
         MPI_Request *request),
         (buf, count, datatype, message, request))
TSMPI_FN(1, P2P, int, MPI_Iprobe, (int source, int tag, MPI_Comm comm, int *flag, MPI_Status *status),
         (source, tag, comm, flag, status))
TSMPI_FN(1, P2P, int, MPI_Irecv, (void *buf, int count, MPI_Datatype datatype, int source, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, source, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Irsend, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, dest, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Isend, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, dest, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Issend, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, dest, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Mprobe, (int source, int tag, MPI_Comm comm, MPI_Message *message,
         MPI_Status *status),
         (source, tag, comm, message, status))
TSMPI_FN(1, P2P, int, MPI_Mrecv, (void *buf, int count, MPI_Datatype datatype, MPI_Message *message,
         MPI_Status *status),
         (buf, count, datatype, message, status))
TSMPI_FN(1, P2P, int, MPI_Probe, (int source, int tag, MPI_Comm comm, MPI_Status *status),
         (source, tag, comm, status))
TSMPI_FN(1, P2P, int, MPI_Recv, (void *buf, int count, MPI_Datatype datatype, int source, int tag,
         MPI_Comm comm, MPI_Status *status),
         (buf, count, datatype, source, tag, comm, status))
TSMPI_FN(1, P2P, int, MPI_Recv_init, (void *buf, int count, MPI_Datatype datatype, int source, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, source, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Request_free, (MPI_Request *request),
         (request))
TSMPI_FN(1, P2P, int, MPI_Request_get_status, (MPI_Request request, int *flag, MPI_Status *status),
         (request, flag, status))
TSMPI_FN(1, P2P, int, MPI_Rsend, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm),
         (buf, count, datatype, dest, tag, comm))
TSMPI_FN(1, P2P, int, MPI_Rsend_init, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, dest, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Send, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm),
         (buf, count, datatype, dest, tag, comm))
TSMPI_FN(1, P2P, int, MPI_Send_init, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, dest, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Sendrecv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, int dest,
         int sendtag, void *recvbuf, int recvcount, MPI_Datatype recvtype, int source, int recvtag,
         MPI_Comm comm, MPI_Status *status),
         (sendbuf, sendcount, sendtype, dest, sendtag, recvbuf, recvcount, recvtype, source, recvtag, comm,
         status))
TSMPI_FN(1, P2P, int, MPI_Sendrecv_replace, (void *buf, int count, MPI_Datatype datatype, int dest,
         int sendtag, int source, int recvtag, MPI_Comm comm, MPI_Status *status),
         (buf, count, datatype, dest, sendtag, source, recvtag, comm, status))
TSMPI_FN(1, P2P, int, MPI_Ssend, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm),
         (buf, count, datatype, dest, tag, comm))
TSMPI_FN(1, P2P, int, MPI_Ssend_init, (const void *buf, int count, MPI_Datatype datatype, int dest, int tag,
         MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, dest, tag, comm, request))
TSMPI_FN(1, P2P, int, MPI_Start, (MPI_Request *request),
         (request))
TSMPI_FN(1, P2P, int, MPI_Startall, (int count, MPI_Request array_of_requests[]),
         (count, array_of_requests))
TSMPI_FN(1, P2P, int, MPI_Test, (MPI_Request *request, int *flag, MPI_Status *status),
         (request, flag, status))
TSMPI_FN(1, P2P, int, MPI_Test_cancelled, (const MPI_Status *status, int *flag),
         (status, flag))
TSMPI_FN(1, P2P, int, MPI_Testall, (int count, MPI_Request array_of_requests[], int *flag,
         MPI_Status array_of_statuses[]),
         (count, array_of_requests, flag, array_of_statuses))
TSMPI_FN(1, P2P, int, MPI_Testany, (int count, MPI_Request array_of_requests[], int *indx, int *flag,
         MPI_Status *status),
         (count, array_of_requests, indx, flag, status))
TSMPI_FN(1, P2P, int, MPI_Testsome, (int incount, MPI_Request array_of_requests[], int *outcount,
         int array_of_indices[], MPI_Status array_of_statuses[]),
         (incount, array_of_requests, outcount, array_of_indices, array_of_statuses))
TSMPI_FN(1, P2P, int, MPI_Wait, (MPI_Request *request, MPI_Status *status),
         (request, status))
TSMPI_FN(1, P2P, int, MPI_Waitall, (int count, MPI_Request array_of_requests[],
         MPI_Status array_of_statuses[]),
         (count, array_of_requests, array_of_statuses))
TSMPI_FN(1, P2P, int, MPI_Waitany, (int count, MPI_Request array_of_requests[], int *indx,
         MPI_Status *status),
         (count, array_of_requests, indx, status))
TSMPI_FN(1, P2P, int, MPI_Waitsome, (int incount, MPI_Request array_of_requests[], int *outcount,
         int array_of_indices[], MPI_Status array_of_statuses[]),
         (incount, array_of_requests, outcount, array_of_indices, array_of_statuses))

/* --- DTYPE --- */
TSMPI_FN(1, DTYPE, MPI_Aint, MPI_Aint_add, (MPI_Aint base, MPI_Aint disp),
         (base, disp))
TSMPI_FN(1, DTYPE, MPI_Aint, MPI_Aint_diff, (MPI_Aint addr1, MPI_Aint addr2),
         (addr1, addr2))
TSMPI_FN(1, DTYPE, int, MPI_Get_address, (const void *location, MPI_Aint *address),
         (location, address))
TSMPI_FN(1, DTYPE, int, MPI_Get_elements, (const MPI_Status *status, MPI_Datatype datatype, int *count),
         (status, datatype, count))
TSMPI_FN(1, DTYPE, int, MPI_Get_elements_x, (const MPI_Status *status, MPI_Datatype datatype,
         MPI_Count *count),
         (status, datatype, count))
TSMPI_FN(1, DTYPE, int, MPI_Pack, (const void *inbuf, int incount, MPI_Datatype datatype, void *outbuf,
         int outsize, int *position, MPI_Comm comm),
         (inbuf, incount, datatype, outbuf, outsize, position, comm))
TSMPI_FN(1, DTYPE, int, MPI_Pack_external, (const char *datarep, const void *inbuf, int incount,
         MPI_Datatype datatype, void *outbuf, MPI_Aint outsize, MPI_Aint *position),
         (datarep, inbuf, incount, datatype, outbuf, outsize, position))
TSMPI_FN(1, DTYPE, int, MPI_Pack_external_size, (const char *datarep, int incount, MPI_Datatype datatype,
         MPI_Aint *size),
         (datarep, incount, datatype, size))
TSMPI_FN(1, DTYPE, int, MPI_Pack_size, (int incount, MPI_Datatype datatype, MPI_Comm comm, int *size),
         (incount, datatype, comm, size))
TSMPI_FN(1, DTYPE, int, MPI_Type_commit, (MPI_Datatype *datatype),
         (datatype))
TSMPI_FN(1, DTYPE, int, MPI_Type_contiguous, (int count, MPI_Datatype oldtype, MPI_Datatype *newtype),
         (count, oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_create_darray, (int size, int rank, int ndims, const int array_of_gsizes[],
         const int array_of_distribs[], const int array_of_dargs[], const int array_of_psizes[], int order,
         MPI_Datatype oldtype, MPI_Datatype *newtype),
         (size, rank, ndims, array_of_gsizes, array_of_distribs, array_of_dargs, array_of_psizes, order,
         oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_create_hindexed, (int count, const int array_of_blocklengths[],
         const MPI_Aint array_of_displacements[], MPI_Datatype oldtype, MPI_Datatype *newtype),
         (count, array_of_blocklengths, array_of_displacements, oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_create_hindexed_block, (int count, int blocklength,
         const MPI_Aint array_of_displacements[], MPI_Datatype oldtype, MPI_Datatype *newtype),
         (count, blocklength, array_of_displacements, oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_create_hvector, (int count, int blocklength, MPI_Aint stride,
         MPI_Datatype oldtype, MPI_Datatype *newtype),
         (count, blocklength, stride, oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_create_indexed_block, (int count, int blocklength,
         const int array_of_displacements[], MPI_Datatype oldtype, MPI_Datatype *newtype),
         (count, blocklength, array_of_displacements, oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_create_keyval, (MPI_Type_copy_attr_function *type_copy_attr_fn,
         MPI_Type_delete_attr_function *type_delete_attr_fn, int *type_keyval, void *extra_state),
         (type_copy_attr_fn, type_delete_attr_fn, type_keyval, extra_state))
TSMPI_FN(1, DTYPE, int, MPI_Type_create_resized, (MPI_Datatype oldtype, MPI_Aint lb, MPI_Aint extent,
         MPI_Datatype *newtype),
         (oldtype, lb, extent, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_create_struct, (int count, const int array_of_blocklengths[],
         const MPI_Aint array_of_displacements[], const MPI_Datatype array_of_types[], MPI_Datatype *newtype),
         (count, array_of_blocklengths, array_of_displacements, array_of_types, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_create_subarray, (int ndims, const int array_of_sizes[],
         const int array_of_subsizes[], const int array_of_starts[], int order, MPI_Datatype oldtype,
         MPI_Datatype *newtype),
         (ndims, array_of_sizes, array_of_subsizes, array_of_starts, order, oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_delete_attr, (MPI_Datatype datatype, int type_keyval),
         (datatype, type_keyval))
TSMPI_FN(1, DTYPE, int, MPI_Type_dup, (MPI_Datatype oldtype, MPI_Datatype *newtype),
         (oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_free, (MPI_Datatype *datatype),
         (datatype))
TSMPI_FN(1, DTYPE, int, MPI_Type_free_keyval, (int *type_keyval),
         (type_keyval))
TSMPI_FN(1, DTYPE, int, MPI_Type_get_attr, (MPI_Datatype datatype, int type_keyval, void *attribute_val,
         int *flag),
         (datatype, type_keyval, attribute_val, flag))
TSMPI_FN(1, DTYPE, int, MPI_Type_get_contents, (MPI_Datatype datatype, int max_integers, int max_addresses,
         int max_datatypes, int array_of_integers[], MPI_Aint array_of_addresses[],
         MPI_Datatype array_of_datatypes[]),
         (datatype, max_integers, max_addresses, max_datatypes, array_of_integers, array_of_addresses,
         array_of_datatypes))
TSMPI_FN(1, DTYPE, int, MPI_Type_get_envelope, (MPI_Datatype datatype, int *num_integers, int *num_addresses,
         int *num_datatypes, int *combiner),
         (datatype, num_integers, num_addresses, num_datatypes, combiner))
TSMPI_FN(1, DTYPE, int, MPI_Type_get_extent, (MPI_Datatype datatype, MPI_Aint *lb, MPI_Aint *extent),
         (datatype, lb, extent))
TSMPI_FN(1, DTYPE, int, MPI_Type_get_extent_x, (MPI_Datatype datatype, MPI_Count *lb, MPI_Count *extent),
         (datatype, lb, extent))
TSMPI_FN(1, DTYPE, int, MPI_Type_get_name, (MPI_Datatype datatype, char *type_name, int *resultlen),
         (datatype, type_name, resultlen))
TSMPI_FN(1, DTYPE, int, MPI_Type_get_true_extent, (MPI_Datatype datatype, MPI_Aint *true_lb,
         MPI_Aint *true_extent),
         (datatype, true_lb, true_extent))
TSMPI_FN(1, DTYPE, int, MPI_Type_get_true_extent_x, (MPI_Datatype datatype, MPI_Count *true_lb,
         MPI_Count *true_extent),
         (datatype, true_lb, true_extent))
TSMPI_FN(1, DTYPE, int, MPI_Type_indexed, (int count, const int array_of_blocklengths[],
         const int array_of_displacements[], MPI_Datatype oldtype, MPI_Datatype *newtype),
         (count, array_of_blocklengths, array_of_displacements, oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Type_set_attr, (MPI_Datatype datatype, int type_keyval, void *attribute_val),
         (datatype, type_keyval, attribute_val))
TSMPI_FN(1, DTYPE, int, MPI_Type_set_name, (MPI_Datatype datatype, const char *type_name),
         (datatype, type_name))
TSMPI_FN(1, DTYPE, int, MPI_Type_size, (MPI_Datatype datatype, int *size),
         (datatype, size))
TSMPI_FN(1, DTYPE, int, MPI_Type_size_x, (MPI_Datatype datatype, MPI_Count *size),
         (datatype, size))
TSMPI_FN(1, DTYPE, int, MPI_Type_vector, (int count, int blocklength, int stride, MPI_Datatype oldtype,
         MPI_Datatype *newtype),
         (count, blocklength, stride, oldtype, newtype))
TSMPI_FN(1, DTYPE, int, MPI_Unpack, (const void *inbuf, int insize, int *position, void *outbuf,
         int outcount, MPI_Datatype datatype, MPI_Comm comm),
         (inbuf, insize, position, outbuf, outcount, datatype, comm))
TSMPI_FN(1, DTYPE, int, MPI_Unpack_external, (const char datarep[], const void *inbuf, MPI_Aint insize,
         MPI_Aint *position, void *outbuf, int outcount, MPI_Datatype datatype),
         (datarep, inbuf, insize, position, outbuf, outcount, datatype))

/* --- COLL --- */
TSMPI_FN(1, COLL, int, MPI_Allgather, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, MPI_Comm comm),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm))
TSMPI_FN(1, COLL, int, MPI_Allgatherv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm),
         (sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm))
TSMPI_FN(1, COLL, int, MPI_Allreduce, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype,
         MPI_Op op, MPI_Comm comm),
         (sendbuf, recvbuf, count, datatype, op, comm))
TSMPI_FN(1, COLL, int, MPI_Alltoall, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, MPI_Comm comm),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm))
TSMPI_FN(1, COLL, int, MPI_Alltoallv, (const void *sendbuf, const int sendcounts[], const int sdispls[],
         MPI_Datatype sendtype, void *recvbuf, const int recvcounts[], const int rdispls[],
         MPI_Datatype recvtype, MPI_Comm comm),
         (sendbuf, sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls, recvtype, comm))
TSMPI_FN(1, COLL, int, MPI_Alltoallw, (const void *sendbuf, const int sendcounts[], const int sdispls[],
         const MPI_Datatype sendtypes[], void *recvbuf, const int recvcounts[], const int rdispls[],
         const MPI_Datatype recvtypes[], MPI_Comm comm),
         (sendbuf, sendcounts, sdispls, sendtypes, recvbuf, recvcounts, rdispls, recvtypes, comm))
TSMPI_FN(1, COLL, int, MPI_Barrier, (MPI_Comm comm),
         (comm))
TSMPI_FN(1, COLL, int, MPI_Bcast, (void *buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm),
         (buffer, count, datatype, root, comm))
TSMPI_FN(1, COLL, int, MPI_Exscan, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype,
         MPI_Op op, MPI_Comm comm),
         (sendbuf, recvbuf, count, datatype, op, comm))
TSMPI_FN(1, COLL, int, MPI_Gather, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, void *recvbuf,
         int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm))
TSMPI_FN(1, COLL, int, MPI_Gatherv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, const int recvcounts[], const int displs[], MPI_Datatype recvtype, int root,
         MPI_Comm comm),
         (sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, root, comm))
TSMPI_FN(1, COLL, int, MPI_Iallgather, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, request))
TSMPI_FN(1, COLL, int, MPI_Iallgatherv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm,
         MPI_Request *request),
         (sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm, request))
TSMPI_FN(1, COLL, int, MPI_Iallreduce, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype,
         MPI_Op op, MPI_Comm comm, MPI_Request *request),
         (sendbuf, recvbuf, count, datatype, op, comm, request))
TSMPI_FN(1, COLL, int, MPI_Ialltoall, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, request))
TSMPI_FN(1, COLL, int, MPI_Ialltoallv, (const void *sendbuf, const int sendcounts[], const int sdispls[],
         MPI_Datatype sendtype, void *recvbuf, const int recvcounts[], const int rdispls[],
         MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls, recvtype, comm, request))
TSMPI_FN(1, COLL, int, MPI_Ialltoallw, (const void *sendbuf, const int sendcounts[], const int sdispls[],
         const MPI_Datatype sendtypes[], void *recvbuf, const int recvcounts[], const int rdispls[],
         const MPI_Datatype recvtypes[], MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcounts, sdispls, sendtypes, recvbuf, recvcounts, rdispls, recvtypes, comm, request))
TSMPI_FN(1, COLL, int, MPI_Ibarrier, (MPI_Comm comm, MPI_Request *request),
         (comm, request))
TSMPI_FN(1, COLL, int, MPI_Ibcast, (void *buffer, int count, MPI_Datatype datatype, int root, MPI_Comm comm,
         MPI_Request *request),
         (buffer, count, datatype, root, comm, request))
TSMPI_FN(1, COLL, int, MPI_Iexscan, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype,
         MPI_Op op, MPI_Comm comm, MPI_Request *request),
         (sendbuf, recvbuf, count, datatype, op, comm, request))
TSMPI_FN(1, COLL, int, MPI_Igather, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm, request))
TSMPI_FN(1, COLL, int, MPI_Igatherv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, const int recvcounts[], const int displs[], MPI_Datatype recvtype, int root,
         MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, root, comm, request))
TSMPI_FN(1, COLL, int, MPI_Ireduce, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype,
         MPI_Op op, int root, MPI_Comm comm, MPI_Request *request),
         (sendbuf, recvbuf, count, datatype, op, root, comm, request))
TSMPI_FN(1, COLL, int, MPI_Ireduce_scatter, (const void *sendbuf, void *recvbuf, const int recvcounts[],
         MPI_Datatype datatype, MPI_Op op, MPI_Comm comm, MPI_Request *request),
         (sendbuf, recvbuf, recvcounts, datatype, op, comm, request))
TSMPI_FN(1, COLL, int, MPI_Ireduce_scatter_block, (const void *sendbuf, void *recvbuf, int recvcount,
         MPI_Datatype datatype, MPI_Op op, MPI_Comm comm, MPI_Request *request),
         (sendbuf, recvbuf, recvcount, datatype, op, comm, request))
TSMPI_FN(1, COLL, int, MPI_Iscan, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype,
         MPI_Op op, MPI_Comm comm, MPI_Request *request),
         (sendbuf, recvbuf, count, datatype, op, comm, request))
TSMPI_FN(1, COLL, int, MPI_Iscatter, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm, request))
TSMPI_FN(1, COLL, int, MPI_Iscatterv, (const void *sendbuf, const int sendcounts[], const int displs[],
         MPI_Datatype sendtype, void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm,
         MPI_Request *request),
         (sendbuf, sendcounts, displs, sendtype, recvbuf, recvcount, recvtype, root, comm, request))
TSMPI_FN(1, COLL, int, MPI_Op_commutative, (MPI_Op op, int *commute),
         (op, commute))
TSMPI_FN(1, COLL, int, MPI_Op_create, (MPI_User_function *user_fn, int commute, MPI_Op *op),
         (user_fn, commute, op))
TSMPI_FN(1, COLL, int, MPI_Op_free, (MPI_Op *op),
         (op))
TSMPI_FN(1, COLL, int, MPI_Reduce, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype,
         MPI_Op op, int root, MPI_Comm comm),
         (sendbuf, recvbuf, count, datatype, op, root, comm))
TSMPI_FN(1, COLL, int, MPI_Reduce_local, (const void *inbuf, void *inoutbuf, int count,
         MPI_Datatype datatype, MPI_Op op),
         (inbuf, inoutbuf, count, datatype, op))
TSMPI_FN(1, COLL, int, MPI_Reduce_scatter, (const void *sendbuf, void *recvbuf, const int recvcounts[],
         MPI_Datatype datatype, MPI_Op op, MPI_Comm comm),
         (sendbuf, recvbuf, recvcounts, datatype, op, comm))
TSMPI_FN(1, COLL, int, MPI_Reduce_scatter_block, (const void *sendbuf, void *recvbuf, int recvcount,
         MPI_Datatype datatype, MPI_Op op, MPI_Comm comm),
         (sendbuf, recvbuf, recvcount, datatype, op, comm))
TSMPI_FN(1, COLL, int, MPI_Scan, (const void *sendbuf, void *recvbuf, int count, MPI_Datatype datatype,
         MPI_Op op, MPI_Comm comm),
         (sendbuf, recvbuf, count, datatype, op, comm))
TSMPI_FN(1, COLL, int, MPI_Scatter, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm))
TSMPI_FN(1, COLL, int, MPI_Scatterv, (const void *sendbuf, const int sendcounts[], const int displs[],
         MPI_Datatype sendtype, void *recvbuf, int recvcount, MPI_Datatype recvtype, int root, MPI_Comm comm),
         (sendbuf, sendcounts, displs, sendtype, recvbuf, recvcount, recvtype, root, comm))

/* --- COMM --- */
TSMPI_FN(1, COMM, int, MPI_Attr_delete, (MPI_Comm comm, int keyval),
         (comm, keyval))
TSMPI_FN(1, COMM, int, MPI_Attr_get, (MPI_Comm comm, int keyval, void *attribute_val, int *flag),
         (comm, keyval, attribute_val, flag))
TSMPI_FN(1, COMM, int, MPI_Attr_put, (MPI_Comm comm, int keyval, void *attribute_val),
         (comm, keyval, attribute_val))
TSMPI_FN(1, COMM, int, MPI_Comm_compare, (MPI_Comm comm1, MPI_Comm comm2, int *result),
         (comm1, comm2, result))
TSMPI_FN(1, COMM, int, MPI_Comm_create, (MPI_Comm comm, MPI_Group group, MPI_Comm *newcomm),
         (comm, group, newcomm))
TSMPI_FN(1, COMM, int, MPI_Comm_create_group, (MPI_Comm comm, MPI_Group group, int tag, MPI_Comm *newcomm),
         (comm, group, tag, newcomm))
TSMPI_FN(1, COMM, int, MPI_Comm_create_keyval, (MPI_Comm_copy_attr_function *comm_copy_attr_fn,
         MPI_Comm_delete_attr_function *comm_delete_attr_fn, int *comm_keyval, void *extra_state),
         (comm_copy_attr_fn, comm_delete_attr_fn, comm_keyval, extra_state))
TSMPI_FN(1, COMM, int, MPI_Comm_delete_attr, (MPI_Comm comm, int comm_keyval),
         (comm, comm_keyval))
TSMPI_FN(1, COMM, int, MPI_Comm_dup, (MPI_Comm comm, MPI_Comm *newcomm),
         (comm, newcomm))
TSMPI_FN(1, COMM, int, MPI_Comm_dup_with_info, (MPI_Comm comm, MPI_Info info, MPI_Comm *newcomm),
         (comm, info, newcomm))
TSMPI_FN(1, COMM, int, MPI_Comm_free, (MPI_Comm *comm),
         (comm))
TSMPI_FN(1, COMM, int, MPI_Comm_free_keyval, (int *comm_keyval),
         (comm_keyval))
TSMPI_FN(1, COMM, int, MPI_Comm_get_attr, (MPI_Comm comm, int comm_keyval, void *attribute_val, int *flag),
         (comm, comm_keyval, attribute_val, flag))
TSMPI_FN(1, COMM, int, MPI_Comm_get_info, (MPI_Comm comm, MPI_Info *info_used),
         (comm, info_used))
TSMPI_FN(1, COMM, int, MPI_Comm_get_name, (MPI_Comm comm, char *comm_name, int *resultlen),
         (comm, comm_name, resultlen))
TSMPI_FN(1, COMM, int, MPI_Comm_group, (MPI_Comm comm, MPI_Group *group),
         (comm, group))
TSMPI_FN(1, COMM, int, MPI_Comm_idup, (MPI_Comm comm, MPI_Comm *newcomm, MPI_Request *request),
         (comm, newcomm, request))
TSMPI_FN(1, COMM, int, MPI_Comm_rank, (MPI_Comm comm, int *rank),
         (comm, rank))
TSMPI_FN(1, COMM, int, MPI_Comm_remote_group, (MPI_Comm comm, MPI_Group *group),
         (comm, group))
TSMPI_FN(1, COMM, int, MPI_Comm_remote_size, (MPI_Comm comm, int *size),
         (comm, size))
TSMPI_FN(1, COMM, int, MPI_Comm_set_attr, (MPI_Comm comm, int comm_keyval, void *attribute_val),
         (comm, comm_keyval, attribute_val))
TSMPI_FN(1, COMM, int, MPI_Comm_set_info, (MPI_Comm comm, MPI_Info info),
         (comm, info))
TSMPI_FN(1, COMM, int, MPI_Comm_set_name, (MPI_Comm comm, const char *comm_name),
         (comm, comm_name))
TSMPI_FN(1, COMM, int, MPI_Comm_size, (MPI_Comm comm, int *size),
         (comm, size))
TSMPI_FN(1, COMM, int, MPI_Comm_split, (MPI_Comm comm, int color, int key, MPI_Comm *newcomm),
         (comm, color, key, newcomm))
TSMPI_FN(1, COMM, int, MPI_Comm_split_type, (MPI_Comm comm, int split_type, int key, MPI_Info info,
         MPI_Comm *newcomm),
         (comm, split_type, key, info, newcomm))
TSMPI_FN(1, COMM, int, MPI_Comm_test_inter, (MPI_Comm comm, int *flag),
         (comm, flag))
TSMPI_FN(1, COMM, int, MPI_Group_compare, (MPI_Group group1, MPI_Group group2, int *result),
         (group1, group2, result))
TSMPI_FN(1, COMM, int, MPI_Group_difference, (MPI_Group group1, MPI_Group group2, MPI_Group *newgroup),
         (group1, group2, newgroup))
TSMPI_FN(1, COMM, int, MPI_Group_excl, (MPI_Group group, int n, const int ranks[], MPI_Group *newgroup),
         (group, n, ranks, newgroup))
TSMPI_FN(1, COMM, int, MPI_Group_free, (MPI_Group *group),
         (group))
TSMPI_FN(1, COMM, int, MPI_Group_incl, (MPI_Group group, int n, const int ranks[], MPI_Group *newgroup),
         (group, n, ranks, newgroup))
TSMPI_FN(1, COMM, int, MPI_Group_intersection, (MPI_Group group1, MPI_Group group2, MPI_Group *newgroup),
         (group1, group2, newgroup))
TSMPI_FN(1, COMM, int, MPI_Group_range_excl, (MPI_Group group, int n, int ranges[][3], MPI_Group *newgroup),
         (group, n, ranges, newgroup))
TSMPI_FN(1, COMM, int, MPI_Group_range_incl, (MPI_Group group, int n, int ranges[][3], MPI_Group *newgroup),
         (group, n, ranges, newgroup))
TSMPI_FN(1, COMM, int, MPI_Group_rank, (MPI_Group group, int *rank),
         (group, rank))
TSMPI_FN(1, COMM, int, MPI_Group_size, (MPI_Group group, int *size),
         (group, size))
TSMPI_FN(1, COMM, int, MPI_Group_translate_ranks, (MPI_Group group1, int n, const int ranks1[],
         MPI_Group group2, int ranks2[]),
         (group1, n, ranks1, group2, ranks2))
TSMPI_FN(1, COMM, int, MPI_Group_union, (MPI_Group group1, MPI_Group group2, MPI_Group *newgroup),
         (group1, group2, newgroup))
TSMPI_FN(1, COMM, int, MPI_Intercomm_create, (MPI_Comm local_comm, int local_leader, MPI_Comm peer_comm,
         int remote_leader, int tag, MPI_Comm *newintercomm),
         (local_comm, local_leader, peer_comm, remote_leader, tag, newintercomm))
TSMPI_FN(1, COMM, int, MPI_Intercomm_merge, (MPI_Comm intercomm, int high, MPI_Comm *newintracomm),
         (intercomm, high, newintracomm))
TSMPI_FN(1, COMM, int, MPI_Keyval_create, (MPI_Copy_function *copy_fn, MPI_Delete_function *delete_fn,
         int *keyval, void *extra_state),
         (copy_fn, delete_fn, keyval, extra_state))
TSMPI_FN(1, COMM, int, MPI_Keyval_free, (int *keyval),
         (keyval))

/* --- TOPO --- */
TSMPI_FN(1, TOPO, int, MPI_Cart_coords, (MPI_Comm comm, int rank, int maxdims, int coords[]),
         (comm, rank, maxdims, coords))
TSMPI_FN(1, TOPO, int, MPI_Cart_create, (MPI_Comm comm_old, int ndims, const int dims[], const int periods[],
         int reorder, MPI_Comm *comm_cart),
         (comm_old, ndims, dims, periods, reorder, comm_cart))
TSMPI_FN(1, TOPO, int, MPI_Cart_get, (MPI_Comm comm, int maxdims, int dims[], int periods[], int coords[]),
         (comm, maxdims, dims, periods, coords))
TSMPI_FN(1, TOPO, int, MPI_Cart_map, (MPI_Comm comm, int ndims, const int dims[], const int periods[],
         int *newrank),
         (comm, ndims, dims, periods, newrank))
TSMPI_FN(1, TOPO, int, MPI_Cart_rank, (MPI_Comm comm, const int coords[], int *rank),
         (comm, coords, rank))
TSMPI_FN(1, TOPO, int, MPI_Cart_shift, (MPI_Comm comm, int direction, int disp, int *rank_source,
         int *rank_dest),
         (comm, direction, disp, rank_source, rank_dest))
TSMPI_FN(1, TOPO, int, MPI_Cart_sub, (MPI_Comm comm, const int remain_dims[], MPI_Comm *newcomm),
         (comm, remain_dims, newcomm))
TSMPI_FN(1, TOPO, int, MPI_Cartdim_get, (MPI_Comm comm, int *ndims),
         (comm, ndims))
TSMPI_FN(1, TOPO, int, MPI_Dims_create, (int nnodes, int ndims, int dims[]),
         (nnodes, ndims, dims))
TSMPI_FN(1, TOPO, int, MPI_Dist_graph_create, (MPI_Comm comm_old, int n, const int sources[],
         const int degrees[], const int destinations[], const int weights[], MPI_Info info, int reorder,
         MPI_Comm *comm_dist_graph),
         (comm_old, n, sources, degrees, destinations, weights, info, reorder, comm_dist_graph))
TSMPI_FN(1, TOPO, int, MPI_Dist_graph_create_adjacent, (MPI_Comm comm_old, int indegree, const int sources[],
         const int sourceweights[], int outdegree, const int destinations[], const int destweights[],
         MPI_Info info, int reorder, MPI_Comm *comm_dist_graph),
         (comm_old, indegree, sources, sourceweights, outdegree, destinations, destweights, info, reorder,
         comm_dist_graph))
TSMPI_FN(1, TOPO, int, MPI_Dist_graph_neighbors, (MPI_Comm comm, int maxindegree, int sources[],
         int sourceweights[], int maxoutdegree, int destinations[], int destweights[]),
         (comm, maxindegree, sources, sourceweights, maxoutdegree, destinations, destweights))
TSMPI_FN(1, TOPO, int, MPI_Dist_graph_neighbors_count, (MPI_Comm comm, int *indegree, int *outdegree,
         int *weighted),
         (comm, indegree, outdegree, weighted))
TSMPI_FN(1, TOPO, int, MPI_Graph_create, (MPI_Comm comm_old, int nnodes, const int indx[], const int edges[],
         int reorder, MPI_Comm *comm_graph),
         (comm_old, nnodes, indx, edges, reorder, comm_graph))
TSMPI_FN(1, TOPO, int, MPI_Graph_get, (MPI_Comm comm, int maxindex, int maxedges, int indx[], int edges[]),
         (comm, maxindex, maxedges, indx, edges))
TSMPI_FN(1, TOPO, int, MPI_Graph_map, (MPI_Comm comm, int nnodes, const int indx[], const int edges[],
         int *newrank),
         (comm, nnodes, indx, edges, newrank))
TSMPI_FN(1, TOPO, int, MPI_Graph_neighbors, (MPI_Comm comm, int rank, int maxneighbors, int neighbors[]),
         (comm, rank, maxneighbors, neighbors))
TSMPI_FN(1, TOPO, int, MPI_Graph_neighbors_count, (MPI_Comm comm, int rank, int *nneighbors),
         (comm, rank, nneighbors))
TSMPI_FN(1, TOPO, int, MPI_Graphdims_get, (MPI_Comm comm, int *nnodes, int *nedges),
         (comm, nnodes, nedges))
TSMPI_FN(1, TOPO, int, MPI_Ineighbor_allgather, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, request))
TSMPI_FN(1, TOPO, int, MPI_Ineighbor_allgatherv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm,
         MPI_Request *request),
         (sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm, request))
TSMPI_FN(1, TOPO, int, MPI_Ineighbor_alltoall, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm, request))
TSMPI_FN(1, TOPO, int, MPI_Ineighbor_alltoallv, (const void *sendbuf, const int sendcounts[],
         const int sdispls[], MPI_Datatype sendtype, void *recvbuf, const int recvcounts[],
         const int rdispls[], MPI_Datatype recvtype, MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls, recvtype, comm, request))
TSMPI_FN(1, TOPO, int, MPI_Ineighbor_alltoallw, (const void *sendbuf, const int sendcounts[],
         const MPI_Aint sdispls[], const MPI_Datatype sendtypes[], void *recvbuf, const int recvcounts[],
         const MPI_Aint rdispls[], const MPI_Datatype recvtypes[], MPI_Comm comm, MPI_Request *request),
         (sendbuf, sendcounts, sdispls, sendtypes, recvbuf, recvcounts, rdispls, recvtypes, comm, request))
TSMPI_FN(1, TOPO, int, MPI_Neighbor_allgather, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, MPI_Comm comm),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm))
TSMPI_FN(1, TOPO, int, MPI_Neighbor_allgatherv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, const int recvcounts[], const int displs[], MPI_Datatype recvtype, MPI_Comm comm),
         (sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm))
TSMPI_FN(1, TOPO, int, MPI_Neighbor_alltoall, (const void *sendbuf, int sendcount, MPI_Datatype sendtype,
         void *recvbuf, int recvcount, MPI_Datatype recvtype, MPI_Comm comm),
         (sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm))
TSMPI_FN(1, TOPO, int, MPI_Neighbor_alltoallv, (const void *sendbuf, const int sendcounts[],
         const int sdispls[], MPI_Datatype sendtype, void *recvbuf, const int recvcounts[],
         const int rdispls[], MPI_Datatype recvtype, MPI_Comm comm),
         (sendbuf, sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls, recvtype, comm))
TSMPI_FN(1, TOPO, int, MPI_Neighbor_alltoallw, (const void *sendbuf, const int sendcounts[],
         const MPI_Aint sdispls[], const MPI_Datatype sendtypes[], void *recvbuf, const int recvcounts[],
         const MPI_Aint rdispls[], const MPI_Datatype recvtypes[], MPI_Comm comm),
         (sendbuf, sendcounts, sdispls, sendtypes, recvbuf, recvcounts, rdispls, recvtypes, comm))
TSMPI_FN(1, TOPO, int, MPI_Topo_test, (MPI_Comm comm, int *status),
         (comm, status))

/* --- INFO --- */
TSMPI_FN(1, INFO, int, MPI_Info_create, (MPI_Info *info),
         (info))
TSMPI_FN(1, INFO, int, MPI_Info_delete, (MPI_Info info, const char *key),
         (info, key))
TSMPI_FN(1, INFO, int, MPI_Info_dup, (MPI_Info info, MPI_Info *newinfo),
         (info, newinfo))
TSMPI_FN(1, INFO, int, MPI_Info_free, (MPI_Info *info),
         (info))
TSMPI_FN(1, INFO, int, MPI_Info_get, (MPI_Info info, const char *key, int valuelen, char *value, int *flag),
         (info, key, valuelen, value, flag))
TSMPI_FN(1, INFO, int, MPI_Info_get_nkeys, (MPI_Info info, int *nkeys),
         (info, nkeys))
TSMPI_FN(1, INFO, int, MPI_Info_get_nthkey, (MPI_Info info, int n, char *key),
         (info, n, key))
TSMPI_FN(1, INFO, int, MPI_Info_get_valuelen, (MPI_Info info, const char *key, int *valuelen, int *flag),
         (info, key, valuelen, flag))
TSMPI_FN(1, INFO, int, MPI_Info_set, (MPI_Info info, const char *key, const char *value),
         (info, key, value))

/* --- SPAWN --- */
TSMPI_FN(0, SPAWN, int, MPI_Close_port, (const char *port_name),
         (port_name))
TSMPI_FN(0, SPAWN, int, MPI_Comm_accept, (const char *port_name, MPI_Info info, int root, MPI_Comm comm,
         MPI_Comm *newcomm),
         (port_name, info, root, comm, newcomm))
TSMPI_FN(0, SPAWN, int, MPI_Comm_connect, (const char *port_name, MPI_Info info, int root, MPI_Comm comm,
         MPI_Comm *newcomm),
         (port_name, info, root, comm, newcomm))
TSMPI_FN(1, SPAWN, int, MPI_Comm_disconnect, (MPI_Comm *comm),
         (comm))
TSMPI_FN(1, SPAWN, int, MPI_Comm_get_parent, (MPI_Comm *parent),
         (parent))
TSMPI_FN(0, SPAWN, int, MPI_Comm_join, (int fd, MPI_Comm *intercomm),
         (fd, intercomm))
TSMPI_FN(0, SPAWN, int, MPI_Comm_spawn, (const char *command, char *argv[], int maxprocs, MPI_Info info,
         int root, MPI_Comm comm, MPI_Comm *intercomm, int array_of_errcodes[]),
         (command, argv, maxprocs, info, root, comm, intercomm, array_of_errcodes))
TSMPI_FN(0, SPAWN, int, MPI_Comm_spawn_multiple, (int count, char *array_of_commands[],
         char **array_of_argv[], const int array_of_maxprocs[], const MPI_Info array_of_info[], int root,
         MPI_Comm comm, MPI_Comm *intercomm, int array_of_errcodes[]),
         (count, array_of_commands, array_of_argv, array_of_maxprocs, array_of_info, root, comm, intercomm,
         array_of_errcodes))
TSMPI_FN(0, SPAWN, int, MPI_Lookup_name, (const char *service_name, MPI_Info info, char *port_name),
         (service_name, info, port_name))
TSMPI_FN(0, SPAWN, int, MPI_Open_port, (MPI_Info info, char *port_name),
         (info, port_name))
TSMPI_FN(0, SPAWN, int, MPI_Publish_name, (const char *service_name, MPI_Info info, const char *port_name),
         (service_name, info, port_name))
TSMPI_FN(0, SPAWN, int, MPI_Unpublish_name, (const char *service_name, MPI_Info info, const char *port_name),
         (service_name, info, port_name))

/* --- RMA --- */
TSMPI_FN(1, RMA, int, MPI_Accumulate, (const void *origin_addr, int origin_count,
         MPI_Datatype origin_datatype, int target_rank, MPI_Aint target_disp, int target_count,
         MPI_Datatype target_datatype, MPI_Op op, MPI_Win win),
         (origin_addr, origin_count, origin_datatype, target_rank, target_disp, target_count,
         target_datatype, op, win))
TSMPI_FN(1, RMA, int, MPI_Compare_and_swap, (const void *origin_addr, const void *compare_addr,
         void *result_addr, MPI_Datatype datatype, int target_rank, MPI_Aint target_disp, MPI_Win win),
         (origin_addr, compare_addr, result_addr, datatype, target_rank, target_disp, win))
TSMPI_FN(1, RMA, int, MPI_Fetch_and_op, (const void *origin_addr, void *result_addr, MPI_Datatype datatype,
         int target_rank, MPI_Aint target_disp, MPI_Op op, MPI_Win win),
         (origin_addr, result_addr, datatype, target_rank, target_disp, op, win))
TSMPI_FN(1, RMA, int, MPI_Get, (void *origin_addr, int origin_count, MPI_Datatype origin_datatype,
         int target_rank, MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Win win),
         (origin_addr, origin_count, origin_datatype, target_rank, target_disp, target_count,
         target_datatype, win))
TSMPI_FN(1, RMA, int, MPI_Get_accumulate, (const void *origin_addr, int origin_count,
         MPI_Datatype origin_datatype, void *result_addr, int result_count, MPI_Datatype result_datatype,
         int target_rank, MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Op op,
         MPI_Win win),
         (origin_addr, origin_count, origin_datatype, result_addr, result_count, result_datatype,
         target_rank, target_disp, target_count, target_datatype, op, win))
TSMPI_FN(1, RMA, int, MPI_Put, (const void *origin_addr, int origin_count, MPI_Datatype origin_datatype,
         int target_rank, MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Win win),
         (origin_addr, origin_count, origin_datatype, target_rank, target_disp, target_count,
         target_datatype, win))
TSMPI_FN(1, RMA, int, MPI_Raccumulate, (const void *origin_addr, int origin_count,
         MPI_Datatype origin_datatype, int target_rank, MPI_Aint target_disp, int target_count,
         MPI_Datatype target_datatype, MPI_Op op, MPI_Win win, MPI_Request *request),
         (origin_addr, origin_count, origin_datatype, target_rank, target_disp, target_count,
         target_datatype, op, win, request))
TSMPI_FN(1, RMA, int, MPI_Rget, (void *origin_addr, int origin_count, MPI_Datatype origin_datatype,
         int target_rank, MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Win win,
         MPI_Request *request),
         (origin_addr, origin_count, origin_datatype, target_rank, target_disp, target_count,
         target_datatype, win, request))
TSMPI_FN(1, RMA, int, MPI_Rget_accumulate, (const void *origin_addr, int origin_count,
         MPI_Datatype origin_datatype, void *result_addr, int result_count, MPI_Datatype result_datatype,
         int target_rank, MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Op op,
         MPI_Win win, MPI_Request *request),
         (origin_addr, origin_count, origin_datatype, result_addr, result_count, result_datatype,
         target_rank, target_disp, target_count, target_datatype, op, win, request))
TSMPI_FN(1, RMA, int, MPI_Rput, (const void *origin_addr, int origin_count, MPI_Datatype origin_datatype,
         int target_rank, MPI_Aint target_disp, int target_count, MPI_Datatype target_datatype, MPI_Win win,
         MPI_Request *request),
         (origin_addr, origin_count, origin_datatype, target_rank, target_disp, target_count,
         target_datatype, win, request))
TSMPI_FN(1, RMA, int, MPI_Win_allocate, (MPI_Aint size, int disp_unit, MPI_Info info, MPI_Comm comm,
         void *baseptr, MPI_Win *win),
         (size, disp_unit, info, comm, baseptr, win))
TSMPI_FN(1, RMA, int, MPI_Win_allocate_shared, (MPI_Aint size, int disp_unit, MPI_Info info, MPI_Comm comm,
         void *baseptr, MPI_Win *win),
         (size, disp_unit, info, comm, baseptr, win))
TSMPI_FN(1, RMA, int, MPI_Win_attach, (MPI_Win win, void *base, MPI_Aint size),
         (win, base, size))
TSMPI_FN(1, RMA, int, MPI_Win_call_errhandler, (MPI_Win win, int errorcode),
         (win, errorcode))
TSMPI_FN(1, RMA, int, MPI_Win_complete, (MPI_Win win),
         (win))
TSMPI_FN(1, RMA, int, MPI_Win_create, (void *base, MPI_Aint size, int disp_unit, MPI_Info info,
         MPI_Comm comm, MPI_Win *win),
         (base, size, disp_unit, info, comm, win))
TSMPI_FN(1, RMA, int, MPI_Win_create_dynamic, (MPI_Info info, MPI_Comm comm, MPI_Win *win),
         (info, comm, win))
TSMPI_FN(1, RMA, int, MPI_Win_create_errhandler, (MPI_Win_errhandler_function *win_errhandler_fn,
         MPI_Errhandler *errhandler),
         (win_errhandler_fn, errhandler))
TSMPI_FN(1, RMA, int, MPI_Win_create_keyval, (MPI_Win_copy_attr_function *win_copy_attr_fn,
         MPI_Win_delete_attr_function *win_delete_attr_fn, int *win_keyval, void *extra_state),
         (win_copy_attr_fn, win_delete_attr_fn, win_keyval, extra_state))
TSMPI_FN(1, RMA, int, MPI_Win_delete_attr, (MPI_Win win, int win_keyval),
         (win, win_keyval))
TSMPI_FN(1, RMA, int, MPI_Win_detach, (MPI_Win win, const void *base),
         (win, base))
TSMPI_FN(1, RMA, int, MPI_Win_fence, (int assert, MPI_Win win),
         (assert, win))
TSMPI_FN(1, RMA, int, MPI_Win_flush, (int rank, MPI_Win win),
         (rank, win))
TSMPI_FN(1, RMA, int, MPI_Win_flush_all, (MPI_Win win),
         (win))
TSMPI_FN(1, RMA, int, MPI_Win_flush_local, (int rank, MPI_Win win),
         (rank, win))
TSMPI_FN(1, RMA, int, MPI_Win_flush_local_all, (MPI_Win win),
         (win))
TSMPI_FN(1, RMA, int, MPI_Win_free, (MPI_Win *win),
         (win))
TSMPI_FN(1, RMA, int, MPI_Win_free_keyval, (int *win_keyval),
         (win_keyval))
TSMPI_FN(1, RMA, int, MPI_Win_get_attr, (MPI_Win win, int win_keyval, void *attribute_val, int *flag),
         (win, win_keyval, attribute_val, flag))
TSMPI_FN(1, RMA, int, MPI_Win_get_errhandler, (MPI_Win win, MPI_Errhandler *errhandler),
         (win, errhandler))
TSMPI_FN(1, RMA, int, MPI_Win_get_group, (MPI_Win win, MPI_Group *group),
         (win, group))
TSMPI_FN(1, RMA, int, MPI_Win_get_info, (MPI_Win win, MPI_Info *info_used),
         (win, info_used))
TSMPI_FN(1, RMA, int, MPI_Win_get_name, (MPI_Win win, char *win_name, int *resultlen),
         (win, win_name, resultlen))
TSMPI_FN(1, RMA, int, MPI_Win_lock, (int lock_type, int rank, int assert, MPI_Win win),
         (lock_type, rank, assert, win))
TSMPI_FN(1, RMA, int, MPI_Win_lock_all, (int assert, MPI_Win win),
         (assert, win))
TSMPI_FN(1, RMA, int, MPI_Win_post, (MPI_Group group, int assert, MPI_Win win),
         (group, assert, win))
TSMPI_FN(1, RMA, int, MPI_Win_set_attr, (MPI_Win win, int win_keyval, void *attribute_val),
         (win, win_keyval, attribute_val))
TSMPI_FN(1, RMA, int, MPI_Win_set_errhandler, (MPI_Win win, MPI_Errhandler errhandler),
         (win, errhandler))
TSMPI_FN(1, RMA, int, MPI_Win_set_info, (MPI_Win win, MPI_Info info),
         (win, info))
TSMPI_FN(1, RMA, int, MPI_Win_set_name, (MPI_Win win, const char *win_name),
         (win, win_name))
TSMPI_FN(1, RMA, int, MPI_Win_shared_query, (MPI_Win win, int rank, MPI_Aint *size, int *disp_unit,
         void *baseptr),
         (win, rank, size, disp_unit, baseptr))
TSMPI_FN(1, RMA, int, MPI_Win_start, (MPI_Group group, int assert, MPI_Win win),
         (group, assert, win))
TSMPI_FN(1, RMA, int, MPI_Win_sync, (MPI_Win win),
         (win))
TSMPI_FN(1, RMA, int, MPI_Win_test, (MPI_Win win, int *flag),
         (win, flag))
TSMPI_FN(1, RMA, int, MPI_Win_unlock, (int rank, MPI_Win win),
         (rank, win))
TSMPI_FN(1, RMA, int, MPI_Win_unlock_all, (MPI_Win win),
         (win))
TSMPI_FN(1, RMA, int, MPI_Win_wait, (MPI_Win win),
         (win))

/* --- EXT --- */
TSMPI_FN(1, EXT, int, MPI_Grequest_complete, (MPI_Request request),
         (request))
TSMPI_FN(1, EXT, int, MPI_Grequest_start, (MPI_Grequest_query_function *query_fn,
         MPI_Grequest_free_function *free_fn, MPI_Grequest_cancel_function *cancel_fn, void *extra_state,
         MPI_Request *request),
         (query_fn, free_fn, cancel_fn, extra_state, request))
TSMPI_FN(1, EXT, int, MPI_Init_thread, (int *argc, char ***argv, int required, int *provided),
         (argc, argv, required, provided))
TSMPI_FN(1, EXT, int, MPI_Is_thread_main, (int *flag),
         (flag))
TSMPI_FN(1, EXT, int, MPI_Query_thread, (int *provided),
         (provided))
TSMPI_FN(1, EXT, int, MPI_Status_set_cancelled, (MPI_Status *status, int flag),
         (status, flag))
TSMPI_FN(1, EXT, int, MPI_Status_set_elements, (MPI_Status *status, MPI_Datatype datatype, int count),
         (status, datatype, count))
TSMPI_FN(1, EXT, int, MPI_Status_set_elements_x, (MPI_Status *status, MPI_Datatype datatype, MPI_Count count),
         (status, datatype, count))

/* --- IO --- */
TSMPI_FN(1, IO, int, MPI_File_call_errhandler, (MPI_File fh, int errorcode),
         (fh, errorcode))
TSMPI_FN(1, IO, int, MPI_File_close, (MPI_File *fh),
         (fh))
TSMPI_FN(1, IO, int, MPI_File_create_errhandler, (MPI_File_errhandler_function *file_errhandler_fn,
         MPI_Errhandler *errhandler),
         (file_errhandler_fn, errhandler))
TSMPI_FN(1, IO, int, MPI_File_delete, (const char *filename, MPI_Info info),
         (filename, info))
TSMPI_FN(1, IO, int, MPI_File_get_amode, (MPI_File fh, int *amode),
         (fh, amode))
TSMPI_FN(1, IO, int, MPI_File_get_atomicity, (MPI_File fh, int *flag),
         (fh, flag))
TSMPI_FN(1, IO, int, MPI_File_get_byte_offset, (MPI_File fh, MPI_Offset offset, MPI_Offset *disp),
         (fh, offset, disp))
TSMPI_FN(1, IO, int, MPI_File_get_errhandler, (MPI_File file, MPI_Errhandler *errhandler),
         (file, errhandler))
TSMPI_FN(1, IO, int, MPI_File_get_group, (MPI_File fh, MPI_Group *group),
         (fh, group))
TSMPI_FN(1, IO, int, MPI_File_get_info, (MPI_File fh, MPI_Info *info_used),
         (fh, info_used))
TSMPI_FN(1, IO, int, MPI_File_get_position, (MPI_File fh, MPI_Offset *offset),
         (fh, offset))
TSMPI_FN(1, IO, int, MPI_File_get_position_shared, (MPI_File fh, MPI_Offset *offset),
         (fh, offset))
TSMPI_FN(1, IO, int, MPI_File_get_size, (MPI_File fh, MPI_Offset *size),
         (fh, size))
TSMPI_FN(1, IO, int, MPI_File_get_type_extent, (MPI_File fh, MPI_Datatype datatype, MPI_Aint *extent),
         (fh, datatype, extent))
TSMPI_FN(1, IO, int, MPI_File_get_view, (MPI_File fh, MPI_Offset *disp, MPI_Datatype *etype,
         MPI_Datatype *filetype, char *datarep),
         (fh, disp, etype, filetype, datarep))
TSMPI_FN(1, IO, int, MPI_File_iread, (MPI_File fh, void *buf, int count, MPI_Datatype datatype,
         MPI_Request *request),
         (fh, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_iread_all, (MPI_File fh, void *buf, int count, MPI_Datatype datatype,
         MPI_Request *request),
         (fh, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_iread_at, (MPI_File fh, MPI_Offset offset, void *buf, int count,
         MPI_Datatype datatype, MPI_Request *request),
         (fh, offset, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_iread_at_all, (MPI_File fh, MPI_Offset offset, void *buf, int count,
         MPI_Datatype datatype, MPI_Request *request),
         (fh, offset, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_iread_shared, (MPI_File fh, void *buf, int count, MPI_Datatype datatype,
         MPI_Request *request),
         (fh, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_iwrite, (MPI_File fh, const void *buf, int count, MPI_Datatype datatype,
         MPI_Request *request),
         (fh, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_iwrite_all, (MPI_File fh, const void *buf, int count, MPI_Datatype datatype,
         MPI_Request *request),
         (fh, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_iwrite_at, (MPI_File fh, MPI_Offset offset, const void *buf, int count,
         MPI_Datatype datatype, MPI_Request *request),
         (fh, offset, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_iwrite_at_all, (MPI_File fh, MPI_Offset offset, const void *buf, int count,
         MPI_Datatype datatype, MPI_Request *request),
         (fh, offset, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_iwrite_shared, (MPI_File fh, const void *buf, int count, MPI_Datatype datatype,
         MPI_Request *request),
         (fh, buf, count, datatype, request))
TSMPI_FN(1, IO, int, MPI_File_open, (MPI_Comm comm, const char *filename, int amode, MPI_Info info,
         MPI_File *fh),
         (comm, filename, amode, info, fh))
TSMPI_FN(1, IO, int, MPI_File_preallocate, (MPI_File fh, MPI_Offset size),
         (fh, size))
TSMPI_FN(1, IO, int, MPI_File_read, (MPI_File fh, void *buf, int count, MPI_Datatype datatype,
         MPI_Status *status),
         (fh, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_read_all, (MPI_File fh, void *buf, int count, MPI_Datatype datatype,
         MPI_Status *status),
         (fh, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_read_all_begin, (MPI_File fh, void *buf, int count, MPI_Datatype datatype),
         (fh, buf, count, datatype))
TSMPI_FN(1, IO, int, MPI_File_read_all_end, (MPI_File fh, void *buf, MPI_Status *status),
         (fh, buf, status))
TSMPI_FN(1, IO, int, MPI_File_read_at, (MPI_File fh, MPI_Offset offset, void *buf, int count,
         MPI_Datatype datatype, MPI_Status *status),
         (fh, offset, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_read_at_all, (MPI_File fh, MPI_Offset offset, void *buf, int count,
         MPI_Datatype datatype, MPI_Status *status),
         (fh, offset, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_read_at_all_begin, (MPI_File fh, MPI_Offset offset, void *buf, int count,
         MPI_Datatype datatype),
         (fh, offset, buf, count, datatype))
TSMPI_FN(1, IO, int, MPI_File_read_at_all_end, (MPI_File fh, void *buf, MPI_Status *status),
         (fh, buf, status))
TSMPI_FN(1, IO, int, MPI_File_read_ordered, (MPI_File fh, void *buf, int count, MPI_Datatype datatype,
         MPI_Status *status),
         (fh, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_read_ordered_begin, (MPI_File fh, void *buf, int count, MPI_Datatype datatype),
         (fh, buf, count, datatype))
TSMPI_FN(1, IO, int, MPI_File_read_ordered_end, (MPI_File fh, void *buf, MPI_Status *status),
         (fh, buf, status))
TSMPI_FN(1, IO, int, MPI_File_read_shared, (MPI_File fh, void *buf, int count, MPI_Datatype datatype,
         MPI_Status *status),
         (fh, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_seek, (MPI_File fh, MPI_Offset offset, int whence),
         (fh, offset, whence))
TSMPI_FN(1, IO, int, MPI_File_seek_shared, (MPI_File fh, MPI_Offset offset, int whence),
         (fh, offset, whence))
TSMPI_FN(1, IO, int, MPI_File_set_atomicity, (MPI_File fh, int flag),
         (fh, flag))
TSMPI_FN(1, IO, int, MPI_File_set_errhandler, (MPI_File file, MPI_Errhandler errhandler),
         (file, errhandler))
TSMPI_FN(1, IO, int, MPI_File_set_info, (MPI_File fh, MPI_Info info),
         (fh, info))
TSMPI_FN(1, IO, int, MPI_File_set_size, (MPI_File fh, MPI_Offset size),
         (fh, size))
TSMPI_FN(1, IO, int, MPI_File_set_view, (MPI_File fh, MPI_Offset disp, MPI_Datatype etype,
         MPI_Datatype filetype, const char *datarep, MPI_Info info),
         (fh, disp, etype, filetype, datarep, info))
TSMPI_FN(1, IO, int, MPI_File_sync, (MPI_File fh),
         (fh))
TSMPI_FN(1, IO, int, MPI_File_write, (MPI_File fh, const void *buf, int count, MPI_Datatype datatype,
         MPI_Status *status),
         (fh, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_write_all, (MPI_File fh, const void *buf, int count, MPI_Datatype datatype,
         MPI_Status *status),
         (fh, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_write_all_begin, (MPI_File fh, const void *buf, int count,
         MPI_Datatype datatype),
         (fh, buf, count, datatype))
TSMPI_FN(1, IO, int, MPI_File_write_all_end, (MPI_File fh, const void *buf, MPI_Status *status),
         (fh, buf, status))
TSMPI_FN(1, IO, int, MPI_File_write_at, (MPI_File fh, MPI_Offset offset, const void *buf, int count,
         MPI_Datatype datatype, MPI_Status *status),
         (fh, offset, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_write_at_all, (MPI_File fh, MPI_Offset offset, const void *buf, int count,
         MPI_Datatype datatype, MPI_Status *status),
         (fh, offset, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_write_at_all_begin, (MPI_File fh, MPI_Offset offset, const void *buf,
         int count, MPI_Datatype datatype),
         (fh, offset, buf, count, datatype))
TSMPI_FN(1, IO, int, MPI_File_write_at_all_end, (MPI_File fh, const void *buf, MPI_Status *status),
         (fh, buf, status))
TSMPI_FN(1, IO, int, MPI_File_write_ordered, (MPI_File fh, const void *buf, int count, MPI_Datatype datatype,
         MPI_Status *status),
         (fh, buf, count, datatype, status))
TSMPI_FN(1, IO, int, MPI_File_write_ordered_begin, (MPI_File fh, const void *buf, int count,
         MPI_Datatype datatype),
         (fh, buf, count, datatype))
TSMPI_FN(1, IO, int, MPI_File_write_ordered_end, (MPI_File fh, const void *buf, MPI_Status *status),
         (fh, buf, status))
TSMPI_FN(1, IO, int, MPI_File_write_shared, (MPI_File fh, const void *buf, int count, MPI_Datatype datatype,
         MPI_Status *status),
         (fh, buf, count, datatype, status))
TSMPI_FN(0, IO, int, MPI_Register_datarep, (const char *datarep,
         MPI_Datarep_conversion_function *read_conversion_fn,
         MPI_Datarep_conversion_function *write_conversion_fn,
         MPI_Datarep_extent_function *dtype_file_extent_fn, void *extra_state),
         (datarep, read_conversion_fn, write_conversion_fn, dtype_file_extent_fn, extra_state))

/* --- TOOL --- */
TSMPI_FN(0, TOOL, int, MPI_T_category_changed, (int *update_number),
         (update_number))
TSMPI_FN(0, TOOL, int, MPI_T_category_get_categories, (int cat_index, int len, int indices[]),
         (cat_index, len, indices))
TSMPI_FN(0, TOOL, int, MPI_T_category_get_cvars, (int cat_index, int len, int indices[]),
         (cat_index, len, indices))
TSMPI_FN(0, TOOL, int, MPI_T_category_get_index, (const char *name, int *cat_index),
         (name, cat_index))
TSMPI_FN(0, TOOL, int, MPI_T_category_get_info, (int cat_index, char *name, int *name_len, char *desc,
         int *desc_len, int *num_cvars, int *num_pvars, int *num_categories),
         (cat_index, name, name_len, desc, desc_len, num_cvars, num_pvars, num_categories))
TSMPI_FN(0, TOOL, int, MPI_T_category_get_num, (int *num_cat),
         (num_cat))
TSMPI_FN(0, TOOL, int, MPI_T_category_get_pvars, (int cat_index, int len, int indices[]),
         (cat_index, len, indices))
TSMPI_FN(0, TOOL, int, MPI_T_cvar_get_index, (const char *name, int *cvar_index),
         (name, cvar_index))
TSMPI_FN(0, TOOL, int, MPI_T_cvar_get_info, (int cvar_index, char *name, int *name_len, int *verbosity,
         MPI_Datatype *datatype, MPI_T_enum *enumtype, char *desc, int *desc_len, int *bind, int *scope),
         (cvar_index, name, name_len, verbosity, datatype, enumtype, desc, desc_len, bind, scope))
TSMPI_FN(0, TOOL, int, MPI_T_cvar_get_num, (int *num_cvar),
         (num_cvar))
TSMPI_FN(0, TOOL, int, MPI_T_cvar_handle_alloc, (int cvar_index, void *obj_handle, MPI_T_cvar_handle *handle,
         int *count),
         (cvar_index, obj_handle, handle, count))
TSMPI_FN(0, TOOL, int, MPI_T_cvar_handle_free, (MPI_T_cvar_handle *handle),
         (handle))
TSMPI_FN(0, TOOL, int, MPI_T_cvar_read, (MPI_T_cvar_handle handle, void *buf),
         (handle, buf))
TSMPI_FN(0, TOOL, int, MPI_T_cvar_write, (MPI_T_cvar_handle handle, const void *buf),
         (handle, buf))
TSMPI_FN(0, TOOL, int, MPI_T_enum_get_info, (MPI_T_enum enumtype, int *num, char *name, int *name_len),
         (enumtype, num, name, name_len))
TSMPI_FN(0, TOOL, int, MPI_T_enum_get_item, (MPI_T_enum enumtype, int indx, int *value, char *name,
         int *name_len),
         (enumtype, indx, value, name, name_len))
TSMPI_FN(0, TOOL, int, MPI_T_finalize, (void),
         ())
TSMPI_FN(0, TOOL, int, MPI_T_init_thread, (int required, int *provided),
         (required, provided))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_get_index, (const char *name, int var_class, int *pvar_index),
         (name, var_class, pvar_index))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_get_info, (int pvar_index, char *name, int *name_len, int *verbosity,
         int *var_class, MPI_Datatype *datatype, MPI_T_enum *enumtype, char *desc, int *desc_len, int *bind,
         int *readonly, int *continuous, int *atomic),
         (pvar_index, name, name_len, verbosity, var_class, datatype, enumtype, desc, desc_len, bind,
         readonly, continuous, atomic))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_get_num, (int *num_pvar),
         (num_pvar))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_handle_alloc, (MPI_T_pvar_session session, int pvar_index,
         void *obj_handle, MPI_T_pvar_handle *handle, int *count),
         (session, pvar_index, obj_handle, handle, count))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_handle_free, (MPI_T_pvar_session session, MPI_T_pvar_handle *handle),
         (session, handle))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_read, (MPI_T_pvar_session session, MPI_T_pvar_handle handle, void *buf),
         (session, handle, buf))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_readreset, (MPI_T_pvar_session session, MPI_T_pvar_handle handle,
         void *buf),
         (session, handle, buf))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_reset, (MPI_T_pvar_session session, MPI_T_pvar_handle handle),
         (session, handle))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_session_create, (MPI_T_pvar_session *session),
         (session))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_session_free, (MPI_T_pvar_session *session),
         (session))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_start, (MPI_T_pvar_session session, MPI_T_pvar_handle handle),
         (session, handle))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_stop, (MPI_T_pvar_session session, MPI_T_pvar_handle handle),
         (session, handle))
TSMPI_FN(0, TOOL, int, MPI_T_pvar_write, (MPI_T_pvar_session session, MPI_T_pvar_handle handle,
         const void *buf),
         (session, handle, buf))

/* --- LANG --- */
TSMPI_FN(1, LANG, MPI_Fint, MPI_Comm_c2f, (MPI_Comm comm),
         (comm))
TSMPI_FN(1, LANG, MPI_Comm, MPI_Comm_f2c, (MPI_Fint comm),
         (comm))
TSMPI_FN(1, LANG, MPI_Fint, MPI_Errhandler_c2f, (MPI_Errhandler errhandler),
         (errhandler))
TSMPI_FN(1, LANG, MPI_Errhandler, MPI_Errhandler_f2c, (MPI_Fint errhandler),
         (errhandler))
TSMPI_FN(1, LANG, MPI_Fint, MPI_File_c2f, (MPI_File fh),
         (fh))
TSMPI_FN(1, LANG, MPI_File, MPI_File_f2c, (MPI_Fint fh),
         (fh))
TSMPI_FN(1, LANG, MPI_Fint, MPI_Group_c2f, (MPI_Group group),
         (group))
TSMPI_FN(1, LANG, MPI_Group, MPI_Group_f2c, (MPI_Fint group),
         (group))
TSMPI_FN(1, LANG, MPI_Fint, MPI_Info_c2f, (MPI_Info info),
         (info))
TSMPI_FN(1, LANG, MPI_Info, MPI_Info_f2c, (MPI_Fint info),
         (info))
TSMPI_FN(1, LANG, MPI_Fint, MPI_Message_c2f, (MPI_Message message),
         (message))
TSMPI_FN(1, LANG, MPI_Message, MPI_Message_f2c, (MPI_Fint message),
         (message))
TSMPI_FN(1, LANG, MPI_Fint, MPI_Op_c2f, (MPI_Op op),
         (op))
TSMPI_FN(1, LANG, MPI_Op, MPI_Op_f2c, (MPI_Fint op),
         (op))
TSMPI_FN(1, LANG, MPI_Fint, MPI_Request_c2f, (MPI_Request request),
         (request))
TSMPI_FN(1, LANG, MPI_Request, MPI_Request_f2c, (MPI_Fint request),
         (request))
TSMPI_FN(1, LANG, int, MPI_Status_c2f, (const MPI_Status *c_status, MPI_Fint *f_status),
         (c_status, f_status))
TSMPI_FN(1, LANG, int, MPI_Status_f2c, (const MPI_Fint *f_status, MPI_Status *c_status),
         (f_status, c_status))
TSMPI_FN(1, LANG, MPI_Fint, MPI_Type_c2f, (MPI_Datatype datatype),
         (datatype))
TSMPI_FN(0, LANG, int, MPI_Type_create_f90_complex, (int p, int r, MPI_Datatype *newtype),
         (p, r, newtype))
TSMPI_FN(0, LANG, int, MPI_Type_create_f90_integer, (int r, MPI_Datatype *newtype),
         (r, newtype))
TSMPI_FN(0, LANG, int, MPI_Type_create_f90_real, (int p, int r, MPI_Datatype *newtype),
         (p, r, newtype))
TSMPI_FN(1, LANG, MPI_Datatype, MPI_Type_f2c, (MPI_Fint datatype),
         (datatype))
TSMPI_FN(1, LANG, int, MPI_Type_match_size, (int typeclass, int size, MPI_Datatype *datatype),
         (typeclass, size, datatype))
TSMPI_FN(1, LANG, MPI_Fint, MPI_Win_c2f, (MPI_Win win),
         (win))
TSMPI_FN(1, LANG, MPI_Win, MPI_Win_f2c, (MPI_Fint win),
         (win))

/* --- REMOVED --- */
TSMPI_FN(1, REMOVED, int, MPI_Address, (void *location, MPI_Aint *address),
         (location, address))
TSMPI_FN(1, REMOVED, int, MPI_Errhandler_create, (MPI_Comm_errhandler_function *comm_errhandler_fn,
         MPI_Errhandler *errhandler),
         (comm_errhandler_fn, errhandler))
TSMPI_FN(1, REMOVED, int, MPI_Errhandler_get, (MPI_Comm comm, MPI_Errhandler *errhandler),
         (comm, errhandler))
TSMPI_FN(1, REMOVED, int, MPI_Errhandler_set, (MPI_Comm comm, MPI_Errhandler errhandler),
         (comm, errhandler))
TSMPI_FN(1, REMOVED, int, MPI_Type_extent, (MPI_Datatype datatype, MPI_Aint *extent),
         (datatype, extent))
TSMPI_FN(1, REMOVED, int, MPI_Type_hindexed, (int count, int array_of_blocklengths[],
         MPI_Aint array_of_displacements[], MPI_Datatype oldtype, MPI_Datatype *newtype),
         (count, array_of_blocklengths, array_of_displacements, oldtype, newtype))
TSMPI_FN(1, REMOVED, int, MPI_Type_hvector, (int count, int blocklength, MPI_Aint stride,
         MPI_Datatype oldtype, MPI_Datatype *newtype),
         (count, blocklength, stride, oldtype, newtype))
TSMPI_FN(1, REMOVED, int, MPI_Type_lb, (MPI_Datatype datatype, MPI_Aint *displacement),
         (datatype, displacement))
TSMPI_FN(1, REMOVED, int, MPI_Type_struct, (int count, int array_of_blocklengths[],
         MPI_Aint array_of_displacements[], MPI_Datatype array_of_types[], MPI_Datatype *newtype),
         (count, array_of_blocklengths, array_of_displacements, array_of_types, newtype))
TSMPI_FN(1, REMOVED, int, MPI_Type_ub, (MPI_Datatype datatype, MPI_Aint *displacement),
         (datatype, displacement))

/* --- MPI4 --- */
TSMPI_FN(1, MPI4, int, MPI_Isendrecv, (const void *sendbuf, int sendcount, MPI_Datatype sendtype, int dest,
         int sendtag, void *recvbuf, int recvcount, MPI_Datatype recvtype, int source, int recvtag, MPI_Comm comm,
         MPI_Request *request),
         (sendbuf, sendcount, sendtype, dest, sendtag, recvbuf, recvcount, recvtype, source, recvtag, comm, request))
TSMPI_FN(1, MPI4, int, MPI_Isendrecv_replace, (void *buf, int count, MPI_Datatype datatype, int dest, int sendtag,
         int source, int recvtag, MPI_Comm comm, MPI_Request *request),
         (buf, count, datatype, dest, sendtag, source, recvtag, comm, request))
