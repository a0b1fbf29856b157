/* info_objects.c -- info objects (MPI 3.1 chapter 9), checked by themselves
 * on any number of ranks: set, get (a value longer than the room asked
 * for comes back cut), the value's length, the keys in the order first
 * set (a value replaced keeps its place), delete, dup (a copy apart), free;
 * the errors under MPI_ERRORS_RETURN (a key or value longer than
 * MPI_MAX_INFO_KEY or MPI_MAX_INFO_VAL, a key not there, n out of range);
 * MPI_INFO_ENV; many objects at once; a communicator's info
 * (MPI_Comm_set_info, MPI_Comm_get_info, MPI_Comm_dup_with_info). */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

static int cls_of(int code) {
  int cls = -1;
  MPI_Error_class(code, &cls);
  return cls;
}

static void io_basic(mtest *t) {
  MPI_Info info, dup;
  char v[MPI_MAX_INFO_VAL + 1], k[MPI_MAX_INFO_KEY + 1];
  int flag = 0, n = -1, len = -1;
  MPI_Info_create(&info);
  MPI_Info_get_nkeys(info, &n);
  MCHECK(t, n == 0, "a new info has %d keys", n);
  MPI_Info_set(info, "file", "runfile.txt");
  MPI_Info_set(info, "soft", "2:1000:4,3:1000:7");
  MPI_Info_set(info, "host", "myhost.myorg.org");
  MPI_Info_get(info, "soft", MPI_MAX_INFO_VAL, v, &flag);
  MCHECK(t, flag && strcmp(v, "2:1000:4,3:1000:7") == 0, "get: %d \"%s\"", flag, v);
  MPI_Info_get_valuelen(info, "host", &len, &flag);
  MCHECK(t, flag && len == 16, "valuelen: %d %d", flag, len);
  MPI_Info_get(info, "nothere", MPI_MAX_INFO_VAL, v, &flag);
  MCHECK(t, !flag, "a key not set was found");
  MPI_Info_get_valuelen(info, "nothere", &len, &flag);
  MCHECK(t, !flag, "valuelen of a key not set");
  /* Room for 4 characters: the first 4 and a NUL. */
  memset(v, 'x', sizeof v);
  MPI_Info_get(info, "file", 4, v, &flag);
  MCHECK(t, flag && strcmp(v, "runf") == 0, "a value cut to 4: \"%s\"", v);
  /* Replaced in place; the keys in order. */
  MPI_Info_set(info, "file", "other.txt");
  MPI_Info_get_nkeys(info, &n);
  MCHECK(t, n == 3, "after a replace: %d keys", n);
  const char *order[3] = {"file", "soft", "host"};
  int bad = 0;
  for (int i = 0; i < n && i < 3; i++) {
    MPI_Info_get_nthkey(info, i, k);
    bad += strcmp(k, order[i]) != 0;
  }
  MCHECK(t, bad == 0, "the keys' order");
  /* A duplicate is a copy apart. */
  MPI_Info_dup(info, &dup);
  MPI_Info_delete(info, "soft");
  MPI_Info_get_nkeys(info, &n);
  MPI_Info_get(dup, "soft", MPI_MAX_INFO_VAL, v, &flag);
  MCHECK(t, n == 2 && flag, "dup apart: %d keys, dup's soft %d", n, flag);
  MPI_Info_get(dup, "file", MPI_MAX_INFO_VAL, v, &flag);
  MCHECK(t, flag && strcmp(v, "other.txt") == 0, "dup's file: \"%s\"", v);
  MPI_Info_get_nthkey(info, 1, k);
  MCHECK(t, strcmp(k, "host") == 0, "the keys after a delete: %s", k);
  MPI_Info_free(&info);
  MPI_Info_free(&dup);
  MCHECK(t, info == MPI_INFO_NULL && dup == MPI_INFO_NULL, "freed info not MPI_INFO_NULL");
}

static void io_errors(mtest *t) {
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_set_errhandler(MPI_COMM_SELF, MPI_ERRORS_RETURN);
  MPI_Info info;
  MPI_Info_create(&info);
  char *big = malloc(MPI_MAX_INFO_VAL + 2);
  memset(big, 'k', MPI_MAX_INFO_VAL + 1);
  big[MPI_MAX_INFO_KEY + 1] = 0;
  int rc = MPI_Info_set(info, big, "v");
  MCHECK(t, rc != MPI_SUCCESS && cls_of(rc) == MPI_ERR_INFO_KEY, "a key too long: class %d", cls_of(rc));
  big[MPI_MAX_INFO_KEY + 1] = 'k';
  big[MPI_MAX_INFO_VAL + 1] = 0;
  rc = MPI_Info_set(info, "key", big);
  MCHECK(t, rc != MPI_SUCCESS && cls_of(rc) == MPI_ERR_INFO_VALUE, "a value too long: class %d", cls_of(rc));
  rc = MPI_Info_delete(info, "nothere");
  MCHECK(t, rc != MPI_SUCCESS && cls_of(rc) == MPI_ERR_INFO_NOKEY, "deleting a key not there: class %d", cls_of(rc));
  MPI_Info_set(info, "a", "1");
  char k[MPI_MAX_INFO_KEY + 1];
  rc = MPI_Info_get_nthkey(info, 1, k);
  MCHECK(t, rc != MPI_SUCCESS && (cls_of(rc) == MPI_ERR_ARG || cls_of(rc) == MPI_ERR_INFO_KEY),
         "the key past the last: class %d (MPI_ERR_ARG as MPICH, or MPI_ERR_INFO_KEY as Open MPI)", cls_of(rc));
  /* A key of MPI_MAX_INFO_KEY - 1 characters and a value of
   * MPI_MAX_INFO_VAL - 1 fit (MPICH and tilesim take one more, Open MPI
   * not). */
  big[MPI_MAX_INFO_VAL - 1] = 0;
  MPI_Info_set(info, "long", big);
  big[MPI_MAX_INFO_KEY - 1] = 0;
  rc = MPI_Info_set(info, big, "fits");
  int len = -1, flag = 0;
  MPI_Info_get_valuelen(info, "long", &len, &flag);
  MCHECK(t, rc == MPI_SUCCESS && flag && len == MPI_MAX_INFO_VAL - 1, "long keys and values: %d %d", rc, len);
  free(big);
  MPI_Info_free(&info);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_ARE_FATAL);
  MPI_Comm_set_errhandler(MPI_COMM_SELF, MPI_ERRORS_ARE_FATAL);
}

