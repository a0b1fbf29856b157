/* union.c -- ./bench --union: the cost of ./tile --union's exact union
 * (geom/polyunion.h) on one slice of overlapping contours.
 *
 *   bench --union [blob|star:K:N ...] [--repeat R]
 *
 * Each input is one slice of K overlapping contours of N points each, their
 * centres on a circle of radius 30 about the origin:
 *   blob  smooth, as drawn pieces are: radius 100 (1 + 0.08 sin(2t + a) +
 *         0.05 sin(5t + b)) at N even angles t, a and b random; two blobs'
 *         boundaries cross a few times;
 *   star  spiky (gen_star: radius 100 times a random factor in [0.85,
 *         1.15] at sorted random angles): the boundaries cross at a good
 *         fraction of the points and the union has thousands of holes -- a
 *         stress, not a structure.
 * Default blob:3:100 blob:5:1000 blob:5:10000 blob:8:100000 star:5:1000.
 * One CSV row each:
 * the union's groups, loops (holes among them), new vertices (the crossings
 * on its boundary), union_ms the best of R runs of polyunion on the slice
 * (the crossings, their exact rationals, the arrangement, the winding
 * numbers, the loops, the rounding and the check), us_per_point per input
 * point, and two checksums: the loops' points and twice their signed area
 * (holes negative). */
#include "prog/bench/bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "input/gen.h"
#include "geom/polyunion.h"
#include "util/progname.h"
#include "util/rng.h"
#include "util/wallclock.h"
#include "util/xmem.h"

static const char *defaults[] = {"blob:3:100", "blob:5:1000", "blob:5:10000", "blob:8:100000", "star:5:1000"};

static const char union_usage[] =
    "usage: bench --union [blob|star:K:N ...] [--repeat R]   (bench --help: every mode)\n";

static double area2(const vec2 *p, int n) {
  double a = 0;
  for (int i = 0; i < n; i++)
    a += (p[i].x - p[0].x) * (p[(i + 1) % n].y - p[0].y) - (p[(i + 1) % n].x - p[0].x) * (p[i].y - p[0].y);
  return a;
}

static int one(const char *in, int star, int k, int n, int repeat) {
  rng g;
  rng_seed(&g, 2022);
  vec2 **p = xmallocarray((size_t)k, sizeof *p);
  crossing_poly *cp = xmallocarray((size_t)k, sizeof *cp);
  const double tau = 6.283185307179586;
  for (int i = 0; i < k; i++) {
    double cx = 30 * cos(tau * i / k), cy = 30 * sin(tau * i / k);
    p[i] = xmallocarray((size_t)n, sizeof **p);
    if (star) gen_star(&g, p[i], n, cx, cy, 100, 0.15);
    else {
      double a = tau * rng_uniform(&g), b = tau * rng_uniform(&g);
      for (int j = 0; j < n; j++) {
        double t = tau * j / n, r = 100 * (1 + 0.08 * sin(2 * t + a) + 0.05 * sin(5 * t + b));
        p[i][j] = (vec2){cx + r * cos(t), cy + r * sin(t)};
      }
    }
    cp[i] = (crossing_poly){p[i], n};
  }
  double best = 1e300, sum = 0;
  int groups = 0, loops = 0, holes = 0, news = 0, points = 0, rc = 0;
  for (int r = 0; r < repeat && rc == 0; r++) {
    polyunion_result u;
    double t0 = wallclock();
    int res = polyunion(cp, k, &u);
    double t = wallclock() - t0;
    if (res != 0) {
      progname_eprintf("bench: %s: the union is refused (%s at %s %s)\n", in,
              u.status == POLYUNION_PINCH ? "it pinches" : "rounding", ARGS_G(u.at.x), ARGS_G(u.at.y));
      rc = 1;
    } else if (r == 0) {
      groups = u.ngroups, loops = u.nloops;
      for (int l = 0; l < u.nloops; l++) {
        holes += u.hole[l];
        sum += area2(u.pt + u.first[l], u.first[l + 1] - u.first[l]);
      }
      for (int gi = 0; gi < u.ngroups; gi++) news += u.newpts[gi];
      points = u.first[u.nloops];
    }
    if (t < best) best = t;
    polyunion_free(&u);
  }
  if (rc == 0)
    printf("%s,%d,%d,%d,%d,%d,%d,%d,%.3f,%.4f,%d,%.17g\n", in, k, k * n, groups, loops, holes, news, repeat,
           best * 1e3, best * 1e6 / ((double)k * n), points, sum);
  for (int i = 0; i < k; i++) free(p[i]);
  free(p), free(cp);
  return rc;
}

int bench_union(int argc, char **argv) {
  int repeat = 5, nin = 0;
  const char **in = xcalloc((size_t)argc + 4, sizeof *in);
  char err[300], shown[200];
  for (int i = 2; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    long x;
    int k, n, used = 0;
    char c;
    if (strcmp(a, "--repeat") == 0) {
      if (!v) {
        progname_eprintf("bench: an option needs a value (%s)\n%s", a, union_usage);
        free(in);
        return 2;
      }
      if (args_long(a, v, 1, 10000, &x, err, sizeof err) != 0) {
        progname_eprintf("bench: %s\n%s", err, union_usage);
        free(in);
        return 2;
      }
      repeat = (int)x;
      i++;
    } else if ((strncmp(a, "blob:", 5) == 0 || strncmp(a, "star:", 5) == 0) &&
               sscanf(a + 5, "%d:%d%n%c", &k, &n, &used, &c) == 2 && a[5 + used] == 0 && k >= 1 && k <= 64 && n >= 3 &&
               n <= 1000000) {
      in[nin++] = a;
    } else {
      args_show(a, shown, sizeof shown);
      progname_eprintf("bench: --union takes blob:K:N or star:K:N, K contours (1 to 64) of N points (3 to 1000000) "
              "(%s)\n%s", shown, union_usage);
      free(in);
      return 2;
    }
  }
  if (nin == 0)
    for (size_t i = 0; i < sizeof defaults / sizeof *defaults; i++) in[nin++] = defaults[i];
  printf("input,contours,points,groups,loops,holes,new_vertices,runs,union_ms,us_per_point,loop_points,area2\n");
  int rc = 0;
  for (int f = 0; f < nin && rc == 0; f++) {
    int k, n;
    sscanf(in[f] + 5, "%d:%d", &k, &n);
    rc = one(in[f], in[f][0] == 's', k, n, repeat);
  }
  free(in);
  return rc;
}
