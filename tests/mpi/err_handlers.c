/* err_handlers.c -- error handlers and error codes (MPI 3.1 sections 8.3 to
 * 8.5), checked by themselves on any number of ranks: a handler of the
 * program's called with the communicator and the code by a failing call
 * (which then returns the code) and by MPI_Comm_call_errhandler, kept by
 * the communicator after MPI_Errhandler_free, inherited by MPI_Comm_dup,
 * given back by MPI_Comm_get_errhandler; the removed MPI-1 names;
 * MPI_ERRORS_RETURN; classes, codes and strings the program adds
 * (MPI_Add_error_class, _code, _string, MPI_Error_class, MPI_Error_string,
 * MPI_LASTUSEDCODE); handlers made for windows and files.
 *
 * The handler finds this rank's record through the communicator's name
 * (the record's address, set by the program), there being no globals. */
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "mtest.h"

/* Open MPI 4 without its MPI-1 compatibility has no MPI_Errhandler_create,
 * _set and _get (MPI 3.0 removed them): there the same checks run through
 * the calls MPI-2 renamed them to, which MPI defines them to be. */
#if defined(OPEN_MPI) && !OMPI_ENABLE_MPI1_COMPAT
#undef MPI_Errhandler_create
#undef MPI_Errhandler_set
#undef MPI_Errhandler_get
#define MPI_Errhandler_create MPI_Comm_create_errhandler
#define MPI_Errhandler_set MPI_Comm_set_errhandler
#define MPI_Errhandler_get MPI_Comm_get_errhandler
#endif

typedef struct {
  int calls;
  MPI_Comm comm;   /* the last call's */
  int code;
} record;

/* Name comm after r. */
static void point(MPI_Comm comm, record *r) {
  char name[MPI_MAX_OBJECT_NAME];
  snprintf(name, sizeof name, "%p", (void *)r);
  MPI_Comm_set_name(comm, name);
}

static void handler(MPI_Comm *comm, int *code, ...) {
  char name[MPI_MAX_OBJECT_NAME];
  int len;
  void *p = NULL;
  MPI_Comm_get_name(*comm, name, &len);
  if (sscanf(name, "%p", &p) != 1 || !p) return;
  record *r = p;
  r->calls++;
  r->comm = *comm;
  r->code = *code;
}

static int cls_of(int code) {
  int cls = -1;
  MPI_Error_class(code, &cls);
  return cls;
}

static void eh_user(mtest *t) {
  record r = {0, MPI_COMM_NULL, 0};
  MPI_Errhandler eh = MPI_ERRHANDLER_NULL, got = MPI_ERRHANDLER_NULL;
  MPI_Comm c, d;
  MPI_Comm_create_errhandler(handler, &eh);
  MPI_Comm_dup(MPI_COMM_WORLD, &c);
  point(c, &r);
  MPI_Comm_set_errhandler(c, eh);
  /* A failing call: the handler, then the code returned. */
  int v = 0, rc = MPI_Send(&v, 1, MPI_INT, t->size + 1, 0, c);
  MCHECK(t, rc != MPI_SUCCESS && cls_of(rc) == MPI_ERR_RANK, "a bad rank gave %d", rc);
  MCHECK(t, r.calls == 1 && r.comm == c && cls_of(r.code) == MPI_ERR_RANK, "the handler: %d calls, code %d", r.calls,
         r.code);
  MPI_Comm_get_errhandler(c, &got);
  MCHECK(t, got == eh, "MPI_Comm_get_errhandler gave another handler");
  MPI_Errhandler_free(&got);
  /* Freed by the program, kept by the communicator. */
  MPI_Errhandler_free(&eh);
  MCHECK(t, eh == MPI_ERRHANDLER_NULL, "MPI_Errhandler_free did not null the handle");
  rc = MPI_Comm_call_errhandler(c, MPI_ERR_OTHER);
  MCHECK(t, rc == MPI_SUCCESS && r.calls == 2 && r.comm == c && r.code == MPI_ERR_OTHER,
         "MPI_Comm_call_errhandler: %d, %d calls, code %d", rc, r.calls, r.code);
  /* A duplicate has it too. */
  MPI_Comm_dup(c, &d);
  point(d, &r);
  MPI_Comm_call_errhandler(d, MPI_ERR_ARG);
  MCHECK(t, r.calls == 3 && r.comm == d && r.code == MPI_ERR_ARG, "inherited: %d calls", r.calls);
  MPI_Comm_free(&d);
  /* MPI_ERRORS_RETURN: the code only. */
  MPI_Comm_set_errhandler(c, MPI_ERRORS_RETURN);
  rc = MPI_Send(&v, -1, MPI_INT, 0, 0, c);
  MCHECK(t, cls_of(rc) == MPI_ERR_COUNT && r.calls == 3, "MPI_ERRORS_RETURN: %d, %d calls", rc, r.calls);
  MPI_Comm_get_errhandler(c, &got);
  MCHECK(t, got == MPI_ERRORS_RETURN, "MPI_Comm_get_errhandler after a set");
  MPI_Errhandler_free(&got);
  MPI_Comm_free(&c);
}

