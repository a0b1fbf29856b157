/* err.c -- error handlers, argument checks, error classes and strings. */
#include "mpi/err.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "mpi/init.h"
#include "mpi/errh.h"

/* ==== raising ============================================================= */

/* Apply handler eh of object `handle` to error cls of call fn. */
static int vapply(st_rank *R, MPI_Errhandler eh, int handle, int cls, const char *fn, const char *fmt, va_list ap) {
  if (eh == MPI_ERRORS_RETURN) return cls;
  errh_fn *f = errh_function(R, eh);
  if (f) {
    int h = handle, code = cls;
    f(&h, &code);
    return cls;
  }
  char why[1024];
  int n = snprintf(why, sizeof why, "rank %d: %s: ", R->wrank, fn);
  if (n > 0 && (size_t)n < sizeof why) vsnprintf(why + n, sizeof why - (size_t)n, fmt, ap);
  mp *self = R->self;
  st_release(R);
  mp_set_user(self, INIT_MARK_STOPPED);
  mp_abort(self, 1, why);
}

static int vraise(st_rank *R, const st_comm *c, int cls, const char *fn, const char *fmt, va_list ap) {
  if (!c) c = &R->world;
  return vapply(R, c->eh, c->h, cls, fn, fmt, ap);
}

int err_raise_on(st_rank *R, MPI_Errhandler eh, int handle, int cls, const char *fn, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int rc = vapply(R, eh, handle, cls, fn, fmt, ap);
  va_end(ap);
  return rc;
}

int err_raise(st_rank *R, const st_comm *c, int cls, const char *fn, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int rc = vraise(R, c, cls, fn, fmt, ap);
  va_end(ap);
  return rc;
}

int err_comm_raise(MPI_Comm comm, int cls, const char *fn, const char *fmt, ...) {
  st_rank *R = st_need(fn);
  va_list ap;
  va_start(ap, fmt);
  int rc = vraise(R, st_comm_get(R, comm), cls, fn, fmt, ap);
  va_end(ap);
  return rc;
}

/* ==== checks ============================================================== */

const char *err_comm_words(MPI_Comm comm, char *buf) {
  if (comm == MPI_COMM_NULL) return "MPI_COMM_NULL";
  if (H_KIND(comm) != HK_COMM)
    snprintf(buf, 64, "handle 0x%x (not a communicator)", (unsigned)comm);
  else
    snprintf(buf, 64, "communicator handle 0x%x (freed, or not this rank's)", (unsigned)comm);
  return buf;
}

int err_check_comm(st_rank *R, MPI_Comm comm, const char *fn, st_comm **out) {
  st_comm *c = st_comm_get(R, comm);
  if (c && c->freed) c = NULL;   /* freed by the program, ending with its collectives */
  *out = c;
  if (c) return MPI_SUCCESS;
  char b[64];
  return err_raise(R, NULL, MPI_ERR_COMM, fn, "invalid communicator: %s", err_comm_words(comm, b));
}

int err_check_count(st_rank *R, const st_comm *c, const char *fn, int count) {
  if (count >= 0) return MPI_SUCCESS;
  return err_raise(R, c, MPI_ERR_COUNT, fn, "invalid count %d (must be >= 0)", count);
}

int err_check_type(st_rank *R, const st_comm *c, const char *fn, MPI_Datatype dt) {
  char why[128] = "";
  if (dtype_check(dt, why, sizeof why) == MPI_SUCCESS) return MPI_SUCCESS;
  return err_raise(R, c, MPI_ERR_TYPE, fn, "invalid datatype: %s", why);
}

int err_check_tag(st_rank *R, const st_comm *c, const char *fn, int tag, int any_ok) {
  if ((tag >= 0 && tag <= ST_TAG_UB) || (any_ok && tag == MPI_ANY_TAG)) return MPI_SUCCESS;
  return err_raise(R, c, MPI_ERR_TAG, fn, "invalid tag %d (tags are 0 .. MPI_TAG_UB = %d%s)", tag,
                   ST_TAG_UB, any_ok ? ", or MPI_ANY_TAG" : "");
}

