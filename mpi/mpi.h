/* mpi.h -- tilesim's MPI: MPI 3.1's names, constants, types and functions, for programs run on
 * the simulated machine (tilesim-mpicc, tilesim-mpirun).
 *
 * Every C function of MPI 3.1 is declared (mpi_funcs.h lists them, with
 * whether tilesim implements each; doc/mpi-support.md is the same list for
 * people): a program that uses any of them compiles, and one that calls a
 * function tilesim does not implement is stopped with a message naming the
 * rank and the function.
 *
 * HANDLES are plain ints, as in MPICH, so the predefined ones (MPI_COMM_WORLD,
 * MPI_INT, MPI_SUM, ...) are integer constant expressions, usable in static
 * initialisers and switch labels, and valid in every rank.  A handle is
 *
 *     kind << 24 | index          kind: 1 communicator, 2 group, 3 datatype,
 *                                       4 operation, 5 error handler,
 *                                       6 request, 7 info, 8 window, 9 file,
 *                                       10 message
 *
 * index 0 is the kind's null handle (MPI_COMM_NULL, MPI_DATATYPE_NULL, ...);
 * predefined objects have small indices below 0x800000, objects a rank
 * creates have bit 23 set (0x800000 | the slot in that rank's table).
 * Handles are local to the rank that made them, as MPI says.  Handle values
 * and the hidden fields of MPI_Status are tilesim's own: programs must use
 * the names, never the numbers (as with every MPI library).
 *
 * This header is tilesim's only: programs compiled with it run under
 * tilesim-mpirun, not under another MPI's mpirun. */
#ifndef TSMPI_MPI_H
#define TSMPI_MPI_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------
 * Version
 * ------------------------------------------------------------------------ */

#define MPI_VERSION    3
#define MPI_SUBVERSION 1

/* ------------------------------------------------------------------------
 * Types
 * ------------------------------------------------------------------------ */

typedef ptrdiff_t MPI_Aint;   /* an address or an address difference */
typedef long long MPI_Offset; /* a file offset */
typedef long long MPI_Count;  /* holds any MPI_Aint, MPI_Offset or int count */
typedef int MPI_Fint;         /* Fortran INTEGER */

typedef int MPI_Comm;
typedef int MPI_Group;
typedef int MPI_Datatype;
typedef int MPI_Op;
typedef int MPI_Errhandler;
typedef int MPI_Request;
typedef int MPI_Info;
typedef int MPI_Win;
typedef int MPI_File;
typedef int MPI_Message;

/* A receive's status: the three public fields, then tilesim's own. */
typedef struct MPI_Status {
  int MPI_SOURCE;
  int MPI_TAG;
  int MPI_ERROR;
  int tsmpi_cancelled;   /* 1 if the request was cancelled */
  MPI_Count tsmpi_count; /* bytes received */
} MPI_Status;

/* Tool information interface (MPI_T) handles. */
typedef struct tsmpi_t_enum *MPI_T_enum;
typedef struct tsmpi_t_cvar *MPI_T_cvar_handle;
typedef struct tsmpi_t_pvar *MPI_T_pvar_handle;
typedef struct tsmpi_t_session *MPI_T_pvar_session;

/* ------------------------------------------------------------------------
 * Callback function types
 * ------------------------------------------------------------------------ */

typedef void MPI_User_function(void *invec, void *inoutvec, int *len, MPI_Datatype *datatype);

typedef int MPI_Comm_copy_attr_function(MPI_Comm oldcomm, int comm_keyval, void *extra_state,
                                        void *attribute_val_in, void *attribute_val_out, int *flag);
typedef int MPI_Comm_delete_attr_function(MPI_Comm comm, int comm_keyval, void *attribute_val,
                                          void *extra_state);
typedef int MPI_Win_copy_attr_function(MPI_Win oldwin, int win_keyval, void *extra_state,
                                       void *attribute_val_in, void *attribute_val_out, int *flag);
typedef int MPI_Win_delete_attr_function(MPI_Win win, int win_keyval, void *attribute_val,
                                         void *extra_state);
typedef int MPI_Type_copy_attr_function(MPI_Datatype oldtype, int type_keyval, void *extra_state,
                                        void *attribute_val_in, void *attribute_val_out, int *flag);
typedef int MPI_Type_delete_attr_function(MPI_Datatype datatype, int type_keyval,
                                          void *attribute_val, void *extra_state);

