/* stack.c -- the stack tiler: slices, junctions, bridges, bands, caps, mesh.
 *
 *   slice k+1   ----- C -----------          a 2-1 junction: A and B are
 *                 /         \                joined by a bridge into one
 *   slice k     - A -  ===  - B -            composite, tiled with C exactly
 *
 * Every phase is a set of independent jobs on the pool (pool.h), written by
 * index; refusals are taken from the lowest job that has one, so that the
 * message, like the output, does not depend on the threads. */
#include "surface/stack.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "surface/bridge.h"
#include "surface/ends.h"
#include "surface/follow.h"
#include "algo/kernel.h"
#include "surface/match.h"
#include "surface/pool.h"
#include "surface/slices.h"
#include "algo/tiling.h"
#include "surface/unpinch.h"
#include "util/xmem.h"

struct stack_surface {
  mesh me;
  int nrows;
  stack_row *rows;
  int npairs;
  par_pair *pairs;
  int ncomp;
  manifold_component *comp;
  double cost, area, volume;   /* the whole surface's (stack_totals) */
  stack_joins joins;
  char rule[40];
};

typedef struct {
  int slice;
  const junction *j;
  composite lo, hi;
  int followed;       /* a 1-1 band tiled on its aligned pair (follow.h): fa, fb */
  follow_side fa, fb;
  double shadow;      /* the weight of the tiles' shadows (follow_shadow), or 0 */
  int solved;         /* t holds the exact tiler's solution already (follow_shadow) */
  const vec2 *P, *Q;  /* the pair the tiler sees: lo.pt and hi.pt, or fa.pt and fb.pt */
  int np, nq;
  tiling t;
  double cost;        /* its path's true cost (tiling_path_cost), scaled as the slices */
  char *err;
  int ntri;
  int (*tri)[3];      /* input ids >= 0; -1-s: Steiner s of lo, then of hi */
  double area, volume;
  int pinched;        /* the optimum used a span twice: 1 replaced by the best
                         path that does not (unpinch.h), 2 too large to */
  double pinched_cost;   /* the optimum's cost */
  int span[2];        /* the span it used twice: points of lo and hi (tiling_repeated_spans) */
} band;

typedef struct {
  const slices *sl;
  const stack_options *o;
  const char *name;
  int threads;
  junctions *js;       /* between slices k and k+1 */
  band *b;             /* the bands: junctions with contours on both sides */
  int nb;
  unsigned char *up, *down;   /* contour c has a band above, below */
  vec3 *verts;         /* the input vertices' positions */
  end_region *ends;    /* with caps: the regions to close, and their caps */
  end_cap *caps;
  int nends;
  atomic_int tiled;    /* bands tiled so far, for o->progress */
  int deg;             /* the cost's degree: 1 span (a length), 2 area */
  match_opts mo;       /* the joining rule, at the working scale */
  double half;         /* a stack of one slice: half the slab's thickness (working scale) */
  char joinopt[48];    /* the --join option that made nearest joins, for notes */
} work;

/* A value of degree d (1 a length, 2 an area, 3 a volume) at the working
 * scale, in the file's units: one rounding, so exactly 2^(d k) times the
 * unit-scale value for a stack scaled by 2^k (inf or 0 beyond a double). */
static double unscale(const slices *sl, double v, int d) { return geom_ldexp(v, d * sl->scale); }

static void match_job(void *ud, int k) {
  work *w = ud;
  match_slices(w->sl, k, &w->mo, &w->js[k]);
}

/* The pair the tiler sees: a 1-1 band's aligned pair (follow.h), unless
 * the paper's plain band on the contours as they lie was asked for; an n-m
 * band's composites as they lie. */
static void pair_of(const work *w, band *b) {
  b->P = b->lo.pt, b->np = b->lo.n, b->Q = b->hi.pt, b->nq = b->hi.n;
  if (w->o->band == STACK_BAND_PLAIN || b->j->nlo != 1 || b->j->nhi != 1) return;
  follow_pair(b->lo.pt, b->lo.n, b->hi.pt, b->hi.n, &b->fa, &b->fb);
  b->followed = 1;
  b->P = b->fa.pt, b->np = b->fa.n, b->Q = b->fb.pt, b->nq = b->fb.n;
  b->shadow = follow_shadow(&b->fa, &b->fb, b->lo.pt, b->hi.pt, w->sl->z[b->slice], w->sl->z[b->slice + 1],
                            w->o->kind, &b->t);
  b->solved = 1;
}

static void bridge_job(void *ud, int i) {
  work *w = ud;
  band *b = &w->b[i];
  const slices *sl = w->sl;
  int k = b->slice;
  double dz = sl->z[k + 1] - sl->z[k];
  char err[600];
  /* The bridges' vertices halfway to the partner slice; a third of the way
   * when both sides have bridges, so the two never meet. */
  double lo_lift = dz * (b->j->nhi > 1 ? 1.0 / 3 : 0.5), hi_lift = -dz * (b->j->nlo > 1 ? 1.0 / 3 : 0.5);
  if (bridge_join(sl, b->j->lo, b->j->nlo, k + 1, lo_lift, w->name, &b->lo, err, sizeof err) != 0 ||
      bridge_join(sl, b->j->hi, b->j->nhi, k, hi_lift, w->name, &b->hi, err, sizeof err) != 0)
    b->err = xstrdup(err);
  else
    pair_of(w, b);
}

static void tile_job(void *ud, int i) {
  work *w = ud;
  band *b = &w->b[i];
  const slices *sl = w->sl;
  if (!b->solved)
    tiling_solve_shadow(b->P, b->np, sl->z[b->slice], b->Q, b->nq, sl->z[b->slice + 1], w->o->kind, b->shadow,
                        -1, &b->t);
  if (w->o->progress) w->o->progress(w->o->progress_ud, atomic_fetch_add(&w->tiled, 1) + 1, w->nb);
}

