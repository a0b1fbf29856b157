/* attr_keyvals.c -- attributes and keyvals (MPI 3.1 section 6.7), checked by
 * themselves on any number of ranks: set, get, replace and delete on
 * communicators with the callbacks counted (each keyval's extra_state is a
 * counter of this rank's), copy on MPI_Comm_dup by MPI_COMM_DUP_FN, by
 * MPI_COMM_NULL_COPY_FN and by a callback of the program's (which may say
 * no), delete on MPI_Comm_free, a keyval freed while in use, callbacks that
 * fail (the call fails, the attribute stays, a failed copy leaves no
 * communicator), the removed MPI-1 names, datatypes' attributes (copied by
 * MPI_Type_dup, deleted by MPI_Type_free), windows' keyvals, the predefined
 * attributes, and MPI_Finalize deleting MPI_COMM_SELF's attributes first,
 * last set first (checked after it: main returns 1 if not). */
#include <mpi.h>
#include <stdint.h>
#include <string.h>

#include "mtest.h"

/* A keyval's counts, its extra_state. */
typedef struct {
  int copies, deletes;
  int fail_copy, fail_delete;   /* return MPI_ERR_OTHER */
  int last_comm_ok;             /* the callback's communicator was a valid one */
  int order[8], norder;         /* values deleted, in turn */
} counts;

static int copy_cb(MPI_Comm old, int keyval, void *extra, void *in, void *out, int *flag) {
  counts *c = extra;
  (void)old, (void)keyval;
  c->copies++;
  if (c->fail_copy) return MPI_ERR_OTHER;
  /* The copy's value is the original's plus 1000. */
  *(void **)out = (void *)((intptr_t)in + 1000);
  *flag = 1;
  return MPI_SUCCESS;
}

static int delete_cb(MPI_Comm comm, int keyval, void *value, void *extra) {
  counts *c = extra;
  int size = -1;
  (void)keyval;
  c->last_comm_ok = MPI_Comm_size(comm, &size) == MPI_SUCCESS && size > 0;
  c->deletes++;
  if (c->norder < 8) c->order[c->norder++] = (int)(intptr_t)value;
  return c->fail_delete ? MPI_ERR_OTHER : MPI_SUCCESS;
}

static int type_copy_cb(MPI_Datatype old, int keyval, void *extra, void *in, void *out, int *flag) {
  counts *c = extra;
  (void)old, (void)keyval;
  c->copies++;
  *(void **)out = in;
  *flag = 1;
  return MPI_SUCCESS;
}

static int type_delete_cb(MPI_Datatype dt, int keyval, void *value, void *extra) {
  counts *c = extra;
  (void)dt, (void)keyval, (void)value;
  c->deletes++;
  return MPI_SUCCESS;
}

/* The value of keyval on comm as an int, or -1 if none. */
static int value_of(MPI_Comm comm, int keyval) {
  void *v = NULL;
  int flag = 0;
  MPI_Comm_get_attr(comm, keyval, &v, &flag);
  return flag ? (int)(intptr_t)v : -1;
}

static void ak_basic(mtest *t) {
  counts c = {0};
  int k = MPI_KEYVAL_INVALID;
  MPI_Comm_create_keyval(copy_cb, delete_cb, &k, &c);
  MCHECK(t, k != MPI_KEYVAL_INVALID, "no keyval made");
  MPI_Comm comm;
  MPI_Comm_dup(MPI_COMM_WORLD, &comm);
  MCHECK(t, value_of(comm, k) == -1, "an attribute before one was set");
  MPI_Comm_set_attr(comm, k, (void *)(intptr_t)(7 + t->rank));
  MCHECK(t, value_of(comm, k) == 7 + t->rank && c.deletes == 0, "set: %d", value_of(comm, k));
  /* Replacing calls the delete callback on the old value. */
  MPI_Comm_set_attr(comm, k, (void *)(intptr_t)5);
  MCHECK(t, value_of(comm, k) == 5 && c.deletes == 1 && c.order[0] == 7 + t->rank, "replace: %d, %d deletes",
         value_of(comm, k), c.deletes);
  /* A duplicate gets the copy callback's value; MPI_Comm_free deletes it. */
  MPI_Comm d;
  MPI_Comm_dup(comm, &d);
  MCHECK(t, c.copies == 1 && value_of(d, k) == 1005 && value_of(comm, k) == 5, "dup: %d copies, %d", c.copies,
         value_of(d, k));
  MPI_Comm_free(&d);
  MCHECK(t, c.deletes == 2 && c.order[1] == 1005 && c.last_comm_ok, "free: %d deletes", c.deletes);
  /* Delete, then nothing there; deleting what is not there is no error. */
  MPI_Comm_delete_attr(comm, k);
  MCHECK(t, c.deletes == 3 && value_of(comm, k) == -1, "delete: %d deletes", c.deletes);
  /* A keyval freed while an attribute uses it: the attribute stays, and
   * its callbacks still run. */
  MPI_Comm_set_attr(comm, k, (void *)(intptr_t)9);
  int saved = k;
  MPI_Comm_free_keyval(&k);
  MCHECK(t, k == MPI_KEYVAL_INVALID, "freed keyval not MPI_KEYVAL_INVALID");
  MPI_Comm_dup(comm, &d);
  MCHECK(t, c.copies == 2 && value_of(d, saved) == 1009, "dup after the keyval's free: %d", value_of(d, saved));
  MPI_Comm_free(&d);
  MPI_Comm_free(&comm);
  MCHECK(t, c.deletes == 5, "the freed keyval's deletes: %d", c.deletes);
}