typedef void MPI_Comm_errhandler_function(MPI_Comm *comm, int *error_code, ...);
typedef void MPI_Win_errhandler_function(MPI_Win *win, int *error_code, ...);
typedef void MPI_File_errhandler_function(MPI_File *file, int *error_code, ...);

typedef int MPI_Grequest_query_function(void *extra_state, MPI_Status *status);
typedef int MPI_Grequest_free_function(void *extra_state);
typedef int MPI_Grequest_cancel_function(void *extra_state, int complete);

typedef int MPI_Datarep_extent_function(MPI_Datatype datatype, MPI_Aint *file_extent,
                                        void *extra_state);
typedef int MPI_Datarep_conversion_function(void *userbuf, MPI_Datatype datatype, int count,
                                            void *filebuf, MPI_Offset position, void *extra_state);

/* Deprecated since MPI 2.0 (still in MPI 3.1). */
typedef int MPI_Copy_function(MPI_Comm oldcomm, int keyval, void *extra_state,
                              void *attribute_val_in, void *attribute_val_out, int *flag);
typedef int MPI_Delete_function(MPI_Comm comm, int keyval, void *attribute_val, void *extra_state);
/* Deprecated by MPI 2.2, removed by MPI 3.0; kept for old programs. */
typedef MPI_Comm_errhandler_function MPI_Comm_errhandler_fn;
typedef MPI_Win_errhandler_function MPI_Win_errhandler_fn;
typedef MPI_File_errhandler_function MPI_File_errhandler_fn;
typedef MPI_Comm_errhandler_function MPI_Handler_function;

/* ------------------------------------------------------------------------
 * Error classes (MPI 3.1 section 8.4)
 * ------------------------------------------------------------------------ */

#define MPI_SUCCESS                   0
#define MPI_ERR_BUFFER                1
#define MPI_ERR_COUNT                 2
#define MPI_ERR_TYPE                  3
#define MPI_ERR_TAG                   4
#define MPI_ERR_COMM                  5
#define MPI_ERR_RANK                  6
#define MPI_ERR_REQUEST               7
#define MPI_ERR_ROOT                  8
#define MPI_ERR_GROUP                 9
#define MPI_ERR_OP                    10
#define MPI_ERR_TOPOLOGY              11
#define MPI_ERR_DIMS                  12
#define MPI_ERR_ARG                   13
#define MPI_ERR_UNKNOWN               14
#define MPI_ERR_TRUNCATE              15
#define MPI_ERR_OTHER                 16
#define MPI_ERR_INTERN                17
#define MPI_ERR_IN_STATUS             18
#define MPI_ERR_PENDING               19
#define MPI_ERR_KEYVAL                20
#define MPI_ERR_NO_MEM                21
#define MPI_ERR_BASE                  22
#define MPI_ERR_INFO_KEY              23
#define MPI_ERR_INFO_VALUE            24
#define MPI_ERR_INFO_NOKEY            25
#define MPI_ERR_SPAWN                 26
#define MPI_ERR_PORT                  27
#define MPI_ERR_SERVICE               28
#define MPI_ERR_NAME                  29
#define MPI_ERR_WIN                   30
#define MPI_ERR_SIZE                  31
#define MPI_ERR_DISP                  32
#define MPI_ERR_INFO                  33
#define MPI_ERR_LOCKTYPE              34
#define MPI_ERR_ASSERT                35
#define MPI_ERR_RMA_CONFLICT          36
#define MPI_ERR_RMA_SYNC              37
#define MPI_ERR_RMA_RANGE             38
#define MPI_ERR_RMA_ATTACH            39
#define MPI_ERR_RMA_SHARED            40
#define MPI_ERR_RMA_FLAVOR            41
#define MPI_ERR_FILE                  42
#define MPI_ERR_NOT_SAME              43
#define MPI_ERR_AMODE                 44
#define MPI_ERR_UNSUPPORTED_DATAREP   45
#define MPI_ERR_UNSUPPORTED_OPERATION 46
#define MPI_ERR_NO_SUCH_FILE          47
#define MPI_ERR_FILE_EXISTS           48
#define MPI_ERR_BAD_FILE              49
#define MPI_ERR_ACCESS                50
#define MPI_ERR_NO_SPACE              51
#define MPI_ERR_QUOTA                 52
#define MPI_ERR_READ_ONLY             53
#define MPI_ERR_FILE_IN_USE           54
#define MPI_ERR_DUP_DATAREP           55
#define MPI_ERR_CONVERSION            56
#define MPI_ERR_IO                    57
#define MPI_T_ERR_MEMORY              58
#define MPI_T_ERR_NOT_INITIALIZED     59
#define MPI_T_ERR_CANNOT_INIT         60
#define MPI_T_ERR_INVALID_INDEX       61
#define MPI_T_ERR_INVALID_ITEM        62
#define MPI_T_ERR_INVALID_HANDLE      63
#define MPI_T_ERR_OUT_OF_HANDLES      64
#define MPI_T_ERR_OUT_OF_SESSIONS     65
#define MPI_T_ERR_INVALID_SESSION     66
#define MPI_T_ERR_CVAR_SET_NOT_NOW    67
#define MPI_T_ERR_CVAR_SET_NEVER      68
#define MPI_T_ERR_PVAR_NO_STARTSTOP   69
#define MPI_T_ERR_PVAR_NO_WRITE       70
#define MPI_T_ERR_PVAR_NO_ATOMIC      71
#define MPI_T_ERR_INVALID_NAME        72
#define MPI_T_ERR_INVALID             73
#define MPI_ERR_LASTCODE              74

