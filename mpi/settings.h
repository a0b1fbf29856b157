/* settings.h -- what the runner (tilesim-mpirun) sets in the MPI layer before a run: the
 * collectives' algorithms, the file systems.  Not for programs (mpi.h is theirs).
 *
 * The setting is per run, not per rank: set it before the ranks start, and
 * leave it alone while they run. */
#ifndef TSMPI_SETTINGS_H
#define TSMPI_SETTINGS_H

#include <stddef.h>
#include <stdio.h>

/* Apply one --coll argument: a comma-separated list of
 *   mpich            every collective as MPICH chooses (the default)
 *   linear           every collective by its plain root-centred algorithm
 *   COLL=ALG         one collective by one algorithm (ALG "auto": MPICH's
 *                    choice again), e.g. bcast=binomial
 * applied left to right on top of the earlier ones.  0, or -1 with a
 * message in err ("--coll: bcast has no algorithm 'ring' (linear, binomial,
 * ...)") and nothing changed. */
int coll_option(const char *spec, char *err, size_t errlen);

/* Back to MPICH's choices everywhere. */
void coll_reset(void);

/* The collectives and their algorithms, one line each ("bcast: auto linear
 * binomial scatter_recursive_doubling_allgather ..."), for --help. */
void coll_usage(FILE *out);

/* Apply one --fs argument: MOUNT[,dir=DIR][,latency=S][,bandwidth=B], a
 * file system of the simulated machine mounted at the absolute path MOUNT
 * (io_model.h): its files in the host's directory DIR (default: the same
 * path; / is the host's own and takes no dir), each request latency
 * seconds (default 1e-4) and bytes / bandwidth (bytes a second, default
 * 1e9).  A mount given again is changed ("/scratch" is there from the
 * start).  0, or -1 with a message in err and nothing changed. */
int io_fs_option(const char *spec, char *err, size_t errlen);

/* Back to the default file systems: / and /scratch. */
void io_fs_reset(void);

#endif
