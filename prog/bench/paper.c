/* paper.c -- the paper's experiments: speedup against processors for
 * contours of 100..500 points (Fig. 16, 18/19), time against processors for
 * d = 20..100 (Fig. 20/21), on the simulated machine or, with --backend
 * threads, measured on this one.
 *
 *   bench [--procs LIST] [--points LIST] [--alloc half|size[,..]] [--min-diag LIST]
 *         [--m LIST] [--c LIST] [--net MODEL] [--machine NAME] [--seed S]
 *         [--input STACK [--pair K]] [-o FILE] [--jobs N] [--backend sim|threads]
 *
 * LIST is comma-separated numbers and ranges a..b.  Every combination is a
 * run; speedup = T(1)/T(P) for the same configuration (P = 1 is run, and not
 * printed, when the list lacks it).  Generated pairs are the same for every
 * configuration with the same points and seed ("generated in a somewhat
 * random fashion", section 6); their optimum, `cost`, is the same on every
 * row of a pair and doubles as a checksum.
 *
 * With --backend threads (or mpi in bench-mpi) the sim_time column holds
 * the wall-clock seconds measured here, the backend column says so, and
 * net, m and c are left empty: they describe only the simulated machine.
 * Runs are then one at a time (--jobs 1), each alone on the cores, and each
 * job is run --repeat R times (default 10; 1 on the simulator, which is
 * deterministic), in rounds (every job once, then every job again): the
 * fastest is reported, since what else runs on the machine only ever adds
 * time, and every repetition must give the same optimum.  wall_s is then
 * the job's R runs together. */
#include "prog/bench/paper.h"
#include "prog/bench/bench.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "prog/bench/net.h"
#include "prog/bench/variant.h"
#include "input/contour.h"
#include "input/gen.h"
#include "util/progname.h"
#include "util/progress.h"
#include "util/wallclock.h"
#include "util/xmem.h"

const char bench_paper_help[] =
    "[--procs LIST] [--points LIST] [--alloc LIST] [--min-diag LIST]\n"
    "      [--m LIST] [--c LIST] [--net ideal|bus|loggp] [--machine NAME] [--seed S]\n"
    "      [--input STACK [--pair K]] [-o FILE] [--jobs N] [--backend NAME]\n"
    "      [--repeat R] [--topology LIST] [--place LIST] [--hop-latency S]\n"
    "      [--switching cut-through|store-and-forward] [--print-place] [--no-wall]\n"
    "      [--variant LIST | --block LIST --schedule static|dynamic[,...]]\n"
    "      [--per-byte S] [--local S] [--L S] [--o S] [--g S] [--G S] [--master-c S]\n"
    "      [--table-c S] [--back-c S] [--spin S] [--o-send S] [--o-send-byte S]\n"
    "      [--o-recv S] [--o-recv-byte S] [--wake S] [--o-wake S] [--slowdown F]\n"
    "      [--slowdown-spin F]   (the machine options: tile --help, tilesim(7))\n"
    "      the paper's experiments (no mode option): every combination is a run;\n"
    "      LIST is numbers and ranges, e.g. 1..16 or 100,200,300.  Defaults: points\n"
    "      100,200,300,400,500, procs 1..16, alloc half, min-diag 1, the tc2000 machine.\n"
    "      --backend threads runs them on threads here (mpi in bench-mpi): sim_time is\n"
    "      then wall-clock seconds (the backend column says which), the fastest of R\n"
    "      runs (default 10).\n"
    "      --variant paper,fit,block16,dynamic,dynamic+block16: the paper's algorithm and\n"
    "      its variants side by side (variant, messages and idle_per_slave columns).\n"
    "      --no-wall leaves the wall_s column (this host's time) empty, so that the\n"
    "      same options give the same bytes on every run";

typedef struct {
  int points, procs, alloc, d, hidden, pairid;
  double m, c;
  int topo, place;   /* indices into plan's lists (-1: no topology list) */
  int block, sched;   /* the variant (variant.h) */
} job;

typedef struct {   /* what a run sends back to the parent */
  double sim_time, wall, cost;
  uint64_t msgs[PAR_KINDS], bytes, nodes;
  net_stats net;   /* on a topology */
  double idle;   /* seconds per slave waiting in receives during the pair */
  int ok;
  char err[200];
} outcome;

typedef struct {
  const job *jobs;
  int njobs;
  bench_machine base;
  unsigned long long seed;
  int repeat;          /* runs per job; the fastest is reported */
  contour_stack *input;
  int pair;
  const bench_topos *topos;   /* n == 0: the machine's own network */
  const bench_places *places;
  const bench_cfg *cfgs;   /* bench_sweep_runs: each job's machine and pair, by
                              its pairid; NULL: base, seed, input and pair */
} plan;

