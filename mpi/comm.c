/* comm.c -- communicators: rank and size, Comm_dup (and idup, and
 * dup_with_info's dup), Comm_split, Comm_split_type, Comm_create,
 * Comm_create_group, Comm_free, Comm_disconnect, Comm_compare, Comm_group,
 * names; the context agreement every constructor shares (comm.h).
 *
 * Comm_split first gathers every rank's (color, key) at the parent's rank 0
 * (one message each) and sends the table down a binomial tree; then the
 * ranks agree on one context pair, which serves every color (their
 * communicators share no rank).  On an intercommunicator, dup, split and
 * create are intercomm.c's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/attr.h"
#include "mpi/coll.h"
#include "mpi/comm.h"
#include "mpi/engine.h"
#include "mpi/errh.h"
#include "mpi/group.h"
#include "mpi/info.h"
#include "mpi/err.h"
#include "mpi/label.h"
#include "mpi/pt2pt.h"
#include "mpi/topo.h"
#include "util/xmem.h"

/* ==== rank and size ======================================================= */

int PMPI_Comm_rank(MPI_Comm comm, int *rank) {
  static const char fn[] = "MPI_Comm_rank";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!rank) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL rank argument");
  *rank = c->rank;
  return MPI_SUCCESS;
}

int PMPI_Comm_size(MPI_Comm comm, int *size) {
  static const char fn[] = "MPI_Comm_size";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!size) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL size argument");
  *size = tsm_comm_lsize(c);
  return MPI_SUCCESS;
}

/* ==== messages among the ranks that make a communicator =================== */

void *tsm_scratch(const char *fn, size_t n) {
  tsmpi_cg g = {.fn = fn};
  return tsmpi_cg_alloc(&g, n);
}

void tsm_scratch_free(void *p) { tsmpi_cg_free(p); }

void tsm_xsend(tsm *R, int ctx, int w, int tag, const void *buf, size_t len) {
  tsm_req q = {.slot = -1, .kind = RQ_SEND, .mode = SM_STANDARD, .wpeer = w, .ctx = ctx, .tag = tag};
  eng_send(R, &q, buf, len);
}

void tsm_xrecv(tsm *R, int ctx, int w, int tag, void *buf, size_t len) {
  tsm_req q = {.slot = -1, .kind = RQ_RECV, .wpeer = w, .ctx = ctx, .tag = tag, .cap = len,
               .contig = buf, .g = R->world.g, .count = (int)len, .dt = MPI_BYTE};
  eng_recv(R, &q);
  if (q.st.MPI_ERROR || q.msglen != len) {
    fprintf(stderr, "tilesim MPI: internal error: rank %d: a %zu-byte message from rank %d where %zu were due\n",
            R->wrank, q.msglen, w, len);
    abort();
  }
}

void tsm_xswap(tsm *R, int ctx, int w, int tag, const void *out, size_t outlen, void **in, size_t *inlen) {
  long n = (long)outlen, m = 0;
  tsm_xsend(R, ctx, w, tag, &n, sizeof n);
  tsm_xsend(R, ctx, w, tag, out, outlen);
  tsm_xrecv(R, ctx, w, tag, &m, sizeof m);
  *in = tsm_scratch("an MPI communicator constructor", (size_t)m);
  tsm_xrecv(R, ctx, w, tag, *in, (size_t)m);
  *inlen = (size_t)m;
}

void tsm_tree_bcast(tsm *R, int ctx, const tsm_ranks *g, int me, int root, int tag, void *buf, size_t len) {
  int n = g->n, rel = (me - root + n) % n, mask = 1;
  while (mask < n) {
    if (rel & mask) {
      tsm_xrecv(R, ctx, tsm_member(g, (rel - mask + root) % n), tag, buf, len);
      break;
    }
    mask <<= 1;
  }
  for (mask >>= 1; mask > 0; mask >>= 1)
    if (rel + mask < n) tsm_xsend(R, ctx, tsm_member(g, (rel + mask + root) % n), tag, buf, len);
}

void tsm_tree_or(tsm *R, int ctx, const tsm_ranks *g, int me, int root, int tag, unsigned char *used) {
  unsigned char other[PAIR_BYTES];
  int n = g->n, rel = (me - root + n) % n;
  for (int mask = 1; mask < n; mask <<= 1) {
    if (rel & mask) {
      tsm_xsend(R, ctx, tsm_member(g, (rel - mask + root) % n), tag, used, PAIR_BYTES);
      break;
    }
    if (rel + mask < n) {
      tsm_xrecv(R, ctx, tsm_member(g, (rel + mask + root) % n), tag, other, PAIR_BYTES);
      for (int i = 0; i < PAIR_BYTES; i++) used[i] |= other[i];
    }
  }
}