/* The hi side's Steiner vertices come after the lo side's. */
static int hi_id(const band *b, int id) { return id >= 0 ? id : id - b->lo.nsteiner; }

static vec3 band_vertex(const work *w, const band *b, int id) {
  if (id >= 0) return w->verts[id];
  int s = -1 - id;
  return s < b->lo.nsteiner ? b->lo.steiner[s] : b->hi.steiner[s - b->lo.nsteiner];
}

static vec3 sub3(vec3 a, vec3 b) { return (vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }

static double vmax(vec3 v, double m) { return fmax(m, fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)))); }
static vec3 scl(vec3 v, int e) { return (vec3){geom_ldexp(v.x, -e), geom_ldexp(v.y, -e), geom_ldexp(v.z, -e)}; }

static double tri_area(vec3 a, vec3 b, vec3 c) {
  vec3 u = sub3(b, a), v = sub3(c, a);
  double x = u.y * v.z - u.z * v.y, y = u.z * v.x - u.x * v.z, z = u.x * v.y - u.y * v.x;
  return 0.5 * sqrt(x * x + y * y + z * z);
}

/* The triangle's share of the volume (divergence theorem) about o. */
static double tri_vol(vec3 a, vec3 b, vec3 c, vec3 o) {
  a = sub3(a, o), b = sub3(b, o), c = sub3(c, o);
  return (a.x * (b.y * c.z - b.z * c.y) + a.y * (b.z * c.x - b.x * c.z) + a.z * (b.x * c.y - b.y * c.x)) / 6;
}

/* Is a triangle of the band with a bridge vertex degenerate in space (its
 * area at most 1e-9 times its longest edge squared, well above the mesh
 * checker's 1e-12)?  A tile from a bridge vertex m1 over the middle of a0 b1
 * to a0 and to a partner vertex straight over b1 lies on one line when m1 is
 * lifted halfway: pixel-traced contours repeat their points slice to slice. */
static int degenerate_bridge_tile(const work *w, const band *b) {
  for (int k = 0; k < b->ntri; k++) {
    if (b->tri[k][0] >= 0 && b->tri[k][1] >= 0 && b->tri[k][2] >= 0) continue;
    vec3 p = band_vertex(w, b, b->tri[k][0]), q = band_vertex(w, b, b->tri[k][1]), r = band_vertex(w, b, b->tri[k][2]);
    vec3 u = sub3(q, p), v = sub3(r, p), x = sub3(r, q);
    double cx = u.y * v.z - u.z * v.y, cy = u.z * v.x - u.x * v.z, cz = u.x * v.y - u.y * v.x;
    double e = fmax(u.x * u.x + u.y * u.y + u.z * u.z, fmax(v.x * v.x + v.y * v.y + v.z * v.z, x.x * x.x + x.y * x.y + x.z * x.z));
    if (sqrt(cx * cx + cy * cy + cz * cz) <= 1e-9 * e) return 1;
  }
  return 0;
}

/* The bridge vertices at the fraction f of the way to the partner slice. */
static void lift_bridges(const work *w, band *b, double f) {
  const slices *sl = w->sl;
  double z0 = sl->z[b->slice], z1 = sl->z[b->slice + 1], dz = z1 - z0;
  for (int s = 0; s < b->lo.nsteiner; s++) b->lo.steiner[s].z = z0 + dz * f;
  for (int s = 0; s < b->hi.nsteiner; s++) b->hi.steiner[s].z = z1 - dz * f;
}

/* The band's triangles from its tiling (tiling_tiles: the edge on P = lo or
 * Q = hi, the apex on the other), then the bridges' fill; its area, and the
 * volume of the slab it closes with the two slices' regions.  Where a tile
 * with a bridge vertex would be degenerate, the bridge vertices are lifted
 * to another height (below half the spacing, so that the two sides' never
 * meet): the same tiling, the same topology. */
