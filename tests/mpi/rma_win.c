/* rma_win.c -- windows (MPI 3.1 sections 11.2, 11.2.6, 11.5.4, 6.7.3,
 * 8.3.2), checked by themselves on any number of ranks: the four ways to
 * make one and their attributes (MPI_WIN_BASE, _SIZE, _DISP_UNIT,
 * _CREATE_FLAVOR, _MODEL), names, info, MPI_Win_get_group, attributes of
 * the program's keyvals with their delete callback (at MPI_Win_delete_attr
 * and MPI_Win_free), error handlers (a window's own, called by a failing
 * call and by MPI_Win_call_errhandler, given back by
 * MPI_Win_get_errhandler), MPI_Win_allocate_shared's memory as one block
 * read and written directly (MPI_Win_shared_query), a dynamic window's
 * regions (MPI_Win_attach, _detach) written by a neighbour, and the errors
 * of wrong synchronisation and bad arguments under MPI_ERRORS_RETURN.
 *
 * The handler and the delete callback find this rank's record through the
 * window's name (there being no globals). */
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "mtest.h"

typedef struct {
  int calls;     /* the handler's */
  MPI_Win win;
  int code;
  int deletes;   /* the delete callback's */
  void *value;
} record;

static record *of(MPI_Win win) {
  char name[MPI_MAX_OBJECT_NAME];
  int len;
  void *p = NULL;
  MPI_Win_get_name(win, name, &len);
  return sscanf(name, "rec %p", &p) == 1 ? p : NULL;
}

static void point(MPI_Win win, record *r) {
  char name[MPI_MAX_OBJECT_NAME];
  snprintf(name, sizeof name, "rec %p", (void *)r);
  MPI_Win_set_name(win, name);
}

static void handler(MPI_Win *win, int *code, ...) {
  record *r = of(*win);
  if (!r) return;
  r->calls++;
  r->win = *win;
  r->code = *code;
}

static int deleted(MPI_Win win, int keyval, void *value, void *extra) {
  (void)keyval, (void)extra;
  record *r = of(win);
  if (r) r->deletes++, r->value = value;
  return MPI_SUCCESS;
}

static int cls_of(int code) {
  int cls = -1;
  MPI_Error_class(code, &cls);
  return cls;
}

/* The predefined attributes of win, against what it was made with. */
static void attributes(mtest *t, MPI_Win win, void *base, MPI_Aint size, int unit, int flavor) {
  void *b = NULL;
  MPI_Aint *s = NULL;
  int *u = NULL, *f = NULL, *m = NULL, flag[5];
  MPI_Win_get_attr(win, MPI_WIN_BASE, &b, &flag[0]);
  MPI_Win_get_attr(win, MPI_WIN_SIZE, &s, &flag[1]);
  MPI_Win_get_attr(win, MPI_WIN_DISP_UNIT, &u, &flag[2]);
  MPI_Win_get_attr(win, MPI_WIN_CREATE_FLAVOR, &f, &flag[3]);
  MPI_Win_get_attr(win, MPI_WIN_MODEL, &m, &flag[4]);
  MCHECK(t, flag[0] && flag[1] && flag[2] && flag[3] && flag[4], "a predefined attribute missing");
  if (!(flag[0] && flag[1] && flag[2] && flag[3] && flag[4])) return;
  if (flavor != MPI_WIN_FLAVOR_DYNAMIC) MCHECK(t, b == base, "MPI_WIN_BASE %p, made at %p", b, base);
  MCHECK(t, *s == size, "MPI_WIN_SIZE %ld, made with %ld", (long)*s, (long)size);
  if (flavor != MPI_WIN_FLAVOR_DYNAMIC) MCHECK(t, *u == unit, "MPI_WIN_DISP_UNIT %d, made with %d", *u, unit);
  MCHECK(t, *f == flavor, "MPI_WIN_CREATE_FLAVOR %d, made as %d", *f, flavor);
  MCHECK(t, *m == MPI_WIN_UNIFIED || *m == MPI_WIN_SEPARATE, "MPI_WIN_MODEL %d", *m);
}

