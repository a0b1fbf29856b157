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
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!rank) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL rank argument");
  *rank = c->rank;
  return MPI_SUCCESS;
}

int PMPI_Comm_size(MPI_Comm comm, int *size) {
  static const char fn[] = "MPI_Comm_size";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!size) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL size argument");
  *size = st_comm_lsize(c);
  return MPI_SUCCESS;
}

/* ==== messages among the ranks that make a communicator =================== */

void *comm_scratch(const char *fn, size_t n) {
  coll_cg g = {.fn = fn};
  return coll_cg_alloc(&g, n);
}

void comm_scratch_free(void *p) { coll_cg_free(p); }

void comm_xsend(st_rank *R, int ctx, int w, int tag, const void *buf, size_t len) {
  st_req q = {.slot = -1, .kind = RQ_SEND, .mode = SM_STANDARD, .wpeer = w, .ctx = ctx, .tag = tag};
  eng_send(R, &q, buf, len);
}

void comm_xrecv(st_rank *R, int ctx, int w, int tag, void *buf, size_t len) {
  st_req q = {.slot = -1, .kind = RQ_RECV, .wpeer = w, .ctx = ctx, .tag = tag, .cap = len,
               .contig = buf, .g = R->world.g, .count = (int)len, .dt = MPI_BYTE};
  eng_recv(R, &q);
  if (q.st.MPI_ERROR || q.msglen != len) {
    fprintf(stderr, "tilesim MPI: internal error: rank %d: a %zu-byte message from rank %d where %zu were due\n",
            R->wrank, q.msglen, w, len);
    abort();
  }
}

void comm_xswap(st_rank *R, int ctx, int w, int tag, const void *out, size_t outlen, void **in, size_t *inlen) {
  long n = (long)outlen, m = 0;
  comm_xsend(R, ctx, w, tag, &n, sizeof n);
  comm_xsend(R, ctx, w, tag, out, outlen);
  comm_xrecv(R, ctx, w, tag, &m, sizeof m);
  *in = comm_scratch("an MPI communicator constructor", (size_t)m);
  comm_xrecv(R, ctx, w, tag, *in, (size_t)m);
  *inlen = (size_t)m;
}

void comm_tree_bcast(st_rank *R, int ctx, const st_ranks *g, int me, int root, int tag, void *buf, size_t len) {
  int n = g->n, rel = (me - root + n) % n, mask = 1;
  while (mask < n) {
    if (rel & mask) {
      comm_xrecv(R, ctx, comm_member(g, (rel - mask + root) % n), tag, buf, len);
      break;
    }
    mask <<= 1;
  }
  for (mask >>= 1; mask > 0; mask >>= 1)
    if (rel + mask < n) comm_xsend(R, ctx, comm_member(g, (rel + mask + root) % n), tag, buf, len);
}

void comm_tree_or(st_rank *R, int ctx, const st_ranks *g, int me, int root, int tag, unsigned char *used) {
  unsigned char other[PAIR_BYTES];
  int n = g->n, rel = (me - root + n) % n;
  for (int mask = 1; mask < n; mask <<= 1) {
    if (rel & mask) {
      comm_xsend(R, ctx, comm_member(g, (rel - mask + root) % n), tag, used, PAIR_BYTES);
      break;
    }
    if (rel + mask < n) {
      comm_xrecv(R, ctx, comm_member(g, (rel + mask + root) % n), tag, other, PAIR_BYTES);
      for (int i = 0; i < PAIR_BYTES; i++) used[i] |= other[i];
    }
  }
}

int comm_pair_lowest(const unsigned char *used, int except) {
  for (int p = 0; p < CTX_PAIRS; p++)
    if (p != except && !(used[p / 8] >> (p % 8) & 1)) return p;
  return -1;
}

void comm_pair_take(st_rank *R, int p) { R->pairs[p / 8] |= (unsigned char)(1u << (p % 8)); }
void comm_pair_give(st_rank *R, int p) { R->pairs[p / 8] &= (unsigned char)~(1u << (p % 8)); }