void bench_machine_init(bench_machine *bm) {
  machine_config_init(&bm->mc);
  par_config_init(&bm->pc);
}

int bench_option(bench_machine *bm, const char *opt, const char *val, char *err, size_t errlen) {
  if (strcmp(opt, "--trace") == 0) {   /* every machine option but this one means the same here */
    snprintf(err, errlen, "--trace: bench's sweeps write no trace (tile --trace writes one run's; bench --ring "
                          "takes --trace-csv and --trace-json)");
    return -1;
  }
  int k = par_config_option(&bm->pc, opt, val, err, errlen);
  return k ? k : machine_option(&bm->mc, opt, val, err, errlen);
}

int bench_run_pairs(const bench_machine *bm, par_pair *pairs, int npairs, launch_extra *x, char *err,
                    size_t errlen) {
  machine_config mc = bm->mc;
  mc.trace = NULL;
  launch_extra none;
  memset(&none, 0, sizeof none);
  launch_job lj = {&mc, x ? x : &none, NULL};
  par_run r = {&bm->pc, mc.sim.c, mc.procs, launch_period_end, lj.x, NULL, NULL, 0, launch_job_run, &lj};
  return par_run_pairs(&r, pairs, npairs, err, errlen);
}

void bench_make_pair(unsigned long long seed, int points, vec2 **P, vec2 **Q) {
  rng g;
  rng_seed(&g, seed * 1000003ULL + (unsigned long long)points);
  *P = xmallocarray((size_t)points, sizeof **P);
  *Q = xmallocarray((size_t)points, sizeof **Q);
  gen_star(&g, *P, points, 0, 0, 100, 0.3);
  /* The centre's two draws in this order, one statement each: as function
   * arguments their order would be the compiler's (gcc took y first, clang
   * x, and the pairs differed). */
  double cy = 4 * rng_uniform(&g) - 2;
  double cx = 4 * rng_uniform(&g) - 2;
  gen_star(&g, *Q, points, cx, cy, 95, 0.3);
}

/* The job's pair: generated (the caller frees it) or a real one; 1 if real. */
static int make_pair(const plan *pl, const job *jb, vec2 **P, int *np, double *zp, vec2 **Q, int *nq,
                     double *zq) {
  const bench_cfg *cf = pl->cfgs ? &pl->cfgs[jb->pairid] : NULL;
  const contour_stack *in = cf ? cf->input : pl->input;
  int pair = cf ? cf->pair : pl->pair;
  if (in) {
    const contour *a = &in->c[pair], *b = &in->c[pair + 1];
    *P = a->pt, *np = a->n, *zp = a->z, *Q = b->pt, *nq = b->n, *zq = b->z;
    return 1;
  }
  bench_make_pair(cf ? cf->seed : pl->seed, jb->points, P, Q);
  *np = *nq = jb->points, *zp = 0, *zq = 5;
  return 0;
}

/* The job's topology and placement into rc. */
static void job_net(const plan *pl, const job *jb, bench_machine *rc) {
  if (pl->topos->n) {
    rc->mc.sim.topo = pl->topos->v[jb->topo];
    rc->mc.sim.net = SIM_NET_TOPOLOGY;
  }
  if (pl->places->n) rc->mc.place = pl->places->v[jb->place];
}

/* One run of a job. */
static outcome one_run(const plan *pl, const job *jb) {
  outcome o;
  memset(&o, 0, sizeof o);
  vec2 *P, *Q;
  int np, nq;
  double zp, zq;
  int real = make_pair(pl, jb, &P, &np, &zp, &Q, &nq, &zq);
  bench_machine rc = pl->cfgs ? pl->cfgs[jb->pairid].rc : pl->base;
  rc.mc.procs = jb->procs;
  rc.pc.opt.alloc = (split_alloc)jb->alloc;
  rc.pc.opt.min_diag = jb->d;
  rc.pc.opt.block = jb->block;
  rc.pc.opt.schedule = (par_schedule)jb->sched;
  rc.mc.sim.m = jb->m;
  rc.mc.sim.c = jb->c;
  rc.mc.sim.warn = NULL;
  job_net(pl, jb, &rc);
  launch_extra x;
  memset(&x, 0, sizeof x);
  x.periods = &o.net, x.nperiods = 1;
  par_pair pr;
  memset(&pr, 0, sizeof pr);
  pr.P = P, pr.np = np, pr.zp = zp, pr.Q = Q, pr.nq = nq, pr.zq = zq;
  double t0 = wallclock();
  o.ok = bench_run_pairs(&rc, &pr, 1, &x, o.err, sizeof o.err) == 0;
  o.wall = wallclock() - t0;
  if (o.ok) {
    o.sim_time = pr.time;
    o.cost = pr.t.cost;
    o.nodes = pr.counts.nodes;
    for (int k = 0; k < PAR_KINDS; k++) o.msgs[k] = pr.counts.msgs[k], o.bytes += pr.counts.bytes[k];
    o.idle = pr.counts.idle / (par_ranks(jb->procs) - 1);
    tiling_free(&pr.t);
  }
  if (!real) free(P), free(Q);
  return o;
}

