/* compute.c -- charging an MPI program's own computing (compute.h). */
#define _GNU_SOURCE
#include "mpirun/compute.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "util/args.h"
#include "mp/mp.h"
#include "util/xmem.h"

const char *compute_mode_name(compute_mode m) {
  static const char *const name[] = {"none", "blocks", "host"};
  return (unsigned)m < 3 ? name[m] : "?";
}

void compute_config_init(compute_config *cc) {
  cc->mode = COMPUTE_NONE;
  cc->block_c = 1e-9;
  cc->flops = 1e9;
}

int compute_option(compute_config *cc, const char *opt, const char *val, char *err, size_t errlen) {
  if (!val) val = "";
  if (strcmp(opt, "--compute") == 0) {
    int w = args_word(opt, val, "none|blocks|host", err, errlen);
    if (w < 0) return -1;
    cc->mode = (compute_mode)w;
    return 1;
  }
  if (strcmp(opt, "--block-c") == 0) return args_real(opt, val, "seconds", 0, 1, &cc->block_c, err, errlen) == 0 ? 1 : -1;
  if (strcmp(opt, "--flops") == 0) return args_real(opt, val, "flop/s", 1e-3, 1e30, &cc->flops, err, errlen) == 0 ? 1 : -1;
  return 0;
}

/* ==== the state of a run ================================================== */

static compute_config cfg;     /* the run's */
static double *last_cpu;       /* host: [rank] the thread's processor time at its last call's end */

/* Blocks counted on this thread since the last charge: on the simulator
 * every rank runs on one thread, one at a time between its calls, so what
 * is counted between two hooks is the running rank's. */
static _Thread_local unsigned long long blocks;

/* The compiler calls this at every basic block of a program built with
 * -fsanitize-coverage=trace-pc (tilesim-mpicc --count-blocks); tilesim-mpirun
 * exports it to the programs it loads. */
void __sanitizer_cov_trace_pc(void) { blocks++; }

unsigned long long compute_blocks_pending(void) { return blocks; }

static double thread_cpu(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* The hooks: before every mp call, charge what the rank computed since its
 * last one (mp_charge: mp_busy would call the hooks again). */
static void enter(mp *self) {
  double s = 0;
  if (cfg.mode == COMPUTE_BLOCKS) {
    s = (double)blocks * cfg.block_c;
    blocks = 0;
  } else if (cfg.mode == COMPUTE_HOST) {
    double t = thread_cpu(), *l = &last_cpu[mp_rank(self)];
    if (*l >= 0 && t > *l) s = t - *l;
    *l = -1;   /* until this call ends: the layer's time is not the program's */
  }
  if (s > 0) mp_charge(self, s);
}

static void leave(mp *self) {
  if (cfg.mode == COMPUTE_HOST) last_cpu[mp_rank(self)] = thread_cpu();
}

static const mp_hooks hooks = {enter, leave};

const mp_hooks *compute_begin(const compute_config *cc, int n) {
  cfg = *cc;
  blocks = 0;
  free(last_cpu);
  last_cpu = NULL;
  if (cfg.mode == COMPUTE_HOST) {
    last_cpu = xmallocarray((size_t)n, sizeof *last_cpu);
    for (int i = 0; i < n; i++) last_cpu[i] = -1;
  }
  return cfg.mode == COMPUTE_NONE ? NULL : &hooks;
}

void compute_end(void) {
  free(last_cpu);
  last_cpu = NULL;
}

void compute_settle(void) {
  mp *self = mp_self();
  if (self && cfg.mode != COMPUTE_NONE) enter(self);
}

/* ==== what a program charges itself ====================================== */

void tilesim_compute(double units) {
  mp *self = mp_self();
  if (self) mp_compute(self, units);
}

void smpi_execute_flops(double flops) {
  mp *self = mp_self();
  if (self) mp_busy(self, flops / cfg.flops);
}

void smpi_execute(double seconds) {
  mp *self = mp_self();
  if (self) mp_busy(self, seconds);
}

void smpi_execute_benched(double seconds) { smpi_execute(seconds); }
