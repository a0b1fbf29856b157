/* trace.h -- the simulator's timeline, as CSV rows and Chrome trace-event JSON.
 *
 * The simulator calls these as it processes each action, so rows come in
 * processing order (by event time, not always by their own time stamp: a
 * wait is written when it ends).  Both outputs are byte-identical across
 * runs with the same inputs: times are printed in fixed formats.
 *
 * CSV, one row per action, header
 *   time,rank,proc,event,peer,tag,bytes,duration,msg,arrival
 * with times in simulated seconds (%.9f) and these events:
 *   compute   time = start, duration = units * c
 *   cpuwait   time = when the rank wanted its processor, duration = the wait
 *             for another rank on the same processor to finish its turn
 *   send      peer = destination, duration = LogGP's o (else 0), msg = the
 *             message's id, arrival = when it arrives at the destination
 *   wait      blocked in recv: peer/tag = what it waits for ("any" for
 *             MP_ANY), duration = how long
 *   recv      peer = source, duration = LogGP's o (else 0), msg = the id
 *   sleep     mp_sleep: time = start, duration = the sleep
 *   MPI_...   a layer's call (mp_call_begin/end: every MPI call under
 *             tilesim-mpirun that took time or moved a message), named by
 *             its function: time = when it began, duration
 *   finish    the rank's main returned
 *   link      a topology's link carried a message (sim/link.h): time = when
 *             it began, proc = the link's index (its name is in the JSON),
 *             rank = the sender, peer = the destination rank, duration = how
 *             long the link was busy with it, msg = the message's id
 *
 * JSON (Perfetto, chrome://tracing): {"traceEvents":[...]} with one pid per
 * processor and one tid per rank (named by "M" metadata), "X" slices for
 * compute, cpuwait, wait, send and recv, times in microseconds (%.3f), and a
 * flow arrow ("s" at the send, "f" bound to the recv) for every message that
 * is received, so the picture shows who waited for whom.  On a topology one
 * more pid, "network" (numbered nprocs), has a track (tid) per link that
 * carried a message, named as topo.h names links, with a "msg" slice for
 * each message it carried. */
#ifndef TRACE_H
#define TRACE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef struct trace trace;

/* A trace writing to csv and/or json (either may be NULL; both NULL gives
 * NULL).  The streams stay the caller's: trace_free does not close them. */
trace *trace_new(FILE *csv, FILE *json);

/* A trace that writes nothing and counts the bytes a CSV (csv != 0) and a
 * JSON (json != 0) trace of the same run would take (both 0 gives NULL):
 * how a program learns a trace's size before writing it.  trace_size
 * gives the counts so far (0 for a writing trace). */
trace *trace_new_count(int csv, int json);
void trace_size(const trace *tr, unsigned long long *csv, unsigned long long *json);

/* A trace writing to csv and/or json while its bytes stay within limit:
 * every call is counted as trace_new_count counts it, and from the call
 * that takes the bytes past the limit on nothing more is written
 * (trace_over says so; trace_size gives the whole trace's bytes, as if it
 * had been written).  How a program that cannot run twice keeps a trace
 * within --trace-limit: the caller removes the partial files. */
trace *trace_new_limited(FILE *csv, FILE *json, unsigned long long limit);
int trace_over(const trace *tr);

/* The largest trace a program writes unless told otherwise (--trace-limit):
 * 1 GB, a few minutes to write and more than a trace viewer opens. */
#define TRACE_LIMIT_DEFAULT 1000000000ULL

/* "512 bytes", "4.3 GB": a size for a message. */
void trace_fmt_bytes(unsigned long long bytes, char *buf, size_t len);

/* 0 if a trace of `bytes` is within limit; else -1 and the message "the
 * trace would take 4.3 GB (4312345678 bytes), more than the limit of
 * 1.0 GB; --trace-limit 5G (or none) writes it". */
int trace_over_limit(unsigned long long bytes, unsigned long long limit, char *err, size_t errlen);

/* The header row and the JSON metadata: processor and rank names. */
void trace_begin(trace *tr, int nranks, const int *place, int nprocs);

/* A span of time on a rank: kind is "compute", "cpuwait" or "wait"; for
 * "wait", peer and tag say what it waits for (-1: any); else pass -1. */
void trace_span(trace *tr, const char *kind, int rank, int proc, double start, double dur,
                int peer, int tag);

void trace_send(trace *tr, int rank, int proc, double t, double dur, int dst, int tag,
                size_t len, uint64_t msg, double arrival);
void trace_recv(trace *tr, int rank, int proc, double t, double dur, int src, int tag,
                size_t len, uint64_t msg);
void trace_finish(trace *tr, int rank, int proc, double t);

/* Name link l's track (JSON; once per link, before its first trace_link). */
void trace_link_track(trace *tr, int link, const char *name);

/* Link `link` carried message msg (from rank to dst) from start for dur. */
void trace_link(trace *tr, int link, int rank, int dst, int tag, size_t len, uint64_t msg,
                double start, double dur);

/* Close the JSON array and flush both streams.  0, or -1 and a message in
 * err if a write failed. */
int trace_end(trace *tr, char *err, size_t errlen);

void trace_free(trace *tr);   /* NULL is fine */

#endif