/* MPI-1's MPI_Errhandler_create, _set and _get. */
static void eh_mpi1(mtest *t) {
  record r = {0, MPI_COMM_NULL, 0};
  MPI_Errhandler eh, got;
  MPI_Comm c;
  MPI_Comm_dup(MPI_COMM_WORLD, &c);
  point(c, &r);
  MPI_Errhandler_create(handler, &eh);
  MPI_Errhandler_set(c, eh);
  MPI_Errhandler_get(c, &got);
  MCHECK(t, got == eh, "MPI_Errhandler_get");
  MPI_Errhandler_free(&got);
  int v = 0, rc = MPI_Send(&v, 1, MPI_INT, 0, -3, c);
  MCHECK(t, cls_of(rc) == MPI_ERR_TAG && r.calls == 1 && r.comm == c, "an MPI-1 handler: %d, %d calls", rc, r.calls);
  MPI_Errhandler_free(&eh);
  MPI_Comm_free(&c);
}

/* Handlers on the predefined communicators, put back before the end. */
static void eh_predefined(mtest *t) {
  record r = {0, MPI_COMM_NULL, 0};
  MPI_Errhandler eh;
  MPI_Comm_create_errhandler(handler, &eh);
  MPI_Comm_set_errhandler(MPI_COMM_SELF, eh);
  MPI_Errhandler_free(&eh);
  point(MPI_COMM_SELF, &r);
  MPI_Comm_call_errhandler(MPI_COMM_SELF, MPI_ERR_UNKNOWN);
  MCHECK(t, r.calls == 1 && r.comm == MPI_COMM_SELF && r.code == MPI_ERR_UNKNOWN, "on MPI_COMM_SELF: %d calls",
         r.calls);
  MPI_Comm_set_errhandler(MPI_COMM_SELF, MPI_ERRORS_ARE_FATAL);
  MPI_Comm_set_name(MPI_COMM_SELF, "MPI_COMM_SELF");
}

/* Classes, codes and strings of the program's. */
static void eh_codes(mtest *t) {
  record r = {0, MPI_COMM_NULL, 0};
  int c1 = -1, c2 = -1, e1 = -1, e2 = -1, e3 = -1, *last = NULL, flag = 0, len = -1;
  char s[MPI_MAX_ERROR_STRING];
  MPI_Add_error_class(&c1);
  MPI_Add_error_class(&c2);
  MPI_Add_error_code(c1, &e1);
  MPI_Add_error_code(c2, &e2);
  MPI_Add_error_code(MPI_ERR_ARG, &e3);
  MCHECK(t, c1 > MPI_ERR_LASTCODE && c2 > MPI_ERR_LASTCODE && c1 != c2 && e1 != e2 && e1 != c1 && e3 != MPI_ERR_ARG,
         "new classes %d %d, codes %d %d %d", c1, c2, e1, e2, e3);
  /* (A class is a code of itself too, MPI_Error_class(c1) == c1, which
   * MPICH's errhan/adderr checks on tilesim: Open MPI 4.1 says
   * MPI_ERR_UNKNOWN.) */
  MCHECK(t, cls_of(e1) == c1 && cls_of(e2) == c2 && cls_of(e3) == MPI_ERR_ARG, "their classes: %d %d %d",
         cls_of(e1), cls_of(e2), cls_of(e3));
  MPI_Add_error_string(e1, "the first code of mine");
  MPI_Add_error_string(c2, "my second class");
  MPI_Error_string(e1, s, &len);
  MCHECK(t, strcmp(s, "the first code of mine") == 0 && len == 22, "a code's string: \"%s\" (%d)", s, len);
  MPI_Error_string(c2, s, &len);
  MCHECK(t, strcmp(s, "my second class") == 0, "a class's string: \"%s\"", s);
  MPI_Add_error_string(e1, "changed");
  MPI_Error_string(e1, s, &len);
  MCHECK(t, strcmp(s, "changed") == 0, "a string changed: \"%s\"", s);
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_LASTUSEDCODE, &last, &flag);
  MCHECK(t, flag && *last >= c1 && *last >= c2 && *last >= e1 && *last >= e2 && *last >= e3, "MPI_LASTUSEDCODE %d",
         flag ? *last : -1);
  MPI_Error_string(MPI_ERR_TRUNCATE, s, &len);
  MCHECK(t, len > 0 && (int)strlen(s) == len, "a predefined class's string: %d", len);
  /* A handler gets the program's code. */
  MPI_Errhandler eh;
  MPI_Comm c;
  MPI_Comm_dup(MPI_COMM_WORLD, &c);
  point(c, &r);
  MPI_Comm_create_errhandler(handler, &eh);
  MPI_Comm_set_errhandler(c, eh);
  MPI_Comm_call_errhandler(c, e2);
  MCHECK(t, r.calls == 1 && r.code == e2, "the handler got code %d (%d due)", r.code, e2);
  MPI_Errhandler_free(&eh);
  MPI_Comm_free(&c);
}

static void win_handler(MPI_Win *win, int *code, ...) { (void)win, (void)code; }
static void file_handler(MPI_File *file, int *code, ...) { (void)file, (void)code; }

/* Handlers for windows and files: made, refused by communicators, freed. */
static void eh_other_kinds(mtest *t) {
  MPI_Errhandler w = MPI_ERRHANDLER_NULL, f = MPI_ERRHANDLER_NULL;
  MPI_Win_create_errhandler(win_handler, &w);
  MPI_File_create_errhandler(file_handler, &f);
  MCHECK(t, w != MPI_ERRHANDLER_NULL && f != MPI_ERRHANDLER_NULL, "window and file handlers");
  MPI_Errhandler_free(&w);
  MPI_Errhandler_free(&f);
  MCHECK(t, w == MPI_ERRHANDLER_NULL && f == MPI_ERRHANDLER_NULL, "window and file handlers freed");
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {eh_user, eh_mpi1, eh_predefined, eh_codes, eh_other_kinds, NULL};
  return mtest_main(&argc, &argv, "err_handlers", 1, 0, checks);
}
