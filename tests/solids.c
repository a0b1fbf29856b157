/* solids.c -- analytic solids, their exact sections, inscribed polygons and
 * volumes (see solids.h).  Every fact here comes from the solid's formula:
 * sections are circles or the curves of a torus, areas come from Green's
 * theorem on the arcs or from quadrature of the section's width, volumes from
 * closed forms or a one-dimensional integral. */
#include "tests/solids.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/rng.h"
#include "util/xmem.h"

#define PI 3.14159265358979323846

/* ---------------------------------------------------------------- solids -- */

enum {
  S_SPHERE, S_CONE, S_CYLINDER, S_OVERLAP, S_SEPARATE, S_TORUS_ACROSS, S_TORUS_ALONG,
  S_HOLLOW, S_ISLAND, S_COUNT
};

static const solid_info infos[S_COUNT] = {
    {"sphere", "a sphere, radius 1", 0, -0.92, 0.92, 1, {2}, {1}},
    {"cone", "an oblique cone, base radius 1, height 2", 0, 0, 1.8, 1, {2}, {1}},
    {"cylinder", "an oblique cylinder, radius 0.8", 0, 0, 1.5, 1, {2}, {1}},
    {"spheres_overlapping", "two overlapping spheres side by side: 2 contours, then 1, then 2", 1,
     -0.93, 0.93, 1, {2}, {1}},
    {"spheres_separate", "two separate spheres at different heights: 1 contour, 2, then 1", 1, -1.32,
     1.27, 2, {2, 2}, {1, 1}},
    {"torus_across", "a torus with its axis across the slices (along x): 1 contour, 2, then 1", 1,
     -1.38, 1.38, 1, {0}, {1}},
    {"torus_along", "a torus with its axis along the slices (along z): a hole on every slice", 1,
     -0.42, 0.42, 1, {0}, {1}},
    {"hollow_sphere", "a sphere with a spherical cavity: holes appear and disappear", 1, -0.93, 0.93,
     2, {2, 2}, {1, -1}},
    {"island", "a ball inside the cavity of a hollow sphere: an island inside a hole", 1, -1.12,
     1.12, 3, {2, 2, 2}, {1, -1, 1}},
};

/* The balls of the sphere-made solids: centre, radius, +1 material or -1 cavity. */
typedef struct { double cx, cy, cz, r; int sign; } ball;
static const ball b_sphere[] = {{0.1, -0.05, 0, 1, 1}};
static const ball b_separate[] = {{-1.1, 0, -0.4, 1, 1}, {1.1, 0.1, 0.45, 0.9, 1}};
static const ball b_hollow[] = {{0, 0, 0, 1, 1}, {0.15, 0.1, 0.05, 0.5, -1}};
static const ball b_island[] = {{0, 0, 0, 1.2, 1}, {0.05, 0, 0, 0.85, -1}, {0.1, 0.05, 0.03, 0.45, 1}};
static const double OV_R = 1, OV_D = 0.6;        /* overlapping: radius, centres at x = +-D */
static const double TO_R = 1, TO_r = 0.45;       /* both tori: major, minor radius */
static const double TA_CX = 0.05;                /* torus_along's centre x */
static const double CY_R = 0.8;                  /* cylinder: radius; centre (0.3 z, -0.1 z) */

int solid_count(void) { return S_COUNT; }
const solid_info *solid_get(int s) { return s >= 0 && s < S_COUNT ? &infos[s] : NULL; }
int solid_find(const char *name) {
  for (int s = 0; s < S_COUNT; s++)
    if (strcmp(infos[s].name, name) == 0) return s;
  return -1;
}

static void balls_of(int s, const ball **b, int *n) {
  switch (s) {
  case S_SPHERE: *b = b_sphere, *n = 1; break;
  case S_SEPARATE: *b = b_separate, *n = 2; break;
  case S_HOLLOW: *b = b_hollow, *n = 2; break;
  case S_ISLAND: *b = b_island, *n = 3; break;
  default: *b = NULL, *n = 0;
  }
}

