/* info.c -- info objects, MPI_INFO_ENV, and communicators' hints (info.h). */
#include "mpi/info.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/comm.h"
#include "mpi/err.h"
#include "util/xmem.h"

typedef struct entry entry;
struct entry {
  entry *next;
  char *key, *value;
};

typedef struct {
  int live;
  int n;
  entry *first;
} info;

struct info_table {
  info env;      /* MPI_INFO_ENV */
  info **t;      /* created ones by slot */
  int nt;
};

enum { ENV_SLOT = 1 };   /* MPI_INFO_ENV's index */

static struct info_table *infos_of(st_rank *R) {
  if (!R->infos) R->infos = xcalloc(1, sizeof *R->infos);
  return R->infos;
}

static void clear(info *o) {
  for (entry *e = o->first, *next; e; e = next) {
    next = e->next;
    free(e->key);
    free(e->value);
    free(e);
  }
  o->first = NULL;
  o->n = 0;
}

void info_release_all(st_rank *R) {
  struct info_table *I = R->infos;
  if (!I) return;
  clear(&I->env);
  for (int i = 0; i < I->nt; i++)
    if (I->t[i]) {
      clear(I->t[i]);
      free(I->t[i]);
    }
  free(I->t);
  free(I);
  R->infos = NULL;
}

static char *dupstr(const char *s) {
  size_t n = strlen(s);
  char *d = xmalloc(n + 1);
  memcpy(d, s, n + 1);
  return d;
}

static entry *find(const info *o, const char *key) {
  for (entry *e = o->first; e; e = e->next)
    if (!strcmp(e->key, key)) return e;
  return NULL;
}

/* Set key to value: replaced in place, or a new last entry. */
static void put(info *o, const char *key, const char *value) {
  entry *e = find(o, key);
  if (e) {
    free(e->value);
    e->value = dupstr(value);
    return;
  }
  entry **at = &o->first;
  while (*at) at = &(*at)->next;
  *at = xcalloc(1, sizeof **at);
  (*at)->key = dupstr(key);
  (*at)->value = dupstr(value);
  o->n++;
}

/* ==== MPI_INFO_ENV ======================================================== */

static void env_make(st_rank *R, info *env) {
  char b[64];
  if (R->argc > 0 && R->argv[0]) {
    put(env, "command", R->argv[0]);
    size_t len = 1;
    for (int i = 1; i < R->argc; i++) len += strlen(R->argv[i]) + 1;
    char *all = xcalloc(len, 1);
    for (int i = 1; i < R->argc; i++) {
      if (i > 1) strcat(all, " ");
      strcat(all, R->argv[i]);
    }
    if (*all && strlen(all) <= MPI_MAX_INFO_VAL) put(env, "argv", all);
    free(all);
  }
  snprintf(b, sizeof b, "%d", R->wsize);
  put(env, "maxprocs", b);
  static const char *const level[] = {"MPI_THREAD_SINGLE", "MPI_THREAD_FUNNELED", "MPI_THREAD_SERIALIZED",
                                      "MPI_THREAD_MULTIPLE"};
  put(env, "thread_level", level[R->thread_level]);
  env->live = 1;
}

/* ==== handles ============================================================= */

static info *info_get(st_rank *R, MPI_Info h) {
  struct info_table *I = infos_of(R);
  if (h == MPI_INFO_ENV) {
    if (!I->env.live) env_make(R, &I->env);
    return &I->env;
  }
  unsigned slot = (unsigned)h - (unsigned)(HK_INFO << H_KIND_SHIFT | H_CREATED);
  return slot < (unsigned)I->nt && I->t[slot] ? I->t[slot] : NULL;
}

/* The info object h names for call fn (MPI_INFO_ENV only where env_ok),
 * or NULL with MPI_ERR_INFO raised in *rc. */
static info *check(st_rank *R, const char *fn, MPI_Info h, int env_ok, int *rc) {
  info *o = info_get(R, h);
  *rc = MPI_SUCCESS;
  if (o && (env_ok || h != MPI_INFO_ENV)) return o;
  *rc = err_raise(R, NULL, MPI_ERR_INFO, fn, "%s",
                  h == MPI_INFO_NULL  ? "MPI_INFO_NULL"
                  : h == MPI_INFO_ENV ? "MPI_INFO_ENV cannot be changed or freed"
                                      : "invalid info object (freed, or not an info object)");
  return NULL;
}