/* ------------------------------------------------------------------------
 * Assorted constants
 * ------------------------------------------------------------------------ */

#define MPI_ANY_SOURCE     (-1)
#define MPI_PROC_NULL      (-2)
#define MPI_ROOT           (-3)
#define MPI_ANY_TAG        (-1)
#define MPI_UNDEFINED      (-32766)
#define MPI_KEYVAL_INVALID (-1)
#define MPI_BSEND_OVERHEAD 64
#define MPI_LOCK_EXCLUSIVE 234
#define MPI_LOCK_SHARED    235

#define MPI_MAX_PROCESSOR_NAME         256
#define MPI_MAX_LIBRARY_VERSION_STRING 256
#define MPI_MAX_ERROR_STRING           256
#define MPI_MAX_DATAREP_STRING         128
#define MPI_MAX_INFO_KEY               255
#define MPI_MAX_INFO_VAL               1024
#define MPI_MAX_OBJECT_NAME            128
#define MPI_MAX_PORT_NAME              256

/* Buffer addresses. */
#define MPI_BOTTOM   ((void *)0)
#define MPI_IN_PLACE ((void *)-1)

/* Ignored or empty arguments. */
#define MPI_STATUS_IGNORE   ((MPI_Status *)0)
#define MPI_STATUSES_IGNORE ((MPI_Status *)0)
#define MPI_ERRCODES_IGNORE ((int *)0)
#define MPI_ARGV_NULL       ((char **)0)
#define MPI_ARGVS_NULL      ((char ***)0)
#define MPI_UNWEIGHTED      ((int *)2)
#define MPI_WEIGHTS_EMPTY   ((int *)3)

/* Fortran status in C (MPI 3.1 section 17.2.5). */
#define MPI_F_STATUS_SIZE     ((int)(sizeof(MPI_Status) / sizeof(MPI_Fint)))
#define MPI_F_SOURCE          0
#define MPI_F_TAG             1
#define MPI_F_ERROR           2
#define MPI_F_STATUS_IGNORE   ((MPI_Fint *)0)
#define MPI_F_STATUSES_IGNORE ((MPI_Fint *)0)

/* ------------------------------------------------------------------------
 * Null and predefined handles
 * ------------------------------------------------------------------------ */

#define MPI_COMM_NULL       ((MPI_Comm)0x01000000)
#define MPI_COMM_WORLD      ((MPI_Comm)0x01000001)
#define MPI_COMM_SELF       ((MPI_Comm)0x01000002)

#define MPI_GROUP_NULL      ((MPI_Group)0x02000000)
#define MPI_GROUP_EMPTY     ((MPI_Group)0x02000001)

#define MPI_DATATYPE_NULL   ((MPI_Datatype)0x03000000)

#define MPI_OP_NULL         ((MPI_Op)0x04000000)

#define MPI_ERRHANDLER_NULL ((MPI_Errhandler)0x05000000)
#define MPI_ERRORS_ARE_FATAL ((MPI_Errhandler)0x05000001)
#define MPI_ERRORS_RETURN   ((MPI_Errhandler)0x05000002)

#define MPI_REQUEST_NULL    ((MPI_Request)0x06000000)

