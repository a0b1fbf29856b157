/* bench.c -- tilesim's benchmarks: pick a mode, it prints CSV on stdout.
 *
 * main only dispatches: each mode lives in a file of its own in prog/bench/
 * (bench.h declares them all, named for their options), parses
 * its own options and returns the exit status (0, 1 for a failed run, 2 for
 * bad usage).  To add a mode, add a row to `modes`. */
#include <stdio.h>
#include <string.h>

#include "prog/bench/bench.h"
#include "prog/bench/paper.h"
#include "util/progname.h"
#ifdef TILESIM_MPI
#include "algo/par_run.h"
#include "machine/launch_mpi.h"
#endif

typedef struct {
  const char *opt;                    /* the option that selects the mode */
  int (*run)(int argc, char **argv);  /* gets the whole command line */
  const char *help;                   /* every option the mode takes, then what it does */
} mode;

static const mode modes[] = {
    {"--ring", bench_ring,
     "P --laps K [--net ideal|bus|loggp] [--m S] [--c S] [--work U] [--profile NAME]\n"
     "      [--trace-csv FILE] [--trace-json FILE] [--trace-limit BYTES]\n"
     "      [--topology NAME] [--place NAME] [--hop-latency S] [--per-byte S]\n"
     "      [--switching cut-through|store-and-forward] [--tokens 1|all] [--stack BYTES]\n"
     "      [--print-place]\n"
     "      a token ring of P ranks on P processors, K laps: simulator speed (P up to\n"
     "      1000000, K up to 1e9, P x K up to 1e10; traces up to --trace-limit, 1G;\n"
     "      each rank's stack --stack, 256 KiB);\n"
     "      on a topology (tile --help lists them), --tokens all: one token a rank"},
    {"--switch", bench_switch,
     "N\n"
     "      two coroutines switching N times (2 to 1e10): ns per context switch"},
    {"--model", bench_model,
     "[--diag LIST] [--procs LIST] [-o FILE] [--alloc NAME] [--min-diag d]\n"
     "      [--block k] [--schedule NAME] [--machine NAME] [--net ideal|bus|loggp]\n"
     "      [--m S] [--c S] [--per-byte S] [--local S] [--L S] [--o S] [--g S] [--G S]\n"
     "      [--master-c S] [--table-c S] [--back-c S] [--spin S] [--o-send S]\n"
     "      [--o-send-byte S] [--o-recv S] [--o-recv-byte S] [--wake S] [--o-wake S]\n"
     "      [--slowdown F] [--slowdown-spin F] [--topology NAME] [--place NAME]\n"
     "      [--hop-latency S] [--switching MODE]   (the machine options: tile --help)\n"
     "      section 7.2: the simulated time per diagonal of mu(0), D nodes a diagonal,\n"
     "      against the paper's cD/p + 2m(p-1) (defaults: D 100,250,500, procs 2..16)"},
    {"--glass", bench_glass,
     "[--slices N] [--points N] [-o FILE]\n"
     "      the contours of a wine glass (the paper's Fig. 17), as a .contours stack"},
    {"--claims", bench_claims,
     "SPEEDUP.csv [MIN_DIAG.csv] [--require LIST]\n"
     "      the paper's seven claims (sections 6, 7), checked against the sweeps"},
    {"--claims-map", bench_claims_map,
     "[--net LIST] [--m LIST] [--c LIST] [--seed LIST] [--input STACK --pair LIST]\n"
     "      [--points LIST] [--jobs N] [-o FILE] [--machine NAME] [--per-byte S]\n"
     "      [--local S] [--L S] [--o S] [--g S] [--G S] [--master-c S] [--table-c S]\n"
     "      [--back-c S] [--o-send S] [--o-send-byte S] [--o-recv S] [--o-recv-byte S]\n"
     "      [--wake S] [--o-wake S] [--slowdown F] [--slowdown-spin F]\n"
     "      where the seven claims hold: each configuration (net, m, c, pair) swept on the\n"
     "      paper's setup and judged; CSV, a row per configuration (tilesim-plot claims)"},
    {"--calibrate", bench_calibrate,
     "[--points LIST] [--procs LIST] [--repeat R] [--seed S] [--messages K]\n"
     "      [--alloc NAME] [--block k] [--schedule NAME] [--min-diag d] [--options-only]\n"
     "      this host measured by micro-benchmarks (c per node; a message's send and\n"
     "      receive overheads, latency, gap, a sleeper's wake-up; busy cores' slowdown),\n"
     "      the simulator options that model it, and its predictions beside the threads\n"
     "      backend's times (defaults: 2000 points, procs 1,2,3, fastest of 10 runs);\n"
     "      --options-only: the options for each size and P alone, no parallel run"},
    {"--dicom", bench_dicom,
     "[FILE...] [--repeat R]\n"
     "      how fast a DICOM RT structure set is read (best of R runs, default 20) and its\n"
     "      ROIs made into stacks; a checksum of the coordinates (default: dicompyler_rtss.dcm)"},
    {"--union", bench_union,
     "[blob|star:K:N ...] [--repeat R]\n"
     "      the exact union (./tile --union) of K overlapping contours of N points on\n"
     "      one slice, smooth (blob) or spiky (star): its loops, holes, new vertices,\n"
     "      the best time of R (default blob:3:100 blob:5:1000 blob:5:10000\n"
     "      blob:8:100000 star:5:1000; best of 5), checksums"},
    {"--stack", bench_stack,
     "[STACK|FILE.dcm:ROI...] [-j LIST] [--repeat R] [--apex] [--join RULE]\n"
     "      whole stacks into one closed surface (several contours a slice: nesting,\n"
     "      branching, caps), on 1, 2, ... threads: time per stack and per band, the\n"
     "      speedup (default: dicompyler's BODY and Lt Lung, prostate_0; -j 1,2; best of 5;\n"
     "      --join as for ./tile, default single)"},
    {"--tiler", bench_tiler,
     "[--points N[,N...]] [--naive N] [--input STACK]... [--cost area|span]\n"
     "      [--seed S] [--repeat R] [--data DIR]\n"
     "      the exact serial tiler's speed and peak memory, the naive reference beside it\n"
     "      (no options: 500 and 5000 points, the naive reference at 500, prostate_0);\n"
     "      a STACK named without a folder is looked for here, in --data DIR, then in\n"
     "      the installed data (PREFIX/share/tilesim) or the source tree's"},
};
enum { NMODES = sizeof modes / sizeof *modes };

