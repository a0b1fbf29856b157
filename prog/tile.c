/* tile.c -- ./tile: contours in, one surface out (CSV report and a mesh).
 *
 *   tile STACK [-o OUT.obj|OUT.ply|OUT.stl] [--cost area|span] [--caps [--cap-style flat|apex]]
 *        [-j N] [-q] [--procs P [--backend sim|threads] [--alloc half|size] [--min-diag d]
 *         [--machine NAME] [--net ideal|bus|loggp] [--m S] [--c S] ... [--trace FILE]]
 *
 * The whole stack, any number of contours per slice, becomes one surface
 * (surface/stack.h): every band tiled exactly, on -j threads (algo/tiling.h),
 * or with --procs by the paper's parallel algorithm (algo/par_run.h) on a
 * machine (machine/launch.h), given to the surface as its tiler: on the
 * simulated machine, on threads with --backend threads, or on MPI processes
 * in the MPI build (tile-mpi, `make mpi`), each band's row then also giving
 * its time and messages.  The mesh is the same either way, bit for bit.  A
 * DICOM RT structure set is handled by tile_dicom.c, through tile_stack. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "input/contour.h"
#include "input/stackfile.h"
#include "surface/mesh.h"
#include "surface/meshio.h"
#include "surface/pool.h"
#include "util/progress.h"
#include "surface/report.h"
#include "algo/par_run.h"
#include "machine/launch.h"
#include "surface/stack.h"
#include "prog/tile_dicom.h"
#include "sim/trace.h"
#include "util/xmem.h"
#ifdef TILESIM_MPI
#include "machine/launch_mpi.h"
#endif

/* The usage hint after a bad-usage message: one line. */
static const char usage_line[] =
    "usage: tile STACK|FILE.dcm [-o OUT.obj|OUT.ply|OUT.stl] [--cost area|span] [--no-caps] [--band aligned|plain] [--join RULE] "
    "[--thickness T] [-j N] [--skip-bad] [--union] [-v|-q] [--procs P [MACHINE OPTIONS] [--trace FILE]]   (tile --help: every option)\n";

