/* errh.c -- error handlers (create, set, get, free, call; the removed
 * MPI-1 names), and the error classes, codes and strings a program adds
 * (errh.h). */
#include "mpi/errh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/err.h"
#include "util/xmem.h"

typedef struct {
  int kind;          /* ERRH_*; 0: a free slot */
  int refs;          /* the program's handles and the objects that use it */
  errh_fn *fn;
} handler;

typedef struct {
  int cls;           /* its class (itself for a class) */
  char *str;         /* MPI_Add_error_string's, or NULL */
} code;

struct errh_table {
  handler *h;
  int nh;
  code *c;
  int nc;
};

static struct errh_table *errs_of(st_rank *R) {
  if (!R->errs) R->errs = xcalloc(1, sizeof *R->errs);
  return R->errs;
}

void errh_release_all(st_rank *R) {
  struct errh_table *E = R->errs;
  if (!E) return;
  for (int i = 0; i < E->nc; i++) free(E->c[i].str);
  free(E->c);
  free(E->h);
  free(E);
  R->errs = NULL;
}

/* ==== handlers ============================================================ */

static const char *const kind_name[] = {"", "communicators", "windows", "files"};

/* The created handler eh names, or NULL. */
static handler *created(st_rank *R, MPI_Errhandler eh) {
  unsigned slot = (unsigned)eh - (unsigned)(HK_ERRH << H_KIND_SHIFT | H_CREATED);
  struct errh_table *E = R->errs;
  if (!E || slot >= (unsigned)E->nh || !E->h[slot].kind) return NULL;
  return &E->h[slot];
}

static int predefined(MPI_Errhandler eh) { return eh == MPI_ERRORS_ARE_FATAL || eh == MPI_ERRORS_RETURN; }

int errh_check(st_rank *R, MPI_Errhandler eh, int kind, char *why) {
  if (predefined(eh)) return 0;
  handler *h = created(R, eh);
  if (h && h->kind == kind) return 0;
  if (h)
    snprintf(why, 96, "error handler 0x%x was made for %s, not %s", (unsigned)eh, kind_name[h->kind],
             kind_name[kind]);
  else if (eh == MPI_ERRHANDLER_NULL)
    snprintf(why, 96, "MPI_ERRHANDLER_NULL");
  else
    snprintf(why, 96, "invalid error handler 0x%x (freed, or not an error handler)", (unsigned)eh);
  return -1;
}

void errh_hold(st_rank *R, MPI_Errhandler eh) {
  handler *h = created(R, eh);
  if (h) h->refs++;
}

void errh_drop(st_rank *R, MPI_Errhandler eh) {
  handler *h = created(R, eh);
  if (h && --h->refs == 0) h->kind = 0;
}

void errh_set(st_rank *R, MPI_Errhandler *slot, MPI_Errhandler eh) {
  errh_hold(R, eh);
  errh_drop(R, *slot);
  *slot = eh;
}

errh_fn *errh_function(st_rank *R, MPI_Errhandler eh) {
  handler *h = created(R, eh);
  return h ? h->fn : NULL;
}

static int create(const char *fn, int kind, errh_fn *f, MPI_Errhandler *errhandler) {
  st_rank *R = st_need(fn);
  if (!f || !errhandler) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL %s argument", f ? "errhandler" : "function");
  struct errh_table *E = errs_of(R);
  int slot = 0;
  while (slot < E->nh && E->h[slot].kind) slot++;
  if (slot == E->nh) E->h = xreallocarray(E->h, (size_t)++E->nh, sizeof *E->h);
  E->h[slot] = (handler){kind, 1, f};
  *errhandler = (MPI_Errhandler)(HK_ERRH << H_KIND_SHIFT | H_CREATED | slot);
  return MPI_SUCCESS;
}

int PMPI_Comm_create_errhandler(MPI_Comm_errhandler_function *comm_errhandler_fn, MPI_Errhandler *errhandler) {
  return create("MPI_Comm_create_errhandler", ERRH_COMM, (errh_fn *)comm_errhandler_fn, errhandler);
}

int PMPI_Errhandler_create(MPI_Handler_function *function, MPI_Errhandler *errhandler) {
  return create("MPI_Errhandler_create", ERRH_COMM, (errh_fn *)function, errhandler);
}

int PMPI_Win_create_errhandler(MPI_Win_errhandler_function *win_errhandler_fn, MPI_Errhandler *errhandler) {
  return create("MPI_Win_create_errhandler", ERRH_WIN, (errh_fn *)win_errhandler_fn, errhandler);
}

int PMPI_File_create_errhandler(MPI_File_errhandler_function *file_errhandler_fn, MPI_Errhandler *errhandler) {
  return create("MPI_File_create_errhandler", ERRH_FILE, (errh_fn *)file_errhandler_fn, errhandler);
}

static int set(const char *fn, MPI_Comm comm, MPI_Errhandler errhandler) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  char why[96];
  if (errh_check(R, errhandler, ERRH_COMM, why)) return err_raise(R, c, MPI_ERR_ARG, fn, "%s", why);
  errh_set(R, &c->eh, errhandler);
  return MPI_SUCCESS;
}

