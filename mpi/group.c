/* group.c -- groups (MPI 3.1 section 6.3): ordered sets of ranks, named by
 * their MPI_COMM_WORLD ranks and shared, counted, with communicators. */
#include "mpi/group.h"

#include <stdlib.h>
#include <string.h>

#include "mpi/err.h"
#include "util/xmem.h"

/* ==== handles ============================================================= */

st_ranks *group_get(st_rank *R, MPI_Group group) {
  if (group == MPI_GROUP_EMPTY) return R->empty;
  unsigned slot = (unsigned)group - (unsigned)(HK_GROUP << H_KIND_SHIFT | H_CREATED);
  return slot < (unsigned)R->ngroups ? R->groups[slot] : NULL;
}

MPI_Group group_add(st_rank *R, st_ranks *g) {
  if (g->n == 0) {   /* every empty group is MPI_GROUP_EMPTY */
    st_ranks_drop(g);
    return MPI_GROUP_EMPTY;
  }
  int slot = 0;
  while (slot < R->ngroups && R->groups[slot]) slot++;
  if (slot == R->ngroups) {
    R->groups = xreallocarray(R->groups, (size_t)R->ngroups + 1, sizeof *R->groups);
    R->ngroups++;
  }
  R->groups[slot] = g;
  return (MPI_Group)(HK_GROUP << H_KIND_SHIFT | H_CREATED | slot);
}

static int member(const st_ranks *g, int i) { return g->world ? g->world[i] : i; }

int group_ranks_same(const st_ranks *a, const st_ranks *b) {
  if (a->n != b->n) return 0;
  int order = 1;
  for (int i = 0; i < a->n && order; i++) order = member(a, i) == member(b, i);
  if (order) return 2;
  for (int i = 0; i < a->n; i++)
    if (st_ranks_find(b, member(a, i)) < 0) return 0;
  return 1;
}

static int check_group(st_rank *R, const char *fn, MPI_Group group, st_ranks **g) {
  *g = group_get(R, group);
  if (*g) return MPI_SUCCESS;
  return err_raise(R, NULL, MPI_ERR_GROUP, fn, "invalid group: %s",
                   group == MPI_GROUP_NULL ? "MPI_GROUP_NULL" : "freed, or not a group");
}

/* A new group of n world ranks (copied) as a handle. */
static MPI_Group make(st_rank *R, int n, const int *world) { return group_add(R, st_ranks_new(n, world)); }

/* ==== queries ============================================================= */

int PMPI_Group_size(MPI_Group group, int *size) {
  static const char fn[] = "MPI_Group_size";
  st_rank *R = st_need(fn);
  st_ranks *g;
  int rc = check_group(R, fn, group, &g);
  if (rc) return rc;
  *size = g->n;
  return MPI_SUCCESS;
}

int PMPI_Group_rank(MPI_Group group, int *rank) {
  static const char fn[] = "MPI_Group_rank";
  st_rank *R = st_need(fn);
  st_ranks *g;
  int rc = check_group(R, fn, group, &g);
  if (rc) return rc;
  int r = st_ranks_find(g, R->wrank);
  *rank = r < 0 ? MPI_UNDEFINED : r;
  return MPI_SUCCESS;
}

int PMPI_Group_translate_ranks(MPI_Group group1, int n, const int ranks1[], MPI_Group group2, int ranks2[]) {
  static const char fn[] = "MPI_Group_translate_ranks";
  st_rank *R = st_need(fn);
  st_ranks *a, *b;
  int rc = check_group(R, fn, group1, &a);
  if (rc || (rc = check_group(R, fn, group2, &b))) return rc;
  if (n < 0) return err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid count %d", n);
  for (int i = 0; i < n; i++) {
    if (ranks1[i] == MPI_PROC_NULL) continue;
    if (ranks1[i] < 0 || ranks1[i] >= a->n)
      return err_raise(R, NULL, MPI_ERR_RANK, fn, "invalid rank %d (the group has %d)", ranks1[i], a->n);
  }
  for (int i = 0; i < n; i++) {
    if (ranks1[i] == MPI_PROC_NULL) {
      ranks2[i] = MPI_PROC_NULL;
      continue;
    }
    int r = st_ranks_find(b, member(a, ranks1[i]));
    ranks2[i] = r < 0 ? MPI_UNDEFINED : r;
  }
  return MPI_SUCCESS;
}

