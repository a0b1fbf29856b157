/* tilesim-mpirun.c -- run an unmodified MPI program on tilesim's machines.
 *
 *   tilesim-mpirun -np N [MACHINE OPTIONS] [--compute none|blocks|host] ./prog [ARGS]
 *
 * The program is built by tilesim-mpicc.  It is loaded once, and each of
 * the N ranks gets its own copy of its writable data (mpirun/loader.h: its
 * own globals and statics, its constructors and destructors run in it) and
 * its own libc state (mpirun/libc.h), and runs its main as a rank of the
 * simulated machine (machine/launch.h; or of threads), calling
 * the MPI library linked into this program (mpi/), which is built on mp.h.
 * The program's stdout and stderr are its ranks' own; the run's summary
 * goes where --stats says.  Exit status: the program's (the first rank, by
 * number, whose main returned or exit()ed non-zero), a rank's MPI_Abort
 * code, 1 for a failed run (a deadlock, an error under
 * MPI_ERRORS_ARE_FATAL, a rank that ended without MPI_Finalize), 128 + the
 * signal for a crash, 2 for bad usage.  tilesim-mpirun(1) is its manual. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "mpirun/compute.h"
#include "mpirun/crash.h"
#include "mpirun/cxx.h"
#include "mpirun/elfprog.h"
#include "mpi/init.h"
#include "machine/launch.h"
#include "mpirun/libc.h"
#include "mpirun/loader.h"
#include "machine/machine.h"
#include "mpi/mpi.h"
#include "mpi/settings.h"
#include "util/xmem.h"

static const char prog[] = "tilesim-mpirun";

extern char **environ;

static const char usage_text[] =
    "usage: tilesim-mpirun -np N [--procs P] [MACHINE OPTIONS] [--compute none|blocks|host]\n"
    "                      [--coll SPEC] [--fs SPEC] [--stack BYTES] [--stats FILE]\n"
    "                      PROGRAM [ARGS]\n"
    "       (tilesim-mpirun --help: every option)\n";

static void help(void) {
  fputs(usage_text, stdout);
  fputs("\n"
        "Run PROGRAM, an MPI program built by tilesim-mpicc, as N ranks of the simulated\n"
        "machine (deterministic, simulated seconds) or of threads: every rank its own copy\n"
        "of the program's globals and of its libc state (getopt, rand, strtok), the clocks\n"
        "and sleeps the machine's.\n"
        "\n"
        "  -np N, -n N, --np N   ranks (1 to 1000000; threads: 1 to 4096)\n",
        stdout);
  fputs(machine_help, stdout);
  fputs("                     (--procs: default one per rank; --trace names the MPI calls\n"
        "                     as the simulator's events: send, recv, wait)\n"
        "  --compute MODE     what the program's own computing costs: none (default: only\n"
        "                     tilesim_compute(units) x c, smpi_execute_flops(f) / --flops,\n"
        "                     smpi_execute(s)); blocks (also each basic block run,\n"
        "                     --block-c seconds: build with tilesim-mpicc --count-blocks;\n"
        "                     deterministic); host (also the host's processor time between\n"
        "                     MPI calls: not reproducible, and the summary says so)\n"
        "  --block-c S        seconds per basic block (default 1e-9; tilesim-bench\n"
        "                     --calibrate measures this host's)\n"
        "  --flops F          smpi_execute_flops's rate, flop/s (default 1e9)\n"
        "  --coll SPEC        the collectives' algorithms: mpich (default: MPICH's choice\n"
        "                     by size and ranks), linear, or COLL=ALG,... (--coll help lists\n"
        "                     them)\n"
        "  --fs MOUNT[,dir=DIR][,latency=S][,bandwidth=B]\n"
        "                     a file system of the machine for MPI-IO, mounted at MOUNT:\n"
        "                     its files in the host's DIR (default the same path; /scratch:\n"
        "                     $TMPDIR/tilesim-scratch-UID), S seconds and 1/B seconds a\n"
        "                     byte per request, one request at a time (default 1e-4, 1e9)\n"
        "  --poll-cost S      seconds a MPI_Test or MPI_Iprobe that finds nothing costs\n"
        "                     (default 1e-6), and a one-sided synchronisation that waits\n"
        "                     for nothing, so that polling loops move the clock\n"
        "  --wtime-cost S     seconds each read of the clock costs (MPI_Wtime, libc's\n"
        "                     and C++'s clocks; default 0)\n"
        "  --stack BYTES      each rank's stack (default 1 MiB; 16k to 1G)\n"
        "  --stats FILE       the run's summary, a CSV header and one row (tilesim(7)'s\n"
        "                     columns, then compute and reproducible): FILE, or - for\n"
        "                     stdout after the program's output\n"
        "  -h, --help         this text\n",
        stdout);
}

static int bad_usage(const char *why, const char *arg) {
  char shown[200] = "";
  if (arg) args_show(arg, shown, sizeof shown);
  fprintf(stderr, "%s: %s%s%s%s\n", prog, why, arg ? " (" : "", shown, arg ? ")" : "");
  fputs(usage_text, stderr);
  return 2;
}

/* ==== the ranks =========================================================== */

