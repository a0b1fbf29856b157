/* intercomm.c -- intercommunicators (MPI 3.1 section 6.6): MPI_Intercomm_create,
 * MPI_Intercomm_merge, MPI_Comm_test_inter, MPI_Comm_remote_size,
 * MPI_Comm_remote_group, and MPI_Comm_dup, MPI_Comm_split and
 * MPI_Comm_create on an intercommunicator (comm.h).
 *
 * An intercommunicator holds the remote group as its ranks (state.h), so
 * point-to-point on it names the remote group's ranks with no more work,
 * its local group, and a hidden intracommunicator of the local group for
 * the collectives' local steps (coll_inter.c), each with a context pair.
 * To make one, each group ORs its ranks' bitmaps of used pairs up to its
 * leader (comm.h), the two leaders swap theirs with whatever the
 * constructor needs (the groups' ranks, the colors of a split), take the
 * lowest pair free on both groups, and the lowest free on their own group
 * but that one for the hidden communicator, and send that down their
 * group's tree.  The leaders talk on the peer communicator's collective
 * context (MPI_Intercomm_create) or the intercommunicator's; the groups on
 * the local communicator's (MPI_Intercomm_create) or the hidden one's. */
#include <stdlib.h>
#include <string.h>

#include "mpi/comm.h"
#include "mpi/err.h"
#include "mpi/group.h"
#include "mpi/label.h"
#include "util/xmem.h"

/* ==== agreeing ============================================================ */

/* A group lg (the calling rank its member me, its leader member lead, the
 * group's messages on context ctx) and another group's leader (world rank
 * wremote, the leaders' messages on context xctx) agree: *p free on every
 * rank of both groups, *q free on every rank of lg and not *p (each group
 * its own; -1 if want_q is 0), each taken by the calling rank (-1: none
 * left, nothing taken).  The leaders swap out (olen bytes: the leader's) for
 * the other leader's, which every rank of lg gets in *in (scratch, *ilen
 * bytes: comm_scratch_free). */
static void agree(st_rank *R, int ctx, const st_ranks *lg, int me, int lead, int xctx, int wremote, int want_q,
                  const void *out, size_t olen, void **in, size_t *ilen, int *p, int *q) {
  unsigned char used[PAIR_BYTES];
  memcpy(used, R->pairs, PAIR_BYTES);
  comm_tree_or(R, ctx, lg, me, lead, TAG_CTXID, used);
  long hdr[3] = {-1, -1, 0};   /* p, q, the other leader's bytes */
  void *theirs = NULL;
  if (me == lead) {
    unsigned char *msg = comm_scratch("an MPI communicator constructor", PAIR_BYTES + olen);
    memcpy(msg, used, PAIR_BYTES);
    if (olen) memcpy(msg + PAIR_BYTES, out, olen);
    void *got;
    size_t glen;
    comm_xswap(R, xctx, wremote, TAG_INTER, msg, PAIR_BYTES + olen, &got, &glen);
    comm_scratch_free(msg);
    unsigned char all[PAIR_BYTES];
    for (int i = 0; i < PAIR_BYTES; i++) all[i] = used[i] | ((unsigned char *)got)[i];
    hdr[0] = comm_pair_lowest(all, -1);
    hdr[1] = want_q && hdr[0] >= 0 ? comm_pair_lowest(used, (int)hdr[0]) : -1;
    hdr[2] = (long)(glen - PAIR_BYTES);
    theirs = comm_scratch("an MPI communicator constructor", (size_t)hdr[2]);
    memcpy(theirs, (unsigned char *)got + PAIR_BYTES, (size_t)hdr[2]);
    comm_scratch_free(got);
  }
  comm_tree_bcast(R, ctx, lg, me, lead, TAG_INTER_BCAST, hdr, sizeof hdr);
  if (me != lead) theirs = comm_scratch("an MPI communicator constructor", (size_t)hdr[2]);
  comm_tree_bcast(R, ctx, lg, me, lead, TAG_INTER_BCAST, theirs, (size_t)hdr[2]);
  *in = theirs;
  *ilen = (size_t)hdr[2];
  *p = (int)hdr[0];
  *q = (int)hdr[1];
  if (*p < 0 || (want_q && *q < 0)) {
    *p = *q = -1;
    return;
  }
  comm_pair_take(R, *p);
  if (want_q) comm_pair_take(R, *q);
}