static void mesh_job(void *ud, int i) {
  work *w = ud;
  band *b = &w->b[i];
  const slices *sl = w->sl;
  if (unpinch_repeats(&b->t)) {
    tiling t2;
    b->span[0] = b->span[1] = 0;
    tiling_repeated_spans(&b->t, &b->span, 1);
    b->pinched_cost = tiling_path_cost(&b->t, b->P, b->np, sl->z[b->slice], b->Q, b->nq, sl->z[b->slice + 1],
                                       w->o->kind);
    b->pinched = 2;
    if (unpinch_solve(b->P, b->np, sl->z[b->slice], b->Q, b->nq, sl->z[b->slice + 1], w->o->kind, b->shadow,
                      &t2) == 0) {
      t2.count.nodes += b->t.count.nodes;
      tiling_free(&b->t);
      b->t = t2;
      b->pinched = 1;
    }
  }
  b->cost = tiling_path_cost(&b->t, b->P, b->np, sl->z[b->slice], b->Q, b->nq, sl->z[b->slice + 1], w->o->kind);
  int steps = b->lo.n + b->hi.n;
  b->ntri = steps + b->lo.ntri + b->hi.ntri;
  b->tri = xmallocarray((size_t)b->ntri, sizeof *b->tri);
  int (*tile)[3] = xmallocarray((size_t)steps, sizeof *tile);
  unsigned char *on = xmalloc((size_t)steps);
  if (b->followed) follow_tiles(&b->t, &b->fa, &b->fb, tile, on);
  else tiling_tiles(&b->t, tile, on);
  int nt = 0;
  for (int k = 0; k < steps; k++) {
    /* Seen from outside, an edge of the lower contour with the apex above
     * runs its own way (material on its left); of the upper, backwards. */
    int xa, xb, y;
    if (on[k]) xa = hi_id(b, b->hi.id[tile[k][0]]), xb = hi_id(b, b->hi.id[tile[k][1]]), y = b->lo.id[tile[k][2]];
    else xa = b->lo.id[tile[k][0]], xb = b->lo.id[tile[k][1]], y = hi_id(b, b->hi.id[tile[k][2]]);
    if (!on[k]) b->tri[nt][0] = xa, b->tri[nt][1] = xb;
    else b->tri[nt][0] = xb, b->tri[nt][1] = xa;
    b->tri[nt++][2] = y;
  }
  free(tile);
  free(on);
  for (int k = 0; k < b->lo.ntri; k++, nt++) memcpy(b->tri[nt], b->lo.tri[k], sizeof b->tri[nt]);
  for (int k = 0; k < b->hi.ntri; k++, nt++)
    for (int e = 0; e < 3; e++) b->tri[nt][e] = hi_id(b, b->hi.tri[k][e]);
  static const double other_lift[] = {0.375, 0.25, 0.4375, 0.3125};
  for (int k = 0; k < 4 && b->lo.nsteiner + b->hi.nsteiner > 0 && degenerate_bridge_tile(w, b); k++)
    lift_bridges(w, b, other_lift[k]);
  /* Summed at the scale 2^-e that brings the band's largest coordinate into
   * [1/2, 1) and scaled back once: exact, the same bits as unscaled, and no
   * inf - inf = NaN at 1e300. */
  double z0 = sl->z[b->slice], z1 = sl->z[b->slice + 1], ahi = 0, mx = fmax(fabs(z0), fabs(z1));
  for (int k = 0; k < b->ntri; k++)
    for (int c = 0; c < 3; c++) mx = vmax(band_vertex(w, b, b->tri[k][c]), mx);
  int e = geom_scale_exp(mx);
  vec3 o = scl((vec3){sl->c[b->j->lo[0]].pt[0].x, sl->c[b->j->lo[0]].pt[0].y, z0}, e);
  double area = 0, volume = 0;
  for (int k = 0; k < b->ntri; k++) {
    vec3 p = scl(band_vertex(w, b, b->tri[k][0]), e), q = scl(band_vertex(w, b, b->tri[k][1]), e),
         r = scl(band_vertex(w, b, b->tri[k][2]), e);
    area += tri_area(p, q, r);
    volume += tri_vol(p, q, r, o);
  }
  for (int k = 0; k < b->j->nhi; k++) ahi += 0.5 * geom_area2_at(sl->c[b->j->hi[k]].pt, sl->c[b->j->hi[k]].n, e);
  volume += (geom_ldexp(z1, -e) - geom_ldexp(z0, -e)) * ahi / 3;
  b->area = ldexp(area, 2 * (e + sl->scale));
  b->volume = ldexp(volume, 3 * (e + sl->scale));
}

static void cap_job(void *ud, int i) {
  work *w = ud;
  ends_cap(w->sl, &w->ends[i], w->o->apex, w->half, &w->caps[i]);
}

static int *positions(const slices *sl, const int *cs, int n) {
  int *p = xmallocarray((size_t)n + 1, sizeof *p);
  for (int i = 0; i < n; i++) p[i] = sl->c[cs[i]].pos;
  return p;
}

/* The bands (junctions with contours on both sides), in order, and which
 * contours have a band above and below. */
static void plan_bands(work *w) {
  const slices *sl = w->sl;
  int nb = 0;
  for (int k = 0; k + 1 < sl->nslices; k++)
    for (int g = 0; g < w->js[k].n; g++) nb += w->js[k].j[g].nlo > 0 && w->js[k].j[g].nhi > 0;
  w->b = xcalloc((size_t)nb + 1, sizeof *w->b);
  w->up = xcalloc((size_t)sl->ncontours + 1, 1);
  w->down = xcalloc((size_t)sl->ncontours + 1, 1);
  for (int k = 0; k + 1 < sl->nslices; k++)
    for (int g = 0; g < w->js[k].n; g++) {
      const junction *j = &w->js[k].j[g];
      if (j->nlo == 0 || j->nhi == 0) continue;
      w->b[w->nb].slice = k;
      w->b[w->nb++].j = j;
      for (int x = 0; x < j->nlo; x++) w->up[j->lo[x]] = 1;
      for (int x = 0; x < j->nhi; x++) w->down[j->hi[x]] = 1;
    }
}

/* With a tiler, every band's tiling by it, every band in one call.  0, or -2
 * when the tiler failed. */
static int tile_bands(work *w, stack_surface *ss, char *err, size_t errlen) {
  const slices *sl = w->sl;
  int nb = w->nb, res = 0;
  ss->npairs = nb;
  ss->pairs = xcalloc((size_t)nb + 1, sizeof *ss->pairs);
  for (int i = 0; i < nb; i++) {
    par_pair *p = &ss->pairs[i];
    p->P = w->b[i].P, p->np = w->b[i].np, p->zp = sl->z[w->b[i].slice];
    p->Q = w->b[i].Q, p->nq = w->b[i].nq, p->zq = sl->z[w->b[i].slice + 1];
    p->shadow = w->b[i].shadow;
  }
  const stack_tiler *tl = w->o->tiler;
  if (tl->pairs(tl->ud, ss->pairs, nb, err, errlen) != 0) res = -2;
  for (int i = 0; i < nb; i++) {
    tiling_free(&w->b[i].t);   /* the exact tiler's, if follow_shadow solved it: the same path */
    w->b[i].t = ss->pairs[i].t;
    ss->pairs[i].t.col = NULL;
  }
  return res;
}