/* Radius of a ball's section at z, 0 outside. */
static double ball_rho(double r, double cz, double z) {
  double h = z - cz;
  return fabs(h) < r ? sqrt(r * r - h * h) : 0;
}

/* ------------------------------------------------------------ quadrature -- */

typedef double (*fn1)(double, const void *);

static double asr(fn1 f, const void *ud, double a, double b, double fa, double fm, double fb,
                  double whole, double eps, int depth) {
  double m = (a + b) / 2, lm = (a + m) / 2, rm = (m + b) / 2;
  double flm = f(lm, ud), frm = f(rm, ud);
  double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
  double delta = left + right - whole;
  if (depth <= 0 || fabs(delta) <= 15 * eps) return left + right + delta / 15;
  return asr(f, ud, a, m, fa, flm, fm, left, eps / 2, depth - 1) +
         asr(f, ud, m, b, fm, frm, fb, right, eps / 2, depth - 1);
}

/* Adaptive Simpson over [a, b], absolute tolerance eps. */
static double integrate(fn1 f, const void *ud, double a, double b, double eps) {
  if (!(b > a)) return 0;
  double fa = f(a, ud), fb = f(b, ud), fm = f((a + b) / 2, ud);
  return asr(f, ud, a, b, fa, fm, fb, (b - a) / 6 * (fa + 4 * fm + fb), eps, 40);
}

/* The same over [a, b] cut at the sorted points cut[] (kinks of f). */
static double integrate_cut(fn1 f, const void *ud, double a, double b, const double *cut, int ncut,
                            double eps) {
  double sum = 0, lo = a;
  for (int i = 0; i < ncut; i++)
    if (cut[i] > lo && cut[i] < b) sum += integrate(f, ud, lo, cut[i], eps), lo = cut[i];
  return sum + integrate(f, ud, lo, b, eps);
}

/* ------------------------------------------------- the torus across its axis -- */

/* The torus of major radius R and minor radius r around the x axis: points
 * with (sqrt(y^2 + z^2) - R)^2 + x^2 <= r^2.  Its section at z is, at height
 * y, the x-interval of half-width sqrt(r^2 - (sqrt(y^2 + z^2) - R)^2). */
typedef struct { double R, r, z, ylo, yhi; } tx_ctx;

static double tx_width(double s, const void *ud) {   /* y = ylo..yhi as s = 0..1 */
  const tx_ctx *c = ud;
  double u = (1 - cos(PI * s)) / 2, y = c->ylo + (c->yhi - c->ylo) * u;
  double dy = (c->yhi - c->ylo) * PI / 2 * sin(PI * s);
  double rho = sqrt(y * y + c->z * c->z) - c->R, w = c->r * c->r - rho * rho;
  return w > 0 ? 2 * sqrt(w) * dy : 0;
}

/* Area of the section at z (both halves, y > 0 and y < 0). */
static double tx_area(double R, double r, double z) {
  double az = fabs(z);
  if (az >= R + r) return 0;
  tx_ctx c = {R, r, z, az < R - r ? sqrt((R - r) * (R - r) - z * z) : 0, sqrt((R + r) * (R + r) - z * z)};
  return 2 * integrate(tx_width, &c, 0, 1, 1e-12);
}

/* Volume between z = a and z = b: the point (x, rho) of the tube's disc
 * sweeps the circle of radius rho around the x axis, of which the arc with
 * z in [a, b] has angle 2 (acos(a / rho) - acos(b / rho)); over the disc's
 * chord at rho (length 2 r sin t, rho = R + r cos t) this gives
 *   V = integral over t in [0, pi] of 4 r^2 sin^2 t rho (acos(a/rho) - acos(b/rho)). */