/* The predefined callbacks: MPI_COMM_DUP_FN copies the value, the null
 * copy does not, MPI_COMM_NULL_DELETE_FN does nothing. */
static void ak_predefined_callbacks(mtest *t) {
  int kd, kn;
  MPI_Comm_create_keyval(MPI_COMM_DUP_FN, MPI_COMM_NULL_DELETE_FN, &kd, NULL);
  MPI_Comm_create_keyval(MPI_COMM_NULL_COPY_FN, MPI_COMM_NULL_DELETE_FN, &kn, NULL);
  MPI_Comm_set_attr(MPI_COMM_WORLD, kd, (void *)(intptr_t)11);
  MPI_Comm_set_attr(MPI_COMM_WORLD, kn, (void *)(intptr_t)12);
  MPI_Comm d;
  MPI_Comm_dup(MPI_COMM_WORLD, &d);
  MCHECK(t, value_of(d, kd) == 11 && value_of(d, kn) == -1, "predefined copies: %d %d", value_of(d, kd),
         value_of(d, kn));
  MPI_Comm_free(&d);
  MPI_Comm_delete_attr(MPI_COMM_WORLD, kd);
  MPI_Comm_delete_attr(MPI_COMM_WORLD, kn);
  MPI_Comm_free_keyval(&kd);
  MPI_Comm_free_keyval(&kn);
}

/* Callbacks that fail, under MPI_ERRORS_RETURN. */
static void ak_failures(mtest *t) {
  counts c = {0};
  int k, rc;
  MPI_Comm comm, d = MPI_COMM_WORLD;
  MPI_Comm_dup(MPI_COMM_WORLD, &comm);
  MPI_Comm_set_errhandler(comm, MPI_ERRORS_RETURN);
  MPI_Comm_create_keyval(copy_cb, delete_cb, &k, &c);
  MPI_Comm_set_attr(comm, k, (void *)(intptr_t)3);
  c.fail_delete = 1;
  rc = MPI_Comm_set_attr(comm, k, (void *)(intptr_t)4);
  MCHECK(t, rc != MPI_SUCCESS && value_of(comm, k) == 3, "a failed delete in set: %d, value %d", rc, value_of(comm, k));
  rc = MPI_Comm_delete_attr(comm, k);
  MCHECK(t, rc != MPI_SUCCESS && value_of(comm, k) == 3, "a failed delete: %d, value %d", rc, value_of(comm, k));
  c.fail_delete = 0;
  c.fail_copy = 1;
  rc = MPI_Comm_dup(comm, &d);
  MCHECK(t, rc != MPI_SUCCESS && d == MPI_COMM_NULL, "a failed copy: %d", rc);
  c.fail_copy = 0;
  MPI_Comm_free(&comm);
  MPI_Comm_free_keyval(&k);
  MCHECK(t, c.deletes == 3, "deletes: %d", c.deletes);
}