/* Without a tiler, a band from start to end in one job (its bridges, its exact
 * tiling, its triangles), and the caps as jobs of the same pool: no thread
 * waits at a barrier between the steps while another finishes a long one.
 * Jobs 0 .. nb-1 are the bands, nb .. nb+nends-1 the caps. */
static void whole_job(void *ud, int i) {
  work *w = ud;
  if (i >= w->nb) {
    cap_job(ud, i - w->nb);
    return;
  }
  bridge_job(ud, i);
  if (w->b[i].err) return;
  tile_job(ud, i);
  mesh_job(ud, i);
}

/* The bands biggest first (the product of their sides' points, bridges not
 * yet counted), then the caps. */
static void whole_run(work *w) {
  const slices *sl = w->sl;
  int nb = w->nb, n = nb + w->nends;
  double *size = xmallocarray((size_t)n + 1, sizeof *size);
  int *order = xmallocarray((size_t)n + 1, sizeof *order);
  for (int i = 0; i < nb; i++) {
    const junction *j = w->b[i].j;
    double lo = 0, hi = 0;
    for (int x = 0; x < j->nlo; x++) lo += sl->c[j->lo[x]].n;
    for (int x = 0; x < j->nhi; x++) hi += sl->c[j->hi[x]].n;
    size[i] = lo * hi;
  }
  pool_order(size, nb, order);
  for (int i = nb; i < n; i++) order[i] = i;
  pool_run(w->threads, n, order, whole_job, w);
  free(size);
  free(order);
}

/* The first band's error, in band order, into err: -1; else 0. */
static int first_error(const work *w, char *err, size_t errlen) {
  for (int i = 0; i < w->nb; i++)
    if (w->b[i].err) {
      snprintf(err, errlen, "%s", w->b[i].err);
      return -1;
    }
  return 0;
}

/* The made single link between slices k and k+1, or NULL. */
static const match_link *single_link(const junctions *js) {
  for (int i = 0; i < js->nlinks; i++)
    if (js->links[i].how == MATCH_LINK_SINGLE && !js->links[i].dropped) return &js->links[i];
  return NULL;
}

/* A link's gap in the file's units. */
static double gap_of(const work *w, const exactdist *g) { return unscale(w->sl, exactdist_value(g), 1); }

/* The joins' notes (stack.h): runs of single joins, nearest joins, dropped
 * joins, then each contour left unjoined. */
static void join_notes(const work *w) {
  const stack_options *o = w->o;
  const slices *sl = w->sl;
  FILE *f = o->notes;
  int ns = sl->nslices;
  for (int k = 0; k + 1 < ns;) {
    const match_link *l = single_link(&w->js[k]), *last = l, *x;
    if (!l) {
      k++;
      continue;
    }
    int k1 = k;
    double g0 = gap_of(w, &l->gap), g1 = g0;
    while (k1 + 2 < ns && (x = single_link(&w->js[k1 + 1])) != NULL) {
      double g = gap_of(w, &x->gap);
      g0 = fmin(g0, g), g1 = fmax(g1, g), last = x, k1++;
    }
    if (k1 == k)
      fprintf(f, "%s: %s:%d: joined to the contour at line %d (slice z=%s to z=%s) without overlap: "
              "one outer contour on each slice (--join single), gap %s\n", o->prefix, w->name,
              sl->c[l->a].line, sl->c[l->b].line, ARGS_G(unscale(sl, sl->z[k], 1)), ARGS_G(unscale(sl, sl->z[k + 1], 1)), ARGS_G(g0));
    else
      fprintf(f, "%s: %s:%d: joined to the contour above, and so on up to line %d (%d joins, slices z=%s "
              "to z=%s) without overlap: one outer contour on each slice (--join single), gaps %s to "
              "%s\n", o->prefix, w->name, sl->c[l->a].line, sl->c[last->b].line, k1 - k + 1,
              ARGS_G(unscale(sl, sl->z[k], 1)), ARGS_G(unscale(sl, sl->z[k1 + 1], 1)), ARGS_G(g0), ARGS_G(g1));
    k = k1 + 1;
  }
  for (int k = 0; k + 1 < ns; k++)
    for (int i = 0; i < w->js[k].nlinks; i++) {
      const match_link *l = &w->js[k].links[i];
      if (l->how == MATCH_LINK_SINGLE) continue;
      int from = l->how == MATCH_LINK_NEAREST ? l->from : l->a, to = l->a ^ l->b ^ from;
      if (l->dropped) {
        char why[120];
        if (l->how == MATCH_LINK_TOUCH) snprintf(why, sizeof why, "their regions touch");
        else if (l->how == MATCH_LINK_OVERLAP) snprintf(why, sizeof why, "their regions overlap");
        else snprintf(why, sizeof why, "its nearest there, gap %s, %s", ARGS_G(gap_of(w, &l->gap)), w->joinopt);
        fprintf(f, "%s: %s:%d: not joined to the contour at line %d on slice z=%s (%s): no bridges can "
                "join the contours of the junction it would make\n", o->prefix, w->name, sl->c[from].line,
                sl->c[to].line, ARGS_G(unscale(sl, sl->z[sl->c[to].slice], 1)), why);
      } else if (l->how == MATCH_LINK_NEAREST) {
        fprintf(f, "%s: %s:%d: joined to its nearest contour on slice z=%s, the contour at line %d, "
                "without overlap (%s), gap %s\n", o->prefix, w->name, sl->c[from].line,
                ARGS_G(unscale(sl, sl->z[sl->c[to].slice], 1)), sl->c[to].line, w->joinopt, ARGS_G(gap_of(w, &l->gap)));
      }
    }
  /* Each contour's ends, below and above, in one line. */
  const match_end **end[2] = {xcalloc((size_t)sl->ncontours + 1, sizeof(match_end *)),
                              xcalloc((size_t)sl->ncontours + 1, sizeof(match_end *))};
  for (int k = 0; k + 1 < ns; k++)
    for (int i = 0; i < w->js[k].nends; i++) {
      const match_end *e = &w->js[k].ends[i];
      end[sl->c[e->c].slice == k][e->c] = e;   /* [1]: the end above */
    }
  for (int c = 0; c < sl->ncontours; c++) {
    int n = (end[0][c] != NULL) + (end[1][c] != NULL), said = 0;
    if (!n) continue;
    fprintf(f, "%s: %s:%d: no partner for this contour (slice z=%s) on slice", o->prefix, w->name, sl->c[c].line,
            ARGS_G(unscale(sl, sl->z[sl->c[c].slice], 1)));
    for (int s = 0; s < 2; s++) {
      const match_end *e = end[s][c];
      if (!e) continue;
      int other = sl->c[c].slice + (s ? 1 : -1);
      if (n == 1)
        fprintf(f, " z=%s; nearest there: the contour at line %d, gap %s", ARGS_G(unscale(sl, sl->z[other], 1)),
                sl->c[e->nearest].line, ARGS_G(gap_of(w, &e->gap)));
      else
        fprintf(f, "%s z=%s (nearest: the contour at line %d, gap %s)", said++ ? " nor on slice" : "",
                ARGS_G(unscale(sl, sl->z[other], 1)), sl->c[e->nearest].line, ARGS_G(gap_of(w, &e->gap)));
    }
    fputc('\n', f);
  }
  free(end[0]), free(end[1]);
}