int tsm_pair_lowest(const unsigned char *used, int except) {
  for (int p = 0; p < CTX_PAIRS; p++)
    if (p != except && !(used[p / 8] >> (p % 8) & 1)) return p;
  return -1;
}

void tsm_pair_take(tsm *R, int p) { R->pairs[p / 8] |= (unsigned char)(1u << (p % 8)); }
void tsm_pair_give(tsm *R, int p) { R->pairs[p / 8] &= (unsigned char)~(1u << (p % 8)); }

int tsm_agree_pair(tsm *R, int ctx, const tsm_ranks *g, int me, int tag) {
  unsigned char used[PAIR_BYTES];
  memcpy(used, R->pairs, PAIR_BYTES);
  tsm_tree_or(R, ctx, g, me, 0, tag, used);
  int pair = me == 0 ? tsm_pair_lowest(used, -1) : -1;
  tsm_tree_bcast(R, ctx, g, me, 0, tag + 1, &pair, sizeof pair);
  if (pair >= 0) tsm_pair_take(R, pair);
  return pair;
}

MPI_Comm tsm_comm_add(tsm *R, tsm_ranks *g, int pair, int rank, MPI_Errhandler eh, unsigned hints) {
  int slot = 0;
  while (slot < R->ncomms && R->comms[slot]) slot++;
  if (slot == R->ncomms) {
    R->comms = xreallocarray(R->comms, (size_t)R->ncomms + 1, sizeof *R->comms);
    R->ncomms++;
  }
  tsm_comm *c = xcalloc(1, sizeof *c);
  c->live = 1;
  c->pair = pair;
  c->rank = rank;
  c->size = g->n;
  c->g = g;
  c->eh = eh;
  tsm_errh_hold(R, eh);
  c->hints = hints;
  c->h = (MPI_Comm)(HK_COMM << H_KIND_SHIFT | H_CREATED | slot);
  c->local = MPI_COMM_NULL;
  R->comms[slot] = c;
  return c->h;
}

int tsm_no_pair(tsm *R, const tsm_comm *c, const char *fn) {
  return tsm_raise(R, c, MPI_ERR_OTHER, fn,
                   "no context left: a rank of it is in %d communicators at once (tilesim's limit; "
                   "free some with MPI_Comm_free)",
                   CTX_PAIRS);
}

void tsm_comm_end(tsm *R, MPI_Comm *comm) {
  tsm_comm *c = tsm_comm_get(R, *comm);
  if (c->inter) {
    tsm_comm_end(R, &c->local);
    tsm_ranks_drop(c->lg);
  }
  tsm_pair_give(R, c->pair);
  tsm_ranks_drop(c->g);
  tsmpi_topo_unref(c->topo);
  tsm_errh_drop(R, c->eh);
  R->comms[(unsigned)*comm & H_SLOT_MASK] = NULL;
  free(c);
  *comm = MPI_COMM_NULL;
}

/* ==== constructors ======================================================== */

/* The duplicate's attributes, copied from comm's by their callbacks: a
 * callback that fails undoes the duplicate (MPI_COMM_NULL), and its error
 * is raised. */
static int dup_attrs(tsm *R, const tsm_comm *c, MPI_Comm comm, const char *fn, MPI_Comm *newcomm) {
  char why[128];
  int rc = tsm_attr_copy(R, TSM_AK_COMM, comm, *newcomm, why);
  if (!rc) return MPI_SUCCESS;
  tsm_comm_end(R, newcomm);
  return tsm_raise(R, c, rc, fn, "%s", why);
}

/* MPI_Comm_dup's work, for dup, idup and dup_with_info. */
int tsm_comm_dup(tsm *R, MPI_Comm comm, const char *fn, MPI_Comm *newcomm) {
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!newcomm) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  *newcomm = MPI_COMM_NULL;
  if (c->inter) {
    if ((rc = tsm_inter_dup(R, c, fn, newcomm))) return rc;
  } else {
    tsm_label l = {.fn = fn, .what = L_COMM, .pair = c->pair};
    tsm_label_set(R, &l);
    int pair = tsm_agree_pair(R, 2 * c->pair + 1, c->g, c->rank, TAG_CTXID);
    tsm_unlabel(R);
    if (pair < 0) return tsm_no_pair(R, c, fn);
    c->g->refs++;
    *newcomm = tsm_comm_add(R, c->g, pair, c->rank, c->eh, c->hints);
    if (c->topo) {   /* MPI 3.1 section 7.1: a duplicate keeps the topology */
      tsmpi_topo_ref(c->topo);
      tsm_comm_get(R, *newcomm)->topo = c->topo;
    }
  }
  return dup_attrs(R, c, comm, fn, newcomm);
}

