/* win.c -- windows (MPI 3.1 sections 11.2 and 11.2.6-11.2.7): the four ways
 * to make one, their memory, attached regions, MPI_Win_free, the group,
 * attributes, names, info and error handlers (win.h says what the ranks
 * share).
 *
 * Making a window is collective: its ranks agree on a context pair for the
 * window's own communicator (as MPI_Comm_dup: a tree up and down), rank 0
 * makes the shared object and broadcasts where it is, each rank fills in
 * its part, and a barrier makes the parts known to all (a shared window has
 * one more, between the sizes and the memory).  MPI_Win_free completes the
 * rank's operations and ends with a barrier; the last rank to let go of the
 * shared object frees it. */
#include "mpi/win.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/attr.h"
#include "mpi/comm.h"
#include "mpi/err.h"
#include "mpi/errh.h"
#include "mpi/group.h"
#include "mpi/info.h"
#include "mpi/label.h"
#include "util/xmem.h"

enum { HK_WIN = 8 };   /* mpi.h: a window's handle is 8 << 24 | index */

/* ==== the rank's windows ================================================== */

typedef struct {
  st_rank *R;
  rma_window **w;
  int n;
} wtable;

static void drop_shared(rma_shared *sh);
static void win_end(st_rank *R, rma_window *w);

static void table_release(void *p) {
  wtable *t = p;
  for (int i = 0; i < t->n; i++)
    if (t->w[i]) win_end(t->R, t->w[i]);
  free(t->w);
  free(t);
}

static wtable *table(st_rank *R) {
  wtable *t = st_part(ST_PART_WIN);
  if (!t) {
    t = xcalloc(1, sizeof *t);
    t->R = R;
    st_part_set(ST_PART_WIN, t, table_release);
  }
  return t;
}

rma_window *rma_win_get(st_rank *R, MPI_Win h) {
  wtable *t = st_part(ST_PART_WIN);
  unsigned slot = (unsigned)h - (unsigned)(HK_WIN << H_KIND_SHIFT | H_CREATED);
  (void)R;
  return t && slot < (unsigned)t->n ? t->w[slot] : NULL;
}

int rma_win_check(st_rank *R, MPI_Win h, const char *fn, rma_window **w) {
  *w = rma_win_get(R, h);
  if (*w) return MPI_SUCCESS;
  return err_raise(R, NULL, MPI_ERR_WIN, fn, "invalid window: %s",
                   h == MPI_WIN_NULL           ? "MPI_WIN_NULL"
                   : H_KIND(h) == HK_WIN ? "freed, or not this rank's"
                                               : "not a window");
}

int rma_win_raise(st_rank *R, rma_window *w, int cls, const char *fn, const char *fmt, ...) {
  char msg[300];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return err_raise_on(R, w->eh, w->h, cls, fn, "%s", msg);
}

const char *rma_win_words(const rma_window *w, char *buf) {
  snprintf(buf, 32, "window %d", w->c->pair);
  return buf;
}

static void wlabel_describe(void *ud, char *buf, size_t len) {
  const rma_wlabel *l = ud;
  char b[32];
  const char *lk = l->lock == MPI_LOCK_EXCLUSIVE ? "MPI_LOCK_EXCLUSIVE, " : l->lock == MPI_LOCK_SHARED ? "MPI_LOCK_SHARED, " : "";
  if (l->rank >= 0)
    snprintf(buf, len, "%s(%srank=%d, %s)", l->fn, lk, l->rank, rma_win_words(l->w, b));
  else
    snprintf(buf, len, "%s(%s)", l->fn, rma_win_words(l->w, b));
}

void rma_wlabel_set(st_rank *R, rma_wlabel *l) { mp_label(R->self, wlabel_describe, l); }

/* ==== hints =============================================================== */

static void hints_default(rma_hints *h) {
  *h = (rma_hints){0};
  snprintf(h->ordering, sizeof h->ordering, "rar,raw,war,waw");
  snprintf(h->ops, sizeof h->ops, "same_op_no_op");
}

static int truth(const char *v) { return !strcmp(v, "true"); }

/* The hints of info that windows know (the others are ignored, as MPICH):
 * MPI_SUCCESS, or MPI_ERR_INFO raised (on c, or on w when c is NULL). */