#define MPI_INFO_NULL       ((MPI_Info)0x07000000)
#define MPI_INFO_ENV        ((MPI_Info)0x07000001)

#define MPI_WIN_NULL        ((MPI_Win)0x08000000)

#define MPI_FILE_NULL       ((MPI_File)0x09000000)

#define MPI_MESSAGE_NULL    ((MPI_Message)0x0a000000)
#define MPI_MESSAGE_NO_PROC ((MPI_Message)0x0a000001)

/* ------------------------------------------------------------------------
 * Predefined datatypes (MPI 3.1 sections 3.2.2, 5.9.4, 17.2.6)
 * ------------------------------------------------------------------------ */

/* C */
#define MPI_CHAR                    ((MPI_Datatype)0x03000001)
#define MPI_SIGNED_CHAR             ((MPI_Datatype)0x03000002)
#define MPI_UNSIGNED_CHAR           ((MPI_Datatype)0x03000003)
#define MPI_BYTE                    ((MPI_Datatype)0x03000004)
#define MPI_WCHAR                   ((MPI_Datatype)0x03000005)
#define MPI_SHORT                   ((MPI_Datatype)0x03000006)
#define MPI_UNSIGNED_SHORT          ((MPI_Datatype)0x03000007)
#define MPI_INT                     ((MPI_Datatype)0x03000008)
#define MPI_UNSIGNED                ((MPI_Datatype)0x03000009)
#define MPI_LONG                    ((MPI_Datatype)0x0300000a)
#define MPI_UNSIGNED_LONG           ((MPI_Datatype)0x0300000b)
#define MPI_LONG_LONG_INT           ((MPI_Datatype)0x0300000c)
#define MPI_LONG_LONG               MPI_LONG_LONG_INT /* a synonym, as the standard says */
#define MPI_UNSIGNED_LONG_LONG      ((MPI_Datatype)0x0300000d)
#define MPI_FLOAT                   ((MPI_Datatype)0x0300000e)
#define MPI_DOUBLE                  ((MPI_Datatype)0x0300000f)
#define MPI_LONG_DOUBLE             ((MPI_Datatype)0x03000010)
#define MPI_C_BOOL                  ((MPI_Datatype)0x03000011)
#define MPI_INT8_T                  ((MPI_Datatype)0x03000012)
#define MPI_INT16_T                 ((MPI_Datatype)0x03000013)
#define MPI_INT32_T                 ((MPI_Datatype)0x03000014)
#define MPI_INT64_T                 ((MPI_Datatype)0x03000015)
#define MPI_UINT8_T                 ((MPI_Datatype)0x03000016)
#define MPI_UINT16_T                ((MPI_Datatype)0x03000017)
#define MPI_UINT32_T                ((MPI_Datatype)0x03000018)
#define MPI_UINT64_T                ((MPI_Datatype)0x03000019)
#define MPI_AINT                    ((MPI_Datatype)0x0300001a)
#define MPI_COUNT                   ((MPI_Datatype)0x0300001b)
#define MPI_OFFSET                  ((MPI_Datatype)0x0300001c)
#define MPI_C_FLOAT_COMPLEX         ((MPI_Datatype)0x0300001d)
#define MPI_C_COMPLEX               MPI_C_FLOAT_COMPLEX /* a synonym */
#define MPI_C_DOUBLE_COMPLEX        ((MPI_Datatype)0x0300001e)
#define MPI_C_LONG_DOUBLE_COMPLEX   ((MPI_Datatype)0x0300001f)
#define MPI_PACKED                  ((MPI_Datatype)0x03000020)
/* Pairs for MPI_MINLOC and MPI_MAXLOC: struct { value; int index; } */
#define MPI_FLOAT_INT               ((MPI_Datatype)0x03000021)
#define MPI_DOUBLE_INT              ((MPI_Datatype)0x03000022)
#define MPI_LONG_INT                ((MPI_Datatype)0x03000023)
#define MPI_2INT                    ((MPI_Datatype)0x03000024)
#define MPI_SHORT_INT               ((MPI_Datatype)0x03000025)
#define MPI_LONG_DOUBLE_INT         ((MPI_Datatype)0x03000026)
/* C++ types, usable from C (bool is one byte, the complex types are C's) */
#define MPI_CXX_BOOL                ((MPI_Datatype)0x03000027)
#define MPI_CXX_FLOAT_COMPLEX       ((MPI_Datatype)0x03000028)
#define MPI_CXX_DOUBLE_COMPLEX      ((MPI_Datatype)0x03000029)
#define MPI_CXX_LONG_DOUBLE_COMPLEX ((MPI_Datatype)0x0300002a)
/* Fortran types, usable from C (INTEGER and LOGICAL of 4 bytes, REAL of 4) */
#define MPI_CHARACTER               ((MPI_Datatype)0x0300002b)
#define MPI_LOGICAL                 ((MPI_Datatype)0x0300002c)
#define MPI_INTEGER                 ((MPI_Datatype)0x0300002d)
#define MPI_REAL                    ((MPI_Datatype)0x0300002e)
#define MPI_DOUBLE_PRECISION        ((MPI_Datatype)0x0300002f)
#define MPI_COMPLEX                 ((MPI_Datatype)0x03000030)
#define MPI_DOUBLE_COMPLEX          ((MPI_Datatype)0x03000031)
#define MPI_2REAL                   ((MPI_Datatype)0x03000032)
#define MPI_2DOUBLE_PRECISION       ((MPI_Datatype)0x03000033)
#define MPI_2INTEGER                ((MPI_Datatype)0x03000034)
#define MPI_INTEGER1                ((MPI_Datatype)0x03000035)
#define MPI_INTEGER2                ((MPI_Datatype)0x03000036)
#define MPI_INTEGER4                ((MPI_Datatype)0x03000037)
#define MPI_INTEGER8                ((MPI_Datatype)0x03000038)
#define MPI_REAL4                   ((MPI_Datatype)0x03000039)
#define MPI_REAL8                   ((MPI_Datatype)0x0300003a)
#define MPI_COMPLEX8                ((MPI_Datatype)0x0300003b)
#define MPI_COMPLEX16               ((MPI_Datatype)0x0300003c)
/* Optional Fortran types this machine has no C type for (MPI 3.1 section
 * 17.2.6 lets them be MPI_DATATYPE_NULL). */