/* The joins' counts (stack_joins). */
static void count_joins(const work *w, stack_surface *ss) {
  for (int k = 0; k + 1 < w->sl->nslices; k++) {
    const junctions *js = &w->js[k];
    for (int i = 0; i < js->nlinks; i++) {
      if (js->links[i].dropped) ss->joins.dropped++;
      else if (js->links[i].how != MATCH_LINK_TOUCH && js->links[i].how != MATCH_LINK_OVERLAP) ss->joins.apart++;
    }
    ss->joins.unjoined += js->nends;
  }
  ss->joins.rule = ss->rule;
}

/* What the run changed or could not avoid: the joins, then band by band,
 * then cap by cap. */
static void print_notes(const work *w) {
  const stack_options *o = w->o;
  const slices *sl = w->sl;
  if (!o->notes) return;
  join_notes(w);
  for (int i = 0; i < w->nb; i++) {
    const band *b = &w->b[i];
    for (int side = 0; side < 2; side++) {
      const composite *c = side ? &b->hi : &b->lo;
      int k = b->slice + side;
      if (c->relaxed)
        fprintf(o->notes,
                "%s: %s:%d: no bridge from this contour to the contour at line %d on slice "
                "z=%s avoids the contours of slice z=%s; it crosses them in projection%s\n",
                o->prefix, w->name, c->relaxed_line[1], c->relaxed_line[0], ARGS_G(unscale(sl, sl->z[k], 1)),
                ARGS_G(unscale(sl, sl->z[side ? k - 1 : k + 1], 1)),
                c->relaxed > 1 ? " (and other bridges of the band too)" : "");
    }
  }
  for (int i = 0; i < w->nb; i++) {
    const band *b = &w->b[i];
    if (!b->pinched) continue;
    vec2 lo = b->lo.pt[b->followed ? b->fa.at[b->span[0]] : b->span[0]];
    vec2 hi = b->hi.pt[b->followed ? b->fb.at[b->span[1]] : b->span[1]];
    fprintf(o->notes,
            "%s: %s:%d: the band from this contour (slice z=%s) to the slice z=%s: its optimum "
            "(cost %s) uses the span from (%s %s) to (%s %s) twice, a pinched, "
            "non-manifold band; %s\n",
            o->prefix, w->name, sl->c[b->j->lo[0]].line, ARGS_G(unscale(sl, sl->z[b->slice], 1)),
            ARGS_G(unscale(sl, sl->z[b->slice + 1], 1)), ARGS_G(unscale(sl, b->pinched_cost, w->deg)),
            ARGS_G(unscale(sl, lo.x, 1)), ARGS_G(unscale(sl, lo.y, 1)), ARGS_G(unscale(sl, hi.x, 1)),
            ARGS_G(unscale(sl, hi.y, 1)),
            b->pinched == 1 ? "the cheapest path that does not is used" : "too large to replace; kept");
  }
  for (int i = 0; i < w->nends; i++)
    if (sl->nslices > 1 && w->ends[i].isolated && w->caps[i].nnew > 1)
      fprintf(o->notes,
              "%s: %s:%d: the contour is alone (no partner on either slice next to it) and "
              "has no point to cap it from: a slab a third of a slice thick\n",
              o->prefix, w->name, sl->c[w->ends[i].outer].line);
}

/* The mesh and the rows: input vertices, bridge vertices band by band, the
 * caps' new vertices; the bands' triangles, then the caps'. */