int err_check_peer(st_rank *R, const st_comm *c, const char *fn, int r, int any_ok) {
  if ((r >= 0 && r < c->size) || r == MPI_PROC_NULL || (any_ok && r == MPI_ANY_SOURCE))
    return MPI_SUCCESS;
  char b[32];
  return err_raise(R, c, MPI_ERR_RANK, fn, "invalid rank %d (%s%s has %d rank%s)", r,
                   c->inter ? "the remote group of " : "", st_pair_name(c->pair, b), c->size,
                   c->size == 1 ? "" : "s");
}

int err_check_buf(st_rank *R, const st_comm *c, const char *fn, const void *buf, int count,
                  MPI_Datatype dt) {
  /* MPI_BOTTOM is NULL: a type of absolute addresses may go with it. */
  if (buf || dtype_bottom_ok(dt, count)) return MPI_SUCCESS;
  return err_raise(R, c, MPI_ERR_BUFFER, fn, "NULL buffer for %d element%s", count,
                   count == 1 ? "" : "s");
}

int err_comm_check_count(MPI_Comm comm, const char *fn, int count) {
  st_rank *R = st_need(fn);
  return err_check_count(R, st_comm_get(R, comm), fn, count);
}

int err_comm_check_buf(MPI_Comm comm, const char *fn, const void *buf, int count, MPI_Datatype dt) {
  st_rank *R = st_need(fn);
  return err_check_buf(R, st_comm_get(R, comm), fn, buf, count, dt);
}

int err_comm_check_rank(MPI_Comm comm, const char *fn, int r, int any_ok) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  return rc ? rc : err_check_peer(R, c, fn, r, any_ok);
}

int err_comm_check_root(MPI_Comm comm, const char *fn, int root) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (root >= 0 && root < c->size) return MPI_SUCCESS;
  char b[32];
  return err_raise(R, c, MPI_ERR_ROOT, fn, "invalid root %d (%s has %d rank%s)", root,
                   st_pair_name(c->pair, b), c->size, c->size == 1 ? "" : "s");
}

/* ==== classes and strings ================================================= */