#define MPI_INTEGER16               MPI_DATATYPE_NULL
#define MPI_REAL2                   MPI_DATATYPE_NULL
#define MPI_REAL16                  MPI_DATATYPE_NULL
#define MPI_COMPLEX4                MPI_DATATYPE_NULL
#define MPI_COMPLEX32               MPI_DATATYPE_NULL
/* The lower- and upper-bound markers MPI 3.0 removed, as MPICH keeps them:
 * no data; in MPI_Type_create_struct (and MPI_Type_struct) they set the
 * type's bounds (MPI 3.1 section 4.1.7's explicit markers). */
#define MPI_LB                      ((MPI_Datatype)0x0300003d)
#define MPI_UB                      ((MPI_Datatype)0x0300003e)

/* ------------------------------------------------------------------------
 * Predefined reduction operations (MPI 3.1 section 5.9.2)
 * ------------------------------------------------------------------------ */

#define MPI_MAX     ((MPI_Op)0x04000001)
#define MPI_MIN     ((MPI_Op)0x04000002)
#define MPI_SUM     ((MPI_Op)0x04000003)
#define MPI_PROD    ((MPI_Op)0x04000004)
#define MPI_LAND    ((MPI_Op)0x04000005)
#define MPI_BAND    ((MPI_Op)0x04000006)
#define MPI_LOR     ((MPI_Op)0x04000007)
#define MPI_BOR     ((MPI_Op)0x04000008)
#define MPI_LXOR    ((MPI_Op)0x04000009)
#define MPI_BXOR    ((MPI_Op)0x0400000a)
#define MPI_MINLOC  ((MPI_Op)0x0400000b)
#define MPI_MAXLOC  ((MPI_Op)0x0400000c)
#define MPI_REPLACE ((MPI_Op)0x0400000d)
#define MPI_NO_OP   ((MPI_Op)0x0400000e)

/* ------------------------------------------------------------------------
 * Communicators, groups, topologies
 * ------------------------------------------------------------------------ */

/* Results of MPI_Comm_compare and MPI_Group_compare. */
#define MPI_IDENT     0
#define MPI_CONGRUENT 1
#define MPI_SIMILAR   2
#define MPI_UNEQUAL   3

/* MPI_Comm_split_type */
#define MPI_COMM_TYPE_SHARED 1

/* MPI_Topo_test */
#define MPI_GRAPH      1
#define MPI_CART       2
#define MPI_DIST_GRAPH 3