/* Fold run `rep` (0-based) of a job into *acc: the fastest time, the wall
 * times summed, and the optimum checked against the first run's (and the
 * node count, but where a measured run's work depends on its timing: the
 * dynamic schedule with --block k sizes its groups, hence its ghost nodes,
 * by which groups finish first). */
static void fold(const plan *pl, const job *jb, outcome *acc, const outcome *o, int rep) {
  int repeat = pl->repeat;
  int exact_work = pl->base.mc.backend == MACHINE_SIM || jb->sched != PAR_DYNAMIC || jb->block <= 1;
  if (rep == 0 || !acc->ok) {
    if (rep == 0) *acc = *o;
    return;
  }
  if (!o->ok) {
    double wall = acc->wall;
    *acc = *o;
    acc->wall += wall;
    return;
  }
  if (o->cost != acc->cost || (exact_work && o->nodes != acc->nodes)) {   /* a checksum */
    snprintf(acc->err, sizeof acc->err, "run %d of %d gave optimum %s (%llu nodes), run 1 %s (%llu)",
             rep + 1, repeat, ARGS_G(o->cost), (unsigned long long)o->nodes, ARGS_G(acc->cost),
             (unsigned long long)acc->nodes);
    acc->ok = 0;
  }
  if (o->sim_time < acc->sim_time) acc->sim_time = o->sim_time, acc->idle = o->idle, acc->nodes = o->nodes;
  acc->wall += o->wall;
}

/* What became of a worker that stopped before its last outcome (st from
 * waitpid): "was killed by signal 9 (SIGKILL): ...", with the likely cause. */
static void worker_fate(int st, char *buf, size_t len) {
  if (WIFSIGNALED(st)) {
    int sig = WTERMSIG(st);
    const char *name = "", *why = "";
    switch (sig) {
    case SIGKILL:
      name = " (SIGKILL)";
      why = ": most likely the system ran out of memory and killed it (fewer --jobs, or fewer points, "
            "need less; dmesg says if it was the out-of-memory killer)";
      break;
    case SIGSEGV: name = " (SIGSEGV)"; goto crash;
    case SIGBUS: name = " (SIGBUS)"; goto crash;
    case SIGFPE: name = " (SIGFPE)"; goto crash;
    case SIGILL: name = " (SIGILL)"; goto crash;
    case SIGABRT: name = " (SIGABRT)";
    crash:
      why = ": it crashed, a bug (please report it with the command line)";
      break;
    case SIGXCPU: name = " (SIGXCPU)", why = ": the processor time limit (ulimit -t) ran out"; break;
    case SIGXFSZ: name = " (SIGXFSZ)", why = ": the file size limit (ulimit -f) ran out"; break;
    case SIGTERM: name = " (SIGTERM)", why = ": stopped from outside"; break;
    case SIGINT: name = " (SIGINT)", why = ": interrupted"; break;
    case SIGHUP: name = " (SIGHUP)", why = ": its terminal went away"; break;
    default: break;
    }
    snprintf(buf, len, "was killed by signal %d%s%s", sig, name, why);
  } else if (WIFEXITED(st)) {
    snprintf(buf, len, "exited with status %d before its last result", WEXITSTATUS(st));
  } else {
    snprintf(buf, len, "stopped before its last result");
  }
}

/* Run every job, on `jobs` forked workers (job i on worker i mod jobs); the
 * outcomes come back in job order whatever the workers' speed.  0, or -1
 * with why in err ("worker 2 of 2, on the run with 30000 points on 3
 * processors, was killed by signal 9 (SIGKILL): ..."); the other workers
 * are stopped then. */
