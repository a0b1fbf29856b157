/* attr.c -- attribute keys and attributes of any kind of object (attr.h).
 *
 * The program's callbacks may call MPI, this module included (a delete
 * callback that frees its keyval, gets the attribute being deleted, sets
 * another): nothing here holds a pointer into the tables across a call
 * of one, and every lookup is made again after it. */
#include "mpi/attr.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/errh.h"
#include "util/xmem.h"

enum { KV_BASE = 16 };

typedef struct {
  int kind;               /* ATTR_* */
  int refs;               /* the program's handle (until freed) and each attribute */
  int freed;              /* the program freed it */
  attr_copy_fn *copy;      /* NULL: copy nothing */
  attr_delete_fn *del;     /* NULL: nothing to do */
  void *extra;
} keyval;

typedef struct attr attr;
struct attr {
  attr *next;
  int keyval;
  void *value;
};

typedef struct {
  int kind, h;
  attr *first;            /* in the order first set */
} object;

struct attr_table {
  keyval **kv;            /* by keyval - KV_BASE; NULL once gone */
  int nkv;
  object *obj;            /* objects with attributes */
  int nobj;
};

static struct attr_table *attrs_of(st_rank *R) {
  if (!R->attrs) R->attrs = xcalloc(1, sizeof *R->attrs);
  return R->attrs;
}

void attr_release_all(st_rank *R) {
  struct attr_table *A = R->attrs;
  if (!A) return;
  for (int i = 0; i < A->nobj; i++)
    for (attr *a = A->obj[i].first, *next; a; a = next) {
      next = a->next;
      free(a);
    }
  free(A->obj);
  for (int i = 0; i < A->nkv; i++) free(A->kv[i]);
  free(A->kv);
  free(A);
  R->attrs = NULL;
}

/* ==== keyvals ============================================================= */

static keyval *kv_get(st_rank *R, int k) {
  struct attr_table *A = R->attrs;
  if (!A || k < KV_BASE || k - KV_BASE >= A->nkv) return NULL;
  return A->kv[k - KV_BASE];
}

static void kv_drop(st_rank *R, int k) {
  keyval *v = kv_get(R, k);
  if (v && --v->refs == 0) {
    free(v);
    R->attrs->kv[k - KV_BASE] = NULL;
  }
}

static const char *const kind_name[] = {"", "communicators", "datatypes", "windows"};

/* The keyval k of kind, or NULL with why.  One the program freed is still
 * usable while attributes keep it alive (as MPICH: a copy of its handle
 * may delete them). */
static keyval *kv_check(st_rank *R, int kind, int k, char *why) {
  keyval *v = kv_get(R, k);
  if (k == MPI_KEYVAL_INVALID)
    snprintf(why, 128, "MPI_KEYVAL_INVALID");
  else if (k > 0 && k < KV_BASE)
    snprintf(why, 128, "keyval %d is predefined", k);
  else if (!v)
    snprintf(why, 128, "invalid keyval %d (freed, or not a keyval of this rank)", k);
  else if (v->kind != kind)
    snprintf(why, 128, "keyval %d was made for %s, not %s", k, kind_name[v->kind], kind_name[kind]);
  else
    return v;
  return NULL;
}

int attr_keyval_is(st_rank *R, int kind, int k) {
  keyval *v = kv_get(R, k);
  return v && !v->freed && v->kind == kind;
}

int attr_keyval_create(st_rank *R, int kind, attr_copy_fn *copy, attr_delete_fn *del, void *extra_state, int *k) {
  struct attr_table *A = attrs_of(R);
  keyval *v = xcalloc(1, sizeof *v);
  *v = (keyval){kind, 1, 0, copy, del, extra_state};
  A->kv = xreallocarray(A->kv, (size_t)A->nkv + 1, sizeof *A->kv);
  A->kv[A->nkv] = v;
  *k = KV_BASE + A->nkv++;
  return MPI_SUCCESS;
}

int attr_keyval_free(st_rank *R, int kind, int *k, char *why) {
  keyval *v = kv_get(R, *k);
  if (v && v->freed && v->kind == kind) {   /* alive through its attributes: freed again */
    *k = MPI_KEYVAL_INVALID;
    return MPI_SUCCESS;
  }
  if (!kv_check(R, kind, *k, why)) return MPI_ERR_KEYVAL;
  v->freed = 1;
  kv_drop(R, *k);
  *k = MPI_KEYVAL_INVALID;
  return MPI_SUCCESS;
}

/* ==== objects and their attributes ======================================== */

static object *obj_get(st_rank *R, int kind, int h) {
  struct attr_table *A = R->attrs;
  for (int i = 0; A && i < A->nobj; i++)
    if (A->obj[i].kind == kind && A->obj[i].h == h) return &A->obj[i];
  return NULL;
}

static attr *attr_find(st_rank *R, int kind, int h, int k) {
  object *o = obj_get(R, kind, h);
  for (attr *a = o ? o->first : NULL; a; a = a->next)
    if (a->keyval == k) return a;
  return NULL;
}

