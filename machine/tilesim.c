/* tilesim.c -- the testbed's public face (tilesim.h): a whole program, and
 * runs one at a time, over the machine (machine.h) and launch.h. */
#include "machine/tilesim.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "machine/launch.h"
#include "util/xmem.h"
#ifdef TILESIM_MPI
#include <mpi.h>
#endif

struct tilesim_machine {
  machine_config mc;
  const char *stats;   /* --stats: a file, "-" (stdout) or "none" */
  const char *prog;    /* the program's name, for messages */
  int mpi_init;        /* tilesim_args called MPI_Init (MPI builds) */
};

const char *tilesim_version(void) { return TILESIM_VERSION; }

tilesim_machine *tilesim_machine_new(void) {
  tilesim_machine *m = xcalloc(1, sizeof *m);
  machine_config_init(&m->mc);
  m->mc.sim.warn = stderr;
  m->stats = "-";
  m->prog = "tilesim";
  return m;
}

void tilesim_machine_free(tilesim_machine *m) { free(m); }

int tilesim_machine_option(tilesim_machine *m, const char *opt, const char *val, char *err,
                           size_t errlen) {
  return machine_option(&m->mc, opt, val, err, errlen);
}

int tilesim_machine_flag(const char *opt) { return machine_option_flag(opt); }

int tilesim_machine_ranks(const tilesim_machine *m) {
  if (m->mc.ranks > 0) return m->mc.ranks;
  if (m->mc.backend == MACHINE_MPI) return machine_backend_ranks(MACHINE_MPI);
  return m->mc.procs;
}

const char *tilesim_machine_help(void) { return machine_help; }

char *tilesim_fmt_double(double v, char *buf, size_t len) {
  args_fmt_double(v, buf, len);
  return buf;
}

int tilesim_run_procs(const tilesim_machine *m, int nranks, const mp_proc *procs, tilesim_stats *st,
                      char *err, size_t errlen) {
  return launch_run(&m->mc, nranks, procs, st, err, errlen);
}

int tilesim_run(const tilesim_machine *m, int nranks, mp_main rank_main, void *ud, tilesim_stats *st,
                char *err, size_t errlen) {
  if (nranks < 1 || nranks > MACHINE_MAX_RANKS) {
    if (st) memset(st, 0, sizeof *st);
    snprintf(err, errlen, "%d ranks: a run has 1 to %d", nranks, MACHINE_MAX_RANKS);
    return -1;
  }
  mp_proc *procs = xmallocarray((size_t)nranks, sizeof *procs);
  for (int r = 0; r < nranks; r++) procs[r] = (mp_proc){rank_main, ud};
  int res = launch_run(&m->mc, nranks, procs, st, err, errlen);
  free(procs);
  return res;
}

/* ==== the summary ========================================================= */

static void num(FILE *f, double v, int shown) {
  char buf[40];
  fputc(',', f);
  if (!shown) return;
  args_fmt_double(v, buf, sizeof buf);
  fputs(buf, f);
}

void tilesim_stats_csv(FILE *f, const tilesim_stats *st, int header) {
  if (header)
    fputs("backend,ranks,procs,makespan,messages,bytes,compute_sum,compute_max,wait_sum,wait_max,"
          "cpu_wait_sum,cpu_wait_max,overhead_sum,overhead_max,unread,deadlock,abort_code\n",
          f);
  fprintf(f, "%s,%d,%d", st->backend ? st->backend : "", st->ranks, st->procs);
  num(f, st->makespan, 1);
  fprintf(f, ",%lld,%lld", st->messages, st->bytes);
  int all = st->measured >= 2, wait = st->measured >= 1;
  num(f, st->compute_sum, all);
  num(f, st->compute_max, all);
  num(f, st->wait_sum, wait);
  num(f, st->wait_max, wait);
  num(f, st->cpu_wait_sum, all);
  num(f, st->cpu_wait_max, all);
  num(f, st->overhead_sum, all);
  num(f, st->overhead_max, all);
  fprintf(f, ",%lld,%d,", st->unread, st->deadlock);
  if (st->aborted) fprintf(f, "%d", st->abort_code);
  fputc('\n', f);
}

/* ==== a whole program ===================================================== */

/* The program's own arguments, for tilesim_argv (read-only in the ranks). */
static int prog_argc;
static char **prog_argv;

char **tilesim_argv(int *argc) {
  if (argc) *argc = prog_argc;
  return prog_argv;
}