static void usage(FILE *f) {
  fputs(usage_line, f);
  if (f != stdout) return;
  fputs("       tile STACK [-o OUT.obj|OUT.ply|OUT.stl] [--cost area|span] [--no-caps]\n"
        "            [--cap-style flat|apex] [--band aligned|plain] [--join RULE]\n"
        "            [--thickness T] [-j N]\n"
        "            [--no-keyholes] [--skip-bad] [--union] [-v | -q]\n"
        "            [--procs P [--backend sim|threads] [--alloc half|size] [--min-diag d]\n"
        "             [--machine NAME] [--net ideal|bus|loggp] [--m S] [--c S]\n"
        "             [--topology NAME] [--place NAME] [--print-place]\n"
        "             [--trace FILE.csv|FILE.json [--trace-limit BYTES]]]\n"
        "       tile FILE.dcm [--list | --roi NAME|NUMBER|all ... [-o OUT.stl|DIR/ [--format stl|obj|ply]]\n"
        "            [--contours OUT.contours|DIR/] [options as for a stack]]\n"
        "\n"
        "Make one surface of the contours of STACK, any number per slice: contours\n"
        "on a slice nest (holes, islands), overlapping or touching contours of\n"
        "neighbouring slices are joined (branching by bridges), every band is the\n"
        "minimum-cost acceptable path over all start rows (Fuchs, Kedem, Uselton 1977;\n"
        "exact), a 1-1 band's on its contours aligned so that the surface follows the\n"
        "structure, and every end is closed: a closed, outward surface.\n"
        "\n"
        "  -o FILE            write the mesh: .obj, .ply (ASCII) or .stl (binary)\n"
        "  --cost area        tile weight: the triangle's area (default)\n"
        "  --cost span        tile weight: the length of the span the tile adds\n"
        "  --no-caps          leave the ends open: the bands alone (no volumes then);\n"
        "                     by default every end is closed (--caps, accepted too)\n"
        "  --cap-style flat   a cap is the region in its plane (default)\n"
        "  --cap-style apex   a fan to a point half a slice out, where it sees the whole\n"
        "                     contour (flat elsewhere)\n"
        "  --band aligned     a 1-1 band is tiled on its two contours' corners, the upper\n"
        "                     moved onto the lower's centroid and scaled to its area, and\n"
        "                     joins them where they lie: prisms, oblique cylinders and\n"
        "                     frustums come out exact, whatever their sampling (default)\n"
        "  --band plain       the paper's minimum-area band of the contours as they lie\n"
        "  --join RULE        which contours of neighbouring slices are joined (same\n"
        "                     depth, parents joined; each rule joins all the one before\n"
        "                     it joins):\n"
        "                       overlap  their regions overlap (share an interior point)\n"
        "                       touch    their closed regions meet (an edge or a corner)\n"
        "                       single   also, when each slice has exactly one outer\n"
        "                                contour, those two (default)\n"
        "                       nearest  also every contour still without a partner, to\n"
        "                                its nearest candidate there (ties: the first in\n"
        "                                canonical order): a branch beside its trunk\n"
        "                       DIST     as nearest, where the gap is at most DIST\n"
        "                     A join no bridge can make is dropped with a note.  Notes\n"
        "                     name each join made without overlap and each contour left\n"
        "                     without a partner though the next slice has candidates\n"
        "                     (its nearest and the gap); the report's joins row counts\n"
        "                     them\n"
        "  --thickness T      a stack (an ROI) of one slice becomes a closed slab T thick,\n"
        "                     half above and half below its plane (volume: area x T);\n"
        "                     without it one slice is refused.  Other stacks ignore it\n",
        f);
  fputs("  -j N               tile the bands on N threads (default: the machine's cores);\n"
        "                     the output is the same on any N\n"
        "  --no-keyholes      refuse a contour that touches itself instead of splitting\n"
        "                     a keyhole contour (loops joined by channels walked out\n"
        "                     and back, exactly) into its loops and dropping its\n"
        "                     zero-width spurs (spikes walked out and back)\n"
        "  --skip-bad         drop the contours that cannot be tiled (fewer than 3\n"
        "                     points, collinear, crossing themselves), each with a\n"
        "                     note, and tile the rest; without it every one is named\n"
        "                     and the stack refused\n"
        "  --union            say the merges of overlapping contours of a slice into\n"
        "                     their union (exact, holes and islands included) in one\n"
        "                     note for the stack; without it they are merged the\n"
        "                     same way, one note a slice (duplicates dropped either way)\n"
        "  -v, --verbose      every note in full: each duplicate point, each\n"
        "                     duplicate contour (by default repairs of one kind are\n"
        "                     counted on one line per contour or stack)\n"
        "  -q, --quiet        no notes about repaired input, no progress, on stderr\n"
        "  -h, --help         this text\n"
        "\n"
        "The parallel algorithm (Johnson, Livadas, Talele 1993) on a machine: simulated,\n"
        "threads, or MPI processes (tile-mpi under mpirun; --procs defaults to all ranks):\n",
        f);
  fputs(machine_help, f);
  fputs(par_config_help, f);
  fputs("(--trace: the trace's size is counted first, by a run that writes none.)\n"
        "\n"
        "A DICOM RT structure set (recognised by its content) instead of STACK: each ROI\n"
        "is tiled as its closed planar contours would be as a stack (patient LPS, mm;\n"
        "contours in parallel planes of any common normal are turned into z and back):\n"
        "  --list             its ROIs, CSV (the default without --roi)\n"
        "  --roi NAME|NUMBER  tile that ROI (repeatable; 'all' for every ROI)\n"
        "  -o DIR/            with several ROIs: one mesh each, DIR/NAME.stl\n"
        "  --format F         the meshes' format under -o DIR/: stl (default), obj, ply\n"
        "  --contours FILE    write the ROI as a .contours stack (DIR/ for several)\n"
        "\n"
        "CSV on stdout, a row per band:\n"
        "band,z0,z1,depth,lower,upper,junction,m,n,bridges,cost,area,volume,nodes,spans,euler,genus\n"
        "(lower, upper: the contours of the two slices by their places on the slice;\n"
        "junction: how many below - above); with --procs also procs,sim_time,\n"
        "msg_boundary,msg_backtrack,msg_bounds,msg_control,bytes,backend (sim_time: the\n"
        "master's time from sending the band's points to holding its optimum, simulated\n"
        "seconds on sim, wall-clock seconds on threads or mpi); with --topology also\n"
        "hops_per_msg,hop_bytes,max_link_msgs,max_link_bytes,link_wait: the band's\n"
        "messages over the network, links crossed per message, bytes x links, the\n"
        "busiest link's messages and bytes, seconds spent waiting for links.  Then a\n"
        "row 'cap' per cap (none with --no-caps but for one slice); a row 'joins'\n"
        "(junction: the --join rule; m: joins made without overlap; n: contour ends\n"
        "left without a partner though the neighbouring slice has candidates; bridges:\n"
        "joins dropped for want of a bridge); a row 'mesh' (vertices, triangles, area,\n"
        "volume, Euler characteristic) and a row 'component' per connected component.\n"
        "Volumes are empty where the surface is open (--no-caps).\n",
        f);
}