static MPI_Info add(st_rank *R, info *o) {
  struct info_table *I = infos_of(R);
  int slot = 0;
  while (slot < I->nt && I->t[slot]) slot++;
  if (slot == I->nt) I->t = xreallocarray(I->t, (size_t)++I->nt, sizeof *I->t);
  I->t[slot] = o;
  o->live = 1;
  return (MPI_Info)(HK_INFO << H_KIND_SHIFT | H_CREATED | slot);
}

static MPI_Info copy(st_rank *R, const info *from) {
  info *o = xcalloc(1, sizeof *o);
  for (entry *e = from->first; e; e = e->next) put(o, e->key, e->value);
  return add(R, o);
}

/* A key's checks: MPI_SUCCESS or MPI_ERR_INFO_KEY raised. */
static int key_ok(st_rank *R, const char *fn, const char *key) {
  if (!key) return err_raise(R, NULL, MPI_ERR_INFO_KEY, fn, "NULL key");
  size_t n = strlen(key);
  if (n == 0) return err_raise(R, NULL, MPI_ERR_INFO_KEY, fn, "empty key");
  if (n > MPI_MAX_INFO_KEY)
    return err_raise(R, NULL, MPI_ERR_INFO_KEY, fn, "a key of %zu characters (at most MPI_MAX_INFO_KEY = %d)", n,
                     MPI_MAX_INFO_KEY);
  return MPI_SUCCESS;
}

/* ==== the calls =========================================================== */

int PMPI_Info_create(MPI_Info *h) {
  static const char fn[] = "MPI_Info_create";
  st_rank *R = st_need(fn);
  if (!h) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL info argument");
  *h = add(R, xcalloc(1, sizeof(info)));
  return MPI_SUCCESS;
}

int PMPI_Info_dup(MPI_Info h, MPI_Info *newinfo) {
  static const char fn[] = "MPI_Info_dup";
  st_rank *R = st_need(fn);
  int rc;
  info *o = check(R, fn, h, 1, &rc);
  if (!o) return rc;
  if (!newinfo) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL newinfo argument");
  *newinfo = copy(R, o);
  return MPI_SUCCESS;
}

int PMPI_Info_free(MPI_Info *h) {
  static const char fn[] = "MPI_Info_free";
  st_rank *R = st_need(fn);
  if (!h) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL info argument");
  int rc;
  info *o = check(R, fn, *h, 0, &rc);
  if (!o) return rc;
  clear(o);
  free(o);
  R->infos->t[(unsigned)*h & H_SLOT_MASK] = NULL;
  *h = MPI_INFO_NULL;
  return MPI_SUCCESS;
}

int PMPI_Info_set(MPI_Info h, const char *key, const char *value) {
  static const char fn[] = "MPI_Info_set";
  st_rank *R = st_need(fn);
  int rc;
  info *o = check(R, fn, h, 0, &rc);
  if (!o || (rc = key_ok(R, fn, key))) return rc;
  if (!value) return err_raise(R, NULL, MPI_ERR_INFO_VALUE, fn, "NULL value");
  size_t n = strlen(value);
  if (n == 0) return err_raise(R, NULL, MPI_ERR_INFO_VALUE, fn, "empty value");
  if (n > MPI_MAX_INFO_VAL)
    return err_raise(R, NULL, MPI_ERR_INFO_VALUE, fn, "a value of %zu characters (at most MPI_MAX_INFO_VAL = %d)",
                     n, MPI_MAX_INFO_VAL);
  put(o, key, value);
  return MPI_SUCCESS;
}

int PMPI_Info_delete(MPI_Info h, const char *key) {
  static const char fn[] = "MPI_Info_delete";
  st_rank *R = st_need(fn);
  int rc;
  info *o = check(R, fn, h, 0, &rc);
  if (!o || (rc = key_ok(R, fn, key))) return rc;
  for (entry **at = &o->first; *at; at = &(*at)->next) {
    if (strcmp((*at)->key, key)) continue;
    entry *e = *at;
    *at = e->next;
    free(e->key);
    free(e->value);
    free(e);
    o->n--;
    return MPI_SUCCESS;
  }
  return err_raise(R, NULL, MPI_ERR_INFO_NOKEY, fn, "no key \"%s\"", key);
}

/* MPI 3.1 section 9: value gets at most valuelen characters and a NUL. */
int PMPI_Info_get(MPI_Info h, const char *key, int valuelen, char *value, int *flag) {
  static const char fn[] = "MPI_Info_get";
  st_rank *R = st_need(fn);
  int rc;
  info *o = check(R, fn, h, 1, &rc);
  if (!o || (rc = key_ok(R, fn, key))) return rc;
  if (valuelen < 0) return err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid valuelen %d", valuelen);
  if (!value || !flag) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL %s argument", flag ? "value" : "flag");
  entry *e = find(o, key);
  *flag = e != NULL;
  if (e) {
    size_t n = strlen(e->value);
    if (n > (size_t)valuelen) n = (size_t)valuelen;
    memcpy(value, e->value, n);
    value[n] = 0;
  }
  return MPI_SUCCESS;
}

