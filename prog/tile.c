/* tile.c -- ./tile: contours in, the optimal tiling out (CSV report and a mesh).
 *
 *   tile STACK [-o OUT.obj|OUT.ply|OUT.stl] [--cost area|span] [--caps] [-q]
 *        [--procs P [--backend sim|threads] [--alloc half|size] [--min-diag d]
 *         [--machine NAME] [--net ideal|bus|loggp] [--m S] [--c S] ... [--trace FILE]]
 *
 * Every contour is tiled with the next one in file order.  Without --procs
 * the serial solver does it (algo/tiling.h); with --procs the paper's
 * parallel algorithm does (run/run.h): on the simulated machine, or on
 * threads with --backend threads, or on MPI processes in the MPI build
 * (tile-mpi, `make mpi`), and each row also gives the pair's time and
 * messages.  The result, path and mesh are the same either way. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "atomicfile.h"
#include "contour.h"
#include "mesh.h"
#include "meshio.h"
#include "run.h"
#include "tiling.h"
#include "xmem.h"
#ifdef TILESIM_MPI
#include "run_mpi.h"
#endif

static const char usage_line[] =
    "usage: tile STACK [-o OUT.obj|OUT.ply|OUT.stl] [--cost area|span] [--caps] [-q]\n"
    "            [--procs P [--backend sim|threads] [--alloc half|size] [--min-diag d]\n"
    "             [--machine NAME] [--net ideal|bus|loggp] [--m S] [--c S]\n"
    "             [--trace FILE.csv|FILE.json]]\n";

static void usage(FILE *f) {
  fputs(usage_line, f);
  if (f != stdout) return;
  fputs("\n"
        "Tile each contour of STACK with the next one by the minimum-cost acceptable\n"
        "path over all start rows (Fuchs, Kedem, Uselton 1977; exact, O(mn log m)).\n"
        "\n"
        "  -o FILE            write the mesh: .obj, .ply (ASCII) or .stl (binary)\n"
        "  --cost area        tile weight: the triangle's area (default)\n"
        "  --cost span        tile weight: the length of the span the tile adds\n"
        "  --caps             close the first and last contours (watertight mesh)\n"
        "  -q, --quiet        no notes about repaired input on stderr\n"
        "  -h, --help         this text\n"
        "\n"
        "The parallel algorithm (Johnson, Livadas, Talele 1993) on a machine: simulated,\n"
        "threads, or MPI processes (tile-mpi under mpirun; --procs defaults to all ranks):\n",
        f);
  fputs(run_options_help, f);
  fputs("  --trace FILE       the simulated timeline: CSV, or Chrome trace JSON (.json)\n"
        "\n"
        "CSV on stdout: pair,z0,z1,m,n,cost,area,volume,nodes; with --procs also\n"
        "procs,sim_time,msg_boundary,msg_backtrack,msg_bounds,msg_control,bytes,backend.\n"
        "sim_time is the master's time from sending the pair's points to holding its\n"
        "optimum: simulated seconds when backend is sim, wall-clock seconds measured on\n"
        "this machine when it is threads or mpi.  With --caps a last row 'mesh' with the\n"
        "whole mesh's area and enclosed volume.\n",
        f);
}

static int bad_usage(const char *fmt, const char *arg) {
  fprintf(stderr, "tile: ");
  fprintf(stderr, fmt, arg);
  fputc('\n', stderr);
  fputs(usage_line, stderr);
  return 2;
}

static void progress(void *ud, int done, int total) {
  (void)ud;
  fprintf(stderr, "\rtile: pair %d of %d", done, total);
}

/* The parallel run of the whole stack, one run of the backend; fills the pairs. */
static int run_parallel(run_config *rc, const contour_stack *s, par_pair *pr, const char *trace) {
  char err[512];
  atomicfile tf = {NULL, NULL, NULL};
  for (int i = 0; i + 1 < s->n; i++) {
    memset(&pr[i], 0, sizeof pr[i]);
    pr[i].P = s->c[i].pt, pr[i].np = s->c[i].n, pr[i].zp = s->c[i].z;
    pr[i].Q = s->c[i + 1].pt, pr[i].nq = s->c[i + 1].n, pr[i].zq = s->c[i + 1].z;
  }
  if (trace) {   /* written beside the target, renamed into place when complete */
    if (atomicfile_open(&tf, trace, "w", err, sizeof err) != 0) {
      fprintf(stderr, "tile: %s\n", err);
      return -1;
    }
    size_t tl = strlen(trace);
    if (tl >= 5 && strcmp(trace + tl - 5, ".json") == 0) rc->trace_json = tf.f;
    else rc->trace_csv = tf.f;
  }
  if (isatty(2) && s->n > 2) rc->progress = progress;
  int res = run_pairs(rc, pr, s->n - 1, err, sizeof err);
  if (rc->progress) fputs("\r\033[K", stderr);
  if (res != 0) fprintf(stderr, "tile: the parallel run (%s) failed: %s\n", run_backend_name(rc->backend), err);
  if (tf.f && atomicfile_close(&tf, res == 0, err, sizeof err) != 0 && res == 0) {
    fprintf(stderr, "tile: %s\n", err);
    res = -1;
  }
  return res;
}