typedef struct { double R, r, a, b; } txv_ctx;
static double clamp1(double v) { return v < -1 ? -1 : v > 1 ? 1 : v; }
static double txv_f(double t, const void *ud) {
  const txv_ctx *c = ud;
  double rho = c->R + c->r * cos(t), s = sin(t);
  return 4 * c->r * c->r * s * s * rho * (acos(clamp1(c->a / rho)) - acos(clamp1(c->b / rho)));
}
static double tx_volume(double R, double r, double a, double b) {
  txv_ctx c = {R, r, a, b};
  double cut[4];
  int n = 0;
  double v[2] = {fabs(a), fabs(b)};
  for (int i = 0; i < 2; i++)   /* where rho = |a| or |b|: the integrand's kinks */
    if (v[i] > R - r && v[i] < R + r) cut[n++] = acos((v[i] - R) / r);
  if (n == 2 && cut[0] > cut[1]) { double t = cut[0]; cut[0] = cut[1]; cut[1] = t; }
  return integrate_cut(txv_f, &c, 0, PI, cut, n, 1e-12);
}

/* ------------------------------------------------------------- sections -- */

enum { P_ARC, P_TORUS };
typedef struct {
  int type;
  double cx, cy, r, a0, a1;   /* arc: centre, radius, from angle a0 to a1 (a1 < a0: clockwise) */
  double R, tr, z, p0, p1;    /* torus across: the upper curve (tr cos p, sqrt((R + tr sin p)^2 - z^2)) */
  int ends;                   /* the curve meets y = 0 at both ends (p0, p1) */
  int lower;                  /* the mirror image y -> -y, run backwards */
} piece;

enum { MAXLOOP = 8, TABLE = 4096 };
typedef struct {
  int np;
  piece p[2];
  int depth;
  double area;                /* signed area of the true curve */
} loop;

/* Green's theorem on an arc: (1/2) integral of (x dy - y dx). */
static double arc_green(const piece *p) {
  return 0.5 * (p->r * p->r * (p->a1 - p->a0) + p->r * p->cx * (sin(p->a1) - sin(p->a0)) -
                p->r * p->cy * (cos(p->a1) - cos(p->a0)));
}

static void add_circle(loop *L, int *n, double cx, double cy, double r, int depth) {
  XASSERT(*n < MAXLOOP);
  loop *l = &L[(*n)++];
  memset(l, 0, sizeof *l);
  l->np = 1, l->depth = depth;
  l->p[0] = (piece){.type = P_ARC, .cx = cx, .cy = cy, .r = r, .a0 = 0, .a1 = depth % 2 ? -2 * PI : 2 * PI};
  l->area = (depth % 2 ? -1 : 1) * PI * r * r;
}

/* The boundary of the union of the discs (-d, 0, r) and (d, 0, r), r > d:
 * the arc of the left circle outside the right disc, from the upper corner
 * (0, h) round to the lower one, then the right circle's arc back up.  The
 * corners are vertices of the polygon, so every chord lies in one disc. */
static void add_union(loop *L, int *n, double d, double r) {
  XASSERT(*n < MAXLOOP);
  loop *l = &L[(*n)++];
  memset(l, 0, sizeof *l);
  double al = atan2(sqrt(r * r - d * d), d);   /* the upper corner, seen from (-d, 0) */
  l->np = 2;
  l->p[0] = (piece){.type = P_ARC, .cx = -d, .cy = 0, .r = r, .a0 = al, .a1 = 2 * PI - al};
  l->p[1] = (piece){.type = P_ARC, .cx = d, .cy = 0, .r = r, .a0 = al - PI, .a1 = PI - al};
  l->area = arc_green(&l->p[0]) + arc_green(&l->p[1]);
}

static void add_torus(loop *L, int *n, double z, int lower, int ends, double area) {
  XASSERT(*n < MAXLOOP);
  loop *l = &L[(*n)++];
  memset(l, 0, sizeof *l);
  double az = fabs(z), p0 = 0, p1 = 2 * PI;
  if (ends) p0 = asin((az - TO_R) / TO_r), p1 = PI - p0;
  piece up = {.type = P_TORUS, .R = TO_R, .tr = TO_r, .z = z, .p0 = p0, .p1 = p1, .ends = ends};
  l->area = area;
  if (!ends) {   /* a closed curve of its own, y > 0 or (mirrored) y < 0 */
    l->np = 1, l->p[0] = up, l->p[0].lower = lower;
  } else {       /* one curve: the upper half, then its mirror image back */
    l->np = 2, l->p[0] = up, l->p[1] = up, l->p[1].lower = 1;
  }
}