int PMPI_Info_get_valuelen(MPI_Info h, const char *key, int *valuelen, int *flag) {
  static const char fn[] = "MPI_Info_get_valuelen";
  st_rank *R = st_need(fn);
  int rc;
  info *o = check(R, fn, h, 1, &rc);
  if (!o || (rc = key_ok(R, fn, key))) return rc;
  if (!valuelen || !flag) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL argument");
  entry *e = find(o, key);
  *flag = e != NULL;
  if (e) *valuelen = (int)strlen(e->value);
  return MPI_SUCCESS;
}

int PMPI_Info_get_nkeys(MPI_Info h, int *nkeys) {
  static const char fn[] = "MPI_Info_get_nkeys";
  st_rank *R = st_need(fn);
  int rc;
  info *o = check(R, fn, h, 1, &rc);
  if (!o) return rc;
  if (!nkeys) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL nkeys argument");
  *nkeys = o->n;
  return MPI_SUCCESS;
}

int PMPI_Info_get_nthkey(MPI_Info h, int n, char *key) {
  static const char fn[] = "MPI_Info_get_nthkey";
  st_rank *R = st_need(fn);
  int rc;
  info *o = check(R, fn, h, 1, &rc);
  if (!o) return rc;
  if (n < 0 || n >= o->n)
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid n %d (the info object has %d key%s)", n, o->n,
                     o->n == 1 ? "" : "s");
  if (!key) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL key argument");
  entry *e = o->first;
  while (n--) e = e->next;
  memcpy(key, e->key, strlen(e->key) + 1);
  return MPI_SUCCESS;
}

/* ==== communicators' hints ================================================ */

static const char *const hint_key[] = {"mpi_assert_no_any_tag", "mpi_assert_no_any_source",
                                       "mpi_assert_exact_length", "mpi_assert_allow_overtaking"};
enum { NHINTS = sizeof hint_key / sizeof hint_key[0] };

int info_hints(st_rank *R, const st_comm *c, const char *fn, MPI_Info h, unsigned *hints) {
  if (h == MPI_INFO_NULL) return MPI_SUCCESS;
  info *o = info_get(R, h);
  if (!o) return err_raise(R, c, MPI_ERR_INFO, fn, "invalid info object (freed, or not an info object)");
  for (int i = 0; i < NHINTS; i++) {
    entry *e = find(o, hint_key[i]);
    if (!e || (strcmp(e->value, "true") && strcmp(e->value, "false"))) continue;
    *hints |= 1u << i;
    if (!strcmp(e->value, "true"))
      *hints |= 1u << (8 + i);
    else
      *hints &= ~(1u << (8 + i));
  }
  return MPI_SUCCESS;
}

int info_value(st_rank *R, MPI_Info h, const char *key, char *value, size_t len) {
  if (h == MPI_INFO_NULL) return 0;
  info *o = info_get(R, h);
  if (!o) return -1;
  entry *e = find(o, key);
  if (!e) return 0;
  snprintf(value, len, "%s", e->value);
  return 1;
}

int PMPI_Comm_set_info(MPI_Comm comm, MPI_Info h) {
  static const char fn[] = "MPI_Comm_set_info";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (h == MPI_INFO_NULL) return err_raise(R, c, MPI_ERR_INFO, fn, "MPI_INFO_NULL");
  return info_hints(R, c, fn, h, &c->hints);
}

int PMPI_Comm_get_info(MPI_Comm comm, MPI_Info *info_used) {
  static const char fn[] = "MPI_Comm_get_info";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!info_used) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL info_used argument");
  info *o = xcalloc(1, sizeof *o);
  for (int i = 0; i < NHINTS; i++)
    if (c->hints >> i & 1) put(o, hint_key[i], c->hints >> (8 + i) & 1 ? "true" : "false");
  *info_used = add(R, o);
  return MPI_SUCCESS;
}

/* MPI_Comm_dup, then the hints of info in place of comm's. */
int PMPI_Comm_dup_with_info(MPI_Comm comm, MPI_Info h, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_dup_with_info";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  unsigned hints = 0;
  if ((rc = info_hints(R, c, fn, h, &hints))) return rc;
  if ((rc = comm_dup(R, comm, fn, newcomm))) return rc;
  st_comm_get(R, *newcomm)->hints = hints;
  return MPI_SUCCESS;
}