int comm_agree_pair(st_rank *R, int ctx, const st_ranks *g, int me, int tag) {
  unsigned char used[PAIR_BYTES];
  memcpy(used, R->pairs, PAIR_BYTES);
  comm_tree_or(R, ctx, g, me, 0, tag, used);
  int pair = me == 0 ? comm_pair_lowest(used, -1) : -1;
  comm_tree_bcast(R, ctx, g, me, 0, tag + 1, &pair, sizeof pair);
  if (pair >= 0) comm_pair_take(R, pair);
  return pair;
}

MPI_Comm comm_add(st_rank *R, st_ranks *g, int pair, int rank, MPI_Errhandler eh, unsigned hints) {
  int slot = 0;
  while (slot < R->ncomms && R->comms[slot]) slot++;
  if (slot == R->ncomms) {
    R->comms = xreallocarray(R->comms, (size_t)R->ncomms + 1, sizeof *R->comms);
    R->ncomms++;
  }
  st_comm *c = xcalloc(1, sizeof *c);
  c->live = 1;
  c->pair = pair;
  c->rank = rank;
  c->size = g->n;
  c->g = g;
  c->eh = eh;
  errh_hold(R, eh);
  c->hints = hints;
  c->h = (MPI_Comm)(HK_COMM << H_KIND_SHIFT | H_CREATED | slot);
  c->local = MPI_COMM_NULL;
  R->comms[slot] = c;
  return c->h;
}

int comm_no_pair(st_rank *R, const st_comm *c, const char *fn) {
  return err_raise(R, c, MPI_ERR_OTHER, fn,
                   "no context left: a rank of it is in %d communicators at once (tilesim's limit; "
                   "free some with MPI_Comm_free)",
                   CTX_PAIRS);
}

void comm_end(st_rank *R, MPI_Comm *comm) {
  st_comm *c = st_comm_get(R, *comm);
  if (c->inter) {
    comm_end(R, &c->local);
    st_ranks_drop(c->lg);
  }
  comm_pair_give(R, c->pair);
  st_ranks_drop(c->g);
  ptopo_unref(c->topo);
  errh_drop(R, c->eh);
  R->comms[(unsigned)*comm & H_SLOT_MASK] = NULL;
  free(c);
  *comm = MPI_COMM_NULL;
}

/* ==== constructors ======================================================== */

/* The duplicate's attributes, copied from comm's by their callbacks: a
 * callback that fails undoes the duplicate (MPI_COMM_NULL), and its error
 * is raised. */
static int dup_attrs(st_rank *R, const st_comm *c, MPI_Comm comm, const char *fn, MPI_Comm *newcomm) {
  char why[128];
  int rc = attr_copy(R, ATTR_COMM, comm, *newcomm, why);
  if (!rc) return MPI_SUCCESS;
  comm_end(R, newcomm);
  return err_raise(R, c, rc, fn, "%s", why);
}

/* MPI_Comm_dup's work, for dup, idup and dup_with_info. */
int comm_dup(st_rank *R, MPI_Comm comm, const char *fn, MPI_Comm *newcomm) {
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!newcomm) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  *newcomm = MPI_COMM_NULL;
  if (c->inter) {
    if ((rc = comm_inter_dup(R, c, fn, newcomm))) return rc;
  } else {
    label_rec l = {.fn = fn, .what = L_COMM, .pair = c->pair};
    label_set(R, &l);
    int pair = comm_agree_pair(R, 2 * c->pair + 1, c->g, c->rank, TAG_CTXID);
    label_clear(R);
    if (pair < 0) return comm_no_pair(R, c, fn);
    c->g->refs++;
    *newcomm = comm_add(R, c->g, pair, c->rank, c->eh, c->hints);
    if (c->topo) {   /* MPI 3.1 section 7.1: a duplicate keeps the topology */
      ptopo_ref(c->topo);
      st_comm_get(R, *newcomm)->topo = c->topo;
    }
  }
  return dup_attrs(R, c, comm, fn, newcomm);
}

int PMPI_Comm_dup(MPI_Comm comm, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_dup";
  return comm_dup(st_need(fn), comm, fn, newcomm);
}