/* Predefined attribute keys (MPI_Comm_get_attr, MPI_Win_get_attr). */
#define MPI_TAG_UB            1
#define MPI_HOST              2
#define MPI_IO                3
#define MPI_WTIME_IS_GLOBAL   4
#define MPI_APPNUM            5
#define MPI_LASTUSEDCODE      6
#define MPI_UNIVERSE_SIZE     7
#define MPI_WIN_BASE          8
#define MPI_WIN_SIZE          9
#define MPI_WIN_DISP_UNIT     10
#define MPI_WIN_CREATE_FLAVOR 11
#define MPI_WIN_MODEL         12

/* Predefined attribute callbacks (defined by tilesim, as the standard's
 * functions of these names). */
MPI_Comm_copy_attr_function MPI_COMM_NULL_COPY_FN, MPI_COMM_DUP_FN;
MPI_Comm_delete_attr_function MPI_COMM_NULL_DELETE_FN;
MPI_Type_copy_attr_function MPI_TYPE_NULL_COPY_FN, MPI_TYPE_DUP_FN;
MPI_Type_delete_attr_function MPI_TYPE_NULL_DELETE_FN;
MPI_Win_copy_attr_function MPI_WIN_NULL_COPY_FN, MPI_WIN_DUP_FN;
MPI_Win_delete_attr_function MPI_WIN_NULL_DELETE_FN;
MPI_Copy_function MPI_NULL_COPY_FN, MPI_DUP_FN;   /* deprecated */
MPI_Delete_function MPI_NULL_DELETE_FN;           /* deprecated */
#define MPI_CONVERSION_FN_NULL ((MPI_Datarep_conversion_function *)0)

/* ------------------------------------------------------------------------
 * Datatype decoding (MPI_Type_get_envelope), classes, distributions
 * ------------------------------------------------------------------------ */

#define MPI_COMBINER_NAMED          1
#define MPI_COMBINER_DUP            2
#define MPI_COMBINER_CONTIGUOUS     3
#define MPI_COMBINER_VECTOR         4
#define MPI_COMBINER_HVECTOR        5
#define MPI_COMBINER_INDEXED        6
#define MPI_COMBINER_HINDEXED       7
#define MPI_COMBINER_INDEXED_BLOCK  8
#define MPI_COMBINER_HINDEXED_BLOCK 9
#define MPI_COMBINER_STRUCT         10
#define MPI_COMBINER_SUBARRAY       11
#define MPI_COMBINER_DARRAY         12
#define MPI_COMBINER_F90_REAL       13
#define MPI_COMBINER_F90_COMPLEX    14
#define MPI_COMBINER_F90_INTEGER    15
#define MPI_COMBINER_RESIZED        16

#define MPI_TYPECLASS_REAL    1
#define MPI_TYPECLASS_INTEGER 2
#define MPI_TYPECLASS_COMPLEX 3

#define MPI_ORDER_C       56
#define MPI_ORDER_FORTRAN 57

#define MPI_DISTRIBUTE_BLOCK     121
#define MPI_DISTRIBUTE_CYCLIC    122
#define MPI_DISTRIBUTE_NONE      123
#define MPI_DISTRIBUTE_DFLT_DARG (-49767)

/* ------------------------------------------------------------------------
 * Threads, one-sided communication, files
 * ------------------------------------------------------------------------ */

#define MPI_THREAD_SINGLE     0
#define MPI_THREAD_FUNNELED   1
#define MPI_THREAD_SERIALIZED 2
#define MPI_THREAD_MULTIPLE   3

/* Window assertions (MPI_Win_fence, MPI_Win_lock, ...) */
#define MPI_MODE_NOCHECK   1024
#define MPI_MODE_NOSTORE   2048
#define MPI_MODE_NOPUT     4096
#define MPI_MODE_NOPRECEDE 8192
#define MPI_MODE_NOSUCCEED 16384

#define MPI_WIN_FLAVOR_CREATE   1
#define MPI_WIN_FLAVOR_ALLOCATE 2
#define MPI_WIN_FLAVOR_DYNAMIC  3
#define MPI_WIN_FLAVOR_SHARED   4
#define MPI_WIN_SEPARATE        1
#define MPI_WIN_UNIFIED         2