static int bad_usage(const char *fmt, const char *arg) {
  fprintf(stderr, "tile: ");
  fprintf(stderr, fmt, arg);
  fputc('\n', stderr);
  fputs(usage_line, stderr);
  return 2;
}

static void show_progress(void *ud, int done, int total) { progress_step(ud, done, total); }

/* The parallel run of a stack's bands (the surface's stack_tiler): the
 * algorithm on the machine, with what the run adds (a trace's stream or its
 * count, the master's progress); on a topology each band's network
 * statistics, for the report. */
typedef struct {
  machine_config mc;   /* the machine; its trace is x's stream */
  const par_config *pc;
  launch_extra x;
  void (*progress)(void *ud, int done, int total);
  void *progress_ud;
  net_stats *nets;     /* on a topology: each band's, after the run (else NULL) */
} tile_run;

static int tile_pairs(void *ud, par_pair *pairs, int npairs, char *err, size_t errlen) {
  tile_run *t = ud;
  free(t->nets);
  t->nets = t->mc.sim.topo.kind != TOPO_NONE ? xcalloc((size_t)npairs + 1, sizeof *t->nets) : NULL;
  t->x.periods = t->nets, t->x.nperiods = npairs;
  t->x.next = t->progress, t->x.next_ud = t->progress_ud;
  launch_job job = {&t->mc, &t->x, NULL};
  par_run r = {t->pc, t->mc.sim.c, t->mc.procs, launch_period_end, &t->x, NULL, NULL, 0, launch_job_run, &job};
  return par_run_pairs(&r, pairs, npairs, err, errlen);
}

/* The report's network columns (on a topology): each band's messages over
 * the network. */
static void net_fields(void *ud, FILE *f, int pair) {
  const net_stats *ns = &((const tile_run *)ud)->nets[pair];
  fprintf(f, ",%.6f,%lld,%lld,%lld,%.9f", ns->messages ? (double)ns->hops / (double)ns->messages : 0.0,
          ns->hop_bytes, ns->max_link_msgs, ns->max_link_bytes, ns->link_wait);
}

/* What tile_stack needs from the command line. */
typedef struct {
  int caps, apex, threads, parallel, quiet;
  stack_band band;    /* --band */
  machine_config mc;  /* the machine (--trace, --trace-limit) */
  par_config pc;      /* the algorithm */
  const char *held;   /* the reader's notes, printed before the surface's */
  size_t heldlen;
  match_rule join;    /* --join */
  double join_dist;
  double thickness;   /* --thickness */
} tile_opts;

/* Tile the stack s (named `name` in messages): the report on stdout (the
 * header first when header != 0; header lines prefixed by hprefix, rows by
 * prefix) and the mesh in *me (always initialised; the caller frees it).
 * 0, or -1 when the stack is refused or the parallel run failed (said on
 * stderr, in one line; the surface's notes are printed only on success). */