static void assemble(const work *w, stack_surface *ss) {
  const slices *sl = w->sl;
  mesh *me = &ss->me;
  int nv = sl->nverts;
  for (int i = 0; i < w->nb; i++) nv += w->b[i].lo.nsteiner + w->b[i].hi.nsteiner;
  for (int i = 0; i < w->nends; i++) nv += w->caps[i].nnew;
  me->nv = nv;
  me->v = xmallocarray((size_t)nv + 1, sizeof *me->v);
  memcpy(me->v, w->verts, (size_t)sl->nverts * sizeof *me->v);
  int next = sl->nverts;
  ss->rows = xcalloc((size_t)(w->nb + w->nends) + 1, sizeof *ss->rows);
  for (int i = 0; i < w->nb; i++) {
    const band *b = &w->b[i];
    int first = next;
    for (int k = 0; k < b->lo.nsteiner; k++) me->v[next++] = b->lo.steiner[k];
    for (int k = 0; k < b->hi.nsteiner; k++) me->v[next++] = b->hi.steiner[k];
    for (int k = 0; k < b->ntri; k++) {
      int v[3];
      for (int e = 0; e < 3; e++) v[e] = b->tri[k][e] >= 0 ? b->tri[k][e] : first - 1 - b->tri[k][e];
      mesh_add_tri(me, v[0], v[1], v[2]);
    }
    stack_row *r = &ss->rows[ss->nrows++];
    r->kind = STACK_BAND;
    r->slice0 = b->slice, r->slice1 = b->slice + 1;
    r->z0 = unscale(sl, sl->z[b->slice], 1), r->z1 = unscale(sl, sl->z[b->slice + 1], 1);
    r->depth = b->j->depth;
    r->nlo = b->j->nlo, r->nhi = b->j->nhi;
    r->lo = positions(sl, b->j->lo, r->nlo), r->hi = positions(sl, b->j->hi, r->nhi);
    r->m = b->lo.n, r->n = b->hi.n;
    r->bridges = b->lo.nbridges + b->hi.nbridges;
    r->cost = unscale(sl, b->cost, w->deg);   /* the path's true cost, not its sum of quanta */
    r->area = b->area, r->volume = b->volume;
    r->nodes = (unsigned long long)b->t.count.nodes;
    r->spans = b->pinched ? 1 : 0;
    r->pair = w->o->tiler ? i : -1;
  }
  for (int i = 0; i < w->nends; i++) {
    const end_region *g = &w->ends[i];
    const end_cap *c = &w->caps[i];
    int first = next;
    for (int k = 0; k < c->nnew; k++) me->v[next++] = c->at[k];
    stack_row *r = &ss->rows[ss->nrows++];
    double z = sl->z[g->slice];
    vec3 o = {sl->c[g->outer].pt[0].x, sl->c[g->outer].pt[0].y, z};
    r->kind = STACK_CAP;
    r->slice0 = r->slice1 = g->slice;
    r->z0 = unscale(sl, z, 1), r->z1 = unscale(sl, c->nnew == 1 ? c->at[0].z : z, 1);
    r->depth = sl->c[g->outer].depth;
    int *cs = xmallocarray((size_t)g->nholes + 1, sizeof *cs);
    cs[0] = g->outer;
    for (int k = 0; k < g->nholes; k++) cs[k + 1] = g->holes[k];
    for (int k = 0; k <= g->nholes; k++) r->m += sl->c[cs[k]].n;
    if (g->up) r->nlo = g->nholes + 1, r->lo = positions(sl, cs, r->nlo), r->hi = positions(sl, cs, 0);
    else r->nhi = g->nholes + 1, r->hi = positions(sl, cs, r->nhi), r->lo = positions(sl, cs, 0);
    free(cs);
    r->pair = -1;
    int t0 = me->nt;
    double mx = fmax(fabs(o.x), fmax(fabs(o.y), fabs(o.z)));
    for (int k = 0; k < c->ntri; k++) {
      int v[3];
      for (int e = 0; e < 3; e++) v[e] = c->tri[k][e] >= 0 ? c->tri[k][e] : first - 1 - c->tri[k][e];
      mesh_add_tri(me, v[0], v[1], v[2]);
      for (int e = 0; e < 3; e++) mx = vmax(me->v[v[e]], mx);
    }
    /* At one safe scale, as the bands (mesh_job). */
    int sc = geom_scale_exp(mx);
    double area = 0, volume = 0;
    for (int t = t0; t < me->nt; t++) {
      vec3 p = scl(me->v[me->t[t][0]], sc), q = scl(me->v[me->t[t][1]], sc), u = scl(me->v[me->t[t][2]], sc);
      area += tri_area(p, q, u);
      volume += tri_vol(p, q, u, scl(o, sc));
    }
    r->area += ldexp(area, 2 * (sc + sl->scale));
    r->volume += ldexp(volume, 3 * (sc + sl->scale));
  }
  XASSERT(next == nv);
}

/* The surface, made at the working scale, in the file's units: the totals
 * and the components measured on the mesh as made, each scaled once; the
 * input vertices are the file's own points (bit for bit, even where scaling
 * rounded them), the others scaled back; the parallel runs' costs too. */
/* The mesh's components and its whole area and volume: two jobs that only
 * read the mesh, on two threads when there are. */
typedef struct {
  stack_surface *ss;
  double area, volume;
} finish;

static void finish_job(void *ud, int i) {
  finish *f = ud;
  if (i == 0) f->ss->ncomp = manifold_components(&f->ss->me, &f->ss->comp);
  else f->area = mesh_area(&f->ss->me), f->volume = mesh_volume(&f->ss->me);
}