/* MPI-1's names for the same. */
static void ak_mpi1(mtest *t) {
  counts c = {0};
  int k;
  MPI_Keyval_create(copy_cb, delete_cb, &k, &c);
  MPI_Attr_put(MPI_COMM_SELF, k, (void *)(intptr_t)21);
  void *v = NULL;
  int flag = 0;
  MPI_Attr_get(MPI_COMM_SELF, k, &v, &flag);
  MCHECK(t, flag && (intptr_t)v == 21, "MPI_Attr_get: %d %d", flag, (int)(intptr_t)v);
  MPI_Comm d;
  MPI_Comm_dup(MPI_COMM_SELF, &d);
  MPI_Attr_get(d, k, &v, &flag);
  MCHECK(t, flag && (intptr_t)v == 1021, "MPI-1 copy: %d %d", flag, (int)(intptr_t)v);
  MPI_Comm_free(&d);
  MPI_Attr_delete(MPI_COMM_SELF, k);
  MPI_Attr_get(MPI_COMM_SELF, k, &v, &flag);
  MCHECK(t, !flag && c.deletes == 2, "MPI_Attr_delete: %d, %d deletes", flag, c.deletes);
  MPI_Keyval_free(&k);
  MCHECK(t, k == MPI_KEYVAL_INVALID, "MPI_Keyval_free");
  /* MPI_NULL_COPY_FN and MPI_DUP_FN */
  int kn, kd;
  MPI_Keyval_create(MPI_NULL_COPY_FN, MPI_NULL_DELETE_FN, &kn, NULL);
  MPI_Keyval_create(MPI_DUP_FN, MPI_NULL_DELETE_FN, &kd, NULL);
  MPI_Attr_put(MPI_COMM_SELF, kn, (void *)(intptr_t)1);
  MPI_Attr_put(MPI_COMM_SELF, kd, (void *)(intptr_t)2);
  MPI_Comm_dup(MPI_COMM_SELF, &d);
  MCHECK(t, value_of(d, kn) == -1 && value_of(d, kd) == 2, "MPI-1 predefined copies: %d %d", value_of(d, kn),
         value_of(d, kd));
  MPI_Comm_free(&d);
  MPI_Attr_delete(MPI_COMM_SELF, kn);
  MPI_Attr_delete(MPI_COMM_SELF, kd);
  MPI_Keyval_free(&kn);
  MPI_Keyval_free(&kd);
}

/* Datatypes' attributes, and a window keyval (no window needed). */
static void ak_types(mtest *t) {
  counts c = {0};
  int k, flag = 0;
  MPI_Type_create_keyval(type_copy_cb, type_delete_cb, &k, &c);
  MPI_Datatype pair, dup;
  MPI_Type_contiguous(2, MPI_INT, &pair);
  MPI_Type_commit(&pair);
  MPI_Type_set_attr(pair, k, (void *)(intptr_t)31);
  MPI_Type_dup(pair, &dup);
  void *v = NULL;
  MPI_Type_get_attr(dup, k, &v, &flag);
  MCHECK(t, c.copies == 1 && flag && (intptr_t)v == 31, "MPI_Type_dup: %d copies, %d", c.copies, (int)(intptr_t)v);
  MPI_Type_delete_attr(dup, k);
  MPI_Type_get_attr(dup, k, &v, &flag);
  MCHECK(t, !flag && c.deletes == 1, "MPI_Type_delete_attr: %d, %d deletes", flag, c.deletes);
  /* MPI_Type_free deletes pair's (Open MPI waits until no type refers to
   * it: both are freed before the count). */
  MPI_Type_free(&pair);
  MPI_Type_free(&dup);
  MCHECK(t, c.deletes == 2, "MPI_Type_free: %d deletes", c.deletes);
  /* On a predefined type. */
  MPI_Type_set_attr(MPI_INT, k, (void *)(intptr_t)32);
  MPI_Type_get_attr(MPI_INT, k, &v, &flag);
  MCHECK(t, flag && (intptr_t)v == 32, "an attribute on MPI_INT: %d", (int)(intptr_t)v);
  MPI_Type_delete_attr(MPI_INT, k);
  MPI_Type_free_keyval(&k);
  MCHECK(t, k == MPI_KEYVAL_INVALID && c.deletes == 3, "MPI_Type_free_keyval: %d deletes", c.deletes);
  int wk = MPI_KEYVAL_INVALID;
  MPI_Win_create_keyval(MPI_WIN_NULL_COPY_FN, MPI_WIN_NULL_DELETE_FN, &wk, NULL);
  MCHECK(t, wk != MPI_KEYVAL_INVALID, "MPI_Win_create_keyval");
  MPI_Win_free_keyval(&wk);
  MCHECK(t, wk == MPI_KEYVAL_INVALID, "MPI_Win_free_keyval");
}