/* Text for stderr, through the map when there is one. */
static void say(const tile_dicom_map *map, const char *pre, const char *text, size_t len) {
  if (!len) return;
  char *t = xmalloc(len + 1);
  memcpy(t, text, len);
  t[len] = 0;
  char *m = map ? map->rewrite(map->ud, t) : t;
  if (pre[0]) tile_say_lines(stderr, m);   /* "tile: " before each line */
  else fputs(m, stderr);
  if (m != t) free(m);
  free(t);
}

static int tile_stack(void *ud, const contour_stack *s, const char *name, const tile_dicom_map *map,
                      const char *hprefix, const char *prefix, int header, mesh *me) {
  tile_opts *o = ud;
  static char err[TILE_ERR_MAX];   /* one refusal at a time (tile_stack is not reentrant) */
  memset(me, 0, sizeof *me);
  char *held = NULL;
  size_t heldlen = 0;
  FILE *notes = o->quiet ? NULL : open_memstream(&held, &heldlen);
  atomicfile tf = {NULL, NULL, NULL};
  tile_run run;
  memset(&run, 0, sizeof run);
  run.mc = o->mc;
  run.mc.trace = NULL;   /* written through tf's stream, below */
  run.pc = &o->pc;
  stack_tiler tiler = {tile_pairs, &run};
  stack_options so = {o->pc.kind, o->caps, o->apex, o->threads, o->parallel ? &tiler : NULL, notes, "tile",
                      NULL, NULL, o->join, o->join_dist, o->thickness, o->band};
  const char *tpath = o->mc.trace;
  if (o->parallel && tpath) {
    /* The trace's size first, by the same run writing none (the simulator
     * is deterministic), and none above the limit (none: not measured);
     * then the trace beside its target, renamed into place when complete. */
    size_t tl = strlen(tpath);
    int json = tl >= 5 && strcmp(tpath + tl - 5, ".json") == 0;
    int measure = o->mc.trace_limit != ULLONG_MAX;
    tile_run dry = run;
    dry.x.count_csv = !json, dry.x.count_json = json;
    dry.mc.sim.warn = NULL;
    dry.progress_ud = progress_new("tile", "measuring the trace: band", !measure || o->quiet || s->nslices < 3);
    dry.progress = dry.progress_ud ? show_progress : NULL;
    stack_tiler dtiler = {tile_pairs, &dry};
    stack_options dso = so;
    dso.tiler = &dtiler;
    dso.notes = NULL;
    stack_surface *dss = NULL;
    int dres = measure ? stack_tile(s, name, &dso, &dss, err, sizeof err) : -1;
    progress_end(dry.progress_ud);
    stack_free(dss);
    free(dry.nets);
    if (dres == 0 && trace_over_limit(dry.x.csv_bytes + dry.x.json_bytes, o->mc.trace_limit, err, sizeof err) != 0) {
      fprintf(stderr, "tile: %s: %s\n", tpath, err);
      if (notes) fclose(notes);
      free(held);
      return -1;
    }
    if (atomicfile_open(&tf, tpath, "w", err, sizeof err) != 0) {
      fprintf(stderr, "tile: %s\n", err);
      if (notes) fclose(notes);
      free(held);
      return -1;
    }
    if (json) run.x.trace_json = tf.f;
    else run.x.trace_csv = tf.f;
  }
  progress *pg = progress_new("tile", "band", o->quiet || s->nslices < 3);
  if (o->parallel) {
    run.progress_ud = pg;
    run.progress = pg ? show_progress : NULL;
  } else {
    so.progress_ud = pg;
    so.progress = pg ? show_progress : NULL;
  }
  stack_surface *ss = NULL;
  int res = stack_tile(s, name, &so, &ss, err, sizeof err);
  progress_end(pg);
  if (notes) fclose(notes);
  if (res == -2)
    fprintf(stderr, "tile: the parallel run (%s) failed: %s\n", machine_backend_name(o->mc.backend), err);
  else if (res != 0) {
    say(map, "tile: ", err, strlen(err));
  } else {
    say(map, "", o->held, o->heldlen);
    say(map, "", held, heldlen);
  }
  free(held);
  if (tf.f && atomicfile_close(&tf, res == 0, err, sizeof err) != 0 && res == 0) {
    fprintf(stderr, "tile: %s\n", err);
    res = -1;
  }
  if (res == 0) {
    int topology = o->mc.sim.topo.kind != TOPO_NONE;
    report_par par = {o->mc.procs, machine_backend_name(o->mc.backend),
                      topology ? ",hops_per_msg,hop_bytes,max_link_msgs,max_link_bytes,link_wait" : "",
                      topology ? net_fields : NULL, &run};
    if (header) report_header(stdout, hprefix, o->parallel ? &par : NULL);
    report_rows(stdout, prefix, ss, o->parallel ? &par : NULL);
    stack_take_mesh(ss, me);
  }
  stack_free(ss);
  free(run.nets);
  return res == 0 ? 0 : -1;
}