static void to_file_units(const work *w, const contour_stack *s, stack_surface *ss, const finish *fin) {
  const slices *sl = w->sl;
  mesh *me = &ss->me;
  double cost = 0;
  for (int i = 0; i < w->nb; i++) cost += w->b[i].cost;
  ss->cost = unscale(sl, cost, w->deg);
  ss->area = unscale(sl, fin->area, 2);
  ss->volume = unscale(sl, fin->volume, 3);
  for (int i = 0; i < ss->ncomp; i++) {
    manifold_component *c = &ss->comp[i];
    c->zmin = unscale(sl, c->zmin, 1), c->zmax = unscale(sl, c->zmax, 1);
    c->area = unscale(sl, c->area, 2), c->volume = unscale(sl, c->volume, 3);
  }
  for (int v = sl->nverts; v < me->nv; v++)
    me->v[v] = (vec3){unscale(sl, me->v[v].x, 1), unscale(sl, me->v[v].y, 1), unscale(sl, me->v[v].z, 1)};
  for (int c = 0; c < sl->ncontours; c++) {
    const slice_contour *x = &sl->c[c];
    const contour *f = &s->c[x->src];
    for (int k = 0; k < x->n; k++) {
      vec2 p = f->pt[(x->rev ? x->from - k + x->n : x->from + k) % x->n];
      me->v[x->base + k] = (vec3){p.x, p.y, f->z};
    }
  }
  for (int i = 0; i < ss->npairs; i++) {
    tiling *t = &ss->pairs[i].t;
    t->qexp += w->deg * sl->scale;
    t->quantum = ldexp(1, t->qexp);
    t->cost = ldexp(t->quanta, t->qexp);
  }
}

/* The bands and the ends, planned from the junctions (plan_work). */
static void plan_free(work *w) {
  for (int i = 0; i < w->nb; i++) {
    follow_free(&w->b[i].fa);
    follow_free(&w->b[i].fb);
    bridge_free(&w->b[i].lo);
    bridge_free(&w->b[i].hi);
    tiling_free(&w->b[i].t);
    free(w->b[i].err);
    free(w->b[i].tri);
  }
  for (int i = 0; i < w->nends; i++) ends_cap_free(&w->caps[i]);
  if (w->ends) ends_free(w->ends, w->nends);
  free(w->caps);
  free(w->b);
  free(w->up);
  free(w->down);
  w->b = NULL, w->nb = 0, w->caps = NULL, w->ends = NULL, w->nends = 0, w->up = w->down = NULL;
}

static void work_free(work *w) {
  plan_free(w);
  free(w->verts);
  for (int k = 0; k + 1 < w->sl->nslices; k++) match_free(&w->js[k]);
  free(w->js);
}

/* The bands and, with caps, the ends to close. */
static void plan_work(work *w) {
  plan_bands(w);
  if (w->o->caps || w->sl->nslices == 1) {   /* one slice: the slab is closed */
    w->nends = ends_plan(w->sl, w->up, w->down, &w->ends);
    w->caps = xcalloc((size_t)w->nends + 1, sizeof *w->caps);
  }
}

/* A branching that no bridges can join (a contour below overlapping six
 * above that bridges cannot gather): its slices matched again with every
 * link, overlaps too, made only where bridges can join the junction it
 * makes, the rest dropped, named in notes, and their contours capped; then
 * everything planned again.  1 if some band failed so, else 0. */
static int rematch_unbridged(work *w) {
  int any = 0;
  unsigned char *redo = xcalloc((size_t)w->sl->nslices + 1, 1);
  for (int i = 0; i < w->nb; i++)
    if (w->b[i].err) redo[w->b[i].slice] = 1, any = 1;
  if (any) {
    match_opts careful = w->mo;
    careful.careful = 1;
    plan_free(w);
    for (int k = 0; k + 1 < w->sl->nslices; k++)
      if (redo[k]) {
        match_free(&w->js[k]);
        match_slices(w->sl, k, &careful, &w->js[k]);
      }
    plan_work(w);
    atomic_store(&w->tiled, 0);
  }
  free(redo);
  return any;
}

int stack_check_slices(const contour_stack *s, const char *name, double thickness, char *err, size_t errlen) {
  if (s->nslices >= 2 || thickness > 0) return 0;
  int first = 0;
  for (int i = 1; i < s->n; i++)
    if (s->c[i].line < s->c[first].line) first = i;
  char what[64];
  if (s->n == 1) snprintf(what, sizeof what, "the only contour lies");
  else snprintf(what, sizeof what, "all %d contours lie", s->n);
  snprintf(err, errlen, "%s:%d: %s on one slice (z=%s): a surface needs two slices, or --thickness T "
           "to make this one a slab T thick", name, s->c[first].line, what, ARGS_G(s->c[first].z));
  return -1;
}

int stack_parse_join(const char *opt, const char *val, match_rule *rule, double *dist, char *err, size_t errlen) {
  static const match_rule rules[] = {MATCH_OVERLAP, MATCH_SINGLE, MATCH_TOUCH, MATCH_NEAREST};
  char shown[300];
  int w = args_word(opt, val, "overlap|single|touch|nearest", err, errlen);
  if (w >= 0) {
    *rule = rules[w];
    *dist = INFINITY;
    return 0;
  }
  if (args_real(opt, val, "a distance", 0, 1e300, dist, err, errlen) == 0) {
    *rule = MATCH_NEAREST;
    return 0;
  }
  args_show(val, shown, sizeof shown);
  snprintf(err, errlen, "%s takes overlap, single, touch, nearest or a distance from 0 to 1e300 (%s)", opt, shown);
  return -1;
}

int stack_parse_thickness(const char *opt, const char *val, double *t, char *err, size_t errlen) {
  double v;
  if (args_real(opt, val, "a length", 0, 1e300, &v, err, errlen) == 0 && v > 0) {
    *t = v;
    return 0;
  }
  char shown[300];
  args_show(val, shown, sizeof shown);
  snprintf(err, errlen, "%s takes a length above 0, at most 1e300 (%s)", opt, shown);
  return -1;
}