static const char *base_name(const char *path) {
  const char *s = path ? strrchr(path, '/') : NULL;
  return s ? s + 1 : path && *path ? path : "tilesim";
}

static void usage_line(FILE *f, const char *prog) {
  fprintf(f, "usage: %s [--procs P] [--ranks R] [MACHINE OPTIONS] [--stats FILE|-|none] [-- ARGS]"
             "   (%s --help: every option)\n",
          prog, prog);
}

static void help(const char *prog) {
  usage_line(stdout, prog);
  printf("\n"
         "Run %s, a program written against tilesim's mp.h, on a machine: the simulated\n"
         "multiprocessor (deterministic, simulated seconds), threads or MPI processes\n"
         "(tilesim %s).  The arguments after -- are the program's own.\n"
         "\n",
         prog, TILESIM_VERSION);
  fputs(machine_ranks_help, stdout);
  fputs(machine_stack_help, stdout);
  fputs(machine_help, stdout);
  fputs("  --stats FILE       where the summary goes: a CSV header and one row (backend,\n"
        "                     ranks, procs, makespan, messages, bytes, compute, wait,\n"
        "                     cpu_wait and overhead as sum and max over the ranks,\n"
        "                     unread, deadlock, abort_code); - for stdout (default),\n"
        "                     none for nowhere\n"
        "  -h, --help         this text\n"
        "\n"
        "Exit status: 0, 1 for a failed run (a deadlock, a rank's bad call, an abort:\n"
        "a rank's mp_abort code from 1 to 255 is the status), 2 for bad usage.\n",
        stdout);
}

static int bad_usage(const char *prog, const char *why, const char *arg) {
  char shown[200] = "";
  if (arg) args_show(arg, shown, sizeof shown);
  fprintf(stderr, "%s: %s%s%s%s\n", prog, why, arg ? " (" : "", shown, arg ? ")" : "");
  usage_line(stderr, prog);
  return 2;
}

int tilesim_args(int *argc, char ***argv, tilesim_machine **out) {
  char **av = *argv;
  int ac = *argc;
  *out = NULL;
  tilesim_machine *m = tilesim_machine_new();
#ifdef TILESIM_MPI
  int up = 0;
  MPI_Initialized(&up);
  if (!up) {
    MPI_Init(argc, argv);
    av = *argv, ac = *argc;
    m->mpi_init = 1;
  }
#endif
  m->prog = base_name(ac > 0 ? av[0] : NULL);
  m->mc.name = m->prog;   /* a long run says how far it has got */
  const char *prog = m->prog;
  char err[512];
  int own = ac;   /* where the program's arguments begin */
  for (int i = 1; i < ac; i++) {
    const char *a = av[i], *v = i + 1 < ac ? av[i + 1] : NULL;
    if (strcmp(a, "--") == 0) {
      own = i + 1;
      break;
    }
    if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
      help(prog);
      tilesim_machine_free(m);
      return 0;
    }
    if (machine_option_flag(a)) {
      machine_option(&m->mc, a, NULL, err, sizeof err);
      continue;
    }
    if (a[0] != '-' || a[1] == 0) {
      tilesim_machine_free(m);
      return bad_usage(prog, "the program's own arguments go after --", a);
    }
    int k;
    if (!v) {   /* the last argument: an option that needs a value, or none we know */
      machine_config scratch = m->mc;
      k = strcmp(a, "--stats") == 0 || machine_option(&scratch, a, "", err, sizeof err) != 0;
      tilesim_machine_free(m);
      return bad_usage(prog, k ? "an option needs a value" : "unknown option", a);
    }
    if (strcmp(a, "--stats") == 0) {
      if (args_name(a, v, "a file name, - or none", 1, err, sizeof err) != 0) {
        tilesim_machine_free(m);
        return bad_usage(prog, err, NULL);
      }
      m->stats = v;
    } else if ((k = machine_option(&m->mc, a, v, err, sizeof err)) <= 0) {
      tilesim_machine_free(m);
      return k < 0 ? bad_usage(prog, err, NULL) : bad_usage(prog, "unknown option", a);
    }
    i++;
  }
  const machine_config *mc = &m->mc;
  const char *why = NULL;
  if (mc->trace_limit_given && !mc->trace) why = "--trace-limit needs --trace";
  else if (mc->backend != MACHINE_SIM && mc->trace) why = "--trace traces the simulated machine (--backend sim)";
  else if (mc->backend != MACHINE_SIM && mc->sim.topo.kind != TOPO_NONE)
    why = "--topology describes the simulated machine (--backend sim)";
  else if (mc->backend != MACHINE_SIM && mc->print_place)
    why = "--print-place shows the simulated machine (--backend sim)";
  char many[160];
  if (!why && mc->backend == MACHINE_THREADS && tilesim_machine_ranks(m) > MACHINE_MAX_THREADS) {
    snprintf(many, sizeof many, "--backend threads runs 1 to %d ranks, a thread each (--ranks %d)",
             MACHINE_MAX_THREADS, tilesim_machine_ranks(m));
    why = many;
  }
  if (why) {
    tilesim_machine_free(m);
    return bad_usage(prog, why, NULL);
  }
  /* argv: the name, then the program's own arguments. */
  int n = 1;
  for (int i = own; i < ac; i++) av[n++] = av[i];
  av[n] = NULL;
  *argc = n;
  *argv = av;
  *out = m;
  return 0;
}