/* The section of solid s at z: its curves, outer ones counter-clockwise. */
static int section(int s, double z, loop *L) {
  int n = 0;
  const ball *b;
  int nb;
  balls_of(s, &b, &nb);
  if (nb) {
    for (int i = 0; i < nb; i++) {
      double rho = ball_rho(b[i].r, b[i].cz, z);
      /* depth: a ball is inside the balls listed before it that contain it */
      if (rho > 0) add_circle(L, &n, b[i].cx, b[i].cy, rho, s == S_SEPARATE ? 0 : i);
    }
    return n;
  }
  switch (s) {
  case S_CONE:
    if (z >= 0 && z < 2) add_circle(L, &n, 0.3 * z / 2, 0.2 * z / 2, 1 - z / 2, 0);
    break;
  case S_CYLINDER: add_circle(L, &n, 0.3 * z, -0.1 * z, CY_R, 0); break;
  case S_OVERLAP: {
    double rho = ball_rho(OV_R, 0, z);
    if (rho > OV_D) add_union(L, &n, OV_D, rho);
    else if (rho > 0) add_circle(L, &n, -OV_D, 0, rho, 0), add_circle(L, &n, OV_D, 0, rho, 0);
    break;
  }
  case S_TORUS_ACROSS: {
    double az = fabs(z), A = tx_area(TO_R, TO_r, z);
    if (az < TO_R - TO_r) add_torus(L, &n, z, 0, 0, A / 2), add_torus(L, &n, z, 1, 0, A / 2);
    else if (az < TO_R + TO_r) add_torus(L, &n, z, 0, 1, A);
    break;
  }
  case S_TORUS_ALONG:
    if (fabs(z) < TO_r) {
      double w = sqrt(TO_r * TO_r - z * z);
      add_circle(L, &n, TA_CX, 0, TO_R + w, 0);
      add_circle(L, &n, TA_CX, 0, TO_R - w, 1);
    }
    break;
  }
  return n;
}

int solid_section_count(int s, double z) {
  loop L[MAXLOOP];
  return section(s, z, L);
}

double solid_section_area(int s, double z) {
  loop L[MAXLOOP];
  int n = section(s, z, L);
  double a = 0;
  for (int i = 0; i < n; i++) a += L[i].area;
  return a;
}

/* --------------------------------------------------------------- volumes -- */

/* A ball's volume between the planes a and b (a spherical zone). */
static double ball_volume(double r, double cz, double a, double b) {
  double lo = fmax(a - cz, -r), hi = fmin(b - cz, r);
  if (!(hi > lo)) return 0;
  return PI * (r * r * (hi - lo) - (hi * hi * hi - lo * lo * lo) / 3);
}

static double area_fn(double z, const void *ud) { return solid_section_area(*(const int *)ud, z); }

double solid_volume(int s, double a, double b) {
  const ball *bl;
  int nb;
  balls_of(s, &bl, &nb);
  if (nb) {
    double v = 0;
    for (int i = 0; i < nb; i++) v += bl[i].sign * ball_volume(bl[i].r, bl[i].cz, a, b);
    return v;
  }
  switch (s) {
  case S_CONE: {   /* oblique: the same as the right cone (Cavalieri) */
    double lo = fmax(a, 0), hi = fmin(b, 2);
    if (!(hi > lo)) return 0;
    double u = 1 - lo / 2, w = 1 - hi / 2;
    return PI * 2 / 3 * (u * u * u - w * w * w);
  }
  case S_CYLINDER: return PI * CY_R * CY_R * (b - a);
  case S_OVERLAP: {   /* the union's section area is closed-form; integrate it */
    double zc = sqrt(OV_R * OV_R - OV_D * OV_D), cut[2] = {-zc, zc};
    return integrate_cut(area_fn, &s, fmax(a, -OV_R), fmin(b, OV_R), cut, 2, 1e-12);
  }
  case S_TORUS_ACROSS: return tx_volume(TO_R, TO_r, a, b);
  case S_TORUS_ALONG: {   /* section area 4 pi R sqrt(r^2 - z^2) */
    double lo = fmax(a, -TO_r), hi = fmin(b, TO_r);
    if (!(hi > lo)) return 0;
    double r = TO_r;
    double Fh = (hi * sqrt(r * r - hi * hi) + r * r * asin(hi / r)) / 2;
    double Fl = (lo * sqrt(r * r - lo * lo) + r * r * asin(lo / r)) / 2;
    return 4 * PI * TO_R * (Fh - Fl);
  }
  }
  xpanic("solid_volume: no solid %d", s);
}