int PMPI_Group_compare(MPI_Group group1, MPI_Group group2, int *result) {
  static const char fn[] = "MPI_Group_compare";
  st_rank *R = st_need(fn);
  st_ranks *a, *b;
  int rc = check_group(R, fn, group1, &a);
  if (rc || (rc = check_group(R, fn, group2, &b))) return rc;
  static const int verdict[3] = {MPI_UNEQUAL, MPI_SIMILAR, MPI_IDENT};
  *result = verdict[group_ranks_same(a, b)];
  return MPI_SUCCESS;
}

/* ==== new groups ========================================================== */

/* ranks[0..n-1]: valid and distinct ranks of g?  MPI_SUCCESS or raised. */
static int check_ranks(st_rank *R, const char *fn, const st_ranks *g, int n, const int *ranks) {
  if (n < 0 || n > g->n)
    return err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid count %d (the group has %d ranks)", n, g->n);
  unsigned char *seen = xcalloc((size_t)g->n + 1, 1);
  for (int i = 0; i < n; i++) {
    int r = ranks[i];
    if (r < 0 || r >= g->n || seen[r]) {
      free(seen);
      return err_raise(R, NULL, MPI_ERR_RANK, fn, "rank %d %s", r,
                       r < 0 || r >= g->n ? "is not in the group" : "is named twice");
    }
    seen[r] = 1;
  }
  free(seen);
  return MPI_SUCCESS;
}

/* The group of g's ranks listed (excl 0) or of the others (excl 1), the
 * ranks already checked. */
static MPI_Group incl_excl(st_rank *R, const st_ranks *g, int excl, int n, const int ranks[]) {
  int *w = xmallocarray((size_t)(excl ? g->n : n) + 1, sizeof *w), m = 0;
  if (!excl) {
    for (int i = 0; i < n; i++) w[m++] = member(g, ranks[i]);
  } else {
    unsigned char *out = xcalloc((size_t)g->n + 1, 1);
    for (int i = 0; i < n; i++) out[ranks[i]] = 1;
    for (int i = 0; i < g->n; i++)
      if (!out[i]) w[m++] = member(g, i);
    free(out);
  }
  MPI_Group ng = make(R, m, w);
  free(w);
  return ng;
}

static int listed(const char *fn, int excl, MPI_Group group, int n, const int ranks[], MPI_Group *newgroup) {
  st_rank *R = st_need(fn);
  st_ranks *g;
  int rc = check_group(R, fn, group, &g);
  if (rc || (rc = check_ranks(R, fn, g, n, ranks))) return rc;
  *newgroup = incl_excl(R, g, excl, n, ranks);
  return MPI_SUCCESS;
}

int PMPI_Group_incl(MPI_Group group, int n, const int ranks[], MPI_Group *newgroup) {
  return listed("MPI_Group_incl", 0, group, n, ranks, newgroup);
}

int PMPI_Group_excl(MPI_Group group, int n, const int ranks[], MPI_Group *newgroup) {
  return listed("MPI_Group_excl", 1, group, n, ranks, newgroup);
}

/* The ranks of n (first, last, stride) triplets, each a valid rank of g
 * (MPI 3.1 section 6.3.2); NULL and *rc raised if not. */