/* A new attribute at the end of the object's list (k counted). */
static void attr_add(st_rank *R, int kind, int h, int k, void *value) {
  struct attr_table *A = attrs_of(R);
  object *o = obj_get(R, kind, h);
  if (!o) {
    A->obj = xreallocarray(A->obj, (size_t)A->nobj + 1, sizeof *A->obj);
    o = &A->obj[A->nobj++];
    *o = (object){kind, h, NULL};
  }
  attr **at = &o->first;
  while (*at) at = &(*at)->next;
  *at = xmalloc(sizeof **at);
  **at = (attr){NULL, k, value};
  kv_get(R, k)->refs++;
}

/* The attribute of k leaves the object (if it is still there). */
static void attr_remove(st_rank *R, int kind, int h, int k) {
  object *o = obj_get(R, kind, h);
  if (!o) return;
  for (attr **at = &o->first; *at; at = &(*at)->next) {
    if ((*at)->keyval != k) continue;
    attr *a = *at;
    *at = a->next;
    free(a);
    kv_drop(R, k);
    break;
  }
  if (!o->first) {
    struct attr_table *A = R->attrs;
    *o = A->obj[--A->nobj];
  }
}

/* A callback's answer as an error class. */
static int failed(st_rank *R, int rc, const char *what, int k, char *why) {
  snprintf(why, 128, "the %s callback of keyval %d returned %d", what, k, rc);
  return errh_class(R, rc) > 0 ? rc : MPI_ERR_OTHER;
}

/* Call the delete callback of k for value on object h. */
static int call_delete(st_rank *R, int h, int k, void *value, char *why) {
  keyval *v = kv_get(R, k);
  if (!v->del) return MPI_SUCCESS;
  int rc = v->del(h, k, value, v->extra);
  return rc == MPI_SUCCESS ? rc : failed(R, rc, "delete", k, why);
}

int attr_set(st_rank *R, int kind, int h, int k, void *value, char *why) {
  if (!kv_check(R, kind, k, why)) return MPI_ERR_KEYVAL;
  attr *a = attr_find(R, kind, h, k);
  if (a) {
    int rc = call_delete(R, h, k, a->value, why);
    if (rc) return rc;
    if ((a = attr_find(R, kind, h, k))) {
      a->value = value;
      return MPI_SUCCESS;
    }
  }
  attr_add(R, kind, h, k, value);
  return MPI_SUCCESS;
}

int attr_get(st_rank *R, int kind, int h, int k, void **value, int *flag, char *why) {
  if (!kv_check(R, kind, k, why)) return MPI_ERR_KEYVAL;
  attr *a = attr_find(R, kind, h, k);
  *flag = a != NULL;
  if (a) *value = a->value;
  return MPI_SUCCESS;
}

int attr_delete(st_rank *R, int kind, int h, int k, char *why) {
  if (!kv_check(R, kind, k, why)) return MPI_ERR_KEYVAL;
  attr *a = attr_find(R, kind, h, k);
  if (!a) return MPI_SUCCESS;
  keyval *v = kv_get(R, k);
  v->refs++;   /* alive through the callback, whatever it frees */
  int rc = call_delete(R, h, k, a->value, why);
  if (!rc) attr_remove(R, kind, h, k);
  kv_drop(R, k);
  return rc;
}

int attr_delete_all(st_rank *R, int kind, int h, char *why) {
  object *o;
  while ((o = obj_get(R, kind, h))) {
    attr *last = o->first;
    while (last->next) last = last->next;
    int k = last->keyval;
    kv_get(R, k)->refs++;
    int rc = call_delete(R, h, k, last->value, why);
    if (!rc) attr_remove(R, kind, h, k);
    kv_drop(R, k);
    if (rc) return rc;
  }
  return MPI_SUCCESS;
}

int attr_copy(st_rank *R, int kind, int old, int h, char *why) {
  object *o = obj_get(R, kind, old);
  if (!o) return MPI_SUCCESS;
  /* A snapshot: the keyvals held while their callbacks run. */
  int n = 0;
  for (attr *a = o->first; a; a = a->next) n++;
  attr *snap = xmallocarray((size_t)n, sizeof *snap);
  n = 0;
  for (attr *a = o->first; a; a = a->next) {
    snap[n++] = *a;
    kv_get(R, a->keyval)->refs++;
  }
  int rc = MPI_SUCCESS;
  for (int i = 0; i < n && !rc; i++) {
    keyval *v = kv_get(R, snap[i].keyval);
    if (!v->copy) continue;
    void *out = NULL;
    int flag = 0, r = v->copy(old, snap[i].keyval, v->extra, snap[i].value, &out, &flag);
    if (r != MPI_SUCCESS)
      rc = failed(R, r, "copy", snap[i].keyval, why);
    else if (flag)
      attr_add(R, kind, h, snap[i].keyval, out);
  }
  for (int i = 0; i < n; i++) kv_drop(R, snap[i].keyval);
  free(snap);
  if (rc) {
    char ignored[128];
    while (attr_delete_all(R, kind, h, ignored)) {
      /* a delete that fails: its attribute goes without it */
      object *p = obj_get(R, kind, h);
      attr *last = p->first;
      while (last->next) last = last->next;
      attr_remove(R, kind, h, last->keyval);
    }
  }
  return rc;
}
