/* comm_attr.c -- the attribute calls of communicators and datatypes, the
 * keyvals of windows, the removed MPI-1 names (MPI_Keyval_create,
 * MPI_Attr_put, ...), and the predefined attributes of MPI 3.1 section
 * 8.1.2 (attr.h holds the keyvals and attributes). */
#include <stdio.h>
#include <string.h>

#include "mpi/attr.h"
#include "mpi/dtype.h"
#include "mpi/err.h"
#include "mpi/errh.h"

/* ==== keyvals ============================================================= */

static int keyval_create(const char *fn, int kind, attr_copy_fn *copy, attr_delete_fn *del, int *keyval,
                         void *extra_state) {
  st_rank *R = st_need(fn);
  if (!keyval) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL keyval argument");
  return attr_keyval_create(R, kind, copy, del, extra_state, keyval);
}

static int keyval_free(const char *fn, int kind, int *keyval) {
  st_rank *R = st_need(fn);
  if (!keyval) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL keyval argument");
  char why[128];
  int rc = attr_keyval_free(R, kind, keyval, why);
  return rc ? err_raise(R, NULL, rc, fn, "%s", why) : rc;
}

int PMPI_Comm_create_keyval(MPI_Comm_copy_attr_function *comm_copy_attr_fn,
                           MPI_Comm_delete_attr_function *comm_delete_attr_fn, int *comm_keyval, void *extra_state) {
  return keyval_create("MPI_Comm_create_keyval", ATTR_COMM, (attr_copy_fn *)comm_copy_attr_fn,
                       (attr_delete_fn *)comm_delete_attr_fn, comm_keyval, extra_state);
}

int PMPI_Keyval_create(MPI_Copy_function *copy_fn, MPI_Delete_function *delete_fn, int *keyval, void *extra_state) {
  return keyval_create("MPI_Keyval_create", ATTR_COMM, (attr_copy_fn *)copy_fn, (attr_delete_fn *)delete_fn, keyval,
                       extra_state);
}

int PMPI_Type_create_keyval(MPI_Type_copy_attr_function *type_copy_attr_fn,
                           MPI_Type_delete_attr_function *type_delete_attr_fn, int *type_keyval, void *extra_state) {
  return keyval_create("MPI_Type_create_keyval", ATTR_TYPE, (attr_copy_fn *)type_copy_attr_fn,
                       (attr_delete_fn *)type_delete_attr_fn, type_keyval, extra_state);
}

int PMPI_Win_create_keyval(MPI_Win_copy_attr_function *win_copy_attr_fn,
                          MPI_Win_delete_attr_function *win_delete_attr_fn, int *win_keyval, void *extra_state) {
  return keyval_create("MPI_Win_create_keyval", ATTR_WIN, (attr_copy_fn *)win_copy_attr_fn,
                       (attr_delete_fn *)win_delete_attr_fn, win_keyval, extra_state);
}

int PMPI_Comm_free_keyval(int *comm_keyval) { return keyval_free("MPI_Comm_free_keyval", ATTR_COMM, comm_keyval); }
int PMPI_Keyval_free(int *keyval) { return keyval_free("MPI_Keyval_free", ATTR_COMM, keyval); }
int PMPI_Type_free_keyval(int *type_keyval) { return keyval_free("MPI_Type_free_keyval", ATTR_TYPE, type_keyval); }
int PMPI_Win_free_keyval(int *win_keyval) { return keyval_free("MPI_Win_free_keyval", ATTR_WIN, win_keyval); }

/* ==== communicators ======================================================= */

/* The predefined attributes, the same on every communicator: the address
 * of the rank's int holding the value, or NULL if keyval is none of them. */
static int *predefined(st_rank *R, int keyval) {
  int *v = NULL;
  switch (keyval) {
  case MPI_TAG_UB: R->attr[0] = ST_TAG_UB; v = &R->attr[0]; break;
  case MPI_HOST: R->attr[1] = MPI_PROC_NULL; v = &R->attr[1]; break;
  case MPI_IO: R->attr[2] = MPI_ANY_SOURCE; v = &R->attr[2]; break;
  case MPI_WTIME_IS_GLOBAL: R->attr[3] = 1; v = &R->attr[3]; break;
  case MPI_UNIVERSE_SIZE: R->attr[4] = R->wsize; v = &R->attr[4]; break;
  case MPI_APPNUM: R->attr[5] = 0; v = &R->attr[5]; break;
  case MPI_LASTUSEDCODE: R->attr[6] = errh_lastused(R); v = &R->attr[6]; break;
  default: break;
  }
  return v;
}

static int comm_set(const char *fn, MPI_Comm comm, int keyval, void *value) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (predefined(R, keyval))
    return err_raise(R, c, MPI_ERR_KEYVAL, fn, "keyval %d is predefined and cannot be set", keyval);
  char why[128];
  rc = attr_set(R, ATTR_COMM, comm, keyval, value, why);
  return rc ? err_raise(R, c, rc, fn, "%s", why) : rc;
}