static int run_all(const plan *pl, outcome *out, int jobs, progress *pg, char *err, size_t errlen) {
  if (jobs > pl->njobs) jobs = pl->njobs;
  progress_step(pg, 0, jobs <= 1 ? (long long)pl->njobs * pl->repeat : pl->njobs);   /* counted from the start */
  if (jobs <= 1) {   /* in rounds: every job once, then again, so that a slow
                        spell of the machine touches all jobs alike */
    for (int rep = 0; rep < pl->repeat; rep++)
      for (int i = 0; i < pl->njobs; i++) {
        outcome o = one_run(pl, &pl->jobs[i]);
        fold(pl, &pl->jobs[i], &out[i], &o, rep);
        progress_step(pg, rep * pl->njobs + i + 1, pl->njobs * pl->repeat);
      }
    return 0;
  }
  fflush(stdout);
  fflush(stderr);
  /* One thread at the forks: the progress's own would leave the workers a
   * lock it might hold (the allocator's). */
  progress_hold(pg);
  int *fd = xmallocarray((size_t)jobs, sizeof *fd);
  pid_t *pid = xmallocarray((size_t)jobs, sizeof *pid);
  for (int w = 0; w < jobs; w++) {
    int p[2] = {-1, -1};
    if (pipe(p) != 0 || (pid[w] = fork()) < 0) {
      snprintf(err, errlen, "cannot start worker %d of %d: %s", w + 1, jobs, strerror(errno));
      if (p[0] >= 0) close(p[0]), close(p[1]);
      for (int k = 0; k < w; k++) close(fd[k]), kill(pid[k], SIGTERM), waitpid(pid[k], NULL, 0);
      free(fd), free(pid);
      return -1;
    }
    if (pid[w] == 0) {
      close(p[0]);
      for (int i = w; i < pl->njobs; i += jobs) {
        outcome o;
        for (int rep = 0; rep < pl->repeat; rep++) {
          outcome x = one_run(pl, &pl->jobs[i]);
          fold(pl, &pl->jobs[i], &o, &x, rep);
        }
        if (write(p[1], &o, sizeof o) != (ssize_t)sizeof o) _exit(1);
      }
      _exit(0);
    }
    close(p[1]);
    fd[w] = p[0];
  }
  progress_resume(pg);
  int done = 0, *next = xcalloc((size_t)jobs, sizeof *next), bad = 0, failed = -1;
  for (int w = 0; w < jobs; w++) next[w] = w;
  struct pollfd *pf = xmallocarray((size_t)jobs, sizeof *pf);
  while (done < pl->njobs && !bad) {
    for (int w = 0; w < jobs; w++) pf[w] = (struct pollfd){next[w] < pl->njobs ? fd[w] : -1, POLLIN, 0};
    if (poll(pf, (nfds_t)jobs, -1) < 0) {
      if (errno == EINTR) continue;
      snprintf(err, errlen, "waiting for the workers: %s", strerror(errno));
      bad = 1;
      break;
    }
    for (int w = 0; w < jobs; w++) {
      if (!(pf[w].revents & (POLLIN | POLLHUP))) continue;
      size_t got = 0;
      char *dst = (char *)&out[next[w]];
      while (got < sizeof(outcome)) {
        ssize_t k = read(fd[w], dst + got, sizeof(outcome) - got);
        if (k <= 0) break;
        got += (size_t)k;
      }
      if (got != sizeof(outcome)) {
        bad = 1, failed = w;
        break;
      }
      next[w] += jobs;
      done++;
      progress_step(pg, done, pl->njobs);
    }
  }
  for (int w = 0; w < jobs; w++) {
    close(fd[w]);
    if (bad && w != failed) kill(pid[w], SIGTERM);   /* its work is of no use now */
    int st;
    waitpid(pid[w], &st, 0);
    if (w == failed || (!bad && (!WIFEXITED(st) || WEXITSTATUS(st) != 0))) {
      char fate[300];
      const job *j = &pl->jobs[next[w] < pl->njobs ? next[w] : pl->njobs - 1];
      worker_fate(st, fate, sizeof fate);
      snprintf(err, errlen, "worker %d of %d, on the run with %d points on %d processor%s, %s", w + 1, jobs,
               j->points, j->procs, j->procs == 1 ? "" : "s", fate);
      bad = 1, failed = w;
    }
  }
  free(fd), free(pid), free(next), free(pf);
  return bad ? -1 : 0;
}

static const char usage_line[] =
    "usage: bench [--procs LIST] [--points LIST] [--alloc half|size[,...]] [--min-diag LIST] "
    "[--m LIST] [--c LIST] [--net MODEL] [--machine NAME] [--seed S] [--input STACK [--pair K]] "
    "[-o FILE] [--jobs N] [--backend sim|threads] [--repeat R] [--topology LIST] [--place LIST] "
    "[--hop-latency S] [--switching MODE] [--print-place] "
    "[--variant LIST | --block LIST --schedule static|dynamic[,...]] [--no-wall]   "
    "(bench --help: every mode)\n";