static const char *const class_text[MPI_ERR_LASTCODE + 1] = {
  [MPI_SUCCESS] = "MPI_SUCCESS: no error",
  [MPI_ERR_BUFFER] = "MPI_ERR_BUFFER: invalid buffer pointer, or no room in the attached buffer",
  [MPI_ERR_COUNT] = "MPI_ERR_COUNT: invalid count argument",
  [MPI_ERR_TYPE] = "MPI_ERR_TYPE: invalid datatype",
  [MPI_ERR_TAG] = "MPI_ERR_TAG: invalid tag",
  [MPI_ERR_COMM] = "MPI_ERR_COMM: invalid communicator",
  [MPI_ERR_RANK] = "MPI_ERR_RANK: invalid rank",
  [MPI_ERR_REQUEST] = "MPI_ERR_REQUEST: invalid request",
  [MPI_ERR_ROOT] = "MPI_ERR_ROOT: invalid root",
  [MPI_ERR_GROUP] = "MPI_ERR_GROUP: invalid group",
  [MPI_ERR_OP] = "MPI_ERR_OP: invalid reduce operation",
  [MPI_ERR_TOPOLOGY] = "MPI_ERR_TOPOLOGY: invalid communicator topology",
  [MPI_ERR_DIMS] = "MPI_ERR_DIMS: invalid topology dimension argument",
  [MPI_ERR_ARG] = "MPI_ERR_ARG: invalid argument of some other kind",
  [MPI_ERR_UNKNOWN] = "MPI_ERR_UNKNOWN: unknown error",
  [MPI_ERR_TRUNCATE] = "MPI_ERR_TRUNCATE: message truncated",
  [MPI_ERR_OTHER] = "MPI_ERR_OTHER: known error not in this list",
  [MPI_ERR_INTERN] = "MPI_ERR_INTERN: internal error",
  [MPI_ERR_IN_STATUS] = "MPI_ERR_IN_STATUS: error code is in status",
  [MPI_ERR_PENDING] = "MPI_ERR_PENDING: pending request",
  [MPI_ERR_KEYVAL] = "MPI_ERR_KEYVAL: invalid keyval",
  [MPI_ERR_NO_MEM] = "MPI_ERR_NO_MEM: out of memory",
  [MPI_ERR_BASE] = "MPI_ERR_BASE: invalid base address",
  [MPI_ERR_INFO_KEY] = "MPI_ERR_INFO_KEY: info key too long",
  [MPI_ERR_INFO_VALUE] = "MPI_ERR_INFO_VALUE: info value too long",
  [MPI_ERR_INFO_NOKEY] = "MPI_ERR_INFO_NOKEY: no such info key",
  [MPI_ERR_SPAWN] = "MPI_ERR_SPAWN: error in spawning processes",
  [MPI_ERR_PORT] = "MPI_ERR_PORT: invalid port name",
  [MPI_ERR_SERVICE] = "MPI_ERR_SERVICE: invalid service name",
  [MPI_ERR_NAME] = "MPI_ERR_NAME: invalid service name in lookup",
  [MPI_ERR_WIN] = "MPI_ERR_WIN: invalid window",
  [MPI_ERR_SIZE] = "MPI_ERR_SIZE: invalid size argument",
  [MPI_ERR_DISP] = "MPI_ERR_DISP: invalid displacement argument",
  [MPI_ERR_INFO] = "MPI_ERR_INFO: invalid info argument",
  [MPI_ERR_LOCKTYPE] = "MPI_ERR_LOCKTYPE: invalid locktype argument",
  [MPI_ERR_ASSERT] = "MPI_ERR_ASSERT: invalid assert argument",
  [MPI_ERR_RMA_CONFLICT] = "MPI_ERR_RMA_CONFLICT: conflicting accesses to a window",
  [MPI_ERR_RMA_SYNC] = "MPI_ERR_RMA_SYNC: wrong synchronization of RMA calls",
  [MPI_ERR_RMA_RANGE] = "MPI_ERR_RMA_RANGE: target memory is not part of the window",
  [MPI_ERR_RMA_ATTACH] = "MPI_ERR_RMA_ATTACH: memory cannot be attached",
  [MPI_ERR_RMA_SHARED] = "MPI_ERR_RMA_SHARED: memory cannot be shared",
  [MPI_ERR_RMA_FLAVOR] = "MPI_ERR_RMA_FLAVOR: wrong window flavor",
  [MPI_ERR_FILE] = "MPI_ERR_FILE: invalid file handle",
  [MPI_ERR_NOT_SAME] = "MPI_ERR_NOT_SAME: collective argument not identical on all processes",
  [MPI_ERR_AMODE] = "MPI_ERR_AMODE: invalid access mode",
  [MPI_ERR_UNSUPPORTED_DATAREP] = "MPI_ERR_UNSUPPORTED_DATAREP: unsupported data representation",
  [MPI_ERR_UNSUPPORTED_OPERATION] = "MPI_ERR_UNSUPPORTED_OPERATION: unsupported operation",
  [MPI_ERR_NO_SUCH_FILE] = "MPI_ERR_NO_SUCH_FILE: file does not exist",
  [MPI_ERR_FILE_EXISTS] = "MPI_ERR_FILE_EXISTS: file exists",
  [MPI_ERR_BAD_FILE] = "MPI_ERR_BAD_FILE: invalid file name",
  [MPI_ERR_ACCESS] = "MPI_ERR_ACCESS: permission denied",
  [MPI_ERR_NO_SPACE] = "MPI_ERR_NO_SPACE: not enough space",
  [MPI_ERR_QUOTA] = "MPI_ERR_QUOTA: quota exceeded",
  [MPI_ERR_READ_ONLY] = "MPI_ERR_READ_ONLY: read-only file or file system",
  [MPI_ERR_FILE_IN_USE] = "MPI_ERR_FILE_IN_USE: file operation could not be completed, the file is in use",
  [MPI_ERR_DUP_DATAREP] = "MPI_ERR_DUP_DATAREP: data representation already defined",
  [MPI_ERR_CONVERSION] = "MPI_ERR_CONVERSION: error in a user conversion function",
  [MPI_ERR_IO] = "MPI_ERR_IO: other I/O error",
  [MPI_T_ERR_MEMORY] = "MPI_T_ERR_MEMORY: out of memory",
  [MPI_T_ERR_NOT_INITIALIZED] = "MPI_T_ERR_NOT_INITIALIZED: interface not initialized",
  [MPI_T_ERR_CANNOT_INIT] = "MPI_T_ERR_CANNOT_INIT: interface not in the state to be initialized",
  [MPI_T_ERR_INVALID_INDEX] = "MPI_T_ERR_INVALID_INDEX: invalid index",
  [MPI_T_ERR_INVALID_ITEM] = "MPI_T_ERR_INVALID_ITEM: item index queried is out of range",
  [MPI_T_ERR_INVALID_HANDLE] = "MPI_T_ERR_INVALID_HANDLE: invalid handle",
  [MPI_T_ERR_OUT_OF_HANDLES] = "MPI_T_ERR_OUT_OF_HANDLES: no more handles available",
  [MPI_T_ERR_OUT_OF_SESSIONS] = "MPI_T_ERR_OUT_OF_SESSIONS: no more sessions available",
  [MPI_T_ERR_INVALID_SESSION] = "MPI_T_ERR_INVALID_SESSION: invalid session",
  [MPI_T_ERR_CVAR_SET_NOT_NOW] = "MPI_T_ERR_CVAR_SET_NOT_NOW: variable cannot be set at this moment",
  [MPI_T_ERR_CVAR_SET_NEVER] = "MPI_T_ERR_CVAR_SET_NEVER: variable cannot be set",
  [MPI_T_ERR_PVAR_NO_STARTSTOP] = "MPI_T_ERR_PVAR_NO_STARTSTOP: variable cannot be started or stopped",
  [MPI_T_ERR_PVAR_NO_WRITE] = "MPI_T_ERR_PVAR_NO_WRITE: variable cannot be written or reset",
  [MPI_T_ERR_PVAR_NO_ATOMIC] = "MPI_T_ERR_PVAR_NO_ATOMIC: variable cannot be read and written atomically",
  [MPI_T_ERR_INVALID_NAME] = "MPI_T_ERR_INVALID_NAME: name does not match",
  [MPI_T_ERR_INVALID] = "MPI_T_ERR_INVALID: invalid use of the interface",
  [MPI_ERR_LASTCODE] = "MPI_ERR_LASTCODE: last error code",
};