double solid_surface_distance(int s, double x, double y, double z) {
  const ball *b;
  int nb;
  balls_of(s, &b, &nb);
  double best = INFINITY;
  for (int i = 0; i < nb; i++)
    best = fmin(best, fabs(sqrt((x - b[i].cx) * (x - b[i].cx) + (y - b[i].cy) * (y - b[i].cy) +
                                (z - b[i].cz) * (z - b[i].cz)) - b[i].r));
  switch (s) {
  case S_CONE: return fabs(hypot(x - 0.3 * z / 2, y - 0.2 * z / 2) - (1 - z / 2));
  case S_CYLINDER: return fabs(hypot(x - 0.3 * z, y + 0.1 * z) - CY_R);
  case S_OVERLAP:
    for (int i = -1; i <= 1; i += 2) best = fmin(best, fabs(sqrt((x - i * OV_D) * (x - i * OV_D) + y * y + z * z) - OV_R));
    return best;
  case S_TORUS_ACROSS: return fabs(hypot(sqrt(y * y + z * z) - TO_R, x) - TO_r);
  case S_TORUS_ALONG: return fabs(hypot(hypot(x - TA_CX, y) - TO_R, z) - TO_r);
  }
  return best;
}

/* -------------------------------------------------------------- sampling -- */

static void piece_point(const piece *p, double t, double *x, double *y) {
  if (p->type == P_ARC) {
    double a = p->a0 + (p->a1 - p->a0) * t;
    *x = p->cx + p->r * cos(a), *y = p->cy + p->r * sin(a);
    return;
  }
  if (p->lower) t = 1 - t;
  if (p->ends && (t == 0 || t == 1)) {   /* exactly on y = 0 */
    double h = fabs(p->z) - p->R;
    *x = (t == 0 ? 1 : -1) * sqrt(p->tr * p->tr - h * h), *y = 0;
    return;
  }
  double u = p->ends ? (1 - cos(PI * t)) / 2 : t, ph = p->p0 + (p->p1 - p->p0) * u;
  double rho = p->R + p->tr * sin(ph), w = rho * rho - p->z * p->z;
  *x = p->tr * cos(ph), *y = w > 0 ? sqrt(w) : 0;
  if (p->lower) *y = -*y;
}

/* Cumulative chord length of a torus piece at TABLE + 1 parameter values. */
static double piece_table(const piece *p, double *cum) {
  double px, py;
  piece_point(p, 0, &px, &py);
  cum[0] = 0;
  for (int i = 1; i <= TABLE; i++) {
    double x, y;
    piece_point(p, (double)i / TABLE, &x, &y);
    cum[i] = cum[i - 1] + hypot(x - px, y - py);
    px = x, py = y;
  }
  return cum[TABLE];
}

static double piece_length(const piece *p, double *cum) {
  return p->type == P_ARC ? p->r * fabs(p->a1 - p->a0) : piece_table(p, cum);
}

/* n points on piece p, its start included and its end not: equal angles on
 * an arc (shifted by phase, a fraction of the arc), equal arc lengths on a
 * torus curve (from a table of its chord lengths).  Returns the closed-form deficit
 * (true area minus polygon area) of the chords, or NAN. */
