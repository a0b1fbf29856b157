/* compute.h -- what an MPI program's own computing costs on the simulated
 * machine (tilesim-mpirun --compute):
 *
 *   none    (the default) only what the program charges itself:
 *           tilesim_compute(units) costs units x --c seconds,
 *           smpi_execute_flops(f) f / --flops, smpi_execute(s) s;
 *   blocks  also every basic block the program ran since its last MPI call
 *           (a program built by tilesim-mpicc --count-blocks counts them: the
 *           compiler calls __sanitizer_cov_trace_pc at each), --block-c
 *           seconds each: deterministic; bench --calibrate measures the value
 *           for this host;
 *   host    also the processor time the host spent in the rank since its last
 *           MPI call (SMPI's way): not reproducible, and said so.
 *
 * The charges are made at the rank's next mp call (mp_set_hooks): before it
 * can communicate or read a clock, so the simulated times are those of
 * charging at once.  Work inside libc and libm is not counted by blocks. */
#ifndef TSMPI_COMPUTE_H
#define TSMPI_COMPUTE_H

#include <stddef.h>

#include "mp/mp.h"

typedef enum { COMPUTE_NONE, COMPUTE_BLOCKS, COMPUTE_HOST } compute_mode;

/* "none", "blocks", "host". */
const char *compute_mode_name(compute_mode m);

typedef struct {
  compute_mode mode;
  double block_c;   /* --block-c: seconds per basic block */
  double flops;     /* --flops: smpi_execute_flops's rate, flop/s */
} compute_config;

/* none, --block-c 1e-9, --flops 1e9. */
void compute_config_init(compute_config *cc);

/* Take --compute, --block-c or --flops (as machine_option does: 1, 0, -1
 * with a message). */
int compute_option(compute_config *cc, const char *opt, const char *val, char *err, size_t errlen);

/* Charge as cc says from now on, for n ranks (before a run; compute_end
 * after it).  Returns the hooks to install (mp_set_hooks), or NULL for
 * none (--compute none). */
const mp_hooks *compute_begin(const compute_config *cc, int n);
void compute_end(void);

/* Charge what the calling rank has computed since its last call now (a
 * rank's main has returned: its last stretch). */
void compute_settle(void);

/* Basic blocks counted so far by the calling thread since the last charge
 * (for tests). */
unsigned long long compute_blocks_pending(void);

/* What a program charges itself (mpi.h declares them for it; the
 * calling rank's, nothing outside a rank). */
void tilesim_compute(double units);       /* units x --c seconds (mp_compute) */
void smpi_execute_flops(double flops);    /* flops / --flops seconds */
void smpi_execute(double seconds);        /* seconds */
void smpi_execute_benched(double seconds);
void __sanitizer_cov_trace_pc(void);      /* a basic block ran (--count-blocks) */

#endif