/* One option of the algorithm or of the machine: 1, 0 (neither's) or -1 (a
 * bad value), as par_config_option and machine_option say. */
static int option(machine_config *mc, par_config *pc, const char *opt, const char *val, char *err,
                  size_t errlen) {
  int k = par_config_option(pc, opt, val, err, errlen);
  return k ? k : machine_option(mc, opt, val, err, errlen);
}

static int tile_main(int argc, char **argv) {
  const char *in = NULL, *out = NULL;
  int backend_given = 0, style_given = 0, place_given = 0, no_keyholes = 0, caps_given = 0, nocaps_given = 0;
  int read_flags = CONTOUR_DROP_DEGENERATE;   /* and CONTOUR_SKIP_BAD, CONTOUR_UNION, CONTOUR_VERBOSE */
  tile_opts o;
  memset(&o, 0, sizeof o);
  o.threads = pool_cores();
  o.caps = 1;   /* closed by default */
  o.join = MATCH_SINGLE, o.join_dist = INFINITY;
  tile_dicom_opts dopt;
  memset(&dopt, 0, sizeof dopt);
  machine_config_init(&o.mc);
  par_config_init(&o.pc);
  o.mc.sim.warn = stderr;
  char err[512];
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int k = 0;
    if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
      usage(stdout);
      return 0;
    } else if (strcmp(a, "--caps") == 0) {
      o.caps = 1, caps_given = 1;
    } else if (strcmp(a, "--no-caps") == 0) {
      o.caps = 0, nocaps_given = 1;
    } else if (strcmp(a, "-q") == 0 || strcmp(a, "--quiet") == 0) {
      o.quiet = 1;
    } else if (strcmp(a, "--no-keyholes") == 0) {
      no_keyholes = 1;
    } else if (strcmp(a, "--skip-bad") == 0) {
      read_flags |= CONTOUR_SKIP_BAD;
    } else if (strcmp(a, "--union") == 0) {
      read_flags |= CONTOUR_UNION;
    } else if (strcmp(a, "-v") == 0 || strcmp(a, "--verbose") == 0) {
      read_flags |= CONTOUR_VERBOSE;
    } else if (machine_option_flag(a)) {   /* --print-place */
      option(&o.mc, &o.pc, a, NULL, err, sizeof err);
    } else if ((k = tile_dicom_option(&dopt, a, v, err, sizeof err)) != 0) {   /* DICOM input */
      if (k < 0) return bad_usage("%s", err);
      i += k - 1;
    } else if (a[0] == '-' && a[1] != 0) {
      if (!v) {   /* the last argument: an option that needs a value, or none we know */
        machine_config mscratch = o.mc;
        par_config pscratch = o.pc;
        int known = strcmp(a, "-o") == 0 || strcmp(a, "--cost") == 0 || strcmp(a, "-j") == 0 ||
                    strcmp(a, "--join") == 0 || strcmp(a, "--thickness") == 0 || strcmp(a, "--band") == 0 ||
                    strcmp(a, "--cap-style") == 0 || option(&mscratch, &pscratch, a, "", err, sizeof err) != 0;
        args_show(a, err, sizeof err);
        return bad_usage(known ? "%s needs a value" : "unknown option (%s)", err);
      }
      if (strcmp(a, "-j") == 0) {
        long j;
        if (args_long(a, v, 1, 1024, &j, err, sizeof err) != 0) return bad_usage("%s", err);
        o.threads = (int)j;
      } else if (strcmp(a, "--join") == 0) {
        if (stack_parse_join(a, v, &o.join, &o.join_dist, err, sizeof err) != 0) return bad_usage("%s", err);
      } else if (strcmp(a, "--thickness") == 0) {
        if (stack_parse_thickness(a, v, &o.thickness, err, sizeof err) != 0) return bad_usage("%s", err);
      } else if (strcmp(a, "--band") == 0) {
        int b = args_word(a, v, "aligned|plain", err, sizeof err);
        if (b < 0) return bad_usage("%s", err);
        o.band = b ? STACK_BAND_PLAIN : STACK_BAND_ALIGNED;
      } else if (strcmp(a, "--cap-style") == 0) {
        if ((o.apex = args_word(a, v, "flat|apex", err, sizeof err)) < 0) return bad_usage("%s", err);
        style_given = 1;
      } else if (strcmp(a, "-o") == 0) {
        if (args_name(a, v, "a mesh file name", 0, err, sizeof err) != 0) return bad_usage("%s", err);
        if (meshio_format_of(v) == MESHIO_NONE && !tile_dicom_is_dir(v)) {
          args_show(v, err, sizeof err);
          return bad_usage("-o takes a file ending in .obj, .ply or .stl (%s)", err);
        }
        out = v;
      } else if (strcmp(a, "--cost") == 0) {
        if (cost_parse(v, &o.pc.kind) != 0) {
          args_word(a, v, "area|span", err, sizeof err);
          return bad_usage("%s", err);
        }
      } else if ((k = option(&o.mc, &o.pc, a, v, err, sizeof err)) < 0) {
        return bad_usage("%s", err);
      } else if (k == 0) {
        args_show(a, err, sizeof err);
        return bad_usage("unknown option (%s)", err);
      }
      if (strcmp(a, "--procs") == 0) o.parallel = 1;
      if (strcmp(a, "--backend") == 0) backend_given = 1;
      if (strcmp(a, "--place") == 0) place_given = 1;
      i++;
    } else if (in) {
      args_show(a, err, sizeof err);
      return bad_usage("one contour stack at a time (%s)", err);
    } else {
      in = a;
    }
  }
  if (!in) return bad_usage("%s", "no contour stack given");
  if (!o.parallel && o.mc.backend == MACHINE_MPI && machine_backend_ranks(MACHINE_MPI) >= 2) {
    o.parallel = 1;   /* tile-mpi under mpirun -np N: the N ranks */
    o.mc.procs = machine_backend_ranks(MACHINE_MPI);
  }
  const char *tpath = o.mc.trace;
  int print_place = o.mc.print_place;
  if (o.mc.trace_limit_given && !tpath) return bad_usage("%s", "--trace-limit needs --trace");
  if (tpath && !o.parallel) return bad_usage("%s", "--trace needs --procs (it traces the simulated machine)");
  if (tpath && o.mc.backend != MACHINE_SIM) return bad_usage("%s", "--trace traces the simulated machine (--backend sim)");
  if (backend_given && !o.parallel) return bad_usage("%s", "--backend needs --procs");
  if (caps_given && nocaps_given) return bad_usage("%s", "--caps and --no-caps: one or the other");
  if (style_given && !o.caps) return bad_usage("%s", "--cap-style is for the caps; leave out --no-caps");
  int topology = o.mc.sim.topo.kind != TOPO_NONE;
  if ((topology || print_place || place_given) && !o.parallel)
    return bad_usage("%s", "--topology, --place and --print-place need --procs (they describe the simulated machine)");
  if (topology && o.mc.backend != MACHINE_SIM)
    return bad_usage("%s", "--topology describes the simulated machine (--backend sim)");
  if (topology) {   /* the machine must fit P before the input is read */
    int *where = xmallocarray((size_t)par_ranks(o.mc.procs), sizeof *where), nodes;
    int bad = machine_place(&o.mc, par_ranks(o.mc.procs), where, &nodes, err, sizeof err) != 0;
    free(where);
    if (bad) return bad_usage("%s", err);
  }
  if (print_place && machine_print_place(stderr, &o.mc, par_ranks(o.mc.procs), err, sizeof err) != 0)
    return bad_usage("%s", err);
  if (o.parallel && machine_backend_ranks(o.mc.backend) > 0 && par_ranks(o.mc.procs) > machine_backend_ranks(o.mc.backend)) {
    char msg[160];
    snprintf(msg, sizeof msg, "--procs %d needs %d ranks; the %s run has %d", o.mc.procs,
             par_ranks(o.mc.procs), machine_backend_name(o.mc.backend), machine_backend_ranks(o.mc.backend));
    return bad_usage("%s", msg);
  }

  /* The files to write can be written, checked before any work: a run
   * never prints its report and then fails to write its mesh or trace. */
  const char *outs[2] = {out && meshio_format_of(out) != MESHIO_NONE ? out : NULL, tpath};
  for (int k = 0; k < 2; k++)
    if (outs[k] && atomicfile_check(outs[k], err, sizeof err) != 0) {
      fprintf(stderr, "tile: %s\n", err);
      return 1;
    }

  /* A DICOM RT structure set (by its content): tile_dicom.c. */
  if (stackfile_is_dicom(in)) {
    tile_dicom_env env = {tile_stack, &o, bad_usage, out, o.quiet, tpath != NULL, 0 /* as below */, no_keyholes,
                          o.thickness, read_flags};
    return tile_dicom_main(&dopt, in, &env);
  }
  if (tile_dicom_given(&dopt)) {
    fprintf(stderr, "tile: %s: not a DICOM file; --list, --roi, --contours and --format read DICOM RT "
            "structure sets\n", in);
    return 1;
  }
  if (out && meshio_format_of(out) == MESHIO_NONE)
    return bad_usage("unknown mesh format, use .obj, .ply or .stl (%s)", out);

  /* (tile_dicom.c reads each ROI's stack as this one is: env.pairs = 0,
   * any number of contours per slice.)  Notes on repaired input are held
   * back until the input is accepted: a refused file gets its one-line
   * message and nothing else. */
  char *held = NULL;
  size_t heldlen = 0;
  FILE *notes = o.quiet ? NULL : open_memstream(&held, &heldlen);
  /* One slice is read, and refused by stack_tile without --thickness. */
  char *rerr = xmalloc(TILE_ERR_MAX);   /* every bad contour, a line each */
  stackfile *sf;
  int bad = stackfile_open(in, NULL, read_flags | (no_keyholes ? CONTOUR_NO_KEYHOLES : 0) | CONTOUR_ONE_SLICE, notes,
                           "tile", &sf, rerr, TILE_ERR_MAX) != 0;
  if (notes) fclose(notes);
  if (bad) {
    tile_say_lines(stderr, rerr);
    free(rerr);
    free(held);
    return 1;
  }
  free(rerr);
  /* The reader's notes go out with the surface's, if it can be made. */
  mesh me;
  o.held = held, o.heldlen = heldlen;
  int rcode = tile_stack(&o, stackfile_stack(sf), stackfile_name(sf), NULL, "", "", 1, &me) != 0;
  free(held);
  if (rcode == 0 && fflush(stdout) != 0) {
    fprintf(stderr, "tile: cannot write the report (%s)\n", strerror(errno));
    rcode = 1;
  }
  if (rcode == 0 && out && meshio_write(&me, out, err, sizeof err) != 0) {
    fprintf(stderr, "tile: %s\n", err);
    rcode = 1;
  }
  mesh_free(&me);
  stackfile_close(sf);
  return rcode;
}

#ifdef TILESIM_MPI
/* tile-mpi: rank 0 runs tile_main with the master on MPI; the others serve
 * as slaves until it is done. */
int main(int argc, char **argv) { return launch_mpi_main(argc, argv, tile_main, par_run_serve); }
#else
int main(int argc, char **argv) { return tile_main(argc, argv); }
#endif