int PMPI_Comm_set_attr(MPI_Comm comm, int comm_keyval, void *attribute_val) {
  return comm_set("MPI_Comm_set_attr", comm, comm_keyval, attribute_val);
}

int PMPI_Attr_put(MPI_Comm comm, int keyval, void *attribute_val) {
  return comm_set("MPI_Attr_put", comm, keyval, attribute_val);
}

static int comm_get(const char *fn, MPI_Comm comm, int keyval, void *attribute_val, int *flag) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!attribute_val || !flag) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL argument");
  void *v = predefined(R, keyval);
  if (v) {
    *flag = 1;
  } else {
    char why[128];
    if ((rc = attr_get(R, ATTR_COMM, comm, keyval, &v, flag, why))) return err_raise(R, c, rc, fn, "%s", why);
  }
  if (*flag) memcpy(attribute_val, &v, sizeof v);
  return MPI_SUCCESS;
}

int PMPI_Comm_get_attr(MPI_Comm comm, int comm_keyval, void *attribute_val, int *flag) {
  return comm_get("MPI_Comm_get_attr", comm, comm_keyval, attribute_val, flag);
}

int PMPI_Attr_get(MPI_Comm comm, int keyval, void *attribute_val, int *flag) {
  return comm_get("MPI_Attr_get", comm, keyval, attribute_val, flag);
}

static int comm_delete(const char *fn, MPI_Comm comm, int keyval) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (predefined(R, keyval))
    return err_raise(R, c, MPI_ERR_KEYVAL, fn, "keyval %d is predefined and cannot be deleted", keyval);
  char why[128];
  rc = attr_delete(R, ATTR_COMM, comm, keyval, why);
  return rc ? err_raise(R, c, rc, fn, "%s", why) : rc;
}

int PMPI_Comm_delete_attr(MPI_Comm comm, int comm_keyval) {
  return comm_delete("MPI_Comm_delete_attr", comm, comm_keyval);
}

int PMPI_Attr_delete(MPI_Comm comm, int keyval) { return comm_delete("MPI_Attr_delete", comm, keyval); }

/* ==== datatypes =========================================================== */

/* Errors of a datatype's calls go to MPI_COMM_WORLD's handler. */
static int type_arg(st_rank *R, const char *fn, MPI_Datatype dt) {
  char why[96];
  if (dtype_valid(dt, why, sizeof why) == MPI_SUCCESS && dt != MPI_DATATYPE_NULL) return MPI_SUCCESS;
  return err_raise(R, NULL, MPI_ERR_TYPE, fn, "invalid datatype: %s", dt == MPI_DATATYPE_NULL ? "MPI_DATATYPE_NULL" : why);
}

int PMPI_Type_set_attr(MPI_Datatype datatype, int type_keyval, void *attribute_val) {
  static const char fn[] = "MPI_Type_set_attr";
  st_rank *R = st_need(fn);
  int rc = type_arg(R, fn, datatype);
  if (rc) return rc;
  char why[128];
  rc = attr_set(R, ATTR_TYPE, datatype, type_keyval, attribute_val, why);
  return rc ? err_raise(R, NULL, rc, fn, "%s", why) : rc;
}

int PMPI_Type_get_attr(MPI_Datatype datatype, int type_keyval, void *attribute_val, int *flag) {
  static const char fn[] = "MPI_Type_get_attr";
  st_rank *R = st_need(fn);
  int rc = type_arg(R, fn, datatype);
  if (rc) return rc;
  if (!attribute_val || !flag) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL argument");
  char why[128];
  void *v;
  if ((rc = attr_get(R, ATTR_TYPE, datatype, type_keyval, &v, flag, why))) return err_raise(R, NULL, rc, fn, "%s", why);
  if (*flag) memcpy(attribute_val, &v, sizeof v);
  return MPI_SUCCESS;
}

int PMPI_Type_delete_attr(MPI_Datatype datatype, int type_keyval) {
  static const char fn[] = "MPI_Type_delete_attr";
  st_rank *R = st_need(fn);
  int rc = type_arg(R, fn, datatype);
  if (rc) return rc;
  char why[128];
  rc = attr_delete(R, ATTR_TYPE, datatype, type_keyval, why);
  return rc ? err_raise(R, NULL, rc, fn, "%s", why) : rc;
}

int attr_type_copy(MPI_Datatype old, MPI_Datatype dup, const char *fn) {
  st_rank *R = st_need(fn);
  char why[128];
  int rc = attr_copy(R, ATTR_TYPE, old, dup, why);
  return rc ? err_raise(R, NULL, rc, fn, "%s", why) : rc;
}

int attr_type_delete(MPI_Datatype dt, const char *fn) {
  st_rank *R = st_need(fn);
  char why[128];
  int rc = attr_delete_all(R, ATTR_TYPE, dt, why);
  return rc ? err_raise(R, NULL, rc, fn, "%s", why) : rc;
}