static double piece_sample(const piece *p, int n, double phase, double *x, double *y, double *cum) {
  if (p->type == P_ARC) {
    for (int j = 0; j < n; j++) piece_point(p, phase + (double)j / n, &x[j], &y[j]);
    double th = fabs(p->a1 - p->a0) / n, sg = p->a1 > p->a0 ? 1 : -1;
    return sg * n * p->r * p->r / 2 * (th - sin(th));
  }
  double L = piece_table(p, cum);
  int m = 0;
  for (int j = 0; j < n; j++) {
    double s = L * j / n;
    while (m < TABLE - 1 && cum[m + 1] <= s) m++;
    double f = cum[m + 1] > cum[m] ? (s - cum[m]) / (cum[m + 1] - cum[m]) : 0;
    piece_point(p, j == 0 ? 0 : (m + f) / TABLE, &x[j], &y[j]);
  }
  return NAN;
}

void solid_slice(int s, const double *z, int K, int N, int vary, sl_stack *out) {
  XASSERT(N >= 8 && K >= 1);
  memset(out, 0, sizeof *out);
  out->nslice = K;
  out->z = xmallocarray((size_t)K, sizeof *out->z);
  out->first = xmallocarray((size_t)K, sizeof *out->first);
  out->count = xmallocarray((size_t)K, sizeof *out->count);
  int cap = 2 * K;
  out->c = xmallocarray((size_t)cap, sizeof *out->c);
  double *cum = xmallocarray(TABLE + 1, sizeof *cum);
  for (int k = 0; k < K; k++) {
    loop L[MAXLOOP];
    int nl = section(s, z[k], L);
    out->z[k] = z[k], out->first[k] = out->n, out->count[k] = nl;
    for (int l = 0; l < nl; l++) {
      if (out->n == cap) out->c = xreallocarray(out->c, (size_t)(cap *= 2), sizeof *out->c);
      sl_contour *c = &out->c[out->n++];
      int n = N + (vary ? (7 * k + 5 * l) % 9 - 4 : 0);
      c->n = n, c->z = z[k], c->depth = L[l].depth, c->region = L[l].area;
      c->x = xmallocarray((size_t)n, sizeof *c->x);
      c->y = xmallocarray((size_t)n, sizeof *c->y);
      double deficit = 0;
      if (L[l].np == 1) {
        double phase = vary && L[l].p[0].type == P_ARC ? fmod(0.37 * k + 0.11 * l, 1.0) / n : 0;
        deficit = piece_sample(&L[l].p[0], n, phase, c->x, c->y, cum);
      } else {   /* points in proportion to the pieces' lengths, at least 3 each */
        double l0 = piece_length(&L[l].p[0], cum), l1 = piece_length(&L[l].p[1], cum);
        int n0 = (int)lround(n * l0 / (l0 + l1));
        if (n0 < 3) n0 = 3;
        if (n0 > n - 3) n0 = n - 3;
        deficit = piece_sample(&L[l].p[0], n0, 0, c->x, c->y, cum) +
                  piece_sample(&L[l].p[1], n - n0, 0, c->x + n0, c->y + n0, cum);
      }
      c->exact = c->region - deficit;   /* NAN for torus curves */
    }
  }
  free(cum);
}

void sl_stack_free(sl_stack *st) {
  for (int i = 0; i < st->n; i++) free(st->c[i].x), free(st->c[i].y);
  free(st->c), free(st->z), free(st->first), free(st->count);
  memset(st, 0, sizeof *st);
}

void solid_planes(int s, int K, int uneven, double *z) {
  const solid_info *in = solid_get(s);
  XASSERT(in && K >= 2);
  for (int k = 0; k < K; k++) {
    double u = (double)k / (K - 1);
    if (uneven) u += 0.3 * sin(2 * PI * u) / (2 * PI);   /* spacing varies 0.7 .. 1.3 */
    z[k] = in->za + (in->zb - in->za) * u;
  }
  z[0] = in->za, z[K - 1] = in->zb;
}

double sl_shoelace(const sl_contour *c) {
  double a = 0;
  for (int i = 0; i < c->n; i++) {
    int j = (i + 1) % c->n;
    a += c->x[i] * c->y[j] - c->x[j] * c->y[i];
  }
  return a / 2;
}

/* ------------------------------------------------------------ file I/O -- */