static int hints_take(st_rank *R, const st_comm *c, rma_window *w, const char *fn, MPI_Info info, rma_hints *h) {
  char v[MPI_MAX_INFO_VAL + 1];
  int rc = info_value(R, info, "no_locks", v, sizeof v);
  if (rc < 0) {
    if (w) return rma_win_raise(R, w, MPI_ERR_INFO, fn, "invalid info object (freed, or not an info object)");
    return err_raise(R, c, MPI_ERR_INFO, fn, "invalid info object (freed, or not an info object)");
  }
  if (rc > 0) h->no_locks = truth(v);
  if (info_value(R, info, "same_size", v, sizeof v) > 0) h->same_size = truth(v);
  if (info_value(R, info, "same_disp_unit", v, sizeof v) > 0) h->same_disp_unit = truth(v);
  if (info_value(R, info, "alloc_shared_noncontig", v, sizeof v) > 0) h->alloc_shared_noncontig = truth(v);
  if (info_value(R, info, "accumulate_ordering", v, sizeof v) > 0)
    snprintf(h->ordering, sizeof h->ordering, "%.63s", v);
  if (info_value(R, info, "accumulate_ops", v, sizeof v) > 0 &&
      (!strcmp(v, "same_op") || !strcmp(v, "same_op_no_op")))
    snprintf(h->ops, sizeof h->ops, "%.31s", v);
  return MPI_SUCCESS;
}

/* ==== making a window ===================================================== */

/* What the four constructors differ in. */
typedef struct {
  const char *fn;
  int flavor;
  void *base;              /* MPI_Win_create's memory */
  MPI_Aint size;
  int disp_unit;
  void *baseptr;           /* _allocate and _allocate_shared: where the base goes */
} wmake;

/* The window's communicator: a duplicate of c (its own context pair),
 * hidden from the program. */
static int own_comm(st_rank *R, st_comm *c, const char *fn, MPI_Comm *out) {
  int pair = comm_agree_pair(R, 2 * c->pair + 1, c->g, c->rank, TAG_CTXID);
  if (pair < 0) return comm_no_pair(R, c, fn);
  c->g->refs++;
  *out = comm_add(R, c->g, pair, c->rank, MPI_ERRORS_ARE_FATAL, 0);
  st_comm_get(R, *out)->hidden = 1;
  return MPI_SUCCESS;
}

/* Rank 0's: the shared object of n parts, held by rank 0. */
static rma_shared *shared_new(int n) {
  rma_shared *sh = xcalloc(1, sizeof *sh + (size_t)n * sizeof(rma_part));
  pthread_mutex_init(&sh->mu, NULL);
  sh->refs = 1;
  sh->n = n;
  return sh;
}

/* Another rank holds it once it has its address (before any rank can let
 * go of it: that comes after the barrier that ends the making, or when the
 * run stops, and then the others' broadcast fails). */
static void hold_shared(rma_shared *sh) {
  pthread_mutex_lock(&sh->mu);
  sh->refs++;
  pthread_mutex_unlock(&sh->mu);
}

static void drop_shared(rma_shared *sh) {
  if (!sh) return;
  pthread_mutex_lock(&sh->mu);
  int last = --sh->refs == 0;
  pthread_mutex_unlock(&sh->mu);
  if (!last) return;
  for (int i = 0; i < sh->n; i++) {
    free(sh->part[i].mem);
    free(sh->part[i].regs);
    free(sh->part[i].q);
  }
  free(sh->seg);
  pthread_mutex_destroy(&sh->mu);
  free(sh);
}

/* MPI_Win_allocate_shared's memory: rank 0 lays the parts out one after
 * the other (each at a multiple of 4096 bytes with alloc_shared_noncontig)
 * in one block, once every size is known. */
static void shared_layout(rma_shared *sh, int noncontig) {
  size_t total = 0;
  for (int i = 0; i < sh->n; i++) {
    if (noncontig) total = (total + 4095) & ~(size_t)4095;
    total += (size_t)sh->part[i].size;
  }
  sh->seg = xcalloc(total ? total : 1, 1);
  size_t at = 0;
  for (int i = 0; i < sh->n; i++) {
    if (noncontig) at = (at + 4095) & ~(size_t)4095;
    sh->part[i].base = sh->seg + at;
    at += (size_t)sh->part[i].size;
  }
}