static int tile_main(int argc, char **argv) {
  const char *in = NULL, *out = NULL, *trace = NULL;
  int caps = 0, quiet = 0, parallel = 0, backend_given = 0;
  run_config rc;
  run_config_init(&rc);
  rc.machine.warn = stderr;
  char err[512];
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
      usage(stdout);
      return 0;
    } else if (strcmp(a, "--caps") == 0) {
      caps = 1;
    } else if (strcmp(a, "-q") == 0 || strcmp(a, "--quiet") == 0) {
      quiet = 1;
    } else if (a[0] == '-' && a[1] != 0) {
      int k = 0;
      if (!v) return bad_usage("option %s needs a value", a);
      if (strcmp(a, "-o") == 0) {
        if (meshio_format_of(v) == MESHIO_NONE)
          return bad_usage("unknown mesh format, use .obj, .ply or .stl (%s)", v);
        out = v;
      } else if (strcmp(a, "--cost") == 0) {
        if (cost_parse(v, &rc.kind) != 0) return bad_usage("unknown cost, use area or span (%s)", v);
      } else if (strcmp(a, "--trace") == 0) {
        trace = v;
      } else if ((k = run_option(&rc, a, v, err, sizeof err)) < 0) {
        return bad_usage("%s", err);
      } else if (k == 0) {
        return bad_usage("unknown option (%s)", a);
      }
      if (strcmp(a, "--procs") == 0) parallel = 1;
      if (strcmp(a, "--backend") == 0) backend_given = 1;
      i++;
    } else if (in) {
      return bad_usage("one contour stack at a time (%s)", a);
    } else {
      in = a;
    }
  }
  if (!in) return bad_usage("%s", "no contour stack given");
  if (!parallel && rc.backend == RUN_MPI && run_backend_ranks(RUN_MPI) >= 2) {
    parallel = 1;   /* tile-mpi under mpirun -np N: the N ranks */
    rc.procs = run_backend_ranks(RUN_MPI);
  }
  if (trace && !parallel) return bad_usage("%s", "--trace needs --procs (it traces the simulated machine)");
  if (trace && rc.backend != RUN_SIM) return bad_usage("%s", "--trace traces the simulated machine (--backend sim)");
  if (backend_given && !parallel) return bad_usage("%s", "--backend needs --procs");
  if (parallel && run_backend_ranks(rc.backend) > 0 && run_ranks(rc.procs) > run_backend_ranks(rc.backend)) {
    char msg[160];
    snprintf(msg, sizeof msg, "--procs %d needs %d ranks; the %s run has %d", rc.procs,
             run_ranks(rc.procs), run_backend_name(rc.backend), run_backend_ranks(rc.backend));
    return bad_usage("%s", msg);
  }

  contour_stack s;
  /* Notes on repaired input are held back until the input is accepted: a
   * refused file gets its one-line message and nothing else. */
  char *held = NULL;
  size_t heldlen = 0;
  FILE *notes = quiet ? NULL : open_memstream(&held, &heldlen);
  int bad = contour_read(in, &s, notes, "tile", err, sizeof err) != 0 ||
            contour_stack_pairs(&s, strcmp(in, "-") == 0 ? "<stdin>" : in, err, sizeof err) != 0;
  if (notes) fclose(notes);
  if (bad) {
    fprintf(stderr, "tile: %s\n", err);
    if (s.c) contour_stack_free(&s);
    free(held);
    return 1;
  }
  if (heldlen) fwrite(held, 1, heldlen, stderr);
  free(held);
  int npairs = s.n - 1, rcode = 0;
  par_pair *pr = NULL;
  if (parallel) {
    pr = xcalloc((size_t)npairs, sizeof *pr);
    if (run_parallel(&rc, &s, pr, trace) != 0) {
      for (int i = 0; i < npairs; i++) tiling_free(&pr[i].t);
      free(pr);
      contour_stack_free(&s);
      return 1;
    }
  }

  mesh me;
  mesh_init(&me, &s);
  int progress_line = !parallel && isatty(2) && s.n > 2;
  double total_cost = 0;
  unsigned long long total_nodes = 0;
  printf("pair,z0,z1,m,n,cost,area,volume,nodes%s\n",
         parallel ? ",procs,sim_time,msg_boundary,msg_backtrack,msg_bounds,msg_control,bytes,backend" : "");
  for (int i = 0; i < npairs; i++) {
    const contour *P = &s.c[i], *Q = &s.c[i + 1];
    tiling t;
    if (parallel) t = pr[i].t;
    else tiling_solve(P->pt, P->n, P->z, Q->pt, Q->n, Q->z, rc.kind, -1, &t);
    double area, volume;
    mesh_add_band(&me, &s, i, &t, &area, &volume);
    printf("%d,%.17g,%.17g,%d,%d,%.17g,%.17g,%.17g,%llu", i, P->z, Q->z, P->n, Q->n, t.cost, area,
           volume, (unsigned long long)t.count.nodes);
    if (parallel) {
      const par_counts *c = &pr[i].counts;
      uint64_t bytes = 0;
      for (int k = 0; k < PAR_KINDS; k++) bytes += c->bytes[k];
      printf(",%d,%.9f,%llu,%llu,%llu,%llu,%llu,%s", rc.procs, pr[i].time,
             (unsigned long long)c->msgs[PAR_BOUNDARY], (unsigned long long)c->msgs[PAR_BACKTRACK],
             (unsigned long long)c->msgs[PAR_BOUNDS], (unsigned long long)c->msgs[PAR_CONTROL],
             (unsigned long long)bytes, run_backend_name(rc.backend));
    }
    putchar('\n');
    total_cost += t.cost;
    total_nodes += t.count.nodes;
    tiling_free(&t);
    if (progress_line) fprintf(stderr, "\rtile: pair %d of %d", i + 1, npairs);
  }
  if (progress_line) fputs("\r\033[K", stderr);
  if (caps) {
    mesh_add_caps(&me, &s);
    printf("mesh,%.17g,%.17g,,,%.17g,%.17g,%.17g,%llu%s\n", s.c[0].z, s.c[s.n - 1].z, total_cost,
           mesh_area(&me), mesh_volume(&me), total_nodes, parallel ? ",,,,,,,," : "");
  }
  if (fflush(stdout) != 0) {
    fprintf(stderr, "tile: cannot write the report (%s)\n", strerror(errno));
    rcode = 1;
  }
  if (rcode == 0 && out && meshio_write(&me, out, err, sizeof err) != 0) {
    fprintf(stderr, "tile: %s\n", err);
    rcode = 1;
  }
  free(pr);
  mesh_free(&me);
  contour_stack_free(&s);
  return rcode;
}

#ifdef TILESIM_MPI
/* tile-mpi: rank 0 runs tile_main with the master on MPI; the others serve
 * as slaves until it is done. */
int main(int argc, char **argv) { return run_mpi_main(argc, argv, tile_main); }
#else
int main(int argc, char **argv) { return tile_main(argc, argv); }
#endif