typedef struct {
  int argc;
  char **argv;         /* the rank's own copy of the arguments */
  int returned;        /* main returned or the rank called exit */
  int status;          /* with this status */
} rank_info;

static rank_info *info;   /* [n]: rank_entry's and on_exit's */
static loader *ld;

/* A rank called exit(status) (its handlers and the program's destructors
 * run first) or _exit(status): before MPI_Finalize, the run stops (a real
 * mpirun reports such a process too). */
static void on_exit_call(mp *self, int status, int run_handlers) {
  rank_info *ri = &info[mp_rank(self)];
  if (run_handlers) loader_finish(ld, mp_rank(self), status);
  int mpi = init_rank_end(self);
  if (mpi == INIT_UNFINALIZED) {
    char why[160];
    snprintf(why, sizeof why, "rank %d called exit(%d) without calling MPI_Finalize", mp_rank(self), status);
    mp_abort(self, 1, why);
  }
  ri->returned = 1;
  ri->status = status;
}

/* A rank called abort(): its MPI state goes before the run stops. */
static void on_abort_call(mp *self) { init_rank_end(self); }

static void rank_entry(mp *self, void *ud) {
  rank_info *ri = ud;
  int r = mp_rank(self);
  loader_main_fn main_fn = loader_start(ld, r, ri->argc, ri->argv, environ);
  int status = main_fn(ri->argc, ri->argv, environ);
  loader_finish(ld, r, status);   /* as exit(status) after main returns */
  compute_settle();   /* what it computed after its last call */
  fflush(stdout);
  if (init_rank_end(self) == INIT_UNFINALIZED) {
    char why[160];
    snprintf(why, sizeof why, "rank %d returned from main without calling MPI_Finalize", mp_rank(self));
    mp_abort(self, 1, why);
  }
  ri->returned = 1;
  ri->status = status;
}

/* ==== the hooks around every call of the machine =========================
 * The compute mode's (charging what the rank computed: it may switch ranks)
 * and a C++ program's (its exceptions in flight), the latter first in and
 * last out. */

static const mp_hooks *hooks_compute, *hooks_cxx;

static void both_enter(mp *self) {
  hooks_cxx->enter(self);
  hooks_compute->enter(self);
}

static void both_leave(mp *self) {
  hooks_compute->leave(self);
  hooks_cxx->leave(self);
}

static const mp_hooks hooks_both = {both_enter, both_leave};

/* ==== the summary ========================================================= */

/* tilesim_stats_csv's header and row, each with compute and reproducible after. */
static int summary(const char *path, const tilesim_stats *st, const compute_config *cc) {
  char *text = NULL;
  size_t len = 0;
  FILE *m = open_memstream(&text, &len);
  if (!m) return -1;
  tilesim_stats_csv(m, st, 1);
  fclose(m);
  char *nl = strchr(text, '\n');
  if (!nl || len < 2) {
    free(text);
    return -1;
  }
  *nl = 0;
  text[len - 1] = 0;
  char err[600];
  atomicfile af = {NULL, NULL, NULL};
  FILE *f = stdout;
  if (strcmp(path, "-") != 0) {
    if (atomicfile_open(&af, path, "w", err, sizeof err) != 0) {
      fprintf(stderr, "%s: %s\n", prog, err);
      free(text);
      return -1;
    }
    f = af.f;
  }
  fflush(stdout);
  fprintf(f, "%s,compute,reproducible\n%s,%s,%s\n", text, nl + 1, compute_mode_name(cc->mode),
          cc->mode == COMPUTE_HOST || st->backend == NULL || strcmp(st->backend, "sim") != 0 ? "no" : "yes");
  free(text);
  if (af.f && atomicfile_close(&af, 1, err, sizeof err) != 0) {
    fprintf(stderr, "%s: %s\n", prog, err);
    return -1;
  }
  return 0;
}

/* ==== checking the program before the run ================================ */

/* A program built by tilesim-mpicc, and one that counts its blocks if
 * --compute blocks asks for that: 0, or -1 and a message saying what the
 * file is instead and how to build one. */