int PMPI_Comm_dup(MPI_Comm comm, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_dup";
  return tsm_comm_dup(tsm_need(fn), comm, fn, newcomm);
}

/* MPI_Comm_idup completes at once: it is MPI_Comm_dup (the ranks agree on
 * the context then), with a request that is done already. */
int PMPI_Comm_idup(MPI_Comm comm, MPI_Comm *newcomm, MPI_Request *request) {
  static const char fn[] = "MPI_Comm_idup";
  tsm *R = tsm_need(fn);
  if (!request) {
    tsm_comm *c;
    int rc = tsm_check_comm(R, comm, fn, &c);
    return rc ? rc : tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL request argument");
  }
  int rc = tsm_comm_dup(R, comm, fn, newcomm);
  if (rc) return rc;
  tsm_req *q = tsm_req_new(R);
  q->kind = RQ_SEND;
  q->state = RS_DONE;
  q->fn = fn;
  q->comm = comm;
  q->peer = MPI_PROC_NULL;
  tsm_status_empty(&q->st);
  *request = tsm_req_handle(q);
  return MPI_SUCCESS;
}

typedef struct {
  int color, key, rank;
} split_entry;

static int cmp_split(const void *a, const void *b) {
  const split_entry *x = a, *y = b;
  if (x->key != y->key) return (x->key > y->key) - (x->key < y->key);
  return (x->rank > y->rank) - (x->rank < y->rank);
}

/* The world ranks of the ranks of `table` ((color, key) by rank of g, n
 * ranks) with color, ordered by key then rank: their number, and the
 * calling rank's place among them in *me (-1 if not there: mine < 0). */
int *tsm_split_members(const int *table, int n, const tsm_ranks *g, int color, int mine, int *m, int *me) {
  split_entry *e = xmallocarray((size_t)n + 1, sizeof *e);
  *m = 0;
  for (int r = 0; r < n; r++)
    if (table[2 * r] == color) e[(*m)++] = (split_entry){color, table[2 * r + 1], r};
  qsort(e, (size_t)*m, sizeof *e, cmp_split);
  int *world = xmallocarray((size_t)*m + 1, sizeof *world);
  *me = -1;
  for (int i = 0; i < *m; i++) {
    world[i] = tsm_member(g, e[i].rank);
    if (e[i].rank == mine) *me = i;
  }
  free(e);
  return world;
}

int PMPI_Comm_split(MPI_Comm comm, int color, int key, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_split";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!newcomm) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  if (color < 0 && color != MPI_UNDEFINED)
    return tsm_raise(R, c, MPI_ERR_ARG, fn, "invalid color %d (>= 0, or MPI_UNDEFINED)", color);
  if (c->inter) return tsm_inter_split(R, c, fn, color, key, newcomm);
  tsm_label l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  tsm_label_set(R, &l);
  int n = c->size, ctx = 2 * c->pair + 1;
  int *table = tsm_scratch(fn, (size_t)n * 2 * sizeof *table);   /* (color, key) by rank */
  if (c->rank == 0) {
    table[0] = color;
    table[1] = key;
    for (int r = 1; r < n; r++) tsm_xrecv(R, ctx, tsm_member(c->g, r), TAG_SPLIT, &table[2 * r], 2 * sizeof *table);
  } else {
    int mine[2] = {color, key};
    tsm_xsend(R, ctx, tsm_member(c->g, 0), TAG_SPLIT, mine, sizeof mine);
  }
  tsm_tree_bcast(R, ctx, c->g, c->rank, 0, TAG_SPLIT_BCAST, table, (size_t)n * 2 * sizeof *table);
  int pair = tsm_agree_pair(R, ctx, c->g, c->rank, TAG_CTXID);
  tsm_unlabel(R);
  if (pair < 0) {
    tsm_scratch_free(table);
    return tsm_no_pair(R, c, fn);
  }
  if (color == MPI_UNDEFINED) {
    /* One pair serves every color's communicator (they share no rank);
     * this rank is in none of them. */
    tsm_pair_give(R, pair);
    tsm_scratch_free(table);
    *newcomm = MPI_COMM_NULL;
    return MPI_SUCCESS;
  }
  int m, me;
  int *world = tsm_split_members(table, n, c->g, color, c->rank, &m, &me);
  *newcomm = tsm_comm_add(R, tsm_ranks_new(m, world), pair, me, c->eh, 0);
  free(world);
  tsm_scratch_free(table);
  return MPI_SUCCESS;
}

