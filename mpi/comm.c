/* comm.c -- communicators: rank and size, Comm_dup, Comm_split,
 * Comm_create, Comm_create_group, Comm_free, Comm_compare, Comm_group,
 * names and the predefined attributes.
 *
 * CONTEXTS.  A new communicator needs a context pair (state.h) that no rank
 * of it uses for another communicator, the same on all of them.  Each rank
 * keeps a bitmap of the pairs it uses; the ranks that make the
 * communicator OR theirs up a binomial tree to the first of them, which
 * takes the lowest pair free on all (MPICH's way, with an allreduce), and
 * the pair comes back down the tree.  That is 2 ceil(log2 P) steps of
 * 128-byte and 4-byte messages on the parent's collective context: a
 * communicator costs simulated time, as on a real machine.  Comm_split first
 * gathers every rank's (color, key) at the parent's rank 0 (one message
 * each) and sends the table down a binomial tree. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine.h"
#include "group.h"
#include "err.h"
#include "label.h"
#include "pt2pt.h"
#include "xmem.h"

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
  *size = c->size;
  return MPI_SUCCESS;
}

int PMPI_Comm_test_inter(MPI_Comm comm, int *flag) {
  static const char fn[] = "MPI_Comm_test_inter";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  *flag = 0;   /* tilesim has intracommunicators only */
  return MPI_SUCCESS;
}

/* ==== messages among the ranks that make a communicator =================== */

/* The world rank of member i of g. */
static int member(const tsm_ranks *g, int i) { return g->world ? g->world[i] : i; }

static void xsend(tsm *R, int ctx, int wdst, int tag, const void *buf, size_t len) {
  tsm_req q = {.slot = -1, .kind = RQ_SEND, .mode = SM_STANDARD, .wpeer = wdst, .ctx = ctx, .tag = tag};
  eng_send(R, &q, buf, len);
}

static void xrecv(tsm *R, int ctx, int wsrc, int tag, void *buf, size_t len) {
  tsm_req q = {.slot = -1, .kind = RQ_RECV, .wpeer = wsrc, .ctx = ctx, .tag = tag, .cap = len,
               .contig = buf, .g = R->world.g, .count = (int)len, .dt = MPI_BYTE};
  eng_recv(R, &q);
  if (q.st.MPI_ERROR || q.msglen != len) {
    fprintf(stderr, "tilesim MPI: internal error: rank %d: a %zu-byte message from rank %d where %zu were due\n",
            R->wrank, q.msglen, wsrc, len);
    abort();
  }
}

/* Broadcast len bytes from member 0 of g (the calling rank is member me)
 * down a binomial tree. */
static void tree_bcast(tsm *R, int ctx, const tsm_ranks *g, int me, int tag, void *buf, size_t len) {
  int n = g->n, mask = 1;
  while (mask < n) {
    if (me & mask) {
      xrecv(R, ctx, member(g, me - mask), tag, buf, len);
      break;
    }
    mask <<= 1;
  }
  for (mask >>= 1; mask > 0; mask >>= 1)
    if (me + mask < n) xsend(R, ctx, member(g, me + mask), tag, buf, len);
}

/* The lowest context pair that no member of g uses, agreed by all of them
 * (and taken by the calling rank), or -1 if every pair is used by one. */
static int agree_pair(tsm *R, int ctx, const tsm_ranks *g, int me) {
  enum { BYTES = CTX_PAIRS / 8 };
  unsigned char used[BYTES], other[BYTES];
  memcpy(used, R->pairs, BYTES);
  for (int mask = 1; mask < g->n; mask <<= 1) {
    if (me & mask) {
      xsend(R, ctx, member(g, me - mask), TAG_CTXID, used, BYTES);
      break;
    }
    if (me + mask < g->n) {
      xrecv(R, ctx, member(g, me + mask), TAG_CTXID, other, BYTES);
      for (int i = 0; i < BYTES; i++) used[i] |= other[i];
    }
  }
  int pair = -1;
  if (me == 0)
    for (int p = 0; p < CTX_PAIRS && pair < 0; p++)
      if (!(used[p / 8] >> (p % 8) & 1)) pair = p;
  tree_bcast(R, ctx, g, me, TAG_CTXID_BCAST, &pair, sizeof pair);
  if (pair >= 0) R->pairs[pair / 8] |= (unsigned char)(1u << (pair % 8));
  return pair;
}

/* A new communicator of R with ranks g (counted: taken), pair, the
 * calling rank's rank and handler; its handle. */
static MPI_Comm comm_add(tsm *R, tsm_ranks *g, int pair, int rank, MPI_Errhandler eh) {
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
  R->comms[slot] = c;
  return (MPI_Comm)(HK_COMM << H_KIND_SHIFT | H_CREATED | slot);
}