static void help_tail(void) {
  puts("Exit status: 0 done, 1 bad input or a failed run (no data row is printed for\n"
       "it), 2 bad usage (one line saying what the option takes, and the usage line).\n"
       "Progress goes to stderr: a self-rewriting line on a terminal, else a line\n"
       "every 5 s (TILESIM_PROGRESS_S sets the interval).  The manual: tilesim-bench(1).");
}

static void help(const char *name) {
  printf("usage: %s [OPTIONS]   (the paper's experiments)\n"
         "       %s MODE ...     (a benchmark mode, below; %s MODE --help: that mode)\n\n"
         "%s -- tilesim's benchmarks; each prints CSV with a header row.\n\n",
         name, name, name, name);
  printf("  %s %s\n\n", name, bench_paper_help);
  for (int i = 0; i < NMODES; i++) printf("  %s %s %s\n\n", name, modes[i].opt, modes[i].help);
  help_tail();
}

static int is_help(const char *a) { return strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0; }

static int bench_main(int argc, char **argv) {
  /* Its messages and --help name it as it was run: bench in the source
   * tree, tilesim-bench installed (util/progname.h). */
  progname_init("bench", argc > 0 ? argv[0] : NULL);
  const char *name = progname();
  if (argc >= 2 && is_help(argv[1])) {
    help(name);
    return 0;
  }
  for (int i = 0; argc >= 2 && i < NMODES; i++)
    if (strcmp(argv[1], modes[i].opt) == 0) {
      /* MODE --help (anywhere after the mode): that mode's options. */
      for (int k = 2; k < argc; k++)
        if (is_help(argv[k])) {
          printf("usage: %s %s %s\n\n", name, modes[i].opt, modes[i].help);
          help_tail();
          return 0;
        }
      return modes[i].run(argc, argv);
    }
  /* No mode: the paper's experiments, which check their own options. */
  for (int k = 2; k < argc; k++)
    if (is_help(argv[k])) {
      help(name);
      return 0;
    }
  return bench_paper(argc, argv);
}

#ifdef TILESIM_MPI
/* bench-mpi: rank 0 runs bench_main with --backend mpi the default; the
 * others serve as slaves until it is done. */
int main(int argc, char **argv) { return launch_mpi_main(argc, argv, bench_main, par_run_serve); }
#else
int main(int argc, char **argv) { return bench_main(argc, argv); }
#endif