/* Bad usage: "bench: why" (why already says the value), the usage line, 2. */
static int usage(const char *why) { return args_usage("bench", usage_line, why, NULL); }

/* The same for a message about one argument, shown as util/args shows values. */
static int usage_arg(const char *why, const char *arg) {
  char shown[200], msg[400];
  args_show(arg, shown, sizeof shown);
  snprintf(msg, sizeof msg, "%s (%s)", why, shown);
  return usage(msg);
}

int bench_paper(int argc, char **argv) {
  args_list procs = {0}, points = {0}, diags = {0}, ms = {0}, cs = {0};
  int allocs[8] = {ALLOC_HALF}, nalloc = 1, jobs = 1, pairk = 0, repeat = 0, pair_given = 0;
  int no_wall = 0;
  int scheds[2] = {PAR_STATIC, -1}, nsched = 1, nvar = 0, lists = 0;
  args_list blocks = {0};
  bench_variant var[BENCH_VARIANTS_MAX];
  const char *outpath = NULL, *input = NULL;
  unsigned long long seed = 1993;
  bench_machine rc;
  bench_machine_init(&rc);
  char err[400];
  static bench_topos topos;
  static bench_places places;
  topos.n = places.n = 0;
  int print_place = 0, net_given = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    long x;
    int bad = 0;
    if (a[0] != '-') return usage_arg("bench takes options, not arguments; bench --help lists them", a);
    if (strcmp(a, "--no-wall") == 0) {
      no_wall = 1;
      continue;
    }
    if (strcmp(a, "--print-place") == 0) {
      print_place = 1;
      continue;
    }
    if (!v) {
      bench_machine scratch = rc;
      static const char *const own[] = {"--procs", "--points", "--min-diag", "--m", "--c", "--alloc",
                                        "--seed", "--jobs", "--repeat", "--input", "--pair", "-o",
                                        "--topology", "--place", "--block", "--schedule", "--variant"};
      int known = bench_option(&scratch, a, "", err, sizeof err) != 0;
      for (size_t k = 0; k < sizeof own / sizeof *own; k++) known |= strcmp(a, own[k]) == 0;
      return usage_arg(known ? "an option needs a value" : "unknown option", a);
    }
    i++;
    if (strcmp(a, "--topology") == 0 || strcmp(a, "--place") == 0) {
      char why[300];
      if ((a[2] == 't' ? bench_topos_parse(v, &topos, why, sizeof why)
                       : bench_places_parse(v, &places, why, sizeof why)) != 0) {
        /* the message names the option */
        if (strncmp(why, a, strlen(a)) == 0) snprintf(err, sizeof err, "%s", why);
        else snprintf(err, sizeof err, "%s: %s", a, why);
        bad = 1;
      }
    } else if (strcmp(a, "--procs") == 0) {
      bad = args_list_parse(a, v, 1, 1, MACHINE_MAX_PROCS, &procs, err, sizeof err);
    } else if (strcmp(a, "--points") == 0) {
      bad = args_list_parse(a, v, 1, 3, 100000, &points, err, sizeof err);
    } else if (strcmp(a, "--min-diag") == 0) {
      bad = args_list_parse(a, v, 1, 1, 1 << 30, &diags, err, sizeof err);
    } else if (strcmp(a, "--m") == 0 || strcmp(a, "--c") == 0) {
      bad = args_list_parse(a, v, 0, 0, 1e9, a[2] == 'm' ? &ms : &cs, err, sizeof err);
    } else if (strcmp(a, "--alloc") == 0) {
      char words[200];
      par_config_alloc_words(words, sizeof words);
      int idx[8], nwords = 1;
      for (const char *w = words; *w; w++) nwords += *w == '|';
      nalloc = args_word_list(a, v, words, idx, nwords < 8 ? nwords : 8, err, sizeof err);
      bad = nalloc < 0;
      for (int k = 0; k < nalloc; k++) {   /* the k-th name of words, parsed */
        const char *w = words;
        for (int j = 0; j < idx[k]; j++) w = strchr(w, '|') + 1;
        char name[32];
        snprintf(name, sizeof name, "%.*s", (int)strcspn(w, "|"), w);
        split_alloc al;
        if (split_alloc_parse(name, &al) != 0) xpanic("bench: alloc name %s", name);
        allocs[k] = (int)al;
      }
      lists = 1;
    } else if (strcmp(a, "--block") == 0) {
      bad = args_list_parse(a, v, 1, 1, 1 << 20, &blocks, err, sizeof err);
      lists = 1;
    } else if (strcmp(a, "--schedule") == 0) {
      int idx[2];
      nsched = args_word_list(a, v, "static|dynamic", idx, 2, err, sizeof err);
      bad = nsched < 0;
      for (int k = 0; k < nsched; k++) {
        par_schedule sch;
        if (par_schedule_parse(idx[k] ? "dynamic" : "static", &sch) != 0) xpanic("bench: schedule");
        scheds[k] = (int)sch;
      }
      lists = 1;
    } else if (strcmp(a, "--variant") == 0) {
      char why[300];
      if (bench_variant_parse(v, var, &nvar, why, sizeof why) != 0) {
        if (strncmp(why, a, strlen(a)) == 0) snprintf(err, sizeof err, "%s", why);
        else snprintf(err, sizeof err, "%s: %s", a, why);
        bad = 1;
      }
    } else if (strcmp(a, "--seed") == 0) {
      bad = args_u64(a, v, 0, ULLONG_MAX, &seed, err, sizeof err);
    } else if (strcmp(a, "--jobs") == 0) {
      bad = args_long(a, v, 1, 256, &x, err, sizeof err);
      jobs = (int)x;
    } else if (strcmp(a, "--repeat") == 0) {
      bad = args_long(a, v, 1, 1000, &x, err, sizeof err);
      repeat = (int)x;
    } else if (strcmp(a, "--input") == 0) {
      bad = args_name(a, v, "a contour stack", 1, err, sizeof err);
      input = v;
    } else if (strcmp(a, "--pair") == 0) {
      bad = args_long(a, v, 0, 1 << 30, &x, err, sizeof err);
      pairk = (int)x;
      pair_given = 1;
    } else if (strcmp(a, "-o") == 0) {
      bad = args_name(a, v, "a file name", 0, err, sizeof err);
      outpath = v;
    } else {
      int k = bench_option(&rc, a, v, err, sizeof err);
      if (k == 0) return usage_arg("unknown option", a);
      bad = k < 0;
      net_given |= strcmp(a, "--net") == 0;
    }
    if (bad) return usage(err);
  }
  if (pair_given && !input) return usage("--pair needs --input (it picks a pair of a real stack)");
  if (no_wall && rc.mc.backend != MACHINE_SIM)
    return usage("--no-wall leaves host times out, but --backend threads measures nothing else");
  if (topos.n && net_given)
    return usage("--net and --topology both choose the network: give one");
  if ((topos.n || rc.mc.sim.topo.kind != TOPO_NONE) && rc.mc.backend != MACHINE_SIM)
    return usage("--topology describes the simulated machine (--backend sim)");
  if (nvar > 0 && lists) return usage("--variant names whole variants: give it, or --alloc, --block and --schedule lists");
  if (nvar == 0) {   /* the cross product of the lists */
    if (blocks.n == 0) blocks.n = 1, blocks.v[0] = 1;
    for (int b = 0; b < nalloc; b++)
      for (int s = 0; s < nsched; s++)
        for (int k = 0; k < blocks.n; k++) {
          if (nvar == BENCH_VARIANTS_MAX) return usage("too many variants: --alloc x --schedule x --block at most 64");
          var[nvar++] = (bench_variant){(split_alloc)allocs[b], (int)blocks.v[k], (par_schedule)scheds[s]};
        }
  }
  if (rc.mc.backend != MACHINE_SIM && jobs > 1)
    return usage("--jobs runs simulations side by side; measured runs (--backend threads) go one at a time");
  int limit = machine_backend_ranks(rc.mc.backend);
  if (procs.n == 0 && limit > 0) {   /* bench-mpi: the processes mpirun gave */
    char all[32];
    snprintf(all, sizeof all, "1..%d", limit);
    args_list_parse("--procs", all, 1, 1, MACHINE_MAX_PROCS, &procs, err, sizeof err);
  }
  if (procs.n == 0) args_list_parse("--procs", "1..16", 1, 1, MACHINE_MAX_PROCS, &procs, err, sizeof err);
  for (int i = 0; limit > 0 && i < procs.n; i++)
    if (par_ranks((int)procs.v[i]) > limit) {
      char msg[160];
      snprintf(msg, sizeof msg, "--procs %d needs %d ranks; the %s run has %d", (int)procs.v[i],
               par_ranks((int)procs.v[i]), machine_backend_name(rc.mc.backend), limit);
      return usage(msg);
    }
  if (points.n == 0) args_list_parse("--points", "100,200,300,400,500", 1, 3, 100000, &points, err, sizeof err);
  if (diags.n == 0) args_list_parse("--min-diag", "1", 1, 1, 1 << 30, &diags, err, sizeof err);
  if (ms.n == 0) ms.n = 1, ms.v[0] = rc.mc.sim.m;
  if (cs.n == 0) cs.n = 1, cs.v[0] = rc.mc.sim.c;

  if (outpath && atomicfile_check(outpath, err, sizeof err) != 0) {   /* before any work */
    progname_eprintf("bench: %s\n", err);
    return 1;
  }
  contour_stack stack = {0, NULL, 0};
  if (input) {
    if (contour_read(input, &stack, NULL, progname_as("bench"), err, sizeof err) != 0 ||
        contour_stack_pairs(&stack, input, err, sizeof err) != 0) {
      if (stack.c) contour_stack_free(&stack);
      progname_eprintf("bench: %s\n", err);
      return 1;
    }
    if (pairk + 1 >= stack.n) {
      progname_eprintf("bench: %s has %d pairs, no pair %d\n", input, stack.n - 1, pairk);
      contour_stack_free(&stack);
      return 1;
    }
    points.n = 1;
    points.v[0] = stack.c[pairk].n;
  }

  /* The runs, and a P = 1 run for each configuration that lacks one. */
  int has1 = 0;
  for (int i = 0; i < procs.n; i++) has1 |= procs.v[i] == 1;
  int per = procs.n + !has1;
  int ntopo = topos.n ? topos.n : 1, nplace = places.n ? places.n : 1;
  int njobs = points.n * nvar * diags.n * ms.n * cs.n * ntopo * nplace * per;
  job *jb = xmallocarray((size_t)njobs, sizeof *jb);
  int k = 0, cfg = 0;
  for (int a = 0; a < points.n; a++)
    for (int b = 0; b < nvar; b++)
      for (int d = 0; d < diags.n; d++)
        for (int x = 0; x < ms.n; x++)
          for (int y = 0; y < cs.n; y++)
            for (int ti = 0; ti < ntopo; ti++)
              for (int pi = 0; pi < nplace; pi++, cfg++) {
                for (int p = 0; p < per; p++) {
                  int P = p < procs.n ? (int)procs.v[p] : 1;
                  jb[k++] = (job){(int)points.v[a], P, (int)var[b].alloc, (int)diags.v[d], p >= procs.n, cfg,
                                  ms.v[x], cs.v[y], ti, pi, var[b].block, (int)var[b].sched};
                }
              }
  if (repeat == 0) repeat = rc.mc.backend == MACHINE_SIM ? 1 : 10;
  plan pl = {jb, njobs, rc, seed, repeat, input ? &stack : NULL, pairk, &topos, &places, NULL};
  /* Every machine and placement fits every P, checked before any run (a
   * group of `per` jobs shares them); the maps on request, once each. */
  unsigned char seen[BENCH_NET_MAX][BENCH_NET_MAX] = {{0}};
  for (int i = 0; i < njobs; i += per) {
    if (seen[jb[i].topo][jb[i].place]) continue;
    seen[jb[i].topo][jb[i].place] = 1;
    bench_machine jr = rc;
    job_net(&pl, &jb[i], &jr);
    for (int p = 0; p < per; p++) {
      int P = jb[i + p].procs, nodes, *where = xmallocarray((size_t)par_ranks(P), sizeof *where);
      jr.mc.procs = P;
      int bad = machine_place(&jr.mc, par_ranks(P), where, &nodes, err, sizeof err) != 0 ||
                (print_place && !jb[i + p].hidden &&
                 machine_print_place(stderr, &jr.mc, par_ranks(P), err, sizeof err) != 0);
      free(where);
      if (bad) {
        free(jb);
        contour_stack_free(&stack);
        return usage(err);
      }
    }
  }
  outcome *o = xcalloc((size_t)njobs, sizeof *o);
  progress *pg = progress_new(progname_as("bench"), "run", 0);   /* a line every 5 s in a log */
  char why[600] = "";
  int rcode = run_all(&pl, o, jobs, pg, why, sizeof why);
  progress_end(pg);
  if (rcode != 0) progname_eprintf("bench: %s\n", why);
  for (int i = 0; rcode == 0 && i < njobs; i++)
    if (!o[i].ok) {
      progname_eprintf("bench: the run with %d points on %d processors failed: %s\n", jb[i].points,
              jb[i].procs, o[i].err);
      rcode = -1;
    }
  if (rcode != 0) {
    free(jb), free(o);
    contour_stack_free(&stack);
    return 1;
  }

  FILE *f = stdout;
  atomicfile af = {NULL, NULL, NULL};
  if (outpath) {   /* a temporary file beside it, renamed when complete */
    if (atomicfile_open(&af, outpath, "w", err, sizeof err) != 0) {
      progname_eprintf("bench: %s\n", err);
      free(jb), free(o);
      contour_stack_free(&stack);
      return 1;
    }
    f = af.f;
  }
  fprintf(f, "points,procs,alloc,min_diag,net,m,c,seed,sim_time,speedup,efficiency,messages,bytes,"
             "nodes,cost,wall_s,msg_boundary,msg_backtrack,msg_bounds,msg_control,input,pair,backend,%s,"
             "variant,block,schedule,idle_per_slave\n",
          bench_net_header);
  for (int i = 0; i < njobs; i++) {
    if (jb[i].hidden) continue;
    double t1 = 0;   /* T(1) of the same configuration */
    for (int j = 0; j < njobs; j++)
      if (jb[j].pairid == jb[i].pairid && jb[j].procs == 1) t1 = o[j].sim_time;
    double sp = t1 / o[i].sim_time;
    uint64_t msgs = 0;
    for (int q = 0; q < PAR_KINDS; q++) msgs += o[i].msgs[q];
    bench_machine jr = rc;   /* the job's machine */
    job_net(&pl, &jb[i], &jr);
    char machine[96] = ",,";   /* net, m, c: the simulated machine's, or empty */
    if (rc.mc.backend == MACHINE_SIM)
      snprintf(machine, sizeof machine, "%s,%.9g,%.9g", sim_net_name(jr.mc.sim.net), jb[i].m, jb[i].c);
    bench_variant bv = {(split_alloc)jb[i].alloc, jb[i].block, (par_schedule)jb[i].sched};
    char vname[64];
    bench_variant_name(&bv, vname, sizeof vname);
    char wall[32] = "";   /* this host's time, left out with --no-wall */
    if (!no_wall) snprintf(wall, sizeof wall, "%.6f", o[i].wall);
    fprintf(f, "%d,%d,%s,%d,%s,%llu,%.9f,%.6f,%.6f,%llu,%llu,%llu,%.17g,%s,%llu,%llu,%llu,%llu,%s,%d,%s",
            jb[i].points, jb[i].procs, split_alloc_name((split_alloc)jb[i].alloc), jb[i].d,
            machine, seed, o[i].sim_time, sp, sp / jb[i].procs,
            (unsigned long long)msgs, (unsigned long long)o[i].bytes, (unsigned long long)o[i].nodes,
            o[i].cost, wall, (unsigned long long)o[i].msgs[PAR_BOUNDARY],
            (unsigned long long)o[i].msgs[PAR_BACKTRACK], (unsigned long long)o[i].msgs[PAR_BOUNDS],
            (unsigned long long)o[i].msgs[PAR_CONTROL], input ? input : "generated", input ? pairk : 0,
            machine_backend_name(rc.mc.backend));
    fputc(',', f);
    bench_net_fields(f, &jr, &o[i].net);
    fprintf(f, ",%s,%d,%s,%.9f\n", vname, jb[i].block, par_schedule_name((par_schedule)jb[i].sched), o[i].idle);
  }
  int wbad = 0;
  if (outpath && atomicfile_close(&af, 1, err, sizeof err) != 0) {
    progname_eprintf("bench: %s\n", err);
    wbad = 1;
  }
  free(jb);
  free(o);
  contour_stack_free(&stack);
  return wbad ? 1 : 0;
}

