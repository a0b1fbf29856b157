/* comm_groups.c -- communicators and groups, checked by themselves on any
 * number of ranks >= 2: a duplicate's messages never meet the original's
 * (not even with MPI_ANY_SOURCE and MPI_ANY_TAG), Comm_split's ranks by
 * color and key, Comm_create and Comm_create_group, Comm_compare, the
 * group calls against their definitions computed here by brute force,
 * names and MPI_TAG_UB, and thousands of communicators made and freed in
 * turn (contexts are reused). */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "mtest.h"

/* A message around the ring of comm, checked by the sender's world rank. */
static void cg_ring(mtest *t, MPI_Comm comm, const char *what, const int *world_of) {
  int r, n;
  MPI_Comm_rank(comm, &r);
  MPI_Comm_size(comm, &n);
  int right = (r + 1) % n, left = (r + n - 1) % n, out = t->rank, in = -1;
  MPI_Status st;
  MPI_Sendrecv(&out, 1, MPI_INT, right, 1, &in, 1, MPI_INT, left, 1, comm, &st);
  MCHECK(t, in == world_of[left] && st.MPI_SOURCE == left, "%s ring: %d from %d (%d due)", what, in,
         st.MPI_SOURCE, world_of[left]);
}

static void cg_dup(mtest *t) {
  MPI_Comm dup;
  MPI_Comm_dup(MPI_COMM_WORLD, &dup);
  int r = -1, n = -1, cmp = -1;
  MPI_Comm_rank(dup, &r);
  MPI_Comm_size(dup, &n);
  MCHECK(t, r == t->rank && n == t->size, "dup: rank %d size %d", r, n);
  MPI_Comm_compare(MPI_COMM_WORLD, dup, &cmp);
  MCHECK(t, cmp == MPI_CONGRUENT, "compare with a dup: %d", cmp);
  MPI_Comm_compare(dup, dup, &cmp);
  MCHECK(t, cmp == MPI_IDENT, "compare with itself: %d", cmp);
  /* Rank 0 sends rank 1 on MPI_COMM_WORLD first, then on the dup: a
   * receive on the dup from anyone with any tag takes the dup's. */
  if (t->rank == 0) {
    int a = 1, b = 2;
    MPI_Send(&a, 1, MPI_INT, 1, 5, MPI_COMM_WORLD);
    MPI_Send(&b, 1, MPI_INT, 1, 5, dup);
  } else if (t->rank == 1) {
    int a = 0, b = 0;
    MPI_Status st;
    MPI_Recv(&b, 1, MPI_INT, MPI_ANY_SOURCE, MPI_ANY_TAG, dup, &st);
    MPI_Recv(&a, 1, MPI_INT, MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MCHECK(t, a == 1 && b == 2 && st.MPI_SOURCE == 0, "communicators apart: %d %d", a, b);
  }
  int *ident = malloc((size_t)t->size * sizeof *ident);
  for (int i = 0; i < t->size; i++) ident[i] = i;
  cg_ring(t, dup, "dup", ident);
  /* A dup of the dup, and the handler and name rules. */
  MPI_Comm dup2;
  MPI_Comm_dup(dup, &dup2);
  cg_ring(t, dup2, "dup of a dup", ident);
  MPI_Comm_free(&dup2);
  MCHECK(t, dup2 == MPI_COMM_NULL, "freed communicator not nulled");
  MPI_Comm_free(&dup);
  free(ident);
}

/* Split by parity, keys reversing the order: a rank's new rank is the
 * number of ranks of its parity above it. */
static void cg_split(mtest *t) {
  MPI_Comm half;
  MPI_Comm_split(MPI_COMM_WORLD, t->rank % 2, -t->rank, &half);
  int r = -1, n = -1, want_n = 0, want_r = 0;
  for (int i = 0; i < t->size; i++) {
    want_n += i % 2 == t->rank % 2;
    want_r += i % 2 == t->rank % 2 && i > t->rank;
  }
  MPI_Comm_rank(half, &r);
  MPI_Comm_size(half, &n);
  MCHECK(t, r == want_r && n == want_n, "split: rank %d size %d (%d %d due)", r, n, want_r, want_n);
  int *world_of = malloc((size_t)n * sizeof *world_of), k = 0;
  for (int i = t->size - 1; i >= 0; i--)
    if (i % 2 == t->rank % 2) world_of[k++] = i;
  cg_ring(t, half, "split", world_of);
  /* A split of the split: ranks whose new rank is below 2 only. */
  MPI_Comm sub;
  MPI_Comm_split(half, r < 2 ? 0 : MPI_UNDEFINED, r, &sub);
  if (r < 2) {
    int sn = -1;
    MPI_Comm_size(sub, &sn);
    MCHECK(t, sn == (n < 2 ? n : 2), "split of a split: size %d", sn);
    cg_ring(t, sub, "split of a split", world_of);
    MPI_Comm_free(&sub);
  } else {
    MCHECK(t, sub == MPI_COMM_NULL, "MPI_UNDEFINED gave a communicator");
  }
  free(world_of);
  int cmp = -1;
  MPI_Comm_compare(MPI_COMM_WORLD, half, &cmp);
  MCHECK(t, cmp == MPI_UNEQUAL, "compare with a half: %d", cmp);
  MPI_Comm_free(&half);
  /* One color, keys reversed: the same ranks in another order. */
  MPI_Comm rev;
  MPI_Comm_split(MPI_COMM_WORLD, 7, t->size - t->rank, &rev);
  MPI_Comm_rank(rev, &r);
  MPI_Comm_compare(MPI_COMM_WORLD, rev, &cmp);
  MCHECK(t, r == t->size - 1 - t->rank && cmp == MPI_SIMILAR, "reversed: rank %d compare %d", r, cmp);
  MPI_Comm_free(&rev);
}

/* A brute-force group: world ranks in order. */
typedef struct {
  int n;
  int w[64];
} cg_set;

static int cg_has(const cg_set *s, int w) {
  for (int i = 0; i < s->n; i++)
    if (s->w[i] == w) return 1;
  return 0;
}

/* Does group g hold exactly s, in s's order? */
static int cg_same(MPI_Group g, const cg_set *s, MPI_Group world) {
  int n = -1;
  MPI_Group_size(g, &n);
  if (n != s->n) return 0;
  for (int i = 0; i < n; i++) {
    int w = -1;
    MPI_Group_translate_ranks(g, 1, &i, world, &w);
    if (w != s->w[i]) return 0;
  }
  return 1;
}

static void cg_groups(mtest *t) {
  if (t->size > 64) return;
  MPI_Group world, evens, odds, low, u, x, d, r;
  MPI_Comm_group(MPI_COMM_WORLD, &world);
  int n = -1, me = -1;
  MPI_Group_size(world, &n);
  MPI_Group_rank(world, &me);
  MCHECK(t, n == t->size && me == t->rank, "world group: %d %d", n, me);
  cg_set E = {0, {0}}, O = {0, {0}}, L = {0, {0}}, U = {0, {0}}, X = {0, {0}}, D = {0, {0}};
  int ev[64], lo[64], nlo = (t->size + 2) / 3;
  for (int i = 0; i < t->size; i++) {
    if (i % 2 == 0) ev[E.n] = i, E.w[E.n++] = i;
    else O.w[O.n++] = i;
  }
  for (int i = 0; i < nlo; i++) lo[i] = nlo - 1 - i, L.w[L.n++] = nlo - 1 - i;   /* reversed */
  MPI_Group_incl(world, E.n, ev, &evens);
  MPI_Group_excl(world, E.n, ev, &odds);
  MPI_Group_incl(world, nlo, lo, &low);
  /* union: L's order, then evens not in L; intersection: L's order, those
   * even; difference: L's, those odd. */
  for (int i = 0; i < L.n; i++) U.w[U.n++] = L.w[i];
  for (int i = 0; i < E.n; i++)
    if (!cg_has(&L, E.w[i])) U.w[U.n++] = E.w[i];
  for (int i = 0; i < L.n; i++) {
    if (cg_has(&E, L.w[i])) X.w[X.n++] = L.w[i];
    else D.w[D.n++] = L.w[i];
  }
  MPI_Group_union(low, evens, &u);
  MPI_Group_intersection(low, evens, &x);
  MPI_Group_difference(low, evens, &d);
  MCHECK(t, cg_same(evens, &E, world) && cg_same(odds, &O, world) && cg_same(low, &L, world),
         "incl, excl");
  MCHECK(t, cg_same(u, &U, world) && cg_same(x, &X, world) && cg_same(d, &D, world),
         "union, intersection, difference");
  int ranges[1][3] = {{0, t->size - 1, 2}}, cmp = -1;
  MPI_Group_range_incl(world, 1, ranges, &r);
  MPI_Group_compare(r, evens, &cmp);
  MCHECK(t, cmp == MPI_IDENT, "range_incl of the evens: %d", cmp);
  MPI_Group_compare(low, world, &cmp);
  MCHECK(t, cmp == (nlo == t->size ? MPI_SIMILAR : MPI_UNEQUAL) || (nlo == 1 && t->size == 1), "compare: %d", cmp);
  MPI_Group_rank(evens, &me);
  MCHECK(t, me == (t->rank % 2 == 0 ? t->rank / 2 : MPI_UNDEFINED), "rank in the evens: %d", me);
  /* Comm_create from the evens: the odd ranks get MPI_COMM_NULL. */
  MPI_Comm ce, cge;
  MPI_Comm_create(MPI_COMM_WORLD, evens, &ce);
  if (t->rank % 2 == 0) {
    int cr = -1, cn = -1;
    MPI_Comm_rank(ce, &cr);
    MPI_Comm_size(ce, &cn);
    MCHECK(t, cr == t->rank / 2 && cn == E.n, "comm_create: %d %d", cr, cn);
    cg_ring(t, ce, "comm_create", E.w);
    MPI_Comm_free(&ce);
    /* Comm_create_group: only the evens take part. */
    MPI_Comm_create_group(MPI_COMM_WORLD, evens, 9, &cge);
    MPI_Comm_rank(cge, &cr);
    MCHECK(t, cr == t->rank / 2, "comm_create_group: %d", cr);
    cg_ring(t, cge, "comm_create_group", E.w);
    MPI_Comm_free(&cge);
  } else {
    MCHECK(t, ce == MPI_COMM_NULL, "comm_create outside the group");
  }
  MPI_Group g[8] = {world, evens, odds, low, u, x, d, r};
  for (int i = 0; i < 8; i++) MPI_Group_free(&g[i]);
  MCHECK(t, g[0] == MPI_GROUP_NULL, "freed group not nulled");
}

/* Many communicators in turn: each dup'ed, used and freed. */
static void cg_many(mtest *t) {
  enum { ROUNDS = 3000 };
  int bad = 0;
  for (int i = 0; i < ROUNDS; i++) {
    MPI_Comm c;
    MPI_Comm_dup(MPI_COMM_WORLD, &c);
    int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size, in = -1, out = i;
    MPI_Sendrecv(&out, 1, MPI_INT, right, 0, &in, 1, MPI_INT, left, 0, c, MPI_STATUS_IGNORE);
    bad += in != i;
    MPI_Comm_free(&c);
  }
  MCHECK(t, bad == 0, "%d of %d communicators made and freed in turn carried a wrong message", bad, ROUNDS);
  /* Sixty at once. */
  MPI_Comm c[60];
  for (int i = 0; i < 60; i++) MPI_Comm_dup(i ? c[i - 1] : MPI_COMM_WORLD, &c[i]);
  bad = 0;
  for (int i = 59; i >= 0; i--) {
    int right = (t->rank + 1) % t->size, left = (t->rank + t->size - 1) % t->size, in = -1, out = i;
    MPI_Sendrecv(&out, 1, MPI_INT, right, 3, &in, 1, MPI_INT, left, 3, c[i], MPI_STATUS_IGNORE);
    bad += in != i;
  }
  for (int i = 0; i < 60; i++) MPI_Comm_free(&c[i]);
  MCHECK(t, bad == 0, "%d of 60 communicators at once carried a wrong message", bad);
}

static void cg_names(mtest *t) {
  char name[MPI_MAX_OBJECT_NAME];
  int len = -1, flag = 0, *ub = NULL;
  MPI_Comm_get_name(MPI_COMM_WORLD, name, &len);
  MCHECK(t, strcmp(name, "MPI_COMM_WORLD") == 0 && len == 14, "world's name: %s", name);
  MPI_Comm dup;
  MPI_Comm_dup(MPI_COMM_SELF, &dup);
  MPI_Comm_set_name(dup, "mine");
  MPI_Comm_get_name(dup, name, &len);
  MCHECK(t, strcmp(name, "mine") == 0 && len == 4, "set name: %s", name);
  MPI_Comm_free(&dup);
  MPI_Comm_get_attr(MPI_COMM_WORLD, MPI_TAG_UB, &ub, &flag);
  MCHECK(t, flag && ub && *ub >= 32767, "MPI_TAG_UB: %d", ub ? *ub : -1);
}

int main(int argc, char **argv) {
  static const mtest_fn checks[] = {cg_dup, cg_split, cg_groups, cg_many, cg_names, NULL};
  return mtest_main(&argc, &argv, "comm_groups", 2, 0, checks);
}