/* The same among the two groups of intercommunicator c: leaders are local
 * rank 0 of each. */
static void agree_inter(st_rank *R, const st_comm *c, int want_q, const void *out, size_t olen, void **in, size_t *ilen,
                        int *p, int *q) {
  const st_comm *l = st_comm_get(R, c->local);
  agree(R, 2 * l->pair + 1, c->lg, c->rank, 0, 2 * c->pair + 1, comm_member(c->g, 0), want_q, out, olen, in, ilen, p,
        q);
}

/* A new intercommunicator: local group lg and remote group rg (one count
 * of each taken), the calling rank's rank in lg, its pair p and the hidden
 * local communicator's q. */
static MPI_Comm inter_new(st_rank *R, st_ranks *lg, st_ranks *rg, int rank, int p, int q, MPI_Errhandler eh,
                          unsigned hints, int low) {
  lg->refs++;
  MPI_Comm local = comm_add(R, lg, q, rank, MPI_ERRORS_ARE_FATAL, 0);
  st_comm_get(R, local)->hidden = 1;
  MPI_Comm h = comm_add(R, rg, p, rank, eh, hints);
  st_comm *c = st_comm_get(R, h);
  c->inter = 1;
  c->lg = lg;
  c->local = local;
  c->low = low;
  return h;
}

/* The world ranks of g, in new scratch memory. */
static int *world_list(const st_ranks *g, const char *fn) {
  int *w = comm_scratch(fn, ((size_t)g->n + 1) * sizeof *w);
  for (int i = 0; i < g->n; i++) w[i] = comm_member(g, i);
  return w;
}

/* ==== MPI_Intercomm_create ================================================ */

int PMPI_Intercomm_create(MPI_Comm local_comm, int local_leader, MPI_Comm peer_comm, int remote_leader, int tag,
                         MPI_Comm *newintercomm) {
  static const char fn[] = "MPI_Intercomm_create";
  st_rank *R = st_need(fn);
  st_comm *lc, *pc = NULL;
  int rc = err_check_comm(R, local_comm, fn, &lc);
  if (rc) return rc;
  if (lc->inter) return err_raise(R, lc, MPI_ERR_COMM, fn, "local_comm is an intercommunicator");
  if (!newintercomm) return err_raise(R, lc, MPI_ERR_ARG, fn, "NULL newintercomm argument");
  if (local_leader < 0 || local_leader >= lc->size)
    return err_raise(R, lc, MPI_ERR_RANK, fn, "invalid local_leader %d (local_comm has %d ranks)", local_leader,
                     lc->size);
  int wremote = -1;
  if (lc->rank == local_leader) {   /* peer_comm, remote_leader and tag matter at the leader only */
    if ((rc = err_check_comm(R, peer_comm, fn, &pc)) || (rc = err_check_tag(R, lc, fn, tag, 0))) return rc;
    if (remote_leader < 0 || remote_leader >= pc->size)
      return err_raise(R, lc, MPI_ERR_RANK, fn, "invalid remote_leader %d (peer_comm has %d ranks)", remote_leader,
                       pc->size);
    wremote = st_world_of(pc, remote_leader);
    if (st_ranks_find(lc->g, wremote) >= 0)
      return err_raise(R, lc, MPI_ERR_RANK, fn, "remote_leader %d of peer_comm is in local_comm: the groups must not overlap",
                       remote_leader);
  }
  /* The leaders swap their leader's world rank and their group's. */
  label_rec l = {.fn = fn, .what = L_COMM, .pair = lc->pair};
  label_set(R, &l);
  int *mine = comm_scratch(fn, ((size_t)lc->size + 1) * sizeof *mine), *theirs, p, q;
  mine[0] = comm_member(lc->g, local_leader);
  for (int i = 0; i < lc->size; i++) mine[i + 1] = comm_member(lc->g, i);
  size_t tlen;
  agree(R, 2 * lc->pair + 1, lc->g, lc->rank, local_leader, pc ? 2 * pc->pair + 1 : -1, wremote, 1, mine,
        ((size_t)lc->size + 1) * sizeof *mine, (void **)&theirs, &tlen, &p, &q);
  label_clear(R);
  int rn = (int)(tlen / sizeof *theirs) - 1;
  if (p < 0) {
    comm_scratch_free(mine);
    comm_scratch_free(theirs);
    return comm_no_pair(R, lc, fn);
  }
  /* The group whose leader has the lower world rank comes first when
   * merged, unless told otherwise. */
  int low = mine[0] < theirs[0];
  lc->g->refs++;
  *newintercomm = inter_new(R, lc->g, st_ranks_new(rn, theirs + 1), lc->rank, p, q, lc->eh, 0, low);
  comm_scratch_free(mine);
  comm_scratch_free(theirs);
  return MPI_SUCCESS;
}