/* MPI_COMM_TYPE_SHARED: a node of the simulated machine is one processor,
 * whose memory no other rank shares, so each rank's communicator is itself
 * alone.  Its context needs no agreement (it is free on the only rank that
 * uses it): the call sends nothing and takes no simulated time. */
int PMPI_Comm_split_type(MPI_Comm comm, int split_type, int key, MPI_Info info, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_split_type";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  (void)key;
  if (!newcomm) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  if (c->inter) return tsm_raise(R, c, MPI_ERR_COMM, fn, "an intercommunicator (MPI_Comm_split_type splits intracommunicators)");
  if (split_type != MPI_COMM_TYPE_SHARED && split_type != MPI_UNDEFINED)
    return tsm_raise(R, c, MPI_ERR_ARG, fn, "invalid split_type %d (MPI_COMM_TYPE_SHARED or MPI_UNDEFINED)",
                     split_type);
  unsigned hints;
  if ((rc = tsm_info_hints(R, c, fn, info, &hints))) return rc;
  *newcomm = MPI_COMM_NULL;
  if (split_type == MPI_UNDEFINED) return MPI_SUCCESS;
  int pair = tsm_pair_lowest(R->pairs, -1);
  if (pair < 0) return tsm_no_pair(R, c, fn);
  tsm_pair_take(R, pair);
  *newcomm = tsm_comm_add(R, tsm_ranks_new(1, &R->wrank), pair, 0, c->eh, hints);
  return MPI_SUCCESS;
}

/* Is every rank of g in c (its local group)? */
static int subset(const tsm_ranks *g, const tsm_comm *c) {
  for (int i = 0; i < g->n; i++)
    if (tsm_ranks_find(tsm_comm_lgroup(c), tsm_member(g, i)) < 0) return 0;
  return 1;
}

static int group_arg(tsm *R, const tsm_comm *c, const char *fn, MPI_Group group, tsm_ranks **g) {
  *g = tsm_group_get(R, group);
  if (!*g) return tsm_raise(R, c, MPI_ERR_GROUP, fn, "invalid group 0x%x", (unsigned)group);
  if (!subset(*g, c))
    return tsm_raise(R, c, MPI_ERR_GROUP, fn, "the group has ranks that are not in the communicator%s",
                     c->inter ? "'s local group" : "");
  return MPI_SUCCESS;
}

int PMPI_Comm_create(MPI_Comm comm, MPI_Group group, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_create";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!newcomm) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  tsm_ranks *g;
  if ((rc = group_arg(R, c, fn, group, &g))) return rc;
  if (c->inter) return tsm_inter_create(R, c, fn, g, newcomm);
  tsm_label l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  tsm_label_set(R, &l);
  int pair = tsm_agree_pair(R, 2 * c->pair + 1, c->g, c->rank, TAG_CTXID);
  tsm_unlabel(R);
  if (pair < 0) return tsm_no_pair(R, c, fn);
  int me = tsm_ranks_find(g, R->wrank);
  if (me < 0) {
    tsm_pair_give(R, pair);
    *newcomm = MPI_COMM_NULL;
    return MPI_SUCCESS;
  }
  g->refs++;
  *newcomm = tsm_comm_add(R, g, pair, me, c->eh, 0);
  return MPI_SUCCESS;
}

int PMPI_Comm_create_group(MPI_Comm comm, MPI_Group group, int tag, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_create_group";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (c->inter) return tsm_raise(R, c, MPI_ERR_COMM, fn, "an intercommunicator (MPI_Comm_create_group needs an intracommunicator)");
  if ((rc = tsm_check_tag(R, c, fn, tag, 0))) return rc;
  if (!newcomm) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  tsm_ranks *g;
  if ((rc = group_arg(R, c, fn, group, &g))) return rc;
  int me = tsm_ranks_find(g, R->wrank);
  if (me < 0) {
    *newcomm = MPI_COMM_NULL;   /* MPI 3.1 section 6.4.2: a rank outside the group gets none */
    return MPI_SUCCESS;
  }
  /* Only the group's ranks take part: they agree among themselves, on the
   * parent's collective context, with tags of their own by the program's
   * tag (state.h: TAG_GROUP). */
  tsm_label l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  tsm_label_set(R, &l);
  int pair = tsm_agree_pair(R, 2 * c->pair + 1, g, me, TAG_GROUP + 2 * (tag % TAG_GROUP_N));
  tsm_unlabel(R);
  if (pair < 0) return tsm_no_pair(R, c, fn);
  g->refs++;
  *newcomm = tsm_comm_add(R, g, pair, me, c->eh, 0);
  return MPI_SUCCESS;
}