static int no_pair(tsm *R, const tsm_comm *c, const char *fn) {
  return tsm_raise(R, c, MPI_ERR_OTHER, fn,
                   "no context left: a rank of it is in %d communicators at once (tilesim's limit; "
                   "free some with MPI_Comm_free)",
                   CTX_PAIRS);
}

/* ==== constructors ======================================================== */

int PMPI_Comm_dup(MPI_Comm comm, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_dup";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!newcomm) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  tsm_label l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  tsm_label_set(R, &l);
  int pair = agree_pair(R, 2 * c->pair + 1, c->g, c->rank);
  tsm_unlabel(R);
  if (pair < 0) return no_pair(R, c, fn);
  c->g->refs++;
  *newcomm = comm_add(R, c->g, pair, c->rank, c->eh);
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

int PMPI_Comm_split(MPI_Comm comm, int color, int key, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_split";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!newcomm) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  if (color < 0 && color != MPI_UNDEFINED)
    return tsm_raise(R, c, MPI_ERR_ARG, fn, "invalid color %d (>= 0, or MPI_UNDEFINED)", color);
  tsm_label l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  tsm_label_set(R, &l);
  int n = c->size, ctx = 2 * c->pair + 1;
  int *table = xmallocarray((size_t)n, 2 * sizeof *table);   /* (color, key) by rank */
  if (c->rank == 0) {
    table[0] = color;
    table[1] = key;
    for (int r = 1; r < n; r++) xrecv(R, ctx, member(c->g, r), TAG_SPLIT, &table[2 * r], 2 * sizeof *table);
  } else {
    int mine[2] = {color, key};
    xsend(R, ctx, member(c->g, 0), TAG_SPLIT, mine, sizeof mine);
  }
  tree_bcast(R, ctx, c->g, c->rank, TAG_SPLIT_BCAST, table, (size_t)n * 2 * sizeof *table);
  int pair = agree_pair(R, ctx, c->g, c->rank);
  tsm_unlabel(R);
  if (pair < 0) {
    free(table);
    return no_pair(R, c, fn);
  }
  if (color == MPI_UNDEFINED) {
    /* One pair serves every color's communicator (they share no rank);
     * this rank is in none of them. */
    R->pairs[pair / 8] &= (unsigned char)~(1u << (pair % 8));
    free(table);
    *newcomm = MPI_COMM_NULL;
    return MPI_SUCCESS;
  }
  int m = 0;
  split_entry *e = xmallocarray((size_t)n, sizeof *e);
  for (int r = 0; r < n; r++)
    if (table[2 * r] == color) e[m++] = (split_entry){color, table[2 * r + 1], r};
  qsort(e, (size_t)m, sizeof *e, cmp_split);
  int *world = xmallocarray((size_t)m, sizeof *world), me = -1;
  for (int i = 0; i < m; i++) {
    world[i] = member(c->g, e[i].rank);
    if (e[i].rank == c->rank) me = i;
  }
  *newcomm = comm_add(R, tsm_ranks_new(m, world), pair, me, c->eh);
  free(world);
  free(e);
  free(table);
  return MPI_SUCCESS;
}

/* Is every rank of g in c? */
static int subset(const tsm_ranks *g, const tsm_comm *c) {
  for (int i = 0; i < g->n; i++)
    if (tsm_comm_rank_of(c, member(g, i)) < 0) return 0;
  return 1;
}

int PMPI_Comm_create(MPI_Comm comm, MPI_Group group, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_create";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!newcomm) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  tsm_ranks *g = tsm_group_get(R, group);
  if (!g) return tsm_raise(R, c, MPI_ERR_GROUP, fn, "invalid group 0x%x", (unsigned)group);
  if (!subset(g, c))
    return tsm_raise(R, c, MPI_ERR_GROUP, fn, "the group has ranks that are not in the communicator");
  tsm_label l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  tsm_label_set(R, &l);
  int pair = agree_pair(R, 2 * c->pair + 1, c->g, c->rank);
  tsm_unlabel(R);
  if (pair < 0) return no_pair(R, c, fn);
  int me = tsm_ranks_find(g, R->wrank);
  if (me < 0) {
    R->pairs[pair / 8] &= (unsigned char)~(1u << (pair % 8));
    *newcomm = MPI_COMM_NULL;
    return MPI_SUCCESS;
  }
  g->refs++;
  *newcomm = comm_add(R, g, pair, me, c->eh);
  return MPI_SUCCESS;
}

int PMPI_Comm_create_group(MPI_Comm comm, MPI_Group group, int tag, MPI_Comm *newcomm) {
  static const char fn[] = "MPI_Comm_create_group";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if ((rc = tsm_check_tag(R, c, fn, tag, 0))) return rc;
  if (!newcomm) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL newcomm argument");
  tsm_ranks *g = tsm_group_get(R, group);
  if (!g) return tsm_raise(R, c, MPI_ERR_GROUP, fn, "invalid group 0x%x", (unsigned)group);
  if (!subset(g, c))
    return tsm_raise(R, c, MPI_ERR_GROUP, fn, "the group has ranks that are not in the communicator");
  int me = tsm_ranks_find(g, R->wrank);
  if (me < 0) {
    *newcomm = MPI_COMM_NULL;   /* MPI 3.1 section 6.4.2: a rank outside the group gets none */
    return MPI_SUCCESS;
  }
  /* Only the group's ranks take part: they agree among themselves, on the
   * parent's collective context (one call at a time per rank, and each
   * message from a named member). */
  tsm_label l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  tsm_label_set(R, &l);
  int pair = agree_pair(R, 2 * c->pair + 1, g, me);
  tsm_unlabel(R);
  if (pair < 0) return no_pair(R, c, fn);
  g->refs++;
  *newcomm = comm_add(R, g, pair, me, c->eh);
  return MPI_SUCCESS;
}

int PMPI_Comm_free(MPI_Comm *comm) {
  static const char fn[] = "MPI_Comm_free";
  tsm *R = tsm_need(fn);
  if (!comm) return tsm_raise(R, NULL, MPI_ERR_ARG, fn, "NULL comm argument");
  tsm_comm *c;
  int rc = tsm_check_comm(R, *comm, fn, &c);
  if (rc) return rc;
  if (c == &R->world || c == &R->selfc)
    return tsm_raise(R, c, MPI_ERR_COMM, fn, "%s cannot be freed", c == &R->world ? "MPI_COMM_WORLD" : "MPI_COMM_SELF");
  unsigned slot = (unsigned)*comm & H_SLOT_MASK;
  R->pairs[c->pair / 8] &= (unsigned char)~(1u << (c->pair % 8));
  tsm_ranks_drop(c->g);
  free(c);
  R->comms[slot] = NULL;
  *comm = MPI_COMM_NULL;
  return MPI_SUCCESS;
}

/* ==== comparing, groups, names, attributes ================================ */

int PMPI_Comm_compare(MPI_Comm comm1, MPI_Comm comm2, int *result) {
  static const char fn[] = "MPI_Comm_compare";
  tsm *R = tsm_need(fn);
  tsm_comm *a, *b;
  int rc = tsm_check_comm(R, comm1, fn, &a);
  if (rc || (rc = tsm_check_comm(R, comm2, fn, &b))) return rc;
  if (!result) return tsm_raise(R, a, MPI_ERR_ARG, fn, "NULL result argument");
  static const int verdict[3] = {MPI_UNEQUAL, MPI_SIMILAR, MPI_CONGRUENT};
  *result = a == b ? MPI_IDENT : verdict[tsm_ranks_same(a->g, b->g)];
  return MPI_SUCCESS;
}

int PMPI_Comm_group(MPI_Comm comm, MPI_Group *group) {
  static const char fn[] = "MPI_Comm_group";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!group) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL group argument");
  c->g->refs++;
  *group = tsm_group_add(R, c->g);
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

/* The predefined attributes of MPI 3.1 section 8.1.2, the same on every
 * communicator; no others exist (attribute keys cannot be made). */
int PMPI_Comm_get_attr(MPI_Comm comm, int comm_keyval, void *attribute_val, int *flag) {
  static const char fn[] = "MPI_Comm_get_attr";
  tsm *R = tsm_need(fn);
  tsm_comm *c;
  int rc = tsm_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!attribute_val || !flag) return tsm_raise(R, c, MPI_ERR_ARG, fn, "NULL argument");
  if (comm_keyval == MPI_KEYVAL_INVALID) return tsm_raise(R, c, MPI_ERR_KEYVAL, fn, "MPI_KEYVAL_INVALID");
  int *v = NULL;
  switch (comm_keyval) {
  case MPI_TAG_UB: R->attr[0] = TSM_TAG_UB; v = &R->attr[0]; break;
  case MPI_HOST: R->attr[1] = MPI_PROC_NULL; v = &R->attr[1]; break;
  case MPI_IO: R->attr[2] = MPI_ANY_SOURCE; v = &R->attr[2]; break;
  case MPI_WTIME_IS_GLOBAL: R->attr[3] = 1; v = &R->attr[3]; break;
  case MPI_UNIVERSE_SIZE: R->attr[4] = R->wsize; v = &R->attr[4]; break;
  case MPI_APPNUM: R->attr[5] = 0; v = &R->attr[5]; break;
  case MPI_LASTUSEDCODE: R->attr[6] = MPI_ERR_LASTCODE - 1; v = &R->attr[6]; break;
  default: break;
  }
  *flag = v != NULL;
  if (v) memcpy(attribute_val, &v, sizeof v);
  return MPI_SUCCESS;
}

int PMPI_Attr_get(MPI_Comm comm, int keyval, void *attribute_val, int *flag) {
  return MPI_Comm_get_attr(comm, keyval, attribute_val, flag);
}