int bench_sweep_runs(const bench_cfg *cfgs, const bench_run *runs, int n, int jobs, double *times,
                     char *err, size_t errlen) {
  static const bench_topos notopo;
  static const bench_places noplace;
  job *jb = xmallocarray((size_t)(n > 0 ? n : 1), sizeof *jb);
  for (int i = 0; i < n; i++) {
    const bench_machine *rc = &cfgs[runs[i].cfg].rc;
    jb[i] = (job){runs[i].points, runs[i].procs, runs[i].alloc, runs[i].d, 0, runs[i].cfg, rc->mc.sim.m,
                  rc->mc.sim.c, 0, 0, rc->pc.opt.block, (int)rc->pc.opt.schedule};
  }
  plan pl = {jb, n, cfgs[0].rc, 0, 1, NULL, 0, &notopo, &noplace, cfgs};
  outcome *o = xcalloc((size_t)(n > 0 ? n : 1), sizeof *o);
  progress *pg = progress_new(progname_as("bench"), "run", 0);   /* a line every 5 s in a log */
  int rcode = run_all(&pl, o, jobs, pg, err, errlen);
  progress_end(pg);
  for (int i = 0; rcode == 0 && i < n; i++) {
    if (!o[i].ok) {
      snprintf(err, errlen, "the run with %d points on %d processors failed: %s", runs[i].points, runs[i].procs,
               o[i].err);
      rcode = -1;
    }
    times[i] = o[i].sim_time;
  }
  free(jb);
  free(o);
  return rcode == 0 ? 0 : -1;
}
