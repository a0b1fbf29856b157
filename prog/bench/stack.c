/* stack.c -- ./bench --stack: the stack tiler's speed: whole
 * stacks, several contours per slice, made into one closed surface
 * (surface/stack.h: slices, nesting, correspondence, bridges, every band
 * tiled exactly, caps, the mesh and its components), on 1, 2, ... threads.
 *
 *   bench --stack [INPUT...] [-j LIST] [--repeat R] [--apex] [--join RULE]
 *
 * INPUT is a .contours stack or FILE.dcm:ROI (an RT structure set's ROI by
 * name or number); by default dicompyler's BODY (141 contours on 98 slices,
 * up to 4 a slice) and Lt Lung (165 on 80, up to 7 a slice, 77 holes), the
 * issue's speed target, and prostate_0 (92 slices of one contour).  One CSV
 * row per input and thread count: read_ms is reading the file and making
 * its stack, tile_ms the best of R runs of stack_tile (caps on),
 * band_ms tile_ms per band, speedup the first thread count's tile_ms over
 * this one's.  Runs go in rounds (every thread count once, then again), so
 * a slow spell of the machine touches every count alike.  cost (the bands'
 * optima summed) and volume (the mesh's) are checksums: a fast wrong answer
 * shows. */
#include "prog/bench/bench.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "prog/bench/data.h"
#include "input/contour.h"
#include "util/progname.h"
#include "input/stackfile.h"
#include "surface/stack.h"
#include "util/wallclock.h"
#include "util/xmem.h"

static const char *defaults[] = {"tests/data/rtstruct/dicompyler_rtss.dcm:BODY",
                                 "tests/data/rtstruct/dicompyler_rtss.dcm:Lt Lung",
                                 "tests/data/slicerrt/prostate_0.contours"};

/* The stack of one input (NULL after a message); the time to read the
 * file and make its stack in *ms. */
static stackfile *load(const char *input, double *ms) {
  char err[1024], path[1024], found[3000];
  const char *colon = strstr(input, ".dcm:");
  if (colon) snprintf(path, sizeof path, "%.*s", (int)(colon + 4 - input), input);
  if (bench_data_find(colon ? path : input, NULL, found, sizeof found) != 0) {   /* installed, or the source tree */
    progname_eprintf("bench: %s\n", found);
    return NULL;
  }
  stackfile *sf;
  double t0 = wallclock();
  int rc = stackfile_open(found, colon ? colon + 5 : NULL, 0, NULL, progname_as("bench"), &sf, err, sizeof err);
  *ms = (wallclock() - t0) * 1e3;
  if (rc != 0) progname_eprintf("bench: %s\n", err);
  return sf;
}

static const char stack_usage[] =
    "usage: bench --stack [STACK|FILE.dcm:ROI...] [-j LIST] [--repeat R] [--apex] [--join RULE]   "
    "(bench --help: every mode)\n";

int bench_stack(int argc, char **argv) {
  int repeat = 5, apex = 0, nj = 2, js[ARGS_LIST_MAX] = {1, 2}, nin = 0;
  match_rule join = MATCH_SINGLE;
  double join_dist = INFINITY;
  const char **in = xcalloc((size_t)argc + 4, sizeof *in);
  char err[300], shown[200];
  for (int i = 2; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL, *why = NULL;
    if (strcmp(a, "--repeat") == 0 || strcmp(a, "-j") == 0) {
      long x;
      args_list l;
      if (!v) {
        snprintf(err, sizeof err, "an option needs a value (%s)", a);
        why = err;
      } else if (a[1] == 'j' ? args_list_parse(a, v, 1, 1, 1024, &l, err, sizeof err) != 0
                             : args_long(a, v, 1, 10000, &x, err, sizeof err) != 0) {
        why = err;
      } else if (a[1] == 'j') {
        nj = l.n;
        for (int k = 0; k < l.n; k++) js[k] = (int)l.v[k];
        i++;
      } else {
        repeat = (int)x;
        i++;
      }
    } else if (strcmp(a, "--apex") == 0) {
      apex = 1;
    } else if (strcmp(a, "--join") == 0) {
      if (!v) {
        snprintf(err, sizeof err, "an option needs a value (%s)", a);
        why = err;
      } else if (stack_parse_join(a, v, &join, &join_dist, err, sizeof err) != 0) {
        why = err;
      }
      i++;
    } else if (a[0] == '-' || !a[0]) {
      args_show(a, shown, sizeof shown);
      snprintf(err, sizeof err, "%s (%s)", a[0] ? "unknown option" : "a file name is not empty", shown);
      why = err;
    } else {
      in[nin++] = a;
    }
    if (why) {
      progname_eprintf("bench: %s\n%s", why, stack_usage);
      free(in);
      return 2;
    }
  }
  if (nin == 0)
    for (size_t i = 0; i < sizeof defaults / sizeof *defaults; i++) in[nin++] = defaults[i];
  printf("input,slices,contours,points,bands,bridges,caps,threads,runs,read_ms,tile_ms,band_ms,speedup,cost,volume\n");
  int rc = 0;
  for (int f = 0; f < nin && rc == 0; f++) {
    double read_ms;
    stackfile *sf = load(in[f], &read_ms);
    if (!sf) {
      rc = 1;
      break;
    }
    const contour_stack *s = stackfile_stack(sf);
    long points = 0;
    for (int i = 0; i < s->n; i++) points += s->c[i].n;
    double *best = xmallocarray((size_t)nj, sizeof *best), cost = 0, volume = 0;
    int bands = 0, bridges = 0, caps = 0;
    for (int j = 0; j < nj; j++) best[j] = 1e300;
    for (int r = 0; r < repeat && rc == 0; r++)
      for (int j = 0; j < nj && rc == 0; j++) {
        stack_options o = {COST_AREA, 1, apex, js[j], NULL, NULL, progname_as("bench"), NULL, NULL, join, join_dist, 0,
                           STACK_BAND_ALIGNED};
        stack_surface *ss;
        double t0 = wallclock();
        char why[1024];
        int res = stack_tile(s, in[f], &o, &ss, why, sizeof why);
        double t = wallclock() - t0;
        if (res != 0) {
          progname_eprintf("bench: %s\n", why);
          rc = 1;
          break;
        }
        if (t < best[j]) best[j] = t;
        double c = 0;
        int nb = 0, nbr = 0, ncap = 0;
        for (int i = 0; i < stack_nrows(ss); i++) {
          const stack_row *x = &stack_rows(ss)[i];
          if (x->kind == STACK_BAND) nb++, nbr += x->bridges, c += x->cost;
          else ncap++;
        }
        double v = mesh_volume(stack_mesh(ss));
        if (r == 0 && j == 0) cost = c, volume = v, bands = nb, bridges = nbr, caps = ncap;
        else if (c != cost || v != volume) {
          progname_eprintf("bench: %s: -j %d gave another surface (cost %s, volume %s)\n", in[f], js[j], ARGS_G(c), ARGS_G(v));
          rc = 1;
        }
        stack_free(ss);
      }
    for (int j = 0; j < nj && rc == 0; j++)
      printf("%s,%d,%d,%ld,%d,%d,%d,%d,%d,%.3f,%.3f,%.4f,%.3f,%.17g,%.17g\n", in[f], s->nslices, s->n, points, bands,
             bridges, caps, js[j], repeat, read_ms, best[j] * 1e3, bands ? best[j] * 1e3 / bands : 0,
             best[0] / best[j], cost, volume);
    fflush(stdout);
    free(best);
    stackfile_close(sf);
  }
  free(in);
  return rc;
}