/* MPI_Comm_idup completes at once: it is MPI_Comm_dup (the ranks agree on
 * the context then), with a request that is done already. */
int PMPI_Comm_idup(MPI_Comm comm, MPI_Comm *newcomm, MPI_Request *request) {
  static const char fn[] = "MPI_Comm_idup";
  st_rank *R = st_need(fn);
  if (!request) {
    st_comm *c;
    int rc = err_check_comm(R, comm, fn, &c);
    return rc ? rc : err_raise(R, c, MPI_ERR_ARG, fn, "NULL request argument");
  }
  int rc = comm_dup(R, comm, fn, newcomm);
  if (rc) return rc;
  st_req *q = st_req_new(R);
  q->kind = RQ_SEND;
  q->state = RS_DONE;
  q->fn = fn;
  q->comm = comm;
  q->peer = MPI_PROC_NULL;
  pt2pt_status_empty(&q->st);
  *request = st_req_handle(q);
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
int *comm_split_members(const int *table, int n, const st_ranks *g, int color, int mine, int *m, int *me) {
  split_entry *e = xmallocarray((size_t)n + 1, sizeof *e);
  *m = 0;
  for (int r = 0; r < n; r++)
    if (table[2 * r] == color) e[(*m)++] = (split_entry){color, table[2 * r + 1], r};
  qsort(e, (size_t)*m, sizeof *e, cmp_split);
  int *world = xmallocarray((size_t)*m + 1, sizeof *world);
  *me = -1;
  for (int i = 0; i < *m; i++) {
    world[i] = comm_member(g, e[i].rank);
    if (e[i].rank == mine) *me = i;
  }
  free(e);
  return world;
}

int PMPI_Comm_split(MPI_Comm comm, int color, int key, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_split";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!newcomm) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  if (color < 0 && color != MPI_UNDEFINED)
    return err_raise(R, c, MPI_ERR_ARG, fn, "invalid color %d (>= 0, or MPI_UNDEFINED)", color);
  if (c->inter) return comm_inter_split(R, c, fn, color, key, newcomm);
  label_rec l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  label_set(R, &l);
  int n = c->size, ctx = 2 * c->pair + 1;
  int *table = comm_scratch(fn, (size_t)n * 2 * sizeof *table);   /* (color, key) by rank */
  if (c->rank == 0) {
    table[0] = color;
    table[1] = key;
    for (int r = 1; r < n; r++) comm_xrecv(R, ctx, comm_member(c->g, r), TAG_SPLIT, &table[2 * r], 2 * sizeof *table);
  } else {
    int mine[2] = {color, key};
    comm_xsend(R, ctx, comm_member(c->g, 0), TAG_SPLIT, mine, sizeof mine);
  }
  comm_tree_bcast(R, ctx, c->g, c->rank, 0, TAG_SPLIT_BCAST, table, (size_t)n * 2 * sizeof *table);
  int pair = comm_agree_pair(R, ctx, c->g, c->rank, TAG_CTXID);
  label_clear(R);
  if (pair < 0) {
    comm_scratch_free(table);
    return comm_no_pair(R, c, fn);
  }
  if (color == MPI_UNDEFINED) {
    /* One pair serves every color's communicator (they share no rank);
     * this rank is in none of them. */
    comm_pair_give(R, pair);
    comm_scratch_free(table);
    *newcomm = MPI_COMM_NULL;
    return MPI_SUCCESS;
  }
  int m, me;
  int *world = comm_split_members(table, n, c->g, color, c->rank, &m, &me);
  *newcomm = comm_add(R, st_ranks_new(m, world), pair, me, c->eh, 0);
  free(world);
  comm_scratch_free(table);
  return MPI_SUCCESS;
}

/* MPI_COMM_TYPE_SHARED: a node of the simulated machine is one processor,
 * whose memory no other rank shares, so each rank's communicator is itself
 * alone.  Its context needs no agreement (it is free on the only rank that
 * uses it): the call sends nothing and takes no simulated time. */
int PMPI_Comm_split_type(MPI_Comm comm, int split_type, int key, MPI_Info info, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_split_type";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  (void)key;
  if (!newcomm) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  if (c->inter) return err_raise(R, c, MPI_ERR_COMM, fn, "an intercommunicator (MPI_Comm_split_type splits intracommunicators)");
  if (split_type != MPI_COMM_TYPE_SHARED && split_type != MPI_UNDEFINED)
    return err_raise(R, c, MPI_ERR_ARG, fn, "invalid split_type %d (MPI_COMM_TYPE_SHARED or MPI_UNDEFINED)",
                     split_type);
  unsigned hints;
  if ((rc = info_hints(R, c, fn, info, &hints))) return rc;
  *newcomm = MPI_COMM_NULL;
  if (split_type == MPI_UNDEFINED) return MPI_SUCCESS;
  int pair = comm_pair_lowest(R->pairs, -1);
  if (pair < 0) return comm_no_pair(R, c, fn);
  comm_pair_take(R, pair);
  *newcomm = comm_add(R, st_ranks_new(1, &R->wrank), pair, 0, c->eh, hints);
  return MPI_SUCCESS;
}

/* Is every rank of g in c (its local group)? */
static int subset(const st_ranks *g, const st_comm *c) {
  for (int i = 0; i < g->n; i++)
    if (st_ranks_find(st_comm_lgroup(c), comm_member(g, i)) < 0) return 0;
  return 1;
}

static int group_arg(st_rank *R, const st_comm *c, const char *fn, MPI_Group group, st_ranks **g) {
  *g = group_get(R, group);
  if (!*g) return err_raise(R, c, MPI_ERR_GROUP, fn, "invalid group 0x%x", (unsigned)group);
  if (!subset(*g, c))
    return err_raise(R, c, MPI_ERR_GROUP, fn, "the group has ranks that are not in the communicator%s",
                     c->inter ? "'s local group" : "");
  return MPI_SUCCESS;
}

int PMPI_Comm_create(MPI_Comm comm, MPI_Group group, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_create";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!newcomm) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  st_ranks *g;
  if ((rc = group_arg(R, c, fn, group, &g))) return rc;
  if (c->inter) return comm_inter_create(R, c, fn, g, newcomm);
  label_rec l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  label_set(R, &l);
  int pair = comm_agree_pair(R, 2 * c->pair + 1, c->g, c->rank, TAG_CTXID);
  label_clear(R);
  if (pair < 0) return comm_no_pair(R, c, fn);
  int me = st_ranks_find(g, R->wrank);
  if (me < 0) {
    comm_pair_give(R, pair);
    *newcomm = MPI_COMM_NULL;
    return MPI_SUCCESS;
  }
  g->refs++;
  *newcomm = comm_add(R, g, pair, me, c->eh, 0);
  return MPI_SUCCESS;
}

int PMPI_Comm_create_group(MPI_Comm comm, MPI_Group group, int tag, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_create_group";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (c->inter) return err_raise(R, c, MPI_ERR_COMM, fn, "an intercommunicator (MPI_Comm_create_group needs an intracommunicator)");
  if ((rc = err_check_tag(R, c, fn, tag, 0))) return rc;
  if (!newcomm) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  st_ranks *g;
  if ((rc = group_arg(R, c, fn, group, &g))) return rc;
  int me = st_ranks_find(g, R->wrank);
  if (me < 0) {
    *newcomm = MPI_COMM_NULL;   /* MPI 3.1 section 6.4.2: a rank outside the group gets none */
    return MPI_SUCCESS;
  }
  /* Only the group's ranks take part: they agree among themselves, on the
   * parent's collective context, with tags of their own by the program's
   * tag (state.h: TAG_GROUP). */
  label_rec l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  label_set(R, &l);
  int pair = comm_agree_pair(R, 2 * c->pair + 1, g, me, TAG_GROUP + 2 * (tag % TAG_GROUP_N));
  label_clear(R);
  if (pair < 0) return comm_no_pair(R, c, fn);
  g->refs++;
  *newcomm = comm_add(R, g, pair, me, c->eh, 0);
  return MPI_SUCCESS;
}

/* Free: the attributes' delete callbacks first, on a communicator still
 * valid (MPI 3.1 section 6.7.2); one that fails leaves it as it is. */
static int comm_free(const char *fn, MPI_Comm *comm) {
  st_rank *R = st_need(fn);
  if (!comm) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL comm argument");
  st_comm *c;
  int rc = err_check_comm(R, *comm, fn, &c);
  if (rc) return rc;
  if (c == &R->world || c == &R->selfc)
    return err_raise(R, c, MPI_ERR_COMM, fn, "%s cannot be freed", c == &R->world ? "MPI_COMM_WORLD" : "MPI_COMM_SELF");
  char why[128];
  if ((rc = attr_delete_all(R, ATTR_COMM, *comm, why))) return err_raise(R, c, rc, fn, "%s", why);
  if (c->holds) {   /* its nonblocking collectives go on; it ends with the last (core.h) */
    c->freed = 1;
    *comm = MPI_COMM_NULL;
    return MPI_SUCCESS;
  }
  comm_end(R, comm);
  return MPI_SUCCESS;
}

int PMPI_Comm_free(MPI_Comm *comm) { return comm_free("MPI_Comm_free", comm); }

/* Collective: it waits, as a barrier, for every rank of the communicator
 * (whose messages have all left by then: sends are eager), then frees. */
int PMPI_Comm_disconnect(MPI_Comm *comm) {
  static const char fn[] = "MPI_Comm_disconnect";
  st_rank *R = st_need(fn);
  if (!comm) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL comm argument");
  st_comm *c;
  int rc = err_check_comm(R, *comm, fn, &c);
  if (rc) return rc;
  if (c == &R->world || c == &R->selfc)
    return err_raise(R, c, MPI_ERR_COMM, fn, "%s cannot be disconnected", c == &R->world ? "MPI_COMM_WORLD" : "MPI_COMM_SELF");
  if ((rc = PMPI_Barrier(*comm))) return rc;
  return comm_free(fn, comm);
}

/* ==== comparing, groups, names ============================================ */

/* MPI 3.1 section 6.4.1; intercommunicators compare both groups. */
int PMPI_Comm_compare(MPI_Comm comm1, MPI_Comm comm2, int *result) {
  static const char fn[] = "MPI_Comm_compare";
  st_rank *R = st_need(fn);
  st_comm *a, *b;
  int rc = err_check_comm(R, comm1, fn, &a);
  if (rc || (rc = err_check_comm(R, comm2, fn, &b))) return rc;
  if (!result) return err_raise(R, a, MPI_ERR_ARG, fn, "NULL result argument");
  static const int verdict[3] = {MPI_UNEQUAL, MPI_SIMILAR, MPI_CONGRUENT};
  int same = a->inter != b->inter ? 0 : group_ranks_same(a->g, b->g);
  if (a->inter && b->inter) {
    int local = group_ranks_same(a->lg, b->lg);
    same = local < same ? local : same;
  }
  *result = a == b ? MPI_IDENT : verdict[same];
  return MPI_SUCCESS;
}

int PMPI_Comm_group(MPI_Comm comm, MPI_Group *group) {
  static const char fn[] = "MPI_Comm_group";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!group) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL group argument");
  st_ranks *g = st_comm_lgroup(c);
  g->refs++;
  *group = group_add(R, g);
  return MPI_SUCCESS;
}

int PMPI_Comm_set_name(MPI_Comm comm, const char *comm_name) {
  static const char fn[] = "MPI_Comm_set_name";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!comm_name) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL name");
  snprintf(c->name, sizeof c->name, "%s", comm_name);
  return MPI_SUCCESS;
}

int PMPI_Comm_get_name(MPI_Comm comm, char *comm_name, int *resultlen) {
  static const char fn[] = "MPI_Comm_get_name";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!comm_name || !resultlen) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL argument");
  size_t n = strlen(c->name);
  memcpy(comm_name, c->name, n + 1);
  *resultlen = (int)n;
  return MPI_SUCCESS;
}