/* Where the summary goes: stdout, a file written atomically, or nowhere. */
static int summary(const tilesim_machine *m, const tilesim_stats *st) {
  if (strcmp(m->stats, "none") == 0) return 0;
  if (strcmp(m->stats, "-") == 0) {
    fflush(stdout);
    tilesim_stats_csv(stdout, st, 1);
    return fflush(stdout) == 0 ? 0 : -1;
  }
  atomicfile af;
  char err[600];
  if (atomicfile_open(&af, m->stats, "w", err, sizeof err) != 0) {
    fprintf(stderr, "%s: %s\n", m->prog, err);
    return -1;
  }
  tilesim_stats_csv(af.f, st, 1);
  if (atomicfile_close(&af, 1, err, sizeof err) != 0) {
    fprintf(stderr, "%s: %s\n", m->prog, err);
    return -1;
  }
  return 0;
}

int tilesim_exec(tilesim_machine *m, int nranks, mp_main rank_main, void *ud) {
  const char *prog = m->prog;
  const machine_config *mc = &m->mc;
  char err[2048];
  int n = nranks > 0 ? nranks : tilesim_machine_ranks(m), status = 0;
  int me = 0;
#ifdef TILESIM_MPI
  if (mc->backend == MACHINE_MPI) MPI_Comm_rank(MPI_COMM_WORLD, &me);
#endif
  if (mc->backend == MACHINE_SIM) {   /* the machine must fit before the run */
    int *where = xmallocarray((size_t)n, sizeof *where), nodes;
    int bad = machine_place(mc, n, where, &nodes, err, sizeof err) != 0 ||
              (mc->print_place && machine_print_place(stderr, mc, n, err, sizeof err) != 0);
    free(where);
    if (bad) status = bad_usage(prog, err, NULL);
  }
  /* The files to write can be written, before the run: a run never ends
   * in "cannot write" after all its work, nor prints a summary then. */
  const char *outs[2] = {strcmp(m->stats, "-") != 0 && strcmp(m->stats, "none") != 0 ? m->stats : NULL, mc->trace};
  for (int k = 0; k < 2 && status == 0 && me == 0; k++)
    if (outs[k] && atomicfile_check(outs[k], err, sizeof err) != 0) {
      fprintf(stderr, "%s: %s\n", prog, err);
      status = 1;
    }
  if (status == 0) {
    tilesim_stats st;
    int res = tilesim_run(m, n, rank_main, ud, &st, err, sizeof err);
    if (res != 0) {
      fflush(stdout);
      fprintf(stderr, "%s: %s\n", prog, err);
      status = st.aborted && st.abort_code >= 1 && st.abort_code <= 255 ? st.abort_code : 1;
    }
    if (me == 0 && summary(m, &st) != 0 && status == 0) status = 1;
  }
#ifdef TILESIM_MPI
  if (m->mpi_init) MPI_Finalize();
#endif
  tilesim_machine_free(m);
  return status;
}

int tilesim_main(int argc, char **argv, mp_main rank_main, void *ud) {
  tilesim_machine *m;
  int status = tilesim_args(&argc, &argv, &m);
  if (!m) return status;
  prog_argc = argc;
  prog_argv = argv;
  status = tilesim_exec(m, 0, rank_main, ud);
  prog_argc = 0;
  prog_argv = NULL;
  return status;
}