static int make(const wmake *m, MPI_Info info, MPI_Comm comm, MPI_Win *win) {
  const char *fn = m->fn;
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (c->inter) return err_raise(R, c, MPI_ERR_COMM, fn, "an intercommunicator (windows are made on intracommunicators)");
  if (!win) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL win argument");
  if (m->size < 0) return err_raise(R, c, MPI_ERR_SIZE, fn, "invalid size %td (must be >= 0)", (ptrdiff_t)m->size);
  if (m->flavor != MPI_WIN_FLAVOR_DYNAMIC && m->disp_unit <= 0)
    return err_raise(R, c, MPI_ERR_DISP, fn, "invalid disp_unit %d (must be > 0)", m->disp_unit);
  if (m->flavor == MPI_WIN_FLAVOR_CREATE && m->size > 0 && !m->base)
    return err_raise(R, c, MPI_ERR_ARG, fn, "NULL base for %td bytes", (ptrdiff_t)m->size);
  if ((m->flavor == MPI_WIN_FLAVOR_ALLOCATE || m->flavor == MPI_WIN_FLAVOR_SHARED) && !m->baseptr)
    return err_raise(R, c, MPI_ERR_ARG, fn, "NULL baseptr argument");
  rma_hints hints;
  hints_default(&hints);
  if ((rc = hints_take(R, c, NULL, fn, info, &hints))) return rc;
  *win = MPI_WIN_NULL;

  label_rec l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  label_set(R, &l);
  MPI_Comm own = MPI_COMM_NULL;
  rc = own_comm(R, c, fn, &own);
  label_clear(R);
  if (rc) return rc;
  /* In the rank's table at once, so that a run stopped while it is made
   * frees it (its handle is the program's when the call returns). */
  rma_window *w = xcalloc(1, sizeof *w);
  w->flavor = m->flavor;
  w->comm = own;
  w->c = st_comm_get(R, own);
  w->rank = c->rank;
  w->size = c->size;
  w->eh = MPI_ERRORS_ARE_FATAL;
  w->hints = hints;
  wtable *t = table(R);
  int slot = 0;
  while (slot < t->n && t->w[slot]) slot++;
  if (slot == t->n) t->w = xreallocarray(t->w, (size_t)++t->n, sizeof *t->w);
  t->w[slot] = w;
  w->h = (MPI_Win)(HK_WIN << H_KIND_SHIFT | H_CREATED | slot);
  /* Rank 0 makes the shared object; each rank fills in its part. */
  rma_shared *sh = w->sh = w->rank == 0 ? shared_new(w->size) : NULL;
  PMPI_Bcast(&sh, (int)sizeof sh, MPI_BYTE, 0, own);
  if (w->rank != 0) hold_shared(w->sh = sh);
  rma_part *p = &sh->part[w->rank];
  p->wrank = R->wrank;
  p->size = m->flavor == MPI_WIN_FLAVOR_DYNAMIC ? 0 : m->size;
  p->disp_unit = m->flavor == MPI_WIN_FLAVOR_DYNAMIC ? 1 : m->disp_unit;
  if (m->flavor == MPI_WIN_FLAVOR_CREATE) p->base = m->base;
  if (m->flavor == MPI_WIN_FLAVOR_ALLOCATE) p->base = p->mem = xcalloc(m->size ? (size_t)m->size : 1, 1);
  if (m->flavor == MPI_WIN_FLAVOR_SHARED) {
    PMPI_Barrier(own);   /* every size in */
    if (w->rank == 0) shared_layout(sh, hints.alloc_shared_noncontig);
  }
  PMPI_Barrier(own);   /* every part in */
  if (m->baseptr) *(void **)m->baseptr = p->base;
  *win = w->h;
  return MPI_SUCCESS;
}

int PMPI_Win_create(void *base, MPI_Aint size, int disp_unit, MPI_Info info, MPI_Comm comm, MPI_Win *win) {
  wmake m = {"MPI_Win_create", MPI_WIN_FLAVOR_CREATE, base, size, disp_unit, NULL};
  return make(&m, info, comm, win);
}

