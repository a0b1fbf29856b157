/* io_model.h -- the simulated machine's file systems: where a program's files are on the host,
 * and what reaching them costs in simulated time (the storage model of MPI-IO).
 *
 * Not for programs (mpi.h is theirs); the runner's options are in settings.h.
 *
 * FILE SYSTEMS.  The machine has file systems mounted at absolute paths: "/", the host's own
 * (a program's path is the host's path), and "/scratch", the scratch file system clusters
 * have, whose files are in a directory of the host's ($TMPDIR/tilesim-scratch-UID, made when
 * first used, kept between runs as a cluster's scratch is), so that programs written for a
 * cluster run unchanged.  --fs adds or changes mounts.  A path belongs to the mount that is its
 * longest prefix (whole components; a relative path is the working directory's); its host
 * path is the mount's directory and the rest of the path.
 *
 * COST.  Each file system is one server that does one request at a time, in the order they
 * come (simulated time; ties in the simulator's fixed order): a request of n bytes that comes
 * at t starts at max(t, the end of the one before) and takes latency + n / bandwidth.  A rank's
 * independent access is one request; a collective access is one request for the bytes of all
 * its ranks, once every rank has come (two-phase I/O's aggregation: one latency, not one a
 * rank); opening, closing, deleting, resizing, preallocating and syncing are requests of no
 * bytes.  The calls leave a rank's clock at its request's end (mp_sleep: the processor is
 * free meanwhile).  Deterministic on the simulator; on threads the same times are slept.
 *
 * The servers' state lives while any rank that used a file system is in MPI (from its first
 * I/O call to its MPI_Finalize); a later run starts with idle servers. */
#ifndef TSMPI_IO_MODEL_H
#define TSMPI_IO_MODEL_H

#include <stddef.h>

typedef struct io_fs io_fs;   /* a mounted file system of the run */

enum { IO_PATH_MAX = 4096 };

/* The file system of program path `path` and its host path (host: at least
 * IO_PATH_MAX bytes).  NULL and why (errlen bytes) if the path is empty
 * or too long, or the mount's directory cannot be made. */
io_fs *io_fs_of(const char *path, char *host, char *err, size_t errlen);

/* A rank starts using the file systems (its first I/O call) and stops (its
 * end): the servers are idle again when the last one stops. */
void io_fs_enter(void);
void io_fs_leave(void);

/* A request of `bytes` bytes coming at t: when it ends. */
double io_fs_request(io_fs *fs, double t, double bytes);

/* The mount's path ("/scratch"), its latency and bandwidth. */
const char *io_fs_mount(const io_fs *fs);
double io_fs_latency(const io_fs *fs);
double io_fs_bandwidth(const io_fs *fs);

#endif