/* A keyval of one kind on another kind of object, and the predefined
 * keyvals, under MPI_ERRORS_RETURN: MPI_ERR_KEYVAL (as MPICH; Open MPI
 * says MPI_ERR_OTHER). */
static int keyval_error(int rc) {
  int cls = -1;
  MPI_Error_class(rc, &cls);
  return rc != MPI_SUCCESS && (cls == MPI_ERR_KEYVAL || cls == MPI_ERR_OTHER);
}

static void ak_errors(mtest *t) {
  int kt, rc;
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Type_create_keyval(MPI_TYPE_NULL_COPY_FN, MPI_TYPE_NULL_DELETE_FN, &kt, NULL);
  rc = MPI_Comm_set_attr(MPI_COMM_WORLD, kt, NULL);
  MCHECK(t, keyval_error(rc), "a type keyval on a communicator: %d", rc);
  MPI_Type_free_keyval(&kt);
  rc = MPI_Comm_set_attr(MPI_COMM_WORLD, MPI_TAG_UB, NULL);
  MCHECK(t, keyval_error(rc), "setting MPI_TAG_UB: %d", rc);
  int k = MPI_KEYVAL_INVALID;
  rc = MPI_Comm_free_keyval(&k);
  MCHECK(t, keyval_error(rc), "freeing MPI_KEYVAL_INVALID: %d", rc);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_ARE_FATAL);
}

/* MPI 3.1 section 8.1.2's attributes of MPI_COMM_WORLD. */
static void ak_environment(mtest *t) {
  int *v = NULL, flag = 0;
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_TAG_UB, &v, &flag);
  MCHECK(t, flag && *v >= 32767, "MPI_TAG_UB: %d", flag ? *v : -1);
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_HOST, &v, &flag);
  MCHECK(t, flag && (*v == MPI_PROC_NULL || (*v >= 0 && *v < t->size)), "MPI_HOST: %d", flag ? *v : -1);
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_IO, &v, &flag);
  MCHECK(t, flag && (*v == MPI_ANY_SOURCE || *v == MPI_PROC_NULL || (*v >= 0 && *v < t->size)), "MPI_IO: %d",
         flag ? *v : -1);
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_WTIME_IS_GLOBAL, &v, &flag);
  MCHECK(t, !flag || *v == 0 || *v == 1, "MPI_WTIME_IS_GLOBAL: %d", *v);
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_UNIVERSE_SIZE, &v, &flag);
  /* (MPICH's test asks for at least the world's size; Open MPI gives its
   * slots, fewer when oversubscribed.) */
  MCHECK(t, !flag || *v >= 1, "MPI_UNIVERSE_SIZE: %d", *v);
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_LASTUSEDCODE, &v, &flag);
  MCHECK(t, flag && *v >= MPI_ERR_LASTCODE, "MPI_LASTUSEDCODE: %d", flag ? *v : -1);
}

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  mtest t;
  mtest_init(&t, "attr_keyvals");
  ak_basic(&t);
  ak_predefined_callbacks(&t);
  ak_failures(&t);
  ak_mpi1(&t);
  ak_types(&t);
  ak_errors(&t);
  ak_environment(&t);
  /* Three attributes on MPI_COMM_SELF, for MPI_Finalize to delete last
   * set first (and before anything else: the callback sees a valid
   * MPI_COMM_SELF), and one on MPI_COMM_WORLD. */
  counts fin = {0};
  int k[3];
  for (int i = 0; i < 3; i++) MPI_Comm_create_keyval(MPI_COMM_NULL_COPY_FN, delete_cb, &k[i], &fin);
  MPI_Comm_set_attr(MPI_COMM_SELF, k[1], (void *)(intptr_t)1);
  MPI_Comm_set_attr(MPI_COMM_SELF, k[0], (void *)(intptr_t)2);
  MPI_Comm_set_attr(MPI_COMM_SELF, k[2], (void *)(intptr_t)3);
  for (int i = 0; i < 3; i++) MPI_Comm_free_keyval(&k[i]);
  int rc = mtest_done(&t);
  MPI_Finalize();
  if (fin.deletes != 3 || fin.order[0] != 3 || fin.order[1] != 2 || fin.order[2] != 1 || !fin.last_comm_ok) {
    printf("attr_keyvals: rank %d: MPI_Finalize deleted %d attributes of MPI_COMM_SELF (%d %d %d; 3 2 1 due)\n",
           t.rank, fin.deletes, fin.order[0], fin.order[1], fin.order[2]);
    rc = 1;
  }
  return rc;
}