int sl_stack_write(const sl_stack *st, const char *path) {
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  for (int i = 0; i < st->n; i++) {
    const sl_contour *c = &st->c[i];
    fprintf(f, "C %d %.17g\n", c->n, c->z);
    for (int j = 0; j < c->n; j++) fprintf(f, "%.17g %.17g\n", c->x[j], c->y[j]);
  }
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) return -1;
  return 0;
}

static void push_contour(sl_stack *st, int *cap, sl_contour *c) {
  if (st->n == *cap) st->c = xreallocarray(st->c, (size_t)(*cap = *cap ? 2 * *cap : 16), sizeof *st->c);
  st->c[st->n++] = *c;
}

/* Slices from the contours' z: consecutive contours with equal z. */
static void group_slices(sl_stack *st) {
  st->nslice = 0;
  st->z = xmallocarray((size_t)(st->n ? st->n : 1), sizeof *st->z);
  st->first = xmallocarray((size_t)(st->n ? st->n : 1), sizeof *st->first);
  st->count = xmallocarray((size_t)(st->n ? st->n : 1), sizeof *st->count);
  for (int i = 0; i < st->n; i++) {
    if (st->nslice == 0 || st->c[i].z != st->z[st->nslice - 1]) {
      st->z[st->nslice] = st->c[i].z, st->first[st->nslice] = i, st->count[st->nslice] = 0;
      st->nslice++;
    }
    st->count[st->nslice - 1]++;
  }
}

int sl_stack_read(const char *path, sl_stack *st, char *err, size_t errlen) {
  memset(st, 0, sizeof *st);
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(err, errlen, "%s: cannot open (%s)", path, strerror(errno));
    return -1;
  }
  char line[4200];
  int lineno = 0, cap = 0, want = 0;
  sl_contour cur = {0};
  while (fgets(line, sizeof line, f)) {
    lineno++;
    char *p = line;
    while (*p == ' ' || *p == '\t') p++;
    if (*p == '#' || *p == '\n' || *p == '\r' || *p == 0) continue;
    if (want == 0) {
      int n;
      char zs[128];
      if (sscanf(p, "C %d %127s", &n, zs) != 2 || n < 1) {
        snprintf(err, errlen, "%s:%d: expected 'C <n> <z>'", path, lineno);
        goto fail;
      }
      cur = (sl_contour){.n = n, .z = strtod(zs, NULL), .exact = NAN, .region = NAN};
      cur.x = xmallocarray((size_t)n, sizeof *cur.x);
      cur.y = xmallocarray((size_t)n, sizeof *cur.y);
      want = n;
      continue;
    }
    char *e1, *e2;
    double x = strtod(p, &e1), y = strtod(e1, &e2);
    if (e1 == p || e2 == e1) {
      snprintf(err, errlen, "%s:%d: expected 'x y'", path, lineno);
      free(cur.x), free(cur.y);
      goto fail;
    }
    cur.x[cur.n - want] = x, cur.y[cur.n - want] = y;
    if (--want == 0) push_contour(st, &cap, &cur);
  }
  if (want) {
    snprintf(err, errlen, "%s: the last contour is short of %d points", path, want);
    free(cur.x), free(cur.y);
    goto fail;
  }
  fclose(f);
  group_slices(st);
  return 0;
fail:
  fclose(f);
  sl_stack_free(st);
  return -1;
}

void sl_stack_clean(sl_stack *st) {
  for (int i = 0; i < st->n; i++) {
    sl_contour *c = &st->c[i];
    int m = 0;
    for (int j = 0; j < c->n; j++)
      if (m == 0 || c->x[j] != c->x[m - 1] || c->y[j] != c->y[m - 1]) c->x[m] = c->x[j], c->y[m] = c->y[j], m++;
    while (m > 1 && c->x[m - 1] == c->x[0] && c->y[m - 1] == c->y[0]) m--;
    c->n = m;
  }
}