/* Free: the attributes' delete callbacks first, on a communicator still
 * valid (MPI 3.1 section 6.7.2); one that fails leaves it as it is. */
static int comm_free(const char *fn, MPI_Comm *comm) {
  tsm *R = tsm_need(fn);
  if (!comm) return tsm_raise(R, NULL, MPI_ERR_ARG, fn, "NULL comm argument");
  tsm_comm *c;
  int rc = tsm_check_comm(R, *comm, fn, &c);
  if (rc) return rc;
  if (c == &R->world || c == &R->selfc)
    return tsm_raise(R, c, MPI_ERR_COMM, fn, "%s cannot be freed", c == &R->world ? "MPI_COMM_WORLD" : "MPI_COMM_SELF");
  char why[128];
  if ((rc = tsm_attr_delete_all(R, TSM_AK_COMM, *comm, why))) return tsm_raise(R, c, rc, fn, "%s", why);
  if (c->holds) {   /* its nonblocking collectives go on; it ends with the last (core.h) */
    c->freed = 1;
    *comm = MPI_COMM_NULL;
    return MPI_SUCCESS;
  }
  tsm_comm_end(R, comm);
  return MPI_SUCCESS;
}

int PMPI_Comm_free(MPI_Comm *comm) { return comm_free("MPI_Comm_free", comm); }

/* Collective: it waits, as a barrier, for every rank of the communicator
 * (whose messages have all left by then: sends are eager), then frees. */
int PMPI_Comm_disconnect(MPI_Comm *comm) {
  static const char fn[] = "MPI_Comm_disconnect";
  tsm *R = tsm_need(fn);
  if (!comm) return tsm_raise(R, NULL, MPI_ERR_ARG, fn, "NULL comm argument");
  tsm_comm *c;
  int rc = tsm_check_comm(R, *comm, fn, &c);
  if (rc) return rc;
  if (c == &R->world || c == &R->selfc)
    return tsm_raise(R, c, MPI_ERR_COMM, fn, "%s cannot be disconnected", c == &R->world ? "MPI_COMM_WORLD" : "MPI_COMM_SELF");
  if ((rc = PMPI_Barrier(*comm))) return rc;
  return comm_free(fn, comm);
}

/* ==== comparing, groups, names ============================================ */

/* MPI 3.1 section 6.4.1; intercommunicators compare both groups. */
int PMPI_Comm_compare(MPI_Comm comm1, MPI_Comm comm2, int *result) {
  static const char fn[] = "MPI_Comm_compare";
  tsm *R = tsm_need(fn);
  tsm_comm *a, *b;
  int rc = tsm_check_comm(R, comm1, fn, &a);
  if (rc || (rc = tsm_check_comm(R, comm2, fn, &b))) return rc;
  if (!result) return tsm_raise(R, a, MPI_ERR_ARG, fn, "NULL result argument");
  static const int verdict[3] = {MPI_UNEQUAL, MPI_SIMILAR, MPI_CONGRUENT};
  int same = a->inter != b->inter ? 0 : tsm_ranks_same(a->g, b->g);
  if (a->inter && b->inter) {
    int local = tsm_ranks_same(a->lg, b->lg);
    same = local < same ? local : same;
  }
  *result = a == b ? MPI_IDENT : verdict[same];
  return MPI_SUCCESS;
}

int PMPI_Comm_group(MPI_Comm comm, MPI_Group *group) {
  static const char fn[] = "MPI_Comm_group";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!group) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL group argument");
  tsm_ranks *g = tsm_comm_lgroup(c);
  g->refs++;
  *group = tsm_group_add(R, g);
  return MPI_SUCCESS;
}

int PMPI_Comm_set_name(MPI_Comm comm, const char *comm_name) {
  static const char fn[] = "MPI_Comm_set_name";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!comm_name) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL name");
  snprintf(c->name, sizeof c->name, "%s", comm_name);
  return MPI_SUCCESS;
}

int PMPI_Comm_get_name(MPI_Comm comm, char *comm_name, int *resultlen) {
  static const char fn[] = "MPI_Comm_get_name";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!comm_name || !resultlen) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL argument");
  size_t n = strlen(c->name);
  memcpy(comm_name, c->name, n + 1);
  *resultlen = (int)n;
  return MPI_SUCCESS;
}