static int check_program(const char *path, const compute_config *cc, char *err, size_t errlen) {
  if (access(path, F_OK) != 0) {
    snprintf(err, errlen, "%s: no such program", path);
    return -1;
  }
  char what[400];
  elf_describe(path, what, sizeof what);
  if (strcmp(what, "a program built by tilesim-mpicc") != 0) {
    snprintf(err, errlen, "%s is %s, not a program built by tilesim-mpicc: build it with tilesim-mpicc (tilesim-mpicc "
             "prog.c -o prog; tilesim-mpicxx for C++)", path, what);
    return -1;
  }
  elf_prog e;
  if (elf_read(path, &e, err, errlen) != 0) return -1;
  const elf_sym *cov = elf_find(&e, "__sanitizer_cov_trace_pc");
  int has_main = e.has_main, counts = cov && !cov->defined;
  elf_free(&e);
  if (!has_main) {
    snprintf(err, errlen, "%s has no main: tilesim-mpirun runs programs, not libraries", path);
    return -1;
  }
  if (cc->mode == COMPUTE_BLOCKS && !counts) {
    snprintf(err, errlen, "--compute blocks: %s does not count its basic blocks (build it with tilesim-mpicc "
                          "--count-blocks)", path);
    return -1;
  }
  return 0;
}

/* libc's name for the process (err(3), warn(3), error(3) print it) is the
 * program's, as in its own processes; tilesim-mpirun's messages name
 * tilesim-mpirun themselves. */
static void name_process(const char *path) {
#ifdef __GLIBC__
  extern char *program_invocation_name, *program_invocation_short_name;
  const char *slash = strrchr(path, '/');
  program_invocation_name = (char *)path;
  program_invocation_short_name = (char *)(slash ? slash + 1 : path);
#else
  (void)path;
#endif
}

/* ==== main ================================================================ */