/* ==== MPI_Intercomm_merge ================================================= */

/* The group that passes high = 0 comes first; if both pass the same, the
 * one whose leader had the lower world rank at MPI_Intercomm_create. */
int PMPI_Intercomm_merge(MPI_Comm intercomm, int high, MPI_Comm *newintracomm) {
  static const char fn[] = "MPI_Intercomm_merge";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, intercomm, fn, &c);
  if (rc) return rc;
  if (!c->inter) return err_raise(R, c, MPI_ERR_COMM, fn, "not an intercommunicator");
  if (!newintracomm) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL newintracomm argument");
  label_rec l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  label_set(R, &l);
  int mine = high != 0, *theirs, p, q;
  size_t tlen;
  agree_inter(R, c, 0, &mine, sizeof mine, (void **)&theirs, &tlen, &p, &q);
  label_clear(R);
  int first = mine != *theirs ? !mine : c->low;
  comm_scratch_free(theirs);
  if (p < 0) return comm_no_pair(R, c, fn);
  int ln = c->lg->n, rn = c->g->n, *w = xmallocarray((size_t)(ln + rn), sizeof *w);
  const st_ranks *a = first ? c->lg : c->g, *b = first ? c->g : c->lg;
  for (int i = 0; i < a->n; i++) w[i] = comm_member(a, i);
  for (int i = 0; i < b->n; i++) w[a->n + i] = comm_member(b, i);
  *newintracomm = comm_add(R, st_ranks_new(ln + rn, w), p, first ? c->rank : rn + c->rank, c->eh, 0);
  free(w);
  return MPI_SUCCESS;
}

/* ==== queries ============================================================= */

int PMPI_Comm_test_inter(MPI_Comm comm, int *flag) {
  static const char fn[] = "MPI_Comm_test_inter";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = err_check_comm(R, comm, fn, &c);
  if (rc) return rc;
  if (!flag) return err_raise(R, c, MPI_ERR_ARG, fn, "NULL flag argument");
  *flag = c->inter;
  return MPI_SUCCESS;
}

static int inter_arg(st_rank *R, MPI_Comm comm, const char *fn, st_comm **c, const void *out) {
  int rc = err_check_comm(R, comm, fn, c);
  if (rc) return rc;
  if (!(*c)->inter) return err_raise(R, *c, MPI_ERR_COMM, fn, "not an intercommunicator");
  if (!out) return err_raise(R, *c, MPI_ERR_ARG, fn, "NULL argument");
  return MPI_SUCCESS;
}

int PMPI_Comm_remote_size(MPI_Comm comm, int *size) {
  static const char fn[] = "MPI_Comm_remote_size";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = inter_arg(R, comm, fn, &c, size);
  if (rc) return rc;
  *size = c->g->n;
  return MPI_SUCCESS;
}

int PMPI_Comm_remote_group(MPI_Comm comm, MPI_Group *group) {
  static const char fn[] = "MPI_Comm_remote_group";
  st_rank *R = st_need(fn);
  st_comm *c;
  int rc = inter_arg(R, comm, fn, &c, group);
  if (rc) return rc;
  c->g->refs++;
  *group = group_add(R, c->g);
  return MPI_SUCCESS;
}

/* No rank of a tilesim run was spawned by another (MPI_Comm_spawn is not
 * there): MPI 3.1 section 10.3.2 says MPI_COMM_NULL. */
int PMPI_Comm_get_parent(MPI_Comm *parent) {
  static const char fn[] = "MPI_Comm_get_parent";
  st_rank *R = st_need(fn);
  if (!parent) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL parent argument");
  *parent = MPI_COMM_NULL;
  return MPI_SUCCESS;
}

/* ==== dup, split, create ================================================== */