int PMPI_Win_allocate(MPI_Aint size, int disp_unit, MPI_Info info, MPI_Comm comm, void *baseptr, MPI_Win *win) {
  wmake m = {"MPI_Win_allocate", MPI_WIN_FLAVOR_ALLOCATE, NULL, size, disp_unit, baseptr};
  return make(&m, info, comm, win);
}

int PMPI_Win_allocate_shared(MPI_Aint size, int disp_unit, MPI_Info info, MPI_Comm comm, void *baseptr,
                             MPI_Win *win) {
  wmake m = {"MPI_Win_allocate_shared", MPI_WIN_FLAVOR_SHARED, NULL, size, disp_unit, baseptr};
  return make(&m, info, comm, win);
}

int PMPI_Win_create_dynamic(MPI_Info info, MPI_Comm comm, MPI_Win *win) {
  wmake m = {"MPI_Win_create_dynamic", MPI_WIN_FLAVOR_DYNAMIC, NULL, 0, 1, NULL};
  return make(&m, info, comm, win);
}

/* ==== freeing ============================================================= */

/* The rank's part of w ends (its operations complete, or a stopped run). */
static void win_end(st_rank *R, rma_window *w) {
  rma_release(w);
  free(w->acc);
  free(w->expo);
  free(w->postrq);
  free(w->donerq);
  drop_shared(w->sh);
  errh_drop(R, w->eh);
  free(w);
}

int PMPI_Win_free(MPI_Win *win) {
  static const char fn[] = "MPI_Win_free";
  st_rank *R = st_need(fn);
  if (!win) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL win argument");
  rma_window *w;
  int rc = rma_win_check(R, *win, fn, &w);
  if (rc) return rc;
  if (w->acc || w->expo || w->lockall || w->nlocked)
    return rma_win_raise(R, w, MPI_ERR_RMA_SYNC, fn, "an epoch is still open (%s)",
                         w->acc ? "MPI_Win_start without MPI_Win_complete"
                         : w->expo ? "MPI_Win_post without MPI_Win_wait"
                         : w->lockall ? "MPI_Win_lock_all without MPI_Win_unlock_all"
                                      : "MPI_Win_lock without MPI_Win_unlock");
  char why[128];
  if ((rc = attr_delete_all(R, ATTR_WIN, w->h, why))) return rma_win_raise(R, w, rc, fn, "%s", why);
  rma_wlabel l = {.fn = fn, .w = w, .rank = -1};
  rma_wlabel_set(R, &l);
  rma_complete(R, w, -1, 0);
  PMPI_Barrier(w->comm);
  label_clear(R);
  MPI_Comm own = w->comm;
  wtable *t = table(R);
  t->w[(unsigned)*win & H_SLOT_MASK] = NULL;
  win_end(R, w);
  comm_end(R, &own);
  *win = MPI_WIN_NULL;
  return MPI_SUCCESS;
}

/* ==== memory ============================================================== */

int PMPI_Win_shared_query(MPI_Win win, int rank, MPI_Aint *size, int *disp_unit, void *baseptr) {
  static const char fn[] = "MPI_Win_shared_query";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (w->flavor != MPI_WIN_FLAVOR_SHARED)
    return rma_win_raise(R, w, MPI_ERR_RMA_FLAVOR, fn, "not a window of MPI_Win_allocate_shared");
  if (rank != MPI_PROC_NULL && (rank < 0 || rank >= w->size))
    return rma_win_raise(R, w, MPI_ERR_RANK, fn, "invalid rank %d (the window has %d rank%s)", rank, w->size,
                         w->size == 1 ? "" : "s");
  if (!size || !disp_unit || !baseptr) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL argument");
  if (rank == MPI_PROC_NULL) {   /* the lowest rank with memory */
    rank = 0;
    while (rank < w->size - 1 && w->sh->part[rank].size == 0) rank++;
  }
  const rma_part *p = &w->sh->part[rank];
  *size = p->size;
  *disp_unit = p->disp_unit;
  *(void **)baseptr = p->base;
  return MPI_SUCCESS;
}