static void flavors(mtest *t) {
  int rank = t->rank, size = t->size;
  int mem[8];
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  attributes(t, win, mem, sizeof mem, sizeof(int), MPI_WIN_FLAVOR_CREATE);
  MPI_Group wg;
  MPI_Win_get_group(win, &wg);
  mtest_world_group(t, wg, "MPI_Win_get_group");
  MPI_Win_free(&win);
  MCHECK(t, win == MPI_WIN_NULL, "MPI_Win_free left the handle");

  double *d = NULL;
  MPI_Aint dsize = (MPI_Aint)(rank + 1) * (MPI_Aint)sizeof(double);
  MPI_Win_allocate(dsize, sizeof(double), MPI_INFO_NULL, MPI_COMM_WORLD, &d, &win);
  MCHECK(t, d != NULL, "MPI_Win_allocate gave no memory");
  attributes(t, win, d, dsize, sizeof(double), MPI_WIN_FLAVOR_ALLOCATE);
  for (int i = 0; i <= rank; i++) d[i] = rank + i / 10.0;   /* the memory is the program's */
  MPI_Win_free(&win);

  /* A zero-size window on some ranks, made on a split communicator. */
  MPI_Comm half;
  MPI_Comm_split(MPI_COMM_WORLD, rank % 2, rank, &half);
  MPI_Win_create(rank % 2 ? mem : NULL, rank % 2 ? (MPI_Aint)sizeof mem : 0, 1, MPI_INFO_NULL, half, &win);
  MPI_Win_get_group(win, &wg);
  int gs;
  MPI_Group_size(wg, &gs);
  MCHECK(t, gs == (size + 1 - rank % 2) / 2, "a window on half the ranks has a group of %d", gs);
  MPI_Group_free(&wg);
  MPI_Win_free(&win);
  MPI_Comm_free(&half);

  MPI_Win_create_dynamic(MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  attributes(t, win, NULL, 0, 1, MPI_WIN_FLAVOR_DYNAMIC);
  MPI_Win_free(&win);
}

static void names_info(mtest *t) {
  int mem[2];
  MPI_Win win;
  MPI_Info in;
  MPI_Info_create(&in);
  MPI_Info_set(in, "no_locks", "true");
  MPI_Info_set(in, "accumulate_ordering", "none");
  MPI_Win_create(mem, sizeof mem, 1, in, MPI_COMM_WORLD, &win);
  MPI_Info_free(&in);
  char name[MPI_MAX_OBJECT_NAME], v[MPI_MAX_INFO_VAL + 1];
  int len, flag;
  MPI_Win_set_name(win, "halo window");
  MPI_Win_get_name(win, name, &len);
  MCHECK(t, !strcmp(name, "halo window") && len == 11, "the name is '%s' (%d)", name, len);
  MPI_Info out;
  MPI_Win_get_info(win, &out);
  MPI_Info_get(out, "no_locks", MPI_MAX_INFO_VAL, v, &flag);
  MCHECK(t, flag && !strcmp(v, "true"), "no_locks: %s", flag ? v : "(not there)");
  MPI_Info_free(&out);
  MPI_Info_create(&in);
  MPI_Info_set(in, "no_locks", "false");
  MPI_Win_set_info(win, in);
  MPI_Info_free(&in);
  /* (What MPI_Win_get_info says after MPI_Win_set_info differs: Open MPI
   * 4.1 forgets no_locks, MPICH and tilesim keep it; test_mpi_rma checks
   * tilesim's.) */
  MPI_Win_get_info(win, &out);
  int nkeys = -1;
  MPI_Info_get_nkeys(out, &nkeys);
  MCHECK(t, nkeys >= 0, "MPI_Win_get_info after MPI_Win_set_info");
  MPI_Info_free(&out);
  MPI_Win_free(&win);
}

static void handlers_keyvals(mtest *t) {
  int mem[4] = {0}, v = 1;
  record rec = {0};
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  point(win, &rec);
  MPI_Errhandler eh, got;
  MPI_Win_create_errhandler(handler, &eh);
  MPI_Win_set_errhandler(win, eh);
  MPI_Errhandler_free(&eh);
  MPI_Win_get_errhandler(win, &got);
  int rc = MPI_Put(&v, 1, MPI_INT, 0, 0, 1, MPI_INT, win);   /* no epoch */
  MCHECK(t, cls_of(rc) == MPI_ERR_RMA_SYNC && rec.calls == 1 && rec.win == win && cls_of(rec.code) == MPI_ERR_RMA_SYNC,
         "a put outside an epoch: %d, the handler called %d times with class %d", rc, rec.calls, cls_of(rec.code));
  MPI_Win_call_errhandler(win, MPI_ERR_OTHER);
  MCHECK(t, rec.calls == 2 && rec.code == MPI_ERR_OTHER, "MPI_Win_call_errhandler: %d calls, code %d", rec.calls,
         rec.code);
  MPI_Win_set_errhandler(win, MPI_ERRORS_RETURN);
  MPI_Errhandler_free(&got);

  int key;
  MPI_Win_create_keyval(MPI_WIN_NULL_COPY_FN, deleted, &key, NULL);
  void *val = NULL;
  int flag = 1;
  MPI_Win_get_attr(win, key, &val, &flag);
  MCHECK(t, !flag, "an attribute before any was set");
  MPI_Win_set_attr(win, key, &mem[1]);
  MPI_Win_get_attr(win, key, &val, &flag);
  MCHECK(t, flag && val == &mem[1], "MPI_Win_get_attr gave %p (flag %d)", val, flag);
  MPI_Win_delete_attr(win, key);
  MCHECK(t, rec.deletes == 1 && rec.value == &mem[1], "MPI_Win_delete_attr: %d deletes", rec.deletes);
  MPI_Win_set_attr(win, key, &mem[2]);
  MPI_Win_free_keyval(&key);
  MPI_Win_free(&win);
  MCHECK(t, rec.deletes == 2 && rec.value == &mem[2], "MPI_Win_free: %d deletes", rec.deletes);
}

/* MPI_Win_allocate_shared: one block, each rank's part after the one
 * before, written by its rank and read by the others directly. */
static void shared(mtest *t) {
  int rank = t->rank, size = t->size;
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int nr, ns;
  MPI_Comm_rank(node, &nr);
  MPI_Comm_size(node, &ns);
  int *mine;
  MPI_Win win;
  MPI_Win_allocate_shared((MPI_Aint)(nr + 1) * (MPI_Aint)sizeof(int), sizeof(int), MPI_INFO_NULL, node, &mine, &win);
  attributes(t, win, mine, (MPI_Aint)(nr + 1) * (MPI_Aint)sizeof(int), sizeof(int), MPI_WIN_FLAVOR_SHARED);
  MPI_Win_lock_all(0, win);
  for (int i = 0; i <= nr; i++) mine[i] = 100 * rank + i;
  MPI_Win_sync(win);
  MPI_Barrier(node);
  MPI_Win_sync(win);
  int bad = 0, contiguous = 1;
  char *prev_end = NULL;
  for (int q = 0; q < ns; q++) {
    MPI_Aint qs;
    int unit, *base;
    MPI_Win_shared_query(win, q, &qs, &unit, &base);
    if (qs != (MPI_Aint)(q + 1) * (MPI_Aint)sizeof(int) || unit != (int)sizeof(int)) bad++;
    if (q > 0 && (char *)base != prev_end) contiguous = 0;
    prev_end = (char *)base + qs;
  }
  MPI_Group ng, wg;
  MPI_Comm_group(node, &ng);
  MPI_Comm_group(MPI_COMM_WORLD, &wg);
  for (int q = 0; q < ns; q++) {
    int w, *base, unit;
    MPI_Aint qs;
    MPI_Group_translate_ranks(ng, 1, &q, wg, &w);
    MPI_Win_shared_query(win, q, &qs, &unit, &base);
    for (int i = 0; i <= q; i++) bad += base[i] != 100 * w + i;
  }
  MPI_Group_free(&ng);
  MPI_Group_free(&wg);
  MPI_Win_unlock_all(win);
  MCHECK(t, bad == 0, "%d wrong values or sizes in the shared window", bad);
  MCHECK(t, contiguous, "the parts do not follow each other");
  (void)size;
  MPI_Win_free(&win);
  MPI_Comm_free(&node);
}

/* A dynamic window: each rank attaches a region, tells its left neighbour
 * where, and the neighbour puts into it. */
static void dynamic(mtest *t) {
  int rank = t->rank, size = t->size, right = (rank + 1) % size, left = (rank + size - 1) % size;
  int region[6] = {0};
  MPI_Win win;
  MPI_Win_create_dynamic(MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Win_attach(win, region, sizeof region);
  MPI_Aint mine, theirs;
  MPI_Get_address(region, &mine);
  MPI_Sendrecv(&mine, 1, MPI_AINT, left, 7, &theirs, 1, MPI_AINT, right, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  int vals[3] = {rank, rank * 2, rank * 3};
  MPI_Win_fence(0, win);
  MPI_Put(vals, 3, MPI_INT, right, MPI_Aint_add(theirs, 2 * sizeof(int)), 3, MPI_INT, win);
  MPI_Win_fence(0, win);
  MCHECK(t, region[0] == 0 && region[2] == left && region[3] == 2 * left && region[4] == 3 * left && region[5] == 0,
         "the region holds %d %d %d %d %d %d", region[0], region[1], region[2], region[3], region[4], region[5]);
  MPI_Win_detach(win, region);
  MPI_Win_free(&win);
}

static void errors(mtest *t) {
  int rank = t->rank, size = t->size, mem[4] = {0}, v[4] = {0};
  MPI_Win win;
  MPI_Win_create(mem, sizeof mem, sizeof(int), MPI_INFO_NULL, MPI_COMM_WORLD, &win);
  MPI_Win_set_errhandler(win, MPI_ERRORS_RETURN);
  int other = (rank + 1) % size;
  MCHECK(t, cls_of(MPI_Get(v, 1, MPI_INT, other, 0, 1, MPI_INT, win)) == MPI_ERR_RMA_SYNC, "a get outside an epoch");
  MCHECK(t, cls_of(MPI_Win_unlock(other, win)) == MPI_ERR_RMA_SYNC, "an unlock of what is not locked");
  MCHECK(t, cls_of(MPI_Win_flush(other, win)) == MPI_ERR_RMA_SYNC, "a flush outside a passive-target epoch");
  MCHECK(t, cls_of(MPI_Win_complete(win)) == MPI_ERR_RMA_SYNC, "MPI_Win_complete without MPI_Win_start");
  MCHECK(t, cls_of(MPI_Win_wait(win)) == MPI_ERR_RMA_SYNC, "MPI_Win_wait without MPI_Win_post");
  MCHECK(t, cls_of(MPI_Win_lock(12345, other, 0, win)) == MPI_ERR_LOCKTYPE, "a lock of no type");
  MCHECK(t, cls_of(MPI_Win_lock(MPI_LOCK_SHARED, size + 2, 0, win)) == MPI_ERR_RANK, "a lock of no rank");
  MPI_Win_lock(MPI_LOCK_SHARED, other, 0, win);
  MCHECK(t, cls_of(MPI_Put(v, 1, MPI_INT, size + 2, 0, 1, MPI_INT, win)) == MPI_ERR_RANK, "a put to no rank");
  MCHECK(t, cls_of(MPI_Put(v, -1, MPI_INT, other, 0, 1, MPI_INT, win)) == MPI_ERR_COUNT, "a put of -1 elements");
  MCHECK(t, cls_of(MPI_Put(v, 1, MPI_DATATYPE_NULL, other, 0, 1, MPI_INT, win)) == MPI_ERR_TYPE, "MPI_DATATYPE_NULL");
  MCHECK(t, cls_of(MPI_Accumulate(v, 1, MPI_INT, other, 0, 1, MPI_INT, MPI_OP_NULL, win)) == MPI_ERR_OP,
         "an accumulate with MPI_OP_NULL");
  MPI_Win_unlock(other, win);
  MPI_Aint qs;
  int unit;
  void *base;
  MCHECK(t, cls_of(MPI_Win_shared_query(win, 0, &qs, &unit, &base)) == MPI_ERR_RMA_FLAVOR,
         "MPI_Win_shared_query of MPI_Win_create's window");
  MPI_Win_free(&win);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {flavors, names_info, handlers_keyvals, shared, dynamic, errors, NULL};
  return mtest_main(&argc, &argv, "rma_win", 1, 0, checks);
}