/* File access modes (MPI_File_open) */
#define MPI_MODE_CREATE          1
#define MPI_MODE_RDONLY          2
#define MPI_MODE_WRONLY          4
#define MPI_MODE_RDWR            8
#define MPI_MODE_DELETE_ON_CLOSE 16
#define MPI_MODE_UNIQUE_OPEN     32
#define MPI_MODE_EXCL            64
#define MPI_MODE_APPEND          128
#define MPI_MODE_SEQUENTIAL      256

#define MPI_SEEK_SET 600
#define MPI_SEEK_CUR 602
#define MPI_SEEK_END 604
#define MPI_DISPLACEMENT_CURRENT ((MPI_Offset)-54278278)

/* ------------------------------------------------------------------------
 * Tool information interface (MPI 3.1 chapter 14.3)
 * ------------------------------------------------------------------------ */

#define MPI_T_VERBOSITY_USER_BASIC   1
#define MPI_T_VERBOSITY_USER_DETAIL  2
#define MPI_T_VERBOSITY_USER_ALL     3
#define MPI_T_VERBOSITY_TUNER_BASIC  4
#define MPI_T_VERBOSITY_TUNER_DETAIL 5
#define MPI_T_VERBOSITY_TUNER_ALL    6
#define MPI_T_VERBOSITY_MPIDEV_BASIC 7
#define MPI_T_VERBOSITY_MPIDEV_DETAIL 8
#define MPI_T_VERBOSITY_MPIDEV_ALL   9

#define MPI_T_BIND_NO_OBJECT      0
#define MPI_T_BIND_MPI_COMM       1
#define MPI_T_BIND_MPI_DATATYPE   2
#define MPI_T_BIND_MPI_ERRHANDLER 3
#define MPI_T_BIND_MPI_FILE       4
#define MPI_T_BIND_MPI_GROUP      5
#define MPI_T_BIND_MPI_OP         6
#define MPI_T_BIND_MPI_REQUEST    7
#define MPI_T_BIND_MPI_WIN        8
#define MPI_T_BIND_MPI_MESSAGE    9
#define MPI_T_BIND_MPI_INFO       10

#define MPI_T_SCOPE_CONSTANT 0
#define MPI_T_SCOPE_READONLY 1
#define MPI_T_SCOPE_LOCAL    2
#define MPI_T_SCOPE_GROUP    3
#define MPI_T_SCOPE_GROUP_EQ 4
#define MPI_T_SCOPE_ALL      5
#define MPI_T_SCOPE_ALL_EQ   6

#define MPI_T_PVAR_CLASS_STATE         0
#define MPI_T_PVAR_CLASS_LEVEL         1
#define MPI_T_PVAR_CLASS_SIZE          2
#define MPI_T_PVAR_CLASS_PERCENTAGE    3
#define MPI_T_PVAR_CLASS_HIGHWATERMARK 4
#define MPI_T_PVAR_CLASS_LOWWATERMARK  5
#define MPI_T_PVAR_CLASS_COUNTER       6
#define MPI_T_PVAR_CLASS_AGGREGATE     7
#define MPI_T_PVAR_CLASS_TIMER         8
#define MPI_T_PVAR_CLASS_GENERIC       9

#define MPI_T_ENUM_NULL          ((MPI_T_enum)0)
#define MPI_T_CVAR_HANDLE_NULL   ((MPI_T_cvar_handle)0)
#define MPI_T_PVAR_HANDLE_NULL   ((MPI_T_pvar_handle)0)
#define MPI_T_PVAR_SESSION_NULL  ((MPI_T_pvar_session)0)
#define MPI_T_PVAR_ALL_HANDLES   ((MPI_T_pvar_handle)-1)

/* ------------------------------------------------------------------------
 * Functions: every one of MPI 3.1, and its profiling name PMPI_
 * (mpi_funcs.h, one per line with whether tilesim implements it)
 * ------------------------------------------------------------------------ */

#define TSMPI_FN(impl, chapter, ret, name, params, args) ret name params; ret P##name params;
#include "mpi/mpi_funcs.h"
#undef TSMPI_FN

/* ------------------------------------------------------------------------
 * Computing on the simulated machine: the calling rank's processor is busy
 * (tilesim-mpirun(1), --compute)
 * ------------------------------------------------------------------------ */

void tilesim_compute(double units);      /* units x --c seconds */
void smpi_execute_flops(double flops);   /* flops / --flops seconds (SMPI's name) */
void smpi_execute(double seconds);       /* seconds (SMPI's name) */
void smpi_execute_benched(double seconds);

#ifdef __cplusplus
}
#endif

#endif