int PMPI_Win_attach(MPI_Win win, void *base, MPI_Aint size) {
  static const char fn[] = "MPI_Win_attach";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (w->flavor != MPI_WIN_FLAVOR_DYNAMIC)
    return rma_win_raise(R, w, MPI_ERR_RMA_FLAVOR, fn, "not a window of MPI_Win_create_dynamic");
  if (size < 0) return rma_win_raise(R, w, MPI_ERR_SIZE, fn, "invalid size %td (must be >= 0)", (ptrdiff_t)size);
  if (size > 0 && !base) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL base for %td bytes", (ptrdiff_t)size);
  rma_part *p = &w->sh->part[w->rank];
  char *b = base;
  pthread_mutex_lock(&w->sh->mu);
  for (int i = 0; i < p->nregs; i++) {
    if (size && p->regs[i].size && b < p->regs[i].base + p->regs[i].size && p->regs[i].base < b + size) {
      pthread_mutex_unlock(&w->sh->mu);
      return rma_win_raise(R, w, MPI_ERR_RMA_ATTACH, fn, "the region overlaps one attached already");
    }
  }
  if (p->nregs == p->capregs)
    p->regs = xreallocarray(p->regs, (size_t)(p->capregs = p->capregs ? 2 * p->capregs : 4), sizeof *p->regs);
  p->regs[p->nregs++] = (rma_region){b, size};
  pthread_mutex_unlock(&w->sh->mu);
  return MPI_SUCCESS;
}

int PMPI_Win_detach(MPI_Win win, const void *base) {
  static const char fn[] = "MPI_Win_detach";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (w->flavor != MPI_WIN_FLAVOR_DYNAMIC)
    return rma_win_raise(R, w, MPI_ERR_RMA_FLAVOR, fn, "not a window of MPI_Win_create_dynamic");
  rma_part *p = &w->sh->part[w->rank];
  pthread_mutex_lock(&w->sh->mu);
  for (int i = 0; i < p->nregs; i++) {
    if (p->regs[i].base != base) continue;
    memmove(p->regs + i, p->regs + i + 1, (size_t)(p->nregs - i - 1) * sizeof *p->regs);
    p->nregs--;
    pthread_mutex_unlock(&w->sh->mu);
    return MPI_SUCCESS;
  }
  pthread_mutex_unlock(&w->sh->mu);
  return rma_win_raise(R, w, MPI_ERR_RMA_ATTACH, fn, "no region attached at %p", base);
}

int PMPI_Win_get_group(MPI_Win win, MPI_Group *group) {
  static const char fn[] = "MPI_Win_get_group";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!group) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL group argument");
  w->c->g->refs++;
  *group = group_add(R, w->c->g);
  return MPI_SUCCESS;
}

/* ==== attributes ========================================================== */

/* The predefined attributes' values: where each lies (the window's
 * memory, or a copy the window keeps). */
static int predefined(rma_window *w, int key, void **value) {
  rma_part *p = &w->sh->part[w->rank];
  switch (key) {
  case MPI_WIN_BASE: *value = p->base; return 1;
  case MPI_WIN_SIZE: *value = &p->size; return 1;
  case MPI_WIN_DISP_UNIT: *value = &p->disp_unit; return 1;
  case MPI_WIN_CREATE_FLAVOR: *value = &w->flavor; return 1;
  case MPI_WIN_MODEL: {
    static const int unified = MPI_WIN_UNIFIED;
    *value = (void *)&unified;
    return 1;
  }
  }
  return 0;
}

static int is_predefined(int key) { return key >= MPI_WIN_BASE && key <= MPI_WIN_MODEL; }

int PMPI_Win_set_attr(MPI_Win win, int win_keyval, void *attribute_val) {
  static const char fn[] = "MPI_Win_set_attr";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (is_predefined(win_keyval))
    return rma_win_raise(R, w, MPI_ERR_KEYVAL, fn, "keyval %d is predefined and cannot be set", win_keyval);
  char why[128];
  rc = attr_set(R, ATTR_WIN, win, win_keyval, attribute_val, why);
  return rc ? rma_win_raise(R, w, rc, fn, "%s", why) : rc;
}

int PMPI_Win_get_attr(MPI_Win win, int win_keyval, void *attribute_val, int *flag) {
  static const char fn[] = "MPI_Win_get_attr";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!attribute_val || !flag) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL argument");
  void *v;
  if (predefined(w, win_keyval, &v)) {
    *flag = 1;
    *(void **)attribute_val = v;
    return MPI_SUCCESS;
  }
  char why[128];
  if ((rc = attr_get(R, ATTR_WIN, win, win_keyval, &v, flag, why))) return rma_win_raise(R, w, rc, fn, "%s", why);
  if (*flag) *(void **)attribute_val = v;
  return MPI_SUCCESS;
}