static int *expand(st_rank *R, const char *fn, const st_ranks *g, int n, int ranges[][3], int *m, int *rc) {
  *m = 0;
  *rc = MPI_SUCCESS;
  long total = 0;
  if (n < 0) {
    *rc = err_raise(R, NULL, MPI_ERR_ARG, fn, "invalid count %d", n);
    return NULL;
  }
  for (int i = 0; i < n; i++) {
    int first = ranges[i][0], last = ranges[i][1], stride = ranges[i][2];
    if (stride == 0 || first < 0 || first >= g->n || last < 0 || last >= g->n ||
        (stride > 0 && first > last) || (stride < 0 && first < last)) {
      *rc = err_raise(R, NULL, MPI_ERR_RANK, fn, "invalid range (%d, %d, %d) of a group of %d ranks", first,
                      last, stride, g->n);
      return NULL;
    }
    total += (last - first) / stride + 1;
    if (total > g->n) {
      *rc = err_raise(R, NULL, MPI_ERR_RANK, fn, "the ranges name more ranks than the group has (%d)", g->n);
      return NULL;
    }
  }
  int *r = xmallocarray((size_t)total + 1, sizeof *r);
  for (int i = 0; i < n; i++)
    for (int k = ranges[i][0]; ranges[i][2] > 0 ? k <= ranges[i][1] : k >= ranges[i][1]; k += ranges[i][2])
      r[(*m)++] = k;
  return r;
}

static int ranged(const char *fn, int excl, MPI_Group group, int n, int ranges[][3], MPI_Group *newgroup) {
  st_rank *R = st_need(fn);
  st_ranks *g;
  int rc = check_group(R, fn, group, &g), m;
  if (rc) return rc;
  int *r = expand(R, fn, g, n, ranges, &m, &rc);
  if (!r) return rc;
  if (!(rc = check_ranks(R, fn, g, m, r))) *newgroup = incl_excl(R, g, excl, m, r);
  free(r);
  return rc;
}

int PMPI_Group_range_incl(MPI_Group group, int n, int ranges[][3], MPI_Group *newgroup) {
  return ranged("MPI_Group_range_incl", 0, group, n, ranges, newgroup);
}

int PMPI_Group_range_excl(MPI_Group group, int n, int ranges[][3], MPI_Group *newgroup) {
  return ranged("MPI_Group_range_excl", 1, group, n, ranges, newgroup);
}

/* Union, intersection, difference (MPI 3.1 section 6.3.2): the first
 * group's ranks in its order, then (union) the second's not in it. */
enum { G_UNION, G_INTER, G_DIFF };

static int combine(const char *fn, int how, MPI_Group group1, MPI_Group group2, MPI_Group *newgroup) {
  st_rank *R = st_need(fn);
  st_ranks *a, *b;
  int rc = check_group(R, fn, group1, &a);
  if (rc || (rc = check_group(R, fn, group2, &b))) return rc;
  int *w = xmallocarray((size_t)a->n + (size_t)b->n + 1, sizeof *w), m = 0;
  for (int i = 0; i < a->n; i++) {
    int in_b = st_ranks_find(b, member(a, i)) >= 0;
    if (how == G_UNION || (how == G_INTER && in_b) || (how == G_DIFF && !in_b)) w[m++] = member(a, i);
  }
  if (how == G_UNION)
    for (int i = 0; i < b->n; i++)
      if (st_ranks_find(a, member(b, i)) < 0) w[m++] = member(b, i);
  *newgroup = make(R, m, w);
  free(w);
  return MPI_SUCCESS;
}

int PMPI_Group_union(MPI_Group group1, MPI_Group group2, MPI_Group *newgroup) {
  return combine("MPI_Group_union", G_UNION, group1, group2, newgroup);
}

int PMPI_Group_intersection(MPI_Group group1, MPI_Group group2, MPI_Group *newgroup) {
  return combine("MPI_Group_intersection", G_INTER, group1, group2, newgroup);
}

int PMPI_Group_difference(MPI_Group group1, MPI_Group group2, MPI_Group *newgroup) {
  return combine("MPI_Group_difference", G_DIFF, group1, group2, newgroup);
}

int PMPI_Group_free(MPI_Group *group) {
  static const char fn[] = "MPI_Group_free";
  st_rank *R = st_need(fn);
  if (!group) return err_raise(R, NULL, MPI_ERR_ARG, fn, "NULL group argument");
  st_ranks *g;
  int rc = check_group(R, fn, *group, &g);
  if (rc) return rc;
  if (*group != MPI_GROUP_EMPTY) {
    R->groups[(unsigned)*group & H_SLOT_MASK] = NULL;
    st_ranks_drop(g);
  }
  *group = MPI_GROUP_NULL;
  return MPI_SUCCESS;
}