/* The rule's name for the report, and the option for notes. */
static void rule_names(const stack_options *o, char *rule, size_t rl, char *opt, size_t ol) {
  static const char *const names[] = {"single", "overlap", "touch", "nearest"};
  if (o->join == MATCH_NEAREST && isfinite(o->join_dist)) args_fmt_double(o->join_dist, rule, rl);
  else snprintf(rule, rl, "%s", names[o->join]);
  snprintf(opt, ol, "--join %s", rule);
}

int stack_tile(const contour_stack *s, const char *name, const stack_options *o,
               stack_surface **out, char *err, size_t errlen) {
  *out = NULL;
  int threads = o->threads < 1 ? 1 : o->threads;
  kernel_simd(-1);   /* the kernel's choice made once, before the threads share it */
  if (stack_check_slices(s, name, o->thickness, err, errlen) != 0) return -1;
  /* The whole stack at one scale, its largest coordinate in [1/2, 1) (stack.h);
   * a slab's faces too. */
  int scale = slices_scale_exp(s);
  if (s->nslices == 1) {
    int e = geom_scale_exp(fabs(s->c[0].z) + o->thickness / 2);
    if (e > scale) scale = e;
  }
  slices sl;
  if (slices_build_at(s, name, scale, threads, &sl, err, errlen) != 0) return -1;
  int ns = sl.nslices;
  if (o->notes && sl.ncontours > ns && sl.reoriented)
    fprintf(o->notes,
            "%s: %s: %d of %d contours ran against their nesting (an outer boundary or island "
            "clockwise, or a hole counter-clockwise); oriented by depth\n",
            o->prefix, name, sl.reoriented, sl.ncontours);

  work w;
  memset(&w, 0, sizeof w);
  atomic_init(&w.tiled, 0);
  w.sl = &sl, w.o = o, w.name = name, w.threads = threads;
  w.deg = o->kind == COST_SPAN ? 1 : 2;
  w.mo.rule = o->join;
  w.mo.dist = o->join == MATCH_NEAREST && isfinite(o->join_dist) ? geom_ldexp(o->join_dist, -sl.scale) : INFINITY;
  w.mo.gaps = o->notes != NULL;
  w.half = ns == 1 ? geom_ldexp(o->thickness / 2, -sl.scale) : 0;
  w.js = xcalloc((size_t)ns, sizeof *w.js);
  pool_run(threads, ns - 1, NULL, match_job, &w);
  plan_work(&w);
  w.verts = xmallocarray((size_t)sl.nverts + 1, sizeof *w.verts);
  for (int c = 0; c < sl.ncontours; c++)
    for (int k = 0; k < sl.c[c].n; k++)
      w.verts[sl.c[c].base + k] = (vec3){sl.c[c].pt[k].x, sl.c[c].pt[k].y, sl.z[sl.c[c].slice]};
  int rc = 0;
  stack_surface *ss = xcalloc(1, sizeof *ss);
  rule_names(o, ss->rule, sizeof ss->rule, w.joinopt, sizeof w.joinopt);
  if (o->tiler) {
    pool_run(threads, w.nb, NULL, bridge_job, &w);
    if (rematch_unbridged(&w)) pool_run(threads, w.nb, NULL, bridge_job, &w);
    count_joins(&w, ss);
    rc = first_error(&w, err, errlen);
    if (rc == 0) rc = tile_bands(&w, ss, err, errlen);
    if (rc == 0) pool_run(threads, w.nb, NULL, mesh_job, &w);
    if (rc == 0) pool_run(threads, w.nends, NULL, cap_job, &w);
  } else {
    whole_run(&w);
    if (rematch_unbridged(&w)) whole_run(&w);
    count_joins(&w, ss);
    rc = first_error(&w, err, errlen);
  }
  if (rc == 0) {
    print_notes(&w);
    assemble(&w, ss);
    if (o->notes && ss->me.nt == 0)
      fprintf(o->notes, "%s: %s: the mesh is empty: no contour is joined to one on a neighbouring slice%s%s\n",
              o->prefix, name, o->join != MATCH_NEAREST ? "; --join nearest joins contours that lie apart" : "",
              o->caps ? "" : "; without --no-caps each contour is closed on its own");
    finish f = {ss, 0, 0};
    pool_run(threads, 2, NULL, finish_job, &f);
    to_file_units(&w, s, ss, &f);
  }
  work_free(&w);
  slices_free(&sl);
  if (rc != 0) {
    stack_free(ss);
    return rc;
  }
  *out = ss;
  return 0;
}

const mesh *stack_mesh(const stack_surface *ss) { return &ss->me; }
void stack_take_mesh(stack_surface *ss, mesh *me) {
  *me = ss->me;
  memset(&ss->me, 0, sizeof ss->me);
}
int stack_nrows(const stack_surface *ss) { return ss->nrows; }
const stack_row *stack_rows(const stack_surface *ss) { return ss->rows; }
const par_pair *stack_pairs(const stack_surface *ss) { return ss->pairs; }
int stack_ncomponents(const stack_surface *ss) { return ss->ncomp; }
void stack_totals(const stack_surface *ss, double *cost, double *area, double *volume) {
  *cost = ss->cost, *area = ss->area, *volume = ss->volume;
}
const manifold_component *stack_components(const stack_surface *ss) { return ss->comp; }
const stack_joins *stack_join_counts(const stack_surface *ss) { return &ss->joins; }

void stack_free(stack_surface *ss) {
  if (!ss) return;
  for (int i = 0; i < ss->nrows; i++) free(ss->rows[i].lo), free(ss->rows[i].hi);
  free(ss->rows);
  if (ss->pairs)
    for (int i = 0; i < ss->npairs; i++) tiling_free(&ss->pairs[i].t);
  free(ss->pairs);
  free(ss->comp);
  mesh_free(&ss->me);
  free(ss);
}