const char *err_class_text(int cls) { return class_text[cls]; }

/* Both are allowed before MPI_Init and after MPI_Finalize (the predefined
 * codes only, then). */
int PMPI_Error_class(int errorcode, int *errorclass) {
  static const char fn[] = "MPI_Error_class";
  st_rank *R = st_get();
  int cls = R ? errh_class(R, errorcode) : errorcode >= 0 && errorcode <= MPI_ERR_LASTCODE ? errorcode : -1;
  if (cls < 0 || !errorclass)
    return R ? err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid error code %d", errorcode) : MPI_ERR_ARG;
  *errorclass = cls;
  return MPI_SUCCESS;
}

int PMPI_Error_string(int errorcode, char *string, int *resultlen) {
  static const char fn[] = "MPI_Error_string";
  st_rank *R = st_get();
  int cls = R ? errh_class(R, errorcode) : errorcode >= 0 && errorcode <= MPI_ERR_LASTCODE ? errorcode : -1;
  if (cls < 0 || !string || !resultlen)
    return R ? err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid error code %d", errorcode) : MPI_ERR_ARG;
  const char *s = R ? errh_string(R, errorcode) : class_text[errorcode];
  size_t n = strlen(s);
  if (n > MPI_MAX_ERROR_STRING - 1) n = MPI_MAX_ERROR_STRING - 1;
  memcpy(string, s, n);
  string[n] = 0;
  *resultlen = (int)n;
  return MPI_SUCCESS;
}
