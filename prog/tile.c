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
 * messages.  The result, path and mesh are the same either way.  A DICOM
 * RT structure set is handled by tile_dicom.c, through tile_stack. */
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
#include "run_net.h"
#include "tile_dicom.h"
#include "tiling.h"
#include "xmem.h"
#ifdef TILESIM_MPI
#include "run_mpi.h"
#endif

static const char usage_line[] =
    "usage: tile STACK [-o OUT.obj|OUT.ply|OUT.stl] [--cost area|span] [--caps] [-q]\n"
    "            [--procs P [--backend sim|threads] [--alloc half|size] [--min-diag d]\n"
    "             [--machine NAME] [--net ideal|bus|loggp] [--m S] [--c S]\n"
    "             [--topology NAME] [--place NAME] [--print-place]\n"
    "             [--trace FILE.csv|FILE.json]]\n"
    "       tile FILE.dcm [--list | --roi NAME|NUMBER|all ... [-o OUT.stl|DIR/ [--format stl|obj|ply]]\n"
    "            [--contours OUT.contours|DIR/] [options as for a stack]]\n";

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
  fputs(run_net_help, f);
  fputs("  --print-place      print where the ranks run on the machine (stderr)\n"
        "  --trace FILE       the simulated timeline: CSV, or Chrome trace JSON (.json)\n"
        "\n"
        "A DICOM RT structure set (recognised by its content) instead of STACK: each ROI\n"
        "is tiled as its closed planar contours would be as a stack (patient LPS, mm):\n"
        "  --list             its ROIs, CSV (the default without --roi)\n"
        "  --roi NAME|NUMBER  tile that ROI (repeatable; 'all' for every ROI)\n"
        "  -o DIR/            with several ROIs: one mesh each, DIR/NAME.stl\n"
        "  --format F         the meshes' format under -o DIR/: stl (default), obj, ply\n"
        "  --contours FILE    write the ROI as a .contours stack (DIR/ for several)\n"
        "\n"
        "CSV on stdout: pair,z0,z1,m,n,cost,area,volume,nodes; with --procs also\n"
        "procs,sim_time,msg_boundary,msg_backtrack,msg_bounds,msg_control,bytes,backend.\n"
        "sim_time is the master's time from sending the pair's points to holding its\n"
        "optimum: simulated seconds when backend is sim, wall-clock seconds measured on\n"
        "this machine when it is threads or mpi.  With --topology also hops_per_msg,\n"
        "hop_bytes,max_link_msgs,max_link_bytes,link_wait: the pair's messages over the\n"
        "network, links crossed per message, bytes x links, the busiest link's messages\n"
        "and bytes, seconds spent waiting for links.  With --caps a last row 'mesh' with the\n"
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

/* What tile_stack needs from the command line. */
typedef struct {
  int caps, parallel;
  const char *trace;
  run_config rc;
} tile_opts;

/* Tile the stack: the report on stdout (the header first when header != 0;
 * header lines prefixed by hprefix, rows by prefix) and the mesh in *me
 * (always initialised; the caller frees it).  0, or -1 when the parallel run
 * failed (said on stderr). */
static int tile_stack(void *ud, const contour_stack *s, const char *hprefix, const char *prefix,
                      int header, mesh *me) {
  tile_opts *o = ud;
  int npairs = s->n - 1, parallel = o->parallel;
  int topology = parallel && o->rc.machine.topo.kind != TOPO_NONE;
  par_pair *pr = NULL;
  net_stats *pnet = NULL;   /* each pair's, on a topology */
  mesh_init(me, s);
  if (parallel) {
    pr = xcalloc((size_t)npairs, sizeof *pr);
    if (topology) o->rc.pair_net = pnet = xcalloc((size_t)npairs, sizeof *pnet);
    int res = run_parallel(&o->rc, s, pr, o->trace);
    o->rc.pair_net = NULL;
    if (res != 0) {
      for (int i = 0; i < npairs; i++) tiling_free(&pr[i].t);
      free(pr);
      free(pnet);
      return -1;
    }
  }
  int progress_line = !parallel && isatty(2) && s->n > 2;
  double total_cost = 0;
  unsigned long long total_nodes = 0;
  if (header)
    printf("%spair,z0,z1,m,n,cost,area,volume,nodes%s%s\n", hprefix,
           parallel ? ",procs,sim_time,msg_boundary,msg_backtrack,msg_bounds,msg_control,bytes,backend" : "",
           topology ? ",hops_per_msg,hop_bytes,max_link_msgs,max_link_bytes,link_wait" : "");
  for (int i = 0; i < npairs; i++) {
    const contour *P = &s->c[i], *Q = &s->c[i + 1];
    tiling t;
    if (parallel) t = pr[i].t;
    else tiling_solve(P->pt, P->n, P->z, Q->pt, Q->n, Q->z, o->rc.kind, -1, &t);
    double area, volume;
    mesh_add_band(me, s, i, &t, &area, &volume);
    printf("%s%d,%.17g,%.17g,%d,%d,%.17g,%.17g,%.17g,%llu", prefix, i, P->z, Q->z, P->n, Q->n, t.cost,
           area, volume, (unsigned long long)t.count.nodes);
    if (parallel) {
      const par_counts *c = &pr[i].counts;
      uint64_t bytes = 0;
      for (int k = 0; k < PAR_KINDS; k++) bytes += c->bytes[k];
      printf(",%d,%.9f,%llu,%llu,%llu,%llu,%llu,%s", o->rc.procs, pr[i].time,
             (unsigned long long)c->msgs[PAR_BOUNDARY], (unsigned long long)c->msgs[PAR_BACKTRACK],
             (unsigned long long)c->msgs[PAR_BOUNDS], (unsigned long long)c->msgs[PAR_CONTROL],
             (unsigned long long)bytes, run_backend_name(o->rc.backend));
    }
    if (topology) {
      const net_stats *ns = &pnet[i];
      printf(",%.6f,%lld,%lld,%lld,%.9f", ns->messages ? (double)ns->hops / (double)ns->messages : 0.0,
             ns->hop_bytes, ns->max_link_msgs, ns->max_link_bytes, ns->link_wait);
    }
    putchar('\n');
    total_cost += t.cost;
    total_nodes += t.count.nodes;
    tiling_free(&t);
    if (progress_line) fprintf(stderr, "\rtile: pair %d of %d", i + 1, npairs);
  }
  if (progress_line) fputs("\r\033[K", stderr);
  if (o->caps) {
    mesh_add_caps(me, s);
    printf("%smesh,%.17g,%.17g,,,%.17g,%.17g,%.17g,%llu%s%s\n", prefix, s->c[0].z, s->c[s->n - 1].z,
           total_cost, mesh_area(me), mesh_volume(me), total_nodes, parallel ? ",,,,,,,," : "",
           topology ? ",,,,," : "");
  }
  free(pr);
  free(pnet);
  return 0;
}

static int tile_main(int argc, char **argv) {
  const char *in = NULL, *out = NULL;
  int quiet = 0, backend_given = 0, print_place = 0, place_given = 0;
  tile_opts o = {0, 0, NULL, {0}};
  tile_dicom_opts dopt;
  memset(&dopt, 0, sizeof dopt);
  run_config_init(&o.rc);
  o.rc.machine.warn = stderr;
  char err[512];
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int k = 0;
    if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
      usage(stdout);
      return 0;
    } else if (strcmp(a, "--caps") == 0) {
      o.caps = 1;
    } else if (strcmp(a, "-q") == 0 || strcmp(a, "--quiet") == 0) {
      quiet = 1;
    } else if (strcmp(a, "--print-place") == 0) {
      print_place = 1;
    } else if ((k = tile_dicom_option(&dopt, a, v, err, sizeof err)) != 0) {   /* DICOM input */
      if (k < 0) return bad_usage("%s", err);
      i += k - 1;
    } else if (a[0] == '-' && a[1] != 0) {
      if (!v) return bad_usage("option %s needs a value", a);
      if (strcmp(a, "-o") == 0) {
        if (meshio_format_of(v) == MESHIO_NONE && !tile_dicom_is_dir(v))
          return bad_usage("unknown mesh format, use .obj, .ply or .stl (%s)", v);
        out = v;
      } else if (strcmp(a, "--cost") == 0) {
        if (cost_parse(v, &o.rc.kind) != 0) return bad_usage("unknown cost, use area or span (%s)", v);
      } else if (strcmp(a, "--trace") == 0) {
        o.trace = v;
      } else if ((k = run_option(&o.rc, a, v, err, sizeof err)) < 0) {
        return bad_usage("%s", err);
      } else if (k == 0) {
        return bad_usage("unknown option (%s)", a);
      }
      if (strcmp(a, "--procs") == 0) o.parallel = 1;
      if (strcmp(a, "--backend") == 0) backend_given = 1;
      if (strcmp(a, "--place") == 0) place_given = 1;
      i++;
    } else if (in) {
      return bad_usage("one contour stack at a time (%s)", a);
    } else {
      in = a;
    }
  }
  if (!in) return bad_usage("%s", "no contour stack given");
  if (!o.parallel && o.rc.backend == RUN_MPI && run_backend_ranks(RUN_MPI) >= 2) {
    o.parallel = 1;   /* tile-mpi under mpirun -np N: the N ranks */
    o.rc.procs = run_backend_ranks(RUN_MPI);
  }
  if (o.trace && !o.parallel) return bad_usage("%s", "--trace needs --procs (it traces the simulated machine)");
  if (o.trace && o.rc.backend != RUN_SIM) return bad_usage("%s", "--trace traces the simulated machine (--backend sim)");
  if (backend_given && !o.parallel) return bad_usage("%s", "--backend needs --procs");
  int topology = o.rc.machine.topo.kind != TOPO_NONE;
  if ((topology || print_place || place_given) && !o.parallel)
    return bad_usage("%s", "--topology, --place and --print-place need --procs (they describe the simulated machine)");
  if (topology && o.rc.backend != RUN_SIM)
    return bad_usage("%s", "--topology describes the simulated machine (--backend sim)");
  if (topology) {   /* the machine must fit P before the input is read */
    int *where = xmallocarray((size_t)run_ranks(o.rc.procs), sizeof *where), nodes;
    int bad = run_net_place(&o.rc, o.rc.procs, where, &nodes, err, sizeof err) != 0;
    free(where);
    if (bad) return bad_usage("%s", err);
  }
  if (print_place && run_net_print(stderr, &o.rc, o.rc.procs, err, sizeof err) != 0)
    return bad_usage("%s", err);
  if (o.parallel && run_backend_ranks(o.rc.backend) > 0 && run_ranks(o.rc.procs) > run_backend_ranks(o.rc.backend)) {
    char msg[160];
    snprintf(msg, sizeof msg, "--procs %d needs %d ranks; the %s run has %d", o.rc.procs,
             run_ranks(o.rc.procs), run_backend_name(o.rc.backend), run_backend_ranks(o.rc.backend));
    return bad_usage("%s", msg);
  }

  /* A DICOM RT structure set (by its content): tile_dicom.c. */
  if (tile_dicom_sniff(in)) {
    tile_dicom_env env = {tile_stack, &o, bad_usage, out, quiet, o.trace != NULL, 1 /* as below */};
    return tile_dicom_main(&dopt, in, &env);
  }
  if (tile_dicom_given(&dopt)) {
    fprintf(stderr, "tile: %s: not a DICOM file; --list, --roi, --contours and --format read DICOM RT "
            "structure sets\n", in);
    return 1;
  }
  if (out && meshio_format_of(out) == MESHIO_NONE)
    return bad_usage("unknown mesh format, use .obj, .ply or .stl (%s)", out);

  contour_stack s;
  /* (tile_dicom.c checks each ROI's stack as this one is: env.pairs.)
   * Notes on repaired input are held back until the input is accepted: a
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
  mesh me;
  int rcode = tile_stack(&o, &s, "", "", 1, &me) != 0;
  if (rcode == 0 && fflush(stdout) != 0) {
    fprintf(stderr, "tile: cannot write the report (%s)\n", strerror(errno));
    rcode = 1;
  }
  if (rcode == 0 && out && meshio_write(&me, out, err, sizeof err) != 0) {
    fprintf(stderr, "tile: %s\n", err);
    rcode = 1;
  }
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