/* MPI_INFO_ENV: readable and copied; maxprocs, if there, is the size. */
static void io_env(mtest *t) {
  char v[MPI_MAX_INFO_VAL + 1];
  int n = -1, flag = 0;
  MPI_Info_get_nkeys(MPI_INFO_ENV, &n);
  MPI_Info_get(MPI_INFO_ENV, "maxprocs", MPI_MAX_INFO_VAL, v, &flag);
  MCHECK(t, n >= 0 && (!flag || atoi(v) == t->size), "MPI_INFO_ENV: %d keys, maxprocs %s", n, flag ? v : "-");
  MPI_Info dup;
  int m = -1;
  MPI_Info_dup(MPI_INFO_ENV, &dup);
  MPI_Info_get_nkeys(dup, &m);
  MCHECK(t, m == n, "MPI_INFO_ENV's copy: %d keys of %d", m, n);
  MPI_Info_free(&dup);
}

/* Many at once, each its own keys. */
static void io_many(mtest *t) {
  enum { N = 50, KEYS = 12 };
  MPI_Info info[N];
  char k[64], v[64], got[64];
  int bad = 0;
  for (int i = 0; i < N; i++) {
    MPI_Info_create(&info[i]);
    for (int j = 0; j < KEYS; j++) {
      snprintf(k, sizeof k, "key%d-%d", i, j);
      snprintf(v, sizeof v, "value%d-%d", i, j);
      MPI_Info_set(info[i], k, v);
    }
  }
  for (int i = 0; i < N; i++) {
    int n = -1, flag = 0;
    MPI_Info_get_nkeys(info[i], &n);
    bad += n != KEYS;
    for (int j = 0; j < n; j++) {
      MPI_Info_get_nthkey(info[i], j, got);
      snprintf(k, sizeof k, "key%d-%d", i, j);
      snprintf(v, sizeof v, "value%d-%d", i, j);
      bad += strcmp(got, k) != 0;
      MPI_Info_get(info[i], k, sizeof got - 1, got, &flag);
      bad += !flag || strcmp(got, v) != 0;
    }
  }
  for (int i = 0; i < N; i++) MPI_Info_free(&info[i]);
  MCHECK(t, bad == 0, "%d wrong among %d info objects", bad, N);
}

/* A communicator's info: set, got back as a new object, given to a dup. */
static void io_comm(mtest *t) {
  MPI_Info in, out;
  MPI_Comm c, d;
  MPI_Info_create(&in);
  MPI_Info_set(in, "an_unknown_hint", "true");
  MPI_Comm_dup(MPI_COMM_WORLD, &c);
  MPI_Comm_set_info(c, in);
  int n = -1, rc = MPI_Comm_get_info(c, &out);
  MPI_Info_get_nkeys(out, &n);
  MCHECK(t, rc == MPI_SUCCESS && out != MPI_INFO_NULL && n >= 0, "MPI_Comm_get_info: %d, %d keys", rc, n);
  MPI_Info_free(&out);
  MPI_Comm_dup_with_info(c, in, &d);
  int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size, got = -1;
  MPI_Sendrecv(&t->rank, 1, MPI_INT, right, 0, &got, 1, MPI_INT, left, 0, d, MPI_STATUS_IGNORE);
  MCHECK(t, got == left, "a ring on MPI_Comm_dup_with_info's: %d", got);
  MPI_Comm_get_info(d, &out);
  MPI_Info_free(&out);
  MPI_Comm_free(&d);
  MPI_Comm_dup_with_info(c, MPI_INFO_NULL, &d);
  MPI_Sendrecv(&t->rank, 1, MPI_INT, right, 0, &got, 1, MPI_INT, left, 0, d, MPI_STATUS_IGNORE);
  MCHECK(t, got == left, "a ring on a dup with MPI_INFO_NULL: %d", got);
  MPI_Comm_free(&d);
  MPI_Comm_free(&c);
  MPI_Info_free(&in);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {io_basic, io_errors, io_env, io_many, io_comm, NULL};
  return mtest_main(&argc, &argv, "info_objects", 1, 0, checks);
}