void sl_stack_scramble(const sl_stack *in, unsigned long long seed, sl_stack *out) {
  rng r;
  rng_seed(&r, seed);
  memset(out, 0, sizeof *out);
  int cap = 0;
  for (int k = 0; k < in->nslice; k++) {
    int m = in->count[k], *perm = xmallocarray((size_t)m, sizeof *perm);
    for (int i = 0; i < m; i++) perm[i] = i;
    for (int i = m - 1; i > 0; i--) {   /* Fisher-Yates */
      int j = rng_int(&r, 0, i), t = perm[i];
      perm[i] = perm[j], perm[j] = t;
    }
    for (int i = 0; i < m; i++) {
      const sl_contour *c = &in->c[in->first[k] + perm[i]];
      int n = c->n;
      if (n > 3 && c->x[n - 1] == c->x[0] && c->y[n - 1] == c->y[0]) n--;   /* closing point */
      sl_contour d = *c;
      d.n = n;
      d.x = xmallocarray((size_t)n, sizeof *d.x);
      d.y = xmallocarray((size_t)n, sizeof *d.y);
      int rot = rng_int(&r, 0, n - 1);
      for (int j = 0; j < n; j++) {   /* reversed, starting at point rot */
        int src = ((rot - j) % n + n) % n;
        d.x[j] = c->x[src], d.y[j] = c->y[src];
      }
      d.region = -c->region, d.exact = -c->exact;
      push_contour(out, &cap, &d);
    }
    free(perm);
  }
  group_slices(out);
}

/* --------------------------------------------------------- stack geometry -- */

double sl_stack_margin(const sl_stack *st) {
  double best = INFINITY;
  for (int k = 0; k < st->nslice; k++)
    for (int a = st->first[k]; a < st->first[k] + st->count[k]; a++)
      for (int b = a; b < st->first[k] + st->count[k]; b++) {
        const sl_contour *A = &st->c[a], *B = &st->c[b];
        for (int i = 0; i < A->n; i++)
          for (int j = a == b ? i + 1 : 0; j < B->n; j++) {
            if (a == b) {
              int sep = j - i < A->n - (j - i) ? j - i : A->n - (j - i);
              if (sep < A->n / 8) continue;
            }
            double d = hypot(A->x[i] - B->x[j], A->y[i] - B->y[j]);
            if (d < best) best = d;
          }
      }
  return best;
}

static int sgn(double v) { return (v > 0) - (v < 0); }
static double orient(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}
static int on_seg(double ax, double ay, double bx, double by, double px, double py) {
  return fmin(ax, bx) <= px && px <= fmax(ax, bx) && fmin(ay, by) <= py && py <= fmax(ay, by);
}
/* Segments ab and cd cross or touch. */
static int seg_meet(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy) {
  int o1 = sgn(orient(ax, ay, bx, by, cx, cy)), o2 = sgn(orient(ax, ay, bx, by, dx, dy));
  int o3 = sgn(orient(cx, cy, dx, dy, ax, ay)), o4 = sgn(orient(cx, cy, dx, dy, bx, by));
  if (o1 * o2 < 0 && o3 * o4 < 0) return 1;
  return (!o1 && on_seg(ax, ay, bx, by, cx, cy)) || (!o2 && on_seg(ax, ay, bx, by, dx, dy)) ||
         (!o3 && on_seg(cx, cy, dx, dy, ax, ay)) || (!o4 && on_seg(cx, cy, dx, dy, bx, by));
}

int sl_stack_crossings(const sl_stack *st) {
  int count = 0;
  for (int k = 0; k < st->nslice; k++)
    for (int a = st->first[k]; a < st->first[k] + st->count[k]; a++)
      for (int b = a; b < st->first[k] + st->count[k]; b++) {
        const sl_contour *A = &st->c[a], *B = &st->c[b];
        for (int i = 0; i < A->n; i++) {
          int i1 = (i + 1) % A->n;
          for (int j = a == b ? i + 1 : 0; j < B->n; j++) {
            int j1 = (j + 1) % B->n;
            if (a == b && (j == i1 || j1 == i)) continue;   /* neighbours share a point */
            count += seg_meet(A->x[i], A->y[i], A->x[i1], A->y[i1], B->x[j], B->y[j], B->x[j1], B->y[j1]);
          }
        }
      }
  return count;
}