int PMPI_Comm_set_errhandler(MPI_Comm comm, MPI_Errhandler errhandler) {
  return set("MPI_Comm_set_errhandler", comm, errhandler);
}

int PMPI_Errhandler_set(MPI_Comm comm, MPI_Errhandler errhandler) {
  return set("MPI_Errhandler_set", comm, errhandler);
}

/* The handler is the program's to free (MPI 3.1 section 8.3.1). */
static int get(const char *fn, MPI_Comm comm, MPI_Errhandler *errhandler) {
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!errhandler) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL errhandler argument");
  errh_hold(R, c->eh);
  *errhandler = c->eh;
  return MPI_SUCCESS;
}

int PMPI_Comm_get_errhandler(MPI_Comm comm, MPI_Errhandler *errhandler) {
  return get("MPI_Comm_get_errhandler", comm, errhandler);
}

int PMPI_Errhandler_get(MPI_Comm comm, MPI_Errhandler *errhandler) {
  return get("MPI_Errhandler_get", comm, errhandler);
}

int PMPI_Errhandler_free(MPI_Errhandler *errhandler) {
  static const char fn[] = "MPI_Errhandler_free";
  st_rank *R = st_need(fn);
  if (!errhandler) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL errhandler argument");
  if (!predefined(*errhandler)) {
    if (!created(R, *errhandler))
      return err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid error handler 0x%x (freed, or not an error handler)",
                       (unsigned)*errhandler);
    errh_drop(R, *errhandler);
  }
  *errhandler = MPI_ERRHANDLER_NULL;   /* the predefined ones stay */
  return MPI_SUCCESS;
}

int PMPI_Comm_call_errhandler(MPI_Comm comm, int errorcode) {
  static const char fn[] = "MPI_Comm_call_errhandler";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  int cls = errh_class(R, errorcode);
  const char *s = cls < 0 ? "" : errh_string(R, errorcode);
  err_raise(R, c, errorcode, fn, "error code %d%s%s", errorcode, *s ? ": " : "", s);
  /* MPI 3.1 section 8.3.1: MPI_SUCCESS once the handler has returned. */
  return MPI_SUCCESS;
}

/* ==== classes, codes, strings ============================================= */

int errh_lastused(st_rank *R) { return MPI_ERR_LASTCODE + (R->errs ? R->errs->nc : 0); }

int errh_class(st_rank *R, int c) {
  if (c >= 0 && c <= MPI_ERR_LASTCODE) return c;
  if (c > MPI_ERR_LASTCODE && c <= errh_lastused(R)) return R->errs->c[c - MPI_ERR_LASTCODE - 1].cls;
  return -1;
}

/* The added code c's entry (c > MPI_ERR_LASTCODE, in use). */
static code *added(st_rank *R, int c) { return &R->errs->c[c - MPI_ERR_LASTCODE - 1]; }

const char *errh_string(st_rank *R, int c) {
  if (c <= MPI_ERR_LASTCODE) return err_class_text(c);
  const char *s = added(R, c)->str;
  return s ? s : "";
}

static int add_code(st_rank *R, int cls) {
  struct errh_table *E = errs_of(R);
  E->c = xreallocarray(E->c, (size_t)E->nc + 1, sizeof *E->c);
  int c = MPI_ERR_LASTCODE + 1 + E->nc;
  E->c[E->nc++] = (code){cls < 0 ? c : cls, NULL};
  return c;
}

int PMPI_Add_error_class(int *errorclass) {
  static const char fn[] = "MPI_Add_error_class";
  st_rank *R = st_need(fn);
  if (!errorclass) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL errorclass argument");
  *errorclass = add_code(R, -1);
  return MPI_SUCCESS;
}

int PMPI_Add_error_code(int errorclass, int *errorcode) {
  static const char fn[] = "MPI_Add_error_code";
  st_rank *R = st_need(fn);
  if (!errorcode) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL errorcode argument");
  if (errh_class(R, errorclass) != errorclass)
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "%d is not an error class", errorclass);
  *errorcode = add_code(R, errorclass);
  return MPI_SUCCESS;
}

int PMPI_Add_error_string(int errorcode, const char *string) {
  static const char fn[] = "MPI_Add_error_string";
  st_rank *R = st_need(fn);
  if (!string) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL string argument");
  if (errorcode <= MPI_ERR_LASTCODE || errh_class(R, errorcode) < 0)
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "%d is not an error code or class the program added", errorcode);
  size_t n = strlen(string);
  if (n > MPI_MAX_ERROR_STRING - 1)
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "a string of %zu characters (at most MPI_MAX_ERROR_STRING - 1 = %d)",
                     n, MPI_MAX_ERROR_STRING - 1);
  code *e = added(R, errorcode);
  free(e->str);
  e->str = xmalloc(n + 1);
  memcpy(e->str, string, n + 1);
  return MPI_SUCCESS;
}