int PMPI_Win_delete_attr(MPI_Win win, int win_keyval) {
  static const char fn[] = "MPI_Win_delete_attr";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (is_predefined(win_keyval))
    return rma_win_raise(R, w, MPI_ERR_KEYVAL, fn, "keyval %d is predefined and cannot be deleted", win_keyval);
  char why[128];
  rc = attr_delete(R, ATTR_WIN, win, win_keyval, why);
  return rc ? rma_win_raise(R, w, rc, fn, "%s", why) : rc;
}

/* ==== names and info ====================================================== */

int PMPI_Win_set_name(MPI_Win win, const char *win_name) {
  static const char fn[] = "MPI_Win_set_name";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!win_name) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL win_name argument");
  snprintf(w->name, sizeof w->name, "%s", win_name);
  return MPI_SUCCESS;
}

int PMPI_Win_get_name(MPI_Win win, char *win_name, int *resultlen) {
  static const char fn[] = "MPI_Win_get_name";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!win_name || !resultlen) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL argument");
  snprintf(win_name, MPI_MAX_OBJECT_NAME, "%s", w->name);
  *resultlen = (int)strlen(win_name);
  return MPI_SUCCESS;
}

int PMPI_Win_set_info(MPI_Win win, MPI_Info info) {
  static const char fn[] = "MPI_Win_set_info";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (info == MPI_INFO_NULL) return rma_win_raise(R, w, MPI_ERR_INFO, fn, "MPI_INFO_NULL");
  return hints_take(R, NULL, w, fn, info, &w->hints);
}

int PMPI_Win_get_info(MPI_Win win, MPI_Info *info_used) {
  static const char fn[] = "MPI_Win_get_info";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!info_used) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL info_used argument");
  const rma_hints *h = &w->hints;
  PMPI_Info_create(info_used);
  PMPI_Info_set(*info_used, "no_locks", h->no_locks ? "true" : "false");
  PMPI_Info_set(*info_used, "accumulate_ordering", h->ordering[0] ? h->ordering : "none");
  PMPI_Info_set(*info_used, "accumulate_ops", h->ops);
  PMPI_Info_set(*info_used, "same_size", h->same_size ? "true" : "false");
  PMPI_Info_set(*info_used, "same_disp_unit", h->same_disp_unit ? "true" : "false");
  PMPI_Info_set(*info_used, "alloc_shared_noncontig", h->alloc_shared_noncontig ? "true" : "false");
  return MPI_SUCCESS;
}

/* ==== error handlers ====================================================== */

int PMPI_Win_set_errhandler(MPI_Win win, MPI_Errhandler errhandler) {
  static const char fn[] = "MPI_Win_set_errhandler";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  char why[96];
  if (errh_check(R, errhandler, ERRH_WIN, why)) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "%s", why);
  errh_set(R, &w->eh, errhandler);
  return MPI_SUCCESS;
}

/* The handler is the program's to free (MPI 3.1 section 8.3.2). */
int PMPI_Win_get_errhandler(MPI_Win win, MPI_Errhandler *errhandler) {
  static const char fn[] = "MPI_Win_get_errhandler";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  if (!errhandler) return rma_win_raise(R, w, MPI_ERR_ARG, fn, "NULL errhandler argument");
  errh_hold(R, w->eh);
  *errhandler = w->eh;
  return MPI_SUCCESS;
}

int PMPI_Win_call_errhandler(MPI_Win win, int errorcode) {
  static const char fn[] = "MPI_Win_call_errhandler";
  st_rank *R = st_need(fn);
  rma_window *w;
  int rc = rma_win_check(R, win, fn, &w);
  if (rc) return rc;
  int cls = errh_class(R, errorcode);
  const char *s = cls < 0 ? "" : errh_string(R, errorcode);
  rma_win_raise(R, w, errorcode, fn, "error code %d%s%s", errorcode, *s ? ": " : "", s);
  return MPI_SUCCESS;   /* once the handler has returned */
}