int main(int argc, char **argv) {
  machine_config mc;
  machine_config_init(&mc);
  mc.sim.warn = NULL;   /* mp's warnings name mp's tags, not the program's: the summary counts unread messages */
  mc.sim.stack = 1 << 20;
  mc.name = prog;   /* a long simulated run says how far it has got */
  compute_config cc;
  compute_config_init(&cc);
  const char *stats = NULL;
  long np = 0;
  int procs_given = 0, i;
  char err[1024];
  for (i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (a[0] != '-' || strcmp(a, "-") == 0) break;   /* the program */
    if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
      help();
      return 0;
    }
    if (machine_option_flag(a)) {
      machine_option(&mc, a, NULL, err, sizeof err);
      continue;
    }
    int known = strcmp(a, "-np") == 0 || strcmp(a, "-n") == 0 || strcmp(a, "--np") == 0 || strcmp(a, "--coll") == 0 ||
                strcmp(a, "--stats") == 0 || strcmp(a, "--poll-cost") == 0 ||
                strcmp(a, "--wtime-cost") == 0 || strcmp(a, "--fs") == 0;
    if (!known) {
      compute_config c2 = cc;
      machine_config m2 = mc;
      known = compute_option(&c2, a, "", err, sizeof err) != 0 || machine_option(&m2, a, "", err, sizeof err) != 0;
    }
    if (!known) return bad_usage("unknown option", a);
    if (!v) return bad_usage("an option needs a value", a);
    i++;
    int k;
    if (strcmp(a, "-np") == 0 || strcmp(a, "-n") == 0 || strcmp(a, "--np") == 0) {
      if (args_long(a, v, 1, MACHINE_MAX_RANKS, &np, err, sizeof err) != 0) return bad_usage(err, NULL);
    } else if (strcmp(a, "--coll") == 0) {
      if (strcmp(v, "help") == 0) {
        coll_usage(stdout);
        return 0;
      }
      if (coll_option(v, err, sizeof err) != 0) return bad_usage(err, NULL);
    } else if (strcmp(a, "--fs") == 0) {
      if (io_fs_option(v, err, sizeof err) != 0) return bad_usage(err, NULL);
    } else if (strcmp(a, "--stats") == 0) {
      if (args_name(a, v, "a file name or -", 1, err, sizeof err) != 0) return bad_usage(err, NULL);
      stats = v;
    } else if (strcmp(a, "--poll-cost") == 0 || strcmp(a, "--wtime-cost") == 0) {
      double s;
      if (args_real(a, v, "seconds", 0, 1, &s, err, sizeof err) != 0) return bad_usage(err, NULL);
      if (a[2] == 'p') init_set_poll_cost(s);
      else init_set_wtime_cost(s);
    } else if ((k = compute_option(&cc, a, v, err, sizeof err)) != 0) {
      if (k < 0) return bad_usage(err, NULL);
    } else if ((k = machine_option(&mc, a, v, err, sizeof err)) < 0) {
      return bad_usage(err, NULL);
    } else if (strcmp(a, "--ranks") == 0) {
      return bad_usage("-np N gives the ranks", NULL);
    } else {
      procs_given |= strcmp(a, "--procs") == 0;
    }
  }
  if (i >= argc) return bad_usage("no program given", NULL);
  if (np == 0) return bad_usage("-np N is needed: how many ranks", NULL);
  if (mc.backend == MACHINE_MPI)
    return bad_usage("--backend mpi: an MPI program runs under a real mpirun; tilesim-mpirun runs it on sim or "
                     "threads", NULL);
  if (mc.backend == MACHINE_THREADS && np > MACHINE_MAX_THREADS) {
    snprintf(err, sizeof err, "--backend threads runs 1 to %d ranks, a thread each; the simulator up to %d",
             MACHINE_MAX_THREADS, MACHINE_MAX_RANKS);
    return bad_usage(err, NULL);
  }
  if (mc.trace_limit_given && !mc.trace) return bad_usage("--trace-limit needs --trace", NULL);
  if (mc.backend != MACHINE_SIM && (mc.trace || mc.print_place || mc.sim.topo.kind != TOPO_NONE))
    return bad_usage("--trace, --print-place and --topology describe the simulated machine (--backend sim)", NULL);
  int n = (int)np;
  mc.ranks = n;
  if (!procs_given) mc.procs = n;
  const char *path = argv[i];
  if (check_program(path, &cc, err, sizeof err) != 0) {
    fprintf(stderr, "%s: %s\n", prog, err);
    return 2;
  }
  if (mc.backend == MACHINE_SIM) {   /* the machine must fit before anything is loaded */
    int *where = xmallocarray((size_t)n, sizeof *where), nodes;
    int bad = machine_place(&mc, n, where, &nodes, err, sizeof err) != 0 ||
              (mc.print_place && machine_print_place(stderr, &mc, n, err, sizeof err) != 0);
    free(where);
    if (bad) return bad_usage(err, NULL);
  }

  const char *outs[2] = {stats && strcmp(stats, "-") != 0 ? stats : NULL, mc.trace};
  for (int k = 0; k < 2; k++)   /* the files can be written, before any work */
    if (outs[k] && atomicfile_check(outs[k], err, sizeof err) != 0) {
      fprintf(stderr, "%s: %s\n", prog, err);
      return 1;
    }

  rlibc_setup(n, on_exit_call, on_abort_call);
  name_process(path);
  ld = loader_new(path, n, err, sizeof err);
  if (!ld) {
    fprintf(stderr, "%s: %s\n", prog, err);
    rlibc_free();
    return 1;
  }
  info = xcalloc((size_t)n, sizeof *info);
  mp_proc *procs = xmallocarray((size_t)n, sizeof *procs);
  int pargc = argc - i;
  for (int r = 0; r < n; r++) {
    rank_info *ri = &info[r];
    ri->argc = pargc;
    ri->argv = xcalloc((size_t)pargc + 1, sizeof *ri->argv);
    for (int k = 0; k < pargc; k++) ri->argv[k] = xstrdup(argv[i + k]);
    procs[r] = (mp_proc){rank_entry, ri};
  }
  hooks_compute = compute_begin(&cc, n);
  void *(*get_globals)(void) = NULL;
  *(void **)&get_globals = loader_library_symbol(ld, "__cxa_get_globals");
  int cxx = loader_cxx(ld) && mc.backend == MACHINE_SIM && get_globals;
  if (cxx) hooks_cxx = cxx_ranks_begin(n, get_globals);   /* the ranks share one thread */
  mp_set_hooks(hooks_cxx && hooks_compute ? &hooks_both : hooks_cxx ? hooks_cxx : hooks_compute);
  crash_install(prog);
  tilesim_stats st;
  int res = launch_run(&mc, n, procs, &st, err, sizeof err);
  mp_set_hooks(NULL);
  compute_end();
  fflush(stdout);
  int status = 0;
  if (res != 0) {
    fprintf(stderr, "%s: %s\n", prog, err);
    status = st.aborted && st.abort_code >= 1 && st.abort_code <= 255 ? st.abort_code : 1;
  } else {
    for (int r = 0; r < n && status == 0; r++)
      if (info[r].returned && info[r].status != 0) status = info[r].status & 255 ? info[r].status & 255 : 1;
  }
  if (stats && summary(stats, &st, &cc) != 0 && status == 0) status = 1;
  for (int r = 0; r < n; r++) {
    for (int k = 0; k < pargc; k++) free(info[r].argv[k]);
    free(info[r].argv);
  }
  free(info);
  free(procs);
  if (cxx) cxx_ranks_end();
  loader_free(ld);
  rlibc_free();
  return status;
}