int comm_inter_dup(st_rank *R, st_comm *c, const char *fn, MPI_Comm *newcomm) {
  label_rec l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  label_set(R, &l);
  void *in;
  size_t ilen;
  int p, q;
  agree_inter(R, c, 1, NULL, 0, &in, &ilen, &p, &q);
  label_clear(R);
  comm_scratch_free(in);
  if (p < 0) return comm_no_pair(R, c, fn);
  c->lg->refs++;
  c->g->refs++;
  *newcomm = inter_new(R, c->lg, c->g, c->rank, p, q, c->eh, c->hints, c->low);
  return MPI_SUCCESS;
}

/* Each group splits by color; the ranks of one color in both groups make
 * an intercommunicator (MPI 3.1 section 6.4.2), whose local and remote
 * groups are ordered by key.  A color that one group lacks gives
 * MPI_COMM_NULL.  One pair serves every color's intercommunicator. */
int comm_inter_split(st_rank *R, st_comm *c, const char *fn, int color, int key, MPI_Comm *newcomm) {
  label_rec l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  label_set(R, &l);
  const st_comm *lc = st_comm_get(R, c->local);
  int n = c->lg->n, ctx = 2 * lc->pair + 1;
  int *table = comm_scratch(fn, (size_t)n * 2 * sizeof *table);   /* (color, key) by local rank */
  if (c->rank == 0) {
    table[0] = color;
    table[1] = key;
    for (int r = 1; r < n; r++) comm_xrecv(R, ctx, comm_member(c->lg, r), TAG_SPLIT, &table[2 * r], 2 * sizeof *table);
  } else {
    int mine[2] = {color, key};
    comm_xsend(R, ctx, comm_member(c->lg, 0), TAG_SPLIT, mine, sizeof mine);
  }
  comm_tree_bcast(R, ctx, c->lg, c->rank, 0, TAG_SPLIT_BCAST, table, (size_t)n * 2 * sizeof *table);
  int *theirs, p, q;
  size_t tlen;
  agree_inter(R, c, 1, table, (size_t)n * 2 * sizeof *table, (void **)&theirs, &tlen, &p, &q);
  label_clear(R);
  *newcomm = MPI_COMM_NULL;
  if (p < 0) {
    comm_scratch_free(table);
    comm_scratch_free(theirs);
    return comm_no_pair(R, c, fn);
  }
  int lm = 0, rm = 0, me, none;
  int *lw = color == MPI_UNDEFINED ? NULL : comm_split_members(table, n, c->lg, color, c->rank, &lm, &me);
  int *rw = color == MPI_UNDEFINED ? NULL : comm_split_members(theirs, (int)(tlen / (2 * sizeof *theirs)), c->g, color, -1, &rm, &none);
  if (lm && rm) {
    *newcomm = inter_new(R, st_ranks_new(lm, lw), st_ranks_new(rm, rw), me, p, q, c->eh, 0, c->low);
  } else {
    comm_pair_give(R, p);
    comm_pair_give(R, q);
  }
  free(lw);
  free(rw);
  comm_scratch_free(table);
  comm_scratch_free(theirs);
  return MPI_SUCCESS;
}

/* Each group passes a group of its own ranks; the two make an
 * intercommunicator, for their ranks (MPI_COMM_NULL for the others, and
 * for all if either group is empty). */
int comm_inter_create(st_rank *R, st_comm *c, const char *fn, const st_ranks *group, MPI_Comm *newcomm) {
  label_rec l = {.fn = fn, .what = L_COMM, .pair = c->pair};
  label_set(R, &l);
  int *mine = world_list(group, fn), *theirs, p, q;
  size_t tlen;
  agree_inter(R, c, 1, mine, (size_t)group->n * sizeof *mine, (void **)&theirs, &tlen, &p, &q);
  label_clear(R);
  *newcomm = MPI_COMM_NULL;
  int rn = (int)(tlen / sizeof *theirs), me = st_ranks_find(group, R->wrank);
  if (p < 0) {
    comm_scratch_free(mine);
    comm_scratch_free(theirs);
    return comm_no_pair(R, c, fn);
  }
  if (me >= 0 && rn > 0) {
    *newcomm = inter_new(R, st_ranks_new(group->n, mine), st_ranks_new(rn, theirs), me, p, q, c->eh, 0, c->low);
  } else {
    comm_pair_give(R, p);
    comm_pair_give(R, q);
  }
  comm_scratch_free(mine);
  comm_scratch_free(theirs);
  return MPI_SUCCESS;
}
