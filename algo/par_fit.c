/* par_fit.c -- --alloc fit: groups capped at what their bands can use
 * (par_fit.h; sections 6, 7.1, 7.2, 8 and 9). */
#include "algo/par_fit.h"

#include "algo/split.h"
#include "algo/tiling.h"

int par_fit_cap(par_master_ctx *M, int lo, int hi, const gpath *U, const gpath *L, int p) {
  if (lo >= 0 && hi - lo < 2) return 0;   /* no paths */
  int s = lo < 0 ? 0 : tiling_mid(lo, hi);
  int rc = par_master_charge(M, (uint64_t)M->T + 1);
  if (rc < 0) return par_master_fail(M, rc, "par_master_charge");
  int use = split_usable(M->m, M->n, s, U, L, M->arg->opt.min_diag);
  return p < use ? p : use;
}

int par_fit_split(par_master_ctx *M, const par_group *G, const gpath *P, int *nb, int *na) {
  int cb = par_fit_cap(M, G->mid, G->hi, P, G->L, G->p);
  int ca = par_fit_cap(M, G->lo, G->mid, G->U, P, G->p);
  if (cb < 0 || ca < 0) return -1;
  /* Surplus moves to the sibling as far as the sibling can use it. */
  if (*nb > cb && *na < ca) {
    int x = *nb - cb < ca - *na ? *nb - cb : ca - *na;
    *nb -= x, *na += x;
  } else if (*na > ca && *nb < cb) {
    int x = *na - ca < cb - *nb ? *na - ca : cb - *nb;
    *na -= x, *nb += x;
  }
  return 0;
}
